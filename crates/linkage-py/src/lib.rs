//! Python bindings of `linkage-core`: the `linkage._core` extension module.
//!
//! Thin by design: each module converts Python arguments, calls the core with the GIL released,
//! and converts results to numpy arrays. Validation messages for Python users that need Python
//! context (argument names, dtypes) live in the pure-Python package `linkage`.

use pyo3::prelude::*;

mod catalog;
mod centres;
mod error;
mod fourbar;
mod mechanism;

/// Maximum joints of a mechanism built from Python.
pub const CAPACITY: usize = 64;

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("LinkageError", py.get_type::<error::LinkageError>())?;
    m.add("AssemblyError", py.get_type::<error::AssemblyError>())?;
    m.add("CAPACITY", CAPACITY)?;
    m.add_class::<mechanism::Mechanism>()?;
    m.add_class::<fourbar::FourBar>()?;
    m.add_function(wrap_pyfunction!(catalog::catalog_four_bar, m)?)?;
    m.add_function(wrap_pyfunction!(catalog::catalog_linkage, m)?)?;
    m.add_function(wrap_pyfunction!(catalog::catalog_names, m)?)?;
    m.add_function(wrap_pyfunction!(centres::curvature_centres, m)?)?;
    m.add_function(wrap_pyfunction!(centres::circumcentres, m)?)?;
    m.add_function(wrap_pyfunction!(centres::straight_run, m)?)?;
    Ok(())
}
