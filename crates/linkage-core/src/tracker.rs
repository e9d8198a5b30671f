//! Sweeping a mechanism over driver angles on a continuously tracked assembly branch.

use nalgebra::RealField;

use crate::error::{check_finite, Error};
use crate::mechanism::{Candidates, Mechanism, Motion};
use crate::scalar::{lit, Vec2};

/// Assembly margin (`sin γ`, see [`crate::DyadPose::margin`]) below which a dyad is "near a
/// toggle" and its branch is chosen by continuation rather than kept.
pub const DEFAULT_TOGGLE_MARGIN: f64 = 0.2;

/// Largest driver step (radians) taken while a dyad is near a toggle; longer steps are subdivided
/// there so that continuation sees the motion, whatever the caller's sampling.
const DEFAULT_MAX_STEP: f64 = 1.0 / 128.0;

/// Longest driver step (radians) taken at all: longer requested steps are cut, so that a toggle
/// between two far-apart samples (a change-point linkage's flat position) is seen.
const COARSE_STEP: f64 = 0.25;

/// Cap on the substeps of one refined step, so a pathological request stays bounded in time.
const MAX_SUBSTEPS: u32 = 1 << 16;

/// Where a sweep sample writes the rates it is asked for; absent buffers are not computed.
/// Higher rates need the lower ones (a jerk needs an acceleration and a velocity buffer).
#[derive(Debug, Default)]
pub struct Rates<'a, T> {
    /// Joint velocities.
    pub velocity: Option<&'a mut [Vec2<T>]>,
    /// Joint accelerations.
    pub acceleration: Option<&'a mut [Vec2<T>]>,
    /// Joint jerks.
    pub jerk: Option<&'a mut [Vec2<T>]>,
}

impl<'a, T> Rates<'a, T> {
    /// Positions only.
    pub fn none() -> Self {
        Rates {
            velocity: None,
            acceleration: None,
            jerk: None,
        }
    }

    /// Velocities only.
    pub fn velocity(v: &'a mut [Vec2<T>]) -> Self {
        Rates {
            velocity: Some(v),
            acceleration: None,
            jerk: None,
        }
    }

    /// Velocities and accelerations.
    pub fn acceleration(v: &'a mut [Vec2<T>], a: &'a mut [Vec2<T>]) -> Self {
        Rates {
            velocity: Some(v),
            acceleration: Some(a),
            jerk: None,
        }
    }
}

/// Result of one sweep sample that assembled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<T> {
    /// Smallest assembly margin of the mechanism's dyads at this sample (1 when it has none).
    pub margin: T,
    /// False when some joint is at an exact toggle, so its rates are NaN.
    pub regular: bool,
}

/// Sweeps a [`Mechanism`] over driver angles, keeping each dyad on its assembly branch.
///
/// # Branch tracking
/// A dyad's branch is its orientation (the side of its base line its joint is on). The tracker
/// keeps each dyad's orientation from sample to sample, except near a toggle: when the dyad's
/// margin is below `toggle_margin` at this or the previous sample, the orientation may
/// legitimately change (a change-point linkage passing its flat position, a chain whose dyad
/// straightens), so the tracker chooses the candidate nearest the position extrapolated from the
/// two previous samples: the branch consistent with the motion so far.
///
/// The caller's sampling does not decide the branch: a requested step longer than 0.25 rad is
/// walked in equal hops of at most that, and a hop near a toggle is walked in steps of at most
/// `max_step` (default 1/128 rad), so the extrapolation is always local. Far from toggles this
/// costs nothing (a Grashof crank-rocker sampled every 100° keeps its orientation in 7 hops per
/// step); near them it is what makes a coarse sweep of a parallelogram stay a parallelogram.
///
/// A sample that cannot assemble writes NaN joints and returns its error; the history is kept,
/// and the next sample that assembles resumes from the orientation held before the gap.
///
/// ```
/// use linkage_core::{Assembly, FourBar, Rates, Tracker, Vec2};
/// let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let mut t = Tracker::new(&m).unwrap();
/// let mut joints = [Vec2::zeros(); 5];
/// for k in 0..4 {
///     // 100° steps: far from any toggle, the orientation is simply kept.
///     let s = t.step(1.745 * k as f64, None, &mut joints, Rates::none()).unwrap();
///     assert!(s.margin > 0.1);
/// }
/// ```
#[derive(Clone, Debug)]
pub struct Tracker<'m, T: RealField + Copy, const N: usize> {
    mech: &'m Mechanism<T, N>,
    /// Orientation of each branch joint, `+1` or `-1` (compact, as it is saved per step).
    sign: [i8; N],
    /// `hist[newest]`: last assembled sample, `hist[1 - newest]`: the one before (a two-slot
    /// ring, so committing a sample copies only the mechanism's joints).
    hist: [[Vec2<T>; N]; 2],
    newest: usize,
    hist_theta: [T; 2],
    hist_margin: [T; N],
    /// Margins of the joints as last placed (committed into `hist_margin` with the sample).
    placed_margin: [T; N],
    nhist: u8,
    toggle_margin: T,
    max_step: T,
}

