//! Mirrors `linkage_core::{efd, atlas, path_synthesis, slider_circuit, curve_equation,
//! slider_equation}`: the Rust half of
//! `linkage.synthesis` (descriptors, the atlas, circuit errors and residuals). Converts arrays,
//! allocates outputs with numpy, releases the GIL and calls the core.

use linkage_core::{
    arc_frame, covering_arc, descriptor_len, fourbars_from_curve, nearest, path_errors,
    path_residuals, place_entry, place_slider_entry, polyline_distances, polyline_distances_each,
    query_descriptors, slider_arc_frame, slider_cranks_from_curve, slider_path_errors,
    slider_path_residuals, ArcSpec, Atlas, AtlasSpec, Circuit, CircuitPath, FootSearch,
    Normalisation, PathError, SliderCircuit, Vec2, ARC_ENTRY_PARAMS, ENTRY_PARAMS, PLACED_PARAMS,
    QUERY_VARIANTS, SLIDER_ARC_ENTRY_PARAMS, SLIDER_ENTRY_PARAMS, SLIDER_PARAMS,
};
use numpy::ndarray::{Ix2, Ix3};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::error::{linkage_error, to_py};
use crate::mechanism::{as_points, as_slice};
use crate::memory;

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

fn points<'a>(what: &str, a: &'a crate::args::F64Array2<'_>) -> PyResult<&'a [Vec2<f64>]> {
    bytemuck::try_cast_slice(rows(what, a, 2)?)
        .map_err(|e| linkage_error(format!("{what} must be an aligned float64 array ({e})")))
}

fn flags<'a>(what: &str, a: &'a PyReadonlyArray1<'_, bool>) -> PyResult<&'a [bool]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{what} must be a contiguous bool array")))
}

fn threads_of(threads: usize) -> usize {
    threads.clamp(1, MAX_THREADS)
}

fn frame_array<'py>(py: Python<'py>, f: &linkage_core::Normalisation<f64>) -> Arr1<'py, f64> {
    vec![f.centre.x, f.centre.y, f.scale, f.rotation].into_pyarray(py)
}

/// Builds an atlas: `(descriptors (N, D) float32, params (N, 6) float64, candidate (N,) uint64)`.
#[pyfunction]
#[pyo3(name = "build_atlas")]
#[pyo3(signature = (entries, harmonics=8, samples=64, threads=1))]
pub fn synth_atlas_build<'py>(
    py: Python<'py>,
    entries: usize,
    harmonics: usize,
    samples: usize,
    threads: usize,
) -> PyResult<AtlasArrays<'py>> {
    let spec = AtlasSpec { harmonics, samples };
    atlas_arrays(py, entries, spec, ENTRY_PARAMS, || {
        Atlas::build(entries, spec, threads_of(threads))
    })
}

/// Builds a slider-crank atlas (`linkage_core::Atlas::build_slider_cranks`): `(descriptors
/// (N, D) float32, params (N, 4) float64 [coupler, offset, along, left], candidate (N,))`.
#[pyfunction]
#[pyo3(name = "build_slider_atlas")]
#[pyo3(signature = (entries, harmonics=8, samples=64, threads=1))]
pub fn synth_slider_atlas_build<'py>(
    py: Python<'py>,
    entries: usize,
    harmonics: usize,
    samples: usize,
    threads: usize,
) -> PyResult<AtlasArrays<'py>> {
    let spec = AtlasSpec { harmonics, samples };
    atlas_arrays(py, entries, spec, SLIDER_ENTRY_PARAMS, || {
        Atlas::build_slider_cranks(entries, spec, threads_of(threads))
    })
}

