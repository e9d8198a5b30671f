//! The fast window check of [`super::straight_part`]: running moments for the window's line,
//! and its extremes across that line from a queue of two hulls (see there).

use alloc::vec::Vec;

use nalgebra::RealField;

use super::hull::{Chain, NONE};
use super::moments::Stats;
use super::samples::{Piece, Samples, LEAF};
use super::{fits_directly, scan};
use crate::numeric::scalar::{eps, lit, Vec2};

/// Updates of the running moments after which they are recomputed from the tree.
const REFRESH: usize = 128;

/// Windows of at most this many samples are scanned for their extremes directly (in `O(1)`),
/// leaving the queue as it is until a longer window needs it.
const SHORT: usize = 32;

/// The upper and lower hull chains of one side of the queue, and the log that undoes its
/// insertions (two records per sample, upper then lower).
struct Side {
    upper: Chain,
    lower: Chain,
    log: Vec<u32>,
}

impl Side {
    fn new(n: usize) -> Self {
        Side {
            upper: Chain::new(n, true),
            lower: Chain::new(n, false),
            log: Vec::new(),
        }
    }

    fn insert<T: RealField + Copy>(&mut self, pts: &[Vec2<T>], links: &mut Links, slot: u32) {
        self.upper.insert(pts, &mut links[0], slot, &mut self.log);
        self.lower.insert(pts, &mut links[1], slot, &mut self.log);
    }

    /// Undoes the last insertion; returns the number of hull vertices that restored.
    fn undo(&mut self, links: &mut Links) -> usize {
        let lower = self.lower.undo(&mut links[1], &mut self.log);
        let upper = self.upper.undo(&mut links[0], &mut self.log);
        lower as usize + upper as usize
    }

    fn clear(&mut self, links: &Links) {
        self.upper.clear(&links[0]);
        self.lower.clear(&links[1]);
        self.log.clear();
    }

    /// Largest `u·q` over the side's samples (`None` if it has none); `kind` as for
    /// [`Chain::support`].
    fn support<T: RealField + Copy>(
        &mut self,
        pts: &[Vec2<T>],
        links: &Links,
        u: Vec2<T>,
        kind: usize,
    ) -> Option<T> {
        let s = if u.y < T::zero() {
            self.lower.support(pts, &links[1], u, kind)
        } else {
            self.upper.support(pts, &links[0], u, kind)
        };
        pts.get(s as usize).map(|p| u.dot(p))
    }
}

/// The previous and next live slot of each slot in the upper (0) and lower (1) chains, shared
/// by the front and the back: they never hold the same sample.
type Links = [Vec<[u32; 2]>; 2];

/// The window check of [`super::straight_part`], with the refit budget.
struct Checker<'a, T> {
    path: &'a [Vec2<T>],
    tol: T,
    s: Samples<T>,
    pieces: Vec<Piece>,
    /// The tree nodes of the whole leaves `middle_of` of the last window that had some.
    middle: Vec<Piece>,
    middle_of: (usize, usize),
    budget: usize,
    /// Running moments of samples `ma..mb` (indices past the end wrapping), the number of
    /// single-sample updates since they were exact and the sum of the updates' sizes.
    ma: usize,
    mb: usize,
    moments: Stats<T>,
    updates: usize,
    drift: T,
    /// The queue: `front` holds samples `a..m` (inserted from `m − 1` down, so undoing its
    /// last insertion drops sample `a`), `back` holds `m..b` (undoing drops `b − 1`).
    front: Side,
    back: Side,
    links: Links,
    a: usize,
    m: usize,
    b: usize,
    counts: Counts,
}

/// What a scan did, for the cost argument of [`super::straight_part`] (read by tests).
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(
    not(test),
    allow(dead_code, reason = "the counters are read by tests only")
)]
pub(super) struct Counts {
    /// Window checks, those that shrank the window (`S` of `straight_part`), and those
    /// decided by a direct refit.
    pub(super) checks: usize,
    pub(super) shrinks: usize,
    pub(super) refits: usize,
    /// Refills of the queue and the samples they inserted.
    pub(super) refills: usize,
    pub(super) refilled: usize,
    /// Samples dropped from the queue's end as the window shrank, and the hull vertices
    /// that restored.
    pub(super) shrunk: usize,
    pub(super) restored: usize,
}

