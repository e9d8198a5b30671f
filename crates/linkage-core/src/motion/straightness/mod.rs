//! Straight-line quality of a sampled path: the longest run of samples within a tolerance of
//! its best-fit line.

use nalgebra::RealField;

use crate::numeric::scalar::{cross, lit, Vec2};

/// A near-straight run of a sampled path.
///
/// ```
/// use linkage_core::{straight_part, Vec2};
/// // Five samples along y = 0, then a corner.
/// let path = [(0.0_f64, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0), (4.0, 0.0), (4.0, 3.0)]
///     .map(|(x, y)| Vec2::new(x, y));
/// let part = straight_part(&path, 1e-9, false).unwrap();
/// assert_eq!((part.start, part.count, part.max_deviation), (0, 5, 0.0));
/// assert!((part.length - 4.0).abs() < 1e-12);
/// assert!((part.direction - Vec2::new(1.0, 0.0)).norm() < 1e-15);
/// // Fewer than three samples have no straight part.
/// assert!(straight_part(&path[..2], 1e-9, false).is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StraightPart<T> {
    /// Index of the run's first sample.
    pub start: usize,
    /// Number of samples in the run (on a closed path it may wrap past the last sample).
    pub count: usize,
    /// A point of the best-fit line: the run's centroid.
    pub point: Vec2<T>,
    /// Unit direction of the best-fit line, pointing from the run's first sample to its last.
    pub direction: Vec2<T>,
    /// Largest distance of a run sample from the line.
    pub max_deviation: T,
    /// Extent of the run along the line.
    pub length: T,
}

impl<T: RealField + Copy> StraightPart<T> {
    /// The run's sample indices into a path of `n` samples (wrapping past its end).
    pub fn indices(&self, n: usize) -> impl Iterator<Item = usize> {
        let start = self.start;
        (0..self.count).map(move |k| (start + k) % n.max(1))
    }

    /// The speed along the run from the path's velocities `velocity` (one a sample of the
    /// path the run was found on): `(mean, (max − min)/mean)`, both formed relative to the
    /// largest speed so that huge speeds do not overflow the sum. `(∞, ∞)` when a speed on the
    /// run is not finite (the run reaches a toggle, where the speed at constant crank speed is
    /// unbounded); `(0, NaN)` for a run at rest; `None` when `velocity` is too short.
    ///
    /// ```
    /// use linkage_core::{straight_part, Vec2};
    /// // Along y = 0 at speeds 1, 2, 3, 2: mean 2, variation (3 − 1)/2 = 1.
    /// let path = [0.0, 1.0, 3.0, 6.0].map(|x| Vec2::new(x, 0.0_f64));
    /// let velocity = [1.0, 2.0, 3.0, 2.0].map(|v| Vec2::new(v, 0.0));
    /// let part = straight_part(&path, 1e-9, false).unwrap();
    /// let (mean, variation) = part.speed(&velocity).unwrap();
    /// assert!((mean - 2.0).abs() < 1e-15 && (variation - 1.0).abs() < 1e-15);
    /// ```
    pub fn speed(&self, velocity: &[Vec2<T>]) -> Option<(T, T)> {
        let n = velocity.len();
        if self.start >= n || self.count > n || self.count == 0 {
            return None;
        }
        let speed = |k: usize| crate::numeric::scalar::length(velocity[k]);
        let mut top = T::zero();
        for k in self.indices(n) {
            let v = speed(k);
            if !v.is_finite() {
                let inf = T::max_value().map_or(T::one() / T::zero(), |m| m * lit::<T>(2.0));
                return Some((inf, inf));
            }
            top = top.max(v);
        }
        if top == T::zero() {
            return Some((T::zero(), crate::numeric::scalar::nan()));
        }
        let (mut sum, mut least) = (T::zero(), T::one());
        for k in self.indices(n) {
            let rel = speed(k) / top;
            sum += rel;
            least = least.min(rel);
        }
        let mean = sum / lit::<T>(self.count as f64);
        Some((mean * top, (T::one() - least) / mean))
    }

