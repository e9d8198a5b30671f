//! Mirrors `linkage_core::support`: support polygons and stability margins per sample.

use linkage_core::{support_margins as core_support_margins, Vec2};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::error::linkage_error;
use crate::memory;

/// For each sample `k`: the convex hull of the finite points `points[k]` (N, K, 2; NaN rows are
/// absent) and the signed distance of `cg[k]` (N, 2) from its boundary. Returns (margin (N,)
/// NaN where no point, hull (N, K + 1, 2) NaN-padded counter-clockwise, count (N,)).
#[pyfunction]
#[allow(
    clippy::type_complexity,
    reason = "the Python tuple returned, spelled out where it is built"
)]
pub fn support_margins<'py>(
    py: Python<'py>,
    points: crate::args::F64Array3<'py>,
    cg: crate::args::F64Array2<'py>,
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
    // Outputs: margin and count (n each, twice for the count), hulls (n × (k + 1) × 2, twice:
    // the core's points and numpy's floats); copies of the inputs as points (n·k·2 + n·2);
    // scratch 2k floats. The input holds n·k·2 floats, so these sizes fit usize; the bytes are
    // checked all the same.
    let what = || format!("support polygons of {n} samples × {k} feet");
    let (nu, ku) = (n as u128, k as u128);
    let cells = nu * (ku + 1) * 2;
    memory::check(
        &what,
        memory::bytes_of::<f64>(2 * cells + 3 * nu + nu * ku * 2 + 2 * nu + 2 * ku),
    )?;
    let mut margin = memory::filled(&what, n, f64::NAN)?;
    let mut hull_pts = memory::filled(&what, n * (k + 1), Vec2::zeros())?;
    let mut counts = memory::filled(&what, n, 0usize)?;
    let mut scratch = memory::filled(&what, k, Vec2::zeros())?;
    let pads: Vec<Vec2<f64>> = p.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect();
    let cg: Vec<Vec2<f64>> = c.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect();
    py.detach(|| {
        core_support_margins(
            &pads,
            k,
            &cg,
            &mut scratch,
            &mut hull_pts,
            &mut counts,
            &mut margin,
        )
    })
    .map_err(crate::error::to_py)?;
    let hulls: Vec<f64> = hull_pts.iter().flat_map(|v| [v.x, v.y]).collect();
    // h ≤ k + 1, far below u64::MAX.
    let counts: Vec<u64> = counts.iter().map(|&h| h as u64).collect();
    let hulls = PyArray1::from_vec(py, hulls)
        .reshape([n, k + 1, 2])?
        .into_any();
    Ok((
        PyArray1::from_vec(py, margin),
        hulls,
        PyArray1::from_vec(py, counts),
    ))
}