/// Builds an atlas of open arcs of four-bar circuits (`linkage_core::Atlas::build_arcs`):
/// `(descriptors (N, D) float32, params (N, 8) float64 [crank, coupler, rocker, along, left,
/// crossed, phase, fraction], candidate (N,))`; with `slider`, of slider-crank circuits
/// (`Atlas::build_slider_arcs`, params `(N, 6)` `[coupler, offset, along, left, phase,
/// fraction]`).
#[pyfunction]
#[pyo3(name = "build_arc_atlas")]
#[pyo3(signature = (entries, harmonics=8, samples=128, phases=8, threads=1, slider=false))]
pub fn synth_arc_atlas_build<'py>(
    py: Python<'py>,
    entries: usize,
    harmonics: usize,
    samples: usize,
    phases: usize,
    threads: usize,
    slider: bool,
) -> PyResult<AtlasArrays<'py>> {
    let spec = ArcSpec {
        harmonics,
        samples,
        phases,
    };
    let closed = AtlasSpec { harmonics, samples };
    let (params, t) = (arc_params(slider), threads_of(threads));
    atlas_arrays(py, entries, closed, params, || {
        if slider {
            Atlas::build_slider_arcs(entries, spec, t)
        } else {
            Atlas::build_arcs(entries, spec, t)
        }
    })
}

fn arc_params(slider: bool) -> usize {
    if slider {
        SLIDER_ARC_ENTRY_PARAMS
    } else {
        ARC_ENTRY_PARAMS
    }
}

/// The normalisation frame `[cx, cy, scale, rotation]` of an arc atlas entry's arc
/// (`linkage_core::arc_frame`; with `slider`, of a slider-crank arc entry,
/// `linkage_core::slider_arc_frame`).
#[pyfunction]
#[pyo3(name = "arc_entry_frame")]
#[pyo3(signature = (entry, harmonics, samples, phases, slider=false))]
pub fn synth_arc_frame<'py>(
    py: Python<'py>,
    entry: crate::args::F64Array1<'py>,
    harmonics: usize,
    samples: usize,
    phases: usize,
    slider: bool,
) -> PyResult<Arr1<'py, f64>> {
    let spec = ArcSpec {
        harmonics,
        samples,
        phases,
    };
    let frame = if slider {
        let e = entry_head::<SLIDER_ARC_ENTRY_PARAMS>(&entry)?;
        py.detach(|| slider_arc_frame(&e, spec))
    } else {
        let e = entry_head::<ARC_ENTRY_PARAMS>(&entry)?;
        py.detach(|| arc_frame(&e, spec))
    }
    .map_err(to_py)?;
    Ok(frame_array(py, &frame))
}

/// An atlas's descriptors, parameters and candidate indices as numpy arrays.
type AtlasArrays<'py> = (Arr2<'py, f32>, Arr2<'py, f64>, Arr1<'py, u64>);

/// Builds an atlas of `params` numbers an entry with `build` (GIL released) and moves it into
/// numpy.
fn atlas_arrays<'py>(
    py: Python<'py>,
    entries: usize,
    spec: AtlasSpec,
    params: usize,
    build: impl FnOnce() -> Result<Atlas, linkage_core::Error> + Send,
) -> PyResult<AtlasArrays<'py>> {
    // The atlas is built in Rust vectors (entries arrive in rounds), then moved into numpy.
    let per_entry = 4 * descriptor_len(spec.harmonics) as u128 + 8 * params as u128 + 8;
    memory::check(
        &|| format!("atlas of {entries} entries"),
        (entries as u128).saturating_mul(2 * per_entry),
    )?;
    let atlas = py.detach(build).map_err(to_py)?;
    let n = atlas.len();
    let d = atlas.dim;
    let desc = numpy::ndarray::Array2::from_shape_vec((n, d), atlas.descriptors)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    let params = numpy::ndarray::Array2::from_shape_vec((n, params), atlas.params)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    Ok((
        desc.into_pyarray(py),
        params.into_pyarray(py),
        atlas.candidate.into_pyarray(py),
    ))
}

/// The `k` atlas entries nearest any target descriptor: `(entry, squared distance, target)`.
#[pyfunction]
#[pyo3(name = "nearest_entries")]
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

