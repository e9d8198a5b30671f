//! Mirrors `linkage_core::cam`.

use linkage_core::{CamPoint, FlatFollower, RollerFollower};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::Real;
use crate::error::{linkage_error, to_py};
use crate::memory;

/// Cam geometry at cam angles `phi` for follower motion `y` (N, 3: s, ds/dφ, d²s/dφ²).
/// `roller_radius` None means a flat-faced follower. Returns a dict of arrays.
#[pyfunction]
#[pyo3(signature = (phi, y, base_radius, roller_radius=None, offset=0.0))]
pub fn cam_geometry<'py>(
    py: Python<'py>,
    phi: crate::args::F64Array1<'py>,
    y: crate::args::F64Array2<'py>,
    base_radius: Real,
    roller_radius: Option<Real>,
    #[pyo3(from_py_with = crate::args::real)] offset: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (base_radius, roller_radius) = (base_radius.0, roller_radius.map(|r| r.0));
    let phi = phi
        .as_slice()
        .map_err(|_| linkage_error("phi must be a contiguous float64 array"))?;
    let ys = y
        .as_slice()
        .map_err(|_| linkage_error("y must be a contiguous float64 array"))?;
    if ys.len() / 3 != phi.len() || ys.len() % 3 != 0 {
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
    // Seven floats a sample (pitch and profile points, three columns), checked and reserved
    // before any is computed; the columns are then filled in one pass.
    let what = || format!("cam geometry of {n} angles");
    memory::check(&what, memory::bytes_of::<f64>(7 * n as u128))?;
    let mut pitch = memory::with_capacity(&what, 2 * n)?;
    let mut profile = memory::with_capacity(&what, 2 * n)?;
    let mut pressure = memory::with_capacity(&what, n)?;
    let mut pitch_radius = memory::with_capacity(&what, n)?;
    let mut profile_radius = memory::with_capacity(&what, n)?;
    py.detach(|| {
        for (&p, y) in phi.iter().zip(ys.chunks_exact(3)) {
            let c: CamPoint<f64> = point(p, [y[0], y[1], y[2]]);
            pitch.extend([c.pitch.x, c.pitch.y]);
            profile.extend([c.profile.x, c.profile.y]);
            pressure.push(c.pressure_angle);
            pitch_radius.push(c.pitch_radius);
            profile_radius.push(c.profile_radius);
        }
    });
    let d = PyDict::new(py);
    d.set_item("pitch", PyArray1::from_vec(py, pitch).reshape([n, 2])?)?;
    d.set_item("profile", PyArray1::from_vec(py, profile).reshape([n, 2])?)?;
    d.set_item("pressure_angle", PyArray1::from_vec(py, pressure))?;
    d.set_item("pitch_radius", PyArray1::from_vec(py, pitch_radius))?;
    d.set_item("profile_radius", PyArray1::from_vec(py, profile_radius))?;
    Ok(d)
}
