//! One half (upper or lower) of the convex hull of a changing set of samples: insertions, an
//! undo of the last one, and support queries, each `O(log n)` — plus `O(log₆₄ n)` per vertex
//! an insertion removes or its undo restores.

use alloc::vec::Vec;

use nalgebra::RealField;

use crate::numeric::scalar::{cross, Vec2};

/// No slot.
pub(super) const NONE: u32 = u32::MAX;

/// Steps the support search walks along the chain from its last answer before it bisects
/// the slots instead.
const WALK: usize = 8;

/// A set of slots `0..n` as a tree of 64-bit words: a bit of a word above the bottom says
/// whether the word below it has any bit set. Adding, removing and finding the nearest member
/// before or after a slot take at most one word operation per level, and there are
/// `⌈log₆₄ n⌉ ≤ 6` levels for the `n < 2³²` slots used here.
struct Bits {
    /// Bottom level first; the top level is one word.
    levels: Vec<Vec<u64>>,
}

impl Bits {
    fn new(n: usize) -> Self {
        let mut levels = Vec::new();
        let mut len = n.max(1);
        loop {
            let words = len.div_ceil(64);
            levels.push(alloc::vec![0u64; words]);
            if words == 1 {
                break;
            }
            len = words;
        }
        Bits { levels }
    }

    fn has(&self, s: u32) -> bool {
        let s = s as usize;
        self.levels[0]
            .get(s / 64)
            .is_some_and(|w| w >> (s % 64) & 1 == 1)
    }

    fn insert(&mut self, s: u32) {
        let mut s = s as usize;
        for level in &mut self.levels {
            let Some(word) = level.get_mut(s / 64) else {
                return;
            };
            let was = *word;
            *word |= 1 << (s % 64);
            if was != 0 {
                return;
            }
            s /= 64;
        }
    }

    fn remove(&mut self, s: u32) {
        let mut s = s as usize;
        for level in &mut self.levels {
            let Some(word) = level.get_mut(s / 64) else {
                return;
            };
            *word &= !(1 << (s % 64));
            if *word != 0 {
                return;
            }
            s /= 64;
        }
    }

    /// The largest member below level `from`'s position `s` (a member word of that level),
    /// descending to the bottom: its last set bit at each level.
    fn down_last(&self, from: usize, mut s: usize) -> u32 {
        for level in self.levels[..from].iter().rev() {
            let word = level[s];
            s = s * 64 + 63 - word.leading_zeros() as usize;
        }
        s as u32
    }

    fn down_first(&self, from: usize, mut s: usize) -> u32 {
        for level in self.levels[..from].iter().rev() {
            let word = level[s];
            s = s * 64 + word.trailing_zeros() as usize;
        }
        s as u32
    }

    /// The largest member below `s`, or `NONE`.
    fn before(&self, s: u32) -> u32 {
        let mut s = s as usize;
        for (l, level) in self.levels.iter().enumerate() {
            let below = level[s / 64] & ((1u64 << (s % 64)) - 1);
            if below != 0 {
                return self.down_last(l, s / 64 * 64 + 63 - below.leading_zeros() as usize);
            }
            s /= 64;
        }
        NONE
    }

    /// The smallest member above `s`, or `NONE`.
    fn after(&self, s: u32) -> u32 {
        let mut s = s as usize;
        for (l, level) in self.levels.iter().enumerate() {
            let b = s % 64;
            let above = if b == 63 {
                0
            } else {
                level[s / 64] & (u64::MAX << (b + 1))
            };
            if above != 0 {
                return self.down_first(l, s / 64 * 64 + above.trailing_zeros() as usize);
            }
            s /= 64;
        }
        NONE
    }

    fn first(&self) -> u32 {
        let top = self.levels.len() - 1;
        if self.levels[top][0] == 0 {
            return NONE;
        }
        self.down_first(top + 1, 0)
    }

    fn last(&self) -> u32 {
        let top = self.levels.len() - 1;
        if self.levels[top][0] == 0 {
            return NONE;
        }
        self.down_last(top + 1, 0)
    }
}

/// An upper or lower hull chain of a set of samples, as the live slots of the samples' ranks
/// in `(x, y, index)` order (`pts[slot]` is the sample of that rank): a [`Bits`] set for
/// finding neighbours and searching, and `prev`/`next` links for walks along the chain.
pub(super) struct Chain {
    upper: bool,
    live: Bits,
    /// The last support vertex found for each kind of query (may since have left the chain).
    finger: [u32; 2],
}

impl Chain {
    /// An empty chain over `n` slots (`n < u32::MAX`).
    pub(super) fn new(n: usize, upper: bool) -> Self {
        Chain {
            upper,
            live: Bits::new(n),
            finger: [NONE; 2],
        }
    }

    /// Puts slot `s` into the chain between its live neighbours.
    fn link(&mut self, links: &mut [[u32; 2]], s: u32) {
        let (p, n) = (self.live.before(s), self.live.after(s));
        self.join(links, p, s, n);
    }

    /// Puts slot `s` into the chain between the live slots `p` and `n` (or the ends).
    fn join(&mut self, links: &mut [[u32; 2]], p: u32, s: u32, n: u32) {
        self.live.insert(s);
        links[s as usize][0] = p;
        links[s as usize][1] = n;
        if p != NONE {
            links[p as usize][1] = s;
        }
        if n != NONE {
            links[n as usize][0] = s;
        }
    }

