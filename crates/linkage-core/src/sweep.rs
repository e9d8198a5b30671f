//! The sweep engine: a mechanism over many driver angles, every output written into slices the
//! caller provides (numpy arrays in the binding, static buffers on firmware).
//!
//! One call does what a sweep is: for each angle the [`Tracker`] places the joints on their
//! tracked branches (written straight into the caller's row), then, only for the outputs asked
//! for, the rates for the given drive, the instant centres of every pair of links and the path
//! curvature of every joint (both per unit crank angle: they do not depend on timing). Which
//! failures make an invalid sample (NaN rows, `valid` false) rather than an error is decided
//! here, once, for every caller.

use nalgebra::RealField;

use crate::bodies::{Bodies, BodyId, GROUND};
use crate::centres::{path_curvature, relative_centre, BodyMotion, Centre};
use crate::error::Error;
use crate::mechanism::{Mechanism, Motion};
use crate::scalar::{lit, nan, Vec2};
use crate::tracker::{Rates, Tracker};

/// Samples between two calls of a sweep's `go_on`, at most.
pub const SWEEP_CHUNK: usize = 4096;

/// Tracker placements (solves of every joint at one angle, [`Tracker::work`]) between two calls
/// of a sweep's `go_on`, at most: a sample costs one placement plus the grid points walked to
/// reach it (up to a few hundred for a jump of many turns), so counting work rather than
/// samples bounds the time between two checks (about 10 ms on a desktop) whatever the spacing
/// of the samples.
pub const SWEEP_WORK_CHUNK: u64 = 1 << 15;

/// A driver rate for a sweep: one value for every sample, or one per sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rate<'a, T> {
    /// The same value at every sample.
    Scalar(T),
    /// One value per sample (as many as angles).
    PerSample(&'a [T]),
}

impl<T: Copy> Rate<'_, T> {
    #[inline]
    fn at(&self, k: usize) -> T {
        match *self {
            Rate::Scalar(x) => x,
            Rate::PerSample(v) => v[k],
        }
    }
}

/// Where a sweep of `n` samples of a mechanism of `j` joints and `p` link pairs
/// ([`sweep_pairs`]) writes its results, row-major by sample. The per-sample fields are
/// always written; an output left `None` is not computed at all.
///
/// Every element of every slice given is written (the slices may hold anything before the
/// call): NaN rows at samples that do not assemble, and NaN entries where a value does not
/// exist (a centre at infinity in `centres`, a finite one in `centre_directions`).
#[derive(Debug)]
pub struct SweepOutputs<'a, T> {
    /// `n·j` joint positions (NaN where the sample is invalid).
    pub joints: &'a mut [Vec2<T>],
    /// `n`: whether each sample assembled.
    pub valid: &'a mut [bool],
    /// `n`: the smallest dyad margin (NaN where invalid).
    pub margin: &'a mut [T],
    /// `n`: whether a valid sample is clear of the rate margin ([`crate::rate_margin`]), so
    /// its rates, centres and curvatures are numbers.
    pub regular: &'a mut [bool],
    /// `n`: how much the lengths miss closure (0 where valid, NaN where undetermined).
    pub gap: &'a mut [T],
    /// `n·j` joint velocities for the drive (needs `omega`).
    pub velocity: Option<&'a mut [Vec2<T>]>,
    /// `n·j` joint accelerations for the drive.
    pub acceleration: Option<&'a mut [Vec2<T>]>,
    /// `n·p` finite instant centres of every pair of bodies (NaN otherwise).
    pub centres: Option<&'a mut [Vec2<T>]>,
    /// `n·p` directions of the instant centres at infinity (NaN otherwise).
    pub centre_directions: Option<&'a mut [Vec2<T>]>,
    /// `n·j` finite centres of curvature of every joint's path (NaN otherwise).
    pub curvature_centres: Option<&'a mut [Vec2<T>]>,
    /// `n·j` signed path curvatures of every joint.
    pub curvature: Option<&'a mut [T]>,
}

/// Number of body pairs `(k, l)`, `k < l` in [`Bodies::ids`] order, a sweep writes instant
/// centres for: `B(B − 1)/2` for `B` bodies, the ground included.
pub fn sweep_pairs<T: RealField + Copy, const N: usize>(mech: &Mechanism<T, N>) -> usize {
    let b = Bodies::of(mech).count();
    b * b.saturating_sub(1) / 2
}

/// How a sweep ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Swept {
    /// Samples written: all of them, or fewer when `go_on` stopped the sweep (the rows after
    /// them are left as they were).
    pub samples: usize,
    /// Tracker placements done ([`Tracker::work`]).
    pub work: u64,
}

/// Checks that `got` has `expected` elements.
fn check_len(what: &'static str, expected: usize, got: usize) -> Result<(), Error> {
    if expected == got {
        Ok(())
    } else {
        Err(Error::BufferLength {
            what,
            expected,
            got,
        })
    }
}

