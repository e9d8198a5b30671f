//! Property tests of the solver and the sweep over random four-bars, including link-length
//! ratios up to 1e6 and pivots far from the origin.
//!
//! Cases per property: `LINKAGE_PROPTEST_CASES` (default 2000; the long run uses 1e5).

use linkage_core::{
    Assembly, CrankRates, FourBar, GrashofClass, InputRange, Mechanism, Rates, Tracker, Vec2,
};
use proptest::prelude::*;
use std::f64::consts::PI;

mod common;

/// log-uniform in [10^lo, 10^hi].
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi).prop_map(|e: f64| 10f64.powf(e))
}

/// A crank-rocker by construction: ground, coupler and rocker form a proper triangle, the crank is
/// a fraction (1e-6 … 0.9) of the shortest of them and of the Grashof slack `p + q − l`, so `s + l < p + q` holds. Placed anywhere
/// (offset up to 1e3 × its size), at any scale (1e-3 … 1e3), rotated.
#[derive(Clone, Debug)]
struct Case {
    fb: FourBar<f64>,
    size: f64,
}

fn crank_rocker() -> impl Strategy<Value = Case> {
    (
        log_uniform(-3.0, 3.0),
        (0.5f64..2.0, 0.5f64..2.0, 0.5f64..2.0),
        log_uniform(-6.0, -0.05),
        (-1e3f64..1e3, -1e3f64..1e3, 0.0..2.0 * PI),
        (-3.0f64..3.0, -3.0f64..3.0),
        any::<bool>(),
    )
        .prop_filter_map(
            "ground, coupler, rocker must form a proper triangle",
            |(scale, (g, c, k), frac, (ox, oy, rot), (pa, pl), open)| {
                let (g, c, k) = (g * scale, c * scale, k * scale);
                let longest = g.max(c).max(k);
                if 2.0 * longest >= 0.98 * (g + c + k) {
                    return None;
                }
                // Grashof with the crank shortest: r < min(g, c, k) and r + l < p + q.
                let slack = g + c + k - 2.0 * longest;
                let r = frac * g.min(c).min(k).min(slack);
                let o = Vec2::new(ox, oy) * scale;
                let cpos = o + Vec2::new(rot.cos(), rot.sin()) * g;
                let assembly = if open {
                    Assembly::Open
                } else {
                    Assembly::Crossed
                };
                let fb = FourBar::with_pivots(o, cpos, r, c, k, (pa * c, pl * c), assembly).ok()?;
                Some(Case { fb, size: longest })
            },
        )
}

fn sweep(fb: &FourBar<f64>, thetas: &[f64]) -> Vec<Option<[Vec2<f64>; 5]>> {
    let m = fb.mechanism();
    let mut t = Tracker::new(&m).unwrap();
    thetas
        .iter()
        .map(|&th| {
            let mut j = [Vec2::zeros(); 5];
            t.step(th, None, &mut j, Rates::none()).ok().map(|_| j)
        })
        .collect()
}

