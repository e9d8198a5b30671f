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

use crate::error::Error;
use crate::mechanism::bodies::{Bodies, BodyId, GROUND};
use crate::mechanism::joint_rates::rate_margin;
use crate::mechanism::program::{CrankRates, Mechanism};
use crate::motion::centres::{path_curvature, relative_centre, BodyMotion, Centre};
use crate::numeric::scalar::{lit, nan, Vec2};
use crate::sweep::block_centres::BlockCentres;
use crate::sweep::block_poses::{padded, BlockJointRates, BlockPoses, BLOCK};
use crate::sweep::layout::{Columns, Pairs};
use crate::sweep::tracker::{Rates, Tracker};

/// Samples between two calls of a sweep's `go_on`, at most.
pub const SWEEP_CHUNK: usize = 4096;

/// Tracker placements (solves of every joint at one angle, [`Tracker::work`]) between two calls
/// of a sweep's `go_on`, at most: a sample costs one placement plus the grid points walked to
/// reach it (up to a few hundred for a jump of many turns), so counting work rather than
/// samples bounds the time between two checks (about 10 ms on a desktop) whatever the spacing
/// of the samples.
#[doc(hidden)]
pub const SWEEP_WORK_CHUNK: u64 = 1 << 15;

/// A driver rate for a sweep: one value for every sample, or one per sample.
///
/// ```
/// use linkage_core::{catalog, sweep, Error, Rate, SweepOutputs, Vec2};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let theta = [0.0, 1.0];
/// let (mut joints, mut valid, mut vel) = ([Vec2::zeros(); 10], [false; 2], [Vec2::zeros(); 10]);
/// let mut out = SweepOutputs::positions(&mut joints, &mut valid);
/// out.velocity = Some(&mut vel);
/// // A crank speeding up: 1 rad/s at the first sample, 3 at the second (crank pin A = joint 2).
/// sweep(&m, &theta, Rate::PerSample(&[1.0, 3.0]), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// assert!((vel[2].norm() - 10.0).abs() < 1e-12 && (vel[5 + 2].norm() - 30.0).abs() < 1e-12);
/// // One value per angle, or an error.
/// let out = SweepOutputs::positions(&mut joints, &mut valid);
/// let short = sweep(&m, &theta, Rate::PerSample(&[1.0]), Rate::Scalar(0.0), out, &mut || true);
/// assert_eq!(short, Err(Error::BufferLength { what: "omega", expected: 2, got: 1 }));
/// ```
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

impl<T: RealField + Copy> Rate<'_, T> {
    /// The values at samples `k0 … k0 + BLOCK` as a block ([`padded`]).
    #[inline(always)]
    fn block(&self, k0: usize) -> [T; BLOCK] {
        match *self {
            Rate::Scalar(x) => [x; BLOCK],
            Rate::PerSample(v) => padded(v.get(k0..).unwrap_or_default()),
        }
    }
}

/// Where a sweep of `n` samples of a mechanism of `j` joints and `p` body pairs
/// ([`Pairs::count`]) writes its results, row-major by sample, `w` entries per sample in the
/// per-joint outputs (`w = columns.width(j)`). `joints` and `valid` are always written; an
/// output left `None` is not computed at all.
///
/// Every element of every slice given is written (the slices may hold anything before the
/// call): NaN rows at samples that do not assemble, and NaN entries where a value does not
/// exist (a centre at infinity in `centres`, a finite one in `centre_directions`).
///
/// ```
/// use linkage_core::{catalog, sweep, Rate, SweepOutputs, Vec2};
/// // Evans C's crank reaches only |θ| ≤ acos(1/4) ≈ 1.32: at θ = 2 it does not assemble.
/// let m = catalog::evans_c::<f64>().mechanism();
/// let (mut joints, mut valid, mut gap) = ([Vec2::zeros(); 10], [false; 2], [0.0; 2]);
/// let mut out = SweepOutputs::positions(&mut joints, &mut valid);
/// out.gap = Some(&mut gap);
/// sweep(&m, &[0.0, 2.0], Rate::Scalar(0.0), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// assert_eq!(valid, [true, false]);
/// assert!(joints[5..].iter().all(|p| p.x.is_nan() && p.y.is_nan()));
/// assert!(gap[0] == 0.0 && gap[1] > 5.0); // |AC| ≈ 25.8 at θ = 2, coupler + rocker = 20
/// ```
#[derive(Debug)]
pub struct SweepOutputs<'a, T> {
    /// Which joints `joints`, `velocity`, `acceleration`, `curvature_centres` and `curvature`
    /// hold.
    pub columns: Columns,
    /// `n·w` joint positions (NaN where the sample is invalid).
    pub joints: &'a mut [Vec2<T>],
    /// `n`: whether each sample assembled.
    pub valid: &'a mut [bool],
    /// `n`: the smallest dyad margin (NaN where invalid).
    pub margin: Option<&'a mut [T]>,
    /// `n`: whether a valid sample is clear of the rate margin ([`crate::rate_margin`]), so
    /// its rates, centres and curvatures are numbers.
    pub regular: Option<&'a mut [bool]>,
    /// `n`: how much the lengths miss closure (0 where valid, NaN where undetermined).
    pub gap: Option<&'a mut [T]>,
    /// `n·w` joint velocities for the drive (needs `omega`).
    pub velocity: Option<&'a mut [Vec2<T>]>,
    /// `n·w` joint accelerations for the drive.
    pub acceleration: Option<&'a mut [Vec2<T>]>,
    /// Which pairs of bodies `centres` and `centre_directions` hold (default: every pair).
    pub pairs: Pairs<'a>,
    /// `n·p` finite instant centres of the pairs `pairs` names (NaN otherwise).
    pub centres: Option<&'a mut [Vec2<T>]>,
    /// `n·p` directions of the instant centres at infinity (NaN otherwise).
    pub centre_directions: Option<&'a mut [Vec2<T>]>,
    /// `n·w` finite centres of curvature of the joints' paths (NaN otherwise).
    pub curvature_centres: Option<&'a mut [Vec2<T>]>,
    /// `n·w` signed path curvatures of the joints.
    pub curvature: Option<&'a mut [T]>,
}

