//! Mirrors `linkage_core::cam`.

use linkage_core::{CamPoint, FlatFollower, RollerFollower};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

use crate::args::Real;
use crate::error::{linkage_error, to_py};
use crate::memory;

/// A cam's geometry sampled at `n` cam angles (`linkage_core::CamPoint` by columns).
#[pyclass(module = "linkage._core.drive", frozen, get_all)]
pub struct CamGeometry {
    /// Pitch-curve points `(n, 2)`: the roller centre (for a flat face, the face's point on the
    /// axis).
    pub pitch: Py<PyArray2<f64>>,
    /// Cam-profile points `(n, 2)` in contact with the follower.
    pub profile: Py<PyArray2<f64>>,
    /// Pressure angles `(n,)`: between the follower's axis and the contact normal (radians,
    /// signed).
    pub pressure_angle: Py<PyArray1<f64>>,
    /// Signed radii of curvature `(n,)` of the pitch curve (positive where convex).
    pub pitch_radius: Py<PyArray1<f64>>,
    /// Signed radii of curvature `(n,)` of the profile (positive where convex; a convex part
    /// with a negative value is undercut).
    pub profile_radius: Py<PyArray1<f64>>,
}

#[pymethods]
impl CamGeometry {
    /// `result[key]`, the 0.1 dict's keys, kept while the flat name is.
    fn __getitem__<'py>(slf: &Bound<'py, Self>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match key {
            "pitch" | "profile" | "pressure_angle" | "pitch_radius" | "profile_radius" => {
                slf.getattr(key)
            }
            _ => Err(pyo3::exceptions::PyKeyError::new_err(key.to_string())),
        }
    }
}

/// Cam geometry at cam angles `phi` for follower motion `y` (N, 3: s, ds/dφ, d²s/dφ²).
/// `roller_radius` None means a flat-faced follower.
#[pyfunction]
#[pyo3(signature = (phi, y, base_radius, roller_radius=None, offset=0.0))]
pub fn cam_geometry<'py>(
    py: Python<'py>,
    phi: crate::args::F64Array1<'py>,
    y: crate::args::F64Array2<'py>,
    base_radius: Real,
    roller_radius: Option<Real>,
    #[pyo3(from_py_with = crate::args::real)] offset: f64,
) -> PyResult<CamGeometry> {
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
    Ok(CamGeometry {
        pitch: PyArray1::from_vec(py, pitch).reshape([n, 2])?.unbind(),
        profile: PyArray1::from_vec(py, profile).reshape([n, 2])?.unbind(),
        pressure_angle: PyArray1::from_vec(py, pressure).unbind(),
        pitch_radius: PyArray1::from_vec(py, pitch_radius).unbind(),
        profile_radius: PyArray1::from_vec(py, profile_radius).unbind(),
    })
}
