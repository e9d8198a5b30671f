//! A path's samples as the fast window check reads them: centred, ranked in `(x, y)` order,
//! and summed in a segment tree of moments.

use alloc::vec::Vec;
use core::cmp::Ordering;

use nalgebra::RealField;

use super::hull::NONE;
use super::moments::Stats;
use crate::numeric::scalar::{lit, Vec2};

/// Samples per leaf of the tree of moments (a window's partial leaves are summed directly).
pub(super) const LEAF: usize = 16;

/// A piece of a window: a node of the tree of moments (level, index) or a short span.
#[derive(Clone, Copy)]
pub(super) enum Piece {
    Node(usize, usize),
    Span(usize, usize),
}

pub(super) fn finite<T: RealField + Copy>(p: Vec2<T>) -> bool {
    p.x.is_finite() && p.y.is_finite()
}

/// The centred samples of a path and what the window check needs to know of them.
pub(super) struct Samples<T> {
    /// The samples less the middle of their bounding box.
    pub(super) q: Vec<Vec2<T>>,
    /// Rank of each sample in `(x, y, index)` order (`NONE` for a non-finite one), and the
    /// centred sample of each rank.
    pub(super) rank: Vec<u32>,
    pub(super) by_rank: Vec<Vec2<T>>,
    /// Moments of the finite samples of each node, level by level (leaves of [`LEAF`]).
    pub(super) levels: Vec<Vec<Stats<T>>>,
    /// Number of non-finite centred samples before each index (`n + 1` entries).
    pub(super) bad: Vec<u32>,
    /// For each sample, the end of the run of samples with its original `y`.
    pub(super) level_end: Vec<u32>,
    /// Largest distance of a finite centred sample from the centre.
    pub(super) extent: T,
}

impl<T: RealField + Copy> Samples<T> {
    /// `path` must hold fewer than `u32::MAX` samples.
    pub(super) fn new(path: &[Vec2<T>]) -> Self {
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
        let n = q.len();
        let mut bad = Vec::with_capacity(n + 1);
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
        let mut level_end = alloc::vec![0u32; n];
        let mut end = n;
        for k in (0..n).rev() {
            if k + 1 < n && path[k + 1].y != path[k].y {
                end = k + 1;
            }
            level_end[k] = end as u32;
        }
        let order = sorted(&q, path);
        let mut rank = alloc::vec![NONE; n];
        let by_rank = order
            .iter()
            .enumerate()
            .map(|(r, &k)| {
                rank[k as usize] = r as u32;
                q[k as usize]
            })
            .collect();
        let levels = moments_tree(&q, path);
        Samples {
            q,
            rank,
            by_rank,
            levels,
            bad,
            level_end,
            extent,
        }
    }

    /// Splits samples `a..b` into the largest aligned tree nodes and short spans.
    pub(super) fn pieces(&self, a: usize, b: usize, out: &mut Vec<Piece>) {
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

/// The indices of the finite samples (of `q` and `path`) in `(x, y, index)` order of `q`: a
/// radix sort on the leading 32 bits of `x` as an `f64` (an order-keeping key: sign, exponent
/// and 20 bits of mantissa), then each run of equal keys sorted by comparison.
fn sorted<T: RealField + Copy>(q: &[Vec2<T>], path: &[Vec2<T>]) -> Vec<u32> {
    // Order-preserving bits of x (−0 counted as +0).
    let key = |x: T| {
        let b = (x + T::zero()).to_subset().unwrap_or(0.0f64).to_bits();
        let b = if b >> 63 == 1 { !b } else { b | 1 << 63 };
        (b >> 32) as u32
    };
    let mut items: Vec<(u32, u32)> = (0..q.len())
        .filter(|&k| finite(q[k]) && finite(path[k]))
        .map(|k| (key(q[k].x), k as u32))
        .collect();
    let mut spare = alloc::vec![(0u32, 0u32); items.len()];
    for shift in (0..32).step_by(8) {
        let mut count = [0usize; 257];
        for &(k, _) in &items {
            count[((k >> shift) & 255) as usize + 1] += 1;
        }
        if count.contains(&items.len()) {
            continue; // one digit throughout: nothing to move
        }
        for d in 0..256 {
            count[d + 1] += count[d];
        }
        for &item in &items {
            let d = ((item.0 >> shift) & 255) as usize;
            spare[count[d]] = item;
            count[d] += 1;
        }
        core::mem::swap(&mut items, &mut spare);
    }
    // Equal keys: by x, y, index.
    let exact = |a: &(u32, u32), b: &(u32, u32)| {
        let (p, r) = (q[a.1 as usize], q[b.1 as usize]);
        p.x.partial_cmp(&r.x)
            .unwrap_or(Ordering::Equal)
            .then(p.y.partial_cmp(&r.y).unwrap_or(Ordering::Equal))
            .then(a.1.cmp(&b.1))
    };
    let mut s = 0;
    while s < items.len() {
        let mut e = s + 1;
        while e < items.len() && items[e].0 == items[s].0 {
            e += 1;
        }
        if e - s > 1 {
            items[s..e].sort_unstable_by(exact);
        }
        s = e;
    }
    items.into_iter().map(|(_, k)| k).collect()
}

/// The tree of moments of the finite samples, built bottom-up: leaves of [`LEAF`] samples
/// (a leaf with a non-finite sample gets the moments of its finite ones; no window holds it
/// whole), then pairs merged.
fn moments_tree<T: RealField + Copy>(q: &[Vec2<T>], path: &[Vec2<T>]) -> Vec<Vec<Stats<T>>> {
    let n = q.len();
    let leaves = (0..n)
        .step_by(LEAF)
        .map(|s| {
            let e = (s + LEAF).min(n);
            let ok = |k: usize| finite(q[k]) && finite(path[k]);
            if (s..e).all(ok) {
                Stats::of_span(q, path, s, e)
            } else {
                (s..e).filter(|&k| ok(k)).fold(Stats::empty(), |st, k| {
                    st.merge(Stats::of_span(q, path, k, k + 1))
                })
            }
        })
        .collect();
    let mut levels: Vec<Vec<Stats<T>>> = alloc::vec![leaves];
    while let Some(below) = levels.last().filter(|l| l.len() > 1) {
        let up = below
            .chunks(2)
            .map(|pair| pair.iter().fold(Stats::empty(), |st, c| st.merge(*c)))
            .collect();
        levels.push(up);
    }
    levels
}