/// The query descriptors of a target curve (`linkage_core::query_descriptors`):
/// `(descriptors (4, D) float32, frame [cx, cy, scale, rotation])`.
#[pyfunction]
#[pyo3(name = "query_descriptors")]
#[pyo3(signature = (points, harmonics, closed))]
pub fn synth_descriptors<'py>(
    py: Python<'py>,
    points: crate::args::F64Array2<'py>,
    harmonics: usize,
    closed: bool,
) -> PyResult<(Arr2<'py, f32>, Arr1<'py, f64>)> {
    let pts = self::points("points", &points)?;
    let dim = descriptor_len(harmonics);
    let what = || format!("descriptors of {harmonics} harmonics");
    memory::check(
        &what,
        memory::bytes_of::<f32>((QUERY_VARIANTS * dim) as u128),
    )?;
    let out = memory::zeros::<f32, Ix2>(py, &what, &[QUERY_VARIANTS, dim])?;
    let frame = {
        let mut w = out.readwrite();
        let o = as_slice(&mut w)?;
        py.detach(|| query_descriptors(pts, harmonics, closed, o))
            .map_err(to_py)?
    };
    Ok((out, frame_array(py, &frame)))
}

/// The normalisation frame `[cx, cy, scale, rotation]` of a placed four-bar's circuit curve
/// (`samples` points).
#[pyfunction]
#[pyo3(name = "circuit_frame")]
#[pyo3(signature = (params, crossed, harmonics, samples))]
pub fn synth_frame<'py>(
    py: Python<'py>,
    params: crate::args::F64Array1<'py>,
    crossed: bool,
    harmonics: usize,
    samples: usize,
) -> PyResult<Arr1<'py, f64>> {
    let p = contiguous(&params)?;
    let frame = py
        .detach(|| CircuitPath::placed(p, crossed)?.normalisation(samples, harmonics))
        .map_err(to_py)?;
    Ok(frame_array(py, &frame))
}

/// [`synth_frame`] of a placed slider-crank (`params (8,)`).
#[pyfunction]
#[pyo3(name = "slider_circuit_frame")]
#[pyo3(signature = (params, harmonics, samples))]
pub fn synth_slider_frame<'py>(
    py: Python<'py>,
    params: crate::args::F64Array1<'py>,
    harmonics: usize,
    samples: usize,
) -> PyResult<Arr1<'py, f64>> {
    let p = contiguous(&params)?;
    let frame = py
        .detach(|| SliderCircuit::placed(p)?.normalisation(samples, harmonics))
        .map_err(to_py)?;
    Ok(frame_array(py, &frame))
}

fn contiguous<'a>(params: &'a crate::args::F64Array1<'_>) -> PyResult<&'a [f64]> {
    params
        .as_slice()
        .map_err(|_| linkage_error("params must be contiguous"))
}

/// Residuals `P(s_i) − target_i` of `M` placed four-bars (`params (M, 9)`, `crossed (M,)`) at
/// circuit parameters `s (M, n)`: `(M, n, 2)`, NaN where a linkage or sample does not assemble.
#[pyfunction]
#[pyo3(name = "residuals")]
#[pyo3(signature = (params, crossed, targets, s))]
pub fn synth_residuals<'py>(
    py: Python<'py>,
    params: crate::args::F64Array2<'py>,
    crossed: PyReadonlyArray1<'py, bool>,
    targets: crate::args::F64Array2<'py>,
    s: crate::args::F64Array2<'py>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let p = rows("params", &params, PLACED_PARAMS)?;
    let cr = flags("crossed", &crossed)?;
    let t = points("targets", &targets)?;
    let sv = rows("s", &s, t.len())?;
    residual_array(py, cr.len(), t.len(), |o| path_residuals(p, cr, t, sv, o))
}

