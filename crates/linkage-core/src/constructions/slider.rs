//! The RRP slider dyad: a joint on a line, at a given distance from a known joint; the line's
//! direction, fixed or carried by a link.

use nalgebra::RealField;

use crate::constructions::dyad::DyadFailure;
use crate::numeric::scalar::{cross, eps, lit, perp, Vec2};

/// Which of the two intersections of a circle and a line.
///
/// ```
/// use linkage_core::{Error, Reach, SliderDyad, Vec2};
/// // Pivot (0, 3), link 5, the x axis as the line: the joint 4 ahead of the foot, or 4 behind.
/// let s = SliderDyad { r: 5.0_f64 };
/// let pose = s.solve(Vec2::new(0.0, 3.0), Vec2::zeros(), Vec2::new(1.0, 0.0), 0.0).unwrap();
/// assert_eq!(pose.point(Reach::Ahead), Vec2::new(4.0, 0.0));
/// assert_eq!(pose.point(Reach::Behind), Vec2::new(-4.0, 0.0));
/// assert_eq!(Reach::Behind.sign::<f64>(), -1.0);
/// // Named "ahead" and "behind".
/// assert_eq!("behind".parse::<Reach>(), Ok(Reach::Behind));
/// assert_eq!(Reach::Ahead.name(), "ahead");
/// assert_eq!(
///     "back".parse::<Reach>(),
///     Err(Error::InvalidChoice { what: "reach", choices: "'ahead' or 'behind'" })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Reach {
    /// Ahead of the foot of the perpendicular, along the line's direction.
    Ahead,
    /// Behind the foot of the perpendicular.
    Behind,
}

impl Reach {
    /// `+1` for [`Reach::Ahead`], `-1` for [`Reach::Behind`].
    #[inline]
    pub fn sign<T: RealField>(self) -> T {
        match self {
            Reach::Ahead => T::one(),
            Reach::Behind => -T::one(),
        }
    }
}

crate::choice::choice_names!(Reach, "reach", Ahead => "ahead", Behind => "behind");

/// Direction of a slider's line.
///
/// ```
/// use linkage_core::{Construction, Error, LineDirection, Mechanism, Reach, Vec2};
/// // Slider-crank: crank 2 about O, rod 5, the slider on the x axis through O.
/// let mut m = Mechanism::<f64, 4>::new();
/// let o = m.fixed(Vec2::zeros()).unwrap();
/// let a = m.crank(o, 2.0, 0.0).unwrap();
/// let b = m.slider(a, 5.0, o, LineDirection::Fixed(Vec2::new(3.0, 0.0)), Reach::Ahead).unwrap();
/// // A fixed direction is stored as a unit vector.
/// let Construction::Slider { direction, .. } = m.constructions()[b] else { unreachable!() };
/// assert_eq!(direction, LineDirection::Fixed(Vec2::new(1.0, 0.0)));
/// let mut j = [Vec2::zeros(); 3];
/// m.pose(core::f64::consts::FRAC_PI_2, &mut j).unwrap();
/// assert!((j[b] - Vec2::new(21.0_f64.sqrt(), 0.0)).norm() < 1e-12);
/// // A zero direction names no line.
/// assert_eq!(
///     m.slider(a, 5.0, o, LineDirection::Fixed(Vec2::zeros()), Reach::Ahead),
///     Err(Error::InvalidLength { what: "slider direction", value: 0.0 })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineDirection<T> {
    /// A fixed direction (stored as a unit vector).
    Fixed(Vec2<T>),
    /// The direction of the link `from → to`, turned counter-clockwise by `angle`: the line is
    /// carried by that link.
    Link {
        /// First joint of the carrying link.
        from: usize,
        /// Second joint of the carrying link.
        to: usize,
        /// Angle from `from → to` to the line direction (radians).
        angle: T,
    },
}

