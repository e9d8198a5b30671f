//! Small numeric helpers shared by the solvers.

use nalgebra::{RealField, Vector2};

/// A point or vector in the plane.
///
/// ```
/// use linkage_core::Vec2;
/// let v = Vec2::new(3.0_f64, 4.0);
/// assert_eq!((v.norm(), v.dot(&Vec2::new(1.0, 0.0))), (5.0, 3.0));
/// ```
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

/// The least sum of squares [`length`] takes as it is: far above the subnormal range, 1e-270
/// (about 2⁻⁸⁹⁷) for f64; that literal is zero in f32, whose squares turn subnormal below
/// |v| ≈ 1e-19, so there the bound is ε⁵ ≈ 2.4e-35 (f32's smallest normal is 1.2e-38).
#[inline]
pub(crate) fn tiny_square<T: RealField + Copy>() -> T {
    let tiny = T::from_subset(&1e-270_f64);
    if tiny > T::zero() {
        tiny
    } else {
        let e = T::default_epsilon();
        e * e * e * e * e
    }
}

/// The smallest positive normal number of `T`: `f64::MIN_POSITIVE` (2.2e-308) for f64; that
/// literal is zero in f32, whose own (1.2e-38) is used there.
#[inline]
pub(crate) fn min_normal<T: RealField + Copy>() -> T {
    let m = T::from_subset(&f64::MIN_POSITIVE);
    if m > T::zero() {
        m
    } else {
        T::from_subset(&f64::from(f32::MIN_POSITIVE))
    }
}

/// The max-abs size `max(|x|, |y|)` of a vector: within `√2` of its length, with no square
/// root and no squares to overflow. For tolerances, which need a size, not a distance.
#[inline(always)]
pub(crate) fn size<T: RealField + Copy>(x: T, y: T) -> T {
    x.abs().max(y.abs())
}

/// Euclidean length without overflow or underflow of the squares: `√(x² + y²)` when the sum
/// of squares is a normal number, else the same formula on the vector divided by a power of two
/// near its size, times that power ([`crate::numeric::pow2::pow2_scale`]: exact, so a linkage scaled by
/// a power of two gets the same bits as at unit size, which `hypot` would not give).
#[inline]
pub(crate) fn length<T: RealField + Copy>(v: Vec2<T>) -> T {
    let n2 = v.x * v.x + v.y * v.y;
    if n2.is_finite() && n2 > tiny_square::<T>() {
        n2.sqrt()
    } else if v.x.is_finite() && v.y.is_finite() && (v.x != T::zero() || v.y != T::zero()) {
        let s = crate::numeric::pow2::pow2_scale(v.x.abs().max(v.y.abs()));
        let (x, y) = (v.x / s, v.y / s);
        (x * x + y * y).sqrt() * s
    } else {
        v.x.hypot(v.y)
    }
}

#[cfg(test)]
mod tests {
    use super::{length, Vec2};

    /// A 3-4-5 triangle at sizes where the squares are subnormal or overflow: the length is
    /// right to the last bit in f32 and f64 (f32 squares turn subnormal below ~1e-19).
    #[test]
    fn length_is_exact_where_the_squares_are_not_normal() {
        for s in [1e-21_f32, 3e-20, 1.0, 1e19, 1e37] {
            let l = length(Vec2::new(3.0 * s, 4.0 * s));
            assert!(
                (l - 5.0 * s).abs() <= f32::EPSILON * 5.0 * s,
                "f32 at {s}: {l}"
            );
        }
        for s in [1e-160_f64, 1e-140, 1.0, 1e160, 1e300] {
            let l = length(Vec2::new(3.0 * s, 4.0 * s));
            assert!(
                (l - 5.0 * s).abs() <= f64::EPSILON * 5.0 * s,
                "f64 at {s}: {l}"
            );
        }
    }
}
