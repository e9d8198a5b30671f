//! Mirrors `linkage_core`'s `walking/`: gaits of legs and of four-bar legs, support margins.

use pyo3::prelude::*;

pub mod gait;
pub mod support;

/// Adds the submodule `_core.walking` (gaits of legs and of four-bar legs, support margins (`linkage_core` `walking/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "walking",
        "Gaits of legs and of four-bar legs, support margins (`linkage_core` `walking/`).",
    )?;
    m.add_function(wrap_pyfunction!(crate::walking::gait::leg_gait, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::walking::gait::four_bar_gaits, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::walking::gait::gait_columns, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::walking::support::support_margins,
        &m
    )?)?;
    Ok(())
}
