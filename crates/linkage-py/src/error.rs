//! Mapping of core errors to the Python exception hierarchy rooted at `linkage.LinkageError`.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

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

/// Converts a core error into the matching Python exception: an assembly failure is an
/// `AssemblyError` carrying the core's data as `.joint` (index), `.gap` (how far the lengths
/// miss closure; None for coincident joints) and `.reason` (the message after `joint N`).
pub fn to_py(e: linkage_core::Error) -> PyErr {
    match e {
        linkage_core::Error::CannotAssemble { joint, gap } => assembly_error(e, joint, Some(gap)),
        linkage_core::Error::Coincident { joint } => assembly_error(e, joint, None),
        _ => LinkageError::new_err(e.to_string()),
    }
}

/// An `AssemblyError` with the core error's message and its joint and gap as attributes.
fn assembly_error(e: linkage_core::Error, joint: usize, gap: Option<f64>) -> PyErr {
    let message = e.to_string();
    // The core words every assembly error `joint {joint} {reason}`: the reason is what follows
    // that prefix (the whole message should the wording ever change).
    let prefix = format!("joint {joint} ");
    let reason = message
        .strip_prefix(&prefix)
        .unwrap_or(&message)
        .to_string();
    Python::attach(|py| {
        let err = AssemblyError::new_err(message.clone());
        let value = err.value(py);
        let set = value
            .setattr("joint", joint)
            .and_then(|()| value.setattr("gap", gap))
            .and_then(|()| value.setattr("reason", reason));
        match set {
            Ok(()) => err,
            Err(failed) => failed,
        }
    })
}

/// Class defaults of `AssemblyError`'s attributes, for one raised without them (from Python).
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let t = m.py().get_type::<AssemblyError>();
    t.setattr("joint", m.py().None())?;
    t.setattr("gap", m.py().None())?;
    t.setattr("reason", m.py().None())?;
    Ok(())
}

/// A `LinkageError` with a message.
pub fn linkage_error(msg: impl Into<String>) -> PyErr {
    LinkageError::new_err(msg.into())
}
