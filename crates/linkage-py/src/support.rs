//! Mirrors `linkage_core::support`: support polygons and stability margins per sample.

use linkage_core::{convex_hull, stability_margin, Vec2};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArray3};
use pyo3::prelude::*;

use crate::error::linkage_error;
use crate::memory;

/// For each sample `k`: the convex hull of the finite points `points[k]` (N, K, 2; NaN rows are
/// absent) and the signed distance of `cg[k]` (N, 2) from its boundary. Returns (margin (N,)
/// NaN where no point, hull (N, K + 1, 2) NaN-padded counter-clockwise, count (N,)).
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn support_margins<'py>(
    py: Python<'py>,
    points: PyReadonlyArray3<'py, f64>,
    cg: PyReadonlyArray2<'py, f64>,
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyAny>,
    Bound<'py, PyArray1<u64>>,
)> {
    let shape = points.as_array().shape().to_vec();
    let [n, k, two] = shape[..] else {
        return Err(linkage_error("points must be (N, K, 2) and cg (N, 2)"));
    };
    if two != 2 || cg.as_array().shape() != [n, 2] {
        return Err(linkage_error("points must be (N, K, 2) and cg (N, 2)"));
    }
    let p = points
        .as_slice()
        .map_err(|_| linkage_error("points must be a contiguous float64 array"))?;
    let c = cg
        .as_slice()
        .map_err(|_| linkage_error("cg must be a contiguous float64 array"))?;
    // Outputs: margin and count (n each), hulls (n × (k + 1) × 2); scratch 2k + 1 points. The
    // input holds n·k·2 floats, so these sizes fit usize; the bytes are checked all the same.
    let what = || format!("support polygons of {n} samples × {k} feet");
    let cells = (n as u128) * (k as u128 + 1) * 2;
    memory::check(
        &what,
        memory::bytes_of::<f64>(cells + 2 * n as u128 + 4 * k as u128 + 2),
    )?;
    let mut margin = memory::filled(&what, n, f64::NAN)?;
    let mut hulls = memory::filled(&what, n * (k + 1) * 2, f64::NAN)?;
    let mut counts = memory::filled(&what, n, 0u64)?;
    let mut pts = memory::with_capacity(&what, k)?;
    let mut out = memory::filled(&what, k + 1, Vec2::zeros())?;
    let result = py.detach(|| {
        for s in 0..n {
            pts.clear();
            for q in 0..k {
                let (x, y) = (p[(s * k + q) * 2], p[(s * k + q) * 2 + 1]);
                if x.is_finite() && y.is_finite() {
                    pts.push(Vec2::new(x, y));
                }
            }
            // `out` has room for k + 1 ≥ finite points + 1: the hull always fits.
            let h = convex_hull(&mut pts, &mut out)?;
            counts[s] = h as u64; // h ≤ k + 1, far below u64::MAX
            for (i, v) in out[..h].iter().enumerate() {
                hulls[(s * (k + 1) + i) * 2] = v.x;
                hulls[(s * (k + 1) + i) * 2 + 1] = v.y;
            }
            if let Some(m) = stability_margin(Vec2::new(c[2 * s], c[2 * s + 1]), &out[..h]) {
                margin[s] = m;
            }
        }
        Ok::<_, linkage_core::Error>(())
    });
    result.map_err(crate::error::to_py)?;
    let hulls = PyArray1::from_vec(py, hulls)
        .reshape([n, k + 1, 2])?
        .into_any();
    Ok((
        PyArray1::from_vec(py, margin),
        hulls,
        PyArray1::from_vec(py, counts),
    ))
}
