//! Mirrors `linkage_core::catalog`.

use linkage_core::catalog as core_catalog;
use pyo3::prelude::*;

use crate::error::linkage_error;
use crate::linkages::fourbar::FourBar;
use crate::mechanism::Mechanism;
use crate::CAPACITY;

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

/// A catalogued multi-loop linkage: `(mechanism, joint names, trace index)`. `scale` is the
/// pantograph's (ignored by the others).
#[pyfunction]
#[pyo3(name = "linkage")]
#[pyo3(signature = (name, scale=2.0))]
pub fn catalog_linkage(
    name: &str,
    #[pyo3(from_py_with = crate::args::real)] scale: f64,
) -> PyResult<(Mechanism, Vec<&'static str>, usize)> {
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
    Ok((
        Mechanism::from_core(m),
        linkage.joint_names.to_vec(),
        linkage.trace,
    ))
}

/// Adds the submodule `_core.catalog` (named classic linkages (`linkage_core::catalog`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::submodule(
        parent,
        "catalog",
        "Named classic linkages (`linkage_core::catalog`).",
    )?;
    m.add_function(wrap_pyfunction!(crate::catalog::catalog_four_bar, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::catalog::catalog_linkage, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::catalog::catalog_names, &m)?)?;
    Ok(())
}