impl<'a, T> SweepOutputs<'a, T> {
    /// Positions of every joint and the validity flags only (add outputs by setting fields).
    pub fn positions(joints: &'a mut [Vec2<T>], valid: &'a mut [bool]) -> Self {
        SweepOutputs {
            columns: Columns::All,
            joints,
            valid,
            margin: None,
            regular: None,
            gap: None,
            velocity: None,
            acceleration: None,
            pairs: Pairs::All,
            centres: None,
            centre_directions: None,
            curvature_centres: None,
            curvature: None,
        }
    }
}

/// Number of body pairs `(k, l)`, `k < l` in [`Bodies::ids`] order, a sweep writes instant
/// centres for: `B(B − 1)/2` for `B` bodies, the ground included.
pub fn sweep_pairs<T: RealField + Copy, const N: usize>(mech: &Mechanism<T, N>) -> usize {
    Pairs::All.count(Bodies::of(mech).count())
}

/// How a sweep ended.
///
/// ```
/// use linkage_core::{catalog, sweep, Rate, SweepOutputs, Vec2, SWEEP_CHUNK};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let n = SWEEP_CHUNK + 10;
/// let theta: Vec<f64> = (0..n).map(|k| k as f64 * 1e-3).collect();
/// let (mut joints, mut valid) = (vec![Vec2::zeros(); 5 * n], vec![false; n]);
/// // `go_on` says stop at its first call: the first chunk of samples is written, no more.
/// let out = SweepOutputs::positions(&mut joints, &mut valid);
/// let done = sweep(&m, &theta, Rate::Scalar(0.0), Rate::Scalar(0.0), out, &mut || false).unwrap();
/// assert_eq!(done.samples, SWEEP_CHUNK);
/// assert!(valid[..SWEEP_CHUNK].iter().all(|&v| v) && !valid[SWEEP_CHUNK]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Swept {
    /// Samples written: all of them, or fewer when `go_on` stopped the sweep (the rows after
    /// them are left as they were).
    pub samples: usize,
    /// Tracker placements done ([`Tracker::work`]; 0 when the held pass swept it).
    pub work: u64,
    /// Whether the held pass swept it (see [`Plan`]).
    pub held: bool,
}

/// How [`sweep_planned`] sweeps. Every plan gives the same results, bit for bit.
///
/// ```
/// use linkage_core::{catalog, sweep_planned, Plan, Rate, SweepOutputs, Vec2};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let theta = [0.3, 2.0, 1.0];
/// let run = |plan| {
///     let (mut joints, mut valid) = ([Vec2::zeros(); 15], [false; 3]);
///     let out = SweepOutputs::positions(&mut joints, &mut valid);
///     let still = Rate::Scalar(0.0);
///     let s = sweep_planned(&m, &theta, still, still, out, &mut || true, plan);
///     (joints, s.unwrap())
/// };
/// let ((tracked, t), (held, h)) = (run(Plan::Tracked), run(Plan::Held));
/// assert_eq!(tracked, held); // the same bits either way
/// assert!(!t.held && t.work > 0);
/// assert!(h.held && h.work == 0); // a crank-rocker never nears a toggle: posed directly
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Plan {
    /// The held pass when there are at least as many samples as the tracker's grid points
    /// per turn (so its check costs at most one pose per sample), or a block of them for a
    /// mechanism whose orientations are in closed form (no check: every full-turn four-bar,
    /// change points included, see [`Tracker`]); the tracker otherwise.
    #[default]
    Auto,
    /// The tracker, sample by sample.
    Tracked,
    /// The held pass whenever it applies, however few the samples.
    Held,
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

/// What one sweep call needs besides its outputs: the mechanism, its bodies, what is asked,
/// and scratch rows.
struct Engine<'m, T: RealField + Copy, const N: usize> {
    mech: &'m Mechanism<T, N>,
    bodies: Bodies<N>,
    /// Joints and body pairs.
    j: usize,
    np: usize,
    columns: Columns,
    rates: bool,
    wants_acc: bool,
    wants_centres: bool,
    wants_curvature: bool,
    /// One sample's positions, velocities and accelerations of every joint.
    pos: [Vec2<T>; N],
    vel: [Vec2<T>; N],
    acc: [Vec2<T>; N],
    /// Unit-drive rates of centres and curvature.
    uvel: [Vec2<T>; N],
    uacc: [Vec2<T>; N],
    motions: Motions<T, N>,
}

