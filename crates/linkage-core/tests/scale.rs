//! Scale invariance of tracked sweeps: every length of a linkage multiplied by `k` multiplies
//! its joint positions, velocities, accelerations and jerks by `k` (the drive is in radians, so
//! its rates do not change) and leaves its margins alone — at scales such as `2^±1000` and
//! `1e±300`, where a product of two lengths underflows to zero or overflows to infinity, so
//! every such product in the solver must be formed on lengths rescaled by a power of two.
//!
//! Checked to `4ε` of each quantity's largest size over a 721-sample tracked sweep (through
//! toggles and, for the parallelogram, flat positions): `2^e` against the unit linkage, and a
//! non-power-of-two `k = b·2^e` (`b` in `[1, 2)`) against the linkage scaled by `b`, whose
//! lengths have the same bits up to the exponent (so the rounding of `k · length` is shared and
//! any difference is the solver's). Measured: 0 (bit for bit) everywhere except components
//! that are themselves subnormal at `2^-1000` / `1e-300` (Peaucellier, ~1e-25 relative).
//!
//! Not covered: scales where the outputs are not normal floats — at `1e-305` a crank pin near
//! the ground line has a subnormal coordinate (absolute precision 5e-324), which the
//! parallelogram's flat positions amplify by `1/margin³` in the jerk (measured 4e-10); at
//! `1.7e305` the true jerks exceed the largest float.

use linkage_core::catalog;
use linkage_core::{Assembly, Construction, CrankRates, FourBar, Mechanism, Rates, Tracker, Vec2};

/// The mechanism with every length multiplied by `k` (angles and topology unchanged).
fn scaled<const N: usize>(m: &Mechanism<f64, N>, k: f64) -> Mechanism<f64, N> {
    let mut out = Mechanism::new();
    for c in m.constructions() {
        let c = match *c {
            Construction::Fixed { at } => Construction::Fixed { at: at * k },
            Construction::Crank {
                centre,
                radius,
                phase,
            } => Construction::Crank {
                centre,
                radius: radius * k,
                phase,
            },
            Construction::Dyad {
                p1,
                p2,
                mut dyad,
                side,
            } => {
                dyad.r1 *= k;
                dyad.r2 *= k;
                Construction::Dyad { p1, p2, dyad, side }
            }
            Construction::Slider {
                pivot,
                origin,
                direction,
                mut slider,
                reach,
            } => {
                // A line direction is a unit vector or an angle: it does not scale.
                slider.r *= k;
                Construction::Slider {
                    pivot,
                    origin,
                    direction,
                    slider,
                    reach,
                }
            }
            Construction::Point {
                from,
                to,
                along,
                left,
            } => Construction::Point {
                from,
                to,
                along: along * k,
                left: left * k,
            },
        };
        out.push(c).expect("a scaled valid program is valid");
    }
    out
}

/// One tracked sample: margin (NaN when it did not assemble) and, per joint, position,
/// velocity, acceleration and jerk.
struct Sampled {
    margin: f64,
    rows: Vec<[Vec2<f64>; 4]>,
}

/// Tracked sweep over `thetas` with a drive that has a velocity, an acceleration and a jerk.
fn sweep<const N: usize>(m: &Mechanism<f64, N>, thetas: &[f64]) -> Vec<Sampled> {
    let n = m.len();
    let mut t = Tracker::new(m).unwrap();
    let drive = CrankRates {
        omega: 1.3,
        alpha: -0.4,
        jerk: 0.25,
    };
    thetas
        .iter()
        .map(|&th| {
            let (mut p, mut v, mut a, mut j) = (
                vec![Vec2::zeros(); n],
                vec![Vec2::zeros(); n],
                vec![Vec2::zeros(); n],
                vec![Vec2::zeros(); n],
            );
            let rates = Rates {
                velocity: Some(&mut v),
                acceleration: Some(&mut a),
                jerk: Some(&mut j),
            };
            let margin = t
                .step(th, Some(drive), &mut p, rates)
                .map_or(f64::NAN, |s| s.margin);
            Sampled {
                margin,
                rows: (0..n).map(|i| [p[i], v[i], a[i], j[i]]).collect(),
            }
        })
        .collect()
}

