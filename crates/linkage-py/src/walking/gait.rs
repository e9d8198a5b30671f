//! Mirrors `linkage_core::gait`: leg figures of a foot path, and of a batch of four-bar legs.

use linkage_core::{Assembly, FourBarBatch, FourBarGait, GaitScratch, LegGait, Vec2};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{linkage_error, to_py};
use crate::memory;

/// Most threads one call starts (the bits are the same for any count).
const MAX_THREADS: usize = 256;

/// Figure names of `four_bar_gaits`' columns, in order.
pub const COLUMNS: [&str; 13] = [
    "full_turn",
    "min_transmission",
    "duty_factor",
    "stride",
    "lift",
    "straightness",
    "speed_variation",
    "peak_torque",
    "ground",
    "stance_count",
    "stance_runs",
    "stance_start",
    "stance_longest",
];

fn row(g: &FourBarGait<f64>) -> [f64; 13] {
    let l = &g.gait;
    [
        if g.full_turn { 1.0 } else { 0.0 },
        g.min_transmission,
        l.duty_factor,
        l.stride,
        l.lift,
        l.straightness,
        l.speed_variation,
        l.peak_torque,
        l.ground,
        l.stance_count as f64,
        l.stance_runs as f64,
        l.stance_start as f64,
        l.stance_longest as f64,
    ]
}

fn points<'a>(name: &str, a: &'a crate::args::F64Array2<'_>) -> PyResult<&'a [Vec2<f64>]> {
    if a.shape()[1] != 2 {
        return Err(linkage_error(format!(
            "{name} must have shape (N, 2), got {:?}",
            a.shape()
        )));
    }
    let flat = a
        .as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a C-contiguous float64 array")))?;
    bytemuck::try_cast_slice(flat)
        .map_err(|e| linkage_error(format!("{name} must be an aligned float64 array ({e})")))
}

fn slice<'a>(name: &str, a: &'a crate::args::F64Array1<'_>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))
}

/// Leg figures of one foot path `path` (N, 2) with rates `rate` (N, 2) over a turn at evenly
/// spaced crank angles: stance within `tol` of `ground` (default the lowest level). Returns
/// (figures dict, stance mask (N,)).
#[pyfunction]
#[pyo3(signature = (path, rate, tol, ground=None))]
pub fn leg_gait<'py>(
    py: Python<'py>,
    path: crate::args::F64Array2<'py>,
    rate: crate::args::F64Array2<'py>,
    tol: f64,
    ground: Option<f64>,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyArray1<bool>>)> {
    let p = points("path", &path)?;
    let r = points("rate", &rate)?;
    let what = || format!("stance mask of {} samples", p.len());
    let mut stance = memory::filled(&what, p.len(), false)?;
    let g = py
        .detach(|| LegGait::measure(p, r, tol, ground, &mut stance))
        .map_err(to_py)?;
    let d = PyDict::new(py);
    d.set_item("ground", g.ground)?;
    d.set_item("stance_count", g.stance_count)?;
    d.set_item("stance_runs", g.stance_runs)?;
    d.set_item("stance_start", g.stance_start)?;
    d.set_item("stance_longest", g.stance_longest)?;
    d.set_item("duty_factor", g.duty_factor)?;
    d.set_item("stride", g.stride)?;
    d.set_item("lift", g.lift)?;
    d.set_item("straightness", g.straightness)?;
    d.set_item("speed_variation", g.speed_variation)?;
    d.set_item("peak_torque", g.peak_torque)?;
    Ok((d, PyArray1::from_vec(py, stance)))
}