/// [`synth_residuals`] of `M` placed slider-cranks (`params (M, 8)`).
#[pyfunction]
#[pyo3(name = "slider_residuals")]
#[pyo3(signature = (params, targets, s))]
pub fn synth_slider_residuals<'py>(
    py: Python<'py>,
    params: crate::args::F64Array2<'py>,
    targets: crate::args::F64Array2<'py>,
    s: crate::args::F64Array2<'py>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let p = rows("params", &params, SLIDER_PARAMS)?;
    let t = points("targets", &targets)?;
    let sv = rows("s", &s, t.len())?;
    let m = params.shape()[0];
    residual_array(py, m, t.len(), |o| slider_path_residuals(p, t, sv, o))
}

/// An `(m, n, 2)` array filled by `run` with the GIL released.
fn residual_array<'py>(
    py: Python<'py>,
    m: usize,
    n: usize,
    run: impl FnOnce(&mut [Vec2<f64>]) -> Result<(), linkage_core::Error> + Send,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let what = || format!("residuals of {m} linkages × {n} points");
    memory::check(
        &what,
        memory::bytes_of::<f64>((m as u128) * (n as u128) * 2),
    )?;
    let out = memory::zeros::<f64, Ix3>(py, &what, &[m, n, 2])?;
    {
        let mut w = out.readwrite();
        let o = as_points(&mut w)?;
        py.detach(|| run(o)).map_err(to_py)?;
    }
    Ok(out)
}

/// Errors of `M` placed four-bars against target points: `(errors (M, 3) [max, rms, back],
/// feet (M, n))` (`linkage_core::path_errors`); `exact` finds each target's true nearest curve
/// point, otherwise the nearest segment of a `samples`-point polyline. NaN rows for a linkage
/// whose circuit does not assemble throughout.
#[pyfunction]
#[pyo3(name = "path_errors")]
#[pyo3(signature = (params, crossed, targets, samples=256, exact=false, closed=true, threads=1))]
#[allow(
    clippy::too_many_arguments,
    reason = "mirrors the Python call's keywords"
)]
pub fn synth_errors<'py>(
    py: Python<'py>,
    params: crate::args::F64Array2<'py>,
    crossed: PyReadonlyArray1<'py, bool>,
    targets: crate::args::F64Array2<'py>,
    samples: usize,
    exact: bool,
    closed: bool,
    threads: usize,
) -> PyResult<(Arr2<'py, f64>, Arr2<'py, f64>)> {
    let p = rows("params", &params, PLACED_PARAMS)?;
    let cr = flags("crossed", &crossed)?;
    let t = points("targets", &targets)?;
    let (search, threads) = (search_of(exact), threads_of(threads));
    error_arrays(py, cr.len(), t.len(), |errs, f| {
        path_errors(p, cr, t, samples, search, closed, threads, errs, f)
    })
}

/// [`synth_errors`] of `M` placed slider-cranks (`params (M, 8)`,
/// `linkage_core::slider_path_errors`).
#[pyfunction]
#[pyo3(name = "slider_path_errors")]
#[pyo3(signature = (params, targets, samples=256, exact=false, closed=true, threads=1))]
pub fn synth_slider_errors<'py>(
    py: Python<'py>,
    params: crate::args::F64Array2<'py>,
    targets: crate::args::F64Array2<'py>,
    samples: usize,
    exact: bool,
    closed: bool,
    threads: usize,
) -> PyResult<(Arr2<'py, f64>, Arr2<'py, f64>)> {
    let p = rows("params", &params, SLIDER_PARAMS)?;
    let t = points("targets", &targets)?;
    let (search, threads) = (search_of(exact), threads_of(threads));
    let m = params.shape()[0];
    error_arrays(py, m, t.len(), |errs, f| {
        slider_path_errors(p, t, samples, search, closed, threads, errs, f)
    })
}

fn search_of(exact: bool) -> FootSearch {
    if exact {
        FootSearch::Exact
    } else {
        FootSearch::Polyline
    }
}

