//! The window check before the queue: `O(log² n)` on a segment tree of hulls (test-only, for
//! timing comparisons; see `tests::direct_scan_timing`).

use alloc::vec::Vec;
use core::cmp::Ordering;

use nalgebra::RealField;

use super::moments::Stats;
use super::{fits_directly, scan};
use crate::numeric::scalar::{cross, eps, lit, Vec2};

/// Samples per leaf of the segment tree (a window's partial leaves are scanned directly).
const LEAF: usize = 16;

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
                    let bound =
                        d - du.dot(&(q - c.centre)) + (du.x.abs() + du.y.abs()) * c.radius + slack;
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
