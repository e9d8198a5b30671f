//! Mirrors `linkage_core::{efd, atlas, path_synthesis}`: the Rust half of
//! `linkage.synthesis` (descriptors, the atlas, circuit distances and residuals).

use linkage_core::{
    descriptor_len, nearest, Assembly, Atlas, AtlasSpec, CircuitPath, Efd, FourBar, Vec2,
    ENTRY_PARAMS,
};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::error::{linkage_error, to_py};

type Arr1<'py, T> = Bound<'py, PyArray1<T>>;
type Arr2<'py, T> = Bound<'py, PyArray2<T>>;

/// Most threads a synthesis call starts.
const MAX_THREADS: usize = 64;

fn rows<'a, T: numpy::Element>(
    what: &str,
    a: &'a PyReadonlyArray2<'_, T>,
    cols: usize,
) -> PyResult<&'a [T]> {
    let shape = a.shape();
    if cols != 0 && shape[1] != cols {
        return Err(linkage_error(format!(
            "{what} must have {cols} columns, got shape ({}, {})",
            shape[0], shape[1]
        )));
    }
    a.as_slice()
        .map_err(|_| linkage_error(format!("{what} must be a C-contiguous array")))
}

fn points(what: &str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<Vec2<f64>>> {
    let flat = rows(what, a, 2)?;
    Ok(flat
        .chunks_exact(2)
        .map(|p| Vec2::new(p[0], p[1]))
        .collect())
}

/// A placed four-bar from `[ox, oy, cx, cy, crank, coupler, rocker, along, left]`.
fn linkage(p: &[f64], crossed: bool) -> Result<FourBar<f64>, linkage_core::Error> {
    FourBar::with_pivots(
        Vec2::new(p[0], p[1]),
        Vec2::new(p[2], p[3]),
        p[4],
        p[5],
        p[6],
        (p[7], p[8]),
        if crossed {
            Assembly::Crossed
        } else {
            Assembly::Open
        },
    )
}

fn threads_of(threads: usize) -> usize {
    threads.clamp(1, MAX_THREADS)
}

/// Builds an atlas: `(descriptors (N, D) float32, params (N, 6) float64, candidate (N,) uint64)`.
#[pyfunction]
#[pyo3(signature = (entries, harmonics=8, samples=64, threads=1))]
pub fn synth_atlas_build<'py>(
    py: Python<'py>,
    entries: usize,
    harmonics: usize,
    samples: usize,
    threads: usize,
) -> PyResult<(Arr2<'py, f32>, Arr2<'py, f64>, Arr1<'py, u64>)> {
    crate::memory::check(
        &|| format!("atlas of {entries} entries"),
        (entries as u128).saturating_mul((4 * descriptor_len(harmonics) + 56) as u128),
    )?;
    let spec = AtlasSpec { harmonics, samples };
    let atlas = py
        .detach(|| Atlas::build(entries, spec, threads_of(threads)))
        .map_err(to_py)?;
    let n = atlas.len();
    let d = atlas.dim;
    let desc = numpy::ndarray::Array2::from_shape_vec((n, d), atlas.descriptors)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    let params = numpy::ndarray::Array2::from_shape_vec((n, ENTRY_PARAMS), atlas.params)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    Ok((
        desc.into_pyarray(py),
        params.into_pyarray(py),
        atlas.candidate.into_pyarray(py),
    ))
}

/// The `k` atlas entries nearest any target descriptor: `(entry, squared distance, target)`.
#[pyfunction]
#[pyo3(signature = (descriptors, targets, k, threads=1))]
pub fn synth_atlas_nearest<'py>(
    py: Python<'py>,
    descriptors: PyReadonlyArray2<'py, f32>,
    targets: PyReadonlyArray2<'py, f32>,
    k: usize,
    threads: usize,
) -> PyResult<(Arr1<'py, i64>, Arr1<'py, f32>, Arr1<'py, i64>)> {
    let dim = descriptors.shape()[1];
    let d = rows("descriptors", &descriptors, 0)?;
    let t = rows("targets", &targets, dim)?;
    let hits = py
        .detach(|| nearest(d, dim, t, k, threads_of(threads)))
        .map_err(to_py)?;
    let idx: Vec<i64> = hits.iter().map(|h| h.0 as i64).collect();
    let dist: Vec<f32> = hits.iter().map(|h| h.1).collect();
    let which: Vec<i64> = hits.iter().map(|h| h.2 as i64).collect();
    Ok((
        idx.into_pyarray(py),
        dist.into_pyarray(py),
        which.into_pyarray(py),
    ))
}

