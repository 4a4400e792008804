//! `frontier.bench.load`: a study's SQLite store read through the bench crate's own
//! reader, so the columns are exactly those of `frontier bench export` (CSV).

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::{path_arg, value_error};

/// `path=` of `load_rows`.
fn store_arg(v: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    path_arg(v, "path")
}

/// Every trial of the study store at `path` as a JSON array of row objects (ordered by
/// key); a file that is not a store of this version is refused with the CLI's message.
#[pyfunction]
pub fn load_rows(
    py: Python<'_>,
    #[pyo3(from_py_with = store_arg)] path: PathBuf,
) -> PyResult<String> {
    if path.is_dir() {
        return Err(value_error(format!(
            "{}: is a folder; expected a study store (a file written by `frontier bench`)",
            path.display()
        )));
    }
    if !path.is_file() {
        return Err(value_error(format!(
            "{}: no such study store (a file written by `frontier bench`)",
            path.display()
        )));
    }
    py.detach(|| {
        // Read only, as `bench export` reads: a store on a read-only file system, or one
        // being written by a running study, is read without being touched.
        let store = bench::Store::open_read_only(&path)?;
        let rows = store.rows()?;
        serde_json::to_string(&rows).map_err(|e| bench::BenchError::Other(e.to_string()))
    })
    .map_err(value_error)
}
