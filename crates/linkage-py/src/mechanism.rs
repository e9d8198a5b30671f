//! Mirrors `linkage_core::mechanism` and `linkage_core::tracker`: the mechanism builder and
//! the sweep over numpy arrays.

use linkage_core::{
    path_curvature, relative_centre, Bodies, BodyId, BodyMotion, Centre, Error, LineDirection,
    Mechanism as CoreMechanism, Motion, Rates, Reach, Side, Tracker, Vec2,
};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use std::sync::{Mutex, MutexGuard};

use crate::args::{named, Real};
use crate::error::{linkage_error, to_py};
use crate::memory;
use crate::CAPACITY;

/// A per-sample rate input: one value for every sample, or one per sample.
#[derive(Clone, Copy)]
pub enum Rate<'a> {
    /// The same value at every sample.
    Scalar(f64),
    /// One value per sample.
    PerSample(&'a [f64]),
}

impl Rate<'_> {
    #[inline]
    fn at(&self, k: usize) -> f64 {
        match self {
            Rate::Scalar(x) => *x,
            Rate::PerSample(v) => v[k],
        }
    }
}

/// What a sweep computes besides positions.
#[derive(Clone, Copy, Debug, Default)]
pub struct Wanted {
    /// Joint velocities for the given drive.
    pub velocity: bool,
    /// Joint accelerations for the given drive.
    pub acceleration: bool,
    /// Instant centres of every pair of links.
    pub instant_centres: bool,
    /// Path curvature of every joint.
    pub curvature: bool,
}

/// Flat sweep results (`n` samples, `j` joints, `p` link pairs), row-major.
pub struct SweepArrays {
    /// `n·j·2` positions (NaN where invalid).
    pub joints: Vec<f64>,
    /// Whether each sample assembled.
    pub valid: Vec<bool>,
    /// Smallest dyad margin per sample (NaN where invalid).
    pub margin: Vec<f64>,
    /// Whether each valid sample is clear of the rate margin (its rates are numbers).
    pub regular: Vec<bool>,
    /// How much the lengths miss closure (0 where valid, NaN where undetermined).
    pub gap: Vec<f64>,
    /// `n·j·2` velocities, if asked.
    pub velocity: Option<Vec<f64>>,
    /// `n·j·2` accelerations, if asked.
    pub acceleration: Option<Vec<f64>>,
    /// `n·p·2` finite instant centres (NaN otherwise), if asked.
    pub centres: Option<Vec<f64>>,
    /// `n·p·2` directions of instant centres at infinity (NaN otherwise), if asked.
    pub centre_directions: Option<Vec<f64>>,
    /// `n·j·2` finite centres of curvature (NaN otherwise), if asked.
    pub curvature_centres: Option<Vec<f64>>,
    /// `n·j` signed curvatures, if asked.
    pub curvature: Option<Vec<f64>>,
}

/// The pairs `(k, l)`, `k < l`, of `count` bodies.
pub fn body_pairs(count: usize) -> Vec<(usize, usize)> {
    (0..count)
        .flat_map(|k| (k + 1..count).map(move |l| (k, l)))
        .collect()
}

/// Writes centre `c` as row `k` of `dst`: its point if `finite` is asked and it is finite, its
/// direction if `finite` is not asked and it is at infinity, NaN otherwise.
fn put(dst: &mut [f64], k: usize, c: Centre<f64>, finite: bool) {
    let v = match (c, finite) {
        (Centre::Finite(p), true) | (Centre::AtInfinity(p), false) => [p.x, p.y],
        _ => [f64::NAN; 2],
    };
    dst[2 * k..2 * k + 2].copy_from_slice(&v);
}

/// Samples between two calls of a sweep's `go_on`, at most.
pub const CHUNK: usize = 4096;

/// Tracker placements (solves of every joint at one angle) between two calls of `go_on`, at
/// most: a sample costs one placement, plus the grid points walked to reach it (up to a few
/// hundred for a jump of many turns), so counting work rather than samples bounds the time
/// between two checks (about 10 ms here) whatever the spacing of the samples.
pub const WORK_CHUNK: u64 = 1 << 15;