impl<T: RealField + Copy> LineDirection<T> {
    /// The line's direction at the joint positions `pos`.
    ///
    /// A [`LineDirection::Fixed`] direction is returned as it is: a [`Mechanism`](crate::Mechanism) stores it as a
    /// unit vector ([`Mechanism::push`](crate::Mechanism::push)), whatever `pos`. A [`LineDirection::Link`] direction is
    /// the unit vector `ê = (pos[to] − pos[from]) / |pos[to] − pos[from]|` turned
    /// counter-clockwise by `angle`: `(c·ê.x − s·ê.y, s·ê.x + c·ê.y)` with `(s, c)` the sine and
    /// cosine of `angle`.
    ///
    /// `None` when a carried direction is undetermined: the link's two joints coincide, or its
    /// length is not finite (a joint of it is NaN, as in a sample that did not assemble, or
    /// infinite).
    ///
    /// ```
    /// use linkage_core::{LineDirection, Vec2};
    /// // The link 0 → 1 points along +y; turned by −90° the line points along +x.
    /// let pos = [Vec2::new(1.0_f64, 1.0), Vec2::new(1.0, 3.0)];
    /// let carried = LineDirection::Link { from: 0, to: 1, angle: -core::f64::consts::FRAC_PI_2 };
    /// assert!((carried.at(&pos).unwrap() - Vec2::new(1.0, 0.0)).norm() < 1e-15);
    /// // Coincident or NaN joints carry no direction; a fixed one needs no joints.
    /// assert_eq!(carried.at(&[pos[0], pos[0]]), None);
    /// assert_eq!(carried.at(&[pos[0], Vec2::new(f64::NAN, 0.0)]), None);
    /// let fixed = LineDirection::Fixed(Vec2::new(0.0_f64, 1.0));
    /// assert_eq!(fixed.at(&[]), Some(Vec2::new(0.0, 1.0)));
    /// ```
    ///
    /// # Panics
    /// If `pos` does not hold the joints `from` and `to` of a [`LineDirection::Link`] (a
    /// mechanism's constructions refer only to joints placed before them, so `pos` of a
    /// mechanism's joints always does).
    #[inline]
    pub fn at(self, pos: &[Vec2<T>]) -> Option<Vec2<T>> {
        match self {
            LineDirection::Fixed(u) => Some(u),
            LineDirection::Link { from, to, angle } => {
                let d = pos[to] - pos[from];
                let n = crate::numeric::scalar::length(d);
                if n == T::zero() || !n.is_finite() {
                    return None;
                }
                let (s, c) = angle.sin_cos();
                let e = d / n;
                Some(Vec2::new(c * e.x - s * e.y, s * e.x + c * e.y))
            }
        }
    }
}

/// A solved slider dyad: the candidates are `foot ± offset`.
///
/// ```
/// use linkage_core::{DyadFailure, SliderDyad, Vec2};
/// let s = SliderDyad { r: 5.0_f64 };
/// let x_axis = Vec2::new(1.0, 0.0);
/// // Half-chord 4 of a link of 5: margin 0.8.
/// let pose = s.solve(Vec2::new(0.0, 3.0), Vec2::zeros(), x_axis, 0.0).unwrap();
/// assert_eq!(pose.margin, 0.8);
/// // The link perpendicular to the line: one joint, margin 0 (a toggle).
/// let at = s.solve(Vec2::new(0.0, 5.0), Vec2::zeros(), x_axis, 0.0).unwrap();
/// assert_eq!((at.offset.norm(), at.margin), (0.0, 0.0));
/// // The pivot 6 from the line: it passes outside the circle by 1.
/// let far = s.solve(Vec2::new(0.0, 6.0), Vec2::zeros(), x_axis, 0.0);
/// assert_eq!(far, Err(DyadFailure::Gap(1.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderPose<T: RealField + Copy> {
    /// Foot of the perpendicular from the pivot onto the line.
    pub foot: Vec2<T>,
    /// From the foot to the [`Reach::Ahead`] candidate (half the chord, along the line).
    pub offset: Vec2<T>,
    /// Assembly margin: half-chord / r, the sine of the angle between the link and the normal to
    /// the line. 0 when the link is perpendicular to the line (toggle), 1 when along it.
    pub margin: T,
}

impl<T: RealField + Copy> SliderPose<T> {
    /// The joint at the given reach.
    #[inline]
    pub fn point(&self, reach: Reach) -> Vec2<T> {
        match reach {
            Reach::Ahead => self.foot + self.offset,
            Reach::Behind => self.foot - self.offset,
        }
    }
}

/// An RRP dyad: a joint at distance `r` from a pivot `a`, sliding on the line through `q` with
/// unit direction `u`.
///
/// ```
/// use linkage_core::{SliderDyad, Reach, Vec2};
/// // Slider-crank: crank pin at (0, 3), connecting rod 5, slider on the x axis.
/// let s = SliderDyad { r: 5.0_f64 };
/// let pose = s.solve(Vec2::new(0.0, 3.0), Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 0.0).unwrap();
/// assert!((pose.point(Reach::Ahead) - Vec2::new(4.0, 0.0)).norm() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderDyad<T> {
    /// Length of the link from the pivot to the sliding joint.
    pub r: T,
}

