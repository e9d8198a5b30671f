//! Property tests of the tracker at toggles and bifurcations: change-point linkages (the
//! parallelogram, kites, deltoids and general ones) swept through their flat positions.
//!
//! - sampling independence: a subset of the samples gives bit-identical poses on the common
//!   samples (the branch never depends on the sampling);
//! - a jump of many turns lands on the pose that walking every turn gives, and its work
//!   (placements, a counter, not a clock) is bounded whatever the jump;
//! - rates at and next to a flat position are either finite and equal to central differences
//!   of the positions, or NaN with the sample flagged — never a huge number.
//!
//! Cases per property: `LINKAGE_PROPTEST_CASES` (default 2000).

use linkage_core::{
    rate_margin, Assembly, CrankRates, FourBar, GrashofClass, Rates, Tracker, Vec2,
};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

mod common;

/// Placements a jump of any size may cost: Brent's cycle finding over turn boundaries walks at
/// most a few turns for a four-bar (its state at a turn boundary is its orientation at two grid
/// points), a turn costs at most 1024 grid placements and 64 coarse probes, and the partial
/// turns at both ends cost at most two more.
const JUMP_BOUND: u64 = 12 * (1024 + 64);

#[derive(Clone, Debug)]
struct Case {
    fb: FourBar<f64>,
    /// Crank angles (absolute) of the flat positions in one turn.
    flats: Vec<f64>,
    size: f64,
}

/// A change-point four-bar whose crank turns fully: `kind` 0 parallelogram, 1 kite (crank =
/// ground, coupler = rocker), 2 deltoid (crank = coupler, ground = rocker), 3 general (the
/// crank shortest, `s + l = p + q`), 4 a Grashof crank-rocker (no flat position). Scaled,
/// rotated and moved at random, either assembly.
fn linkage() -> impl Strategy<Value = Case> {
    (
        0usize..5,
        (0.1f64..0.9, 1.1f64..3.0, 1.1f64..3.0),
        (-1.0f64..1.0, -2.0f64..2.0, -2.0f64..2.0),
        (0.0f64..TAU, -5.0f64..5.0, -5.0f64..5.0),
        0usize..3,
        any::<bool>(),
    )
        .prop_filter_map(
            "a full-turn crank",
            |(kind, (fr, a, b), (lscale, pa, pl), (rot, ox, oy), perm, open)| {
                let scale = 10f64.powf(lscale);
                let r = fr;
                let (g, c, k) = match kind {
                    0 => (a, a, r),
                    1 => (r, a.max(r * 1.05), a.max(r * 1.05)),
                    2 => (a, r, a),
                    3 => {
                        let l = a + b - r;
                        match perm {
                            0 => (a, b, l),
                            1 => (b, l, a),
                            _ => (l, a, b),
                        }
                    }
                    _ => {
                        // crank-rocker: r + l < p + q
                        let l = a.max(b);
                        (a, b, l * 0.9 + 0.1 * (a + b - r).min(l))
                    }
                };
                let (g, r, c, k) = (g * scale, r * scale, c * scale, k * scale);
                let o = Vec2::new(ox, oy) * scale;
                let cp = o + Vec2::new(rot.cos(), rot.sin()) * g;
                let asm = if open {
                    Assembly::Open
                } else {
                    Assembly::Crossed
                };
                let fb = FourBar::with_pivots(o, cp, r, c, k, (pa * c, pl * c), asm).ok()?;
                let class = fb.grashof();
                if kind < 4 && class != GrashofClass::ChangePoint {
                    return None;
                }
                if kind == 4 && class != GrashofClass::CrankRocker {
                    return None;
                }
                let (delta, sigma) = ((c - k).abs(), c + k);
                let near =
                    |d: f64| (d - delta).abs() < 1e-9 * scale || (d - sigma).abs() < 1e-9 * scale;
                let mut flats = Vec::new();
                if near((g - r).abs()) {
                    flats.push(rot);
                }
                if near(g + r) {
                    flats.push(rot + PI);
                }
                Some(Case {
                    fb,
                    flats,
                    size: g + r + c + k,
                })
            },
        )
}