/// Allocates the outputs of a sweep of `n` samples of `j` joints and `np` link pairs: the total
/// is checked first (`MemoryError` naming it), then each buffer is reserved without aborting.
fn allocate(n: usize, j: usize, np: usize, wanted: Wanted) -> PyResult<SweepArrays> {
    let rates = wanted.velocity || wanted.acceleration;
    let (nu, ju, pu) = (n as u128, j as u128, np as u128);
    let on = |b: bool| u128::from(b);
    // In f64 units: joints, margin, gap, the optional arrays; `valid` and `regular` are one
    // byte a sample each.
    let floats = nu * ju * 2 * (1 + on(rates) + on(wanted.acceleration) + on(wanted.curvature))
        + nu * 2
        + nu * pu * 4 * on(wanted.instant_centres)
        + nu * ju * on(wanted.curvature);
    let what = || format!("sweep of {n} samples");
    memory::check(&what, memory::bytes_of::<f64>(floats) + 2 * nu)?;
    // The total fits isize, so every product below fits usize.
    let rows = |on: bool| -> PyResult<Option<Vec<f64>>> {
        on.then(|| memory::with_capacity(&what, n * j * 2))
            .transpose()
    };
    let nans = |len: usize, on: bool| -> PyResult<Option<Vec<f64>>> {
        on.then(|| memory::filled(&what, len, f64::NAN)).transpose()
    };
    Ok(SweepArrays {
        joints: memory::with_capacity(&what, n * j * 2)?,
        valid: memory::filled(&what, n, false)?,
        margin: memory::filled(&what, n, f64::NAN)?,
        regular: memory::filled(&what, n, false)?,
        gap: memory::filled(&what, n, 0.0)?,
        velocity: rows(rates)?,
        acceleration: rows(wanted.acceleration)?,
        centres: nans(n * np * 2, wanted.instant_centres)?,
        centre_directions: nans(n * np * 2, wanted.instant_centres)?,
        curvature_centres: nans(n * j * 2, wanted.curvature)?,
        curvature: nans(n * j, wanted.curvature)?,
    })
}

