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
//! with the CLI's message; a `TypeError` names the argument, what it expected and what it
//! found (`kind: expected a str, found int`), where PyO3's conversion message would name
//! none (the environments' cores take what their Python wrappers have checked). A panic
//! inside a run is caught and raised as `RuntimeError`, so nothing unwinds across the
//! boundary.

pub mod env;
pub mod map;
pub mod run;
pub mod store;

use std::path::PathBuf;

use pyo3::exceptions::{PyOverflowError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyComplex, PyFloat, PyInt, PyMapping, PyString};

/// A `ValueError` carrying `e`'s message.
pub(crate) fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// The name of `v`'s type, for messages ("found str").
pub(crate) fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_default()
}

/// A `TypeError`: argument `name` expected `what`, found `v`'s type.
pub(crate) fn type_error(name: &str, what: &str, v: &Bound<'_, PyAny>) -> PyErr {
    PyTypeError::new_err(format!("{name}: expected {what}, found {}", type_name(v)))
}

/// Whether `v` is a bool, Python's or numpy's: numpy's converts to a number (`float(np.True_)`
/// is 1.0) and is no more a number than Python's.
pub(crate) fn is_bool(v: &Bound<'_, PyAny>) -> bool {
    v.is_instance_of::<PyBool>()
        || v.get_type()
            .fully_qualified_name()
            .is_ok_and(|n| matches!(n.to_string().as_str(), "numpy.bool" | "numpy.bool_"))
}

/// Whether `v` is a complex number: Python's, numpy's (`np.complex64`, a 0-d array of a
/// complex dtype...) or any other `numbers.Complex` that is no `numbers.Real`. A float of
/// one is its real part (numpy's gives only a `ComplexWarning`), so it is no real number.
pub(crate) fn is_complex(v: &Bound<'_, PyAny>) -> bool {
    if v.is_instance_of::<PyFloat>() || v.is_instance_of::<PyInt>() {
        return false;
    }
    if v.is_instance_of::<PyComplex>() {
        return true;
    }
    let complex_dtype = v
        .getattr("dtype")
        .and_then(|d| d.getattr("kind"))
        .is_ok_and(|k| k.eq("c").unwrap_or(false));
    complex_dtype
        || v.py().import("numbers").is_ok_and(|numbers| {
            let abc = |name| numbers.getattr(name).and_then(|c| v.is_instance(&c));
            matches!((abc("Complex"), abc("Real")), (Ok(true), Ok(false)))
        })
}

/// `v` as a float (a complex number is none): an int beyond a float's range is infinite, as
/// `float("1e400")` and the CLI's `1e400` are, so that the argument's range check refuses it
/// with its message.
fn real(v: &Bound<'_, PyAny>) -> Option<f64> {
    if is_complex(v) {
        return None;
    }
    match v.extract::<f64>() {
        Ok(x) => Some(x),
        Err(e) if e.is_instance_of::<PyOverflowError>(v.py()) => {
            let negative = v.lt(0).ok()?;
            Some(if negative {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            })
        }
        Err(_) => None,
    }
}

/// Argument `name` as a real number (an int, a float or a numpy scalar; not a bool or a
/// complex number).
pub(crate) fn real_arg(v: &Bound<'_, PyAny>, name: &str, what: &str) -> PyResult<f64> {
    if is_bool(v) || v.is_instance_of::<PyString>() {
        return Err(type_error(name, what, v));
    }
    real(v).ok_or_else(|| type_error(name, what, v))
}

/// Argument `name` as a bool (Python's or numpy's).
pub(crate) fn bool_arg(v: &Bound<'_, PyAny>, name: &str) -> PyResult<bool> {
    v.extract::<bool>()
        .map_err(|_| type_error(name, "a bool", v))
}

/// Argument `name` as a str (or a subclass, such as numpy's); `what` says what was expected
/// ("a str", "a str or None").
pub(crate) fn str_arg(v: &Bound<'_, PyAny>, name: &str, what: &str) -> PyResult<String> {
    if !v.is_instance_of::<PyString>() {
        return Err(type_error(name, what, v));
    }
    v.extract()
}