    /// Takes slot `s` out of the chain.
    fn unlink(&mut self, links: &mut [[u32; 2]], s: u32) {
        self.live.remove(s);
        let [p, n] = links[s as usize];
        if p != NONE {
            links[p as usize][1] = n;
        }
        if n != NONE {
            links[n as usize][0] = p;
        }
    }

    /// Whether the chain turns strictly the hull's way at `b` between `a` and `c`.
    fn convex<T: RealField + Copy>(&self, pts: &[Vec2<T>], a: u32, b: u32, c: u32) -> bool {
        let a = pts[a as usize];
        let t = cross(pts[b as usize] - a, pts[c as usize] - a);
        if self.upper {
            t < T::zero()
        } else {
            t > T::zero()
        }
    }

    /// Adds the sample of slot `s` (or nothing for `NONE`) and records in `log` how to undo it:
    /// the vertices it removed, their number, then `s` if it became a vertex (else `NONE`).
    pub(super) fn insert<T: RealField + Copy>(
        &mut self,
        pts: &[Vec2<T>],
        links: &mut [[u32; 2]],
        s: u32,
        log: &mut Vec<u32>,
    ) {
        if s == NONE || self.live.has(s) {
            log.extend_from_slice(&[0, NONE]);
            return;
        }
        let (mut p, mut n) = (self.live.before(s), self.live.after(s));
        if p != NONE && n != NONE && !self.convex(pts, p, s, n) {
            // Inside the chain (or on it): nothing changes.
            log.extend_from_slice(&[0, NONE]);
            return;
        }
        let mut removed = 0u32;
        while p != NONE {
            let pp = links[p as usize][0];
            if pp == NONE || self.convex(pts, pp, p, s) {
                break;
            }
            self.unlink(links, p);
            log.push(p);
            removed += 1;
            p = pp;
        }
        while n != NONE {
            let nn = links[n as usize][1];
            if nn == NONE || self.convex(pts, s, n, nn) {
                break;
            }
            self.unlink(links, n);
            log.push(n);
            removed += 1;
            n = nn;
        }
        self.join(links, p, s, n);
        log.extend_from_slice(&[removed, s]);
    }

    /// Removes every vertex (`O(1)` word operations each).
    pub(super) fn clear(&mut self, links: &[[u32; 2]]) {
        let mut k = self.live.first();
        while k != NONE {
            self.live.remove(k);
            k = links[k as usize][1];
        }
    }

    /// Undoes the last [`Chain::insert`] recorded in `log`; returns the number of vertices
    /// it restored.
    pub(super) fn undo(&mut self, links: &mut [[u32; 2]], log: &mut Vec<u32>) -> u32 {
        let (Some(s), Some(removed)) = (log.pop(), log.pop()) else {
            return 0;
        };
        if s != NONE {
            self.unlink(links, s);
        }
        for _ in 0..removed {
            if let Some(r) = log.pop() {
                self.link(links, r);
            }
        }
        removed
    }

    /// The slot of the largest `u·pts[slot]` over the chain, or `NONE` if it is empty. `u`
    /// must point to the chain's side (`u.y > 0` for an upper chain, `< 0` for a lower one;
    /// along `x`, either chain's ends hold the extremes).
    ///
    /// Along the chain `u·(next − this)` is positive, then not (the chain turns one way), and
    /// the answer is the first vertex after which it is not. A walk of a few steps from the
    /// last answer to a query of the same `kind` (0 or 1) finds it when the direction has
    /// changed little; otherwise a bisection of the slots does, `O(log n)` steps of one
    /// [`Bits::before`] each.
    pub(super) fn support<T: RealField + Copy>(
        &mut self,
        pts: &[Vec2<T>],
        links: &[[u32; 2]],
        u: Vec2<T>,
        kind: usize,
    ) -> u32 {
        let kind = kind & 1;
        if u.y == T::zero() {
            return if u.x > T::zero() {
                self.live.last()
            } else {
                self.live.first()
            };
        }
        let rising = |a: u32, b: u32| u.dot(&(pts[b as usize] - pts[a as usize])) > T::zero();
        let mut k = self.finger[kind];
        if k != NONE && !self.live.has(k) {
            // The last answer has left the chain: start from a live neighbour.
            k = match self.live.before(k) {
                NONE => self.live.after(k),
                p => p,
            };
        }
        if k != NONE {
            for _ in 0..WALK {
                let [p, n] = links[k as usize];
                if n != NONE && rising(k, n) {
                    k = n;
                } else if p != NONE && !rising(p, k) {
                    k = p;
                } else {
                    self.finger[kind] = k;
                    return k;
                }
            }
        }
        // The answer is a live slot in lo..=hi.
        let (mut lo, mut hi) = (self.live.first(), self.live.last());
        if lo == NONE {
            return NONE;
        }
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            // The last live slot at or before mid (lo is live), and the next (hi is live).
            let k = if self.live.has(mid) {
                mid
            } else {
                self.live.before(mid)
            };
            let n = links[k as usize][1];
            if n != NONE && rising(k, n) {
                lo = n;
            } else {
                hi = k;
            }
        }
        self.finger[kind] = lo;
        lo
    }
}