/// `(errors (m, 3), feet (m, n))` filled by `run` with the GIL released.
fn error_arrays<'py>(
    py: Python<'py>,
    m: usize,
    n: usize,
    run: impl FnOnce(&mut [PathError<f64>], &mut [f64]) -> Result<(), linkage_core::Error> + Send,
) -> PyResult<(Arr2<'py, f64>, Arr2<'py, f64>)> {
    let what = || format!("errors of {m} linkages × {n} points");
    memory::check(
        &what,
        memory::bytes_of::<f64>((m as u128) * (n as u128 + 6)),
    )?;
    let feet = memory::zeros::<f64, Ix2>(py, &what, &[m, n])?;
    let mut errs = memory::filled(&what, m, PathError::nan())?;
    {
        let mut w = feet.readwrite();
        let f = as_slice(&mut w)?;
        py.detach(|| run(&mut errs, f)).map_err(to_py)?;
    }
    let flat: Vec<f64> = errs.iter().flat_map(|e| [e.max, e.rms, e.back]).collect();
    let e = numpy::ndarray::Array2::from_shape_vec((m, 3), flat)
        .map_err(|e| linkage_error(format!("internal error: {e}")))?;
    Ok((e.into_pyarray(py), feet))
}

/// Validity and figures of a circuit ([`synth_info`]).
type Info = (Option<String>, bool, f64, f64, f64, bool);

/// Validity of a placed four-bar's circuit and its figures over the arc `s_lo … s_hi`:
/// `(problem or None, full_turn, theta_lo, theta_hi, min transmission angle, through a limit)`.
#[pyfunction]
#[pyo3(name = "circuit_info")]
#[pyo3(signature = (params, crossed, s_lo, s_hi, check_samples=2048))]
pub fn synth_info(
    py: Python<'_>,
    params: crate::args::F64Array1<'_>,
    crossed: bool,
    s_lo: f64,
    s_hi: f64,
    check_samples: usize,
) -> PyResult<Info> {
    let path = CircuitPath::placed(contiguous(&params)?, crossed).map_err(to_py)?;
    Ok(info_of(py, &path, s_lo, s_hi, check_samples))
}

/// [`synth_info`] of a placed slider-crank (`params (8,)`).
#[pyfunction]
#[pyo3(name = "slider_circuit_info")]
#[pyo3(signature = (params, s_lo, s_hi, check_samples=2048))]
pub fn synth_slider_info(
    py: Python<'_>,
    params: crate::args::F64Array1<'_>,
    s_lo: f64,
    s_hi: f64,
    check_samples: usize,
) -> PyResult<Info> {
    let path = SliderCircuit::placed(contiguous(&params)?).map_err(to_py)?;
    Ok(info_of(py, &path, s_lo, s_hi, check_samples))
}

fn info_of(
    py: Python<'_>,
    path: &(impl Circuit<f64> + Sync),
    s_lo: f64,
    s_hi: f64,
    check_samples: usize,
) -> Info {
    let (problem, arc) = py.detach(|| {
        let problem = path.check(check_samples).err().map(|e| e.to_string());
        (problem, path.arc(s_lo, s_hi, 512))
    });
    (
        problem,
        path.full_turn(),
        arc.theta.0,
        arc.theta.1,
        arc.min_transmission,
        arc.through_limit,
    )
}

/// A frame `[cx, cy, scale, rotation]` as the core's normalisation.
fn frame_of(what: &str, f: &crate::args::F64Array1<'_>) -> PyResult<Normalisation<f64>> {
    match f.as_slice() {
        Ok(&[cx, cy, scale, rotation]) => Ok(Normalisation {
            centre: Vec2::new(cx, cy),
            scale,
            rotation,
            start: 0.0,
        }),
        _ => Err(linkage_error(format!(
            "{what} must be a contiguous [cx, cy, scale, rotation]"
        ))),
    }
}