impl<T: RealField + Copy> SliderDyad<T> {
    /// Solves the joint on the line `q + s·u` (`u` a unit vector) at distance `r` from `a`.
    ///
    /// With `e` the distance of `a` from the line, the half chord is `√((r − e)(r + e))`, formed
    /// without the cancellation of `√(r² − e²)`. `slack` widens the rounding tolerance as in
    /// [`crate::Dyad::solve`].
    ///
    /// # Errors
    /// [`DyadFailure::Gap`] (`e − r`) when the line passes outside the circle.
    pub fn solve(
        &self,
        a: Vec2<T>,
        q: Vec2<T>,
        u: Vec2<T>,
        slack: T,
    ) -> Result<SliderPose<T>, DyadFailure<T>> {
        let r = self.r;
        let w = q - a;
        let e = cross(u, w).abs();
        let tol = eps::<T>() * lit::<T>(8.0) * (r + e + a.amax() + q.amax()) + slack;
        let half = if e > r {
            if e - r > tol {
                return Err(DyadFailure::Gap(e - r));
            }
            T::zero()
        } else {
            // In units of a power of two near r (exact; 1 for ordinary sizes), so the product
            // neither overflows nor underflows at any linkage scale.
            let sc = crate::numeric::pow2::pow2_scale(r);
            (((r - e) / sc) * ((r + e) / sc)).sqrt() * sc
        };
        let foot = q - u * u.dot(&w);
        Ok(SliderPose {
            foot,
            offset: u * half,
            margin: half / r,
        })
    }

