//! Exact reduction of a driver angle to two turns: `θ = 4π·k + θ'` with `k` an integer and
//! `θ' ∈ [0, 4π]`, the one reduction every mechanism sweep applies to its crank angle before
//! anything else (crank pins, crank bases, flat-position parities, the tracker's grid).
//!
//! # Why two turns
//! Everything a [`crate::Mechanism`] computes from the driver angle is periodic in `4π`: crank
//! pins `θ + phase` in `2π`, and the parity of the flat positions passed, read off
//! `sin((θ + phase − β)/2)`, in `4π`. So `θ'` may replace `θ` everywhere, and no turn count
//! needs carrying beside it. Without the reduction, `θ + phase − β` rounds to a multiple of
//! `ulp(θ)` — 1.2·10⁻¹⁰ rad at `θ = 10⁶`, 0.25 rad at `1.6·10¹⁵`, several radians beyond
//! `10¹⁶` — which moved Jansen's joints and mislaid the tracker on its grid.
//!
//! # Method
//! Payne–Hanek: `|θ| = m·2ᵉ` (`m` a 53-bit integer) times 256 bits of `1/(4π)` taken from the
//! bit of weight `2⁶⁴⁻ᵉ` on (the bits above only add multiples of `2⁶⁴` to `k`): the product's
//! top word is `k mod 2⁶⁴`, the next 128 bits the fraction of two turns, to within `2⁻¹³⁹`;
//! `θ'` is that fraction times `4π` in double-double arithmetic, rounded once. So `θ'` is
//! within an ulp or so (`1.8·10⁻¹⁵`) of the exact `θ mod 4π`, for every finite `f64`.
//! `f32` angles are reduced as `f64` (exact conversion) and rounded back.
//!
//! Angles of magnitude below [`REDUCE_FROM`] are left as they are (so the first turns keep
//! their bits): there `θ + phase` rounds by at most `2⁻⁴⁸ ≈ 3.6·10⁻¹⁵` rad.
//!
//! # What "exact" means for a product
//! A drive that turns the crank `ratio` times as fast as a motor (a gear train) or adds a phase
//! hands the sweep the float `θ = fl(ratio·t)` (or `fl(t + φ)`): the sweep is exact for the
//! angle it is given; the rounding of the product is the caller's, `½ulp(θ)` — at `θ ≈ 10¹⁶`
//! that is one radian, which no reduction after the fact can recover. A crank's own `phase` is
//! added after the reduction, `θ' + phase`, so it is kept to full accuracy at any `θ`.
//!
//! The bits of `1/(4π)` were computed with mpmath at 1600 bits of precision (the leading ones
//! agree with fdlibm's table of `2/π`, shifted by three places).

use nalgebra::RealField;

use crate::numeric::scalar::to_f64;

/// Angles of magnitude at least this are reduced (see the module).
pub(crate) const REDUCE_FROM: f64 = 64.0;

/// The first 1280 bits of `1/(4π)` after the binary point, most significant first.
const INV_FOUR_PI: [u64; 20] = [
    0x145F_306D_C9C8_82A5,
    0x3F84_EAFA_3EA6_9BB8,
    0x1B6C_52B3_2788_7208,
    0x3FCA_2C75_7BD7_78AC,
    0x36E4_8DC7_4849_BA5C,
    0x00C9_25DD_413A_3243,
    0x9FC3_BD63_9625_34E7,
    0xDD10_46BE_A5D7_6890,
    0x9D33_8E04_D68B_EFC8,
    0x2732_3AC7_306A_673E,
    0x9390_8BF1_77BF_2507,
    0x63FF_12FF_FBC0_B301,
    0xFDE5_E231_6B41_4DA3,
    0xEDA6_CFD9_E4F9_6136,
    0xE9E8_C7EC_D3CB_FD45,
    0xAEA4_F758_FD7C_BE2F,
    0x67A0_E73E_F14A_525D,
    0x4D7F_6BF6_23F1_ABA1,
    0x0AC0_6608_DF8F_6D75,
    0x7E19_F784_135E_86C3,
];

/// `4π` as a double-double, `FOUR_PI_HI + FOUR_PI_LO`.
const FOUR_PI_HI: f64 = 12.566_370_614_359_172;
const FOUR_PI_LO: f64 = 4.898_587_196_589_413e-16;