/// The classes of [`linkage`] with lengths and pivots in multiples of 1/64 and the ground on
/// the x axis, so that the change-point equality holds exactly in floating point: a linkage
/// that is a change point only to rounding has, within ~`√(ε)·size` of its flat position, an
/// avoided crossing whose rapid turn no finite difference resolves.
fn exact_linkage() -> impl Strategy<Value = Case> {
    (
        0usize..4,
        4u32..58,
        70u32..190,
        70u32..190,
        -64i32..64,
        -64i32..64,
        0usize..3,
        any::<bool>(),
    )
        .prop_filter_map(
            "a full-turn crank",
            |(kind, r, a, b, ox, oy, perm, open)| {
                let q = |x: u32| x as f64 / 64.0;
                let (r, a, b) = (q(r), q(a), q(b));
                let (g, c, k) = match kind {
                    0 => (a, a, r),
                    1 => (r, a, a),
                    2 => (a, r, a),
                    _ => {
                        let l = a + b - r;
                        match perm {
                            0 => (a, b, l),
                            1 => (b, l, a),
                            _ => (l, a, b),
                        }
                    }
                };
                let o = Vec2::new(ox as f64 / 64.0, oy as f64 / 64.0);
                let asm = if open {
                    Assembly::Open
                } else {
                    Assembly::Crossed
                };
                let fb = FourBar::with_pivots(
                    o,
                    o + Vec2::new(g, 0.0),
                    r,
                    c,
                    k,
                    (0.5 * c, 0.25 * c),
                    asm,
                )
                .ok()?;
                if fb.grashof() != GrashofClass::ChangePoint || fb.crank > g.min(c).min(k) {
                    return None;
                }
                let (delta, sigma) = ((c - k).abs(), c + k);
                let mut flats = Vec::new();
                if (g - r).abs() == delta || (g - r).abs() == sigma {
                    flats.push(0.0);
                }
                if g + r == delta || g + r == sigma {
                    flats.push(PI);
                }
                Some(Case {
                    fb,
                    flats,
                    size: g + r + c + k,
                })
            },
        )
}

type Pose = Option<[Vec2<f64>; 5]>;

fn sweep(fb: &FourBar<f64>, th: &[f64]) -> (Vec<Pose>, u64) {
    let m = fb.mechanism();
    let mut t = Tracker::new(&m).unwrap();
    let poses = th
        .iter()
        .map(|&x| {
            let mut j = [Vec2::zeros(); 5];
            t.step(x, None, &mut j, Rates::none()).ok().map(|_| j)
        })
        .collect();
    (poses, t.work())
}

