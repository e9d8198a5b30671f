//! Batches of four-bars swept over shared crank angles: the evaluator of dimensional synthesis
//! and design search.
//!
//! # The rule
//! Every linkage of a batch follows what a [`Tracker`] sweep of its [`FourBar::mechanism`]
//! gives at the same angles in the same order: the same branch, the same valid/invalid decision
//! (NaN and `valid = false` where it cannot assemble), and the same point to rounding (the same
//! bits in the toggle band, where both pose the sample by [`FourBar::pose`]). Most linkages
//! take a branch-free fast path that gives those numbers without tracking, because for them
//! tracking provably never changes the branch:
//!
//! The tracker changes the coupler–rocker dyad's orientation only at a flat position (crank pin
//! on the ground line with coupler and rocker collinear, see
//! [`FourBar::check_fixed_assembly_path`]): for a dyad built on a crank pin and a fixed joint —
//! every four-bar's — it counts flat positions in closed form and never extrapolates. It walks
//! only angles between the smallest and the largest sample, and a path that cannot be walked
//! restarts on the orientation already held. So a linkage with no flat position in
//! `[min θ, max θ]` (every non-change-point linkage, and a change point whose flat positions lie
//! outside the swept angles) is on its declared assembly at every sample: the tracked sample is
//! [`FourBar::pose`] at that angle. Other linkages (a change point with a flat position among the
//! swept angles, or a linkage far from unit size) go through the tracker itself.
//!
//! # The fast kernel
//! With the crank pin `A = O + r(cos θ, sin θ)` and `s = |C − A|²` (the squared base, no root
//! taken), `σ = r₁ + r₂`, `δ = |r₁ − r₂|`, the joint `B` is
//! `A + ((s + r₁² − r₂²)(C − A) ± √((σ² − s)(s − δ²))(C − A)⊥)/2s` (`+` open, `−` crossed):
//! `x = (d² + r₁² − r₂²)/2d` along `A → C` and `h = 2·Area/d` to its left with
//! `16·Area² = (σ² − d²)(d² − δ²)`, each divided by `d` once more for the unit vector. The
//! coupler point is `P = A + along·e + left·e⊥`, `e = (B − A)/r₁`. One square root and one
//! division a sample, evaluated branch-free over blocks of angles whose `sin`/`cos` are computed
//! once for the whole batch, so it vectorises.
//!
//! Next to a toggle the two factors under the root cancel (`σ² − s` against `σ² + s`,
//! `s − δ²` against `s + δ²`), and `h` loses half the digits left; where the base itself is short
//! (a crank pin passing near the rocker pivot), its direction carries a relative error `ε·L/d`.
//! [`FourBar::pose`] forms both without cancellation, and takes that form exactly where the
//! triangle's slack `f₂ = min(σ − d, d − δ)` is below a sixteenth of the longest side
//! (`f₂ < max(d, r₁, r₂)/16`; `f₂` is also at most `d` there, so a short base is one case of
//! it). The kernel marks every such sample, by bounds on `s` squared once per linkage (a slight
//! superset), and solves it again by [`FourBar::pose`]. Elsewhere each factor carries at most
//! `3ε/(1/16)` of relative error, so the kernel's points are within about `24ε` of the size times
//! the coupler point's lever of the exact ones (5.4e-16 of the size at most, measured against
//! mpmath on random linkages), and the valid/invalid decision (a closure miss within `8ε` of the
//! lengths is a toggle, beyond it a failure) is made by the same code as the tracker's wherever
//! it could go either way.

use nalgebra::RealField;

use crate::constructions::dyad::flat_angles;
use crate::error::{check_finite, Error};
use crate::linkages::fourbar::{Assembly, FourBar};
use crate::numeric::scalar::{lit, nan, Vec2};
use crate::sweep::block_poses::{self, BlockPoses};
use crate::sweep::tracker::{Rates, Tracker};

/// Tracked samples between two calls of [`FourBarBatch::sweep_with`]'s `go_on`.
#[doc(hidden)]
pub const GO_ON_EVERY: usize = 256;

/// Crank angles per block of the fast kernel (their `sin`/`cos` live on the stack).
const BLOCK: usize = 512;

