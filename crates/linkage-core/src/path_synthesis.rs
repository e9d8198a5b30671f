//! A four-bar's coupler curve as one smooth closed circuit, for path synthesis: points by a
//! circuit parameter, the tracker's check that the circuit is what a driven linkage traces, and
//! the true distance from target points to the curve.
//!
//! # The circuit parameter
//! A circuit is parametrised by `s` (period `2π`). A crank that turns fully sweeps
//! `θ = β + s` (`β` the ground direction `O → C`) on the declared assembly. A crank limited to
//! `[lo, hi]` (for two intervals, the first, as [`FourBar::circuit`]) sweeps
//! `θ = (lo + hi)/2 − (hi − lo)/2·cos s`: from `lo` to `hi` on the declared assembly
//! (`0 ≤ s ≤ π`) and back on the other one (`π < s < 2π`). At a limit the coupler and rocker are
//! collinear and the two assemblies meet, and since `θ_lim − θ ∝ s²` there while the coupler
//! point moves as `√(θ_lim − θ)`, the point is a smooth function of `s` through the limits: a
//! least-squares fit may move target points across them.

use alloc::vec::Vec;
use nalgebra::RealField;

use crate::error::Error;
use crate::fourbar::{Assembly, FourBar, InputRange};
use crate::scalar::{lit, to_f64, Vec2};
use crate::tracker::{Rates, Tracker};

/// Local minima of the polyline distance refined by [`CircuitPath::foot`].
pub const FOOT_STARTS: usize = 4;

/// A four-bar's circuit, parametrised as in the module.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircuitPath<T> {
    /// The linkage on its declared assembly.
    pub linkage: FourBar<T>,
    other: FourBar<T>,
    /// `Some((lo, hi))` for a limited crank, `None` for a full turn.
    pub limits: Option<(T, T)>,
    base: T,
}

impl<T: RealField + Copy> CircuitPath<T> {
    /// The circuit of `linkage`.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] (joint 3) when the linkage never assembles.
    pub fn new(linkage: FourBar<T>) -> Result<Self, Error> {
        let limits = match linkage.input_range() {
            InputRange::Never => {
                return Err(Error::CannotAssemble {
                    joint: FourBar::<T>::B,
                    gap: f64::NAN,
                })
            }
            InputRange::Full => None,
            InputRange::Between { lo, hi } => Some((lo, hi)),
            InputRange::TwoIntervals { first, .. } => Some(first),
        };
        let mut other = linkage;
        other.assembly = match linkage.assembly {
            Assembly::Open => Assembly::Crossed,
            Assembly::Crossed => Assembly::Open,
        };
        let d = linkage.c - linkage.o;
        Ok(CircuitPath {
            linkage,
            other,
            limits,
            base: d.y.atan2(d.x),
        })
    }

    /// Whether the crank turns fully.
    pub fn full_turn(&self) -> bool {
        self.limits.is_none()
    }

    /// Crank angle at circuit parameter `s`, and whether it is on the other assembly.
    pub fn theta(&self, s: T) -> (T, bool) {
        match self.limits {
            None => (self.base + s, false),
            Some((lo, hi)) => {
                let half = lit::<T>(0.5);
                let theta = (lo + hi) * half - (hi - lo) * half * s.cos();
                (theta, s.sin() < T::zero())
            }
        }
    }

    /// Coupler point at circuit parameter `s`; `None` where rounding at a limit leaves it
    /// unassembled.
    pub fn point(&self, s: T) -> Option<Vec2<T>> {
        let (theta, other) = self.theta(s);
        let fb = if other { &self.other } else { &self.linkage };
        fb.pose(theta).ok().map(|p| p.coupler_point)
    }

    /// Transmission angle's distance from a toggle, `min(μ, π − μ)`, at `s` (`None` where it
    /// does not assemble).
    pub fn transmission(&self, s: T) -> Option<T> {
        let (theta, other) = self.theta(s);
        let fb = if other { &self.other } else { &self.linkage };
        fb.transmission_angle(theta).map(|mu| mu.min(T::pi() - mu))
    }

    /// Sweeps the circuit with the [`Tracker`] (`n` samples at `s = 2πk/n`, passing to the other
    /// assembly after the upper limit as [`FourBar::circuit`] does) and checks that each
    /// tracked coupler point is [`CircuitPath::point`]: the circuit is one branch of the driven
    /// linkage, never switched at a flat position or lost.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] at a sample that does not assemble; [`Error::ToggleOnPath`]
    /// (its crank angle) where the tracked point leaves the circuit's (a branch switch);
    /// [`Error::BufferLength`] for `n < 4`.
    pub fn check(&self, n: usize) -> Result<(), Error> {
        if n < 4 {
            return Err(Error::BufferLength {
                what: "check samples",
                expected: 4,
                got: n,
            });
        }
        let m = self.linkage.mechanism();
        let mut tracker = Tracker::new(&m)?;
        let mut joints = [Vec2::zeros(); 5];
        let size = self.size();
        let tol = lit::<T>(1e-9) * size;
        let mut flipped = false;
        for k in 0..n {
            let s = T::two_pi() * lit::<T>(k as f64) / lit::<T>(n as f64);
            let (theta, other) = self.theta(s);
            if other && !flipped {
                let b = tracker.branch(FourBar::<T>::B);
                tracker.set_branch(FourBar::<T>::B, -b);
                flipped = true;
            }
            tracker.step(theta, None, &mut joints, Rates::none())?;
            let want = self.point(s).ok_or(Error::CannotAssemble {
                joint: FourBar::<T>::B,
                gap: 0.0,
            })?;
            if (joints[FourBar::<T>::P] - want).norm() > tol {
                return Err(Error::ToggleOnPath {
                    angle: to_f64(theta),
                });
            }
        }
        Ok(())
    }

