//! Mirrors `linkage_core::batch`: many four-bars swept over shared crank angles.

use linkage_core::{Assembly, FourBarBatch, Vec2};
use numpy::{PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use crate::args::{finite, mid_sentence, named};
use crate::error::{linkage_error, to_py};
use crate::memory;
use numpy::ndarray::{Ix2, Ix3};

/// Most threads one batch sweep starts (the bits are the same for any split).
const MAX_THREADS: usize = 256;

/// Work (in fast samples, ~1 ms) below which a one-thread call runs on the calling thread
/// without watching for Ctrl-C.
const INLINE: usize = 1 << 18;

/// How often the calling thread checks for Ctrl-C while workers sweep.
const POLL: Duration = Duration::from_millis(20);

/// Work of a tracked sample in fast samples (an upper estimate for ordinary steps).
const TRACKED_COST: usize = 64;

/// The core batch sweep, compiled again for AVX-512 and for AVX2 + FMA and chosen at run time
/// by what the CPU has (the same choice as the uniform sweep's, see `sweep_simd`). Rust does
/// not contract `a * b + c` into a fused multiply-add, so every build gives the same bits.
fn sweep_part(
    simd: &str,
    batch: &FourBarBatch<'_, f64>,
    theta: &[f64],
    points: &mut [Vec2<f64>],
    valid: &mut [bool],
    go_on: &dyn Fn() -> bool,
) -> Result<(), linkage_core::Error> {
    match simd {
        #[cfg(target_arch = "x86_64")]
        "avx512" => {
            #[allow(unsafe_code, reason = "calling a target_feature function")]
            // SAFETY: calling a `target_feature` function needs only that the CPU has those
            // features; `sweep_simd` names "avx512" only after detecting them.
            unsafe {
                batch_avx512(batch, theta, points, valid, go_on)
            }
        }
        #[cfg(target_arch = "x86_64")]
        "avx2" => {
            #[allow(unsafe_code, reason = "calling a target_feature function")]
            // SAFETY: as above ("avx2" only after detecting AVX2 and FMA).
            unsafe {
                batch_avx2(batch, theta, points, valid, go_on)
            }
        }
        _ => batch
            .sweep_with(theta, points, valid, &mut || go_on())
            .map(|_| ()),
    }
}

macro_rules! batch_with_features {
    ($($name:ident = $features:literal;)*) => {$(
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        fn $name(
            batch: &FourBarBatch<'_, f64>,
            theta: &[f64],
            points: &mut [Vec2<f64>],
            valid: &mut [bool],
            go_on: &dyn Fn() -> bool,
        ) -> Result<(), linkage_core::Error> {
            batch.sweep_with(theta, points, valid, &mut || go_on()).map(|_| ())
        }
    )*};
}

batch_with_features! {
    batch_avx512 = "avx512f,avx512dq,avx512vl,avx2,fma";
    batch_avx2 = "avx2,fma";
}

/// A contiguous 1-D float64 argument as a slice.
fn slice1<'a>(name: &str, a: &'a crate::args::F64Array1<'_>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))
}

/// A contiguous `(M, 2)` float64 argument as points.
fn points2<'a>(name: &str, a: &'a crate::args::F64Array2<'_>) -> PyResult<&'a [Vec2<f64>]> {
    if a.shape()[1] != 2 {
        return Err(linkage_error(format!(
            "{name} must have shape (M, 2), got {:?}",
            a.shape()
        )));
    }
    let flat = slice1_2(name, a)?;
    bytemuck::try_cast_slice(flat)
        .map_err(|e| linkage_error(format!("{name} must be an aligned float64 array ({e})")))
}

fn slice1_2<'a>(name: &str, a: &'a crate::args::F64Array2<'_>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a C-contiguous float64 array")))
}

/// The batch sweep's outputs: points `(M, N, 2)` and validity `(M, N)`.
type Outputs<'py> = (Bound<'py, PyArray3<f64>>, Bound<'py, PyArray2<bool>>);