    /// The largest distance of `path` (the closed path the run was found on) from the run's
    /// line on the side the rest of the path lies on: how high the swing of a foot whose
    /// stance is the run lifts — the obstacle it can step over. Samples that are not finite
    /// are skipped; 0 when the run is the whole path.
    ///
    /// ```
    /// use linkage_core::{straight_part, Vec2};
    /// // A flat bottom from (0, 0) to (4, 0), then up to (2, 1.5) and back.
    /// let path = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0), (4.0, 0.0), (2.0, 1.5)]
    ///     .map(|(x, y)| Vec2::new(x, y));
    /// let part = straight_part(&path, 1e-9, true).unwrap();
    /// assert_eq!(part.lift(&path), 1.5);
    /// ```
    pub fn lift(&self, path: &[Vec2<T>]) -> T {
        let n = path.len();
        let normal = Vec2::new(-self.direction.y, self.direction.x);
        let offset = |p: Vec2<T>| (p - self.point).dot(&normal);
        let finite = |p: &Vec2<T>| p.x.is_finite() && p.y.is_finite();
        let in_run = |k: usize| (k + n - self.start % n.max(1)) % n.max(1) < self.count;
        // The swing's side: the sign of its mean offset.
        let (mut sum, mut swing) = (T::zero(), 0usize);
        for (k, &p) in path.iter().enumerate() {
            if !in_run(k) && finite(&p) {
                sum += offset(p);
                swing += 1;
            }
        }
        if swing == 0 {
            return T::zero();
        }
        let side = if sum < T::zero() { -T::one() } else { T::one() };
        path.iter()
            .filter(|p| finite(p))
            .map(|&p| side * offset(p))
            .fold(T::zero(), |a, b| a.max(b))
    }
}

