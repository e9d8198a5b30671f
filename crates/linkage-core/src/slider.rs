//! The RRP slider dyad: a joint on a line, at a given distance from a known joint.

use nalgebra::RealField;

use crate::dyad::DyadFailure;
use crate::error::Error;
use crate::scalar::{cross, eps, lit, perp, Vec2};

/// Which of the two intersections of a circle and a line.
///
/// ```
/// use linkage_core::{Reach, SliderDyad, Vec2};
/// // Pivot (0, 3), link 5, the x axis as the line: the joint 4 ahead of the foot, or 4 behind.
/// let s = SliderDyad { r: 5.0_f64 };
/// let pose = s.solve(Vec2::new(0.0, 3.0), Vec2::zeros(), Vec2::new(1.0, 0.0), 0.0).unwrap();
/// assert_eq!(pose.point(Reach::Ahead), Vec2::new(4.0, 0.0));
/// assert_eq!(pose.point(Reach::Behind), Vec2::new(-4.0, 0.0));
/// assert_eq!(Reach::Behind.sign::<f64>(), -1.0);
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

    /// Every name [`Reach::from_str`](core::str::FromStr::from_str) takes, in declaration order.
    pub const NAMES: [&'static str; 2] = ["ahead", "behind"];

    /// The name users write: `"ahead"` or `"behind"`.
    ///
    /// ```
    /// use linkage_core::{Error, Reach};
    /// assert_eq!("behind".parse::<Reach>(), Ok(Reach::Behind));
    /// assert_eq!(Reach::Ahead.name(), "ahead");
    /// assert_eq!(
    ///     "back".parse::<Reach>(),
    ///     Err(Error::InvalidChoice { what: "reach", choices: "'ahead' or 'behind'" })
    /// );
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Reach::Ahead => "ahead",
            Reach::Behind => "behind",
        }
    }
}

impl core::str::FromStr for Reach {
    type Err = Error;

    /// The reach named `"ahead"` or `"behind"` (exactly; see [`Reach::name`]).
    ///
    /// # Errors
    /// [`Error::InvalidChoice`] for any other name.
    fn from_str(name: &str) -> Result<Self, Error> {
        match name {
            "ahead" => Ok(Reach::Ahead),
            "behind" => Ok(Reach::Behind),
            _ => Err(Error::InvalidChoice {
                what: "reach",
                choices: "'ahead' or 'behind'",
            }),
        }
    }
}

impl core::fmt::Display for Reach {
    /// [`Reach::name`].
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
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
            let sc = crate::dyad::pow2_scale(r);
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

    #[test]
    fn line_outside_circle_reports_gap() {
        let s = SliderDyad { r: 1.0 };
        let got = s.solve(
            Vec2::new(0.0, 3.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            0.0,
        );
        assert_eq!(got, Err(DyadFailure::Gap(2.0)));
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
        assert!((p.x - (r * th.cos() + root)).abs() < 1e-14);
        let (_, v) = SliderDyad::velocity(a, va, q, Vec2::zeros(), u, 0.0, p).unwrap();
        let xdot = -r * th.sin() * w - r * r * th.sin() * th.cos() * w / root;
        assert!((v.x - xdot).abs() < 1e-13 && v.y.abs() < 1e-15);
    }
}