impl<T: RealField + Copy> Checker<'_, T> {
    fn slot(&self, k: usize) -> u32 {
        self.s.rank[k % self.path.len()]
    }

    fn push_front(&mut self) {
        self.a -= 1;
        let slot = self.slot(self.a);
        self.front.insert(&self.s.by_rank, &mut self.links, slot);
    }

    fn pop_front(&mut self) {
        self.front.undo(&mut self.links);
        self.a += 1;
    }

    fn push_back(&mut self) {
        let slot = self.slot(self.b);
        self.back.insert(&self.s.by_rank, &mut self.links, slot);
        self.b += 1;
    }

    fn pop_back(&mut self) {
        self.counts.shrunk += 1;
        self.counts.restored += self.back.undo(&mut self.links);
        self.b -= 1;
    }

    /// Empties the queue and refills it with samples `i..e`: the last eighth in the back, the
    /// rest in the front (so that the window can shrink at its end by an eighth before the
    /// queue must be refilled again).
    fn rebuild(&mut self, i: usize, e: usize) {
        self.counts.refills += 1;
        self.counts.refilled += e - i;
        self.front.clear(&self.links);
        self.back.clear(&self.links);
        let m = e - (e - i) / 8;
        (self.a, self.m, self.b) = (m, m, m);
        while self.a > i {
            self.push_front();
        }
        while self.b < e {
            self.push_back();
        }
    }

    /// Moves the queue to hold samples `i..j` or `i..j − 1` (then sample `j − 1` is taken
    /// separately), `i + 2 ≤ j`. The front drops its samples before `i` first, so that the
    /// queue never holds more than the window: no sample twice on a closed path, and the
    /// front and back never share a slot of the chains' links.
    fn sync(&mut self, i: usize, j: usize) {
        if i < self.a || i >= self.m || i >= self.b || j < self.m {
            // A window left of the last one, past its front (used up) or past it, or ending
            // inside the front (which drops samples at its start only): refill.
            self.rebuild(i, j);
            return;
        }
        while self.a < i {
            self.pop_front();
        }
        while self.b > j {
            self.pop_back();
        }
        while self.b + 1 < j {
            self.push_back();
        }
    }

    /// Moves the running moments to samples `i..j`: one sample at a time when that is
    /// short and accurate, from the tree's nodes (`self.pieces`) otherwise.
    fn move_to(&mut self, i: usize, j: usize) {
        let n = self.path.len();
        let steps = self.ma.abs_diff(i) + self.mb.abs_diff(j);
        let q = |k: usize| self.s.q[k % n];
        if self.updates + steps <= REFRESH && self.ma < j && i < self.mb {
            while self.mb < j {
                self.drift += self.moments.add(q(self.mb));
                self.mb += 1;
            }
            while self.ma > i {
                self.ma -= 1;
                self.drift += self.moments.add(q(self.ma));
            }
            while self.mb > j {
                self.mb -= 1;
                self.drift += self.moments.remove(q(self.mb));
            }
            while self.ma < i {
                self.drift += self.moments.remove(q(self.ma));
                self.ma += 1;
            }
            self.updates += steps;
            if self.drift <= self.moments.sxx + self.moments.syy {
                return;
            }
        }
        self.window_pieces(i, j);
        let mut st = Stats::empty();
        for &p in &self.pieces {
            st = st.merge(match p {
                Piece::Node(l, k) => self.s.levels[l][k],
                Piece::Span(a, b) => Stats::of_span(&self.s.q, self.path, a, b),
            });
        }
        (self.ma, self.mb, self.moments, self.updates, self.drift) = (i, j, st, 0, T::zero());
    }

    /// Splits window `i..j` (indices past the end wrapping) into `self.pieces`: the tree
    /// nodes between its first and last whole leaves are kept from the last window with
    /// the same ones (they change once in `LEAF` moves of the scan), the rest are spans.
    fn window_pieces(&mut self, i: usize, j: usize) {
        let n = self.path.len();
        self.pieces.clear();
        let (a, b) = (i.next_multiple_of(LEAF), j / LEAF * LEAF);
        if j <= n && a < b {
            // What `Samples::pieces(i, j)` gives: the span up to the first leaf boundary,
            // the nodes of `a..b` (sized by `b − s`, as by `j − s`), the span after `b`.
            if self.middle_of != (a, b) {
                self.middle.clear();
                self.s.pieces(a, b, &mut self.middle);
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
        self.s.pieces(i, j.min(n), &mut self.pieces);
        if j > n {
            self.s.pieces(0, j - n, &mut self.pieces);
        }
    }

    /// Whether samples `i..j` (indices past the end wrapping) are all finite once
    /// centred, and whether they all have the same original `y`.
    fn complete_and_level(&self, i: usize, j: usize) -> (bool, bool) {
        let (n, s) = (self.path.len(), &self.s);
        let bad = |a: usize, b: usize| s.bad[b] != s.bad[a];
        if j <= n {
            (!bad(i, j), s.level_end[i] as usize >= j)
        } else {
            let complete = !bad(i, n) && !bad(0, j - n);
            let level = s.level_end[i] as usize == n
                && s.level_end[0] as usize >= j - n
                && self.path[0].y == self.path[i].y;
            (complete, level)
        }
    }

    fn fits(&mut self, i: usize, j: usize) -> bool {
        self.counts.checks += 1;
        let (complete, level) = self.complete_and_level(i, j);
        if complete && level {
            // Same y throughout: the direct refit finds the x axis and deviation 0 exactly.
            return true;
        }
        if complete {
            self.move_to(i, j);
            if j - i > SHORT {
                self.sync(i, j);
            }
            let st = self.moments;
            let (v, gap) = axis(&st);
            // Σ|q − mean|² bounds every |q − mean|², up to the running moments' drift.
            let r = (lit::<T>(2.0) * (st.sxx + st.syy) + self.drift).sqrt();
            let (slope, floor) = self.error(gap);
            // A deviation beyond this is too much whatever the rest of the window holds.
            let hopeless = self.tol + slope * r + floor;
            let dev = self.spread(v, i, j, 0, Some(hopeless));
            // First with a cheap bound on the window's radius, then with a tight one.
            for tight in [false, true] {
                let r = if tight { self.radius(dev, v, i, j) } else { r };
                let err = slope * r + floor;
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
        self.counts.refits += 1;
        fits_directly(self.path, self.tol, i, j)
    }

    /// Largest `|u·(q − mean)|` over window `i..j` — the queue and, if it stops short of it,
    /// the window's last sample; the samples themselves for a short window — with `kind` 0
    /// for `u` across the line, 1 along it; or, as soon as one exceeds `stop`, that one.
    fn spread(&mut self, u: Vec2<T>, i: usize, j: usize, kind: usize, stop: Option<T>) -> T {
        let c = u.dot(&self.moments.mean);
        let far = |top: T, bottom: T| {
            if top - c > c - bottom {
                top - c
            } else {
                c - bottom
            }
        };
        let (mut top, mut bottom) = (c, c);
        if j - i <= SHORT {
            let n = self.path.len();
            for k in i..j {
                let d = u.dot(&self.s.q[k % n]);
                top = top.max(d);
                bottom = bottom.min(d);
            }
            return far(top, bottom);
        }
        if self.b < j {
            let d = u.dot(&self.s.q[(j - 1) % self.path.len()]);
            (top, bottom) = (d, d);
        }
        let (pts, links) = (&self.s.by_rank, &self.links);
        for side in [&mut self.back, &mut self.front] {
            if let Some(d) = side.support(pts, links, u, kind) {
                top = top.max(d);
            }
            if let Some(d) = side.support(pts, links, -u, kind) {
                bottom = bottom.min(-d);
            }
            if stop.is_some_and(|s| far(top, bottom) > s) {
                break;
            }
        }
        far(top, bottom)
    }

    /// The window's radius about its centroid, up to rounding (which the error bound's terms
    /// in the path's extent cover), from its spreads across and along its line `v`.
    fn radius(&mut self, dev: T, v: Vec2<T>, i: usize, j: usize) -> T {
        let along = self.spread(Vec2::new(v.y, -v.x), i, j, 1, None);
        (dev * dev + along * along).sqrt() + eps::<T>() * lit(64.0) * self.s.extent
    }

    /// Bound on the difference between the fast deviation and a direct refit's, for a
    /// window of radius `r`, as `slope · r + floor` (see `straight_part`); `gap` as from
    /// [`Checker::deviation`].
    fn error(&self, gap: T) -> (T, T) {
        let st = self.moments;
        let (two, four): (T, T) = (lit(2.0), lit(4.0));
        let e: T = eps::<T>() * lit(8.0);
        // Rounding in sums of w terms: statistically √w ε (the worst case, w ε, is only
        // reached by adversarial orderings; see `straight_part`).
        let w4 = st.w.sqrt() + four;
        let total = st.sxx + st.syy;
        let rc = self.s.extent;
        let moments = w4 * total + four * (rc * (st.w * total).sqrt() + self.drift);
        // At most a right angle's worth (also when the gap is 0 or the bound NaN).
        let dphi = e * moments / gap;
        let dphi = if dphi < two { dphi } else { two };
        (dphi + e * w4, e * lit::<T>(8.0) * rc)
    }
}

/// The unit normal `v` of the least-squares line of samples with moments `st`, and the gap
/// `√((Sxx − Syy)² + 4 Sxy²)` between the eigenvalues of their scatter.
fn axis<T: RealField + Copy>(st: &Stats<T>) -> (Vec2<T>, T) {
    let two: T = lit(2.0);
    // The principal axis at half the angle of (Sxx − Syy, 2 Sxy), without trigonometry.
    let (c2, s2) = (st.sxx - st.syy, two * st.sxy);
    let gap = (c2 * c2 + s2 * s2).sqrt();
    let v = if gap > T::zero() && gap.is_finite() {
        let inv = T::one() / gap;
        let (c2, s2) = (c2 * inv, s2 * inv);
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
    (v, gap)
}

/// The longest run of [`super::straight_part`], or `None`.
pub(super) fn longest_run<T: RealField + Copy>(
    path: &[Vec2<T>],
    tol: T,
    closed: bool,
) -> Option<(usize, usize)> {
    longest_run_counted(path, tol, closed).0
}

/// [`longest_run`] and what it did (the counts are zero past the slots' range).
pub(super) fn longest_run_counted<T: RealField + Copy>(
    path: &[Vec2<T>],
    tol: T,
    closed: bool,
) -> (Option<(usize, usize)>, Counts) {
    let n = path.len();
    if n >= NONE as usize {
        // Beyond the slots' indices (some 68 GB of f64 samples): direct refits.
        let run = scan(path, closed, |i, j| fits_directly(path, tol, i, j));
        return (run, Counts::default());
    }
    let mut checker = Checker {
        path,
        tol,
        s: Samples::new(path),
        pieces: Vec::new(),
        middle: Vec::new(),
        middle_of: (0, 0),
        budget: n.saturating_mul(64),
        ma: 0,
        mb: 0,
        moments: Stats::empty(),
        updates: 0,
        drift: T::zero(),
        front: Side::new(n),
        back: Side::new(n),
        // Read only for live slots, which are written first.
        links: [alloc::vec![[0; 2]; n], alloc::vec![[0; 2]; n]],
        a: 0,
        m: 0,
        b: 0,
        counts: Counts::default(),
    };
    let mut last = (usize::MAX, 0);
    let run = scan(path, closed, |i, j| {
        if (i, j + 1) == last {
            checker.counts.shrinks += 1;
        }
        last = (i, j);
        checker.fits(i, j)
    });
    (run, checker.counts)
}