/// Writes `row` (every joint of one sample) into sample `k`'s entries of a per-joint output.
#[inline]
fn put<V: Copy>(buf: &mut [V], columns: Columns, k: usize, row: &[V]) {
    match columns {
        Columns::All => buf[k * row.len()..(k + 1) * row.len()].copy_from_slice(row),
        Columns::One(t) => buf[k] = row[t],
    }
}

/// Fills sample `k`'s entries of a per-joint output with `v`.
#[inline]
fn fill<V: Copy>(buf: &mut [V], columns: Columns, k: usize, j: usize, v: V) {
    let w = columns.width(j);
    buf[k * w..(k + 1) * w].fill(v);
}

impl<'m, T: RealField + Copy, const N: usize> Engine<'m, T, N> {
    /// Writes sample `k` as invalid: NaN rows everywhere, `gap` its gap.
    fn invalid(&self, out: &mut SweepOutputs<'_, T>, k: usize, gap: T) {
        let nan_t = nan::<T>();
        let nan2 = Vec2::new(nan_t, nan_t);
        let (j, cols) = (self.j, self.columns);
        out.valid[k] = false;
        if let Some(m) = out.margin.as_deref_mut() {
            m[k] = nan_t;
        }
        if let Some(r) = out.regular.as_deref_mut() {
            r[k] = false;
        }
        if let Some(g) = out.gap.as_deref_mut() {
            g[k] = gap;
        }
        for buf in [
            Some(&mut *out.joints),
            out.velocity.as_deref_mut(),
            out.acceleration.as_deref_mut(),
            out.curvature_centres.as_deref_mut(),
        ]
        .into_iter()
        .flatten()
        {
            fill(buf, cols, k, j, nan2);
        }
        if let Some(c) = out.curvature.as_deref_mut() {
            fill(c, cols, k, j, nan_t);
        }
        let pairs = k * self.np..(k + 1) * self.np;
        for buf in [
            out.centres.as_deref_mut(),
            out.centre_directions.as_deref_mut(),
        ]
        .into_iter()
        .flatten()
        {
            buf[pairs.clone()].fill(nan2);
        }
    }

    /// Writes sample `k`, valid with its joints in `self.pos` (and its rates in `self.vel`,
    /// `self.acc` when asked): positions, flags, rates, and the instant centres and curvatures
    /// asked for (per unit crank angle).
    fn valid(
        &mut self,
        out: &mut SweepOutputs<'_, T>,
        k: usize,
        margin: T,
        regular: bool,
    ) -> Result<(), Error> {
        let (j, np, cols) = (self.j, self.np, self.columns);
        put(out.joints, cols, k, &self.pos[..j]);
        out.valid[k] = true;
        if let Some(m) = out.margin.as_deref_mut() {
            m[k] = margin;
        }
        if let Some(r) = out.regular.as_deref_mut() {
            r[k] = regular;
        }
        if let Some(g) = out.gap.as_deref_mut() {
            g[k] = T::zero();
        }
        if let Some(v) = out.velocity.as_deref_mut() {
            put(v, cols, k, &self.vel[..j]);
        }
        if let Some(a) = out.acceleration.as_deref_mut() {
            put(a, cols, k, &self.acc[..j]);
        }
        if !(self.wants_centres || self.wants_curvature) {
            return Ok(());
        }
        let nan2 = Vec2::new(nan::<T>(), nan::<T>());
        let zero = [Vec2::zeros(); N];
        let pos = &self.pos[..j];
        let unit_acc = self.wants_curvature.then_some(&mut self.uacc[..j]);
        self.mech
            .rates(pos, CrankRates::unit(), &mut self.uvel[..j], unit_acc, None)?;
        if self.wants_centres {
            let bodies = &self.bodies;
            for id in bodies.ids() {
                let m = BodyMotion::of(bodies, id, pos, &self.uvel[..j], &zero[..j], &zero[..j])
                    .conditioned(margin);
                if id == GROUND {
                    self.motions.ground = m;
                } else {
                    self.motions.of[id.joint][usize::from(id.slot)] = m;
                }
            }
            let motions = &self.motions;
            out.pairs.each(bodies, |q, ka, kb| {
                let ic = relative_centre(bodies, (ka, motions.get(ka)), (kb, motions.get(kb)), pos);
                let (finite, far) = match ic {
                    Centre::Finite(p) => (p, nan2),
                    Centre::AtInfinity(d) => (nan2, d),
                    Centre::Undefined => (nan2, nan2),
                };
                if let Some(c) = out.centres.as_deref_mut() {
                    c[k * np + q] = finite;
                }
                if let Some(d) = out.centre_directions.as_deref_mut() {
                    d[k * np + q] = far;
                }
            });
        }
        if self.wants_curvature {
            let mut write = |i: usize, e: usize| {
                let (kappa, centre) = path_curvature(pos[i], self.uvel[i], self.uacc[i]);
                if let Some(c) = out.curvature.as_deref_mut() {
                    c[e] = kappa;
                }
                if let Some(c) = out.curvature_centres.as_deref_mut() {
                    c[e] = centre.finite().unwrap_or(nan2);
                }
            };
            match cols {
                Columns::All => (0..j).for_each(|i| write(i, k * j + i)),
                Columns::One(t) => write(t, k),
            }
        }
        Ok(())
    }

