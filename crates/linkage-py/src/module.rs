//! What every binding module shares: the joint capacity of a Python-built mechanism and the
//! helper that makes a `_core` submodule.

use pyo3::prelude::*;

/// Maximum joints of a mechanism built from Python.
pub const CAPACITY: usize = 64;

/// A new submodule `parent.<name>`, also importable as `linkage._core.<name>` (pyo3 adds no
/// `sys.modules` entry for a submodule, so `import linkage._core.<name>` needs this one).
pub fn submodule<'py>(
    parent: &Bound<'py, PyModule>,
    name: &str,
    doc: &str,
) -> PyResult<Bound<'py, PyModule>> {
    let py = parent.py();
    let m = PyModule::new(py, name)?;
    let full = format!("linkage._core.{name}");
    // Before any function is added: a function's `__module__` is its module's `__name__`.
    m.setattr("__name__", &full)?;
    m.setattr("__doc__", doc)?;
    parent.add(name, &m)?;
    py.import("sys")?.getattr("modules")?.set_item(&full, &m)?;
    Ok(m)
}