/// Sizes (the largest length or coordinate) the fast kernel takes; outside, the tracker (its
/// products of four lengths would overflow or underflow).
const SIZE_LO: f64 = 1.0 / 65_536.0;
const SIZE_HI: f64 = 65_536.0;

/// Relative closure slack below which a sample is solved by [`FourBar::pose`] (see the module):
/// the slack below which the mechanism forms the dyad's base without cancellation.
const NEAR_TOGGLE: f64 = crate::constructions::dyad::EXACT_BASE_SLACK;

/// Angle margin (radians) kept between the swept angles and a flat position for the fast path:
/// far above the rounding of the angles that locate it.
const FLAT_PAD: f64 = 1e-6;

/// `M` four-bars as parallel parameter slices (structure of arrays), one entry per linkage, with
/// the meaning of [`FourBar`]'s fields.
///
/// ```
/// use linkage_core::{Assembly, FourBarBatch, Vec2};
/// // Two Hoecken linkages, the second twice the size, swept over three angles.
/// let o = [Vec2::new(0.0, 0.0); 2];
/// let c = [Vec2::new(20.0, 0.0), Vec2::new(40.0, 0.0)];
/// let batch = FourBarBatch {
///     o: &o,
///     c: &c,
///     crank: &[10.0, 20.0],
///     coupler: &[25.0, 50.0],
///     rocker: &[25.0, 50.0],
///     along: &[50.0, 100.0],
///     left: &[0.0, 0.0],
///     assembly: &[Assembly::Open; 2],
/// };
/// let theta = [0.0, 1.0, 2.0];
/// let mut points = [Vec2::zeros(); 6];
/// let mut valid = [false; 6];
/// let work = batch.sweep(&theta, &mut points, &mut valid).unwrap();
/// assert_eq!(work.tracked, 0); // crank-rockers: the fast path
/// assert!(valid.iter().all(|&v| v));
/// assert!((points[3] - points[0] * 2.0).norm() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FourBarBatch<'a, T> {
    /// Crank pivots.
    pub o: &'a [Vec2<T>],
    /// Rocker pivots.
    pub c: &'a [Vec2<T>],
    /// Crank lengths.
    pub crank: &'a [T],
    /// Coupler lengths.
    pub coupler: &'a [T],
    /// Rocker lengths.
    pub rocker: &'a [T],
    /// Coupler points: distance along `A → B`.
    pub along: &'a [T],
    /// Coupler points: distance to the left of `A → B`.
    pub left: &'a [T],
    /// Assemblies.
    pub assembly: &'a [Assembly],
}

/// How a batch sweep's linkages were solved: a deterministic account of the work.
///
/// ```
/// use linkage_core::{Assembly, FourBarBatch, Vec2};
/// // A crank-rocker, and a parallelogram (a change point, flat at θ = π) swept through π.
/// let (o, c) = ([Vec2::zeros(); 2], [Vec2::new(20.0, 0.0), Vec2::new(3.0, 0.0)]);
/// let batch = FourBarBatch {
///     o: &o,
///     c: &c,
///     crank: &[10.0, 1.0],
///     coupler: &[25.0, 3.0],
///     rocker: &[25.0, 1.0],
///     along: &[50.0, 1.0],
///     left: &[0.0, 0.0],
///     assembly: &[Assembly::Open; 2],
/// };
/// let theta = [3.0, 3.1, 3.2];
/// let (mut points, mut valid) = ([Vec2::zeros(); 6], [false; 6]);
/// let work = batch.sweep(&theta, &mut points, &mut valid).unwrap();
/// assert_eq!((work.fast, work.tracked, work.stopped), (1, 1, false));
/// // `go_on` can stop it: the outputs are then partly written.
/// let stopped = batch.sweep_with(&theta, &mut points, &mut valid, &mut || false).unwrap();
/// assert!(stopped.stopped);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BatchWork {
    /// Linkages on the fast path.
    pub fast: usize,
    /// Linkages swept by the tracker (a flat position among the swept angles, or far from unit
    /// size).
    pub tracked: usize,
    /// Fast-path samples next to a toggle, solved again by [`FourBar::pose`].
    pub exact: usize,
    /// Whether the sweep stopped early because `go_on` said so
    /// ([`FourBarBatch::sweep_with`]); the outputs are then partly written.
    pub stopped: bool,
}

