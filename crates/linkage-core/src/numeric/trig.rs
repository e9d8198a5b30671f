//! `sin` and `cos` of a crank angle, one code for a single angle and for a block of angles, so a
//! sweep gives the same bits whether it poses samples one by one or many at once.
//!
//! # Method
//! Cody–Waite reduction `x = n·π/2 + y` with `n = round(2x/π)` and `π/2` split into three
//! 33-bit parts and a tail, so `n·part` is exact for `|n| < 2²⁰`; the remainder is accumulated
//! in double-double (two-sum, exact), about 150 bits of `π/2` in all, and kept as `y₀ + y₁`.
//! Then the polynomial kernels of fdlibm (`__kernel_sin`, `__kernel_cos` as in FreeBSD's msun:
//! degree-13 odd and degree-14 even minimax polynomials on `[−π/4, π/4]`, error below 1 ulp,
//! taking the low part `y₁` into account) and the quadrant `n mod 4`. There is no branch but
//! selects, so a loop over angles compiles to vector code.
//!
//! `|x| ≥ REDUCE_LIMIT` (about 8·10⁵ rad) and non-finite angles take the platform's `sin_cos`
//! (`std`/`libm`) instead; `f32` and other types always do.
//!
//! The kernel polynomials and the splitting of `π/2` are those of fdlibm:
//! "Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved. Developed at SunPro, a Sun
//! Microsystems, Inc. business. Permission to use, copy, modify, and distribute this software is
//! freely granted, provided that this notice is preserved."

use core::any::TypeId;
use nalgebra::RealField;

use crate::numeric::scalar::to_f64;

/// Angles of magnitude below this are reduced here; others by the platform's `sin_cos`:
/// `2¹⁹·π/2`, so `n` has at most 19 bits and every `n·part` below is exact.
pub(crate) const REDUCE_LIMIT: f64 = 823_549.665_803_927_5;

const INV_PIO2: f64 = f64::from_bits(0x3FE45F30_6DC9C883); // 6.366_197_723_675_813_824_33e-01
const PIO2_1: f64 = f64::from_bits(0x3FF921FB_54400000); // 1.570_796_326_734_125_614_17e+00
const PIO2_2: f64 = f64::from_bits(0x3DD0B461_1A600000); // 6.077_100_506_303_965_976_60e-11
const PIO2_3: f64 = f64::from_bits(0x3BA3198A_2E000000); // 2.022_266_248_711_166_455_80e-21
const PIO2_3T: f64 = f64::from_bits(0x397B839A_252049C1); // 8.478_427_660_368_899_569_97e-32
/// `1.5·2⁵²`: adding and subtracting it rounds a number below `2⁵¹` to the nearest integer.
const ROUNDER: f64 = 6_755_399_441_055_744.0;

const S1: f64 = f64::from_bits(0xBFC55555_55555549); // -1.666_666_666_666_663_243_48e-01
const S2: f64 = f64::from_bits(0x3F811111_1110F8A6); // 8.333_333_333_322_489_461_24e-03
const S3: f64 = f64::from_bits(0xBF2A01A0_19C161D5); // -1.984_126_982_985_794_931_34e-04
const S4: f64 = f64::from_bits(0x3EC71DE3_57B1FE7D); // 2.755_731_370_707_006_767_89e-06
const S5: f64 = f64::from_bits(0xBE5AE5E6_8A2B9CEB); // -2.505_076_025_340_686_341_95e-08
const S6: f64 = f64::from_bits(0x3DE5D93A_5ACFD57C); // 1.589_690_995_211_550_102_21e-10
const C1: f64 = f64::from_bits(0x3FA55555_5555554C); // 4.166_666_666_666_660_190_37e-02
const C2: f64 = f64::from_bits(0xBF56C16C_16C15177); // -1.388_888_888_887_410_957_49e-03
const C3: f64 = f64::from_bits(0x3EFA01A0_19CB1590); // 2.480_158_728_947_672_941_78e-05
const C4: f64 = f64::from_bits(0xBE927E4F_809C52AD); // -2.755_731_435_139_066_330_35e-07
const C5: f64 = f64::from_bits(0x3E21EE9E_BDB4B1C4); // 2.087_572_321_298_174_827_90e-09
const C6: f64 = f64::from_bits(0xBDA8FAE9_BE8838D4); // -1.135_964_755_778_819_482_65e-11

