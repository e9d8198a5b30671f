//! Moments and bounding boxes of sets of centred samples, exact-merged.

use nalgebra::RealField;

use crate::numeric::scalar::{lit, Vec2};

/// Moments and bounds of a set of samples, in centred coordinates.
#[derive(Clone, Copy)]
pub(super) struct Stats<T> {
    /// Number of samples (as a count and as `T`).
    pub(super) count: usize,
    pub(super) w: T,
    pub(super) mean: Vec2<T>,
    /// Second central moments.
    pub(super) sxx: T,
    pub(super) sxy: T,
    pub(super) syy: T,
    /// Bounding box (centred).
    pub(super) lo: Vec2<T>,
    pub(super) hi: Vec2<T>,
    /// Smallest and largest `y` of the original samples, uncentred.
    pub(super) ylo: T,
    pub(super) yhi: T,
}

impl<T: RealField + Copy> Stats<T> {
    pub(super) fn empty() -> Self {
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
    pub(super) fn of_span(q: &[Vec2<T>], path: &[Vec2<T>], a: usize, b: usize) -> Self {
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
    pub(super) fn add(&mut self, p: Vec2<T>) -> T {
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
    pub(super) fn remove(&mut self, p: Vec2<T>) -> T {
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
    pub(super) fn merge(self, o: Self) -> Self {
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