/// Which side of A → C the joint B is on.
fn orientation(j: &[Vec2<f64>; 5]) -> f64 {
    let (a, b, c) = (j[2], j[3], j[1]);
    let (u, w) = (c - a, b - a);
    (u.x * w.y - u.y * w.x).signum()
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/properties.txt"))]

    /// Every link keeps its length to 1e-12 relative to the larger of the link and the coordinates
    /// of its joints (stored coordinates carry rounding of their own magnitude; a link 1e-6 the
    /// size of its coordinates cannot be held more closely than that in any absolute frame).
    #[test]
    fn link_lengths_kept(case in crank_rocker(), steps in 3usize..400) {
        let fb = case.fb;
        let th: Vec<f64> = (0..steps).map(|k| 2.0 * PI * k as f64 / steps as f64).collect();
        for j in sweep(&fb, &th) {
            let j = j.expect("a crank-rocker assembles at every angle");
            for (p, q, len) in [(0, 2, fb.crank), (2, 3, fb.coupler), (1, 3, fb.rocker)] {
                let scale = len.max(j[p].amax()).max(j[q].amax());
                let err = ((j[q] - j[p]).norm() - len).abs();
                prop_assert!(err <= 1e-12 * scale, "link {p}-{q}: error {err:e}, scale {scale:e}");
            }
        }
    }

    /// A crank-rocker never changes orientation, however coarsely it is sampled, and its pose is
    /// 2π-periodic in the crank angle.
    #[test]
    fn branch_continuity_and_periodicity(case in crank_rocker(), steps in 2usize..50, start in -10.0f64..10.0) {
        let fb = case.fb;
        let want = match fb.assembly { Assembly::Open => 1.0, Assembly::Crossed => -1.0 };
        let th: Vec<f64> = (0..=2 * steps).map(|k| start + 2.0 * PI * k as f64 / steps as f64).collect();
        let poses = sweep(&fb, &th);
        for j in &poses {
            prop_assert_eq!(orientation(j.as_ref().unwrap()), want, "{:?} branch changed orientation: joints {:?}", fb.assembly, j);
        }
        for k in 0..steps {
            let (a, b) = (poses[k].unwrap(), poses[k + steps].unwrap());
            for i in 0..5 {
                let scale = case.size.max(a[i].amax());
                prop_assert!((a[i] - b[i]).norm() <= 1e-11 * scale, "joint {i} not 2π-periodic from θ = {}: {:?} vs {:?}", th[k], a[i], b[i]);
            }
        }
    }

    /// Analytic velocity and acceleration equal central finite differences of the positions
    /// (in the crank angle, times ω, and of the velocity for α).
    #[test]
    fn rates_match_finite_differences(case in crank_rocker(), theta in 0.0f64..2.0 * PI, omega in -5.0f64..5.0, alpha in -5.0f64..5.0) {
        let fb = case.fb;
        let m = fb.mechanism();
        let pose = |th: f64| { let mut j = [Vec2::zeros(); 5]; m.pose(th, &mut j).unwrap(); j };
        let rates = |th: f64| {
            let j = pose(th);
            let (mut v, mut a) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5]);
            m.rates(&j, CrankRates::new(omega, alpha), &mut v, Some(&mut a), None).unwrap();
            (v, a)
        };
        let (v, a) = rates(theta);
        let h = 1e-5;
        let (pp, pm) = (pose(theta + h), pose(theta - h));
        // Unit-speed rates to difference the velocity in θ: v = ω·dP/dθ, a = ω²·d²P/dθ² + α·dP/dθ.
        let unit = |th: f64| { let j = pose(th); let mut v = [Vec2::zeros(); 5]; m.rates(&j, CrankRates::unit(), &mut v, None, None).unwrap(); v };
        let (up, um) = (unit(theta + h), unit(theta - h));
        let u0 = unit(theta);
        for i in 2..5 {
            let dp = (pp[i] - pm[i]) / (2.0 * h);
            let d2p = (up[i] - um[i]) / (2.0 * h);
            // Central differences carry O(h²)·P''' truncation and ε·|P|/h rounding.
            let vscale = u0[i].norm().max(case.size * 1e-3) * (1.0 + omega.abs());
            // A position carries a few ulp of its coordinates (a chain of ~10 roundings).
            let pos_round = 16.0 * f64::EPSILON * pp[i].amax() / h;
            prop_assert!((v[i] - dp * omega).norm() <= 1e-5 * vscale + pos_round * omega.abs() * 4.0,
                "joint {i}: v {:?} fd {:?}", v[i], dp * omega);
            let want = d2p * omega * omega + dp * alpha;
            let ascale = d2p.norm().max(dp.norm()).max(case.size * 1e-3) * (1.0 + omega * omega + alpha.abs());
            let vel_round = 16.0 * f64::EPSILON * (u0[i].norm() + pp[i].amax()) / h;
            prop_assert!((a[i] - want).norm() <= 1e-4 * ascale + vel_round * (omega * omega) * 8.0 + pos_round * alpha.abs() * 4.0,
                "joint {i}: a {:?} fd {:?}", a[i], want);
        }
    }

    /// Grashof class agrees with whether the crank assembles over a full turn.
    #[test]
    fn grashof_agrees_with_full_turn(g in log_uniform(0.0, 2.0), r in log_uniform(0.0, 2.0), c in log_uniform(0.0, 2.0), k in log_uniform(0.0, 2.0)) {
        let fb = FourBar::new(g, r, c, k, (0.0, 0.0), Assembly::Open).unwrap();
        let class = fb.grashof();
        prop_assume!(class != GrashofClass::ChangePoint);
        let turns = matches!(class, GrashofClass::CrankRocker | GrashofClass::DoubleCrank);
        prop_assert_eq!(matches!(fb.input_range(), InputRange::Full), turns, "{:?} vs input range {:?}", class, fb.input_range());
        let m = fb.mechanism();
        let mut j = [Vec2::zeros(); 5];
        let all = (0..720).all(|i| m.pose(2.0 * PI * i as f64 / 720.0, &mut j).is_ok());
        if turns {
            prop_assert!(all, "{class:?} failed to assemble within a sampled turn");
        } else if all {
            // A sampled full turn can slip between toggle limits only if the unreachable arc is
            // narrower than the sampling; then the limits must be that close.
            match fb.input_range() {
                InputRange::Between { lo, hi } => prop_assert!(2.0 * PI - (hi - lo) < 2.0 * PI / 720.0, "every sample assembled, yet limits {lo}…{hi} leave a gap of {}", 2.0 * PI - (hi - lo)),
                InputRange::TwoIntervals { .. } | InputRange::Never => prop_assert!(false, "{:?}", fb.input_range()),
                InputRange::Full => unreachable!(),
            }
        }
    }
}