    /// Rates of the joints in `self.pos` for the drive `(w, a)` into `self.vel`, `self.acc`;
    /// whether they are regular. `None` for a drive that is not finite.
    fn rates_at(&mut self, w: T, a: T) -> Result<Option<bool>, Error> {
        if !(w.is_finite() && a.is_finite()) {
            return Ok(None);
        }
        let j = self.j;
        let acc = self.wants_acc.then_some(&mut self.acc[..j]);
        self.mech
            .rates(
                &self.pos[..j],
                CrankRates::new(w, a),
                &mut self.vel[..j],
                acc,
                None,
            )
            .map(Some)
    }

    /// The tracker, sample by sample.
    fn tracked(
        &mut self,
        tracker: &mut Tracker<'m, T, N>,
        theta: &[T],
        (omega, alpha): (Rate<'_, T>, Rate<'_, T>),
        out: &mut SweepOutputs<'_, T>,
        go_on: &mut dyn FnMut() -> bool,
    ) -> Result<Swept, Error> {
        let j = self.j;
        let mut next_check = SWEEP_WORK_CHUNK;
        for (k, &th) in theta.iter().enumerate() {
            if k > 0 && (k % SWEEP_CHUNK == 0 || tracker.work() >= next_check) {
                if !go_on() {
                    return Ok(Swept {
                        samples: k,
                        work: tracker.work(),
                        held: false,
                    });
                }
                next_check = tracker.work().saturating_add(SWEEP_WORK_CHUNK);
            }
            let motion = self
                .rates
                .then(|| CrankRates::new(omega.at(k), alpha.at(k)));
            let buffers = match (self.rates, self.wants_acc) {
                (true, true) => Rates::acceleration(&mut self.vel[..j], &mut self.acc[..j]),
                (true, false) => Rates::velocity(&mut self.vel[..j]),
                _ => Rates::none(),
            };
            match tracker.step(th, motion, &mut self.pos[..j], buffers) {
                Ok(s) => self.valid(out, k, s.margin, s.regular)?,
                Err(
                    e @ (Error::CannotAssemble { .. }
                    | Error::Coincident { .. }
                    | Error::NotFinite { .. }),
                ) => {
                    let gap = match e {
                        Error::CannotAssemble { gap, .. } => lit(gap),
                        _ => nan::<T>(),
                    };
                    self.invalid(out, k, gap);
                }
                Err(e) => return Err(e),
            }
        }
        Ok(Swept {
            samples: theta.len(),
            work: tracker.work(),
            held: false,
        })
    }