/// `a + b` as an exactly rounded sum and its rounding error (Knuth's two-sum).
#[inline(always)]
fn two_sum<T: RealField + Copy>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `(sin x, cos x)` for `|x| < REDUCE_LIMIT`, branch-free (see the module). Only for `f64`
/// (written over `T` so a block of `T = f64` needs no copy); meaningless (but no trap) outside
/// that range: callers check.
#[inline(always)]
fn sin_cos_reduced<T: RealField + Copy>(x: T) -> (T, T) {
    let c = |v: f64| T::from_subset(&v);
    let (half, one, four, quarter) = (c(0.5), c(1.0), c(4.0), c(0.25));
    let rounder = c(ROUNDER);
    let n = (x * c(INV_PIO2) + rounder) - rounder;
    // x − n·PIO2_1 is exact (both terms exact and within a factor 2 of each other, or n = 0).
    let r = x - n * c(PIO2_1);
    let (s1, e1) = two_sum(r, -(n * c(PIO2_2)));
    let (s2, e2) = two_sum(s1, -(n * c(PIO2_3)));
    let low = (e1 + e2) - n * c(PIO2_3T);
    let y0 = s2 + low;
    let y1 = low - (y0 - s2);
    // fdlibm's kernels on y0 + y1, |y0| ≤ π/4.
    let z = y0 * y0;
    let w = z * z;
    let rs = c(S2) + z * (c(S3) + z * c(S4)) + z * w * (c(S5) + z * c(S6));
    let v = z * y0;
    let sin = y0 - ((z * (half * y1 - v * rs) - y1) - v * c(S1));
    let rc = z * (c(C1) + z * (c(C2) + z * c(C3))) + w * w * (c(C4) + z * (c(C5) + z * c(C6)));
    let hz = half * z;
    let one_hz = one - hz;
    let cos = one_hz + (((one - one_hz) - hz) + (z * rc - y0 * y1));
    // Quadrant n mod 4 as q = n − 4·round(n/4) ∈ {−2, …, 2} (exact integer arithmetic, no
    // floor, which baseline x86-64 cannot vectorise): quadrant 1 is q = 1, 2 is q = ±2, 3 is
    // q = −1.
    let q = n - four * ((n * quarter + rounder) - rounder);
    let (two, m1, m2) = (c(2.0), c(-1.0), c(-2.0));
    let odd = q == one || q == m1;
    let (s, co) = if odd { (cos, sin) } else { (sin, cos) };
    let s = if q == two || q == m2 || q == m1 {
        -s
    } else {
        s
    };
    let co = if q == one || q == two || q == m2 {
        -co
    } else {
        co
    };
    (s, co)
}

/// `(sin x, cos x)` of one angle: the same bits as [`sin_cos_f64_slice`] gives it.
#[inline]
pub fn sin_cos_f64(x: f64) -> (f64, f64) {
    if x.abs() < REDUCE_LIMIT {
        sin_cos_reduced(x)
    } else {
        // The platform's `f64::sin_cos` with `std`, libm's without (`f64` has no inherent
        // `sin_cos` in `no_std`).
        <f64 as nalgebra::ComplexField>::sin_cos(x)
    }
}

/// `sin` and `cos` of every angle of `x` into `sin`, `cos` (the first `x.len()` of each): the
/// same bits as [`sin_cos_f64`] angle by angle. A loop the compiler vectorises.
///
/// # Panics
/// If `sin` or `cos` is shorter than `x`.
pub fn sin_cos_f64_slice(x: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    sin_cos_block(x, sin, cos);
}