/// Normalised descriptors of a target curve and its reversal, each also started at the other
/// end of the major axis: `(descriptors (4, D) float32, frame [cx, cy, scale, rotation])`.
#[pyfunction]
#[pyo3(signature = (points, harmonics, closed))]
pub fn synth_descriptors<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    harmonics: usize,
    closed: bool,
) -> PyResult<(Arr2<'py, f32>, Arr1<'py, f64>)> {
    let pts = self::points("points", &points)?;
    let of = |p: &[Vec2<f64>]| {
        if closed {
            Efd::closed(p, harmonics)
        } else {
            Efd::open(p, harmonics)
        }
    };
    let dim = descriptor_len(harmonics);
    let mut out = vec![0.0f32; 4 * dim];
    let (fwd, frame) = of(&pts).and_then(|e| e.normalised()).map_err(to_py)?;
    let rev_pts: Vec<_> = pts.iter().rev().copied().collect();
    let (rev, _) = of(&rev_pts).and_then(|e| e.normalised()).map_err(to_py)?;
    for (j, (e, flip)) in [(&fwd, false), (&fwd, true), (&rev, false), (&rev, true)]
        .into_iter()
        .enumerate()
    {
        e.descriptor(flip, &mut out[j * dim..(j + 1) * dim])
            .map_err(to_py)?;
    }
    let arr = numpy::ndarray::Array2::from_shape_vec((4, dim), out)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    Ok((
        arr.into_pyarray(py),
        vec![frame.centre.x, frame.centre.y, frame.scale, frame.rotation].into_pyarray(py),
    ))
}

/// The normalisation frame `[cx, cy, scale, rotation]` of a linkage's circuit curve
/// (`samples` points).
#[pyfunction]
#[pyo3(signature = (params, crossed, harmonics, samples))]
pub fn synth_frame<'py>(
    py: Python<'py>,
    params: PyReadonlyArray1<'py, f64>,
    crossed: bool,
    harmonics: usize,
    samples: usize,
) -> PyResult<Arr1<'py, f64>> {
    let p = params
        .as_slice()
        .map_err(|_| linkage_error("params must be contiguous"))?;
    if p.len() != 9 {
        return Err(linkage_error("params must hold 9 numbers"));
    }
    let path = linkage(p, crossed)
        .and_then(CircuitPath::new)
        .map_err(to_py)?;
    let poly = path.polyline(samples.max(8));
    let (_, f) = Efd::closed(&poly, harmonics)
        .and_then(|e| e.normalised())
        .map_err(to_py)?;
    Ok(vec![f.centre.x, f.centre.y, f.scale, f.rotation].into_pyarray(py))
}

/// Residuals `P(s_i) − target_i` of `M` linkages (`params (M, 9)`, `crossed (M,)`) at circuit
/// parameters `s (M, n)`: `(M, n, 2)`, NaN where a linkage or sample does not assemble.
#[pyfunction]
#[pyo3(signature = (params, crossed, targets, s))]
pub fn synth_residuals<'py>(
    py: Python<'py>,
    params: PyReadonlyArray2<'py, f64>,
    crossed: PyReadonlyArray1<'py, bool>,
    targets: PyReadonlyArray2<'py, f64>,
    s: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let p = rows("params", &params, 9)?;
    let m = p.len() / 9;
    let cr = crossed
        .as_slice()
        .map_err(|_| linkage_error("crossed must be contiguous"))?;
    let t = points("targets", &targets)?;
    let n = t.len();
    let sv = rows("s", &s, n)?;
    if cr.len() != m || sv.len() != m * n {
        return Err(linkage_error(format!(
            "params ({m} rows), crossed ({}) and s ({} values) disagree for {n} targets",
            cr.len(),
            sv.len()
        )));
    }
    let out = py.detach(|| {
        let mut out = vec![f64::NAN; m * n * 2];
        for i in 0..m {
            let Ok(path) = linkage(&p[9 * i..9 * i + 9], cr[i]).and_then(CircuitPath::new) else {
                continue;
            };
            for j in 0..n {
                if let Some(q) = path.point(sv[i * n + j]) {
                    let r = q - t[j];
                    out[2 * (i * n + j)] = r.x;
                    out[2 * (i * n + j) + 1] = r.y;
                }
            }
        }
        out
    });
    let arr = numpy::ndarray::Array3::from_shape_vec((m, n, 2), out)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    Ok(arr.into_pyarray(py))
}