/// Bits `b, b + 1, …, b + 63` of `1/(4π)` (bit 1 is the first after the point; bits before it
/// are zero), most significant first.
fn chunk(b: i64) -> u64 {
    if b + 63 < 1 {
        return 0;
    }
    if b < 1 {
        return INV_FOUR_PI[0] >> (1 - b);
    }
    let word = |i: usize| INV_FOUR_PI.get(i).copied().unwrap_or(0);
    let (i, o) = (((b - 1) / 64) as usize, ((b - 1) % 64) as u32);
    if o == 0 {
        word(i)
    } else {
        (word(i) << o) | (word(i + 1) >> (64 - o))
    }
}

/// `a·b` as an exactly rounded product and its rounding error (Dekker, no fused multiply-add).
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    const SPLIT: f64 = 134_217_729.0; // 2²⁷ + 1
    let split = |x: f64| {
        let t = SPLIT * x;
        let hi = t - (t - x);
        (hi, x - hi)
    };
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// `θ = 4π·k + θ'` for a finite `θ`: `(k mod 2⁶⁴, θ')` with `θ' ∈ [0, 4π]` (see the module).
pub(crate) fn split_f64(theta: f64) -> (u64, f64) {
    let bits = theta.to_bits() & !(1u64 << 63); // |θ| (no `f64::abs` needed in no_std)
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp - 1075)
    };
    // |θ|/(4π) ≡ m·W·2⁻¹⁹² (mod 2⁶⁴), W the bits of 1/(4π) from e − 63 to e + 192.
    let s = e - 64;
    let w = [chunk(s + 193), chunk(s + 129), chunk(s + 65), chunk(s + 1)];
    let mut p = [0u64; 5];
    let mut carry = 0u128;
    for (pi, &wi) in p.iter_mut().zip(&w) {
        let t = u128::from(m) * u128::from(wi) + carry;
        *pi = t as u64;
        carry = t >> 64;
    }
    p[4] = carry as u64;
    let mut k = p[3];
    let mut f = (u128::from(p[2]) << 64) | u128::from(p[1]);
    if theta < 0.0 {
        // −(k + f) = (−k − 1) + (1 − f), or −k when f = 0.
        if f == 0 {
            k = k.wrapping_neg();
        } else {
            k = !k;
            f = f.wrapping_neg();
        }
    }
    // f·4π in double-double: the top 53 bits of f exactly, the rest rounded.
    let f_hi = (f >> 75) as f64 * f64::from_bits(0x3CA0_0000_0000_0000); // 2⁻⁵³
    let f_lo = (f & ((1u128 << 75) - 1)) as f64 * f64::from_bits(0x37F0_0000_0000_0000); // 2⁻¹²⁸
    let (ph, pl) = two_prod(f_hi, FOUR_PI_HI);
    (k, ph + (pl + (f_hi * FOUR_PI_LO + f_lo * FOUR_PI_HI)))
}

/// `θ` reduced to two turns, `θ' ∈ [0, 4π]` with `θ' ≡ θ (mod 4π)`, for `|θ| ≥ REDUCE_FROM`;
/// smaller and non-finite angles as they are. Idempotent.
#[inline]
pub(crate) fn reduce<T: RealField + Copy>(theta: T) -> T {
    if theta.abs() < T::from_subset(&REDUCE_FROM) || !theta.is_finite() {
        return theta;
    }
    T::from_subset(&split_f64(to_f64(theta)).1)
}

/// A driver angle reduced exactly to two turns, the reduction every mechanism sweep applies
/// first: `θ' ∈ [0, 4π]` with `θ' ≡ θ (mod 4π)` to within an ulp of `4π` for `|θ| ≥ 64`, and
/// `θ` itself below that or when not finite. Idempotent. Adding a phase to a large angle
/// (`θ + φ` rounds to a multiple of `ulp(θ)`) keeps full accuracy when it is added to this
/// instead: `reduce_angle(θ) + φ`. Anything periodic in `2π` or `4π` may take `θ'` for `θ`.
///
/// ```
/// use linkage_core::reduce_angle;
/// // 10²² mod 4π = 5.263007914620499 (mpmath); `10²² % (4π as f64)` gives 1.063…, all wrong.
/// assert!((reduce_angle(1e22_f64) - 5.263007914620499).abs() < 2e-15);
/// assert_eq!(reduce_angle(1.5_f64), 1.5);
/// assert!((reduce_angle(-1e300_f64) - 2.1838724841522326).abs() < 2e-15);
/// ```
pub fn reduce_angle<T: RealField + Copy>(theta: T) -> T {
    reduce(theta)
}

