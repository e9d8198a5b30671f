//! Disc cams with translating followers: pitch curve, profile, pressure angle and curvature.

use nalgebra::RealField;

use crate::error::{check_finite, check_length, Error};
use crate::numeric::scalar::{cross, nan, perp, Vec2};

/// One cam angle's geometry, in the cam's frame (cam centre at the origin, the cam turning
/// counter-clockwise, the follower's axis along +y at angle 0).
///
/// ```
/// use linkage_core::{CamPoint, RollerFollower};
/// // Prime circle 30 + 10 = 40, the follower rising 40 per radian there: pressure angle 45°.
/// let f = RollerFollower::new(30.0_f64, 10.0, 0.0).unwrap();
/// let p: CamPoint<f64> = f.point(0.0, [0.0, 40.0, 0.0]);
/// assert!((p.pressure_angle - core::f64::consts::FRAC_PI_4).abs() < 1e-15);
/// // The profile is the pitch curve moved in by the roller's radius.
/// assert!(((p.pitch - p.profile).norm() - 10.0).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CamPoint<T> {
    /// Pitch-curve point: the roller centre (for a flat face, the face's point on the axis).
    pub pitch: Vec2<T>,
    /// Cam-profile point in contact with the follower.
    pub profile: Vec2<T>,
    /// Pressure angle: between the follower's axis and the contact normal (radians, signed).
    pub pressure_angle: T,
    /// Signed radius of curvature of the pitch curve (positive where convex).
    pub pitch_radius: T,
    /// Signed radius of curvature of the profile (positive where convex; a convex part with a
    /// negative value is undercut).
    pub profile_radius: T,
}

/// Rotation of `v` by `−φ` (from the fixed frame into the cam's frame).
#[inline]
fn into_cam<T: RealField + Copy>(v: Vec2<T>, phi: T) -> Vec2<T> {
    let (s, c) = phi.sin_cos();
    Vec2::new(c * v.x + s * v.y, -s * v.x + c * v.y)
}

/// A translating roller follower: base-circle radius `Rb`, roller radius `Rr`, the axis offset
/// `e` from the cam centre (positive to the +x side).
///
/// ```
/// use linkage_core::{Error, RollerFollower, Vec2};
/// // Base circle 40, roller 10, no offset, at a dwell 5 up: the pitch curve is a circle of 55.
/// let f = RollerFollower::new(40.0_f64, 10.0, 0.0).unwrap();
/// let p = f.point(0.0, [5.0, 0.0, 0.0]);
/// assert!((p.pitch - Vec2::new(0.0, 55.0)).norm() < 1e-12 && p.pressure_angle == 0.0);
/// assert!((p.pitch_radius - 55.0).abs() < 1e-12 && (p.profile_radius - 45.0).abs() < 1e-12);
/// // The follower's axis must pass inside the prime circle (radius 50).
/// assert!(matches!(RollerFollower::new(40.0_f64, 10.0, 50.0), Err(Error::InvalidLength { .. })));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RollerFollower<T> {
    /// Base-circle radius of the cam profile.
    pub base_radius: T,
    /// Roller radius.
    pub roller_radius: T,
    /// Offset of the follower axis from the cam centre.
    pub offset: T,
}

impl<T: RealField + Copy> RollerFollower<T> {
    /// # Errors
    /// [`Error::InvalidLength`] for non-positive radii or an offset not inside the prime circle
    /// `Rp = Rb + Rr`.
    pub fn new(base_radius: T, roller_radius: T, offset: T) -> Result<Self, Error> {
        check_length("base radius", base_radius)?;
        check_length("roller radius", roller_radius)?;
        check_finite("offset", offset)?;
        if offset.abs() >= base_radius + roller_radius {
            return Err(Error::InvalidLength {
                what: "prime radius Rb + Rr (must exceed |offset|)",
                value: crate::numeric::scalar::to_f64(base_radius + roller_radius),
            });
        }
        Ok(RollerFollower {
            base_radius,
            roller_radius,
            offset,
        })
    }

    /// Geometry at cam angle `phi` for follower displacement `s` with `ds/dφ`, `d²s/dφ²`
    /// (`y = [s, s', s'']`).
    ///
    /// In the follower's frame the roller centre is `C = (e, d₀ + s)`, `d₀ = √(Rp² − e²)`; in the
    /// cam's frame `P = R(−φ)C`, whose derivatives are `R(−φ)q₁`, `R(−φ)q₂` with
    /// `q₁ = C' − C⊥`, `q₂ = C'' − 2C'⊥ − C`. The pressure angle is `atan2(s' − e, d₀ + s)`
    /// (Norton), the pitch radius `|q₁|³/(q₁ × q₂)` (sign flipped so convex is positive: the
    /// pitch curve runs clockwise in the cam's frame), the profile is `P` moved by `Rr` along the
    /// inward normal and its radius `ρ_pitch − Rr`.
    pub fn point(&self, phi: T, y: [T; 3]) -> CamPoint<T> {
        let [s, s1, s2] = y;
        let e = self.offset;
        let rp = self.base_radius + self.roller_radius;
        let d0 = ((rp - e) * (rp + e)).sqrt();
        let c = Vec2::new(e, d0 + s);
        let c1 = Vec2::new(T::zero(), s1);
        let c2 = Vec2::new(T::zero(), s2);
        let q1 = c1 - perp(c);
        let q2 = c2 - perp(c1) * (T::one() + T::one()) - c;
        let speed = q1.norm();
        let k = cross(q1, q2);
        let pitch_radius = if k == T::zero() {
            nan()
        } else {
            -(speed * speed * speed) / k
        };
        // Outward normal of the pitch curve: the one pointing away from the cam centre.
        let mut n = perp(q1) / speed;
        if n.dot(&c) < T::zero() {
            n = -n;
        }
        let pitch = into_cam(c, phi);
        let profile = into_cam(c - n * self.roller_radius, phi);
        CamPoint {
            pitch,
            profile,
            pressure_angle: (s1 - e).atan2(d0 + s),
            pitch_radius,
            profile_radius: pitch_radius - self.roller_radius,
        }
    }
}

