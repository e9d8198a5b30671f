//! Mirrors `linkage_core`'s `linkages/`: the four-bar (uniform sweep, batch) and the slider-crank.

use pyo3::prelude::*;

pub mod batch;
pub mod fourbar;
pub mod slider_crank;

/// Adds the submodule `_core.linkages` (the four-bar (uniform and batch sweeps) and the slider-crank (`linkage_core` `linkages/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(parent, "linkages", "The four-bar (uniform and batch sweeps) and the slider-crank (`linkage_core` `linkages/`).")?;
    m.add_class::<crate::linkages::fourbar::FourBar>()?;
    m.add_class::<crate::linkages::slider_crank::SliderCrank>()?;
    m.add_function(wrap_pyfunction!(crate::linkages::batch::batch_sweep, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::linkages::fourbar::min_transmission_angle,
        &m
    )?)?;
    // Most samples per turn the table mode of the uniform sweep tabulates.
    m.add("MAX_TABLE", linkage_core::MAX_TABLE)?;
    Ok(())
}