/// Branch sign of f32 and f64 sweeps agree, and positions agree to f32 precision.
#[test]
fn f32_agrees_with_f64() {
    let f64_fb = linkage_core::catalog::hoecken::<f64>();
    let f32_fb = linkage_core::catalog::hoecken::<f32>();
    let (m64, m32) = (f64_fb.mechanism(), f32_fb.mechanism());
    let (mut t64, mut t32) = (Tracker::new(&m64).unwrap(), Tracker::new(&m32).unwrap());
    let mut worst: f64 = 0.0;
    for k in 0..3600 {
        let th = 2.0 * PI * k as f64 / 3600.0;
        let (mut a, mut b) = ([Vec2::<f64>::zeros(); 5], [Vec2::<f32>::zeros(); 5]);
        t64.step(th, None, &mut a, Rates::none()).unwrap();
        t32.step(th as f32, None, &mut b, Rates::none()).unwrap();
        for i in 0..5 {
            worst = worst.max((a[i] - b[i].cast::<f64>()).norm());
        }
    }
    // Coordinates up to ~50 mm; f32 ε = 1.2e-7, so a few ε·50 ≈ 2e-5 mm plus crank-angle
    // rounding (θ to f32 is 2.4e-7 rad, times the foot's lever ~ 100 mm).
    assert!(worst < 1e-4, "worst f32 error {worst:e} mm");
    println!("f32 against f64, Hoecken over a turn: largest difference {worst:.2e} mm");
    assert!(
        worst > 0.0,
        "f32 sweep identical to f64 (worst {worst:e}): not computed in f32?"
    );
}

/// The general mechanism's tracker with rates: velocity of the crank pin is ω × r.
#[test]
fn tracker_rates_of_crank_pin() {
    let fb = linkage_core::catalog::hoecken::<f64>();
    let m: Mechanism<f64, 5> = fb.mechanism();
    let mut t = Tracker::new(&m).unwrap();
    let (mut j, mut v, mut a) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5], [Vec2::zeros(); 5]);
    let s = t
        .step(
            0.3,
            Some(CrankRates::new(2.0, 0.5)),
            &mut j,
            Rates::acceleration(&mut v, &mut a),
        )
        .unwrap();
    assert!(s.regular, "θ = 0.3 not regular: margin {:e}", s.margin);
    let r = j[2];
    let (v_want, a_want) = (
        Vec2::new(-r.y, r.x) * 2.0,
        Vec2::new(-r.y, r.x) * 0.5 - r * 4.0,
    );
    assert!(
        (v[2] - v_want).norm() < 1e-13,
        "crank pin velocity {:?} vs ω × r = {v_want:?}",
        v[2]
    );
    assert!(
        (a[2] - a_want).norm() < 1e-12,
        "crank pin acceleration {:?} vs α × r − ω²r = {a_want:?}",
        a[2]
    );
}