/// A translating flat-faced follower, its face perpendicular to its axis through the cam
/// centre, touching a cam of base-circle radius `Rb`.
///
/// ```
/// use linkage_core::{FlatFollower, Vec2};
/// let f = FlatFollower::new(20.0_f64).unwrap();
/// // At s = 5 with s' = 3 the contact is 3 off the axis; with s'' = −30 the profile's radius
/// // 20 + 5 − 30 is negative: a cusp, the cam is undercut there.
/// let p = f.point(0.0, [5.0, 3.0, -30.0]);
/// assert_eq!((p.profile, p.pressure_angle), (Vec2::new(3.0, 25.0), 0.0));
/// assert_eq!(p.profile_radius, -5.0);
/// assert!(FlatFollower::new(0.0_f64).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatFollower<T> {
    /// Base-circle radius of the cam profile.
    pub base_radius: T,
}

impl<T: RealField + Copy> FlatFollower<T> {
    /// # Errors
    /// [`Error::InvalidLength`] for a non-positive radius.
    pub fn new(base_radius: T) -> Result<Self, Error> {
        Ok(FlatFollower {
            base_radius: check_length("base radius", base_radius)?,
        })
    }

    /// Geometry at cam angle `phi`: the contact lies on the face `s'` off the axis, at
    /// `(s', Rb + s)` in the follower's frame; the profile's radius of curvature is
    /// `Rb + s + s''` (a cusp, i.e. undercut, where it is negative); the pressure angle is zero.
    pub fn point(&self, phi: T, y: [T; 3]) -> CamPoint<T> {
        let [s, s1, s2] = y;
        let h = self.base_radius + s;
        let radius = h + s2;
        CamPoint {
            pitch: into_cam(Vec2::new(T::zero(), h), phi),
            profile: into_cam(Vec2::new(s1, h), phi),
            pressure_angle: T::zero(),
            pitch_radius: radius,
            profile_radius: radius,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dwell_gives_the_base_circle() {
        let f = RollerFollower::new(20.0_f64, 5.0, 0.0).unwrap();
        for k in 0..12 {
            let phi = k as f64 * 0.5;
            let p = f.point(phi, [0.0, 0.0, 0.0]);
            assert!(
                (p.profile.norm() - 20.0).abs() < 1e-12,
                "profile radius {} at φ = {phi}",
                p.profile.norm()
            );
            assert!(
                (p.pitch.norm() - 25.0).abs() < 1e-12,
                "pitch radius {} at φ = {phi}",
                p.pitch.norm()
            );
            assert!(
                (p.pitch_radius - 25.0).abs() < 1e-12 && (p.profile_radius - 20.0).abs() < 1e-12,
                "radii of curvature: pitch {}, profile {} at φ = {phi}",
                p.pitch_radius,
                p.profile_radius
            );
            assert!(
                p.pressure_angle.abs() < 1e-15,
                "pressure angle {:e} at φ = {phi}",
                p.pressure_angle
            );
        }
        let flat = FlatFollower::new(20.0_f64)
            .unwrap()
            .point(1.0, [0.0, 0.0, 0.0]);
        assert!(
            (flat.profile.norm() - 20.0).abs() < 1e-12
                && (flat.profile_radius - 20.0).abs() < 1e-12,
            "flat follower on a dwell: profile at radius {}, radius of curvature {}",
            flat.profile.norm(),
            flat.profile_radius
        );
    }

    /// Constant-velocity rise s = Lφ/β, no offset: tan(pressure angle) = (L/β)/(Rp + s).
    #[test]
    fn pressure_angle_closed_form() {
        let f = RollerFollower::new(30.0_f64, 6.0, 0.0).unwrap();
        let (l, beta) = (12.0, 1.2);
        for k in 0..10 {
            let phi = beta * k as f64 / 10.0;
            let s = l * phi / beta;
            let p = f.point(phi, [s, l / beta, 0.0]);
            let want = ((l / beta) / (36.0 + s)).atan();
            assert!(
                (p.pressure_angle - want).abs() < 1e-14,
                "pressure angle {} against {want} at φ = {phi}",
                p.pressure_angle
            );
            // The profile is one roller radius from the pitch curve.
            assert!(
                ((p.pitch - p.profile).norm() - 6.0).abs() < 1e-12,
                "pitch-to-profile distance {} at φ = {phi} (want the roller radius 6)",
                (p.pitch - p.profile).norm()
            );
        }
        assert!(
            RollerFollower::new(10.0, 2.0, 12.0).is_err(),
            "offset 12 not inside the prime circle (radius 12) accepted"
        );
    }
}
