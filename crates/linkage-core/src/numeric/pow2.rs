//! Rescaling by powers of two: the one overflow-safe size of the crate. A length, speed or
//! acceleration far from 1 is divided by a power of two near it (exact), worked on, and scaled
//! back, so products of such quotients neither overflow nor underflow.
use nalgebra::RealField;

/// `x` in `T`, as [`crate::numeric::scalar`]'s `lit` does (repeated here so that `scalar`, which
/// rescales by [`pow2_scale`], and this module do not import each other).
#[inline(always)]
fn lit<T: RealField>(x: f64) -> T {
    T::from_subset(&x)
}

/// Whether `x ≥ 0` is a size at which [`pow2_scale`] is 1: within `[2⁻³², 2³²]`.
#[inline(always)]
pub(crate) fn unit_scale<T: RealField + Copy>(x: T) -> bool {
    let step = lit::<T>(4_294_967_296.0); // 2³²
    x <= step && x * step >= T::one()
}

/// A power of two `s` for rescaling by `x` without rounding: `1` for `x` in `[2⁻³², 2³²]`
/// (ordinary sizes keep their bits), otherwise one with `x / s` in `[1, 2)` (for a positive
/// finite `x`; within `2³²` of `x` for zero or infinity, `1` for NaN). Dividing by it is exact.
///
/// Why tight: the callers divide lengths by it and then form products of the quotients with
/// other quantities that carry the linkage's scale (velocities, other lengths). A quotient left
/// anywhere in `[2⁻³², 2³²]` would push such a product `2³²` closer to underflow or overflow —
/// the rates of a linkage at 1e−300 lost digits to subnormal right-hand sides that way.
#[inline]
pub(crate) fn pow2_scale<T: RealField + Copy>(x: T) -> T {
    if unit_scale(x) {
        return T::one();
    }
    let step = lit::<T>(4_294_967_296.0); // 2³²
    let mut s = T::one();
    while x / s > step && (s * step).is_finite() {
        s *= step;
    }
    while x / s < T::one() / step && s / step > T::zero() {
        s /= step;
    }
    // Now within 2³² of `x`: settle the last bits (at most 32 halvings or doublings, and only
    // for extreme sizes).
    if x > T::zero() && x.is_finite() {
        let two = lit::<T>(2.0);
        while x / s >= two && (s * two).is_finite() {
            s *= two;
        }
        while x / s < T::one() && s / two > T::zero() {
            s /= two;
        }
    }
    s
}