/// Sweeps `m` over `theta` with the core tracker. Pure Rust, no Python: runs with the GIL
/// released (the allocation errors it can return are created lazily). Only what `wanted` asks
/// is computed; instant centres and curvature use rates per unit crank angle (they do not
/// depend on timing). `go_on` is called every [`CHUNK`] samples or [`WORK_CHUNK`] placements,
/// whichever comes first; when it returns false the
/// sweep stops early (the caller raises what stopped it).
pub fn sweep_arrays<const N: usize>(
    m: &CoreMechanism<f64, N>,
    theta: &[f64],
    omega: Rate<'_>,
    alpha: Rate<'_>,
    wanted: Wanted,
    go_on: &mut dyn FnMut() -> bool,
) -> PyResult<SweepArrays> {
    let (n, j) = (theta.len(), m.len());
    let rates = wanted.velocity || wanted.acceleration;
    let bodies = Bodies::of(m);
    let ids: Vec<BodyId> = bodies.ids().collect();
    let pairs = body_pairs(ids.len());
    let np = pairs.len();
    // Positions and rates are appended sample by sample (NaN rows where a sample does not
    // assemble), so each output byte is written once.
    let mut out = allocate(n, j, np, wanted)?;
    let mut tracker = Tracker::new(m).map_err(to_py)?;
    let zero = [Vec2::zeros(); N];
    let (mut pos, mut vel, mut acc) = (zero, zero, zero);
    let (mut uvel, mut uacc) = (zero, zero);
    let mut motions = Vec::with_capacity(ids.len());
    let mut next_check = WORK_CHUNK;
    for (k, &th) in theta.iter().enumerate() {
        if (k % CHUNK == CHUNK - 1 || tracker.work() >= next_check) && k > 0 {
            if !go_on() {
                break;
            }
            next_check = tracker.work().saturating_add(WORK_CHUNK);
        }
        let motion = rates.then(|| Motion::new(omega.at(k), alpha.at(k)));
        let buffers = match (wanted.acceleration, rates) {
            (true, _) => Rates::acceleration(&mut vel[..j], &mut acc[..j]),
            (false, true) => Rates::velocity(&mut vel[..j]),
            _ => Rates::none(),
        };
        match tracker.step(th, motion, &mut pos[..j], buffers) {
            Ok(s) => {
                out.valid[k] = true;
                out.margin[k] = s.margin;
                out.regular[k] = s.regular;
            }
            Err(
                e @ (Error::CannotAssemble { .. }
                | Error::Coincident { .. }
                | Error::NotFinite { .. }),
            ) => {
                out.gap[k] = match e {
                    Error::CannotAssemble { gap, .. } => gap,
                    _ => f64::NAN,
                };
                for buf in [
                    Some(&mut out.joints),
                    out.velocity.as_mut(),
                    out.acceleration.as_mut(),
                ]
                .into_iter()
                .flatten()
                {
                    buf.extend(core::iter::repeat_n(f64::NAN, 2 * j));
                }
                continue;
            }
            Err(e) => return Err(to_py(e)),
        }
        let row = k * j * 2;
        push_rows(&mut out.joints, &pos[..j]);
        if let Some(v) = out.velocity.as_mut() {
            push_rows(v, &vel[..j]);
        }
        if let Some(a) = out.acceleration.as_mut() {
            push_rows(a, &acc[..j]);
        }
        if !(wanted.instant_centres || wanted.curvature) {
            continue;
        }
        let unit_acc = wanted.curvature.then_some(&mut uacc[..j]);
        m.motion(&pos[..j], Motion::unit(), &mut uvel[..j], unit_acc, None)
            .map_err(to_py)?;
        if let (Some(c), Some(d)) = (out.centres.as_mut(), out.centre_directions.as_mut()) {
            motions.clear();
            motions.extend(ids.iter().map(|&id| {
                BodyMotion::of(&bodies, id, &pos[..j], &uvel[..j], &zero[..j], &zero[..j])
                    .conditioned(out.margin[k])
            }));
            for (q, &(a, b)) in pairs.iter().enumerate() {
                let ic = relative_centre(
                    &bodies,
                    (ids[a], &motions[a]),
                    (ids[b], &motions[b]),
                    &pos[..j],
                );
                put(&mut c[k * np * 2..], q, ic, true);
                put(&mut d[k * np * 2..], q, ic, false);
            }
        }
        if let (Some(c), Some(kap)) = (out.curvature_centres.as_mut(), out.curvature.as_mut()) {
            for i in 0..j {
                let (kappa, centre) = path_curvature(pos[i], uvel[i], uacc[i]);
                kap[k * j + i] = kappa;
                put(&mut c[row..], i, centre, true);
            }
        }
    }
    Ok(out)
}

#[inline]
fn push_rows(dst: &mut Vec<f64>, src: &[Vec2<f64>]) {
    dst.extend(src.iter().flat_map(|p| [p.x, p.y]));
}

/// Reads an optional rate array: absent is `default`, length 1 is a scalar, length `n` per sample.
fn rate<'a>(
    name: &str,
    arr: &'a Option<PyReadonlyArray1<'_, f64>>,
    n: usize,
    default: f64,
) -> PyResult<Rate<'a>> {
    let Some(arr) = arr else {
        return Ok(Rate::Scalar(default));
    };
    let s = arr
        .as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))?;
    match s.len() {
        1 => Ok(Rate::Scalar(s[0])),
        len if len == n => Ok(Rate::PerSample(s)),
        len => Err(linkage_error(format!(
            "{name} must be a scalar or have one value per angle ({n}), got {len}"
        ))),
    }
}

/// Turns a flat result into an `(n, j, 2)` array.
fn to_array3<'py>(py: Python<'py>, v: Vec<f64>, n: usize, j: usize) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, v).reshape([n, j, 2])?.into_any())
}

/// Parses `"left"` / `"right"`.
fn parse_side(side: &str) -> PyResult<Side> {
    match side {
        "left" => Ok(Side::Left),
        "right" => Ok(Side::Right),
        other => Err(linkage_error(format!(
            "side must be 'left' or 'right', got {other:?}"
        ))),
    }
}

