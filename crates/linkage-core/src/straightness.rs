//! Straight-line quality of a sampled path: the longest run of samples within a tolerance of
//! its best-fit line.

use nalgebra::RealField;

use crate::scalar::{cross, lit, Vec2};

/// A near-straight run of a sampled path.
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
/// A two-pointer sweep: for each start `i` (a finite sample) the end `j` first shrinks while
/// the window `i..j` does not fit (dropping the first sample can, rarely, tilt the fit), then
/// grows while the next sample is finite and the grown window still fits. "Fits" means that
/// the deviation of the window from its least-squares line, computed as the reported
/// `max_deviation` is, is at most `tol`. That is `O(n)` window checks.
///
/// With the `alloc` feature each check costs `O(log² n)` at most: the samples, centred on the
/// middle of their bounding box, are kept in a segment tree whose nodes hold their moments and
/// their convex hull. A window's line comes from running moments (Welford updates as the
/// pointers move, recomputed from the `O(log n)` covering nodes — Chan's pairwise merge — every
/// 32 updates or when the updates grow as large as the moments); its largest deviation from the
/// hulls' support in the line's normal direction. Each node remembers its last extreme samples
/// and direction, which bound its support in a nearby direction in `O(1)`; only nodes that can
/// hold the window's extreme are searched, by galloping from the last position along the hull
/// (`O(log h)`). The tree is built bottom-up in `O(n log n)`: a node's lower (upper) hull
/// chain is the lower (upper) hull of its children's, concatenated when they lie apart along
/// `x` (the usual case on a path). The whole run costs `O(n log² n)` time and `O(n log n)`
/// memory at most: hull indices take up to `4·n·log₂(n/16)` bytes (about 64 MB for 10⁶
/// samples of a convex curve, far less for noisy or straight data), plus about 55 bytes per
/// sample. On a 10⁶-sample closed foot path (a run of 193 545 samples, tolerance 0.1 % of the
/// coupler) that is about 3·10⁶ window checks, 0.75–0.8 s in all, a fifth of it building the
/// tree.
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
    let (i, j) = fast::longest_run(path, tol, closed)?;
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
        // Dropping the first sample can (rarely) tilt the fit; shrink until it holds.
        while j > i + 2 && !fits(i, j) {
            j -= 1;
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

/// The `O(log² n)` window check of [`straight_part`] (see there).
#[cfg(feature = "alloc")]
mod fast {
    use alloc::vec::Vec;
    use core::cmp::Ordering;

    use nalgebra::RealField;

    use super::{fits_directly, scan};
    use crate::scalar::{cross, eps, lit, Vec2};

    /// Samples per leaf of the segment tree (a window's partial leaves are scanned directly).
    const LEAF: usize = 16;

    /// Moments and bounds of a set of samples, in centred coordinates.
    #[derive(Clone, Copy)]
    struct Stats<T> {
        /// Number of samples (as a count and as `T`).
        count: usize,
        w: T,
        mean: Vec2<T>,
        /// Second central moments.
        sxx: T,
        sxy: T,
        syy: T,
        /// Bounding box (centred).
        lo: Vec2<T>,
        hi: Vec2<T>,
        /// Smallest and largest `y` of the original samples, uncentred.
        ylo: T,
        yhi: T,
    }

    impl<T: RealField + Copy> Stats<T> {
        fn empty() -> Self {
            let z = T::zero();
            Stats {
                count: 0,
                w: z,
                mean: Vec2::zeros(),
                sxx: z,
                sxy: z,
                syy: z,
                lo: Vec2::zeros(),
                hi: Vec2::zeros(),
                ylo: z,
                yhi: z,
            }
        }

        /// Direct two-pass moments of `q[a..b]` (all finite), original `y` from `path`.
        fn of_span(q: &[Vec2<T>], path: &[Vec2<T>], a: usize, b: usize) -> Self {
            let pts = &q[a..b];
            let Some(&first) = pts.first() else {
                return Self::empty();
            };
            let w: T = lit((b - a) as f64);
            let (mut sum, mut lo, mut hi) = (Vec2::zeros(), first, first);
            for p in pts {
                sum += p;
                lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
                hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
            }
            let mean = sum / w;
            let (mut sxx, mut sxy, mut syy) = (T::zero(), T::zero(), T::zero());
            for p in pts {
                let d = p - mean;
                sxx += d.x * d.x;
                sxy += d.x * d.y;
                syy += d.y * d.y;
            }
            let (mut ylo, mut yhi) = (path[a].y, path[a].y);
            for p in &path[a..b] {
                ylo = ylo.min(p.y);
                yhi = yhi.max(p.y);
            }
            Stats {
                count: b - a,
                w,
                mean,
                sxx,
                sxy,
                syy,
                lo,
                hi,
                ylo,
                yhi,
            }
        }

        /// Adds one sample to the moments (Welford's update; the bounds are left alone).
        /// Returns the size of the update term, for the error bound.
        fn add(&mut self, p: Vec2<T>) -> T {
            self.count += 1;
            self.w += T::one();
            let d = p - self.mean;
            self.mean += d / self.w;
            let e = p - self.mean;
            self.sxx += d.x * e.x;
            self.sxy += d.x * e.y;
            self.syy += d.y * e.y;
            (d.x * e.x).abs() + (d.y * e.y).abs()
        }

        /// Removes one of its samples from the moments (the inverse of [`Stats::add`]).
        fn remove(&mut self, p: Vec2<T>) -> T {
            if self.count <= 1 {
                *self = Self::empty();
                return T::zero();
            }
            self.count -= 1;
            self.w -= T::one();
            let d = p - self.mean;
            self.mean -= d / self.w;
            let e = p - self.mean;
            self.sxx -= e.x * d.x;
            self.sxy -= e.x * d.y;
            self.syy -= e.y * d.y;
            (d.x * e.x).abs() + (d.y * e.y).abs()
        }

        /// The union of two disjoint sets (Chan, Golub and LeVeque's pairwise update).
        fn merge(self, o: Self) -> Self {
            if o.count == 0 {
                return self;
            }
            if self.count == 0 {
                return o;
            }
            let w = self.w + o.w;
            let d = o.mean - self.mean;
            let f = self.w * o.w / w;
            Stats {
                count: self.count + o.count,
                w,
                mean: self.mean + d * (o.w / w),
                sxx: self.sxx + o.sxx + d.x * d.x * f,
                sxy: self.sxy + o.sxy + d.x * d.y * f,
                syy: self.syy + o.syy + d.y * d.y * f,
                lo: Vec2::new(self.lo.x.min(o.lo.x), self.lo.y.min(o.lo.y)),
                hi: Vec2::new(self.hi.x.max(o.hi.x), self.hi.y.max(o.hi.y)),
                ylo: self.ylo.min(o.ylo),
                yhi: self.yhi.max(o.yhi),
            }
        }
    }

    /// One level of the tree: nodes of `size` samples (the last may be shorter).
    struct Level<T> {
        size: usize,
        /// Moments of each node's finite samples.
        stats: Vec<Stats<T>>,
        /// Per node: its lower and upper hull chains, left to right, as (start, length) in
        /// `chains`, and where the last search on each chain ended (a finger).
        hot: Vec<[u32; 6]>,
        /// Per node: the last exact extremes (see [`Cache`]).
        cache: Vec<Cache<T>>,
        chains: Vec<u32>,
    }

    /// What a node remembers of its last exact extremes, to bound the next ones cheaply.
    ///
    /// For `side` 0 (largest `v·q`) and 1 (largest `−v·q`): the direction `u` of the last
    /// exact search and the sample that was extreme (`NONE` before any). For a new direction
    /// `u'` the node's largest `u'·q` is at least `u'·q[arg]` and at most
    /// `u·q[arg] + (u' − u)·centre + |u' − u|₁·radius`.
    #[derive(Clone, Copy)]
    struct Cache<T> {
        centre: Vec2<T>,
        radius: T,
        u: [Vec2<T>; 2],
        arg: [u32; 2],
        /// `q[arg]`, kept here to spare a load from the (large) sample array.
        at: [Vec2<T>; 2],
    }

    /// No sample.
    const NONE: u32 = u32::MAX;

    /// A piece of a window: a tree node or a short span of samples.
    #[derive(Clone, Copy)]
    enum Piece {
        Node(usize, usize),
        Span(usize, usize),
    }

    /// The centred samples and their segment tree of moments and hulls.
    struct Tree<T> {
        q: Vec<Vec2<T>>,
        levels: Vec<Level<T>>,
        /// Number of non-finite centred samples before each index (`n + 1` entries).
        bad: Vec<u32>,
        /// For each sample, the end of the run of samples with its original `y`.
        level_end: Vec<u32>,
        /// Largest distance of a finite centred sample from the centre.
        extent: T,
    }

    fn finite<T: RealField + Copy>(p: Vec2<T>) -> bool {
        p.x.is_finite() && p.y.is_finite()
    }

    impl<T: RealField + Copy> Tree<T> {
        fn new(path: &[Vec2<T>]) -> Self {
            // Centre on the middle of the finite samples' bounding box.
            let mut it = path.iter().copied().filter(|p| finite(*p));
            let centre = it.next().map_or(Vec2::zeros(), |f| {
                let (lo, hi) = it.fold((f, f), |(lo, hi), p| {
                    (
                        Vec2::new(lo.x.min(p.x), lo.y.min(p.y)),
                        Vec2::new(hi.x.max(p.x), hi.y.max(p.y)),
                    )
                });
                let half: T = lit(0.5);
                Vec2::new(lo.x * half + hi.x * half, lo.y * half + hi.y * half)
            });
            let q: Vec<Vec2<T>> = path.iter().map(|p| p - centre).collect();
            let mut bad = Vec::with_capacity(q.len() + 1);
            let mut count = 0u32;
            let mut extent = T::zero();
            bad.push(0);
            for p in &q {
                if finite(*p) {
                    extent = extent.max(p.norm());
                } else {
                    count += 1;
                }
                bad.push(count);
            }
            let mut level_end = alloc::vec![0u32; q.len()];
            let mut end = q.len();
            for k in (0..q.len()).rev() {
                if k + 1 < q.len() && path[k + 1].y != path[k].y {
                    end = k + 1;
                }
                level_end[k] = end as u32;
            }
            let mut tree = Tree {
                q,
                levels: Vec::new(),
                bad,
                level_end,
                extent,
            };
            tree.build(path);
            tree
        }

        /// `q[a]` before `q[b]`: by `x`, then `y`, then index.
        fn before(&self, a: u32, b: u32) -> bool {
            let (p, r) = (self.q[a as usize], self.q[b as usize]);
            match p.x.partial_cmp(&r.x) {
                Some(Ordering::Less) => true,
                Some(Ordering::Greater) => false,
                _ => match p.y.partial_cmp(&r.y) {
                    Some(Ordering::Less) => true,
                    Some(Ordering::Greater) => false,
                    _ => a < b,
                },
            }
        }

        /// Merges two sorted index lists into `out`, dropping repeated indices.
        fn merge_sorted(&self, a: &[u32], b: &[u32], out: &mut Vec<u32>) {
            out.clear();
            // Children far apart along x (the usual case on a path): a concatenation.
            match (a.first(), a.last(), b.first(), b.last()) {
                (None, ..) | (_, _, None, _) => {
                    out.extend_from_slice(a);
                    out.extend_from_slice(b);
                    return;
                }
                (_, Some(&al), Some(&bf), _) if self.before(al, bf) => {
                    out.extend_from_slice(a);
                    out.extend_from_slice(b);
                    return;
                }
                (Some(&af), _, _, Some(&bl)) if self.before(bl, af) => {
                    out.extend_from_slice(b);
                    out.extend_from_slice(a);
                    return;
                }
                _ => {}
            }
            let (mut i, mut j) = (0, 0);
            while i < a.len() || j < b.len() {
                let k = if j >= b.len() || (i < a.len() && self.before(a[i], b[j])) {
                    i += 1;
                    a[i - 1]
                } else {
                    j += 1;
                    b[j - 1]
                };
                if out.last() != Some(&k) {
                    out.push(k);
                }
            }
        }

        /// Appends the lower (`upper` false) or upper hull chain of the sorted samples
        /// `sorted` to `chains`.
        fn half_hull(&self, sorted: &[u32], upper: bool, chains: &mut Vec<u32>) {
            let q = &self.q;
            let turn = |c: &[u32], k: u32| {
                let (a, b) = (q[c[c.len() - 2] as usize], q[c[c.len() - 1] as usize]);
                let t = cross(b - a, q[k as usize] - a);
                if upper {
                    -t
                } else {
                    t
                }
            };
            let start = chains.len();
            for &k in sorted {
                while chains.len() >= start + 2 && turn(&chains[start..], k) <= T::zero() {
                    chains.pop();
                }
                chains.push(k);
            }
        }

        /// Appends the lower and upper hull chains of the sorted samples `sorted` to `chains`.
        fn hull(&self, sorted: &[u32], chains: &mut Vec<u32>) -> [u32; 6] {
            self.hulls(sorted, sorted, chains)
        }

        /// Appends the lower hull chain of the sorted samples `lower` and the upper one of
        /// `upper` to `chains`: a node's chains from its children's (a lower hull of a union
        /// is the lower hull of the parts' lower hulls, and likewise upper).
        fn hulls(&self, lower: &[u32], upper: &[u32], chains: &mut Vec<u32>) -> [u32; 6] {
            let start = chains.len();
            self.half_hull(lower, false, chains);
            let mid = chains.len();
            self.half_hull(upper, true, chains);
            // The tree is only built for n ≤ u32::MAX / 4 samples, so offsets fit.
            let at = |x: usize| x as u32;
            [
                at(start),
                at(mid - start),
                at(mid),
                at(chains.len() - mid),
                0,
                0,
            ]
        }

        /// A node's lower and upper chains.
        fn chain_pair<'c>(chains: &'c [u32], hot: &[u32; 6]) -> (&'c [u32], &'c [u32]) {
            let range = |s: u32, l: u32| &chains[s as usize..(s + l) as usize];
            (range(hot[0], hot[1]), range(hot[2], hot[3]))
        }

        fn build(&mut self, path: &[Vec2<T>]) {
            let n = self.q.len();
            let (mut sorted, mut a, mut b) = (Vec::new(), Vec::new(), Vec::new());
            // Leaves: runs of finite samples are kept; a leaf with a non-finite sample still
            // gets the moments and hull of its finite ones (windows never hold it whole).
            let mut leaves = Level {
                size: LEAF,
                stats: Vec::with_capacity(n.div_ceil(LEAF)),
                hot: Vec::with_capacity(n.div_ceil(LEAF)),
                cache: Vec::new(),
                chains: Vec::new(),
            };
            for s in (0..n).step_by(LEAF) {
                let e = (s + LEAF).min(n);
                sorted.clear();
                let mut stats = Stats::empty();
                sorted.extend(
                    (s..e)
                        .zip(&self.q[s..e])
                        .zip(&path[s..e])
                        .filter(|((_, q), p)| finite(**q) && finite(**p))
                        .map(|((k, _), _)| k as u32),
                );
                if sorted.len() == e - s {
                    stats = Stats::of_span(&self.q, path, s, e);
                } else {
                    for &k in &sorted {
                        let k = k as usize;
                        stats = stats.merge(Stats::of_span(&self.q, path, k, k + 1));
                    }
                }
                sorted.sort_unstable_by(|&x, &y| {
                    if self.before(x, y) {
                        Ordering::Less
                    } else {
                        Ordering::Greater
                    }
                });
                leaves.hot.push(self.hull(&sorted, &mut leaves.chains));
                leaves.stats.push(stats);
            }
            self.levels.push(leaves);
            while self.levels.last().is_some_and(|l| l.hot.len() > 1) {
                let Some(below) = self.levels.last() else {
                    break;
                };
                let mut level = Level {
                    size: below.size * 2,
                    stats: Vec::with_capacity(below.hot.len().div_ceil(2)),
                    hot: Vec::with_capacity(below.hot.len().div_ceil(2)),
                    cache: Vec::new(),
                    chains: Vec::new(),
                };
                for (pair, pair_stats) in below.hot.chunks(2).zip(below.stats.chunks(2)) {
                    let mut stats = Stats::empty();
                    a.clear();
                    b.clear();
                    for (h, child) in pair.iter().zip(pair_stats) {
                        stats = stats.merge(*child);
                        let (lo, up) = Self::chain_pair(&below.chains, h);
                        self.merge_sorted(&a, lo, &mut sorted);
                        core::mem::swap(&mut sorted, &mut a);
                        self.merge_sorted(&b, up, &mut sorted);
                        core::mem::swap(&mut sorted, &mut b);
                    }
                    level.hot.push(self.hulls(&a, &b, &mut level.chains));
                    level.stats.push(stats);
                }
                self.levels.push(level);
            }
            for level in &mut self.levels {
                level.cache = level
                    .stats
                    .iter()
                    .map(|st| {
                        // The farthest corner of the bounding box from the centroid.
                        let far = |lo: T, hi: T, m: T| (lo - m).abs().max((hi - m).abs());
                        let radius = Vec2::new(
                            far(st.lo.x, st.hi.x, st.mean.x),
                            far(st.lo.y, st.hi.y, st.mean.y),
                        )
                        .norm();
                        Cache {
                            centre: st.mean,
                            radius,
                            u: [Vec2::zeros(); 2],
                            arg: [NONE; 2],
                            at: [Vec2::zeros(); 2],
                        }
                    })
                    .collect();
            }
        }

        /// Largest `v·q` over a hull chain along which it is unimodal, searching from the
        /// chain position `hint` outwards (galloping, then bisecting) and leaving the answer
        /// there: `O(log d)` for an answer `d` places from the last one.
        fn chain_max(q: &[Vec2<T>], chain: &[u32], v: Vec2<T>, hint: &mut u32) -> (T, u32) {
            let at = |k: usize| q[chain[k] as usize];
            let Some(edges) = chain.len().checked_sub(1) else {
                return (T::zero(), NONE);
            };
            // Rising along edge k (monotone: true, then false); the answer is the first false.
            let rising = |k: usize| v.dot(&(at(k + 1) - at(k))) > T::zero();
            let h = (*hint as usize).min(edges);
            let (mut lo, mut hi);
            if h < edges && rising(h) {
                (lo, hi) = (h + 1, edges);
                let mut step = 1;
                while lo < edges {
                    let probe = (lo + step - 1).min(edges - 1);
                    if rising(probe) {
                        lo = probe + 1;
                        step *= 2;
                    } else {
                        hi = probe;
                        break;
                    }
                }
            } else {
                (lo, hi) = (0, h);
                let mut step = 1;
                while hi > 0 {
                    let probe = hi.saturating_sub(step);
                    if rising(probe) {
                        lo = probe + 1;
                        break;
                    }
                    hi = probe;
                    step *= 2;
                }
            }
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if rising(mid) {
                    lo = mid + 1;
                } else {
                    hi = mid;
                }
            }
            *hint = lo as u32;
            (v.dot(&at(lo)), chain[lo])
        }

        /// Largest `u·q` over the samples of node `k` of level `l`, and a sample where it is.
        fn node_max(&mut self, l: usize, k: usize, u: Vec2<T>) -> (T, u32) {
            let level = &mut self.levels[l];
            let hot = &mut level.hot[k];
            let (lower, upper) = Self::chain_pair(&level.chains, hot);
            let q = &self.q;
            if u.y == T::zero() {
                // Along x: the first or last sample of a chain.
                let end = if u.x > T::zero() {
                    upper.last()
                } else {
                    upper.first()
                };
                return end.map_or((T::zero(), NONE), |&k| (u.dot(&q[k as usize]), k));
            }
            // The upper chain holds the largest u·q for u pointing up, the lower one otherwise.
            if u.y > T::zero() {
                Self::chain_max(q, upper, u, &mut hot[4])
            } else {
                Self::chain_max(q, lower, u, &mut hot[5])
            }
        }

        /// Splits samples `a..b` into the largest aligned tree nodes and short spans.
        fn pieces(&self, a: usize, b: usize, out: &mut Vec<Piece>) {
            let top = self.levels.len().saturating_sub(1);
            let mut s = a;
            while s < b {
                if s.is_multiple_of(LEAF) && b - s >= LEAF {
                    let blocks = s / LEAF;
                    let by_align = if blocks == 0 {
                        usize::MAX
                    } else {
                        blocks.trailing_zeros() as usize
                    };
                    let by_len = ((b - s) / LEAF).ilog2() as usize;
                    let l = by_align.min(by_len).min(top);
                    out.push(Piece::Node(l, s / (LEAF << l)));
                    s += LEAF << l;
                } else {
                    let e = ((s / LEAF + 1) * LEAF).min(b);
                    out.push(Piece::Span(s, e));
                    s = e;
                }
            }
        }
    }

    /// Updates of the running moments after which they are recomputed from the tree.
    const REFRESH: usize = 32;

    /// The window check of [`super::straight_part`] on a tree, with the refit budget.
    struct Checker<'a, T> {
        path: &'a [Vec2<T>],
        tol: T,
        tree: Tree<T>,
        pieces: Vec<Piece>,
        /// The tree nodes of the whole leaves `middle_of` of the last window that had some.
        middle: Vec<Piece>,
        middle_of: (usize, usize),
        budget: usize,
        /// Running moments of samples `a..b` (indices past the end wrapping), the number of
        /// single-sample updates since they were exact and the sum of the updates' sizes.
        a: usize,
        b: usize,
        moments: Stats<T>,
        updates: usize,
        drift: T,
        /// The last window's samples of largest `v·q` and `−v·q` (or `NONE`).
        seed: [u32; 2],
    }

    impl<T: RealField + Copy> Checker<'_, T> {
        /// Moves the running moments to samples `i..j`: one sample at a time when that is
        /// short and accurate, from the tree's nodes (`self.pieces`) otherwise.
        fn move_to(&mut self, i: usize, j: usize) {
            let n = self.path.len();
            let steps = self.a.abs_diff(i) + self.b.abs_diff(j);
            let q = |k: usize| self.tree.q[k % n];
            if self.updates + steps <= REFRESH && self.a < j && i < self.b {
                while self.b < j {
                    self.drift += self.moments.add(q(self.b));
                    self.b += 1;
                }
                while self.a > i {
                    self.a -= 1;
                    self.drift += self.moments.add(q(self.a));
                }
                while self.b > j {
                    self.b -= 1;
                    self.drift += self.moments.remove(q(self.b));
                }
                while self.a < i {
                    self.drift += self.moments.remove(q(self.a));
                    self.a += 1;
                }
                self.updates += steps;
                if self.drift <= self.moments.sxx + self.moments.syy {
                    return;
                }
            }
            let mut st = Stats::empty();
            for &p in &self.pieces {
                st = st.merge(match p {
                    Piece::Node(l, k) => self.tree.levels[l].stats[k],
                    Piece::Span(a, b) => Stats::of_span(&self.tree.q, self.path, a, b),
                });
            }
            (self.a, self.b, self.moments, self.updates, self.drift) = (i, j, st, 0, T::zero());
        }

        /// Splits window `i..j` (indices past the end wrapping) into `self.pieces`: the tree
        /// nodes between its first and last whole leaves are kept from the last window with
        /// the same ones (they change once in `LEAF` moves of the scan), the rest are spans.
        fn window_pieces(&mut self, i: usize, j: usize) {
            let n = self.path.len();
            self.pieces.clear();
            let (a, b) = (i.next_multiple_of(LEAF), j / LEAF * LEAF);
            if j <= n && a < b {
                // What `Tree::pieces(i, j)` gives: the span up to the first leaf boundary,
                // the nodes of `a..b` (sized by `b − s`, as by `j − s`), the span after `b`.
                if self.middle_of != (a, b) {
                    self.middle.clear();
                    self.tree.pieces(a, b, &mut self.middle);
                    self.middle_of = (a, b);
                }
                if i < a {
                    self.pieces.push(Piece::Span(i, a));
                }
                self.pieces.extend_from_slice(&self.middle);
                if b < j {
                    self.pieces.push(Piece::Span(b, j));
                }
                return;
            }
            self.tree.pieces(i, j.min(n), &mut self.pieces);
            if j > n {
                self.tree.pieces(0, j - n, &mut self.pieces);
            }
        }

        /// Whether samples `i..j` (indices past the end wrapping) are all finite once
        /// centred, and whether they all have the same original `y`.
        fn complete_and_level(&self, i: usize, j: usize) -> (bool, bool) {
            let (n, t) = (self.path.len(), &self.tree);
            let bad = |a: usize, b: usize| t.bad[b] != t.bad[a];
            if j <= n {
                (!bad(i, j), t.level_end[i] as usize >= j)
            } else {
                let complete = !bad(i, n) && !bad(0, j - n);
                let level = t.level_end[i] as usize == n
                    && t.level_end[0] as usize >= j - n
                    && self.path[0].y == self.path[i].y;
                (complete, level)
            }
        }

        fn fits(&mut self, i: usize, j: usize) -> bool {
            let (complete, level) = self.complete_and_level(i, j);
            if complete && level {
                // Same y throughout: the direct refit finds the x axis and deviation 0 exactly.
                return true;
            }
            self.window_pieces(i, j);
            if complete {
                self.move_to(i, j);
                let (dev, r) = self.deviation(i, j);
                // First with a cheap bound on the window's radius, then with its bounding box.
                for tight in [false, true] {
                    let err = self.error(if tight { self.radius() } else { r });
                    if dev.is_finite() && err.is_finite() {
                        if dev + err < self.tol {
                            return true;
                        }
                        if dev - err > self.tol {
                            return false;
                        }
                    }
                }
                let w = j - i;
                if w > self.budget {
                    return dev <= self.tol;
                }
            }
            let w = j - i;
            if w > self.budget {
                return false;
            }
            self.budget -= w;
            fits_directly(self.path, self.tol, i, j)
        }

        /// Largest deviation of the window (`self.pieces`, running moments) from its
        /// least-squares line — or a lower bound on it that already exceeds `tol` by more
        /// than the error bound — and a bound on the window's radius about its centroid.
        fn deviation(&mut self, i: usize, j: usize) -> (T, T) {
            let st = self.moments;
            let two: T = lit(2.0);
            // The principal axis at half the angle of (Sxx − Syy, 2 Sxy), without trigonometry;
            // v is its normal.
            let (c2, s2) = (st.sxx - st.syy, two * st.sxy);
            let gap = (c2 * c2 + s2 * s2).sqrt();
            let v = if gap > T::zero() && gap.is_finite() {
                let (c2, s2) = (c2 / gap, s2 / gap);
                let (c, s) = if c2 >= T::zero() {
                    let c = ((T::one() + c2) / two).sqrt();
                    (c, s2 / (two * c))
                } else {
                    let s = ((T::one() - c2) / two).sqrt();
                    let s = if s2 < T::zero() { -s } else { s };
                    (s2 / (two * s), s)
                };
                Vec2::new(-s, c)
            } else {
                Vec2::new(T::zero(), T::one())
            };
            let vc = v.dot(&st.mean);
            // Σ|q − mean|² bounds every |q − mean|², up to the running moments' drift.
            let r = (two * (st.sxx + st.syy) + self.drift).sqrt();
            // A deviation this large is certainly beyond tol (given the error bound).
            let hopeless = self.tol + self.error(r);
            // Largest v·q and −v·q over the window: exact on the spans; on the nodes first
            // the value at each one's last extreme sample (attained, so a lower bound), then
            // an exact search only where the cached upper bound exceeds the best so far.
            let mut best = [vc, -vc];
            let mut best_at = [NONE; 2];
            let us = [v, -v];
            // Start from the last window's extreme samples, if this window holds them.
            let n = self.path.len();
            for side in 0..2 {
                let k = self.seed[side] as usize;
                let inside = if j <= n {
                    i <= k && k < j
                } else {
                    k >= i || k < j - n
                };
                if let (true, Some(q)) = (inside, self.tree.q.get(k)) {
                    let d = us[side].dot(q);
                    if d > best[side] {
                        (best[side], best_at[side]) = (d, self.seed[side]);
                    }
                }
            }
            let slack = eps::<T>() * lit(16.0) * self.tree.extent;
            for &p in &self.pieces {
                if best[0] - vc > hopeless || best[1] + vc > hopeless {
                    // Attained values: the deviation is at least this.
                    break;
                }
                let (l, k) = match p {
                    Piece::Node(l, k) => (l, k),
                    Piece::Span(a, b) => {
                        for (k, q) in (a..b).zip(&self.tree.q[a..b]) {
                            let d = v.dot(q);
                            if d > best[0] {
                                (best[0], best_at[0]) = (d, k as u32);
                            }
                            if -d > best[1] {
                                (best[1], best_at[1]) = (-d, k as u32);
                            }
                        }
                        continue;
                    }
                };
                for side in 0..2 {
                    let u = us[side];
                    let c = &self.tree.levels[l].cache[k];
                    if c.arg[side] != NONE {
                        // The last extreme sample: attained, and the base of the bound.
                        let q = &c.at[side];
                        let d = u.dot(q);
                        if d > best[side] {
                            (best[side], best_at[side]) = (d, c.arg[side]);
                        }
                        let du = u - c.u[side];
                        let bound = d - du.dot(&(q - c.centre))
                            + (du.x.abs() + du.y.abs()) * c.radius
                            + slack;
                        if bound <= best[side] {
                            continue;
                        }
                    }
                    let (d, arg) = self.tree.node_max(l, k, u);
                    let at = self.tree.q.get(arg as usize).copied();
                    let c = &mut self.tree.levels[l].cache[k];
                    c.u[side] = u;
                    c.arg[side] = if at.is_some() { arg } else { NONE };
                    c.at[side] = at.unwrap_or_else(Vec2::zeros);
                    if d > best[side] {
                        (best[side], best_at[side]) = (d, arg);
                    }
                }
            }
            self.seed = best_at;
            let (top, bottom) = (best[0], -best[1]);
            let dev = if top - vc > vc - bottom {
                top - vc
            } else {
                vc - bottom
            };
            (dev, r)
        }

        /// The window's radius about its centroid, from the bounding boxes of its pieces.
        fn radius(&self) -> T {
            let (t, m) = (&self.tree, self.moments.mean);
            let mut far: Vec2<T> = Vec2::zeros();
            let mut widen = |lo: Vec2<T>, hi: Vec2<T>| {
                far.x = far.x.max((lo.x - m.x).abs()).max((hi.x - m.x).abs());
                far.y = far.y.max((lo.y - m.y).abs()).max((hi.y - m.y).abs());
            };
            for &p in &self.pieces {
                match p {
                    Piece::Node(l, k) => {
                        let s = &t.levels[l].stats[k];
                        widen(s.lo, s.hi);
                    }
                    Piece::Span(a, b) => t.q[a..b].iter().for_each(|&q| widen(q, q)),
                }
            }
            far.norm()
        }

        /// Bound on the difference between the fast deviation and a direct refit's, for a
        /// window of radius `r` (see `straight_part`).
        fn error(&self, r: T) -> T {
            let st = self.moments;
            let (two, four): (T, T) = (lit(2.0), lit(4.0));
            let e: T = eps::<T>() * lit(8.0);
            // Rounding in sums of w terms: statistically √w ε (the worst case, w ε, is only
            // reached by adversarial orderings; see `straight_part`).
            let w4 = st.w.sqrt() + four;
            let total = st.sxx + st.syy;
            let (c2, s2) = (st.sxx - st.syy, two * st.sxy);
            let gap = (c2 * c2 + s2 * s2).sqrt();
            let rc = self.tree.extent;
            let moments = w4 * total + four * (rc * (st.w * total).sqrt() + self.drift);
            // At most a right angle's worth (also when the gap is 0 or the bound NaN).
            let dphi = e * moments / gap;
            let dphi = if dphi < two { dphi } else { two };
            dphi * r + e * (w4 * r + lit::<T>(8.0) * rc)
        }
    }

    /// The longest run of [`super::straight_part`], or `None`.
    pub(super) fn longest_run<T: RealField + Copy>(
        path: &[Vec2<T>],
        tol: T,
        closed: bool,
    ) -> Option<(usize, usize)> {
        let n = path.len();
        if n > (u32::MAX / 4) as usize {
            // Beyond the tree's indices (some 68 GB of f64 samples): direct refits.
            return scan(path, closed, |i, j| fits_directly(path, tol, i, j));
        }
        let mut checker = Checker {
            path,
            tol,
            tree: Tree::new(path),
            pieces: Vec::new(),
            middle: Vec::new(),
            middle_of: (0, 0),
            budget: n.saturating_mul(64),
            a: 0,
            b: 0,
            moments: Stats::empty(),
            updates: 0,
            drift: T::zero(),
            seed: [NONE; 2],
        };
        scan(path, closed, |i, j| checker.fits(i, j))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The direct scan: every window refitted (the algorithm before the segment tree).
    fn reference<T: RealField + Copy>(
        path: &[Vec2<T>],
        tol: T,
        closed: bool,
    ) -> Option<StraightPart<T>> {
        if path.len() < 3 || !tol.is_finite() || tol < T::zero() {
            return None;
        }
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

    /// Same run, and the same numbers bit for bit (NaN equal to NaN).
    fn same<T: RealField + Copy>(a: Option<StraightPart<T>>, b: Option<StraightPart<T>>) -> bool {
        #[allow(clippy::eq_op, reason = "x != x is the NaN test")]
        let eq = |x: T, y: T| x == y || (x != x && y != y);
        match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => {
                (a.start, a.count) == (b.start, b.count)
                    && [a.point, a.direction]
                        .iter()
                        .zip([b.point, b.direction].iter())
                        .all(|(u, v)| eq(u.x, v.x) && eq(u.y, v.y))
                    && eq(a.max_deviation, b.max_deviation)
                    && eq(a.length, b.length)
            }
            _ => false,
        }
    }

    /// A test path of one of several kinds, from per-sample random numbers `raw`.
    fn make_path(kind: u8, raw: &[(u8, f64, f64)], angle: f64, offset: f64) -> Vec<Vec2<f64>> {
        let n = raw.len();
        let (mut pos, mut heading) = (Vec2::new(0.0, 0.0), 0.0_f64);
        let mut out = Vec::with_capacity(n);
        for (k, &(b, r1, r2)) in raw.iter().enumerate() {
            let p = match kind {
                // Smooth curve with flats: the heading turns at one step in three.
                0 => {
                    if b % 3 == 0 {
                        heading += r1 * 0.3;
                    }
                    pos += Vec2::new(heading.cos(), heading.sin()) * 0.1;
                    pos
                }
                // Noisy line.
                1 => Vec2::new(k as f64 * 0.1, r1 * 1e-3 * f64::from(b) / 255.0),
                // Closed curve, slightly noisy.
                2 => {
                    let t = core::f64::consts::TAU * k as f64 / n as f64;
                    Vec2::new(2.0 * t.cos(), t.sin() + 0.2 * (3.0 * t).sin())
                        + Vec2::new(r1, r2) * 1e-4
                }
                // Small integer grid, many repeated samples and exact flats.
                3 => {
                    if b % 2 == 0 && k > 0 {
                        pos
                    } else {
                        pos = Vec2::new((r1 * 3.0).round(), (r2 * 3.0).round());
                        pos
                    }
                }
                // Axis-parallel walk: exact flats along x, some random steps.
                _ => {
                    pos += if b % 4 == 0 {
                        Vec2::new(r1, r2) * 0.1
                    } else {
                        Vec2::new(0.125, 0.0)
                    };
                    pos
                }
            };
            out.push(p);
        }
        let (s, c) = angle.sin_cos();
        for (p, &(b, _, _)) in out.iter_mut().zip(raw) {
            if angle != 0.0 {
                *p = Vec2::new(c * p.x - s * p.y, s * p.x + c * p.y);
            }
            *p += Vec2::new(offset, -0.5 * offset);
            match b {
                255 => p.x = f64::NAN,
                254 => p.y = f64::INFINITY,
                _ => {}
            }
        }
        out
    }

    fn tolerance(kind: u8, log: f64) -> f64 {
        match kind {
            0 => 0.0,
            1 => 1e300,
            2 => f64::MAX,
            _ => 10f64.powf(log),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// The fast scan finds exactly the run, line, deviation and length of the direct one.
        #[test]
        fn equals_the_direct_scan(
            kind in 0u8..5,
            raw in prop::collection::vec((any::<u8>(), -1.0f64..1.0, -1.0f64..1.0), 0..200),
            tol_kind in 0u8..7,
            log_tol in -9.0f64..0.5,
            closed in any::<bool>(),
            angle in prop_oneof![Just(0.0), -3.2f64..3.2],
            offset in prop_oneof![Just(0.0), Just(1e6), Just(-3e3)],
        ) {
            let path = make_path(kind, &raw, angle, offset);
            let tol = tolerance(tol_kind, log_tol);
            let fast = straight_part(&path, tol, closed);
            let direct = reference(&path, tol, closed);
            prop_assert!(same(fast, direct), "fast {fast:?}\ndirect {direct:?}");
            // And in single precision.
            let p32: Vec<Vec2<f32>> = path.iter().map(|p| p.cast::<f32>()).collect();
            let t32 = tol as f32;
            let fast = straight_part(&p32, t32, closed);
            let direct = reference(&p32, t32, closed);
            prop_assert!(same(fast, direct), "f32: fast {fast:?}\ndirect {direct:?}");
        }
    }

    #[test]
    fn equals_the_direct_scan_on_long_paths() {
        // Long enough for deep trees: a noisy closed curve and an open smooth one with flats.
        for (n, kind, tol, closed) in [
            (3000, 2, 0.05, true),
            (3000, 2, 1e-3, false),
            (4000, 0, 1e-4, false),
            (4000, 0, 0.0, true),
            (4000, 1, 4e-4, false),
            (4000, 4, 0.0, true),
        ] {
            let raw: Vec<(u8, f64, f64)> = (0..n)
                .map(|k: usize| {
                    let h = (k as f64 * 12.9898).sin() * 43758.5453;
                    let f = h - h.floor();
                    (
                        (f * 253.0) as u8,
                        2.0 * f - 1.0,
                        ((f * 7.0).fract() - 0.5) * 2.0,
                    )
                })
                .collect();
            let path = make_path(kind, &raw, 0.3, 1e6);
            let fast = straight_part(&path, tol, closed);
            let direct = reference(&path, tol, closed);
            assert!(fast.is_some_and(|s| s.count >= 3));
            assert!(
                same(fast, direct),
                "{kind}: fast {fast:?}\ndirect {direct:?}"
            );
        }
    }

    /// The path file named by `STRAIGHT_BENCH_PATH` (a first line `tol closed`, then one `x y`
    /// line per sample) for the two timing helpers below.
    fn bench_path() -> (Vec<Vec2<f64>>, f64, bool) {
        extern crate std;
        let file = std::env::var("STRAIGHT_BENCH_PATH").expect("STRAIGHT_BENCH_PATH");
        let text = std::fs::read_to_string(file).expect("readable path file");
        let mut lines = text.lines();
        let head: Vec<&str> = lines.next().expect("header").split_whitespace().collect();
        let tol: f64 = head[0].parse().expect("tol");
        let closed = head[1] == "1";
        let path = lines
            .map(|l| {
                let v: Vec<f64> = l
                    .split_whitespace()
                    .map(|x| x.parse().expect("number"))
                    .collect();
                Vec2::new(v[0], v[1])
            })
            .collect();
        (path, tol, closed)
    }

    /// Not a check of speed: `bench/straightness.py` runs it to time the direct scan against
    /// the fast one, in one process, on the path it writes to the file named by
    /// `STRAIGHT_BENCH_PATH` (a first line `tol closed`, then one `x y` line per sample).
    #[test]
    #[ignore = "run by bench/straightness.py"]
    fn direct_scan_timing() {
        extern crate std;
        use std::time::Instant;
        let (path, tol, closed) = bench_path();
        let t = Instant::now();
        let direct = reference(&path, tol, closed);
        let direct_s = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let fast = straight_part(&path, tol, closed);
        let fast_s = t.elapsed().as_secs_f64();
        std::println!(
            "n = {}: direct scan {direct_s:.3} s, fast {fast_s:.4} s, ratio {:.0}, run of {:?}",
            path.len(),
            direct_s / fast_s,
            fast.map(|s| s.count)
        );
        assert!(same(fast, direct), "fast {fast:?}\ndirect {direct:?}");
    }

    /// Not a check of speed: times the fast scan alone (best of 3) on the path file named by
    /// `STRAIGHT_BENCH_PATH` (as for `direct_scan_timing`), for paths too long for the direct one.
    #[test]
    #[ignore = "timing helper for bench/straightness.py"]
    fn fast_scan_timing() {
        extern crate std;
        use std::time::Instant;
        let (path, tol, closed) = bench_path();
        let mut best = f64::INFINITY;
        let mut part = None;
        for _ in 0..3 {
            let t = Instant::now();
            part = straight_part(&path, tol, closed);
            best = best.min(t.elapsed().as_secs_f64());
        }
        std::println!(
            "n = {}: fast {best:.4} s (best of 3), run of {:?}",
            path.len(),
            part.map(|s| (s.start, s.count))
        );
        assert!(part.is_some());
    }

    #[test]
    fn finds_the_flat_of_a_d_shape() {
        // A "D": 21 samples on y = 0 from x = 0 to 10, then a half circle back.
        let mut path = [Vec2::zeros(); 60];
        for (k, p) in path.iter_mut().enumerate() {
            *p = if k <= 20 {
                Vec2::new(k as f64 * 0.5, 0.0)
            } else {
                let t = core::f64::consts::PI * (k - 20) as f64 / 40.0;
                Vec2::new(5.0 + 5.0 * t.cos(), 5.0 * t.sin())
            };
        }
        let s = straight_part(&path, 1e-9, false).unwrap();
        assert_eq!((s.start, s.count), (0, 21));
        assert!((s.length - 10.0).abs() < 1e-12 && s.max_deviation < 1e-12);
        assert!((s.direction - Vec2::new(1.0, 0.0)).norm() < 1e-12);
        // Closed: the flat run is the same; a looser tolerance takes in more of the arc.
        let c = straight_part(&path, 1e-9, true).unwrap();
        assert_eq!(c.count, 21);
        let loose = straight_part(&path, 0.5, true).unwrap();
        assert!(loose.count > 21 && loose.max_deviation <= 0.5);
    }

    #[test]
    fn wraps_around_a_closed_path() {
        // A 2 × 1 rectangle sampled every 0.1 by arc length, starting mid-bottom: the longest
        // side (21 samples with its corners) is split between the array's end and start.
        let mut path = [Vec2::zeros(); 60];
        for (k, p) in path.iter_mut().enumerate() {
            let s = (k as f64 * 0.1 + 1.0) % 6.0; // arc length from the bottom-left corner
            *p = if s < 2.0 {
                Vec2::new(s, 0.0)
            } else if s < 3.0 {
                Vec2::new(2.0, s - 2.0)
            } else if s < 5.0 {
                Vec2::new(5.0 - s, 1.0)
            } else {
                Vec2::new(0.0, 6.0 - s)
            };
        }
        let open = straight_part(&path, 1e-9, false).unwrap();
        let closed = straight_part(&path, 1e-9, true).unwrap();
        assert_eq!(open.count, 21); // the top side, inside the array
        assert_eq!(closed.count, 21);
        assert!((closed.length - 2.0).abs() < 1e-9);
        // Break the top side: only the wrapped bottom side is left at full length.
        let mut broken = path;
        broken[30] = Vec2::new(f64::NAN, f64::NAN);
        assert!(straight_part(&broken, 1e-9, false).unwrap().count < 21);
        let wrapped = straight_part(&broken, 1e-9, true).unwrap();
        assert_eq!(wrapped.count, 21);
        assert!(wrapped.start + wrapped.count > 60 && wrapped.point.y.abs() < 1e-12);
    }
}