/// The first `K` numbers of an atlas entry (a contiguous array).
fn entry_head<const K: usize>(entry: &crate::args::F64Array1<'_>) -> PyResult<[f64; K]> {
    entry
        .as_slice()
        .ok()
        .and_then(|e| e.get(..K))
        .and_then(|e| e.try_into().ok())
        .ok_or_else(|| linkage_error(format!("entry must hold at least {K} numbers, contiguous")))
}

/// An atlas entry `[crank, coupler, rocker, along, left, ...]` placed by the similarity taking
/// its curve's frame `curve` onto the target's `target` (`flip`: the other end of the major
/// axis): the 9 placed parameters (`linkage_core::place_entry`).
#[pyfunction]
#[pyo3(name = "place_entry")]
#[pyo3(signature = (entry, curve, target, flip))]
pub fn synth_place<'py>(
    py: Python<'py>,
    entry: crate::args::F64Array1<'py>,
    curve: crate::args::F64Array1<'py>,
    target: crate::args::F64Array1<'py>,
    flip: bool,
) -> PyResult<Arr1<'py, f64>> {
    let e = entry_head::<5>(&entry)?;
    let (c, t) = (frame_of("curve", &curve)?, frame_of("target", &target)?);
    Ok(place_entry(&e, &c, &t, flip).to_vec().into_pyarray(py))
}

/// A slider-crank atlas entry `[coupler, offset, along, left]` placed as [`synth_place`]
/// places a four-bar's: the 8 placed parameters (`linkage_core::place_slider_entry`).
#[pyfunction]
#[pyo3(name = "place_slider_entry")]
#[pyo3(signature = (entry, curve, target, flip))]
pub fn synth_slider_place<'py>(
    py: Python<'py>,
    entry: crate::args::F64Array1<'py>,
    curve: crate::args::F64Array1<'py>,
    target: crate::args::F64Array1<'py>,
    flip: bool,
) -> PyResult<Arr1<'py, f64>> {
    let e = entry_head::<4>(&entry)?;
    let (c, t) = (frame_of("curve", &curve)?, frame_of("target", &target)?);
    Ok(place_slider_entry(&e, &c, &t, flip)
        .to_vec()
        .into_pyarray(py))
}

/// Distance `(n,)` from each of `points (n, 2)` to the polyline through `path (m, 2)`, broken
/// at samples that are not finite (`linkage_core::polyline_distances`).
#[pyfunction]
#[pyo3(signature = (points, path))]
pub fn polyline_distance<'py>(
    py: Python<'py>,
    points: crate::args::F64Array2<'py>,
    path: crate::args::F64Array2<'py>,
) -> PyResult<Arr1<'py, f64>> {
    let (q, p) = (
        self::points("points", &points)?,
        self::points("path", &path)?,
    );
    distances(py, q.len(), |o| polyline_distances(q, p, o))
}

/// Distance `(m,)` from each of `points (m, 2)` to its own polyline of `stride` samples, the
/// rows of `paths (m·stride, 2)` (`linkage_core::polyline_distances_each`).
#[pyfunction]
#[pyo3(signature = (points, paths, stride))]
pub fn polyline_distance_each<'py>(
    py: Python<'py>,
    points: crate::args::F64Array2<'py>,
    paths: crate::args::F64Array2<'py>,
    stride: usize,
) -> PyResult<Arr1<'py, f64>> {
    let (q, p) = (
        self::points("points", &points)?,
        self::points("paths", &paths)?,
    );
    distances(py, q.len(), |o| polyline_distances_each(q, p, stride, o))
}

/// `n` distances written by `fill` into a new array, the GIL released.
fn distances<'py>(
    py: Python<'py>,
    n: usize,
    fill: impl FnOnce(&mut [f64]) -> Result<(), linkage_core::Error> + Send,
) -> PyResult<Arr1<'py, f64>> {
    let what = || format!("distances of {n} points");
    let out = memory::zeros::<f64, numpy::ndarray::Ix1>(py, &what, &[n])?;
    {
        let mut w = out.readwrite();
        let o = w
            .as_slice_mut()
            .map_err(|_| linkage_error("internal: output not contiguous"))?;
        py.detach(|| fill(o)).map_err(to_py)?;
    }
    Ok(out)
}