/// Coupler points `(M, N, 2)` and validity `(M, N)` of `M` four-bars at the `N` crank angles
/// `theta`, each row what a tracked sweep of that linkage gives. `o`, `c`: `(M, 2)` pivots;
/// `crank`, `coupler`, `rocker`, `along`, `left`: `(M,)`; `crossed`: `(M,)` bool (the crossed
/// assembly). `threads` split the linkages (the same bits for any count). `out`, a pair of
/// C-contiguous writeable arrays of those shapes (float64, bool), receives the results instead
/// of new arrays (and is returned): a search that evaluates batch after batch reuses it. A call of more than
/// about a millisecond of work runs on worker threads while this thread checks for Ctrl-C.
#[pyfunction]
#[pyo3(name = "sweep_four_bar_batch")]
#[pyo3(signature = (o, c, crank, coupler, rocker, along, left, crossed, theta, threads=1, out=None))]
#[allow(
    clippy::too_many_arguments,
    reason = "one array per four-bar parameter, as the Python call passes them"
)]
pub fn batch_sweep<'py>(
    py: Python<'py>,
    o: crate::args::F64Array2<'py>,
    c: crate::args::F64Array2<'py>,
    crank: crate::args::F64Array1<'py>,
    coupler: crate::args::F64Array1<'py>,
    rocker: crate::args::F64Array1<'py>,
    along: crate::args::F64Array1<'py>,
    left: crate::args::F64Array1<'py>,
    crossed: PyReadonlyArray1<'py, bool>,
    theta: crate::args::F64Array1<'py>,
    #[pyo3(from_py_with = named::threads)] threads: usize,
    out: Option<Outputs<'py>>,
) -> PyResult<Outputs<'py>> {
    if threads == 0 {
        return Err(linkage_error("threads must be at least 1"));
    }
    let crossed_flags = crossed
        .as_slice()
        .map_err(|_| linkage_error("crossed must be a contiguous bool array"))?;
    let m = crossed_flags.len();
    let what_asm = || format!("assemblies of {m} linkages");
    let mut assembly: Vec<Assembly> = memory::with_capacity(&what_asm, m)?;
    assembly.extend(crossed_flags.iter().map(
        |&x| {
            if x {
                Assembly::Crossed
            } else {
                Assembly::Open
            }
        },
    ));
    let batch = FourBarBatch {
        o: points2("o", &o)?,
        c: points2("c", &c)?,
        crank: slice1("crank", &crank)?,
        coupler: slice1("coupler", &coupler)?,
        rocker: slice1("rocker", &rocker)?,
        along: slice1("along", &along)?,
        left: slice1("left", &left)?,
        assembly: &assembly,
    };
    let th = slice1("theta", &theta)?;
    let n = th.len();
    // Every check the core makes, before anything is allocated or written.
    batch.check_lengths().map_err(to_py)?;
    if let Some((i, e)) = batch.first_invalid() {
        return Err(linkage_error(format!("linkage {i}: {e}")));
    }
    finite("theta", th)?;
    let (points, valid) = match out {
        Some((p, v)) => {
            let shape = |s: &[usize]| {
                let parts: Vec<String> = s.iter().map(usize::to_string).collect();
                parts.join(", ")
            };
            if p.shape() != [m, n, 2] || v.shape() != [m, n] {
                return Err(linkage_error(format!(
                    "out must be arrays of shapes ({m}, {n}, 2) and ({m}, {n}), got ({}) and ({})",
                    shape(p.shape()),
                    shape(v.shape())
                )));
            }
            if !p.is_c_contiguous() || !v.is_c_contiguous() {
                return Err(linkage_error("out arrays must be C-contiguous"));
            }
            if !p.is_aligned() {
                return Err(linkage_error(crate::args::UNALIGNED_OUT));
            }
            (p, v)
        }
        None => {
            let what = || format!("batch sweep of {m} linkages × {n} angles");
            let samples = (m as u128) * (n as u128);
            memory::check(&what, samples.saturating_mul(17))?;
            // numpy's own empty arrays: the kernel writes every element (a failed call drops
            // them unseen), and numpy asks the system for huge pages for large ones.
            (
                memory::uninit::<f64, Ix3>(py, &what, &[m, n, 2])?,
                memory::uninit::<bool, Ix2>(py, &what, &[m, n])?,
            )
        }
    };
    {
        let mut pw = points.try_readwrite().map_err(|e| {
            linkage_error(format!(
                "out must be writeable arrays not in use: {}",
                mid_sentence(e)
            ))
        })?;
        let mut vw = valid.try_readwrite().map_err(|e| {
            linkage_error(format!(
                "out must be writeable arrays not in use: {}",
                mid_sentence(e)
            ))
        })?;
        let flat = pw
            .as_slice_mut()
            .map_err(|_| linkage_error("internal error: output not contiguous"))?;
        let pts: &mut [Vec2<f64>] = bytemuck::try_cast_slice_mut(flat)
            .map_err(|e| linkage_error(format!("internal error: output misaligned ({e})")))?;
        let ok = vw
            .as_slice_mut()
            .map_err(|_| linkage_error("internal error: output not contiguous"))?;
        let simd = crate::simd::sweep_simd();
        // Work in fast samples (a tracked sample counted as TRACKED_COST): a small call runs
        // here; a larger one on worker threads while this thread watches for Ctrl-C.
        let (lo, hi) = th
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
                (a.min(t), b.max(t))
            });
        // Every linkage costs at least its n samples: only a call smaller than INLINE samples
        // needs the tracked linkages looked up (a pass over the batch).
        let cost = if m.saturating_mul(n) >= INLINE {
            INLINE
        } else {
            (0..m).fold(0usize, |acc, i| {
                let per = if batch.is_tracked(i, lo, hi) {
                    TRACKED_COST
                } else {
                    1
                };
                acc.saturating_add(n.saturating_mul(per))
            })
        };
        let stopped = py.detach(|| {
            if threads <= 1 && cost < INLINE {
                sweep_part(simd, &batch, th, pts, ok, &|| true)
                    .map(|_| None)
                    .map_err(to_py)
            } else {
                run_threads(simd, &batch, th, pts, ok, threads)
            }
        })?;
        if let Some(e) = stopped {
            return Err(e);
        }
    }
    Ok((points, valid))
}