    /// Writes a posed block straight from `blk` (and its rates from `rates`, when the sweep
    /// asks for rates) when every sample of it is plain: a finite angle and drive, posed by the
    /// kernel, watched margins clear of `toggle_margin`. What the sample-by-sample path writes,
    /// without its per-sample work. Returns whether it wrote the block.
    #[inline(always)]
    #[allow(
        clippy::too_many_arguments,
        reason = "the block, its rates and drive, and where it goes"
    )]
    fn block_write(
        &self,
        blk: &BlockPoses<T, N>,
        rates: Option<(&BlockJointRates<T, N>, &[T; BLOCK], &[T; BLOCK])>,
        toggle_margin: T,
        theta: &[T],
        k0: usize,
        out: &mut SweepOutputs<'_, T>,
    ) -> bool {
        let m = theta.len().min(BLOCK);
        // A fold without early exit over the whole block: it vectorises.
        let mut plain = true;
        for (b, th) in theta[..m].iter().enumerate() {
            plain &= th.is_finite()
                & !blk.scalar[b]
                & !blk.failed[b]
                & (blk.watched[b] >= toggle_margin);
        }
        if let Some((r, w, a)) = rates {
            for b in 0..m {
                plain &= w[b].is_finite() & a[b].is_finite() & !r.scalar[b];
            }
        }
        if !plain {
            return false;
        }
        let (j, cols) = (self.j, self.columns);
        let write = |buf: &mut [Vec2<T>], x: &[[T; BLOCK]; N], y: &[[T; BLOCK]; N]| match cols {
            Columns::One(t) => match <&mut [Vec2<T>; BLOCK]>::try_from(&mut buf[k0..k0 + m]) {
                // A whole block: a loop of known length, which vectorises.
                Ok(whole) => {
                    for (b, p) in whole.iter_mut().enumerate() {
                        *p = Vec2::new(x[t][b], y[t][b]);
                    }
                }
                Err(_) => {
                    for (b, p) in buf[k0..k0 + m].iter_mut().enumerate() {
                        *p = Vec2::new(x[t][b], y[t][b]);
                    }
                }
            },
            Columns::All => {
                for (b, row) in buf[k0 * j..(k0 + m) * j].chunks_exact_mut(j).enumerate() {
                    for (i, p) in row.iter_mut().enumerate() {
                        *p = Vec2::new(x[i][b], y[i][b]);
                    }
                }
            }
        };
        write(out.joints, &blk.x, &blk.y);
        if let Some((r, _, _)) = rates {
            if let Some(v) = out.velocity.as_deref_mut() {
                write(v, &r.vx, &r.vy);
            }
            if let Some(a) = out.acceleration.as_deref_mut() {
                write(a, &r.ax, &r.ay);
            }
        }
        out.valid[k0..k0 + m].fill(true);
        if let Some(g) = out.margin.as_deref_mut() {
            g[k0..k0 + m].copy_from_slice(&blk.margin[..m]);
        }
        if let Some(reg) = out.regular.as_deref_mut() {
            match rates {
                Some((r, _, _)) => reg[k0..k0 + m].copy_from_slice(&r.regular[..m]),
                None => {
                    let m_star = rate_margin::<T>();
                    for (reg, &g) in reg[k0..k0 + m].iter_mut().zip(&blk.margin[..m]) {
                        *reg = g >= m_star;
                    }
                }
            }
        }
        if let Some(g) = out.gap.as_deref_mut() {
            g[k0..k0 + m].fill(T::zero());
        }
        true
    }

    /// Writes the instant centres and curvatures asked for of the `m` samples of a block
    /// that [`Self::block_write`] wrote (from sample `k0` on), from unit-drive rates: what
    /// [`Self::valid`] writes, a block at a time. Returns false, having written some of them,
    /// when a sample needs the scalar code (see [`BlockCentres`]): the block must be redone.
    #[inline(always)]
    fn block_centres(
        &self,
        blk: &BlockPoses<T, N>,
        unit: &mut BlockJointRates<T, N>,
        cen: &mut BlockCentres<T, N>,
        (k0, m): (usize, usize),
        out: &mut SweepOutputs<'_, T>,
    ) -> bool {
        unit.rates(self.mech, blk, &[T::one(); BLOCK], &[T::zero(); BLOCK]);
        cen.start();
        if self.wants_centres {
            cen.bodies(&self.bodies, blk, unit);
            let (c, d) = (
                out.centres.as_deref_mut(),
                out.centre_directions.as_deref_mut(),
            );
            cen.centres(&self.bodies, blk, unit, (k0, m, self.np), c, d);
        }
        if self.wants_curvature {
            let (kappa, c) = (
                out.curvature.as_deref_mut(),
                out.curvature_centres.as_deref_mut(),
            );
            cen.curvature(blk, unit, self.columns, (k0, m, self.j), kappa, c);
        }
        !(unit.scalar[..m].iter().any(|&s| s) || cen.scalar[..m].iter().any(|&s| s))
    }

    /// The held pass: every sample posed on the declared orientations, no walk (valid only
    /// after [`Tracker::holds_everywhere`]), a block of samples at a time where the block
    /// kernel applies ([`BlockPoses`]: the same bits as one pose). With a `reference` angle
    /// (a mechanism whose orientations are in closed form, [`Tracker::closed_form`]) the dyads
    /// with flat positions are turned at each one crossed from there, as the tracker turns
    /// them. Returns `None`, having written some rows, at the first sample whose own `watched`
    /// margins are below the toggle margin or that does not assemble: the tracker must sweep
    /// then.
    #[inline(always)]
    #[allow(
        clippy::too_many_arguments,
        reason = "the pass's rule (margin, watched dyads, reference), its samples and outputs"
    )]
    fn held(
        &mut self,
        toggle_margin: T,
        watched: &[bool],
        reference: Option<T>,
        theta: &[T],
        (omega, alpha): (Rate<'_, T>, Rate<'_, T>),
        out: &mut SweepOutputs<'_, T>,
        go_on: &mut dyn FnMut() -> bool,
    ) -> Result<Option<Swept>, Error> {
        let j = self.j;
        let m_star = rate_margin::<T>();
        let blocks = BlockPoses::<T, N>::applies(self.mech);
        let mut blk = BlockPoses::<T, N>::new();
        blk.prepare(self.mech);
        if let Some(r) = reference {
            blk.orient(self.mech, r);
        }
        let mut rts = BlockJointRates::<T, N>::new();
        // Unit-drive rates and body turns, built only for sweeps that ask for centres or
        // curvatures (their tables are sized by the capacity).
        let mut scratch = (self.wants_centres || self.wants_curvature).then(|| {
            (
                BlockJointRates::<T, N>::new(),
                BlockCentres::<T, N>::new(&self.bodies, out.pairs),
            )
        });
        // Margins are needed for the watched dyads always, for the others only when written
        // (margin, regular) or used (centres condition on them; rates by the sample path).
        // Curvatures do not use them.
        blk.margins =
            out.margin.is_some() || out.regular.is_some() || self.rates || self.wants_centres;
        let n = theta.len();
        let mut k0 = 0;
        while k0 < n {
            // SWEEP_CHUNK is a multiple of BLOCK: blocks never straddle a check.
            if k0 > 0 && k0 % SWEEP_CHUNK == 0 && !go_on() {
                return Ok(Some(Swept {
                    samples: k0,
                    work: 0,
                    held: true,
                }));
            }
            let k1 = (k0 + BLOCK).min(n);
            if blocks {
                blk.pose(self.mech, &padded(&theta[k0..k1]), watched);
                let mut done = if self.rates {
                    let (w, a) = (omega.block(k0), alpha.block(k0));
                    rts.rates(self.mech, &blk, &w, &a);
                    let r = Some((&rts, &w, &a));
                    self.block_write(&blk, r, toggle_margin, &theta[k0..k1], k0, out)
                } else {
                    self.block_write(&blk, None, toggle_margin, &theta[k0..k1], k0, out)
                };
                if let (true, Some((unit, cen))) = (done, scratch.as_mut()) {
                    done = self.block_centres(&blk, unit, cen, (k0, k1 - k0), out);
                }
                if done {
                    k0 = k1;
                    continue;
                }
            }
            for (b, &th) in theta[k0..k1].iter().enumerate() {
                let k = k0 + b;
                // The tracker's order: the angle, the pose, then the drive.
                if !th.is_finite() {
                    self.invalid(out, k, nan::<T>());
                    continue;
                }
                let (margin, least) = if blocks && !blk.scalar[b] {
                    if blk.failed[b] {
                        return Ok(None);
                    }
                    for (i, p) in self.pos[..j].iter_mut().enumerate() {
                        *p = Vec2::new(blk.x[i][b], blk.y[i][b]);
                    }
                    (blk.margin[b], blk.watched[b])
                } else {
                    let flipped = blk.flipped(th);
                    match self
                        .mech
                        .pose_oriented(th, &mut self.pos[..j], watched, &flipped)
                    {
                        Ok(m) => m,
                        Err(_) => return Ok(None),
                    }
                };
                if least < toggle_margin || !least.is_finite() {
                    return Ok(None);
                }
                let regular = if self.rates {
                    match self.rates_at(omega.at(k), alpha.at(k))? {
                        Some(r) => r,
                        None => {
                            self.invalid(out, k, nan::<T>());
                            continue;
                        }
                    }
                } else {
                    margin >= m_star
                };
                self.valid(out, k, margin, regular)?;
            }
            k0 = k1;
        }
        Ok(Some(Swept {
            samples: n,
            work: 0,
            held: true,
        }))
    }
}