/// The motion of each body (the ground's, and `[joint][slot]` for the others).
struct Motions<T, const N: usize> {
    ground: BodyMotion<T>,
    of: [[BodyMotion<T>; 2]; N],
}

impl<T: RealField + Copy, const N: usize> Motions<T, N> {
    fn get(&self, id: BodyId) -> &BodyMotion<T> {
        if id == GROUND {
            &self.ground
        } else {
            &self.of[id.joint][usize::from(id.slot)]
        }
    }
}

/// Sweeps `mech` over the driver angles `theta` on tracked branches (see [`Tracker`]),
/// writing only the outputs `out` asks for.
///
/// `omega`, `alpha`: the crank's angular velocity and acceleration, for velocities and
/// accelerations (unused otherwise). Instant centres and curvatures use rates per unit crank
/// angle. A sample that does not assemble (a gap, an undetermined construction, numbers that
/// overflow, a non-finite angle or drive) is written as NaN rows with `valid` false and its
/// `gap` (NaN when there is none to give); it does not move the tracked branches.
///
/// `go_on` is called every [`SWEEP_CHUNK`] samples or [`SWEEP_WORK_CHUNK`] placements,
/// whichever comes first; when it returns false the sweep stops there (see [`Swept`]).
///
/// ```
/// use linkage_core::{sweep, sweep_pairs, Assembly, FourBar, Rate, SweepOutputs, Vec2};
/// let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let theta = [0.0, 0.5, 1.0];
/// let (n, j) = (theta.len(), m.len());
/// let mut joints = [Vec2::zeros(); 15];
/// let mut vel = [Vec2::zeros(); 15];
/// let (mut valid, mut regular) = ([false; 3], [false; 3]);
/// let (mut margin, mut gap) = ([0.0; 3], [0.0; 3]);
/// let out = SweepOutputs {
///     joints: &mut joints, valid: &mut valid, margin: &mut margin,
///     regular: &mut regular, gap: &mut gap, velocity: Some(&mut vel),
///     acceleration: None, centres: None, centre_directions: None,
///     curvature_centres: None, curvature: None,
/// };
/// let done = sweep(&m, &theta, Rate::Scalar(2.0), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// assert_eq!(done.samples, n);
/// assert!(valid.iter().all(|&v| v));
/// // The crank pin A (joint 2) turns at 2 rad/s on a radius of 10.
/// assert!((vel[j + 2].norm() - 20.0).abs() < 1e-12);
/// # let _ = sweep_pairs(&m);
/// ```
///
/// # Errors
/// [`Error::NoDriver`] for a mechanism without a crank; [`Error::BufferLength`] for an output
/// slice or per-sample rate of the wrong length. Nothing is written then.
pub fn sweep<T: RealField + Copy, const N: usize>(
    mech: &Mechanism<T, N>,
    theta: &[T],
    omega: Rate<'_, T>,
    alpha: Rate<'_, T>,
    out: SweepOutputs<'_, T>,
    go_on: &mut dyn FnMut() -> bool,
) -> Result<Swept, Error> {
    let (n, j) = (theta.len(), mech.len());
    let mut tracker = Tracker::new(mech)?;
    let bodies = Bodies::of(mech);
    let nb = bodies.count();
    let np = nb * nb.saturating_sub(1) / 2;
    let SweepOutputs {
        joints,
        valid,
        margin,
        regular,
        gap,
        mut velocity,
        mut acceleration,
        mut centres,
        mut centre_directions,
        mut curvature_centres,
        mut curvature,
    } = out;
    let rows = n.saturating_mul(j);
    check_len("joints", rows, joints.len())?;
    check_len("valid", n, valid.len())?;
    check_len("margin", n, margin.len())?;
    check_len("regular", n, regular.len())?;
    check_len("gap", n, gap.len())?;
    for (what, len, got) in [
        ("velocity", rows, velocity.as_ref().map(|v| v.len())),
        ("acceleration", rows, acceleration.as_ref().map(|v| v.len())),
        (
            "centres",
            n.saturating_mul(np),
            centres.as_ref().map(|v| v.len()),
        ),
        (
            "centre_directions",
            n.saturating_mul(np),
            centre_directions.as_ref().map(|v| v.len()),
        ),
        (
            "curvature_centres",
            rows,
            curvature_centres.as_ref().map(|v| v.len()),
        ),
        ("curvature", rows, curvature.as_ref().map(|v| v.len())),
    ] {
        if let Some(got) = got {
            check_len(what, len, got)?;
        }
    }
    for (what, r) in [("omega", omega), ("alpha", alpha)] {
        if let Rate::PerSample(v) = r {
            check_len(what, n, v.len())?;
        }
    }

    let nan_t = nan::<T>();
    let nan2 = Vec2::new(nan_t, nan_t);
    let zero = [Vec2::zeros(); N];
    let rates = velocity.is_some() || acceleration.is_some();
    let wants_centres = centres.is_some() || centre_directions.is_some();
    let wants_curvature = curvature.is_some() || curvature_centres.is_some();
    // Velocities for accelerations asked without them, and the unit-drive rates of centres
    // and curvature.
    let mut own_vel = zero;
    let (mut uvel, mut uacc) = (zero, zero);
    let still = BodyMotion::of(
        &bodies,
        GROUND,
        &zero[..0],
        &zero[..0],
        &zero[..0],
        &zero[..0],
    );
    let mut motions = Motions {
        ground: still,
        of: [[still; 2]; N],
    };
    let mut next_check = SWEEP_WORK_CHUNK;
    for (k, &th) in theta.iter().enumerate() {
        if k > 0 && (k % SWEEP_CHUNK == 0 || tracker.work() >= next_check) {
            if !go_on() {
                return Ok(Swept {
                    samples: k,
                    work: tracker.work(),
                });
            }
            next_check = tracker.work().saturating_add(SWEEP_WORK_CHUNK);
        }
        let row = k * j..(k + 1) * j;
        let pos = &mut joints[row.clone()];
        let motion = rates.then(|| Motion::new(omega.at(k), alpha.at(k)));
        let buffers = match (velocity.as_deref_mut(), acceleration.as_deref_mut()) {
            (Some(v), Some(a)) => Rates::acceleration(&mut v[row.clone()], &mut a[row.clone()]),
            (None, Some(a)) => Rates::acceleration(&mut own_vel[..j], &mut a[row.clone()]),
            (Some(v), None) => Rates::velocity(&mut v[row.clone()]),
            (None, None) => Rates::none(),
        };
        let step = tracker.step(th, motion, pos, buffers);
        let s = match step {
            Ok(s) => s,
            Err(
                e @ (Error::CannotAssemble { .. }
                | Error::Coincident { .. }
                | Error::NotFinite { .. }),
            ) => {
                valid[k] = false;
                margin[k] = nan_t;
                regular[k] = false;
                gap[k] = match e {
                    Error::CannotAssemble { gap, .. } => lit(gap),
                    _ => nan_t,
                };
                for buf in [
                    Some(&mut *joints),
                    velocity.as_deref_mut(),
                    acceleration.as_deref_mut(),
                    curvature_centres.as_deref_mut(),
                ]
                .into_iter()
                .flatten()
                {
                    buf[row.clone()].fill(nan2);
                }
                if let Some(c) = curvature.as_deref_mut() {
                    c[row.clone()].fill(nan_t);
                }
                let pairs = k * np..(k + 1) * np;
                for buf in [centres.as_deref_mut(), centre_directions.as_deref_mut()]
                    .into_iter()
                    .flatten()
                {
                    buf[pairs.clone()].fill(nan2);
                }
                continue;
            }
            Err(e) => return Err(e),
        };
        valid[k] = true;
        margin[k] = s.margin;
        regular[k] = s.regular;
        gap[k] = T::zero();
        if !(wants_centres || wants_curvature) {
            continue;
        }
        let pos = &joints[row.clone()];
        let unit_acc = wants_curvature.then_some(&mut uacc[..j]);
        mech.motion(pos, Motion::unit(), &mut uvel[..j], unit_acc, None)?;
        if wants_centres {
            for id in bodies.ids() {
                let m = BodyMotion::of(&bodies, id, pos, &uvel[..j], &zero[..j], &zero[..j])
                    .conditioned(s.margin);
                if id == GROUND {
                    motions.ground = m;
                } else {
                    motions.of[id.joint][usize::from(id.slot)] = m;
                }
            }
            let mut q = k * np;
            for (a, ka) in bodies.ids().enumerate() {
                for kb in bodies.ids().skip(a + 1) {
                    let ic =
                        relative_centre(&bodies, (ka, motions.get(ka)), (kb, motions.get(kb)), pos);
                    let (finite, far) = match ic {
                        Centre::Finite(p) => (p, nan2),
                        Centre::AtInfinity(d) => (nan2, d),
                        Centre::Undefined => (nan2, nan2),
                    };
                    if let Some(c) = centres.as_deref_mut() {
                        c[q] = finite;
                    }
                    if let Some(d) = centre_directions.as_deref_mut() {
                        d[q] = far;
                    }
                    q += 1;
                }
            }
        }
        if wants_curvature {
            for i in 0..j {
                let (kappa, centre) = path_curvature(pos[i], uvel[i], uacc[i]);
                if let Some(c) = curvature.as_deref_mut() {
                    c[k * j + i] = kappa;
                }
                if let Some(c) = curvature_centres.as_deref_mut() {
                    c[k * j + i] = centre.finite().unwrap_or(nan2);
                }
            }
        }
    }
    Ok(Swept {
        samples: n,
        work: tracker.work(),
    })
}