/// Total-least-squares line through `pts`: centroid, unit direction (first → last), largest
/// deviation and extent along the line. Coordinates are taken relative to the first point so
/// that paths far from the origin keep their digits.
fn fit<T: RealField + Copy>(
    pts: impl Iterator<Item = Vec2<T>> + Clone,
) -> (Vec2<T>, Vec2<T>, T, T) {
    let mut it = pts.clone();
    let Some(first) = it.next() else {
        return (
            Vec2::zeros(),
            Vec2::new(T::one(), T::zero()),
            T::zero(),
            T::zero(),
        );
    };
    let mut last = first;
    let (mut n, mut sx, mut sy) = (T::zero(), T::zero(), T::zero());
    for p in pts.clone() {
        let d = p - first;
        n += T::one();
        sx += d.x;
        sy += d.y;
        last = p;
    }
    let c = Vec2::new(sx / n, sy / n);
    let (mut sxx, mut sxy, mut syy) = (T::zero(), T::zero(), T::zero());
    for p in pts.clone() {
        let d = p - first - c;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    // Principal axis of the scatter: angle ½·atan2(2 Sxy, Sxx − Syy).
    let phi = (lit::<T>(2.0) * sxy).atan2(sxx - syy) * lit::<T>(0.5);
    let (s, co) = phi.sin_cos();
    let mut dir = Vec2::new(co, s);
    if dir.dot(&(last - first)) < T::zero() {
        dir = -dir;
    }
    let (mut dev, mut lo, mut hi) = (T::zero(), T::zero(), T::zero());
    for p in pts {
        let d = p - first - c;
        dev = dev.max(cross(dir, d).abs());
        let t = dir.dot(&d);
        lo = lo.min(t);
        hi = hi.max(t);
    }
    (first + c, dir, dev, hi - lo)
}

/// The longest run of consecutive samples of `path` that stays within `tol` of its own
/// total-least-squares line (at least 3 samples), or `None` if there is none.
///
/// On a `closed` path (the last sample followed by the first, without repeating it) runs may
/// wrap around. Non-finite samples break runs. The least-squares line is not the minimax one,
/// so the reported deviation can exceed the narrowest strip's half-width by a little; it is the
/// honest deviation from the reported line, computed from the run's own samples (relative to
/// its first sample, so paths far from the origin keep their digits).
///
/// # The scan
///
/// A two-pointer sweep: for each start `i` (a finite sample), the window `i..j` left by the
/// previous start (less its first sample) is checked; if it no longer fits (dropping the first
/// sample can, rarely, tilt the fit), the start is skipped, else `j` grows while the next
/// sample is finite and the grown window still fits. "Fits" means that the deviation of the
/// window from its least-squares line, computed as the reported `max_deviation` is, is at most
/// `tol`. Skipping loses nothing: a window from `i` that ends before `j` is shorter than the
/// previous start's fitting window, and growing to one that ends past `j` would pass through
/// `i..j`. So `j` never moves back, and every check but one per start moves `j`: at most `3n`
/// checks in all (3.0·10⁶ on the bench's 10⁶-sample foot path).
///
/// # The window check
///
/// With the `alloc` feature each check costs `O(log n)` amortised (below), so the scan costs
/// `O(n log n)`. A window's line comes from running
/// moments (Welford updates as the pointers move, recomputed every 128 updates — or when the
/// updates grow as large as the moments — from the `O(log n)` covering nodes of a segment tree
/// of moments, by Chan's pairwise merge). Its largest distance from the line is the largest
/// and smallest `v·q` over the window, `v` the line's normal: support queries on the window's
/// convex hull, which a queue of two hulls answers (the maximum of a linear function over a
/// union is the larger of the parts' maxima):
///
/// - The window is split at `m` into a front `i..m` and a back `m..j`; while a grown window
///   `i..j + 1` is tried, its new sample is taken on its own, so a failed try changes nothing.
/// - Each part is an upper and a lower hull chain, kept as the live slots of the samples'
///   ranks in `(x, y)` order (a radix sort, once): a 64-ary tree of bit words finds a slot's
///   live neighbours in `⌈log₆₄ n⌉ ≤ 6` word operations, and links walk the chain. Inserting a
///   sample removes the vertices it hides and logs them; undoing the insertion restores them.
/// - The back grows by inserting sample `j` as `j` grows (`j` never moves back). The
///   front is filled from `m − 1` down to `i`, so that dropping sample `i` undoes the last
///   insertion. When `i` reaches `m`, or the window leaves the queue, the queue is refilled
///   with the window: the last eighth in the back, the rest in the front.
/// - A support query walks up to 8 steps along the chain from its last answer (the line turns
///   little from one window to the next) and otherwise bisects the slots, `O(log n)` steps.
/// - Windows of at most 32 samples are scanned directly instead; the queue catches up when a
///   longer window needs it (at a cost bounded by the pointers' moves since).
///
/// Why `O(log n)` amortised: a check makes at most 4 support queries (8 if the cheap bound on
/// the window's radius does not decide it), each `O(log n)`. The front only inserts then
/// undoes, newest first, so its removals and restorations are at most its insertions. A refill
/// because `i` reached `m` inserts the samples `j` passed since the last refill plus an eighth
/// of that one's, which `i` has since passed seven times over; one because the window left the
/// queue inserts no more samples than the pointers moved since. So refills insert `O(1)`
/// samples per pointer move, amortised. The back inserts each sample once, and an insertion
/// removes each vertex at most once. So every check costs `O(log n)` amortised, and the scan
/// `O(n log n)` in all.
///
/// Memory is `O(n)`: for `f64` about 90 bytes per sample (centred and rank-ordered copies,
/// 32; chain links, shared by front and back, 16; the tree of moments, 13; ranks and run
/// indices, 12; undo logs, up to 16), plus 20 during the sort; the segment tree of hulls this
/// replaced took `O(n log n)`, some 120 bytes per sample at 10⁶.
///
/// Measured (`bench/straightness.py`, a 2-core machine shared with other jobs, load average
/// 3–4): on the closed 10⁶-sample Hoecken foot path (a run of 193 545 samples, tolerance
/// 0.1 % of the coupler; 3.04·10⁶ checks, 36 refills of the queue, 17 direct refits) a call
/// takes 0.40 s (best of 3; 0.45 s of CPU from Python), the tree check it replaced 0.75 s in
/// the same process; CPU time grows 9.8, 9.9 and 12.5 times per decade from 10³ to 10⁶
/// samples, where `n log n` grows 13.3, 12.5 and 12.0 times.
///
/// The result is the one a direct refit of every window gives (the `O(n·w)` scan used without
/// `alloc`, for runs of `w` samples): same run, and the line, deviation and length are computed
/// from the run's samples exactly as there. The fast check carries an error bound on the
/// difference between its deviation and the direct refit's: `8·ε·(√w + 4)` times the window's
/// radius, plus `64·ε` times the path's extent from its centre, both enlarged as the window
/// nears isotropy (where its line is ill-defined). The `√w` is the statistical growth of
/// rounding in the direct refit's sequential sums; the worst case, `w·ε`, needs adversarial
/// orderings of rounding errors, and bounding with it made long windows (10⁵ samples) fall
/// back to refits by the hundred. A window whose deviation is within that bound of `tol` —
/// including every window at rounding level with `tol = 0`, except windows with one `y`
/// throughout, which the direct refit puts at deviation 0 exactly — is decided by a direct
/// refit instead. Those refits are budgeted (`64·n` samples in all): past the budget, which only
/// data that stays at rounding level from `tol` over very many long windows can exhaust, the
/// fast deviation decides, which may differ from a direct refit at the level of rounding.
/// Windows holding samples whose squared spread overflows (|coordinates| beyond about `1e150`
/// for `f64`, `1e18` for `f32`) are always decided by the direct refit, within the same budget.
pub fn straight_part<T: RealField + Copy>(
    path: &[Vec2<T>],
    tol: T,
    closed: bool,
) -> Option<StraightPart<T>> {
    let n = path.len();
    if n < 3 || !tol.is_finite() || tol < T::zero() {
        return None;
    }
    #[cfg(feature = "alloc")]
    let (i, j) = queue::longest_run(path, tol, closed)?;
    #[cfg(not(feature = "alloc"))]
    let (i, j) = scan(path, closed, |i, j| fits_directly(path, tol, i, j))?;
    let (point, direction, max_deviation, length) = fit(window(path, i, j));
    Some(StraightPart {
        start: i,
        count: j - i,
        point,
        direction,
        max_deviation,
        length,
    })
}

/// Samples `i..j` of `path`, wrapping past its end.
fn window<T: RealField + Copy>(
    path: &[Vec2<T>],
    i: usize,
    j: usize,
) -> impl Iterator<Item = Vec2<T>> + Clone + '_ {
    let n = path.len();
    (i..j).map(move |k| path[k % n])
}

