//! `swm::Error` as Python exceptions.
//!
//! The classes live in `swm/errors.py`, so that they can inherit from the
//! matching built-in as well (`swm.IoError` is an `OSError`,
//! `swm.FormatError` a `ValueError`, ...): one class per kind of
//! `swm::Error`, all under `swm.SwmError`. The message is the library's
//! `Display` text, unchanged.

use pyo3::prelude::*;
use pyo3::types::PyAnyMethods;

/// The name of the `swm.errors` class for `e`'s kind.
fn class_name(e: &swm::Error) -> &'static str {
    match e {
        swm::Error::Io(_) => "IoError",
        swm::Error::Format(_) => "FormatError",
        swm::Error::Parameter(_) => "ParameterError",
        swm::Error::LimitExceeded(_) => "LimitError",
        swm::Error::Topology(_) => "TopologyError",
        swm::Error::Unsupported(_) => "UnsupportedError",
        swm::Error::Retile(_) => "RetileError",
        // A glTF buffer file that could not be read: the class of why.
        swm::Error::ExternalFile { error, .. } => class_name(error),
        swm::Error::Size(_) => "SizeError",
        // `swm::Error` is `#[non_exhaustive]`: a kind added later is still
        // an `SwmError` until it gets its own class.
        _ => "SwmError",
    }
}

/// The Python exception for a library error, with the library's message.
/// `filename`, when given, is set as the exception's `filename` attribute
/// (the file a read or write concerned).
pub fn to_py(py: Python<'_>, e: swm::Error, filename: Option<&str>) -> PyErr {
    match build(py, &e, filename) {
        Ok(err) => err,
        // swm.errors could not be imported (a broken installation): still
        // raise, with the library's message.
        Err(import_error) => import_error,
    }
}

fn build(py: Python<'_>, e: &swm::Error, filename: Option<&str>) -> PyResult<PyErr> {
    let class = py.import("swm.errors")?.getattr(class_name(e))?;
    let message = e.to_string().replace('\n', " ");
    let instance = class.call1((message,))?;
    if let swm::Error::Io(io) = e {
        if let Some(code) = io.raw_os_error() {
            instance.setattr("errno", code)?;
        }
    }
    if let swm::Error::Size(size) = e {
        instance.setattr("requested", size.requested)?;
        instance.setattr("smallest", size.smallest)?;
    }
    if let Some(name) = filename {
        instance.setattr("filename", name)?;
    }
    Ok(PyErr::from_value(instance))
}

/// `Result<T, swm::Error>` to `PyResult<T>`.
pub trait IntoPyResult<T> {
    /// Converts the error, if any (needs the GIL).
    fn py_err(self, py: Python<'_>) -> PyResult<T>;
    /// The same, naming the file the error concerns.
    fn py_err_file(self, py: Python<'_>, filename: &str) -> PyResult<T>;
}

impl<T> IntoPyResult<T> for Result<T, swm::Error> {
    fn py_err(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| to_py(py, e, None))
    }
    fn py_err_file(self, py: Python<'_>, filename: &str) -> PyResult<T> {
        self.map_err(|e| to_py(py, e, Some(filename)))
    }
}
