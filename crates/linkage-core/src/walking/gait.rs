//! Walking-leg figures from a foot path over one crank turn: stance and swing, stride, lift,
//! duty factor, straightness, stance speed variation and crank torque per unit foot load; and
//! the same for a batch of four-bar legs, with the transmission angle and circuit check.
//!
//! # Frame and definitions
//! The path is in the leg's own frame: `x` along the direction of walking, `y` up, sampled at
//! evenly spaced crank angles over one turn (the last sample followed by the first). With
//! `ground` the lowest foot level (or one given, e.g. a walker's lowest foot of all legs):
//!
//! - **stance**: the samples within `tol` of the ground (`y ≤ ground + tol`, the rule of the
//!   Python walker); **swing**: the others. `stance_runs` counts the stance's cyclic runs (a
//!   leg that touches down twice a turn has two).
//! - **duty factor**: stance samples / samples (at constant crank speed, the share of the turn).
//! - **stride**: the extent of the stance samples along `x` (the body's advance per step).
//! - **lift**: highest foot level above the ground (the obstacle the swing clears).
//! - **straightness**: the largest distance of a stance sample from the stance samples'
//!   total-least-squares line (0 for a straight stance; at most about `tol`).
//! - **speed variation**: `(max − min)/|mean|` of the foot's `x` rate `dx/dθ` over the stance:
//!   the body speed's relative ripple at constant crank speed (0 for a uniform stance).
//! - **peak torque**: by the power method `τ·ω = F·v`, the crank torque per unit foot force is
//!   `F̂·dP/dθ`, at most `|dP/dθ|` (a force along the foot's motion); its largest value over the
//!   stance, in length units (N·mm per N with mm lengths). A horizontal stance carries its
//!   weight at almost no torque; this is the torque of a propulsive (horizontal) load.
//!
//! A four-bar leg ([`FourBarBatch::gaits`]) adds the smallest transmission angle over the turn
//! (the angle between coupler and rocker folded into `[0, π/2]`) and whether the whole turn
//! assembles on one circuit (every sample valid, no flat position of a change point on the
//! path); a leg that does not has NaN figures.

use nalgebra::RealField;

use crate::error::{check_finite, Error};
use crate::linkages::batch::FourBarBatch;
use crate::linkages::fourbar::min_transmission_angle;
use crate::linkages::fourbar::FourBar;
use crate::linkages::uniform_sweep::AngleMode;
use crate::numeric::scalar::{cross, lit, nan, Vec2};

/// Stance and swing figures of one leg's foot path over a crank turn (see the module for the
/// definitions). Figures that need a stance sample are NaN when the path has none.
///
/// ```
/// use linkage_core::{LegGait, Vec2};
/// // A foot going round the unit circle, with the ground given 1 below its lowest point: it never
/// // touches down, so the figures that need a stance are NaN.
/// let n = 16;
/// let path: Vec<Vec2<f64>> = (0..n)
///     .map(|k| {
///         let t = k as f64 * core::f64::consts::TAU / n as f64;
///         Vec2::new(t.cos(), t.sin())
///     })
///     .collect();
/// let rate: Vec<Vec2<f64>> = path.iter().map(|p| Vec2::new(-p.y, p.x)).collect();
/// let mut stance = vec![true; n];
/// let g = LegGait::measure(&path, &rate, 1e-9, Some(-2.0), &mut stance).unwrap();
/// assert_eq!((g.stance_count, g.duty_factor, g.lift), (0, 0.0, 3.0));
/// assert!(g.stride.is_nan() && g.peak_torque.is_nan() && !stance.contains(&true));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegGait<T> {
    /// The ground level (the lowest foot level unless given).
    pub ground: T,
    /// Samples in stance.
    pub stance_count: usize,
    /// Cyclic runs of stance samples (1 for a leg that touches down once a turn).
    pub stance_runs: usize,
    /// First sample of the longest stance run (0 with no stance).
    pub stance_start: usize,
    /// Samples of the longest stance run.
    pub stance_longest: usize,
    /// Stance samples / samples.
    pub duty_factor: T,
    /// Extent of the stance samples along `x`.
    pub stride: T,
    /// Highest foot level above the ground.
    pub lift: T,
    /// Largest distance of a stance sample from the stance's least-squares line.
    pub straightness: T,
    /// `(max − min)/|mean|` of `dx/dθ` over the stance.
    pub speed_variation: T,
    /// Largest `|dP/dθ|` over the stance: crank torque per unit foot force (power method).
    pub peak_torque: T,
}