    /// Velocity of the joint `p = q + s·u`.
    ///
    /// `u` turns at `omega_u` (zero for a fixed direction). From `p = q + s u` and
    /// `(p − a)·(ṗ − ȧ) = 0`: `ṡ = (p − a)·(va − vq − s u̇) / ((p − a)·u)`. Returns `(ṡ, ṗ)`, or
    /// `None` at a toggle (link perpendicular to the line).
    #[allow(
        clippy::too_many_arguments,
        reason = "the base pin and line with their velocities"
    )]
    pub fn velocity(
        a: Vec2<T>,
        va: Vec2<T>,
        q: Vec2<T>,
        vq: Vec2<T>,
        u: Vec2<T>,
        omega_u: T,
        p: Vec2<T>,
    ) -> Option<(T, Vec2<T>)> {
        let e = p - a;
        let den = e.dot(&u);
        if den == T::zero() {
            return None;
        }
        let s = (p - q).dot(&u);
        let du = perp(u) * omega_u;
        let sdot = e.dot(&(va - vq - du * s)) / den;
        Some((sdot, vq + u * sdot + du * s))
    }

    /// Acceleration of the joint `p = q + s·u` moving at `v` with `ṡ = sdot`.
    ///
    /// `ü = α_u u⊥ − ω_u² u`; from `(p − a)·(p̈ − ä) + |ṗ − ȧ|² = 0`. Returns `None` at a toggle.
    #[allow(
        clippy::too_many_arguments,
        reason = "the base pin and line with their velocities and accelerations"
    )]
    pub fn acceleration(
        a: Vec2<T>,
        va: Vec2<T>,
        aa: Vec2<T>,
        q: Vec2<T>,
        aq: Vec2<T>,
        u: Vec2<T>,
        omega_u: T,
        alpha_u: T,
        p: Vec2<T>,
        v: Vec2<T>,
        sdot: T,
    ) -> Option<Vec2<T>> {
        let e = p - a;
        let den = e.dot(&u);
        if den == T::zero() {
            return None;
        }
        let s = (p - q).dot(&u);
        let du = perp(u) * omega_u;
        let ddu = perp(u) * alpha_u - u * (omega_u * omega_u);
        let known = aq + du * (lit::<T>(2.0) * sdot) + ddu * s;
        let sddot = (e.dot(&(aa - known)) - (v - va).norm_squared()) / den;
        Some(known + u * sddot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use crate::mechanism::program::Mechanism;

    #[test]
    fn line_outside_circle_reports_gap() {
        let s = SliderDyad { r: 1.0 };
        let got = s.solve(
            Vec2::new(0.0, 3.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            0.0,
        );
        assert_eq!(
            got,
            Err(DyadFailure::Gap(2.0)),
            "rod 1 from (0, 3) to the x axis"
        );
    }

    #[test]
    fn slider_crank_velocity_matches_closed_form() {
        // x(θ) = r cos θ + √(l² − r² sin² θ); ẋ by differentiation.
        let (r, l, th, w) = (2.0_f64, 5.0_f64, 0.7_f64, 3.0_f64);
        let a = Vec2::new(r * th.cos(), r * th.sin());
        let va = Vec2::new(-r * th.sin(), r * th.cos()) * w;
        let q = Vec2::new(0.0, 0.0);
        let u = Vec2::new(1.0, 0.0);
        let pose = SliderDyad { r: l }.solve(a, q, u, 0.0).unwrap();
        let p = pose.point(Reach::Ahead);
        let root = (l * l - r * r * th.sin() * th.sin()).sqrt();
        assert!(
            (p.x - (r * th.cos() + root)).abs() < 1e-14,
            "slider at x = {} against r cos θ + √(l² − r² sin² θ) = {}",
            p.x,
            r * th.cos() + root
        );
        let (_, v) = SliderDyad::velocity(a, va, q, Vec2::zeros(), u, 0.0, p).unwrap();
        let xdot = -r * th.sin() * w - r * r * th.sin() * th.cos() * w / root;
        assert!(
            (v.x - xdot).abs() < 1e-13 && v.y.abs() < 1e-15,
            "slider velocity {v:?} against ({xdot}, 0)"
        );
    }

    /// A slider through O on a line carried by the crank O → A turned by 1.1 rad, at 3 from
    /// C = (3, 0) with a rod of 2.5: it assembles only while the line passes within 2.5 of C.
    fn carried_slider() -> (Mechanism<f64, 4>, usize) {
        let mut m = Mechanism::new();
        let o = m.fixed(Vec2::zeros()).unwrap();
        let c = m.fixed(Vec2::new(3.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        let line = LineDirection::Link {
            from: o,
            to: a,
            angle: 1.1,
        };
        let s = m.slider(c, 2.5, o, line, Reach::Ahead).unwrap();
        (m, s)
    }

    #[test]
    fn line_directions_are_the_crank_angle_plus_the_turn() {
        // Independently of `at`: the crank O → A points at θ, so the line points at θ + 1.1,
        // (cos, sin) of that; NaN where the pose fails.
        let (m, s) = carried_slider();
        const K: usize = 64;
        let mut joints = [Vec2::zeros(); 4 * K];
        let mut failed = 0;
        for (k, row) in joints.chunks_exact_mut(4).enumerate() {
            let theta = 2.0 * core::f64::consts::PI * k as f64 / K as f64;
            if m.pose(theta, row).is_err() {
                row.fill(Vec2::new(f64::NAN, f64::NAN));
                failed += 1;
            }
        }
        assert!(
            failed > 0 && failed < K,
            "some samples assemble, some not: {failed}"
        );
        let mut u = [Vec2::zeros(); K];
        m.line_directions(s, &joints, &mut u).unwrap();
        for (k, (u, row)) in u.iter().zip(joints.chunks_exact(4)).enumerate() {
            if row[2].x.is_nan() {
                assert!(u.x.is_nan() && u.y.is_nan(), "sample {k}: {u:?}");
                continue;
            }
            let phi = (row[2].y - row[0].y).atan2(row[2].x - row[0].x) + 1.1;
            let want = Vec2::new(phi.cos(), phi.sin());
            // A few ulp: rounding of θ + 1.1 and of the trigonometric functions.
            assert!(
                (u - want).norm() < 1e-15,
                "sample {k}: {u:?} against {want:?}"
            );
        }
    }

    #[test]
    fn line_directions_refuse_other_joints_and_short_buffers() {
        let (m, s) = carried_slider();
        let joints = [Vec2::zeros(); 8];
        let mut u = [Vec2::zeros(); 2];
        for joint in [0, 2, 4, usize::MAX] {
            assert_eq!(
                m.line_directions(joint, &joints, &mut u),
                Err(Error::NotASlider { joint }),
                "line directions of joint {joint}"
            );
        }
        // 8 positions are 2 rows of 4 joints: not 7 positions, nor one row.
        let short = Error::BufferLength {
            what: "joints",
            expected: 8,
            got: 7,
        };
        assert_eq!(
            m.line_directions(s, &joints[..7], &mut u),
            Err(short),
            "7 positions"
        );
        let one = Error::BufferLength {
            what: "joints",
            expected: 4,
            got: 8,
        };
        assert_eq!(
            m.line_directions(s, &joints, &mut u[..1]),
            Err(one),
            "2 rows into 1 output"
        );
        assert_eq!(
            m.line_directions(s, &joints, &mut u),
            Ok(()),
            "2 rows into 2 outputs"
        );
    }
}