impl<'a, T: RealField + Copy> FourBarBatch<'a, T> {
    /// Number of linkages (the length of `o`).
    pub fn len(&self) -> usize {
        self.o.len()
    }

    /// Whether the batch holds no linkage.
    pub fn is_empty(&self) -> bool {
        self.o.is_empty()
    }

    /// Checks that every slice has one entry per linkage.
    ///
    /// # Errors
    /// [`Error::BufferLength`] naming the first slice whose length differs from `o`'s.
    pub fn check_lengths(&self) -> Result<(), Error> {
        let m = self.len();
        for (what, got) in [
            ("c", self.c.len()),
            ("crank", self.crank.len()),
            ("coupler", self.coupler.len()),
            ("rocker", self.rocker.len()),
            ("along", self.along.len()),
            ("left", self.left.len()),
            ("assembly", self.assembly.len()),
        ] {
            if got != m {
                return Err(Error::BufferLength {
                    what,
                    expected: m,
                    got,
                });
            }
        }
        Ok(())
    }

    /// Linkage `i`, validated as [`FourBar::with_pivots`] does.
    ///
    /// # Errors
    /// As [`FourBar::with_pivots`]; [`Error::BufferLength`] (`"linkage index"`) when `i` is past
    /// the end of a slice.
    pub fn linkage(&self, i: usize) -> Result<FourBar<T>, Error> {
        let past = || Error::BufferLength {
            what: "linkage index",
            expected: i + 1,
            got: self.len(),
        };
        let g = |s: &[T]| s.get(i).copied().ok_or_else(past);
        FourBar::with_pivots(
            *self.o.get(i).ok_or_else(past)?,
            *self.c.get(i).ok_or_else(past)?,
            g(self.crank)?,
            g(self.coupler)?,
            g(self.rocker)?,
            (g(self.along)?, g(self.left)?),
            *self.assembly.get(i).ok_or_else(past)?,
        )
    }

    /// Linkage `i` as given, unchecked (the caller checked the batch and the index).
    #[inline]
    fn get(&self, i: usize) -> FourBar<T> {
        FourBar {
            o: self.o[i],
            c: self.c[i],
            crank: self.crank[i],
            coupler: self.coupler[i],
            rocker: self.rocker[i],
            along: self.along[i],
            left: self.left[i],
            assembly: self.assembly[i],
        }
    }

    /// Whether linkage `i` is swept by the tracker rather than the fast kernel when the angles
    /// span `[lo, hi]` (their least and greatest): it has a flat position there, or is far from
    /// unit size. A caller can weigh the work of a sub-batch by it (a tracked sample costs a
    /// few placements, a huge jump between samples up to a few turns of them). `false` for an
    /// index past the end.
    pub fn is_tracked(&self, i: usize, lo: T, hi: T) -> bool {
        i < self.len() && self.check_lengths().is_ok() && !fast_path(&self.get(i), lo, hi)
    }

    /// The first linkage that is not a valid four-bar, with its index and why.
    pub fn first_invalid(&self) -> Option<(usize, Error)> {
        if self.check_lengths().is_ok() && self.plainly_valid() {
            return None;
        }
        (0..self.len()).find_map(|i| self.linkage(i).err().map(|e| (i, e)))
    }

    /// Whether every linkage passes tests sufficient for [`FourBar::with_pivots`] to accept it
    /// (finite numbers, normal positive lengths, pivots whose squared distance is positive and finite,
    /// so `|c − o|` is too), in one pass without early exit (it vectorises): most batches are
    /// proved valid so, and only the others are searched linkage by linkage.
    fn plainly_valid(&self) -> bool {
        let pos = |v: T| v.is_finite() & (v > T::zero());
        let pivots = self.o.iter().zip(self.c).fold(true, |ok, (o, c)| {
            let (dx, dy) = (c.x - o.x, c.y - o.y);
            let n2 = dx * dx + dy * dy;
            ok & o.x.is_finite() & o.y.is_finite() & c.x.is_finite() & c.y.is_finite() & pos(n2)
        });
        // A length must also be a normal number (`check_length`).
        let normal = crate::numeric::scalar::min_normal::<T>();
        let length = |v: T| v.is_finite() & (v >= normal);
        let lengths = [self.crank, self.coupler, self.rocker]
            .iter()
            .all(|s| s.iter().fold(true, |ok, &v| ok & length(v)));
        let points = [self.along, self.left]
            .iter()
            .all(|s| s.iter().fold(true, |ok, &v| ok & v.is_finite()));
        pivots && lengths && points
    }