/// Leg figures of `M` four-bar legs (the coupler point the foot) over `samples` crank angles
/// `2πk/samples`, the stance within `rel_tol` of each path's extent: an `(M, 13)` float64
/// array whose columns are `gait_columns()`. `threads` split the legs (the same bits for any
/// count).
#[pyfunction]
#[pyo3(signature = (o, c, crank, coupler, rocker, along, left, crossed, samples, rel_tol, threads=1))]
#[allow(
    clippy::too_many_arguments,
    reason = "one array per four-bar parameter and the keywords, as the Python call passes them"
)]
pub fn four_bar_gaits<'py>(
    py: Python<'py>,
    o: crate::args::F64Array2<'py>,
    c: crate::args::F64Array2<'py>,
    crank: crate::args::F64Array1<'py>,
    coupler: crate::args::F64Array1<'py>,
    rocker: crate::args::F64Array1<'py>,
    along: crate::args::F64Array1<'py>,
    left: crate::args::F64Array1<'py>,
    crossed: PyReadonlyArray1<'py, bool>,
    samples: usize,
    rel_tol: f64,
    threads: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if threads == 0 {
        return Err(linkage_error("threads must be at least 1"));
    }
    if samples < 3 {
        return Err(linkage_error(format!(
            "samples must be at least 3, got {samples}"
        )));
    }
    let flags = crossed
        .as_slice()
        .map_err(|_| linkage_error("crossed must be a contiguous bool array"))?;
    let m = flags.len();
    let what = || format!("leg figures of {m} four-bars × {samples} samples");
    let mut assembly: Vec<Assembly> = memory::with_capacity(&what, m)?;
    assembly.extend(
        flags
            .iter()
            .map(|&x| if x { Assembly::Crossed } else { Assembly::Open }),
    );
    let batch = FourBarBatch {
        o: points("o", &o)?,
        c: points("c", &c)?,
        crank: slice("crank", &crank)?,
        coupler: slice("coupler", &coupler)?,
        rocker: slice("rocker", &rocker)?,
        along: slice("along", &along)?,
        left: slice("left", &left)?,
        assembly: &assembly,
    };
    batch.check_lengths().map_err(to_py)?;
    if let Some((i, e)) = batch.first_invalid() {
        return Err(linkage_error(format!("linkage {i}: {e}")));
    }
    let threads = threads.clamp(1, MAX_THREADS).min(m.max(1));
    // Per thread: 4·samples points and samples flags of scratch; the output, 13 floats a leg.
    let scratch_bytes = (threads as u128) * (samples as u128) * 65;
    memory::check(
        &what,
        scratch_bytes + memory::bytes_of::<FourBarGait<f64>>(m as u128) * 2,
    )?;
    let blank = FourBarGait {
        gait: LegGait {
            ground: f64::NAN,
            stance_count: 0,
            stance_runs: 0,
            stance_start: 0,
            stance_longest: 0,
            duty_factor: f64::NAN,
            stride: f64::NAN,
            lift: f64::NAN,
            straightness: f64::NAN,
            speed_variation: f64::NAN,
            peak_torque: f64::NAN,
        },
        min_transmission: f64::NAN,
        full_turn: false,
    };
    let mut out = memory::filled(&what, m, blank)?;
    let chunk = m.div_ceil(threads).max(1);
    let result = py.detach(|| -> Result<(), linkage_core::Error> {
        let run = |part: FourBarBatch<'_, f64>, out: &mut [FourBarGait<f64>]| {
            let mut pts = vec![Vec2::zeros(); 4 * samples];
            let mut stance = vec![false; samples];
            let mut scratch = GaitScratch {
                points: &mut pts,
                stance: &mut stance,
            };
            part.gaits(samples, rel_tol, &mut scratch, out)
        };
        if threads <= 1 {
            return run(batch, &mut out);
        }
        std::thread::scope(|scope| {
            let mut handles = Vec::new();
            let mut results = Vec::new();
            for (t, o) in out.chunks_mut(chunk).enumerate() {
                let lo = t * chunk;
                let part = batch.slice(lo..lo + o.len())?;
                match std::thread::Builder::new().spawn_scoped(scope, move || run(part, o)) {
                    Ok(h) => handles.push(h),
                    // The system refused a thread: that chunk is not lost, it fails the call.
                    Err(_) => results.push(Err(linkage_core::Error::CountOverflow {
                        what: "threads (the system refused one)",
                    })),
                }
            }
            for h in handles {
                results.push(h.join().unwrap_or(Err(linkage_core::Error::CountOverflow {
                    what: "threads (one panicked)",
                })));
            }
            results.into_iter().collect::<Result<(), _>>()
        })
    });
    result.map_err(to_py)?;
    let mut flat: Vec<f64> = memory::with_capacity(&what, m * COLUMNS.len())?;
    for g in &out {
        flat.extend_from_slice(&row(g));
    }
    PyArray1::from_vec(py, flat).reshape([m, COLUMNS.len()])
}

/// Names of `four_bar_gaits`' columns.
#[pyfunction]
pub fn gait_columns() -> Vec<&'static str> {
    COLUMNS.to_vec()
}
