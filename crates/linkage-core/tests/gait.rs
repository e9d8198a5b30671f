//! Leg figures (`gait.rs`) against hand-computed paths, the Hoecken leg's known figures, finite
//! differences and other samplings.

use core::f64::consts::PI;
use linkage_core::{Assembly, FourBar, FourBarBatch, FourBarGait, GaitScratch, LegGait, Vec2};

/// A "D" foot path over a turn of `n` (odd) samples: for θ < π the segment
/// `x = −1 + 2θ/π, y = 0` (rate `(2/π, 0)`), then the upper unit half circle
/// `(−cos θ, −sin θ)` back to the start (rate `(sin θ, −cos θ)`).
fn d_path(n: usize) -> (Vec<Vec2<f64>>, Vec<Vec2<f64>>) {
    (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            if t < PI {
                (
                    Vec2::new(-1.0 + 2.0 * t / PI, 0.0),
                    Vec2::new(2.0 / PI, 0.0),
                )
            } else {
                (Vec2::new(-t.cos(), -t.sin()), Vec2::new(t.sin(), -t.cos()))
            }
        })
        .unzip()
}

#[test]
fn segment_and_arc_by_hand() {
    for n in [9usize, 101, 721] {
        let (path, rate) = d_path(n);
        let mut stance = vec![false; n];
        // A tolerance below the first arc sample's height sin(π/n): the segment alone.
        let tol = 0.5 * (PI / n as f64).sin();
        let g = LegGait::measure(&path, &rate, tol, None, &mut stance).unwrap();
        let seg = n.div_ceil(2); // samples with θ < π (n odd)
        assert_eq!(
            (g.stance_count, g.stance_runs),
            (seg, 1),
            "n = {n}: stance count and runs"
        );
        assert_eq!(
            (g.stance_start, g.stance_longest),
            (0, seg),
            "n = {n}: stance start and longest run"
        );
        assert_eq!(g.duty_factor, seg as f64 / n as f64, "n = {n}: duty factor");
        // Last segment sample: θ = 2π(n−1)/(2n), x = −1 + 2(n−1)/n.
        let stride = 2.0 * (n - 1) as f64 / n as f64;
        assert!(
            (g.stride - stride).abs() < 1e-12,
            "{} vs {stride}",
            g.stride
        );
        // The highest sample is the one nearest θ = 3π/2, π/(2n) away (n odd).
        let lift = (PI / (2.0 * n as f64)).cos();
        assert!(
            (g.lift - lift).abs() < 1e-12,
            "n = {n}: lift {} vs {lift}",
            g.lift
        );
        assert!(
            g.straightness < 1e-15,
            "n = {n}: straightness {:e} of a straight segment",
            g.straightness
        );
        assert!(
            g.speed_variation.abs() < 1e-12,
            "n = {n}: speed variation {:e} at constant speed",
            g.speed_variation
        );
        assert!(
            (g.peak_torque - 2.0 / PI).abs() < 1e-15,
            "n = {n}: peak torque {} vs 2/π",
            g.peak_torque
        );
        // A tolerance that takes in the first arc sample, θ = π + π/n at height sin(π/n) (the
        // last sample, θ = 2π − 2π/n, is sin(2π/n) high).
        let tol = 0.5 * ((PI / n as f64).sin() + (2.0 * PI / n as f64).sin());
        let g = LegGait::measure(&path, &rate, tol, None, &mut stance).unwrap();
        assert_eq!(
            (g.stance_count, g.stance_runs),
            (seg + 1, 1),
            "n = {n}, tol {tol}: stance count and runs"
        );
        assert_eq!(
            (g.stance_start, g.stance_longest),
            (0, seg + 1),
            "n = {n}, tol {tol}: stance start and longest run"
        );
        // From x = −1 to the arc sample's x = −cos(π + π/n) = cos(π/n).
        let stride = 1.0 + (PI / n as f64).cos();
        assert!(
            (g.stride - stride).abs() < 1e-12,
            "n = {n}: stride {} vs {stride}",
            g.stride
        );
        // Its x rate sin(π + π/n) = −sin(π/n); the segment's 2/π.
        let (lo, hi) = (-(PI / n as f64).sin(), 2.0 / PI);
        let mean = (seg as f64 * hi + lo) / (seg + 1) as f64;
        assert!(
            (g.speed_variation - (hi - lo) / mean).abs() < 1e-12,
            "n = {n}: speed variation {} vs {}",
            g.speed_variation,
            (hi - lo) / mean
        );
        // |rate| = 1 on the arc.
        assert!(
            (g.peak_torque - 1.0).abs() < 1e-12,
            "n = {n}: peak torque {} vs 1",
            g.peak_torque
        );
        assert!(
            g.straightness > 0.0 && g.straightness <= tol,
            "n = {n}: straightness {:e} vs tol {tol:e}",
            g.straightness
        );
    }
}