    /// Linkages `range` of the batch (every slice cut the same way).
    ///
    /// # Errors
    /// [`Error::BufferLength`] when the slices differ in length or `range` is past their end.
    pub fn slice(&self, range: core::ops::Range<usize>) -> Result<Self, Error> {
        self.check_lengths()?;
        if range.start > range.end || range.end > self.len() {
            return Err(Error::BufferLength {
                what: "linkage range",
                expected: range.end,
                got: self.len(),
            });
        }
        let r = range;
        Ok(FourBarBatch {
            o: &self.o[r.clone()],
            c: &self.c[r.clone()],
            crank: &self.crank[r.clone()],
            coupler: &self.coupler[r.clone()],
            rocker: &self.rocker[r.clone()],
            along: &self.along[r.clone()],
            left: &self.left[r.clone()],
            assembly: &self.assembly[r],
        })
    }

    /// Coupler points of every linkage at every crank angle of `theta` (the same angles, in the
    /// same order, for all linkages; any spacing), written row-major into `points[i·N + k]`
    /// (linkage `i`, angle `k`) with `valid[i·N + k]` whether that sample assembled. Each row is
    /// what a [`Tracker`] sweep of linkage `i` over `theta` gives (see the module's rule); a
    /// sample that cannot assemble is NaN.
    ///
    /// Linkages are independent: sweeping any sub-batch ([`FourBarBatch::slice`]) gives the same
    /// bits for its rows, so callers may split a batch across threads freely. No heap is used.
    ///
    /// # Errors
    /// Nothing is written on an error. [`Error::BufferLength`] when the parameter slices differ
    /// in length or `points`/`valid` are not `M·N` long; [`Error::CountOverflow`] when `M·N`
    /// overflows; [`Error::NotFinite`] (`"theta"`) for a non-finite angle; the error of
    /// [`FourBar::with_pivots`] for the first linkage that is not a valid four-bar
    /// ([`FourBarBatch::first_invalid`] names its index).
    // Always inlined, so a caller compiled for wider vectors gets the kernel compiled for them.
    #[inline(always)]
    pub fn sweep(
        &self,
        theta: &[T],
        points: &mut [Vec2<T>],
        valid: &mut [bool],
    ) -> Result<BatchWork, Error> {
        self.sweep_with(theta, points, valid, &mut || true)
    }

    /// [`FourBarBatch::sweep`], calling `go_on` between linkages and every [`GO_ON_EVERY`]
    /// samples of a tracked linkage; when it returns `false` the sweep stops early with
    /// [`BatchWork::stopped`] set (a caller that must stay responsive, to Ctrl-C say, checks
    /// there). The work between two calls is bounded: one fast linkage over a block of at most
    /// 512 angles, or `GO_ON_EVERY` tracked samples (each at most a few turns of placements,
    /// see [`Tracker`]).
    ///
    /// # Errors
    /// As [`FourBarBatch::sweep`].
    #[inline(always)]
    pub fn sweep_with(
        &self,
        theta: &[T],
        points: &mut [Vec2<T>],
        valid: &mut [bool],
        go_on: &mut dyn FnMut() -> bool,
    ) -> Result<BatchWork, Error> {
        self.check_lengths()?;
        let (m, n) = (self.len(), theta.len());
        let total = m.checked_mul(n).ok_or(Error::CountOverflow {
            what: "linkages × angles",
        })?;
        for (what, got) in [("points", points.len()), ("valid", valid.len())] {
            if got != total {
                return Err(Error::BufferLength {
                    what,
                    expected: total,
                    got,
                });
            }
        }
        for &t in theta {
            check_finite("theta", t)?;
        }
        if let Some((_, e)) = self.first_invalid() {
            return Err(e);
        }
        let mut work = BatchWork::default();
        if total == 0 {
            return Ok(work);
        }
        let (lo, hi) = theta
            .iter()
            .fold((theta[0], theta[0]), |(a, b), &t| (a.min(t), b.max(t)));
        // One block of angles at a time, sin/cos once for all linkages; a tracked linkage is
        // swept whole (every angle) at the first block.
        let mut cos = [T::zero(); BLOCK];
        let mut sin = [T::zero(); BLOCK];
        let mut near = [false; BLOCK];
        let mut start = 0;
        while start < n {
            let stop = (start + BLOCK).min(n);
            let len = stop - start;
            crate::numeric::trig::sin_cos_block(
                &theta[start..stop],
                &mut sin[..len],
                &mut cos[..len],
            );
            for i in 0..m {
                if !go_on() {
                    work.stopped = true;
                    return Ok(work);
                }
                let fb = self.get(i);
                if !fast_path(&fb, lo, hi) {
                    if start == 0 {
                        work.tracked += 1;
                        let row = i * n..(i + 1) * n;
                        let (p, v) = (&mut points[row.clone()], &mut valid[row]);
                        if !tracked_row(&fb, theta, p, v, go_on)? {
                            work.stopped = true;
                            return Ok(work);
                        }
                    }
                    continue;
                }
                if start == 0 {
                    work.fast += 1;
                }
                let row = i * n + start..i * n + stop;
                let out = &mut points[row.clone()];
                let ok = &mut valid[row];
                let any_near = kernel(&fb, (&cos[..len], &sin[..len]), out, ok, &mut near[..len]);
                if any_near {
                    let near = &near[..len];
                    work.exact += exact_near(&fb, &theta[start..stop], near, out, ok);
                }
            }
            start = stop;
        }
        Ok(work)
    }
}

