//! Golden values of the catalogue linkages, each with its source.

use linkage_core::catalog::{self, Linkage};
use linkage_core::{FourBar, GrashofClass, InputRange, Rates, Tracker, Vec2};
use std::f64::consts::PI;

/// Sweeps a catalogued mechanism over `n` angles in `[lo, hi]`, returning the trace points that
/// assembled.
fn trace(l: &Linkage<f64>, lo: f64, hi: f64, n: usize) -> Vec<Vec2<f64>> {
    let mut t = Tracker::new(&l.mechanism).unwrap();
    let mut j = vec![Vec2::zeros(); l.mechanism.len()];
    (0..n)
        .filter_map(|k| {
            let th = lo + (hi - lo) * k as f64 / (n - 1) as f64;
            t.step(th, None, &mut j, Rates::none())
                .ok()
                .map(|_| j[l.trace])
        })
        .collect()
}

/// Peaucellier: P is the inverse of A in the circle of radius √(40² − 20²) about D, and A runs on
/// a circle through D, so P runs on the line x = 1200/30 = 40 (docs/domain.md; any kinematics text).
#[test]
fn peaucellier_traces_exact_line() {
    let pts = trace(&catalog::peaucellier(), -1.68, 1.68, 2001);
    // Valid while 20 ≤ |DA| = 30|cos(θ/2)| ≤ 60, i.e. |θ| ≤ 2 acos(2/3) = 1.6821 rad.
    assert_eq!(pts.len(), 2001, "{} of 2001 samples assembled", pts.len());
    let dev = pts.iter().map(|p| (p.x - 40.0).abs()).fold(0.0, f64::max);
    let span = pts.iter().map(|p| p.y).fold(f64::MIN, f64::max)
        - pts.iter().map(|p| p.y).fold(f64::MAX, f64::min);
    assert!(dev < 1e-12, "deviation {dev:e} mm");
    assert!(span > 80.0, "span {span}");
}

/// Hart's inversor: O4, E and P stay collinear with |O4E|·|O4P| constant, E on a circle through
/// O4, so P runs on a line perpendicular to O2O4 (docs/domain.md). Here x = 7.5.
#[test]
fn hart_traces_exact_line() {
    let pts = trace(&catalog::hart(), -PI, PI, 4001);
    assert!(pts.len() > 500, "only {} samples assembled", pts.len());
    let dev = pts.iter().map(|p| (p.x - 7.5).abs()).fold(0.0, f64::max);
    assert!(dev < 1e-12, "deviation {dev:e} mm");
    let span = pts.iter().map(|p| p.y).fold(f64::MIN, f64::max)
        - pts.iter().map(|p| p.y).fold(f64::MAX, f64::min);
    assert!(span > 60.0, "span {span}");
}