#[test]
fn two_touchdowns_are_two_runs_and_bad_input_is_an_error() {
    // A path that comes down twice a turn: heights 0 1 0 1 (cyclic).
    let path: Vec<Vec2<f64>> = [0.0, 1.0, 0.0, 1.0]
        .iter()
        .enumerate()
        .map(|(k, &y)| Vec2::new(k as f64, y))
        .collect();
    let rate = vec![Vec2::new(1.0, 0.0); 4];
    let mut stance = vec![false; 4];
    let g = LegGait::measure(&path, &rate, 0.0, None, &mut stance).unwrap();
    assert_eq!(
        (g.stance_count, g.stance_runs, g.stance_longest),
        (2, 2, 1),
        "heights 0 1 0 1: stance count, runs, longest run"
    );
    assert_eq!(
        stance,
        [true, false, true, false],
        "heights 0 1 0 1: stance samples"
    );
    // A ground above every sample: all stance, one run.
    let g = LegGait::measure(&path, &rate, 0.0, Some(5.0), &mut stance).unwrap();
    assert_eq!(
        (g.stance_count, g.stance_runs, g.lift),
        (4, 1, -4.0),
        "ground at 5: stance count, runs, lift"
    );
    // No sample within tol of a ground far below: no stance, NaN stance figures.
    let g = LegGait::measure(&path, &rate, 0.0, Some(-5.0), &mut stance).unwrap();
    assert_eq!(
        (g.stance_count, g.duty_factor),
        (0, 0.0),
        "ground at −5: stance count and duty factor"
    );
    assert!(
        g.stride.is_nan() && g.speed_variation.is_nan(),
        "no stance: stride {}, speed variation {}",
        g.stride,
        g.speed_variation
    );
    assert!(
        LegGait::measure(&path, &rate, -1.0, None, &mut stance).is_err(),
        "tol −1 accepted"
    );
    assert!(
        LegGait::measure(&path, &rate, f64::NAN, None, &mut stance).is_err(),
        "tol NaN accepted"
    );
    assert!(
        LegGait::measure(&path, &rate[..3], 0.0, None, &mut stance).is_err(),
        "3 rates for 4 points accepted"
    );
    let mut bad = path.clone();
    bad[1].x = f64::NAN;
    assert!(
        LegGait::measure(&bad, &rate, 0.0, None, &mut stance).is_err(),
        "a NaN point accepted"
    );
    assert!(
        LegGait::<f64>::measure(&[], &[], 0.0, None, &mut []).is_err(),
        "an empty path accepted"
    );
}