impl<'m, T: RealField + Copy, const N: usize> Tracker<'m, T, N> {
    /// A tracker starting on the branches the constructions declare.
    ///
    /// # Errors
    /// [`Error::NoDriver`] if the mechanism has no crank.
    pub fn new(mech: &'m Mechanism<T, N>) -> Result<Self, Error> {
        Self::with_settings(mech, lit(DEFAULT_TOGGLE_MARGIN), lit(DEFAULT_MAX_STEP))
    }

    /// A tracker with explicit continuation settings: `toggle_margin` in `[0, 1)`, `max_step`
    /// (radians, > 0) the longest driver step taken near a toggle.
    ///
    /// # Errors
    /// [`Error::NoDriver`]; [`Error::NotFinite`] / [`Error::InvalidLength`] for bad settings.
    pub fn with_settings(
        mech: &'m Mechanism<T, N>,
        toggle_margin: T,
        max_step: T,
    ) -> Result<Self, Error> {
        if mech.driver().is_none() {
            return Err(Error::NoDriver);
        }
        check_finite("toggle_margin", toggle_margin)?;
        crate::error::check_length("max_step", max_step)?;
        let mut sign = [1i8; N];
        for (s, c) in sign.iter_mut().zip(mech.constructions()) {
            *s = if c.initial_sign() < T::zero() { -1 } else { 1 };
        }
        Ok(Tracker {
            mech,
            sign,
            hist: [[Vec2::zeros(); N]; 2],
            newest: 0,
            hist_theta: [T::zero(); 2],
            hist_margin: [T::one(); N],
            placed_margin: [T::one(); N],
            nhist: 0,
            toggle_margin,
            max_step,
        })
    }

    /// Current orientation of joint `i`: `+1` for [`crate::Side::Left`] / [`crate::Reach::Ahead`],
    /// `-1` for the other, `+1` for joints without a branch (and for an index beyond `N`).
    pub fn branch(&self, i: usize) -> T {
        if self.sign.get(i).is_some_and(|&s| s < 0) {
            -T::one()
        } else {
            T::one()
        }
    }

    /// Forces the orientation of joint `i` (`+1` / `-1`) and forgets the motion history, so the
    /// next sample starts afresh there. Used to pass to the other branch at a toggle, as a
    /// circuit sweep does.
    /// An index beyond `N` changes nothing.
    pub fn set_branch(&mut self, i: usize, sign: T) {
        if let Some(s) = self.sign.get_mut(i) {
            *s = if sign < T::zero() { -1 } else { 1 };
            self.nhist = 0;
        }
    }

