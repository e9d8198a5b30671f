//! Mirrors `linkage_core::catalog`.

use linkage_core::catalog as core_catalog;
use pyo3::prelude::*;

use crate::error::linkage_error;
use crate::linkages::fourbar::FourBar;
use crate::mechanism::Mechanism;
use crate::module::CAPACITY;

/// Names of the catalogued four-bars and multi-loop linkages.
#[pyfunction]
#[pyo3(name = "names")]
pub fn catalog_names() -> (Vec<&'static str>, Vec<&'static str>) {
    (
        core_catalog::FOUR_BARS.to_vec(),
        core_catalog::MULTI_LOOP.to_vec(),
    )
}

/// A catalogued four-bar by name.
#[pyfunction]
#[pyo3(name = "four_bar")]
pub fn catalog_four_bar(name: &str) -> PyResult<FourBar> {
    core_catalog::four_bar_by_name::<f64>(name)
        .map(FourBar::from_core)
        .ok_or_else(|| linkage_error(format!("unknown catalogue four-bar {name:?}")))
}

/// A catalogued multi-loop linkage (`linkage_core::catalog::Linkage`).
#[pyclass(module = "linkage._core.catalog", frozen, get_all)]
pub struct CatalogLinkage {
    /// The linkage's mechanism.
    pub mechanism: Py<Mechanism>,
    /// The name of each joint, in the mechanism's order.
    pub joint_names: Vec<&'static str>,
    /// Index of the joint whose path is the linkage's output (the traced point).
    pub trace: usize,
}

#[pymethods]
impl CatalogLinkage {
    /// The 0.1 tuple `(mechanism, joint_names, trace)`, kept while the flat name is.
    fn astuple<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        pyo3::types::PyTuple::new(
            slf.py(),
            [
                slf.getattr("mechanism")?,
                slf.getattr("joint_names")?,
                slf.getattr("trace")?,
            ],
        )
    }

    fn __len__(&self) -> usize {
        3
    }

    fn __getitem__<'py>(slf: &Bound<'py, Self>, index: isize) -> PyResult<Bound<'py, PyAny>> {
        Self::astuple(slf)?.as_any().get_item(index)
    }

    fn __iter__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Ok(Self::astuple(slf)?.as_any().try_iter()?.into_any())
    }
}

/// A catalogued multi-loop linkage by name. `scale` is the pantograph's (ignored by the
/// others).
#[pyfunction]
#[pyo3(name = "linkage")]
#[pyo3(signature = (name, scale=2.0))]
pub fn catalog_linkage(
    py: Python<'_>,
    name: &str,
    #[pyo3(from_py_with = crate::args::real)] scale: f64,
) -> PyResult<CatalogLinkage> {
    let linkage = match name {
        "hoecken_pantograph" => {
            core_catalog::hoecken_pantograph::<f64>(scale).map_err(crate::error::to_py)?
        }
        _ => core_catalog::linkage_by_name::<f64>(name)
            .ok_or_else(|| linkage_error(format!("unknown catalogue linkage {name:?}")))?,
    };
    let mut m = linkage_core::Mechanism::<f64, CAPACITY>::new();
    for c in linkage.mechanism.constructions() {
        m.push(*c).map_err(crate::error::to_py)?;
    }
    Ok(CatalogLinkage {
        mechanism: Py::new(py, Mechanism::from_core(m))?,
        joint_names: linkage.joint_names.to_vec(),
        trace: linkage.trace,
    })
}

/// Adds the submodule `_core.catalog` (named classic linkages (`linkage_core::catalog`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "catalog",
        "Named classic linkages (`linkage_core::catalog`).",
    )?;
    m.add_class::<CatalogLinkage>()?;
    // The names `names()` returns, as constants.
    m.add("FOUR_BARS", core_catalog::FOUR_BARS.to_vec())?;
    m.add("MULTI_LOOP", core_catalog::MULTI_LOOP.to_vec())?;
    m.add_function(wrap_pyfunction!(crate::catalog::catalog_four_bar, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::catalog::catalog_linkage, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::catalog::catalog_names, &m)?)?;
    Ok(())
}