fn hoecken() -> FourBar<f64> {
    FourBar::new(20.0, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap()
}

fn gait(fb: &FourBar<f64>, n: usize, rel_tol: f64) -> FourBarGait<f64> {
    let mut points = vec![Vec2::zeros(); 4 * n];
    let mut stance = vec![false; n];
    let mut scratch = GaitScratch {
        points: &mut points,
        stance: &mut stance,
    };
    fb.gait(n, rel_tol, &mut scratch).unwrap()
}

#[test]
fn hoecken_transmission_angle_and_the_quadruped_figures() {
    let fb = hoecken();
    // Smallest transmission angle at θ = 0 (B–D diagonal 10): cos μ = (625 + 625 − 100)/1250.
    let g = gait(&fb, 360, 2.5e-3);
    assert!(g.full_turn, "Hoecken's crank does not turn fully");
    let mu = (1150.0_f64 / 1250.0).acos();
    assert!(
        (g.min_transmission - mu).abs() < 1e-12,
        "{}",
        g.min_transmission
    );
    // The Python walker's quadruped (tests/test_walker.py): ground tolerance 0.1 mm gives a duty
    // factor 0.58 and a stride of 44.376 mm; the Hoecken swing rises 2√600 − 40 above the
    // stance line. The path's extent is its x span, 2·... — find the tolerance from it.
    let n = 1440;
    let g0 = gait(&fb, n, 0.0);
    let (path, rate) = path_and_rate(&fb, n);
    let mut stance = vec![false; n];
    let w = LegGait::measure(&path, &rate, 0.1, None, &mut stance).unwrap();
    assert!((w.duty_factor - 0.58).abs() < 0.005, "{}", w.duty_factor);
    assert!((w.stride - 44.376).abs() < 0.01, "{}", w.stride);
    assert!(
        (w.lift - (2.0 * 600f64.sqrt() - 40.0)).abs() < 1e-9,
        "lift {} vs 2√600 − 40",
        w.lift
    );
    assert_eq!(w.stance_runs, 1, "stance runs at tol 0.1");
    assert!(
        w.straightness <= 0.1,
        "straightness {} above tol 0.1",
        w.straightness
    );
    // The batch path with the same absolute tolerance gives the same figures.
    let extent = extent(&path);
    let b = gait(&fb, n, 0.1 / extent);
    assert_eq!(
        b.gait.stance_count, w.stance_count,
        "stance count: batch at rel_tol 0.1/{extent} vs LegGait at tol 0.1"
    );
    assert!(
        (b.gait.stride - w.stride).abs() < 1e-12,
        "stride: batch {} vs LegGait {}",
        b.gait.stride,
        w.stride
    );
    assert!(
        (b.gait.lift - w.lift).abs() < 1e-12,
        "lift: batch {} vs LegGait {}",
        b.gait.lift,
        w.lift
    );
    assert!(
        (g0.gait.lift - w.lift).abs() < 1e-12,
        "lift at tol 0: {} vs {}",
        g0.gait.lift,
        w.lift
    );
}

fn extent(path: &[Vec2<f64>]) -> f64 {
    let (mut lo, mut hi) = (path[0], path[0]);
    for p in path {
        lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    (hi.x - lo.x).max(hi.y - lo.y)
}

/// Foot points by `FourBar::pose` and rates by central differences of the closed form.
fn path_and_rate(fb: &FourBar<f64>, n: usize) -> (Vec<Vec2<f64>>, Vec<Vec2<f64>>) {
    let h = 1e-5;
    (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            let p = fb.pose(t).unwrap().coupler_point;
            let d = (fb.pose(t + h).unwrap().coupler_point - fb.pose(t - h).unwrap().coupler_point)
                / (2.0 * h);
            (p, d)
        })
        .unzip()
}

#[test]
fn rates_agree_with_finite_differences() {
    // The peak torque uses the closed-form rate: compare with central differences of the pose
    // over the stance, and the figures across sampling (360 vs 3600 samples).
    for fb in [
        hoecken(),
        FourBar::new(18.0, 7.0, 30.0, 22.0, (35.0, 8.0), Assembly::Crossed).unwrap(),
    ] {
        let (_, rate) = path_and_rate(&fb, 3600);
        let g = gait(&fb, 3600, 5e-3);
        let mut peak: f64 = 0.0;
        let mut points = vec![Vec2::zeros(); 4 * 3600];
        let mut stance = vec![false; 3600];
        let mut scratch = GaitScratch {
            points: &mut points,
            stance: &mut stance,
        };
        fb.gait(3600, 5e-3, &mut scratch).unwrap();
        for (k, v) in rate.iter().enumerate() {
            // Same closed-form rates: the scratch holds them after the foot and B points.
            let closed = scratch.points[2 * 3600 + k];
            assert!(
                (closed - v).norm() < 1e-6 * (1.0 + v.norm()),
                "{k}: {closed} vs {v}"
            );
            if scratch.stance[k] {
                peak = peak.max(v.norm());
            }
        }
        assert!(
            (g.gait.peak_torque - peak).abs() < 1e-6 * peak,
            "peak torque {} vs {peak} from differences, {fb:?}",
            g.gait.peak_torque
        );
        let coarse = gait(&fb, 360, 5e-3);
        assert!(
            (coarse.gait.duty_factor - g.gait.duty_factor).abs() < 2.0 / 360.0,
            "duty factor: 360 samples {} vs 3600 {}, {fb:?}",
            coarse.gait.duty_factor,
            g.gait.duty_factor
        );
        // Each end of the stance moves by less than one coarse step of the foot.
        let step = g.gait.peak_torque * 2.0 * PI / 360.0;
        assert!(
            (coarse.gait.stride - g.gait.stride).abs() < 2.0 * step,
            "stride: 360 samples {} vs 3600 {} (step {step}), {fb:?}",
            coarse.gait.stride,
            g.gait.stride
        );
        assert!(
            (coarse.gait.lift - g.gait.lift).abs() < 1e-3 * g.gait.lift,
            "lift: 360 samples {} vs 3600 {}, {fb:?}",
            coarse.gait.lift,
            g.gait.lift
        );
        assert!(
            (coarse.min_transmission - g.min_transmission).abs() < 1e-3,
            "min transmission: 360 samples {} vs 3600 {}, {fb:?}",
            coarse.min_transmission,
            g.min_transmission
        );
    }
}

#[test]
fn batch_rows_are_single_leg_figures_and_a_split_changes_no_bit() {
    let m = 40;
    let mut o = vec![];
    let mut c = vec![];
    let (mut crank, mut coupler, mut rocker, mut along, mut left) =
        (vec![], vec![], vec![], vec![], vec![]);
    for i in 0..m {
        let s = i as f64 / m as f64;
        o.push(Vec2::new(0.0, 0.0));
        c.push(Vec2::new(20.0 * (1.0 + 0.3 * s), 4.0 * s));
        crank.push(10.0);
        coupler.push(15.0 + 20.0 * s);
        rocker.push(25.0 - 10.0 * s);
        along.push(50.0 - 30.0 * s);
        left.push(10.0 * s - 3.0);
    }
    let assembly = vec![Assembly::Open; m];
    let batch = FourBarBatch {
        o: &o,
        c: &c,
        crank: &crank,
        coupler: &coupler,
        rocker: &rocker,
        along: &along,
        left: &left,
        assembly: &assembly,
    };
    let n = 360;
    let mut points = vec![Vec2::zeros(); 4 * n];
    let mut stance = vec![false; n];
    let mut scratch = GaitScratch {
        points: &mut points,
        stance: &mut stance,
    };
    let blank = gait(&hoecken(), 8, 0.0);
    let mut whole = vec![blank; m];
    batch.gaits(n, 2.5e-3, &mut scratch, &mut whole).unwrap();
    let mut parts = vec![blank; m];
    for (lo, hi) in [(0, 7), (7, 8), (8, m)] {
        batch
            .slice(lo..hi)
            .unwrap()
            .gaits(n, 2.5e-3, &mut scratch, &mut parts[lo..hi])
            .unwrap();
    }
    let mut full = 0;
    for i in 0..m {
        let one = gait(&batch.linkage(i).unwrap(), n, 2.5e-3);
        // Bit-identical (NaN figures compared by their bits).
        assert_eq!(
            format!("{:?}", whole[i]),
            format!("{:?}", one),
            "row {i}: batch vs single leg"
        );
        assert_eq!(
            format!("{:?}", whole[i]),
            format!("{:?}", parts[i]),
            "row {i}: whole batch vs split"
        );
        full += whole[i].full_turn as usize;
        if !whole[i].full_turn {
            assert!(
                whole[i].gait.stride.is_nan() && whole[i].min_transmission.is_nan(),
                "row {i} locks up, yet stride {} and min transmission {}",
                whole[i].gait.stride,
                whole[i].min_transmission
            );
        }
    }
    // The family mixes full-turn cranks and legs that lock up.
    assert!(full > 0 && full < m, "{full}");
    let mut short = vec![blank; m - 1];
    assert!(
        batch.gaits(n, 2.5e-3, &mut scratch, &mut short).is_err(),
        "{} gait slots for {m} rows accepted",
        short.len()
    );
    assert!(
        batch.gaits(n, -1.0, &mut scratch, &mut whole).is_err(),
        "rel_tol −1 accepted"
    );
}

#[test]
fn f32_legs_give_the_f64_figures_to_single_precision() {
    let fb32 = FourBar::new(20.0_f32, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    let n = 360;
    let mut points = vec![Vec2::<f32>::zeros(); 4 * n];
    let mut stance = vec![false; n];
    let mut scratch = GaitScratch {
        points: &mut points,
        stance: &mut stance,
    };
    let g32 = fb32.gait(n, 2.5e-3, &mut scratch).unwrap();
    let g64 = gait(&hoecken(), n, 2.5e-3);
    assert!(g32.full_turn, "f32 Hoecken's crank does not turn fully");
    // Measured: the same stance samples; the figures agree to f32 rounding of a 50 mm leg
    // (a height within f32 rounding of the band's edge could move one sample in another case).
    assert_eq!(
        g32.gait.stance_count, g64.gait.stance_count,
        "stance count: f32 vs f64"
    );
    for (what, x32, x64, tol) in [
        ("stride", g32.gait.stride, g64.gait.stride, 1e-4),
        ("lift", g32.gait.lift, g64.gait.lift, 1e-4),
        (
            "straightness",
            g32.gait.straightness,
            g64.gait.straightness,
            1e-5,
        ),
        (
            "speed variation",
            g32.gait.speed_variation,
            g64.gait.speed_variation,
            1e-5,
        ),
        (
            "min transmission",
            g32.min_transmission,
            g64.min_transmission,
            1e-5,
        ),
        (
            "peak torque",
            g32.gait.peak_torque,
            g64.gait.peak_torque,
            1e-3,
        ),
    ] {
        assert!(
            (f64::from(x32) - x64).abs() < tol,
            "{what}: f32 {x32} vs f64 {x64}"
        );
    }
}