/// Sweeps `mech` over the driver angles `theta` on tracked branches (see [`Tracker`]),
/// writing only the outputs `out` asks for; [`sweep_planned`] with [`Plan::Auto`].
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
/// use linkage_core::{sweep, Assembly, Columns, FourBar, Rate, SweepOutputs, Vec2};
/// let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let theta = [0.0, 0.5, 1.0];
/// let n = theta.len();
/// // Every joint's position, and the crank pin A's velocity only (columns: joint 2).
/// let mut joints = [Vec2::zeros(); 15];
/// let mut valid = [false; 3];
/// let mut out = SweepOutputs::positions(&mut joints, &mut valid);
/// sweep(&m, &theta, Rate::Scalar(0.0), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// assert!(valid.iter().all(|&v| v));
/// let (mut a, mut va, mut ok) = ([Vec2::zeros(); 3], [Vec2::zeros(); 3], [false; 3]);
/// let mut out = SweepOutputs::positions(&mut a, &mut ok);
/// out.columns = Columns::One(FourBar::<f64>::A);
/// out.velocity = Some(&mut va);
/// let done = sweep(&m, &theta, Rate::Scalar(2.0), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// assert_eq!(done.samples, n);
/// // The crank pin turns at 2 rad/s on a radius of 10: 20 a second, at the joint's row.
/// assert!((va[1].norm() - 20.0).abs() < 1e-12 && a[1] == joints[5 + 2]);
/// ```
///
/// # Errors
/// [`Error::NoDriver`] for a mechanism without a crank; [`Error::BufferLength`] for an output
/// slice or per-sample rate of the wrong length, or [`Columns::One`] naming no joint;
/// [`Error::OutOfRange`] for a pair of [`Pairs::Only`] naming no body, [`Error::InvalidChoice`]
/// for one naming the same body twice. Nothing is written then.
// Inlined into its caller, so a caller compiled for wider vectors (the binding's AVX builds)
// gets the block kernel compiled for them too.
#[inline(always)]
pub fn sweep<T: RealField + Copy, const N: usize>(
    mech: &Mechanism<T, N>,
    theta: &[T],
    omega: Rate<'_, T>,
    alpha: Rate<'_, T>,
    out: SweepOutputs<'_, T>,
    go_on: &mut dyn FnMut() -> bool,
) -> Result<Swept, Error> {
    sweep_planned(mech, theta, omega, alpha, out, go_on, Plan::Auto)
}

