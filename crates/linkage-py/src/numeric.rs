//! Mirrors `linkage_core`'s `numeric/`: exact angle reduction.

use pyo3::prelude::*;

use crate::error::linkage_error;
use crate::memory;

/// Each angle of `theta` reduced exactly to two turns (`linkage_core::reduce_angle`): the
/// reduction every sweep applies first, for callers that add a phase to a large angle
/// (`reduce_angle(θ) + φ` keeps the phase where `θ + φ` rounds it away).
#[pyfunction]
pub fn reduce_angle<'py>(
    py: Python<'py>,
    theta: crate::args::F64Array1<'py>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let th = theta
        .as_slice()
        .map_err(|_| linkage_error("theta must be a contiguous float64 array"))?;
    let what = || format!("{} reduced angles", th.len());
    let mut out = memory::with_capacity(&what, th.len())?;
    out.extend(th.iter().map(|&t| linkage_core::reduce_angle(t)));
    Ok(numpy::PyArray1::from_vec(py, out))
}

/// Adds the submodule `_core.numeric` (exact angle reduction (`linkage_core` `numeric/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "numeric",
        "Exact angle reduction (`linkage_core` `numeric/`).",
    )?;
    m.add_function(wrap_pyfunction!(crate::numeric::reduce_angle, &m)?)?;
    Ok(())
}
