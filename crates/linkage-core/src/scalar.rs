//! Small numeric helpers shared by the solvers.

use nalgebra::{RealField, Vector2};

/// A point or vector in the plane.
pub type Vec2<T> = Vector2<T>;

/// `x` as the scalar type `T` (exact for the small constants used here).
#[inline]
pub(crate) fn lit<T: RealField>(x: f64) -> T {
    T::from_subset(&x)
}

/// `x` as `f64`, for error payloads (NaN if `T` cannot say).
#[inline]
pub(crate) fn to_f64<T: RealField + Copy>(x: T) -> f64 {
    x.to_subset().unwrap_or(f64::NAN)
}

/// Counter-clockwise quarter turn: `(x, y) -> (-y, x)`.
#[inline]
pub(crate) fn perp<T: RealField + Copy>(v: Vec2<T>) -> Vec2<T> {
    Vec2::new(-v.y, v.x)
}

/// The z component of the cross product `a × b` (positive when `b` is left of `a`).
#[inline]
pub(crate) fn cross<T: RealField + Copy>(a: Vec2<T>, b: Vec2<T>) -> T {
    a.x * b.y - a.y * b.x
}

/// The machine epsilon of `T`.
#[inline]
pub(crate) fn eps<T: RealField + Copy>() -> T {
    T::default_epsilon()
}

/// Not-a-number of `T` (`0/0`), for samples that have no value.
#[inline]
pub(crate) fn nan<T: RealField + Copy>() -> T {
    T::zero() / T::zero()
}

/// Euclidean length without overflow or underflow of the squares: `√(x² + y²)` when the sum
/// of squares is a normal number, else the same formula on the vector divided by a power of two
/// near its size, times that power ([`crate::dyad::pow2_scale`]: exact, so a linkage scaled by
/// a power of two gets the same bits as at unit size, which `hypot` would not give).
#[inline]
pub(crate) fn length<T: RealField + Copy>(v: Vec2<T>) -> T {
    let n2 = v.x * v.x + v.y * v.y;
    // 2⁻⁹⁰⁰ keeps the fast path clear of the subnormal range for f64; for f32 it is zero, and
    // f32 squares underflow only below 1e-19 anyway, where the scaled path takes over via
    // `n2 == 0`.
    if n2.is_finite() && n2 > T::from_subset(&1e-270_f64) {
        n2.sqrt()
    } else if v.x.is_finite() && v.y.is_finite() && (v.x != T::zero() || v.y != T::zero()) {
        let s = crate::dyad::pow2_scale(v.x.abs().max(v.y.abs()));
        let (x, y) = (v.x / s, v.y / s);
        (x * x + y * y).sqrt() * s
    } else {
        v.x.hypot(v.y)
    }
}
