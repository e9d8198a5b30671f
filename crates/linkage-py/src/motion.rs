//! Mirrors `linkage_core::centres` and `linkage_core::straightness`: vectorised over rows of
//! points.

use linkage_core::{circumcentre, path_curvature, straight_part, Centre, Vec2};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::args::Real;
use crate::error::linkage_error;
use crate::memory;

/// Reads an (M, 2) contiguous float64 array as points.
fn points(name: &str, a: &crate::args::F64Array2<'_>) -> PyResult<Vec<Vec2<f64>>> {
    let s = a
        .as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))?;
    if a.as_array().ncols() != 2 {
        return Err(linkage_error(format!("{name} must have shape (M, 2)")));
    }
    let what = || format!("a copy of {name} ({} points)", s.len() / 2);
    let mut out = memory::with_capacity(&what, s.len() / 2)?;
    out.extend(s.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])));
    Ok(out)
}

fn same_rows(names: &[&str], rows: &[usize]) -> PyResult<()> {
    if rows.windows(2).any(|w| w[0] != w[1]) {
        return Err(linkage_error(format!(
            "{} must have the same number of points, got {rows:?}",
            names.join(", ")
        )));
    }
    Ok(())
}

fn finite_xy(c: Centre<f64>) -> [f64; 2] {
    c.finite().map_or([f64::NAN; 2], |p| [p.x, p.y])
}

/// Centres of curvature (M, 2) (NaN where at infinity or undefined) and signed curvatures (M,).
#[pyfunction]
pub fn curvature_centres<'py>(
    py: Python<'py>,
    point: crate::args::F64Array2<'py>,
    velocity: crate::args::F64Array2<'py>,
    acceleration: crate::args::F64Array2<'py>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyArray1<f64>>)> {
    let (p, v, a) = (
        points("point", &point)?,
        points("velocity", &velocity)?,
        points("acceleration", &acceleration)?,
    );
    same_rows(
        &["point", "velocity", "acceleration"],
        &[p.len(), v.len(), a.len()],
    )?;
    let m = p.len();
    let what = || format!("curvature of {m} points");
    memory::check(&what, memory::bytes_of::<f64>(3 * m as u128))?;
    let mut centres = memory::with_capacity(&what, 2 * m)?;
    let mut kappa = memory::with_capacity(&what, m)?;
    py.detach(|| {
        for i in 0..m {
            let (k, c) = path_curvature(p[i], v[i], a[i]);
            centres.extend(finite_xy(c));
            kappa.push(k);
        }
    });
    let c = PyArray1::from_vec(py, centres).reshape([m, 2])?.into_any();
    Ok((c, PyArray1::from_vec(py, kappa)))
}

/// Circumcentres (M, 2) of rows of three points (NaN where collinear or coincident).
#[pyfunction]
pub fn circumcentres<'py>(
    py: Python<'py>,
    p0: crate::args::F64Array2<'py>,
    p1: crate::args::F64Array2<'py>,
    p2: crate::args::F64Array2<'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let (a, b, c) = (points("p0", &p0)?, points("p1", &p1)?, points("p2", &p2)?);
    same_rows(&["p0", "p1", "p2"], &[a.len(), b.len(), c.len()])?;
    let m = a.len();
    let mut out = memory::with_capacity(&|| format!("circumcentres of {m} points"), 2 * m)?;
    py.detach(|| out.extend((0..m).flat_map(|i| finite_xy(circumcentre(a[i], b[i], c[i])))));
    Ok(PyArray1::from_vec(py, out).reshape([m, 2])?.into_any())
}

/// The longest near-straight run of a path (`linkage_core::StraightPart`, with its lift and
/// speed when asked).
#[pyclass(module = "linkage._core.motion", frozen, get_all)]
pub struct StraightRun {
    /// Index of the run's first sample.
    pub start: usize,
    /// Number of samples in the run (on a closed path it may wrap past the last sample).
    pub count: usize,
    /// A point of the best-fit line: the run's centroid.
    pub point: (f64, f64),
    /// Unit direction of the best-fit line, pointing from the run's first sample to its last.
    pub direction: (f64, f64),
    /// Largest distance of a run sample from the line.
    pub max_deviation: f64,
    /// Extent of the run along the line.
    pub length: f64,
    /// How far the rest of a closed path rises off the run's line, to the side it lies on
    /// (`StraightPart::lift`: the obstacle a foot on this path steps over); None for an open
    /// path.
    pub lift: Option<f64>,
    /// Mean speed along the run (`StraightPart::speed`); None without velocities.
    pub mean_speed: Option<f64>,
    /// `(max − min)/mean` of the speed along the run; None without velocities.
    pub speed_variation: Option<f64>,
}

#[pymethods]
impl StraightRun {
    /// `run[key]`, the 0.1 dict's keys (`lift`, `mean_speed`, `speed_variation` only when
    /// computed), kept while the flat `_core.straight_run` is.
    fn __getitem__<'py>(slf: &Bound<'py, Self>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        let absent = match key {
            "start" | "count" | "point" | "direction" | "max_deviation" | "length" => false,
            "lift" => slf.get().lift.is_none(),
            "mean_speed" | "speed_variation" => slf.get().mean_speed.is_none(),
            _ => true,
        };
        if absent {
            return Err(pyo3::exceptions::PyKeyError::new_err(key.to_string()));
        }
        slf.getattr(key)
    }
}

/// The longest near-straight run of a path (see `linkage_core::straight_part`), or
/// None; with `lift` (`StraightPart::lift`) for a closed path, and `mean_speed`,
/// `speed_variation` (`StraightPart::speed`) when the path's `velocity` is given.
#[pyfunction]
#[pyo3(signature = (path, tol, closed, velocity=None))]
pub fn straight_run<'py>(
    py: Python<'py>,
    path: crate::args::F64Array2<'py>,
    tol: Real,
    closed: bool,
    velocity: Option<crate::args::F64Array2<'py>>,
) -> PyResult<Option<StraightRun>> {
    let tol = tol.0;
    let p = points("path", &path)?;
    let v = velocity
        .as_ref()
        .map(|v| points("velocity", v))
        .transpose()?;
    if let Some(v) = &v {
        if v.len() != p.len() {
            return Err(linkage_error(format!(
                "velocity must have the shape of path ({}, 2), got ({}, 2)",
                p.len(),
                v.len()
            )));
        }
    }
    let found = py.detach(|| {
        straight_part(&p, tol, closed).map(|s| {
            let lift = closed.then(|| s.lift(&p));
            let speed = v.as_ref().and_then(|v| s.speed(v));
            (s, lift, speed)
        })
    });
    let Some((s, lift, speed)) = found else {
        return Ok(None);
    };
    Ok(Some(StraightRun {
        start: s.start,
        count: s.count,
        point: (s.point.x, s.point.y),
        direction: (s.direction.x, s.direction.y),
        max_deviation: s.max_deviation,
        length: s.length,
        lift,
        mean_speed: speed.map(|(mean, _)| mean),
        speed_variation: speed.map(|(_, variation)| variation),
    }))
}

/// Adds the submodule `_core.motion` (instant centres, path curvature and straight runs (`linkage_core` `motion/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "motion",
        "Instant centres, path curvature and straight runs (`linkage_core` `motion/`).",
    )?;
    m.add_class::<StraightRun>()?;
    m.add_function(wrap_pyfunction!(crate::motion::curvature_centres, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::motion::circumcentres, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::motion::straight_run, &m)?)?;
    Ok(())
}