impl<T: RealField + Copy> LegGait<T> {
    /// The figures of the foot path `path` (one turn at evenly spaced crank angles, not
    /// repeating the first sample) whose rates `dP/dθ` are `rate`, with stance within `tol` of
    /// `ground` (the path's lowest level when `None`). `stance` receives the stance mask.
    ///
    /// ```
    /// use linkage_core::{LegGait, Vec2};
    /// // A foot that slides along y = 0 for half the turn and lifts by 1 for the other half.
    /// let n = 8;
    /// let path: Vec<Vec2<f64>> = (0..n)
    ///     .map(|k| Vec2::new(k as f64, if k < 4 { 0.0 } else { 1.0 }))
    ///     .collect();
    /// let rate = vec![Vec2::new(1.0, 0.0); n];
    /// let mut stance = vec![false; n];
    /// let g = LegGait::measure(&path, &rate, 1e-9, None, &mut stance).unwrap();
    /// assert_eq!((g.stance_count, g.stance_runs), (4, 1));
    /// assert_eq!((g.duty_factor, g.stride, g.lift), (0.5, 3.0, 1.0));
    /// ```
    ///
    /// # Errors
    /// [`Error::BufferLength`] when `rate` or `stance` differ in length from `path`, or the
    /// path is empty; [`Error::NotFinite`] for a non-finite sample, rate, `tol` or `ground`;
    /// [`Error::InvalidLength`] for a negative `tol`.
    pub fn measure(
        path: &[Vec2<T>],
        rate: &[Vec2<T>],
        tol: T,
        ground: Option<T>,
        stance: &mut [bool],
    ) -> Result<Self, Error> {
        let n = path.len();
        if n == 0 {
            return Err(Error::BufferLength {
                what: "path (at least one sample)",
                expected: 1,
                got: 0,
            });
        }
        for (what, got) in [("rate", rate.len()), ("stance", stance.len())] {
            if got != n {
                return Err(Error::BufferLength {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        check_finite("stance tolerance", tol)?;
        if tol < T::zero() {
            return Err(Error::InvalidLength {
                what: "stance tolerance",
                value: crate::numeric::scalar::to_f64(tol),
            });
        }
        for (p, v) in path.iter().zip(rate) {
            // Component by component: a sum of huge finite values could overflow.
            check_finite("foot path", p.x)?;
            check_finite("foot path", p.y)?;
            check_finite("foot rate", v.x)?;
            check_finite("foot rate", v.y)?;
        }
        let ground = match ground {
            Some(g) => {
                check_finite("ground", g)?;
                g
            }
            None => path.iter().fold(path[0].y, |m, p| m.min(p.y)),
        };
        Ok(measure_unchecked(path, rate, tol, ground, stance))
    }
}

/// [`LegGait::measure`] on checked input (finite, equal lengths, at least one sample).
fn measure_unchecked<T: RealField + Copy>(
    path: &[Vec2<T>],
    rate: &[Vec2<T>],
    tol: T,
    ground: T,
    stance: &mut [bool],
) -> LegGait<T> {
    let n = path.len();
    let level = ground + tol;
    let mut count = 0usize;
    let mut top = path[0].y;
    let (mut xlo, mut xhi) = (T::zero(), T::zero());
    // Moments of the stance samples relative to the first stance sample (keeps the digits of
    // paths far from the origin), the rate's extremes and sum, the largest |rate|².
    let mut origin = Vec2::zeros();
    let (mut sx, mut sy) = (T::zero(), T::zero());
    let (mut vlo, mut vhi, mut vsum) = (T::zero(), T::zero(), T::zero());
    let mut peak2 = T::zero();
    for ((p, v), s) in path.iter().zip(rate).zip(stance.iter_mut()) {
        top = top.max(p.y);
        *s = p.y <= level;
        if !*s {
            continue;
        }
        if count == 0 {
            origin = *p;
            (xlo, xhi) = (p.x, p.x);
            (vlo, vhi) = (v.x, v.x);
        }
        count += 1;
        xlo = xlo.min(p.x);
        xhi = xhi.max(p.x);
        sx += p.x - origin.x;
        sy += p.y - origin.y;
        vlo = vlo.min(v.x);
        vhi = vhi.max(v.x);
        vsum += v.x;
        peak2 = peak2.max(v.norm_squared());
    }
    let (runs, start, longest) = runs(stance);
    let lift = top - ground;
    let nf = lit::<T>(n as f64);
    if count == 0 {
        return LegGait {
            ground,
            stance_count: 0,
            stance_runs: 0,
            stance_start: 0,
            stance_longest: 0,
            duty_factor: T::zero(),
            stride: nan(),
            lift,
            straightness: nan(),
            speed_variation: nan(),
            peak_torque: nan(),
        };
    }
    let cf = lit::<T>(count as f64);
    let c = Vec2::new(sx / cf, sy / cf);
    let (mut sxx, mut sxy, mut syy) = (T::zero(), T::zero(), T::zero());
    for (p, _) in path.iter().zip(stance.iter()).filter(|(_, &s)| s) {
        let d = *p - origin - c;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    // Principal axis of the scatter: angle ½·atan2(2 Sxy, Sxx − Syy).
    let phi = (lit::<T>(2.0) * sxy).atan2(sxx - syy) * lit::<T>(0.5);
    let (s, co) = phi.sin_cos();
    let dir = Vec2::new(co, s);
    let mut dev = T::zero();
    for (p, _) in path.iter().zip(stance.iter()).filter(|(_, &s)| s) {
        dev = dev.max(cross(dir, *p - origin - c).abs());
    }
    let mean = vsum / cf;
    LegGait {
        ground,
        stance_count: count,
        stance_runs: runs,
        stance_start: start,
        stance_longest: longest,
        duty_factor: cf / nf,
        stride: xhi - xlo,
        lift,
        straightness: dev,
        // A stance that does not move along x has no speed to vary: NaN, not a huge number.
        speed_variation: if mean == T::zero() {
            nan()
        } else {
            (vhi - vlo) / mean.abs()
        },
        peak_torque: peak2.sqrt(),
    }
}

/// Cyclic runs of `true` in `mask`: their number, the start and length of the longest (the
/// first of equal ones, counting from index 0).
fn runs(mask: &[bool]) -> (usize, usize, usize) {
    let n = mask.len();
    let count = mask.iter().filter(|&&s| s).count();
    if count == n {
        return (1, 0, n);
    }
    // Start scanning just after a swing sample so that no run is split by the wrap.
    let Some(gap) = mask.iter().position(|&s| !s) else {
        return (0, 0, 0);
    };
    let (mut number, mut best_start, mut best_len) = (0, 0, 0);
    let mut k = 0;
    while k < n {
        let i = (gap + 1 + k) % n;
        if mask[i] {
            let mut len = 0;
            while k < n && mask[(gap + 1 + k) % n] {
                len += 1;
                k += 1;
            }
            number += 1;
            if len > best_len || (len == best_len && i < best_start) {
                (best_start, best_len) = (i, len);
            }
        } else {
            k += 1;
        }
    }
    (number, best_start, best_len)
}

/// The figures of one four-bar leg over a crank turn: its [`LegGait`], the smallest
/// transmission angle and whether the turn assembles on one circuit.
///
/// ```
/// use linkage_core::{catalog, FourBarGait, GaitScratch, Vec2};
/// let n = 64;
/// let (mut points, mut stance) = (vec![Vec2::zeros(); 4 * n], vec![false; n]);
/// let mut scratch = GaitScratch { points: &mut points, stance: &mut stance };
/// let g: FourBarGait<f64> = catalog::hoecken::<f64>().gait(n, 0.01, &mut scratch).unwrap();
/// assert!(g.full_turn && g.gait.stance_count > 0);
/// assert!(g.min_transmission > 0.0 && g.min_transmission <= core::f64::consts::FRAC_PI_2);
/// // Evans C's crank does not turn fully: no leg, NaN figures.
/// let g = catalog::evans_c::<f64>().gait(n, 0.01, &mut scratch).unwrap();
/// assert!(!g.full_turn && g.min_transmission.is_nan() && g.gait.stride.is_nan());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarGait<T> {
    /// Stance and swing figures (NaN and zero counts when the turn does not assemble).
    pub gait: LegGait<T>,
    /// Smallest transmission angle over the turn (radians, in `[0, π/2]`; NaN when the turn
    /// does not assemble).
    pub min_transmission: T,
    /// Whether every sample of the turn assembles on the declared circuit.
    pub full_turn: bool,
}

impl<T: RealField + Copy> FourBarGait<T> {
    /// The figures of a leg that does not turn fully.
    fn failed() -> Self {
        FourBarGait {
            gait: LegGait {
                ground: nan(),
                stance_count: 0,
                stance_runs: 0,
                stance_start: 0,
                stance_longest: 0,
                duty_factor: nan(),
                stride: nan(),
                lift: nan(),
                straightness: nan(),
                speed_variation: nan(),
                peak_torque: nan(),
            },
            min_transmission: nan(),
            full_turn: false,
        }
    }
}

/// Scratch slices of one leg's turn for [`FourBarBatch::gaits`]: `4·samples` points and
/// `samples` flags, reused from leg to leg (no heap in the core).
///
/// ```
/// use linkage_core::{catalog, Error, GaitScratch, Vec2};
/// let (mut points, mut stance) = ([Vec2::zeros(); 4 * 8], [false; 8]);
/// let mut scratch = GaitScratch { points: &mut points, stance: &mut stance };
/// // Scratch for 8 samples: a gait of 8 samples works, one of 16 does not fit.
/// let fb = catalog::hoecken::<f64>();
/// assert!(fb.gait(8, 0.05, &mut scratch).is_ok());
/// assert_eq!(
///     fb.gait(16, 0.05, &mut scratch).err(),
///     Some(Error::BufferLength { what: "scratch points", expected: 64, got: 32 })
/// );
/// ```
pub struct GaitScratch<'a, T> {
    /// Foot points, `B` joints, foot rates and the crank directions: `4·samples` long.
    pub points: &'a mut [Vec2<T>],
    /// Stance mask: `samples` long.
    pub stance: &'a mut [bool],
}

impl<T: RealField + Copy> FourBar<T> {
    /// The leg figures of this four-bar, its coupler point the foot, over `samples` crank
    /// angles `θ_k = 2πk/samples` with the stance within `rel_tol` times the path's extent
    /// (`max(Δx, Δy)`) of its lowest level. The joint `B` comes from
    /// [`FourBar::uniform_sweep`] (`AngleMode::Recurrence` re-anchored every 64 samples: within a
    /// few ulps of the tracker's points, one `sin_cos` per 64 samples) and the foot from it as
    /// the kernel places it, `P = A + along·e + left·e⊥` with `e = (B − A)/r₁`; the foot rate
    /// `dP/dθ` in closed form from the joints: with `u = B − A`, `w = B − C` and
    /// `A' = r(−sin θ, cos θ)`, the rocker turns at `ω₄ = (u·A')/(w × u)`, the coupler at
    /// `ω₃ = u × (B' − A')/|u|²`, and `P' = A' + ω₃ (P − A)⊥`. The transmission angle is
    /// `asin(|u × w|/(r₁ r₂))`.
    ///
    /// # Errors
    /// [`Error::BufferLength`] for scratch slices of the wrong length or zero samples;
    /// [`Error::NotFinite`]/[`Error::InvalidLength`] for a non-finite or negative `rel_tol`.
    pub fn gait(
        &self,
        samples: usize,
        rel_tol: T,
        scratch: &mut GaitScratch<'_, T>,
    ) -> Result<FourBarGait<T>, Error> {
        check_scratch(samples, scratch)?;
        check_finite("stance tolerance", rel_tol)?;
        if rel_tol < T::zero() {
            return Err(Error::InvalidLength {
                what: "stance tolerance",
                value: crate::numeric::scalar::to_f64(rel_tol),
            });
        }
        fill_directions(samples, scratch);
        Ok(self.gait_unchecked(samples, rel_tol, scratch))
    }

    /// [`FourBar::gait`] with the crank directions already in the scratch's last quarter.
    fn gait_unchecked(
        &self,
        n: usize,
        rel_tol: T,
        scratch: &mut GaitScratch<'_, T>,
    ) -> FourBarGait<T> {
        let (foot, rest) = scratch.points.split_at_mut(n);
        let (joint_b, rest) = rest.split_at_mut(n);
        let (rate, dirs) = rest.split_at_mut(n);
        let dtheta = T::two_pi() / lit::<T>(n as f64);
        let mode = AngleMode::Recurrence { block: 64 };
        // B is the coupler point at `along = coupler`, `left = 0`: the same kernel, same branch.
        let to_b = FourBar {
            along: self.coupler,
            left: T::zero(),
            ..*self
        };
        if to_b
            .uniform_sweep(T::zero(), dtheta, 0, mode, joint_b)
            .is_err()
        {
            return FourBarGait::failed();
        }
        let (r, r1, r2) = (self.crank, self.coupler, self.rocker);
        let inv_r1 = T::one() / r1;
        let inv_r1_sq = inv_r1 * inv_r1;
        let (along, left) = (self.along * inv_r1, self.left * inv_r1);
        let mut min_sin = T::one();
        let mut ok = true;
        for (((p, b), v), e) in foot
            .iter_mut()
            .zip(joint_b.iter())
            .zip(rate.iter_mut())
            .zip(dirs.iter())
        {
            let (cs, sn) = (e.x, e.y);
            let a = self.o + *e * r;
            let da = Vec2::new(-sn, cs) * r;
            let u = *b - a;
            // The foot on the coupler as the kernel places it: P = A + along·e + left·e⊥.
            *p = a + u * along + Vec2::new(-u.y, u.x) * left;
            let w = *b - self.c;
            let uw = cross(w, u);
            let w4 = u.dot(&da) / uw;
            let db = Vec2::new(-w.y, w.x) * w4;
            let w3 = cross(u, db - da) * inv_r1_sq;
            let pa = *p - a;
            *v = da + Vec2::new(-pa.y, pa.x) * w3;
            min_sin = min_sin.min(uw.abs() / (r1 * r2));
            // NaN (no assembly) or an infinite rate (a toggle of the rocker) fails the turn.
            ok &= p.x.is_finite() & p.y.is_finite() & v.x.is_finite() & v.y.is_finite();
        }
        if !ok {
            return FourBarGait::failed();
        }
        let (mut lo, mut hi) = (foot[0], foot[0]);
        for p in foot.iter() {
            lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        let extent = (hi.x - lo.x).max(hi.y - lo.y);
        let gait = measure_unchecked(foot, rate, rel_tol * extent, lo.y, scratch.stance);
        FourBarGait {
            gait,
            min_transmission: min_transmission_angle(min_sin),
            full_turn: true,
        }
    }
}

/// The crank directions `(cos θ_k, sin θ_k)`, `θ_k = 2πk/n`, into the scratch's last quarter.
fn fill_directions<T: RealField + Copy>(n: usize, scratch: &mut GaitScratch<'_, T>) {
    let dtheta = T::two_pi() / lit::<T>(n as f64);
    for (k, e) in scratch.points[3 * n..].iter_mut().enumerate() {
        let (s, c) = (dtheta * lit::<T>(k as f64)).sin_cos();
        *e = Vec2::new(c, s);
    }
}

fn check_scratch<T>(samples: usize, scratch: &GaitScratch<'_, T>) -> Result<(), Error> {
    if samples == 0 {
        return Err(Error::BufferLength {
            what: "samples (at least one)",
            expected: 1,
            got: 0,
        });
    }
    let need = samples.checked_mul(4).ok_or(Error::CountOverflow {
        what: "4 × samples",
    })?;
    if scratch.points.len() != need {
        return Err(Error::BufferLength {
            what: "scratch points",
            expected: need,
            got: scratch.points.len(),
        });
    }
    if scratch.stance.len() != samples {
        return Err(Error::BufferLength {
            what: "scratch stance",
            expected: samples,
            got: scratch.stance.len(),
        });
    }
    Ok(())
}

impl<T: RealField + Copy> FourBarBatch<'_, T> {
    /// [`FourBar::gait`] of every linkage of the batch into `out` (one per linkage). Linkages
    /// are independent, so any split of the batch ([`FourBarBatch::slice`]) across threads
    /// gives the same bits.
    ///
    /// # Errors
    /// Nothing is written on an error. [`Error::BufferLength`] when the parameter slices or
    /// `out` differ in length or the scratch slices are wrong; the error of
    /// [`FourBar::with_pivots`] for the first linkage that is not a valid four-bar;
    /// the tolerance errors of [`FourBar::gait`].
    pub fn gaits(
        &self,
        samples: usize,
        rel_tol: T,
        scratch: &mut GaitScratch<'_, T>,
        out: &mut [FourBarGait<T>],
    ) -> Result<(), Error> {
        self.check_lengths()?;
        if out.len() != self.len() {
            return Err(Error::BufferLength {
                what: "out",
                expected: self.len(),
                got: out.len(),
            });
        }
        check_scratch(samples, scratch)?;
        check_finite("stance tolerance", rel_tol)?;
        if rel_tol < T::zero() {
            return Err(Error::InvalidLength {
                what: "stance tolerance",
                value: crate::numeric::scalar::to_f64(rel_tol),
            });
        }
        if let Some((_, e)) = self.first_invalid() {
            return Err(e);
        }
        fill_directions(samples, scratch);
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.linkage(i)?.gait_unchecked(samples, rel_tol, scratch);
        }
        Ok(())
    }
}