/// Parses `"ahead"` / `"behind"`.
fn parse_reach(reach: &str) -> PyResult<Reach> {
    match reach {
        "ahead" => Ok(Reach::Ahead),
        "behind" => Ok(Reach::Behind),
        other => Err(linkage_error(format!(
            "reach must be 'ahead' or 'behind', got {other:?}"
        ))),
    }
}

/// A mechanism program of up to `CAPACITY` joints, addressed by index (the `linkage.Mechanism`
/// class adds names).
///
/// Frozen, with the program behind a mutex: methods take `&self`, so no call can meet a borrow
/// held by another thread or a re-entrant call (`RuntimeError: Already borrowed`). Each method
/// holds the lock only for its own short, panic-free work and never while waiting for the GIL,
/// and a sweep works on a copy taken under the lock.
#[pyclass(module = "linkage._core", frozen)]
pub struct Mechanism {
    inner: Mutex<CoreMechanism<f64, CAPACITY>>,
}

impl Mechanism {
    /// Wraps a core mechanism.
    pub fn from_core(inner: CoreMechanism<f64, CAPACITY>) -> Self {
        Mechanism {
            inner: Mutex::new(inner),
        }
    }

    /// The program, locked. Nothing panics while holding the lock, so it is never poisoned;
    /// if it were, the program itself is still whole (every change is a single `push`).
    fn lock(&self) -> MutexGuard<'_, CoreMechanism<f64, CAPACITY>> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A copy of the program as it is now.
    pub fn snapshot(&self) -> CoreMechanism<f64, CAPACITY> {
        self.lock().clone()
    }
}

#[pymethods]
impl Mechanism {
    #[new]
    fn new() -> Self {
        Mechanism::from_core(CoreMechanism::new())
    }

    fn __len__(&self) -> usize {
        self.lock().len()
    }

    /// Index of the crank joint, or None.
    #[getter]
    fn driver(&self) -> Option<usize> {
        self.lock().driver()
    }

    /// Adds a fixed joint at (x, y); returns its index.
    fn fixed(&self, x: Real, y: Real) -> PyResult<usize> {
        self.lock().fixed(Vec2::new(x.0, y.0)).map_err(to_py)
    }

    /// Adds the crank about joint `centre`; returns its index.
    #[pyo3(signature = (centre, radius, phase=0.0))]
    fn crank(
        &self,
        #[pyo3(from_py_with = named::centre)] centre: usize,
        radius: Real,
        #[pyo3(from_py_with = crate::args::real)] phase: f64,
    ) -> PyResult<usize> {
        self.lock().crank(centre, radius.0, phase).map_err(to_py)
    }

    /// Adds an RRR dyad at r1 from p1 and r2 from p2 on `side` of p1 → p2.
    fn dyad(
        &self,
        #[pyo3(from_py_with = named::p1)] p1: usize,
        #[pyo3(from_py_with = named::p2)] p2: usize,
        r1: Real,
        r2: Real,
        side: &str,
    ) -> PyResult<usize> {
        let side = parse_side(side)?;
        self.lock().dyad(p1, p2, r1.0, r2.0, side).map_err(to_py)
    }

    /// Adds a slider dyad on the fixed direction (dx, dy) through `origin`.
    fn slider(
        &self,
        #[pyo3(from_py_with = named::pivot)] pivot: usize,
        r: Real,
        #[pyo3(from_py_with = named::origin)] origin: usize,
        dx: Real,
        dy: Real,
        reach: &str,
    ) -> PyResult<usize> {
        let reach = parse_reach(reach)?;
        let direction = LineDirection::Fixed(Vec2::new(dx.0, dy.0));
        self.lock()
            .slider(pivot, r.0, origin, direction, reach)
            .map_err(to_py)
    }

    /// Adds a slider dyad on a line through `origin` carried by the link `from_ → to`, turned by
    /// `angle`.
    #[allow(clippy::too_many_arguments)]
    fn slider_on_link(
        &self,
        #[pyo3(from_py_with = named::pivot)] pivot: usize,
        r: Real,
        #[pyo3(from_py_with = named::origin)] origin: usize,
        #[pyo3(from_py_with = named::from_)] from_: usize,
        #[pyo3(from_py_with = named::to)] to: usize,
        angle: Real,
        reach: &str,
    ) -> PyResult<usize> {
        let reach = parse_reach(reach)?;
        let direction = LineDirection::Link {
            from: from_,
            to,
            angle: angle.0,
        };
        self.lock()
            .slider(pivot, r.0, origin, direction, reach)
            .map_err(to_py)
    }