/// Hoecken: hand-computed foot positions. At θ = 90°: A = (0, 10), |AC| = √500, B = (20, 25),
/// P = 2B − A = (40, 40); at 180°: B = (5, 20), P = (20, 40); at 270°: B = (0, 15), P = (0, 40);
/// at 0°: B = (15, √600), P = (20, 2√600). The straight part passes exactly through
/// (0, 40), (20, 40), (40, 40): a stride of 4 cranks.
#[test]
fn hoecken_foot_golden_points() {
    let fb = catalog::hoecken::<f64>();
    assert_eq!(
        fb.grashof(),
        GrashofClass::CrankRocker,
        "Hoecken's Grashof class"
    );
    assert_eq!(fb.input_range(), InputRange::Full, "Hoecken's input range");
    for (deg, x, y) in [
        (90.0, 40.0, 40.0),
        (180.0, 20.0, 40.0),
        (270.0, 0.0, 40.0),
        (0.0, 20.0, 2.0 * 600f64.sqrt()),
    ] {
        let p = fb.pose(f64::to_radians(deg)).unwrap().coupler_point;
        assert!((p - Vec2::new(x, y)).norm() < 1e-13, "{deg}°: {p:?}");
    }
    // Foot-path extent, one quantity two ways: the largest x over a dense sweep, and x where the
    // analytic velocity's x component vanishes (bisection). Symmetric about x = 20; the swing's
    // top is 2√600 at θ = 0.
    let m = fb.mechanism();
    let mut j = [Vec2::zeros(); 5];
    let (mut xmin, mut xmax, mut ymin, mut ymax, mut arg) =
        (f64::MAX, f64::MIN, f64::MAX, f64::MIN, 0.0);
    for k in 0..36000 {
        let th = 2.0 * PI * k as f64 / 36000.0;
        m.pose(th, &mut j).unwrap();
        let p = j[FourBar::<f64>::P];
        if p.x > xmax {
            arg = th;
        }
        (xmin, xmax, ymin, ymax) = (xmin.min(p.x), xmax.max(p.x), ymin.min(p.y), ymax.max(p.y));
    }
    let vx = |th: f64| {
        let mut j = [Vec2::zeros(); 5];
        let mut v = [Vec2::zeros(); 5];
        m.pose(th, &mut j).unwrap();
        m.rates(&j, linkage_core::CrankRates::unit(), &mut v, None, None)
            .unwrap();
        v[FourBar::<f64>::P].x
    };
    let (mut lo, mut hi) = (arg - 1e-3, arg + 1e-3);
    let (v_lo, v_hi) = (vx(lo), vx(hi));
    assert!(
        v_lo > 0.0 && v_hi < 0.0,
        "P's x velocity keeps its sign about θ = {arg}: {v_lo} at {lo}, {v_hi} at {hi}"
    );
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if vx(mid) > 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let x_root = fb.pose(lo).unwrap().coupler_point.x;
    // The sampled maximum is below the true one by at most ½|P''|(Δθ/2)² ≈ 1e-6 mm.
    assert!(x_root >= xmax && x_root - xmax < 1e-6, "{x_root} vs {xmax}");
    assert!((xmin + xmax - 40.0).abs() < 1e-9, "symmetric about x = 20");
    assert!(
        (ymax - 2.0 * 600f64.sqrt()).abs() < 1e-9,
        "ymax {ymax} vs 2√600"
    );
    // The path touches y = 40 at the three golden points and never dips below it.
    assert!((ymin - 40.0).abs() < 1e-12, "ymin {ymin}");
    // Between them (θ in 90°…270°) it bulges slightly above: the straight part's deviation.
    let bulge = (0..=18000)
        .map(|k| {
            fb.pose(PI / 2.0 + PI * k as f64 / 18000.0)
                .unwrap()
                .coupler_point
                .y
                - 40.0
        })
        .fold(0.0, f64::max);
    assert!(bulge > 0.0 && bulge < 0.1, "bulge {bulge}");
    println!("Hoecken straight part (θ 90°…270°, x 0…40): deviation {bulge:.6} mm");
    println!("Hoecken foot path: x {xmin:.6} … {xmax:.6}, y {ymin:.6} … {ymax:.6} mm");
}

/// Each catalogued four-bar's Grashof class: the source (thesis 1 ch. 1) calls Evans A/B/C triple
/// rockers, Chebyshev a double rocker and Hoecken a crank-rocker; Watt and Roberts by hand.
#[test]
fn catalogue_classes() {
    use GrashofClass::*;
    for (name, want) in [
        ("watt", TripleRocker),
        // 20 + 40 < 40 + 40 with the coupler shortest (no class is stated in the source).
        ("roberts", DoubleRocker),
        ("chebyshev", DoubleRocker),
        ("hoecken", CrankRocker),
        ("evans_a", TripleRocker),
        ("evans_b", TripleRocker),
        ("evans_c", TripleRocker),
    ] {
        let fb = catalog::four_bar_by_name::<f64>(name).unwrap();
        assert_eq!(fb.grashof(), want, "{name}");
    }
}

/// The pantograph output is the foot scaled by 2 about its pivot, at every sample.
#[test]
fn pantograph_scales_the_foot_path() {
    let l = catalog::hoecken_pantograph(2.0).unwrap();
    let mut t = Tracker::new(&l.mechanism).unwrap();
    let mut j = vec![Vec2::zeros(); l.mechanism.len()];
    for k in 0..720 {
        let th = 2.0 * PI * k as f64 / 720.0;
        t.step(th, None, &mut j, Rates::none()).unwrap();
        let q = j[5];
        let want = q + (j[4] - q) * 2.0;
        assert!(
            (j[l.trace] - want).norm() < 1e-11,
            "{k}: {:?} vs {want:?}",
            j[l.trace]
        );
    }
    assert!(
        catalog::hoecken_pantograph(1.0).is_err(),
        "a pantograph of scale 1 was accepted"
    );
    assert!(
        catalog::hoecken_pantograph(f64::NAN).is_err(),
        "a pantograph of scale NaN was accepted"
    );
}