/// Distance of a point to segment `a b`.
fn segment_distance(p: Vec2<f64>, a: Vec2<f64>, b: Vec2<f64>) -> f64 {
    let ab = b - a;
    let l2 = ab.norm_squared();
    let u = if l2 > 0.0 {
        ((p - a).dot(&ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * u - p).norm()
}

/// Errors of one linkage against `t`: `[max, rms, back]` and each target's foot parameter.
fn errors_of(
    p: &[f64],
    crossed: bool,
    t: &[Vec2<f64>],
    samples: usize,
    exact: bool,
    closed: bool,
    feet: &mut [f64],
) -> [f64; 3] {
    let bad = [f64::NAN; 3];
    let Ok(path) = linkage(p, crossed).and_then(CircuitPath::new) else {
        return bad;
    };
    let poly = path.polyline(samples);
    if poly.iter().any(|q| !(q.x.is_finite() && q.y.is_finite())) {
        return bad;
    }
    let m = poly.len();
    let (mut worst, mut sum) = (0.0f64, 0.0f64);
    for (j, &q) in t.iter().enumerate() {
        let d = if exact {
            match path.foot(q, &poly) {
                Some((d, s)) => {
                    feet[j] = s;
                    d
                }
                None => return bad,
            }
        } else {
            let mut best = (f64::INFINITY, 0usize);
            for k in 0..m {
                let d = segment_distance(q, poly[k], poly[(k + 1) % m]);
                if d < best.0 {
                    best = (d, k);
                }
            }
            feet[j] = std::f64::consts::TAU * best.1 as f64 / m as f64;
            best.0
        };
        worst = worst.max(d);
        sum += d * d;
    }
    // The curve's distance back to the target polygon (closed targets) or polyline (open).
    let mut back = 0.0f64;
    let segs = if closed { t.len() } else { t.len() - 1 };
    for &q in &poly {
        let mut best = f64::INFINITY;
        for k in 0..segs {
            best = best.min(segment_distance(q, t[k], t[(k + 1) % t.len()]));
        }
        back = back.max(best);
    }
    [worst, (sum / t.len() as f64).sqrt(), back]
}

/// Errors of `M` linkages against target points: `(errors (M, 3) [max, rms, curve→target max],
/// feet (M, n))`; `exact` finds each target's true nearest curve point (golden section),
/// otherwise the nearest segment of a `samples`-point polyline. NaN for a linkage whose circuit
/// does not assemble throughout.
#[pyfunction]
#[pyo3(signature = (params, crossed, targets, samples=256, exact=false, closed=true, threads=1))]
#[allow(clippy::too_many_arguments)]
pub fn synth_errors<'py>(
    py: Python<'py>,
    params: PyReadonlyArray2<'py, f64>,
    crossed: PyReadonlyArray1<'py, bool>,
    targets: PyReadonlyArray2<'py, f64>,
    samples: usize,
    exact: bool,
    closed: bool,
    threads: usize,
) -> PyResult<(Arr2<'py, f64>, Arr2<'py, f64>)> {
    let p = rows("params", &params, 9)?;
    let m = p.len() / 9;
    let cr = crossed
        .as_slice()
        .map_err(|_| linkage_error("crossed must be contiguous"))?;
    let t = points("targets", &targets)?;
    let n = t.len();
    if cr.len() != m || n < 2 || samples < 8 {
        return Err(linkage_error(format!(
            "params ({m} rows) and crossed ({}) disagree, or fewer than 2 targets ({n}) or 8 samples ({samples})",
            cr.len()
        )));
    }
    let (errs, feet) = py.detach(|| {
        let mut errs = vec![f64::NAN; m * 3];
        let mut feet = vec![f64::NAN; m * n];
        let threads = threads_of(threads).min(m.max(1));
        let per = m.div_ceil(threads).max(1);
        std::thread::scope(|scope| {
            for (c, (e, f)) in errs
                .chunks_mut(3 * per)
                .zip(feet.chunks_mut(n * per))
                .enumerate()
            {
                let t = &t;
                scope.spawn(move || {
                    for (i, (ei, fi)) in e.chunks_mut(3).zip(f.chunks_mut(n)).enumerate() {
                        let k = c * per + i;
                        let r =
                            errors_of(&p[9 * k..9 * k + 9], cr[k], t, samples, exact, closed, fi);
                        ei.copy_from_slice(&r);
                    }
                });
            }
        });
        (errs, feet)
    });
    let e = numpy::ndarray::Array2::from_shape_vec((m, 3), errs)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    let f = numpy::ndarray::Array2::from_shape_vec((m, n), feet)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    Ok((e.into_pyarray(py), f.into_pyarray(py)))
}

/// Validity of a placed linkage's circuit and its figures over the arc `s_lo … s_hi`:
/// `(problem or None, full_turn, theta_lo, theta_hi, min transmission angle, through a limit)`.
#[pyfunction]
#[pyo3(signature = (params, crossed, s_lo, s_hi, check_samples=2048))]
pub fn synth_info(
    py: Python<'_>,
    params: PyReadonlyArray1<'_, f64>,
    crossed: bool,
    s_lo: f64,
    s_hi: f64,
    check_samples: usize,
) -> PyResult<(Option<String>, bool, f64, f64, f64, bool)> {
    let p = params
        .as_slice()
        .map_err(|_| linkage_error("params must be contiguous"))?;
    if p.len() != 9 {
        return Err(linkage_error("params must hold 9 numbers"));
    }
    let path = linkage(p, crossed)
        .and_then(CircuitPath::new)
        .map_err(to_py)?;
    let problem = py
        .detach(|| path.check(check_samples))
        .err()
        .map(|e| e.to_string());
    let k = 512;
    let (mut lo, mut hi, mut mu) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..=k {
        let s = s_lo + (s_hi - s_lo) * i as f64 / k as f64;
        let (theta, _) = path.theta(s);
        lo = lo.min(theta);
        hi = hi.max(theta);
        if let Some(m) = path.transmission(s) {
            mu = mu.min(m);
        }
    }
    // A limited circuit's crank limits are at s = 0 and π (mod 2π).
    let through = !path.full_turn() && {
        let pi = std::f64::consts::PI;
        let first = (s_lo / pi).floor() + 1.0;
        first * pi < s_hi
    };
    Ok((problem, path.full_turn(), lo, hi, mu, through))
}