    /// Adds a point carried by the link `from_ → to` at (along, left).
    fn point(
        &self,
        #[pyo3(from_py_with = named::from_)] from_: usize,
        #[pyo3(from_py_with = named::to)] to: usize,
        along: Real,
        left: Real,
    ) -> PyResult<usize> {
        self.lock().point(from_, to, along.0, left.0).map_err(to_py)
    }

    /// Constructions as tuples, for display: (kind, references, numbers, branch).
    fn describe(&self) -> Vec<String> {
        self.snapshot()
            .constructions()
            .iter()
            .map(|c| format!("{c:?}"))
            .collect()
    }

    /// Body (link) members as joint index lists, the ground first.
    fn bodies(&self) -> Vec<Vec<usize>> {
        let m = self.snapshot();
        let b = Bodies::of(&m);
        b.ids()
            .map(|id| (0..m.len()).filter(|&j| b.contains(id, j)).collect())
            .collect()
    }

    /// Kutzbach–Gruebler count: (links, lower pairs, higher pairs, degrees of freedom).
    fn mobility(&self) -> (usize, usize, usize, i64) {
        let m = Bodies::of(&self.snapshot()).mobility();
        (
            m.links,
            m.lower_pairs,
            m.higher_pairs,
            m.degrees_of_freedom(),
        )
    }

    /// Sweeps over `theta` (contiguous float64, 1-D). `omega`, `alpha`: None, one value, or one
    /// per angle. Returns a dict of numpy arrays.
    #[pyo3(signature = (theta, omega=None, alpha=None, velocity=false, acceleration=false,
                        instant_centres=false, curvature=false))]
    #[allow(clippy::too_many_arguments)]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
        omega: Option<PyReadonlyArray1<'py, f64>>,
        alpha: Option<PyReadonlyArray1<'py, f64>>,
        velocity: bool,
        acceleration: bool,
        instant_centres: bool,
        curvature: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let th = theta
            .as_slice()
            .map_err(|_| linkage_error("theta must be a contiguous float64 array"))?;
        let n = th.len();
        let (w, a) = (
            rate("omega", &omega, n, 0.0)?,
            rate("alpha", &alpha, n, 0.0)?,
        );
        let wanted = Wanted {
            velocity,
            acceleration,
            instant_centres,
            curvature,
        };
        let mech = self.snapshot();
        // Ctrl-C: the signal handler only sets a flag; check it between chunks of samples.
        let mut stopped: Option<PyErr> = None;
        let res = py.detach(|| {
            let mut go_on = || match Python::attach(|py| py.check_signals()) {
                Ok(()) => true,
                Err(e) => {
                    stopped = Some(e);
                    false
                }
            };
            sweep_arrays(&mech, th, w, a, wanted, &mut go_on)
        })?;
        if let Some(e) = stopped {
            return Err(e);
        }
        let j = mech.len();
        let np = body_pairs(Bodies::of(&mech).count()).len();
        let d = PyDict::new(py);
        d.set_item("joints", to_array3(py, res.joints, n, j)?)?;
        d.set_item("valid", PyArray1::from_vec(py, res.valid))?;
        d.set_item("margin", PyArray1::from_vec(py, res.margin))?;
        d.set_item("regular", PyArray1::from_vec(py, res.regular))?;
        d.set_item("gap", PyArray1::from_vec(py, res.gap))?;
        for (key, arr, cols) in [
            ("velocity", res.velocity, j),
            ("acceleration", res.acceleration, j),
            ("instant_centres", res.centres, np),
            ("instant_centre_directions", res.centre_directions, np),
            ("curvature_centres", res.curvature_centres, j),
        ] {
            if let Some(v) = arr {
                d.set_item(key, to_array3(py, v, n, cols)?)?;
            }
        }
        if let Some(k) = res.curvature {
            d.set_item("curvature", PyArray1::from_vec(py, k).reshape([n, j])?)?;
        }
        Ok(d)
    }
}