/// Sweeps `batch` into its rows, its linkages split over `threads` worker threads while the
/// calling thread checks for Ctrl-C every [`POLL`]; a chunk whose thread the system refused is
/// swept here afterwards (the same bits). Returns the interrupt that stopped it, if one did.
fn run_threads(
    simd: &str,
    batch: &FourBarBatch<'_, f64>,
    theta: &[f64],
    points: &mut [Vec2<f64>],
    valid: &mut [bool],
    threads: usize,
) -> PyResult<Option<PyErr>> {
    let (m, n) = (batch.len(), theta.len());
    let threads = threads.clamp(1, MAX_THREADS).min(m.max(1));
    let chunk = m.div_ceil(threads).max(1);
    let stop = AtomicBool::new(false);
    let mut interrupt: Option<PyErr> = None;
    let mut refused: Vec<usize> = Vec::new();
    let (tx, rx) = mpsc::channel::<()>();
    std::thread::scope(|scope| -> PyResult<()> {
        let mut handles = Vec::new();
        let rows = chunk * n.max(1);
        for (t, (p, v)) in points
            .chunks_mut(rows)
            .zip(valid.chunks_mut(rows))
            .enumerate()
        {
            let lo = t * chunk;
            let part = batch.slice(lo..(lo + chunk).min(m)).map_err(to_py)?;
            let (stop, tx) = (&stop, tx.clone());
            let work = move || {
                let r = sweep_part(simd, &part, theta, p, v, &|| !stop.load(Ordering::Relaxed));
                let _ = tx.send(()); // the receiver outlives the scope
                r
            };
            match std::thread::Builder::new().spawn_scoped(scope, work) {
                Ok(h) => handles.push(h),
                Err(_) => refused.push(t),
            }
        }
        // Watch for Ctrl-C until every worker has reported.
        let mut done = 0;
        while done < handles.len() {
            match rx.recv_timeout(POLL) {
                Ok(()) => done += 1,
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    // A worker that ended without reporting (a bug) must not hang this loop.
                    if handles.iter().all(|h| h.is_finished()) {
                        break;
                    }
                    if interrupt.is_none() {
                        if let Err(e) = Python::attach(|py| py.check_signals()) {
                            interrupt = Some(e);
                            stop.store(true, Ordering::Relaxed);
                        }
                    }
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            }
        }
        for h in handles {
            // The core has no panicking path; a join error would be a bug, reported as one.
            h.join()
                .map_err(|_| linkage_error("internal error: a batch thread panicked"))?
                .map_err(to_py)?;
        }
        Ok(())
    })?;
    if interrupt.is_some() {
        return Ok(interrupt);
    }
    for t in refused {
        let (lo, hi) = (t * chunk, ((t + 1) * chunk).min(m));
        let part = batch.slice(lo..hi).map_err(to_py)?;
        let (p, v) = (&mut points[lo * n..hi * n], &mut valid[lo * n..hi * n]);
        sweep_part(simd, &part, theta, p, v, &|| true).map_err(to_py)?;
    }
    Ok(None)
}