/// Increasing samples from `start` over three turns, with every flat position and points
/// 1e-12 … 1e-3 rad on either side of it among them.
fn samples(case: &Case, start: f64, random: &[f64]) -> Vec<f64> {
    let mut th: Vec<f64> = random.iter().map(|u| start + u * 3.0 * TAU).collect();
    for turn in -1..4 {
        for &f in &case.flats {
            let base = f + turn as f64 * TAU;
            for o in [0.0, 1e-12, 1e-9, 1e-6, 1e-3] {
                th.extend([base - o, base + o]);
            }
        }
    }
    th.retain(|&x| x > start && x <= start + 3.0 * TAU);
    th.push(start);
    th.sort_by(f64::total_cmp);
    th.dedup();
    th
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/toggles.txt"))]

    /// Removing samples never changes the pose at the samples kept: bit for bit.
    #[test]
    fn sampling_independence(
        case in linkage(),
        start in -10.0f64..10.0,
        random in prop::collection::vec(0.0f64..1.0, 0..60),
        keep in prop::collection::vec(any::<bool>(), 200),
    ) {
        let th = samples(&case, start, &random);
        let (all, _) = sweep(&case.fb, &th);
        let sub: Vec<usize> = (0..th.len()).filter(|&i| i == 0 || keep[i % keep.len()]).collect();
        let th_sub: Vec<f64> = sub.iter().map(|&i| th[i]).collect();
        let (part, _) = sweep(&case.fb, &th_sub);
        for (q, &i) in sub.iter().enumerate() {
            match (all[i], part[q]) {
                (Some(a), Some(b)) => prop_assert!(a == b, "sample {} θ = {}: {:?} vs {:?}", i, th[i], a, b),
                (None, None) => {}
                (a, b) => prop_assert!(false, "θ = {}: {:?} vs {:?}", th[i], a, b),
            }
        }
    }

    /// A jump of `turns` whole turns (and a bit) lands where walking every turn lands, and
    /// costs a bounded number of placements whatever its size.
    #[test]
    fn jumps_are_periodic_and_bounded(
        case in linkage(),
        start in -10.0f64..10.0,
        turns in 3u32..40,
        bit in 0.0f64..TAU,
        huge in 1e3f64..1e9,
    ) {
        let end = start + turns as f64 * TAU + bit;
        let (jump, _) = sweep(&case.fb, &[start, end]);
        let walk: Vec<f64> = (0..=turns).map(|k| start + k as f64 * TAU).chain([end]).collect();
        let (walked, _) = sweep(&case.fb, &walk);
        let (a, b) = (jump[1].unwrap(), walked[walked.len() - 1].unwrap());
        for i in 0..5 {
            prop_assert!((a[i] - b[i]).norm() <= 1e-12 * case.size, "{:?} vs {:?}", a, b);
        }
        let m = case.fb.mechanism();
        let mut t = Tracker::new(&m).unwrap();
        let mut j = [Vec2::zeros(); 5];
        t.step(start, None, &mut j, Rates::none()).unwrap();
        for target in [start + huge, start - huge, start + 1e3 * huge] {
            let before = t.work();
            t.step(target, None, &mut j, Rates::none()).unwrap();
            let cost = t.work() - before;
            prop_assert!(cost <= JUMP_BOUND, "jump to {} cost {} placements", target, cost);
        }
    }

    /// At and next to flat positions: regular samples have finite rates equal to central
    /// differences of the positions (within the ε/margin² conditioning); flagged samples have
    /// NaN rates; no rate is ever huge.
    #[test]
    fn rates_at_toggles_are_right_or_flagged(case in exact_linkage(), which in 0usize..2, o in prop::sample::select(vec![0.0, 1e-14, 1e-12, 1e-9, 1e-7, 1e-6, 1e-4, 1e-2])) {
        prop_assume!(!case.flats.is_empty());
        let flat = case.flats[which % case.flats.len()] + TAU;
        let start = flat - 2.0;
        let h = 1e-5;
        let m = case.fb.mechanism();
        for th in [flat - o, flat + o] {
            // Positions at θ − h, θ, θ + h on one path (the branch does not depend on the
            // sampling, so the same as on separate paths).
            let mut t = Tracker::new(&m).unwrap();
            let mut p = [[Vec2::zeros(); 5]; 3];
            let mut v = [Vec2::zeros(); 5];
            let mut a = [Vec2::zeros(); 5];
            t.step(start, None, &mut p[0], Rates::none()).unwrap();
            let s = match t.step(th, Some(CrankRates::unit()), &mut p[1], Rates::acceleration(&mut v, &mut a)) {
                Ok(s) => s,
                Err(e) => {
                    // Only a kite's crank pin exactly on the rocker pivot is undetermined.
                    let pin = case.fb.o + Vec2::new(th.cos(), th.sin()) * case.fb.crank;
                    prop_assert!((pin - case.fb.c).norm() <= 1e-12 * case.size, "{:?} at θ = {}", e, th);
                    continue;
                }
            };
            let mut t2 = Tracker::new(&m).unwrap();
            t2.step(start, None, &mut p[0], Rates::none()).unwrap();
            t2.step(th - h, None, &mut p[0], Rates::none()).unwrap();
            // θ itself on the path too, as on the first one (it is a sample of its own there).
            t2.step(th + h, None, &mut p[2], Rates::none()).unwrap();
            for i in 2..5 {
                let fd = (p[2][i] - p[0][i]) / (2.0 * h);
                let vmax = 1e3 * case.size;
                if s.regular {
                    prop_assert!(v[i].x.is_finite() && v[i].y.is_finite() && a[i].x.is_finite(), "joint {i} θ = {th}: regular but rates not finite: {:?} {:?}", v[i], a[i]);
                    prop_assert!(v[i].norm() < vmax && a[i].norm() < 1e3 * vmax, "{:?} {:?}", v[i], a[i]);
                    let scale = fd.norm().max(case.fb.crank);
                    let cond = 16.0 * f64::EPSILON / (s.margin * s.margin);
                    // difference error h²·v‴/6 and rounding ε·size/h, plus the conditioning
                    let tol = (1e-6 + cond) * scale + 1e-10 * case.size;
                    prop_assert!((v[i] - fd).norm() <= tol, "joint {} θ = {} margin {:e}: {:?} vs {:?}", i, th, s.margin, v[i], fd);
                } else {
                    prop_assert!(s.margin < rate_margin::<f64>(), "θ = {th} flagged, margin {:e} not below rate_margin", s.margin);
                    prop_assert!(v[3].x.is_nan() && a[3].x.is_nan() && v[4].x.is_nan(), "θ = {th} flagged (margin {:e}) but rates not NaN: v3 {:?} a3 {:?} v4 {:?}", s.margin, v[3], a[3], v[4]);
                }
            }
        }
    }
}