/// Whether samples `i..j` fit within `tol` of their least-squares line, by refitting them.
fn fits_directly<T: RealField + Copy>(path: &[Vec2<T>], tol: T, i: usize, j: usize) -> bool {
    fit(window(path, i, j)).2 <= tol
}

/// The two-pointer scan of [`straight_part`] with the window check `fits(i, j)` (samples
/// `i..j`, indices past the end wrapping): the longest run as `(start, end)`. `fits` is only
/// asked about windows of at least 2 finite samples. `path` must hold at least one sample.
fn scan<T: RealField + Copy>(
    path: &[Vec2<T>],
    closed: bool,
    mut fits: impl FnMut(usize, usize) -> bool,
) -> Option<(usize, usize)> {
    let n = path.len();
    let ok = |k: usize| {
        let p = path[k % n];
        p.x.is_finite() && p.y.is_finite()
    };
    let mut best: Option<(usize, usize)> = None;
    let mut j = 0;
    for i in 0..n {
        if !ok(i) {
            continue;
        }
        let limit = if closed { i + n } else { n };
        j = j.max(i + 1);
        // `i..j` is the previous start's fitting window less its first sample. Dropping a
        // sample can (rarely) tilt the fit past `tol`; then this start is skipped and `j` stays:
        // a window from `i` ending before `j` is shorter than the previous start's, so it cannot
        // be the longest, and one ending past `j` would have had to fit at `j` to be grown to.
        // So `j` never moves back, and the scan asks at most `3n` window checks in all.
        if j - i > 2 && !fits(i, j) {
            continue;
        }
        while j < limit && ok(j) && fits(i, j + 1) {
            j += 1;
        }
        if j - i >= 3 && best.is_none_or(|(a, b)| j - i > b - a) {
            best = Some((i, j));
        }
        if closed && j - i == n {
            break;
        }
    }
    best
}

#[cfg(feature = "alloc")]
mod hull;
#[cfg(feature = "alloc")]
mod moments;
#[cfg(feature = "alloc")]
mod queue;
#[cfg(feature = "alloc")]
mod samples;
/// The window check before the queue (a segment tree of hulls, `O(log² n)`), kept for the
/// timing comparison of `tests::direct_scan_timing`.
#[cfg(all(test, feature = "alloc"))]
mod tree_check;

#[cfg(test)]
mod tests;
