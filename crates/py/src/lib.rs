//! `frontier-py`: the Python package `frontier` (module `frontier._native`), built with
//! PyO3 and maturin.
//!
//! Researchers mostly work in Python; this crate gives them the Rust loop at Rust speed:
//! maps ([`map::Map`]), single runs and parallel batches that print exactly what
//! `frontier explore --json` prints ([`run`]), a study store read into rows ([`store`]) and
//! the core of the Gymnasium environments ([`mod@env`]), one decision per step over
//! [`sim::Session`]. The Python side (`python/frontier`) wraps these in Gymnasium's and
//! pandas' shapes.
//!
//! Errors from user input become `ValueError` (or `TypeError` for a wrong type or dtype)
//! with the CLI's message; a panic inside a run is caught and raised as `RuntimeError`, so
//! nothing unwinds across the boundary.

pub mod env;
pub mod map;
pub mod run;
pub mod store;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// A `ValueError` carrying `e`'s message.
pub(crate) fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Run `f`, turning a panic into an error message instead of unwinding further.
pub(crate) fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|p| {
        let what = p
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        format!("internal error (please report): {what}")
    })
}

/// A `RuntimeError` for a caught panic.
pub(crate) fn internal(msg: String) -> PyErr {
    PyRuntimeError::new_err(msg)
}

/// The native module `frontier._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<map::Map>()?;
    m.add_class::<env::EnvCore>()?;
    m.add_class::<env::VecEnvCore>()?;
    m.add_class::<env::TeamEnvCore>()?;
    m.add_function(wrap_pyfunction!(run::explore, m)?)?;
    m.add_function(wrap_pyfunction!(run::explore_many, m)?)?;
    m.add_function(wrap_pyfunction!(run::strategies, m)?)?;
    m.add_function(wrap_pyfunction!(store::load_rows, m)?)?;
    m.add_function(wrap_pyfunction!(map::restore_map, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