/// Whether linkage `fb` swept over angles in `[lo, hi]` is on its declared assembly at every
/// sample (no flat position there) and of a size the kernel takes.
#[inline]
fn fast_path<T: RealField + Copy>(fb: &FourBar<T>, lo: T, hi: T) -> bool {
    let size = fb
        .crank
        .max(fb.coupler)
        .max(fb.rocker)
        .max(fb.along.abs())
        .max(fb.left.abs())
        .max(fb.o.amax())
        .max(fb.c.amax());
    if size < lit::<T>(SIZE_LO) || size > lit::<T>(SIZE_HI) {
        return false;
    }
    let [at_zero, at_pi] = flat_angles(fb.ground(), fb.crank, fb.coupler, fb.rocker);
    if at_zero.is_none() && at_pi.is_none() {
        return true;
    }
    // A tracked sweep reaches its first sample from the mechanism's start angle (a change
    // point's crank-up position): no flat position may lie between there and the samples.
    let (lo, hi) = match fb.start_angle() {
        Some(a0) => (lo.min(a0), hi.max(a0)),
        None => (lo, hi),
    };
    let pad = lit::<T>(FLAT_PAD);
    fb.check_fixed_assembly_path(lo - pad, hi + pad).is_ok()
}

/// Solves again the samples of `theta` that `near` marks, as [`FourBar::pose`] does (the same
/// bits): up to [`block_poses::BLOCK`] of them at a time by the mechanism's block kernel, whose frame of
/// the crank base is formed once, not per sample; a sample the kernel cannot vouch for by the
/// pose itself. Returns how many were solved. (Inlined, so the binding's AVX builds of the
/// batch vectorise its kernel wider too.)
#[inline(always)]
fn exact_near<T: RealField + Copy>(
    fb: &FourBar<T>,
    theta: &[T],
    near: &[bool],
    out: &mut [Vec2<T>],
    ok: &mut [bool],
) -> usize {
    let mech = fb.mechanism();
    let blocks = BlockPoses::<T, 5>::applies(&mech);
    let mut blk = BlockPoses::<T, 5>::new();
    blk.margins = false;
    blk.prepare(&mech);
    let mut marked = near.iter().enumerate().filter(|&(_, &n)| n).map(|(j, _)| j);
    let (mut joints, mut solved) = ([Vec2::zeros(); 5], 0);
    loop {
        let (mut at, mut angles, mut m) =
            ([0; block_poses::BLOCK], [T::zero(); block_poses::BLOCK], 0);
        for j in marked.by_ref().take(block_poses::BLOCK) {
            (at[m], angles[m], m) = (j, theta[j], m + 1);
        }
        if m == 0 {
            return solved;
        }
        solved += m;
        if blocks {
            blk.pose(&mech, &angles, &[false; 5]);
        }
        for (b, &j) in at[..m].iter().enumerate() {
            let p = Vec2::new(blk.x[FourBar::<T>::P][b], blk.y[FourBar::<T>::P][b]);
            let vouched = blocks && !blk.scalar[b];
            (out[j], ok[j]) = if vouched && blk.failed[b] {
                // A closure miss beyond the pose's own tolerance (the same rule, the same
                // bits): the pose fails there.
                (Vec2::new(nan(), nan()), false)
            } else if vouched && p.x.is_finite() && p.y.is_finite() {
                (p, true)
            } else {
                match mech.pose(angles[b], &mut joints) {
                    Ok(_) => (joints[FourBar::<T>::P], true),
                    Err(_) => (Vec2::new(nan(), nan()), false),
                }
            };
        }
    }
}