    /// A length of the linkage's size (its largest length or pivot offset).
    pub fn size(&self) -> T {
        let f = &self.linkage;
        f.crank
            .max(f.coupler)
            .max(f.rocker)
            .max(f.ground())
            .max(f.along.abs())
            .max(f.left.abs())
    }

    /// `m` points of the circuit at `s = 2πk/m` (NaN where a sample does not assemble).
    pub fn polyline(&self, m: usize) -> Vec<Vec2<T>> {
        (0..m)
            .map(|k| {
                let s = T::two_pi() * lit::<T>(k as f64) / lit::<T>(m as f64);
                self.point(s).unwrap_or(Vec2::new(
                    crate::scalar::nan::<T>(),
                    crate::scalar::nan::<T>(),
                ))
            })
            .collect()
    }

    /// True distance from `target` to the circuit's curve and the circuit parameter of the
    /// nearest point: the vertices of `poly` (from [`CircuitPath::polyline`]) nearest `target`
    /// by vertex or segment distance are found among the local minima along the polyline, and
    /// a golden-section search of `|P(s) − target|` runs about each of the best
    /// [`FOOT_STARTS`] (where the curve crosses itself or passes close by itself the nearest
    /// vertex may lie on the wrong pass). `None` when `poly` has no finite point.
    pub fn foot(&self, target: Vec2<T>, poly: &[Vec2<T>]) -> Option<(T, T)> {
        let m = poly.len();
        let finite = |p: &Vec2<T>| p.x.is_finite() && p.y.is_finite();
        let big = T::max_value().unwrap_or(T::one());
        // Distance of each segment j → j+1 (the vertex's own where the next is not finite).
        let seg = |j: usize| -> T {
            let (p, q) = (&poly[j], &poly[(j + 1) % m]);
            if !finite(p) {
                return big;
            }
            if !finite(q) {
                return (p - target).norm();
            }
            let ab = q - p;
            let l2 = ab.norm_squared();
            let u = if l2 > T::zero() {
                ((target - p).dot(&ab) / l2).max(T::zero()).min(T::one())
            } else {
                T::zero()
            };
            (p + ab * u - target).norm()
        };
        let d: Vec<T> = (0..m).map(seg).collect();
        let mut starts: [(usize, T); FOOT_STARTS] = [(usize::MAX, big); FOOT_STARTS];
        for j in 0..m {
            let (prev, next) = (d[(j + m - 1) % m], d[(j + 1) % m]);
            if d[j] < big && d[j] <= prev && d[j] <= next {
                // Insert into the short sorted list of the best local minima.
                if let Some(at) = starts.iter().position(|&(_, b)| d[j] < b) {
                    starts[at..].rotate_right(1);
                    starts[at] = (j, d[j]);
                }
            }
        }
        if starts[0].0 == usize::MAX {
            return None;
        }
        let step = T::two_pi() / lit::<T>(m as f64);
        let mut best = (big, T::zero());
        for &(j, _) in starts.iter().filter(|s| s.0 != usize::MAX) {
            let centre = step * lit::<T>(j as f64);
            if finite(&poly[j]) {
                let dv = (poly[j] - target).norm();
                if dv < best.0 {
                    best = (dv, centre);
                }
            }
            let (dg, sg) = self.golden(target, centre - step, centre + step + step);
            if dg < best.0 {
                best = (dg, sg);
            }
        }
        Some(best)
    }

    /// Golden-section search of `|P(s) − target|` over `[a, b]`: `(distance, s)`.
    fn golden(&self, target: Vec2<T>, mut a: T, mut b: T) -> (T, T) {
        let dist = |s: T| {
            self.point(s)
                .map_or(T::max_value().unwrap_or(T::one()), |p| (p - target).norm())
        };
        let g = lit::<T>(0.618_033_988_749_894_8);
        let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
        let (mut f1, mut f2) = (dist(x1), dist(x2));
        for _ in 0..64 {
            if f1 < f2 {
                b = x2;
                (x2, f2) = (x1, f1);
                x1 = b - g * (b - a);
                f1 = dist(x1);
            } else {
                a = x1;
                (x1, f1) = (x2, f2);
                x2 = a + g * (b - a);
                f2 = dist(x2);
            }
        }
        if f1 < f2 {
            (f1, x1)
        } else {
            (f2, x2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limited_circuit_is_continuous_and_tracked() {
        // Triple rocker (limited both ways): the circuit passes both limits smoothly.
        let fb = FourBar::new(20.0, 10.0, 10.0, 10.0, (20.0, 5.0), Assembly::Open).unwrap();
        let c = CircuitPath::new(fb).unwrap();
        assert!(!c.full_turn());
        c.check(512).unwrap();
        let poly = c.polyline(2000);
        let worst = (0..2000)
            .map(|k| (poly[(k + 1) % 2000] - poly[k]).norm())
            .fold(0.0, f64::max);
        assert!(worst < 0.2, "{worst}");
        // The foot of a curve point is the point itself.
        let t = c.point(1.234).unwrap();
        let (d, s) = c.foot(t, &c.polyline(256)).unwrap();
        assert!(d < 1e-12, "{d}");
        assert!((c.point(s).unwrap() - t).norm() < 1e-12);
    }

    #[test]
    fn a_change_point_through_its_flat_position_is_refused() {
        // Parallelogram: flat positions at θ = 0 and π, where the tracker switches branch.
        let fb = FourBar::new(3.0, 1.0, 3.0, 1.0, (1.0, 1.0), Assembly::Open).unwrap();
        if let Ok(c) = CircuitPath::new(fb) {
            assert!(c.check(256).is_err());
        }
    }
}