    /// Solves every joint at `theta` into `joints`, choosing branches by continuity.
    /// Returns the smallest margin and whether any dyad was near a toggle.
    fn place(&mut self, theta: T, joints: &mut [Vec2<T>]) -> Result<(T, bool), Error> {
        let mech = self.mech;
        let mut margin = T::one();
        let mut near_any = false;
        // Extrapolation ratio for continuation near a toggle (computed only when needed).
        let ratio = || {
            if self.hist_theta[0] != self.hist_theta[1] {
                (theta - self.hist_theta[0]) / (self.hist_theta[0] - self.hist_theta[1])
            } else {
                T::zero()
            }
        };
        for i in 0..mech.len() {
            joints[i] = match mech.candidates(i, theta, joints, T::zero())? {
                Candidates::One(p) => p,
                Candidates::Two {
                    foot,
                    offset,
                    margin: m,
                } => {
                    margin = margin.min(m);
                    self.placed_margin[i] = m;
                    let near = self.nhist > 0
                        && (m < self.toggle_margin || self.hist_margin[i] < self.toggle_margin);
                    near_any |= near;
                    let mut s = if self.sign[i] < 0 {
                        -T::one()
                    } else {
                        T::one()
                    };
                    if near && self.nhist >= 2 {
                        let prev = self.hist[self.newest][i];
                        let predicted = prev + (prev - self.hist[1 - self.newest][i]) * ratio();
                        let kept = foot + offset * s;
                        let flipped = foot - offset * s;
                        if (flipped - predicted).norm_squared() < (kept - predicted).norm_squared()
                        {
                            s = -s;
                            self.sign[i] = -self.sign[i];
                        }
                    }
                    foot + offset * s
                }
            };
        }
        Ok((margin, near_any))
    }

    /// Records an assembled sample as the newest history entry.
    fn commit(&mut self, theta: T, joints: &[Vec2<T>]) {
        let n = self.mech.len();
        self.newest = 1 - self.newest;
        self.hist[self.newest][..n].copy_from_slice(joints);
        self.hist_theta = [theta, self.hist_theta[0]];
        self.nhist = (self.nhist + 1).min(2);
        self.hist_margin[..n].copy_from_slice(&self.placed_margin[..n]);
    }

    /// Solves the sample at driver angle `theta`, writing joint positions into `joints` and,
    /// for each buffer `rates` holds, velocities, accelerations and jerks for the driver
    /// `motion` (each slice [`Mechanism::len`] long). Rates not asked for are not computed.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] / [`Error::Coincident`] when the sample cannot be assembled
    /// (the slices are filled with NaN); [`Error::NotFinite`] for a non-finite angle or motion;
    /// [`Error::BufferLength`] for wrong slices, or rates requested without a motion.
    pub fn step(
        &mut self,
        theta: T,
        motion: Option<Motion<T>>,
        joints: &mut [Vec2<T>],
        rates: Rates<'_, T>,
    ) -> Result<Sample<T>, Error> {
        let n = self.mech.len();
        if joints.len() != n {
            return Err(Error::BufferLength {
                what: "joints",
                expected: n,
                got: joints.len(),
            });
        }
        let nan = Vec2::new(crate::scalar::nan::<T>(), crate::scalar::nan::<T>());
        let Rates {
            velocity,
            acceleration,
            jerk,
        } = rates;
        let result = check_finite("crank angle", theta).and_then(|_| self.advance(theta, joints));
        let margin = match result {
            Ok(m) => m,
            Err(e) => {
                // Forget the motion: after a gap, continuation restarts from the orientation held.
                self.nhist = 0;
                joints.fill(nan);
                for buf in [velocity, acceleration, jerk].into_iter().flatten() {
                    buf.fill(nan);
                }
                return Err(e);
            }
        };
        let mut regular = true;
        if let Some(vel) = velocity {
            let drive = motion.ok_or(Error::BufferLength {
                what: "motion (omega, alpha)",
                expected: 1,
                got: 0,
            })?;
            check_finite("omega", drive.omega)?;
            check_finite("alpha", drive.alpha)?;
            check_finite("jerk", drive.jerk)?;
            regular = self.mech.motion(joints, drive, vel, acceleration, jerk)?;
        } else if acceleration.is_some() || jerk.is_some() {
            return Err(Error::BufferLength {
                what: "velocities (needed for higher rates)",
                expected: n,
                got: 0,
            });
        }
        Ok(Sample { margin, regular })
    }