/// [`sweep`], choosing how: the tracker sample by sample, or the held pass.
///
/// # The held pass
/// Tracking costs a walk of the canonical path between samples (see [`Tracker`]): cheap for
/// samples in order, up to hundreds of placements per sample for angles in arbitrary order.
/// Most linkages never come near a toggle: when every grid point of the turn places on the
/// declared orientations with the margin of every dyad that may flip at least the toggle
/// margin (one pose per grid point; a four-bar-like dyad on a crank pin and a fixed joint with
/// no flat position never flips), the tracker provably keeps those orientations everywhere,
/// and each sample whose own such margins clear the toggle margin is simply posed on them — one
/// pose per sample, whatever the order of the samples, and the same bits as the tracker. A
/// sample that does not clear it sends the whole sweep back to the tracker (its rows are
/// rewritten). Poses are computed a block of samples at a time by a vectorised kernel with the
/// same formulas (see `held.rs`).
///
/// # Errors
/// As [`sweep`].
#[inline(always)]
pub fn sweep_planned<T: RealField + Copy, const N: usize>(
    mech: &Mechanism<T, N>,
    theta: &[T],
    omega: Rate<'_, T>,
    alpha: Rate<'_, T>,
    mut out: SweepOutputs<'_, T>,
    go_on: &mut dyn FnMut() -> bool,
    plan: Plan,
) -> Result<Swept, Error> {
    let (n, j) = (theta.len(), mech.len());
    let mut tracker = Tracker::new(mech)?;
    let bodies = Bodies::of(mech);
    let nb = bodies.count();
    out.pairs.check(nb)?;
    let np = out.pairs.count(nb);
    if let Columns::One(t) = out.columns {
        if t >= j {
            return Err(Error::BufferLength {
                what: "joint of the one column (joints of the mechanism)",
                expected: j,
                got: t,
            });
        }
    }
    let rows = n.saturating_mul(out.columns.width(j));
    check_len("joints", rows, out.joints.len())?;
    check_len("valid", n, out.valid.len())?;
    for (what, len, got) in [
        ("margin", n, out.margin.as_ref().map(|v| v.len())),
        ("regular", n, out.regular.as_ref().map(|v| v.len())),
        ("gap", n, out.gap.as_ref().map(|v| v.len())),
        ("velocity", rows, out.velocity.as_ref().map(|v| v.len())),
        (
            "acceleration",
            rows,
            out.acceleration.as_ref().map(|v| v.len()),
        ),
        (
            "centres",
            n.saturating_mul(np),
            out.centres.as_ref().map(|v| v.len()),
        ),
        (
            "centre_directions",
            n.saturating_mul(np),
            out.centre_directions.as_ref().map(|v| v.len()),
        ),
        (
            "curvature_centres",
            rows,
            out.curvature_centres.as_ref().map(|v| v.len()),
        ),
        ("curvature", rows, out.curvature.as_ref().map(|v| v.len())),
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
    let zero = [Vec2::zeros(); N];
    let still = BodyMotion::of(
        &bodies,
        GROUND,
        &zero[..0],
        &zero[..0],
        &zero[..0],
        &zero[..0],
    );
    let mut engine = Engine {
        mech,
        bodies,
        j,
        np,
        columns: out.columns,
        rates: out.velocity.is_some() || out.acceleration.is_some(),
        wants_acc: out.acceleration.is_some(),
        wants_centres: out.centres.is_some() || out.centre_directions.is_some(),
        wants_curvature: out.curvature.is_some() || out.curvature_centres.is_some(),
        pos: zero,
        vel: zero,
        acc: zero,
        uvel: zero,
        uacc: zero,
        motions: Motions {
            ground: still,
            of: [[still; 2]; N],
        },
    };
    let try_held = match plan {
        Plan::Tracked => false,
        Plan::Held => true,
        Plan::Auto => n >= tracker.grid_points_per_turn(),
    };
    let mut scratch = zero;
    let mut watched = [false; N];
    let tm = tracker.toggle_margin();
    if tracker.closed_form() && plan != Plan::Tracked && (plan == Plan::Held || n >= BLOCK) {
        // Orientations in closed form: no check of the turn, and no toggle margin to keep
        // (nothing is watched). The tracker's reference: its start angle, or the first sample
        // (which must assemble, as the tracker's first sample does).
        let reference = mech
            .start_angle()
            .or_else(|| theta.iter().copied().find(|t| t.is_finite()));
        if let Some(r) = reference.filter(|&r| mech.pose(r, &mut scratch[..j]).is_ok()) {
            let rates = (omega, alpha);
            if let Some(done) =
                engine.held(tm, &watched[..j], Some(r), theta, rates, &mut out, go_on)?
            {
                return Ok(done);
            }
        }
    } else if try_held && tracker.holds_everywhere(&mut scratch[..j], &mut watched[..j]) {
        let watched = &watched[..j];
        let rates = (omega, alpha);
        if let Some(done) = engine.held(tm, watched, None, theta, rates, &mut out, go_on)? {
            return Ok(done);
        }
    }
    engine.tracked(&mut tracker, theta, (omega, alpha), &mut out, go_on)
}

/// Sweeps `M` mechanisms of one joint count over the same driver angles, positions only, on
/// `threads` threads (feature `std`): mechanism `i`'s [`sweep`] into `joints[i·n·j ..]` and
/// `valid[i·n ..]` (`n` angles, `j` joints). Each is its own sweep, so the bits do not depend on
/// the number of threads. The batch evaluator of design searches over multi-loop legs.
///
/// ```
/// use linkage_core::{sweep_mechanisms, Assembly, FourBar, Vec2};
/// // Two crank-rockers (ground 20, crank 10; coupler 25 and 28, rocker 25).
/// let leg = |c: f64| FourBar::new(20.0, 10.0, c, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
/// let mechs = [leg(25.0).mechanism(), leg(28.0).mechanism()];
/// let theta = [0.0, 1.0, 2.0];
/// let (mut joints, mut valid) = (vec![Vec2::zeros(); 2 * 3 * 5], vec![false; 6]);
/// sweep_mechanisms(&mechs, &theta, 2, &mut joints, &mut valid).unwrap();
/// assert!(valid.iter().all(|&v| v));
/// // Row (1, 2) is the second leg's pose at θ = 2.
/// let mut one = [Vec2::zeros(); 5];
/// mechs[1].pose(2.0, &mut one).unwrap();
/// assert!((joints[(3 + 2) * 5 + 4] - one[4]).norm() < 1e-12);
/// ```
///
/// # Errors
/// [`Error::BufferLength`] when the mechanisms' joint counts differ or a slice has the wrong
/// length; a mechanism's own [`sweep`] error (no crank), with nothing of the batch kept.
#[cfg(feature = "std")]
pub fn sweep_mechanisms<T: RealField + Copy, const N: usize>(
    mechs: &[Mechanism<T, N>],
    theta: &[T],
    threads: usize,
    joints: &mut [Vec2<T>],
    valid: &mut [bool],
) -> Result<(), Error> {
    let n = theta.len();
    let j = mechs.first().map_or(0, |m| m.len());
    if let Some(m) = mechs.iter().find(|m| m.len() != j) {
        return Err(Error::BufferLength {
            what: "joints of every mechanism of a batch",
            expected: j,
            got: m.len(),
        });
    }
    let rows = n.saturating_mul(j);
    check_len("joints", mechs.len().saturating_mul(rows), joints.len())?;
    check_len("valid", mechs.len().saturating_mul(n), valid.len())?;
    let parts = crate::numeric::parallel::map_parts(mechs.len(), threads, |i| {
        let mut p = alloc::vec![Vec2::zeros(); rows];
        let mut v = alloc::vec![false; n];
        let out = SweepOutputs::positions(&mut p, &mut v);
        sweep(
            &mechs[i],
            theta,
            Rate::Scalar(T::zero()),
            Rate::Scalar(T::zero()),
            out,
            &mut || true,
        )
        .map(|_| (p, v))
    });
    for (i, part) in parts.into_iter().enumerate() {
        let (p, v) = part?;
        joints[i * rows..(i + 1) * rows].copy_from_slice(&p);
        valid[i * n..(i + 1) * n].copy_from_slice(&v);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog;

    /// `Pairs::at` (the lookup past the block kernel's table of 256 pairs) gives the pairs of
    /// `each`, in order, for every pair of Jansen's leg and for chosen pairs given in either
    /// order.
    #[test]
    fn pair_lookup_matches_the_walk() {
        let m = catalog::jansen::<f64>().mechanism;
        let bodies = Bodies::of(&m);
        let nb = bodies.count();
        let chosen = [[3, 0], [1, 2], [nb - 1, 0]];
        for pairs in [Pairs::All, Pairs::Only(&chosen)] {
            let mut seen = 0;
            pairs.each(&bodies, |q, ka, kb| {
                assert_eq!(pairs.at(&bodies, q), Some((ka, kb)), "pair {q}");
                seen += 1;
            });
            assert_eq!(seen, pairs.count(nb), "pairs walked, {pairs:?}");
            assert_eq!(pairs.at(&bodies, seen), None, "past the end");
        }
    }
}