/// `θ = 4π·k + θ'` for `|θ| ≥ REDUCE_FROM` and finite: `(k mod 2⁶⁴, θ')`; `(0, θ)` otherwise.
#[inline]
pub(crate) fn split<T: RealField + Copy>(theta: T) -> (u64, T) {
    if theta.abs() < T::from_subset(&REDUCE_FROM) || !theta.is_finite() {
        return (0, theta);
    }
    let (k, r) = split_f64(to_f64(theta));
    (k, T::from_subset(&r))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Golden values from mpmath at 3000 bits: `θ mod 4π` rounded to f64, and `⌊θ/4π⌋ mod 2⁶⁴`.
    #[test]
    fn matches_an_exact_reduction_from_64_to_1e300() {
        let cases: &[(f64, f64, u64)] = &GOLDEN;
        for &(theta, r, k) in cases {
            let (kk, rr) = split_f64(theta);
            assert_eq!(kk, k, "turns of {theta:e}");
            assert!(
                (rr - r).abs() <= 2.0 * f64::EPSILON * 4.0 * core::f64::consts::PI,
                "{theta:e}: {rr} against {r}"
            );
        }
    }

    #[test]
    fn small_and_reduced_angles_are_left_alone() {
        for t in [0.0, -1.0, 63.9, -63.9, 12.0, f64::NAN, f64::INFINITY] {
            let r = reduce(t);
            assert!(
                r.to_bits() == t.to_bits() || (r.is_nan() && t.is_nan()),
                "{t}"
            );
        }
        for t in [64.0, 1e6, -1e16, 1e300, f64::MAX, -f64::MAX] {
            let r = reduce(t);
            assert!((0.0..=FOUR_PI_HI).contains(&r), "{t}: {r}");
            assert_eq!(reduce(r), r, "reduce is idempotent at {t}");
        }
        // f32 through f64 (exact conversion), rounded back.
        let r32 = reduce(1e30_f32);
        assert!(
            (f64::from(r32) - split_f64(f64::from(1e30_f32)).1).abs() < 1e-6,
            "f32 reduced as its f64 value: {r32}"
        );
    }

    #[rustfmt::skip]
    const GOLDEN: [(f64, f64, u64); 22] = [
        (64.0, 1.1681469282041352, 0x0000000000000005),
        (100.0, 12.03540569948579, 0x0000000000000007),
        (1000.0, 7.256721465625336, 0x000000000000004F),
        (1000000.0, 5.925621140093852, 0x00000000000136D9),
        (-1000000.0, 6.640749474265322, 0xFFFFFFFFFFFEC926),
        (100000000000.0, 7.474059892701825, 0x00000001DA5195D2),
        (1600000000000000.0, 3.37551698731218, 0x000073CCEB13EA2C),
        (1e+16, 8.530610556341953, 0x0002D3C0BD3C7794),
        (-1e+16, 4.03576005801722, 0xFFFD2C3F42C3886B),
        (1e+22, 5.263007914620499, 0x2397B783E7A868BC),
        (1e+100, 5.892699463987461, 0xCF7D8496FEA4AFB3),
        (-1e+100, 6.673671150371712, 0x30827B69015B504C),
        (1e+300, 10.38249813020694, 0xD00AD0618C5C63CA),
        (-1e+300, 2.1838724841522326, 0x2FF52F9E73A39C35),
        (1.7976931348623157e+308, 3.136630678439006, 0x686590BA9D9290BA),
        (-1.7976931348623157e+308, 9.429739935920168, 0x979A6F45626D6F45),
        (13816870609430.547, 12.56583200900094, 0x000000FFFFFFFFFF),
        (4461.061568097506, 12.56637061435887, 0x0000000000000162),
        (-155131.84523426398, 1.0751098804921493e-11, 0xFFFFFFFFFFFFCFC7),
        (1.152921504606847e+18, 4.12186531403986, 0x0145F306DC9C882A),
        (3e-05, 3e-05, 0x0000000000000000),
        (-3e-05, 12.566340614359174, 0xFFFFFFFFFFFFFFFF),
    ];
}