    /// Moves the tracked state to `theta`: steps longer than `coarse_step` are cut into equal
    /// hops, and each hop is refined to `max_step` where a dyad is near a toggle.
    fn advance(&mut self, theta: T, joints: &mut [Vec2<T>]) -> Result<T, Error> {
        if self.nhist == 0 {
            let (margin, _) = self.place(theta, joints)?;
            self.commit(theta, joints);
            return Ok(margin);
        }
        let saved_sign = self.sign;
        let start = self.hist_theta[0];
        // The common case is a single hop.
        let hops = if (theta - start).abs() <= lit(COARSE_STEP) {
            1
        } else {
            Self::count(theta - start, lit(COARSE_STEP))
        };
        let mut result = Ok(T::one());
        for k in 1..=hops {
            let t = Self::between(start, theta, k, hops);
            result = self.hop(t, joints);
            if result.is_err() {
                break;
            }
        }
        match result {
            Ok(m) => Ok(m),
            Err(_) => {
                // The motion cannot pass continuously from the last sample to `theta` (a locked
                // zone lies between): restart at `theta` on the orientation held before.
                self.sign = saved_sign;
                self.nhist = 0;
                let (margin, _) = self.place(theta, joints)?;
                self.commit(theta, joints);
                Ok(margin)
            }
        }
    }

    /// One hop from the last committed sample to `t`, subdivided to `max_step` near toggles.
    fn hop(&mut self, t: T, joints: &mut [Vec2<T>]) -> Result<T, Error> {
        let saved_sign = self.sign;
        let (margin, near) = self.place(t, joints)?;
        let start = self.hist_theta[0];
        if !near || (t - start).abs() <= self.max_step {
            self.commit(t, joints);
            return Ok(margin);
        }
        self.sign = saved_sign;
        let steps = Self::count(t - start, self.max_step);
        let mut last = margin;
        for k in 1..=steps {
            let tk = Self::between(start, t, k, steps);
            last = self.place(tk, joints)?.0;
            self.commit(tk, joints);
        }
        Ok(last)
    }

    /// Number of equal steps of at most `step` covering `gap` (at least 1, capped).
    fn count(gap: T, step: T) -> u32 {
        let n = (gap.abs() / step).ceil().to_subset().unwrap_or(1.0);
        n.clamp(1.0, MAX_SUBSTEPS as f64) as u32
    }

    /// The `k`-th of `n` equal steps from `a` to `b`, landing exactly on `b`.
    fn between(a: T, b: T, k: u32, n: u32) -> T {
        if k == n {
            b
        } else {
            a + (b - a) * lit::<T>(k as f64) / lit::<T>(n as f64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dyad::Side;

    /// Parallelogram O(0,0), C(g,0), crank r, coupler g, rocker r.
    fn parallelogram() -> Mechanism<f64, 4> {
        let mut m = Mechanism::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let c = m.fixed(Vec2::new(3.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        // At θ = 90° the parallelogram's B = A + (3, 0) is left of A → C.
        m.dyad(a, c, 3.0, 1.0, Side::Left).unwrap();
        m
    }

    fn sweep_parallelogram(steps: usize) -> f64 {
        let m = parallelogram();
        let mut t = Tracker::new(&m).unwrap();
        let mut j = [Vec2::zeros(); 4];
        let mut worst: f64 = 0.0;
        for k in 0..=steps {
            // Start at 90°, go one full turn and a bit: passes both flat positions.
            let th = core::f64::consts::FRAC_PI_2 + 7.0 * k as f64 / steps as f64;
            t.step(th, None, &mut j, Rates::none()).unwrap();
            let expected = j[2] + Vec2::new(3.0, 0.0);
            worst = worst.max((j[3] - expected).norm());
        }
        worst
    }

    #[test]
    fn parallelogram_stays_parallelogram_through_flat_positions() {
        // Fine sampling, and sampling far too coarse to see the flat positions.
        assert!(sweep_parallelogram(3600) < 1e-12);
        assert!(sweep_parallelogram(5) < 1e-12);
    }

    #[test]
    fn unassemblable_sample_is_nan_and_error() {
        let mut m = Mechanism::<f64, 4>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let c = m.fixed(Vec2::new(10.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        m.dyad(a, c, 4.0, 4.0, Side::Left).unwrap();
        let mut t = Tracker::new(&m).unwrap();
        let mut j = [Vec2::zeros(); 4];
        let e = t.step(0.0, None, &mut j, Rates::none()).unwrap_err();
        match e {
            Error::CannotAssemble { joint: 3, gap } => assert!((gap - 1.0).abs() < 1e-12),
            other => panic!("unexpected {other:?}"),
        }
        assert!(j.iter().all(|p| p.x.is_nan() && p.y.is_nan()));
    }
}