/// The circuit-parameter arc `(start, end)` holding every finite foot, or None
/// (`linkage_core::covering_arc`).
#[pyfunction]
#[pyo3(name = "covering_arc")]
#[pyo3(signature = (feet))]
pub fn synth_arc(feet: crate::args::F64Array1<'_>) -> PyResult<Option<(f64, f64)>> {
    let f = feet
        .as_slice()
        .map_err(|_| linkage_error("feet must be a contiguous float64 array"))?;
    Ok(covering_arc(f))
}

/// The placed slider-cranks, their residuals, the crank pivot, `misfit` and `spread`.
type SliderCurveArrays<'py> = (Arr2<'py, f64>, Arr1<'py, f64>, Arr1<'py, f64>, f64, f64);

/// Slider-cranks from the equation of the curve through `points (n, 2)`
/// (`linkage_core::slider_cranks_from_curve`): placed parameters `(k, 8)` on the ahead reach,
/// least residual first, their residuals `(k,)`, the crank pivot `(2,)`, and the fit's `misfit`
/// and `spread`.
#[pyfunction]
#[pyo3(name = "slider_cranks_from_curve")]
#[pyo3(signature = (points,))]
pub fn synth_slider_curve_equation<'py>(
    py: Python<'py>,
    points: crate::args::F64Array2<'py>,
) -> PyResult<SliderCurveArrays<'py>> {
    let pts = self::points("points", &points)?;
    let found = py.detach(|| slider_cranks_from_curve(pts)).map_err(to_py)?;
    let k = found.fits.len();
    let params: Vec<f64> = found.fits.iter().flat_map(|f| f.params).collect();
    let residuals: Vec<f64> = found.fits.iter().map(|f| f.residual).collect();
    let params = numpy::ndarray::Array2::from_shape_vec((k, SLIDER_PARAMS), params)
        .map_err(|e| linkage_error(format!("internal: {e}")))?;
    Ok((
        params.into_pyarray(py),
        residuals.into_pyarray(py),
        vec![found.pivot.x, found.pivot.y].into_pyarray(py),
        found.misfit,
        found.spread,
    ))
}

/// The placed four-bars, their residuals, the foci, `misfit` and `spread`.
type CurveArrays<'py> = (Arr2<'py, f64>, Arr1<'py, f64>, Arr2<'py, f64>, f64, f64);

/// Four-bars from the equation of the curve through `points (n, 2)`
/// (`linkage_core::fourbars_from_curve`): placed parameters `(k, 9)` least residual first,
/// their residuals `(k,)`, the curve's foci `(3, 2)`, and the fit's `misfit` and `spread`.
#[pyfunction]
#[pyo3(name = "fourbars_from_curve")]
#[pyo3(signature = (points,))]
pub fn synth_curve_equation<'py>(
    py: Python<'py>,
    points: crate::args::F64Array2<'py>,
) -> PyResult<CurveArrays<'py>> {
    let pts = self::points("points", &points)?;
    let found = py.detach(|| fourbars_from_curve(pts)).map_err(to_py)?;
    let k = found.fits.len();
    let params: Vec<f64> = found.fits.iter().flat_map(|f| f.params).collect();
    let residuals: Vec<f64> = found.fits.iter().map(|f| f.residual).collect();
    let foci: Vec<f64> = found.foci.iter().flat_map(|f| [f.x, f.y]).collect();
    let shape = |rows, cols, v: Vec<f64>| {
        numpy::ndarray::Array2::from_shape_vec((rows, cols), v)
            .map_err(|e| linkage_error(format!("internal: {e}")))
    };
    Ok((
        shape(k, PLACED_PARAMS, params)?.into_pyarray(py),
        residuals.into_pyarray(py),
        shape(3, 2, foci)?.into_pyarray(py),
        found.misfit,
        found.spread,
    ))
}