/// Linkage `fb` over `theta` by the [`Tracker`], as a sweep of its mechanism does; `false`
/// when `go_on` stopped it.
fn tracked_row<T: RealField + Copy>(
    fb: &FourBar<T>,
    theta: &[T],
    points: &mut [Vec2<T>],
    valid: &mut [bool],
    go_on: &mut dyn FnMut() -> bool,
) -> Result<bool, Error> {
    let mech = fb.mechanism();
    let mut tracker = Tracker::new(&mech)?;
    let mut joints = [Vec2::zeros(); 5];
    for (k, ((&t, p), ok)) in theta
        .iter()
        .zip(points.iter_mut())
        .zip(valid.iter_mut())
        .enumerate()
    {
        if k % GO_ON_EVERY == GO_ON_EVERY - 1 && !go_on() {
            return Ok(false);
        }
        let placed = tracker.step(t, None, &mut joints, Rates::none()).is_ok();
        *ok = placed;
        *p = if placed {
            joints[FourBar::<T>::P]
        } else {
            Vec2::new(nan(), nan())
        };
    }
    Ok(true)
}

/// The closed form over a block of crank directions, branch-free so it vectorises; `near[k]`
/// marks the samples within [`NEAR_TOGGLE`] of a toggle (to be solved again exactly). A sample
/// that cannot close gets a negative product under the square root, whose root is NaN, and
/// `ok` false. Returns whether any sample is marked.
///
/// With `s = |C − A|²` (no square root taken of it), `σ = r1 + r2`, `δ = |r1 − r2|`:
/// `B − A = ((s + r1² − r2²)·(C − A) ± √((σ² − s)(s − δ²))·(C − A)⊥) / (2s)` — one square root
/// and one division a sample, where the triangle's base `d = √s`, its unit vector and
/// Kahan's area took two roots and a division. The two factors under the root lose digits
/// only next to a toggle (`σ² − s` relative to `σ² + s`, `s − δ²` relative to `s + δ²`), and
/// those samples are marked: `near` holds every sample whose triangle slack
/// `min(σ − d, d − δ)` is within `NEAR_TOGGLE` of the longest side (the test the dyad uses for
/// an exact base), tested on `s` against bounds squared once per linkage. Outside it the factors
/// carry at most `3ε/NEAR_TOGGLE` of relative error, the root half of that.
#[inline(always)]
fn kernel<T: RealField + Copy>(
    fb: &FourBar<T>,
    (cos, sin): (&[T], &[T]),
    out: &mut [Vec2<T>],
    ok: &mut [bool],
    near: &mut [bool],
) -> bool {
    let (o, c) = (fb.o, fb.c);
    let (r, r1, r2) = (fb.crank, fb.coupler, fb.rocker);
    let sign = fb.assembly.side().sign::<T>();
    let (along, left) = (fb.along, fb.left);
    let one = T::one();
    let band = lit::<T>(NEAR_TOGGLE);
    let (sigma, delta, rmax) = (r1 + r2, (r1 - r2).abs(), r1.max(r2));
    let (sigma2, delta2) = (sigma * sigma, delta * delta);
    let diff = (r1 - r2) * (r1 + r2);
    // |d − δ| < band·max(d, rmax) and |σ − d| < band·max(d, rmax), as bounds on s = d².
    let sq = |x: T| x * x;
    let in_lo = sq((delta - band * rmax).max(T::zero()));
    let in_hi = sq((delta + band * rmax) / (one - band));
    let out_lo = sq((sigma / (one + band)).min(sigma - band * rmax));
    let out_hi = sq(sigma / (one - band));
    let k = lit::<T>(0.5) / r1;
    let mut any = false;
    let rows = out.iter_mut().zip(ok.iter_mut()).zip(near.iter_mut());
    for (((p, v), nr), (&cs, &sn)) in rows.zip(cos.iter().zip(sin)) {
        let ax = o.x + r * cs;
        let ay = o.y + r * sn;
        let (dx, dy) = (c.x - ax, c.y - ay);
        let s = dx * dx + dy * dy;
        let close = (s > in_lo) & (s < in_hi) | (s > out_lo) & (s < out_hi);
        *nr = close;
        any |= close;
        let root = ((sigma2 - s) * (s - delta2)).sqrt() * sign;
        let w = k / s;
        let t = s + diff;
        // e = (B − A)/r1; P = A + along·e + left·e⊥.
        let ex = (t * dx - root * dy) * w;
        let ey = (t * dy + root * dx) * w;
        let (px, py) = (ax + along * ex - left * ey, ay + along * ey + left * ex);
        // Written here, not by a second pass over the points (which compiled to gathers).
        *v = px.is_finite() & py.is_finite();
        *p = Vec2::new(px, py);
    }
    any
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `first_invalid`'s one-pass proof of validity never accepts a batch that the linkage by
    /// linkage search rejects: every single-value edit of a valid batch to an extreme value
    /// (zero, negative, NaN, ±∞, overflowing and underflowing sizes) gives the search's answer.
    #[test]
    fn the_quick_validity_pass_agrees_with_the_search() {
        let extremes = [
            0.0,
            -0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            f64::MAX,
            -f64::MAX,
            1e-320,
            1e-160,
            1e200,
            3.0,
        ];
        let mut checked = 0;
        for field in 0..9 {
            for &v in &extremes {
                let mut o = [Vec2::new(0.0_f64, 0.0); 3];
                let mut c = [Vec2::new(3.0, 0.0); 3];
                let (mut crank, mut coupler, mut rocker) = ([1.0; 3], [3.0; 3], [2.5; 3]);
                let (mut along, mut left) = ([1.0; 3], [0.5; 3]);
                let k = 1;
                match field {
                    0 => o[k].x = v,
                    1 => o[k].y = v,
                    2 => c[k].x = v,
                    3 => c[k] = Vec2::new(v, v),
                    4 => crank[k] = v,
                    5 => coupler[k] = v,
                    6 => rocker[k] = v,
                    7 => along[k] = v,
                    _ => left[k] = v,
                }
                let assembly = [Assembly::Open; 3];
                let batch = FourBarBatch {
                    o: &o,
                    c: &c,
                    crank: &crank,
                    coupler: &coupler,
                    rocker: &rocker,
                    along: &along,
                    left: &left,
                    assembly: &assembly,
                };
                let search = (0..3).find_map(|i| batch.linkage(i).err().map(|e| (i, e)));
                // Debug text: an error holding a NaN is not equal to itself.
                let (got, want) = (
                    std::format!("{:?}", batch.first_invalid()),
                    std::format!("{search:?}"),
                );
                assert_eq!(got, want, "field {field} = {v}");
                checked += usize::from(search.is_some());
            }
        }
        assert!(checked > 40, "only {checked} edits made an invalid batch");
    }

    #[test]
    fn mismatched_slices_are_refused_and_nothing_is_written() {
        let o = [Vec2::new(0.0_f64, 0.0); 2];
        let c = [Vec2::new(3.0, 0.0); 2];
        let batch = FourBarBatch {
            o: &o,
            c: &c,
            crank: &[1.0, 1.0],
            coupler: &[3.0],
            rocker: &[2.5, 2.5],
            along: &[0.0, 0.0],
            left: &[0.0, 0.0],
            assembly: &[Assembly::Open; 2],
        };
        let mut p = [Vec2::zeros(); 4];
        let mut v = [false; 4];
        assert_eq!(
            batch.sweep(&[0.0, 1.0], &mut p, &mut v),
            Err(Error::BufferLength {
                what: "coupler",
                expected: 2,
                got: 1
            }),
            "a short coupler slice is refused"
        );
        assert!(
            p.iter().all(|q| *q == Vec2::zeros()),
            "nothing written on a refused batch: {p:?}"
        );
    }
}