/// The largest relative difference, per quantity (position, velocity, acceleration, jerk), of
/// the sweep of the linkage scaled by `k` from the sweep of it scaled by `base`, after dividing
/// by `k / base` (a power of two); relative to the quantity's largest size over the reference
/// sweep. Panics unless both sweeps assemble, and give NaN rates, at the same samples with the
/// same margins (to `4ε`).
fn worst<const N: usize>(m: &Mechanism<f64, N>, base: f64, k: f64) -> [f64; 4] {
    let ratio = k / base;
    assert_eq!(ratio.log2().fract(), 0.0, "k / base must be a power of two");
    let thetas: Vec<f64> = (0..=720).map(|i| -7.0 + 14.0 * i as f64 / 720.0).collect();
    let (s0, s1) = (
        sweep(&scaled(m, base), &thetas),
        sweep(&scaled(m, k), &thetas),
    );
    let mut big = [0.0f64; 4];
    let mut diff = [0.0f64; 4];
    let mut regular = 0;
    for (a, b) in s0.iter().zip(&s1) {
        assert_eq!(
            a.margin.is_nan(),
            b.margin.is_nan(),
            "k = {k:e}: assembly differs"
        );
        if a.margin.is_nan() {
            continue;
        }
        assert!(
            (b.margin - a.margin).abs() <= 4.0 * f64::EPSILON,
            "k = {k:e}: margin {} vs {}",
            b.margin,
            a.margin
        );
        regular += usize::from(a.margin > 1e-6);
        for (ra, rb) in a.rows.iter().zip(&b.rows) {
            for q in 0..4 {
                let (x, y) = (ra[q] / base, rb[q] / k);
                assert_eq!(
                    [x.x.is_nan(), x.y.is_nan()],
                    [y.x.is_nan(), y.y.is_nan()],
                    "k = {k:e}: NaN rates differ (margin {})",
                    a.margin
                );
                if x.x.is_finite() && x.y.is_finite() {
                    big[q] = big[q].max(x.amax());
                    diff[q] = diff[q].max((y - x).amax());
                }
            }
        }
    }
    assert!(regular > 100, "only {regular} regular samples");
    let mut rel = [0.0; 4];
    for q in 0..4 {
        rel[q] = diff[q] / big[q];
    }
    rel
}

/// Scales `2^±700` and `2^±1000` against the unit linkage, and scales `1e±300`, `1e±200`, …
/// against the linkage scaled by the same mantissa (`k / 2^e` in `[1, 2)`): the scaled lengths
/// then have the same bits up to the exponent, so the rounding of `k · length` is the same in
/// both and any difference is the solver's own.
fn check<const N: usize>(what: &str, m: &Mechanism<f64, N>) {
    let tol = 4.0 * f64::EPSILON;
    for e in [-1000, 1000, -700, 700] {
        let k = 2f64.powi(e);
        let rel = worst(m, 1.0, k);
        println!("{what} k = 2^{e}: {rel:?}");
        assert!(rel.iter().all(|&r| r <= tol), "{what} k = 2^{e}: {rel:?}");
    }
    for k in [1e-300_f64, 1e300, 1e-200, 1e200, 3.7e-301, 7.1e299] {
        let base = k / 2f64.powi(k.log2().floor() as i32);
        assert!(
            (1.0..2.0).contains(&base),
            "mantissa {base} of {k:e} not in [1, 2)"
        );
        let rel = worst(m, base, k);
        println!("{what} k = {k:e} (against {base}): {rel:?}");
        assert!(rel.iter().all(|&r| r <= tol), "{what} k = {k:e}: {rel:?}");
    }
}

#[test]
fn fourbar_rates_scale_exactly() {
    let hoecken = FourBar::new(20.0, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    check("hoecken", &hoecken.mechanism());
    // A Grashof-limited one (the tracker turns back at its toggles) and a change-point one (the
    // crank-and-fixed closed forms carry it through its flat positions).
    let evans_b = FourBar::new(23.05, 10.0, 12.0, 11.67, (15.0, 0.0), Assembly::Open).unwrap();
    check("evans_b", &evans_b.mechanism());
    let parallelogram = FourBar::new(10.0, 4.0, 10.0, 4.0, (2.0, 1.0), Assembly::Open).unwrap();
    check("parallelogram", &parallelogram.mechanism());
}

#[test]
fn multi_loop_rates_scale_exactly() {
    for l in [
        catalog::jansen::<f64>(),
        catalog::peaucellier(),
        catalog::hart(),
    ] {
        check(l.name, &l.mechanism);
    }
}

/// The public one-dyad rate functions scale the same way.
#[test]
fn dyad_rate_functions_scale_exactly() {
    use linkage_core::Dyad;
    let (p1, p2, p) = (
        Vec2::new(0.0, 0.0),
        Vec2::new(5.0, 0.0),
        Vec2::new(1.8, 2.4),
    );
    let (v1, v2, a1, a2) = (
        Vec2::new(0.3, -1.1),
        Vec2::new(0.0, 0.0),
        Vec2::new(-0.7, 0.2),
        Vec2::new(0.0, 0.0),
    );
    let v = Dyad::velocity(p1, v1, p2, v2, p).unwrap();
    let a = Dyad::acceleration(p1, v1, a1, p2, v2, a2, p, v).unwrap();
    for k in [2f64.powi(-1000), 2f64.powi(1000), 1e-300, 1e300] {
        let vk = Dyad::velocity(p1 * k, v1 * k, p2 * k, v2 * k, p * k).unwrap();
        let ak =
            Dyad::acceleration(p1 * k, v1 * k, a1 * k, p2 * k, v2 * k, a2 * k, p * k, vk).unwrap();
        assert!(
            (vk / k - v).amax() <= 4.0 * f64::EPSILON * v.amax(),
            "k = {k:e}"
        );
        assert!(
            (ak / k - a).amax() <= 4.0 * f64::EPSILON * a.amax(),
            "k = {k:e}"
        );
    }
}