/// `(sin x, cos x)` of a crank angle for any scalar type: [`sin_cos_f64`] for `f64`, the
/// platform's `sin_cos` otherwise.
#[inline]
pub(crate) fn sin_cos<T: RealField + Copy>(x: T) -> (T, T) {
    if TypeId::of::<T>() == TypeId::of::<f64>() {
        let (s, c) = sin_cos_f64(to_f64(x));
        (T::from_subset(&s), T::from_subset(&c))
    } else {
        x.sin_cos()
    }
}

/// [`sin_cos`] of each of `x` into `sin`, `cos` (the first `x.len()` of each): for `f64` the
/// same bits as [`sin_cos_f64_slice`], in a loop the compiler vectorises (inlined, so a caller
/// compiled for wider vectors vectorises it wider).
#[inline(always)]
pub(crate) fn sin_cos_block<T: RealField + Copy>(x: &[T], sin: &mut [T], cos: &mut [T]) {
    let (sin, cos) = (&mut sin[..x.len()], &mut cos[..x.len()]);
    if TypeId::of::<T>() == TypeId::of::<f64>() {
        let limit = T::from_subset(&REDUCE_LIMIT);
        let mut far = false;
        for ((&xi, s), c) in x.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*s, *c) = sin_cos_reduced(xi);
            far |= xi.abs() >= limit || !xi.is_finite();
        }
        if far {
            for ((&xi, s), c) in x.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
                if xi.abs() >= limit || !xi.is_finite() {
                    (*s, *c) = xi.sin_cos();
                }
            }
        }
    } else {
        for ((&v, s), c) in x.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*s, *c) = v.sin_cos();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the platform's `sin_cos` (glibc: below 1 ulp): never more than 1 ulp apart on
    /// 10⁶ angles spread over the reduced range, near multiples of π/2 and near the limit; the
    /// slice and one-angle forms give the same bits; far and non-finite angles fall back.
    #[test]
    fn within_an_ulp_of_the_platform_and_the_same_bits_both_ways() {
        let ulp = |a: f64, b: f64| -> f64 {
            if a == b {
                return 0.0;
            }
            ((a - b).abs() / (f64::EPSILON * a.abs().max(b.abs()).max(f64::MIN_POSITIVE))).max(0.0)
        };
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut angles = Vec::new();
        for k in 0..1_000_000u64 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let u = (x >> 11) as f64 / (1u64 << 53) as f64;
            angles.push(match k % 4 {
                0 => (u - 0.5) * 20.0,
                1 => (u - 0.5) * 2.0 * REDUCE_LIMIT * 0.999,
                2 => core::f64::consts::FRAC_PI_2 * (k as f64 / 4.0).round() + (u - 0.5) * 1e-9,
                _ => (u - 0.5) * 1e-3,
            });
        }
        let mut s = vec![0.0; angles.len()];
        let mut c = vec![0.0; angles.len()];
        sin_cos_f64_slice(&angles, &mut s, &mut c);
        let mut worst = 0.0f64;
        for (k, &a) in angles.iter().enumerate() {
            let (rs, rc) = a.sin_cos();
            worst = worst.max(ulp(s[k], rs)).max(ulp(c[k], rc));
            assert_eq!(
                (s[k].to_bits(), c[k].to_bits()),
                {
                    let (s1, c1) = sin_cos_f64(a);
                    (s1.to_bits(), c1.to_bits())
                },
                "slice and single differ at {a}"
            );
        }
        assert!(worst <= 1.0, "{worst} ulp from the platform");
        for a in [
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            1e300,
            -3e6,
            REDUCE_LIMIT,
        ] {
            let (s1, c1) = sin_cos_f64(a);
            let (s2, c2) = a.sin_cos();
            assert!(
                s1.to_bits() == s2.to_bits() && c1.to_bits() == c2.to_bits(),
                "{a}"
            );
        }
    }
}
