//! Mirrors `linkage_core::cam`.

use linkage_core::{CamPoint, FlatFollower, RollerFollower};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{linkage_error, to_py};

/// Cam geometry at cam angles `phi` for follower motion `y` (N, 3: s, ds/dφ, d²s/dφ²).
/// `roller_radius` None means a flat-faced follower. Returns a dict of arrays.
#[pyfunction]
#[pyo3(signature = (phi, y, base_radius, roller_radius=None, offset=0.0))]
pub fn cam_geometry<'py>(
    py: Python<'py>,
    phi: PyReadonlyArray1<'py, f64>,
    y: PyReadonlyArray2<'py, f64>,
    base_radius: f64,
    roller_radius: Option<f64>,
    offset: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let phi = phi
        .as_slice()
        .map_err(|_| linkage_error("phi must be a contiguous float64 array"))?;
    let ys = y
        .as_slice()
        .map_err(|_| linkage_error("y must be a contiguous float64 array"))?;
    if ys.len() != 3 * phi.len() {
        return Err(linkage_error("y must have shape (len(phi), 3)"));
    }
    let point: Box<dyn Fn(f64, [f64; 3]) -> CamPoint<f64> + Send + Sync> = match roller_radius {
        Some(r) => {
            let f = RollerFollower::new(base_radius, r, offset).map_err(to_py)?;
            Box::new(move |p, y| f.point(p, y))
        }
        None => {
            let f = FlatFollower::new(base_radius).map_err(to_py)?;
            Box::new(move |p, y| f.point(p, y))
        }
    };
    let n = phi.len();
    let pts: Vec<CamPoint<f64>> = py.detach(|| {
        phi.iter()
            .enumerate()
            .map(|(k, &p)| point(p, [ys[3 * k], ys[3 * k + 1], ys[3 * k + 2]]))
            .collect()
    });
    let xy =
        |f: &dyn Fn(&CamPoint<f64>) -> [f64; 2]| -> Vec<f64> { pts.iter().flat_map(f).collect() };
    let d = PyDict::new(py);
    d.set_item(
        "pitch",
        PyArray1::from_vec(py, xy(&|p| [p.pitch.x, p.pitch.y])).reshape([n, 2])?,
    )?;
    d.set_item(
        "profile",
        PyArray1::from_vec(py, xy(&|p| [p.profile.x, p.profile.y])).reshape([n, 2])?,
    )?;
    let col = |f: fn(&CamPoint<f64>) -> f64| -> Vec<f64> { pts.iter().map(f).collect() };
    d.set_item(
        "pressure_angle",
        PyArray1::from_vec(py, col(|p| p.pressure_angle)),
    )?;
    d.set_item(
        "pitch_radius",
        PyArray1::from_vec(py, col(|p| p.pitch_radius)),
    )?;
    d.set_item(
        "profile_radius",
        PyArray1::from_vec(py, col(|p| p.profile_radius)),
    )?;
    Ok(d)
}
