//! Mapping of core errors to the Python exception hierarchy rooted at `linkage.LinkageError`.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

create_exception!(
    linkage,
    LinkageError,
    PyValueError,
    "Base of every error the linkage package raises for bad input or impossible geometry."
);
create_exception!(
    linkage,
    AssemblyError,
    LinkageError,
    "The mechanism cannot be assembled at the requested position."
);

/// Converts a core error into the matching Python exception.
pub fn to_py(e: linkage_core::Error) -> PyErr {
    match e {
        linkage_core::Error::CannotAssemble { .. } | linkage_core::Error::Coincident { .. } => {
            AssemblyError::new_err(e.to_string())
        }
        _ => LinkageError::new_err(e.to_string()),
    }
}

/// A `LinkageError` with a message.
pub fn linkage_error(msg: impl Into<String>) -> PyErr {
    LinkageError::new_err(msg.into())
}
