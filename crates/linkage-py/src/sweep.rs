//! Mirrors `linkage_core`'s `sweep/`: the sweep of many mechanisms (computed in
//! `mechanism.rs`, beside the one-mechanism sweep it shares its kernels with) and the
//! instruction set the block kernels run.

use pyo3::prelude::*;

/// Adds the submodule `_core.sweep` (sweeps of mechanisms and the instruction set of the sweep kernels (`linkage_core` `sweep/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(parent, "sweep", "Sweeps of mechanisms and the instruction set of the sweep kernels (`linkage_core` `sweep/`).")?;
    m.add_function(wrap_pyfunction!(crate::mechanism::sweep_mechanisms, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::simd::sweep_simd, &m)?)?;
    // The tracker's default toggle margin.
    m.add("DEFAULT_TOGGLE_MARGIN", linkage_core::DEFAULT_TOGGLE_MARGIN)?;
    Ok(())
}