/// Argument `name` as a file path: a str or an `os.PathLike` (a `pathlib.Path`).
pub(crate) fn path_arg(v: &Bound<'_, PyAny>, name: &str) -> PyResult<PathBuf> {
    v.extract::<PathBuf>().map_err(|e| {
        if e.is_instance_of::<PyTypeError>(v.py()) {
            type_error(name, "a path (a str or os.PathLike)", v)
        } else {
            e
        }
    })
}

/// Refuse an empty `path` given as `name`: messages name a file as "<path>: …", and an
/// empty one left them starting with ": ".
pub(crate) fn check_not_empty(path: &std::path::Path, name: &str) -> PyResult<()> {
    if path.as_os_str().is_empty() {
        return Err(value_error(format!(
            "{name}: expected a path, found an empty one"
        )));
    }
    Ok(())
}

/// `v` as an integer (a Python or numpy one; not a bool or a float): `None` if it is no
/// integer, `Err(digits)` if it is one beyond 128 bits.
pub(crate) fn int_value(v: &Bound<'_, PyAny>) -> Option<Result<i128, String>> {
    if is_bool(v) || v.is_instance_of::<PyFloat>() {
        return None;
    }
    match v.extract() {
        Ok(n) => Some(Ok(n)),
        Err(e) if e.is_instance_of::<PyOverflowError>(v.py()) => {
            Some(Err(v.str().map(|s| s.to_string()).unwrap_or_default()))
        }
        Err(_) => None,
    }
}

/// Argument `name` as an integer of type `T` (a Python or numpy integer; not a bool or a
/// float); `out_of_range(digits)` is the error for an integer `T` cannot hold.
pub(crate) fn int_arg<T: TryFrom<i128>>(
    v: &Bound<'_, PyAny>,
    name: &str,
    out_of_range: impl FnOnce(&str) -> PyErr,
) -> PyResult<T> {
    match int_value(v) {
        None => Err(type_error(name, "an int", v)),
        Some(Err(digits)) => Err(out_of_range(&digits)),
        Some(Ok(big)) => T::try_from(big).map_err(|_| out_of_range(&big.to_string())),
    }
}

/// Argument `name` as an integer in 0..2^64 (a Python or numpy integer; not a bool).
pub(crate) fn u64_arg(v: &Bound<'_, PyAny>, name: &str) -> PyResult<u64> {
    int_arg(v, name, |n| {
        value_error(format!("{name}: expected an integer in 0..2^64, found {n}"))
    })
}

/// One number of a pair (an int, a float or a numpy number; not a bool or a complex
/// number).
pub(crate) fn real_item(v: &Bound<'_, PyAny>) -> Option<f64> {
    if is_bool(v) || v.is_instance_of::<PyString>() {
        return None;
    }
    real(v)
}

/// Argument `name` as a pair: any sequence of two items (a tuple, a list, a numpy array),
/// each read by `item`; `what` says what was expected. A mapping is no pair (`{0: x, 1: y}`
/// has two items at 0 and 1, `{x: 0, y: 1}` none), nor a set (its order is not the user's).
pub(crate) fn pair_arg<T>(
    v: &Bound<'_, PyAny>,
    name: &str,
    what: &str,
    item: impl Fn(&Bound<'_, PyAny>) -> Option<T>,
) -> PyResult<(T, T)> {
    if v.is_instance_of::<PyString>()
        || v.is_instance_of::<PyBytes>()
        || v.cast::<PyMapping>().is_ok()
    {
        return Err(type_error(name, what, v));
    }
    let n = v.len().map_err(|_| type_error(name, what, v))?;
    if n != 2 {
        return Err(value_error(format!(
            "{name}: expected {what}, found {n} values"
        )));
    }
    let get = |i: usize| -> PyResult<T> {
        let x = v.get_item(i).map_err(|_| type_error(name, what, v))?;
        item(&x).ok_or_else(|| {
            PyTypeError::new_err(format!(
                "{name}: expected {what}, found {} ({}) among its values",
                x.repr().map(|r| r.to_string()).unwrap_or_default(),
                type_name(&x)
            ))
        })
    };
    Ok((get(0)?, get(1)?))
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
