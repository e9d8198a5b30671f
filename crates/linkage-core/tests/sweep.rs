//! The sweep engine (`linkage_core::sweep`) against the tracker it is built on and against
//! closed forms:
//!
//! - on random four-bars of every toggle class (parallelograms, kites, deltoids, general change
//!   points, crank-rockers, and linkages with locked zones) and the multi-loop catalogue, at
//!   random angles (jumps of many turns, NaN, repeats), every output equals, bit for bit, a
//!   sample-by-sample `Tracker::step` loop;
//! - instant centres equal Kennedy's line intersections; path curvature equals the curvature
//!   of central differences of the positions; rates equal central differences;
//! - `go_on` stops it between chunks, wrong slices are errors before anything is written, and
//!   the same code runs in `f32`.
//!
//! Cases per property: `LINKAGE_PROPTEST_CASES` (default 2000).

use linkage_core::{
    catalog, sweep, sweep_pairs, sweep_planned, Assembly, Bodies, Columns, CrankRates, Error,
    FourBar, Mechanism, Pairs, Plan, Rate, Rates, SweepOutputs, Swept, Tracker, Vec2, SWEEP_CHUNK,
};
use proptest::prelude::*;
use std::f64::consts::TAU;

mod common;

/// Every output of one sweep, in owned buffers.
#[derive(Debug, Clone, PartialEq)]
struct All<T> {
    joints: Vec<Vec2<T>>,
    valid: Vec<bool>,
    margin: Vec<T>,
    regular: Vec<bool>,
    gap: Vec<T>,
    velocity: Vec<Vec2<T>>,
    acceleration: Vec<Vec2<T>>,
    centres: Vec<Vec2<T>>,
    directions: Vec<Vec2<T>>,
    curvature_centres: Vec<Vec2<T>>,
    curvature: Vec<T>,
}

/// Buffers full of a sentinel (every one must be overwritten).
fn buffers(n: usize, j: usize, p: usize) -> All<f64> {
    let junk = Vec2::new(-12345.0, 6789.0);
    All {
        joints: vec![junk; n * j],
        valid: vec![true; n],
        margin: vec![-12345.0; n],
        regular: vec![true; n],
        gap: vec![-12345.0; n],
        velocity: vec![junk; n * j],
        acceleration: vec![junk; n * j],
        centres: vec![junk; n * p],
        directions: vec![junk; n * p],
        curvature_centres: vec![junk; n * j],
        curvature: vec![-12345.0; n * j],
    }
}

/// The engine with every output asked for.
fn engine<const N: usize>(
    m: &Mechanism<f64, N>,
    theta: &[f64],
    omega: Rate<'_, f64>,
    alpha: Rate<'_, f64>,
) -> All<f64> {
    engine_with(Plan::Auto, m, theta, omega, alpha).0
}

/// The engine on `plan`, with every output asked for; and whether the held pass swept it.
fn engine_with<const N: usize>(
    plan: Plan,
    m: &Mechanism<f64, N>,
    theta: &[f64],
    omega: Rate<'_, f64>,
    alpha: Rate<'_, f64>,
) -> (All<f64>, bool) {
    let mut b = buffers(theta.len(), m.len(), sweep_pairs(m));
    let out = SweepOutputs {
        columns: Columns::All,
        joints: &mut b.joints,
        valid: &mut b.valid,
        margin: Some(&mut b.margin),
        regular: Some(&mut b.regular),
        gap: Some(&mut b.gap),
        velocity: Some(&mut b.velocity),
        acceleration: Some(&mut b.acceleration),
        centres: Some(&mut b.centres),
        pairs: Pairs::All,
        centre_directions: Some(&mut b.directions),
        curvature_centres: Some(&mut b.curvature_centres),
        curvature: Some(&mut b.curvature),
    };
    let done = sweep_planned(m, theta, omega, alpha, out, &mut || true, plan).unwrap();
    assert_eq!(done.samples, theta.len(), "the sweep stopped early");
    (b, done.held)
}

/// The reference: one `Tracker::step` per sample, positions and rates only (what the sweep
/// must reproduce bit for bit), NaN rows where a sample fails.
fn reference<const N: usize>(
    m: &Mechanism<f64, N>,
    theta: &[f64],
    omega: &[f64],
    alpha: f64,
) -> All<f64> {
    let j = m.len();
    let nan = Vec2::new(f64::NAN, f64::NAN);
    let mut t = Tracker::new(m).unwrap();
    let (mut pos, mut vel, mut acc) = (vec![nan; j], vec![nan; j], vec![nan; j]);
    let (mut jp, mut jv, mut ja) = (Vec::new(), Vec::new(), Vec::new());
    let (mut valid, mut margin, mut gap, mut regular) = (vec![], vec![], vec![], vec![]);
    for (k, &th) in theta.iter().enumerate() {
        let motion = Some(CrankRates::new(omega[k], alpha));
        match t.step(
            th,
            motion,
            &mut pos,
            Rates::acceleration(&mut vel, &mut acc),
        ) {
            Ok(s) => {
                valid.push(true);
                margin.push(s.margin);
                regular.push(s.regular);
                gap.push(0.0);
                jp.extend_from_slice(&pos);
                jv.extend_from_slice(&vel);
                ja.extend_from_slice(&acc);
            }
            Err(e) => {
                valid.push(false);
                margin.push(f64::NAN);
                regular.push(false);
                gap.push(match e {
                    Error::CannotAssemble { gap, .. } => gap,
                    Error::Coincident { .. } | Error::NotFinite { .. } => f64::NAN,
                    other => panic!("unexpected {other:?}"),
                });
                for v in [&mut jp, &mut jv, &mut ja] {
                    v.extend(std::iter::repeat_n(nan, j));
                }
            }
        }
    }
    All {
        joints: jp,
        valid,
        margin,
        regular,
        gap,
        velocity: jv,
        acceleration: ja,
        centres: vec![],
        directions: vec![],
        curvature_centres: vec![],
        curvature: vec![],
    }
}

/// The held plan with positions (and `rates`) only, every joint or (`one`) the last one,
/// against the tracker's reference, bit for bit.
fn block_case<const N: usize>(
    m: &Mechanism<f64, N>,
    theta: &[f64],
    omega: &[f64],
    rates: bool,
    one: bool,
    centres: bool,
) -> Result<(), TestCaseError> {
    let (n, j) = (theta.len(), m.len());
    let w = if one { 1 } else { j };
    let mut got = buffers(n, w, sweep_pairs(m));
    let mut out = SweepOutputs::positions(&mut got.joints, &mut got.valid);
    out.columns = if one {
        Columns::One(j - 1)
    } else {
        Columns::All
    };
    out.margin = Some(&mut got.margin);
    out.regular = Some(&mut got.regular);
    out.gap = Some(&mut got.gap);
    if rates {
        out.velocity = Some(&mut got.velocity);
        out.acceleration = Some(&mut got.acceleration);
    }
    if centres {
        out.centres = Some(&mut got.centres);
        out.centre_directions = Some(&mut got.directions);
        out.curvature = Some(&mut got.curvature);
        out.curvature_centres = Some(&mut got.curvature_centres);
    }
    let plan = Plan::Held;
    sweep_planned(
        m,
        theta,
        Rate::PerSample(omega),
        Rate::Scalar(0.5),
        out,
        &mut || true,
        plan,
    )
    .unwrap();
    let want = reference(m, theta, omega, 0.5);
    let col = |v: &[Vec2<f64>]| -> Vec<Vec2<f64>> {
        if one {
            (0..n).map(|k| v[k * j + j - 1]).collect()
        } else {
            v.to_vec()
        }
    };
    prop_assert!(
        same_points(&got.joints, &col(&want.joints)),
        "joints: {}",
        point_difference(&got.joints, &col(&want.joints))
    );
    prop_assert_eq!(
        &got.valid,
        &want.valid,
        "validity: {}",
        flag_difference(&got.valid, &want.valid)
    );
    prop_assert!(
        same_floats(&got.margin, &want.margin),
        "margins: {}",
        float_difference(&got.margin, &want.margin)
    );
    prop_assert!(
        same_floats(&got.gap, &want.gap),
        "gaps: {}",
        float_difference(&got.gap, &want.gap)
    );
    if rates {
        prop_assert!(
            same_points(&got.velocity, &col(&want.velocity)),
            "velocities: {}",
            point_difference(&got.velocity, &col(&want.velocity))
        );
        prop_assert!(
            same_points(&got.acceleration, &col(&want.acceleration)),
            "accelerations: {}",
            point_difference(&got.acceleration, &col(&want.acceleration))
        );
        prop_assert_eq!(
            &got.regular,
            &want.regular,
            "regular flags: {}",
            flag_difference(&got.regular, &want.regular)
        );
    }
    if centres {
        // The sample-by-sample engine's centres and curvatures (they do not depend on the drive).
        let (tracked, _) = engine_with(
            Plan::Tracked,
            m,
            theta,
            Rate::PerSample(omega),
            Rate::Scalar(0.5),
        );
        prop_assert!(
            same_points(&got.centres, &tracked.centres),
            "centres vs the tracked plan: {}",
            point_difference(&got.centres, &tracked.centres)
        );
        prop_assert!(
            same_points(&got.directions, &tracked.directions),
            "centre directions vs the tracked plan: {}",
            point_difference(&got.directions, &tracked.directions)
        );
        let colf = |v: &[f64]| -> Vec<f64> {
            if one {
                (0..n).map(|k| v[k * j + j - 1]).collect()
            } else {
                v.to_vec()
            }
        };
        prop_assert!(
            same_floats(&got.curvature, &colf(&tracked.curvature)),
            "curvatures vs the tracked plan: {}",
            float_difference(&got.curvature, &colf(&tracked.curvature))
        );
        prop_assert!(
            same_points(&got.curvature_centres, &col(&tracked.curvature_centres)),
            "curvature centres vs the tracked plan: {}",
            point_difference(&got.curvature_centres, &col(&tracked.curvature_centres))
        );
    }
    Ok(())
}

/// Bitwise equality, NaN equal to NaN.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_points(a: &[Vec2<f64>], b: &[Vec2<f64>]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| same(p.x, q.x) && same(p.y, q.y))
}

fn same_floats(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(&p, &q)| same(p, q))
}

/// Where `a` and `b` first differ by `same`, with both values there (or their lengths): what a
/// failure message shows instead of two whole outputs.
fn first_difference<T: Copy + std::fmt::Debug>(
    a: &[T],
    b: &[T],
    same: impl Fn(T, T) -> bool,
) -> String {
    if a.len() != b.len() {
        return format!("lengths {} vs {}", a.len(), b.len());
    }
    match (0..a.len()).find(|&k| !same(a[k], b[k])) {
        Some(k) => format!("first at [{k}]: {:?} vs {:?}", a[k], b[k]),
        None => String::from("none"),
    }
}

fn point_difference(a: &[Vec2<f64>], b: &[Vec2<f64>]) -> String {
    first_difference(a, b, |p, q| same_points(&[p], &[q]))
}

fn float_difference(a: &[f64], b: &[f64]) -> String {
    first_difference(a, b, same)
}

fn flag_difference(a: &[bool], b: &[bool]) -> String {
    first_difference(a, b, |p, q| p == q)
}

/// A four-bar of one of the toggle classes: 0 parallelogram, 1 kite, 2 deltoid, 3 general
/// change point, 4 crank-rocker, 5 anything (often with locked zones). Lengths in multiples of
/// 1/64 so the change-point equalities hold exactly.
fn fourbar() -> impl Strategy<Value = FourBar<f64>> {
    (
        0usize..6,
        (4u32..58, 70u32..190, 70u32..190, 10u32..250),
        (-64i32..64, -64i32..64, 0.0f64..TAU),
        (-1.0f64..2.0, -1.0f64..1.0),
        any::<bool>(),
    )
        .prop_filter_map(
            "a four-bar that builds",
            |(kind, (r, a, b, x), (ox, oy, rot), (pa, pl), open)| {
                let q = |x: u32| x as f64 / 64.0;
                let (r, a, b, x) = (q(r), q(a), q(b), q(x));
                let (g, c, k) = match kind {
                    0 => (a, a, r),
                    1 => (r, a, a),
                    2 => (a, r, a),
                    3 => (a, b, a + b - r),
                    4 => (a, b, a.max(b) * 0.9 + 0.1 * (a + b - r).min(a.max(b))),
                    _ => (a, b, x),
                };
                let (g, r) = if kind == 1 { (r, r) } else { (g, r) };
                let o = Vec2::new(ox as f64 / 64.0, oy as f64 / 64.0);
                let cp = if kind == 5 {
                    o + Vec2::new(rot.cos(), rot.sin()) * g
                } else {
                    o + Vec2::new(g, 0.0)
                };
                let asm = if open {
                    Assembly::Open
                } else {
                    Assembly::Crossed
                };
                FourBar::with_pivots(o, cp, r, c, k, (pa * c, pl * c), asm).ok()
            },
        )
}

/// Sample angles: a walk of small and large steps (some of many turns), with NaN and repeats.
fn angles() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(
        prop_oneof![
            8 => -0.3f64..0.3,
            2 => -4.0f64..4.0,
            1 => -1e4f64..1e4,
            1 => Just(f64::NAN),
            1 => Just(0.0),
        ],
        1..60,
    )
    .prop_map(|steps| {
        let mut th = 0.3;
        steps
            .into_iter()
            .map(|s| {
                if s.is_nan() {
                    return f64::NAN;
                }
                th += s;
                th
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(common::config("tests/sweep.proptest-regressions"))]

    /// Positions, validity, margins, gaps and rates equal the tracker's, bit for bit, on
    /// every plan (the held pass where it applies).
    #[test]
    fn equals_the_tracker_on_four_bars(
        fb in fourbar(),
        theta in angles(),
        w in -3.0f64..3.0,
        held in any::<bool>(),
    ) {
        let m = fb.mechanism();
        let omega: Vec<f64> = (0..theta.len()).map(|k| w + 0.1 * k as f64).collect();
        let plan = if held { Plan::Held } else { Plan::Tracked };
        let (got, took) = engine_with(plan, &m, &theta, Rate::PerSample(&omega), Rate::Scalar(0.5));
        prop_assert!(held || !took, "the held pass ran on Plan::Tracked");
        let want = reference(&m, &theta, &omega, 0.5);
        prop_assert!(same_points(&got.joints, &want.joints), "joints: {}", point_difference(&got.joints, &want.joints));
        prop_assert!(same_points(&got.velocity, &want.velocity), "velocities: {}", point_difference(&got.velocity, &want.velocity));
        prop_assert!(same_points(&got.acceleration, &want.acceleration), "accelerations: {}", point_difference(&got.acceleration, &want.acceleration));
        prop_assert_eq!(&got.valid, &want.valid, "validity: {}", flag_difference(&got.valid, &want.valid));
        prop_assert_eq!(&got.regular, &want.regular, "regular flags: {}", flag_difference(&got.regular, &want.regular));
        prop_assert!(same_floats(&got.margin, &want.margin), "margins: {}", float_difference(&got.margin, &want.margin));
        prop_assert!(same_floats(&got.gap, &want.gap), "gaps: {}", float_difference(&got.gap, &want.gap));
        // Invalid samples: NaN in every row; valid ones: no sentinel left anywhere.
        let (j, p) = (m.len(), sweep_pairs(&m));
        for k in 0..theta.len() {
            let rows = [
                &got.joints[k * j..(k + 1) * j],
                &got.curvature_centres[k * j..(k + 1) * j],
                &got.centres[k * p..(k + 1) * p],
                &got.directions[k * p..(k + 1) * p],
            ];
            for row in rows {
                prop_assert!(row.iter().all(|q| q.x != -12345.0), "sample {k}: sentinel left in {row:?}");
                if !got.valid[k] {
                    prop_assert!(row.iter().all(|q| q.x.is_nan() && q.y.is_nan()), "invalid sample {k}: a row not NaN: {row:?}");
                }
            }
            prop_assert!(got.curvature[k * j..(k + 1) * j].iter().all(|&c| c != -12345.0), "sample {k}: sentinel left in curvatures {:?}", &got.curvature[k * j..(k + 1) * j]);
            prop_assert!(got.margin[k] != -12345.0 && got.gap[k] != -12345.0, "sample {k}: sentinel left: margin {}, gap {}", got.margin[k], got.gap[k]);
        }
    }

    /// The held pass's block paths (positions only; positions and rates; the trace point
    /// alone; with or without instant centres and curvatures) give the tracker's bits: every sample's row, flag and margin, on four-bars and
    /// on the catalogue's multi-loop linkages.
    #[test]
    fn block_paths_equal_the_tracker(
        fb in fourbar(),
        theta in prop_oneof![angles(), prop::collection::vec(-7.0f64..7.0, 1..80)],
        w in -3.0f64..3.0,
        which in 0usize..5,
        rates in any::<bool>(),
        one in any::<bool>(),
        centres in any::<bool>(),
    ) {
        let omega: Vec<f64> = (0..theta.len()).map(|k| w + 0.1 * k as f64).collect();
        if which == 4 {
            block_case(&fb.mechanism(), &theta, &omega, rates, one, centres)?;
        } else {
            let name = catalog::MULTI_LOOP[which];
            let m = catalog::linkage_by_name::<f64>(name).unwrap().mechanism;
            block_case(&m, &theta, &omega, rates, one, centres)?;
        }
    }

    /// Asking for fewer outputs changes none of the ones asked for.
    #[test]
    fn outputs_do_not_depend_on_what_else_is_asked(fb in fourbar(), theta in angles()) {
        let m = fb.mechanism();
        let all = engine(&m, &theta, Rate::Scalar(1.3), Rate::Scalar(-0.2));
        let mut b = buffers(theta.len(), m.len(), sweep_pairs(&m));
        let out = SweepOutputs {
            columns: Columns::All,
            joints: &mut b.joints,
            valid: &mut b.valid,
            margin: Some(&mut b.margin),
            regular: Some(&mut b.regular),
            gap: Some(&mut b.gap),
            velocity: None,
            acceleration: None,
            centres: Some(&mut b.centres),
            pairs: Pairs::All,
            centre_directions: None,
            curvature_centres: None,
            curvature: Some(&mut b.curvature),
        };
        sweep(&m, &theta, Rate::Scalar(1.3), Rate::Scalar(-0.2), out, &mut || true).unwrap();
        prop_assert!(same_points(&b.joints, &all.joints), "joints with fewer outputs asked: {}", point_difference(&b.joints, &all.joints));
        prop_assert!(same_points(&b.centres, &all.centres), "centres with fewer outputs asked: {}", point_difference(&b.centres, &all.centres));
        prop_assert!(same_floats(&b.curvature, &all.curvature), "curvatures with fewer outputs asked: {}", float_difference(&b.curvature, &all.curvature));
        prop_assert!(same_floats(&b.margin, &all.margin), "margins with fewer outputs asked: {}", float_difference(&b.margin, &all.margin));
        // Untouched outputs stay untouched.
        prop_assert!(b.velocity.iter().all(|q| q.x == -12345.0), "velocity written though not asked for: {:?}", b.velocity.iter().find(|q| q.x != -12345.0));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Centres asked for some pairs only (any order, either order within a pair, repeats) are
    /// the bits of those pairs in an every-pair sweep, on the held pass and on the tracker, on
    /// four-bars and on the catalogue's multi-loop linkages; and nothing else is written.
    #[test]
    fn chosen_pairs_are_those_of_every_pair(
        fb in fourbar(),
        theta in prop_oneof![angles(), prop::collection::vec(-7.0f64..7.0, 1..80)],
        which in 0usize..5,
        picks in prop::collection::vec((0usize..64, 0usize..64), 1..6),
        plan in prop_oneof![Just(Plan::Auto), Just(Plan::Tracked), Just(Plan::Held)],
    ) {
        let m = if which == 4 {
            fb.mechanism().resized::<16>().unwrap()
        } else {
            catalog::linkage_by_name::<f64>(catalog::MULTI_LOOP[which]).unwrap().mechanism
        };
        let nb = Bodies::of(&m).count();
        let pairs: Vec<[usize; 2]> = picks
            .iter()
            .map(|&(a, d)| [a % nb, (a + 1 + d % (nb - 1)) % nb])
            .collect();
        let (all, _) = engine_with(plan, &m, &theta, Rate::Scalar(0.7), Rate::Scalar(0.0));
        let np_all = sweep_pairs(&m);
        let index = |[a, b]: [usize; 2]| {
            let (k, l) = (a.min(b), a.max(b));
            k * nb - k * (k + 1) / 2 + (l - k - 1)
        };
        let n = theta.len();
        let mut b = buffers(n, m.len(), pairs.len());
        let mut out = SweepOutputs::positions(&mut b.joints, &mut b.valid);
        out.centres = Some(&mut b.centres);
        out.centre_directions = Some(&mut b.directions);
        out.pairs = Pairs::Only(&pairs);
        sweep_planned(&m, &theta, Rate::Scalar(0.7), Rate::Scalar(0.0), out, &mut || true, plan).unwrap();
        for k in 0..n {
            for (q, &pair) in pairs.iter().enumerate() {
                let e = k * np_all + index(pair);
                let got = (b.centres[k * pairs.len() + q], b.directions[k * pairs.len() + q]);
                let want = (all.centres[e], all.directions[e]);
                prop_assert!(same_points(&[got.0, got.1], &[want.0, want.1]), "sample {k}, pair {pair:?}: {got:?}, every-pair sweep {want:?}");
            }
        }
        prop_assert!(same_points(&b.joints, &all.joints), "joints: {}", point_difference(&b.joints, &all.joints));
        prop_assert!(b.velocity.iter().all(|q| q.x == -12345.0), "velocity written though not asked for");
    }
}

/// A pair naming no body, or one body twice, is an error and nothing is written.
#[test]
fn bad_pairs_are_errors() {
    let m = catalog::hoecken::<f64>().mechanism();
    for (pairs, want) in [
        (
            [[0, 4]],
            Error::OutOfRange {
                what: "body of an instant-centre pair",
                value: 4,
                max: 3,
            },
        ),
        (
            [[2, 2]],
            Error::InvalidChoice {
                what: "instant-centre pair",
                choices: "two different bodies",
            },
        ),
    ] {
        let mut b = buffers(2, 5, 1);
        let mut out = SweepOutputs::positions(&mut b.joints, &mut b.valid);
        out.centres = Some(&mut b.centres);
        out.pairs = Pairs::Only(&pairs);
        let r = sweep(
            &m,
            &[0.0, 1.0],
            Rate::Scalar(0.0),
            Rate::Scalar(0.0),
            out,
            &mut || true,
        );
        assert_eq!(r.unwrap_err(), want, "pairs {pairs:?}");
        assert!(b.joints.iter().all(|p| p.x == -12345.0), "joints written");
    }
}

/// Curvatures asked for alone (no margin, regular, rates or centres, so the held pass skips
/// the margins of unwatched dyads): the same bits on the held pass as on the tracker, for the
/// Hoecken leg and the multi-loop catalogue.
#[test]
fn curvature_alone_equals_the_tracker() {
    let theta: Vec<f64> = (0..700).map(|k| -2.0 + 0.013 * k as f64).collect();
    let run = |m: &Mechanism<f64, 16>, plan: Plan| {
        let (n, j) = (theta.len(), m.len());
        let mut b = buffers(n, j, 0);
        let mut out = SweepOutputs::positions(&mut b.joints, &mut b.valid);
        out.curvature = Some(&mut b.curvature);
        out.curvature_centres = Some(&mut b.curvature_centres);
        let zero = Rate::Scalar(0.0);
        let done = sweep_planned(m, &theta, zero, zero, out, &mut || true, plan).unwrap();
        (b, done.held)
    };
    let hoecken = FourBar::new(20.0, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    let mut mechs = vec![("hoecken", hoecken.mechanism().resized::<16>().unwrap())];
    for name in catalog::MULTI_LOOP {
        let m = catalog::linkage_by_name::<f64>(name).unwrap().mechanism;
        mechs.push((name, m.resized::<16>().unwrap()));
    }
    let mut swept_held = Vec::new();
    for (name, m) in &mechs {
        let (held, was_held) = run(m, Plan::Held);
        let (tracked, _) = run(m, Plan::Tracked);
        if was_held {
            swept_held.push(*name);
        }
        assert!(
            same_floats(&held.curvature, &tracked.curvature),
            "{name}: curvatures differ"
        );
        assert!(
            same_points(&held.curvature_centres, &tracked.curvature_centres),
            "{name}: centres of curvature differ"
        );
        assert!(
            same_points(&held.joints, &tracked.joints),
            "{name}: joints differ"
        );
    }
    // (linkages that come near a toggle are swept by the tracker under either plan)
    assert!(
        swept_held.contains(&"hoecken") && swept_held.len() >= 2,
        "the held pass swept only {swept_held:?}"
    );
}

/// The multi-loop catalogue, over several turns with a jump and a NaN: the same bits as the
/// tracker loop.
#[test]
fn equals_the_tracker_on_the_catalogue() {
    let mut theta: Vec<f64> = (0..2000).map(|k| -3.0 + 0.011 * k as f64).collect();
    theta.extend([f64::NAN, 1e9, 1e9 + 0.25, -40.0]);
    let omega: Vec<f64> = (0..theta.len()).map(|k| (k as f64 * 0.37).sin()).collect();
    let mut held = Vec::new();
    for name in catalog::MULTI_LOOP {
        let l = catalog::linkage_by_name::<f64>(name).unwrap();
        let m = &l.mechanism;
        let (got, took) = engine_with(
            Plan::Held,
            m,
            &theta,
            Rate::PerSample(&omega),
            Rate::Scalar(0.25),
        );
        held.push(took);
        let (tracked, _) = engine_with(
            Plan::Tracked,
            m,
            &theta,
            Rate::PerSample(&omega),
            Rate::Scalar(0.25),
        );
        assert!(same_points(&got.centres, &tracked.centres), "{name}");
        assert!(same_floats(&got.curvature, &tracked.curvature), "{name}");
        let want = reference(m, &theta, &omega, 0.25);
        assert!(same_points(&got.joints, &want.joints), "{name}");
        assert!(same_points(&got.velocity, &want.velocity), "{name}");
        assert!(same_points(&got.acceleration, &want.acceleration), "{name}");
        assert_eq!(got.valid, want.valid, "{name}");
        assert_eq!(got.regular, want.regular, "{name}");
        assert!(same_floats(&got.margin, &want.margin), "{name}");
        assert!(same_floats(&got.gap, &want.gap), "{name}");
    }
    // The held pass applies to the full-turn ones (so the comparison above tests it):
    // Jansen's crank-pin dyads have no flat position, and its others stay clear of toggles.
    assert_eq!(
        catalog::MULTI_LOOP[2..],
        ["hoecken_pantograph", "jansen"],
        "order of the multi-loop catalogue"
    );
    assert_eq!(
        held,
        [false, false, true, true],
        "held pass per linkage of {:?}",
        catalog::MULTI_LOOP
    );
}

/// 10⁵ angles in arbitrary order on linkages clear of toggles: the held pass sweeps them
/// (one pose per sample, no walk) and gives the tracker's bits; a change point is tracked.
#[test]
fn held_pass_on_arbitrary_angles() {
    let mut x = 0x2545_f491_4f6c_dd1d_u64;
    let theta: Vec<f64> = (0..100_000)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 40.0 - 20.0
        })
        .collect();
    let hoecken = catalog::hoecken::<f64>().mechanism();
    let omega = Rate::Scalar(2.0);
    let (got, held) = engine_with(Plan::Auto, &hoecken, &theta, omega, Rate::Scalar(0.0));
    assert!(held, "Hoecken over arbitrary angles not held");
    let want = reference(&hoecken, &theta, &[2.0; 100_000], 0.0);
    assert!(
        same_points(&got.joints, &want.joints),
        "joints: {}",
        point_difference(&got.joints, &want.joints)
    );
    assert!(
        same_points(&got.velocity, &want.velocity),
        "velocities: {}",
        point_difference(&got.velocity, &want.velocity)
    );
    assert!(
        same_points(&got.acceleration, &want.acceleration),
        "accelerations: {}",
        point_difference(&got.acceleration, &want.acceleration)
    );
    assert!(
        same_floats(&got.margin, &want.margin),
        "margins: {}",
        float_difference(&got.margin, &want.margin)
    );
    assert_eq!(
        got.regular,
        want.regular,
        "regular flags: {}",
        flag_difference(&got.regular, &want.regular)
    );
    // A parallelogram passes flat positions: its orientation is in closed form (turned at
    // each one crossed), so the held pass poses it too, with the tracker's bits; also at 2⁻⁴⁰
    // of the size, outside the block kernel's sizes, where it is posed one by one.
    for scale in [1.0, 2f64.powi(-40)] {
        let par = FourBar::new(
            3.0 * scale,
            scale,
            3.0 * scale,
            scale,
            (1.5 * scale, 0.0),
            Assembly::Open,
        );
        let par = par.unwrap().mechanism();
        let (got, held) = engine_with(Plan::Auto, &par, &theta, omega, Rate::Scalar(0.0));
        assert!(
            held,
            "a parallelogram ({scale}) over arbitrary angles not held"
        );
        let want = reference(&par, &theta, &[2.0; 100_000], 0.0);
        assert!(
            same_points(&got.joints, &want.joints) && got.valid == want.valid,
            "parallelogram ({scale}) joints: {}, validity: {}",
            point_difference(&got.joints, &want.joints),
            flag_difference(&got.valid, &want.valid)
        );
        // Every sample on the parallelogram (B − A = C − O), none on the antiparallelogram.
        let on_parallelogram = got
            .joints
            .chunks_exact(par.len())
            .all(|p| (p[3] - p[2] - Vec2::new(3.0 * scale, 0.0)).norm() < 1e-12 * scale);
        assert!(
            on_parallelogram,
            "a sample left the parallelogram ({scale})"
        );
    }
}

/// Intersection of the lines through `a`, `b` and through `c`, `d`.
fn meet(a: Vec2<f64>, b: Vec2<f64>, c: Vec2<f64>, d: Vec2<f64>) -> Vec2<f64> {
    let (u, v) = (b - a, d - c);
    let den = u.x * v.y - u.y * v.x;
    let t = ((c - a).x * v.y - (c - a).y * v.x) / den;
    a + u * t
}

/// Instant centres against Kennedy's construction, rates and curvature against central
/// differences of the positions, on a Hoecken linkage (joints O, C, A, B, P; bodies ground,
/// crank, coupler, rocker).
#[test]
fn centres_curvature_and_rates_match_closed_forms() {
    let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 8.0), Assembly::Open).unwrap();
    let m = fb.mechanism();
    assert_eq!(sweep_pairs(&m), 6, "body pairs of a four-bar");
    let h = 1e-4;
    let mut theta = Vec::new();
    for k in 0..40 {
        let t = 0.1 + TAU * k as f64 / 40.0;
        theta.extend([t - h, t, t + h]);
    }
    let (w, al) = (1.7, 0.3);
    let got = engine(&m, &theta, Rate::Scalar(w), Rate::Scalar(al));
    let j = m.len();
    for k in (1..theta.len()).step_by(3) {
        assert!(
            got.valid[k] && got.regular[k],
            "θ = {}: valid {}, regular {}",
            theta[k],
            got.valid[k],
            got.regular[k]
        );
        let p = |s: usize, i: usize| got.joints[s * j + i];
        let (o, c, a, b) = (p(k, 0), p(k, 1), p(k, 2), p(k, 3));
        let row = &got.centres[k * 6..k * 6 + 6];
        // Pairs: (g,crank)=O, (g,coupler)=OA∩CB, (g,rocker)=C, (crank,coupler)=A,
        // (crank,rocker)=AB∩OC, (coupler,rocker)=B.
        let want = [o, meet(o, a, c, b), c, a, meet(a, b, o, c), b];
        for (got, want) in row.iter().zip(want) {
            assert!(
                (got - want).norm() < 1e-9 * (1.0 + want.norm()),
                "{got} {want}"
            );
        }
        assert!(
            got.directions[k * 6..k * 6 + 6]
                .iter()
                .all(|d| d.x.is_nan()),
            "θ = {}: a centre at infinity, directions {:?}",
            theta[k],
            &got.directions[k * 6..k * 6 + 6]
        );
        for i in 0..j {
            let (pm, p0, pp) = (p(k - 1, i), p(k, i), p(k + 1, i));
            let d1 = (pp - pm) / (2.0 * h);
            let d2 = (pp - 2.0 * p0 + pm) / (h * h);
            // Rates: v = ω·dp/dθ, a = ω²·d²p/dθ² + α·dp/dθ.
            let v = got.velocity[k * j + i];
            let acc = got.acceleration[k * j + i];
            assert!(
                (v - d1 * w).norm() < 1e-6 * (1.0 + v.norm()),
                "velocity {i}"
            );
            assert!(
                (acc - (d2 * w * w + d1 * al)).norm() < 1e-4 * (1.0 + acc.norm()),
                "acceleration {i}"
            );
            let kappa = got.curvature[k * j + i];
            if d1.norm() < 1e-9 {
                // O and C are at rest: no curvature.
                assert!(
                    kappa.is_nan() || kappa == 0.0 || i < 2,
                    "joint {i} at rest at θ = {}: κ = {kappa}",
                    theta[k]
                );
                continue;
            }
            let fd = (d1.x * d2.y - d1.y * d2.x) / d1.norm().powi(3);
            assert!(
                (kappa - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                "curvature {i}"
            );
            let centre = got.curvature_centres[k * j + i];
            let normal = Vec2::new(-d1.y, d1.x) / d1.norm();
            let want = p0 + normal / fd;
            assert!(
                (centre - want).norm() < 1e-4 * (1.0 + want.norm()),
                "centre {i}"
            );
        }
    }
}

/// A parallelogram's coupler translates: its centre with the ground is at infinity,
/// perpendicular to the crank, and not written as a finite point.
#[test]
fn parallelogram_centre_at_infinity() {
    let fb = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.5, 0.0), Assembly::Open).unwrap();
    let m = fb.mechanism();
    let theta = [0.7, 1.9, 4.0];
    let got = engine(&m, &theta, Rate::Scalar(1.0), Rate::Scalar(0.0));
    for (k, &t) in theta.iter().enumerate() {
        assert!(got.valid[k], "θ = {t}: invalid");
        // (ground, coupler) is pair 1.
        assert!(
            got.centres[k * 6 + 1].x.is_nan(),
            "θ = {t}: I13 finite at {:?}",
            got.centres[k * 6 + 1]
        );
        let d = got.directions[k * 6 + 1];
        let crank = Vec2::new(t.cos(), t.sin());
        assert!(d.dot(&crank).abs() > 1.0 - 1e-9, "{d} {crank}");
    }
}

/// Samples in a locked zone are NaN rows with their gap; the others are unaffected.
#[test]
fn unassemblable_samples_are_nan_with_their_gap() {
    // Triple rocker: the crank cannot turn fully.
    let fb = FourBar::new(1.5_f64, 1.0, 0.9, 1.2, (0.5, 0.0), Assembly::Open).unwrap();
    let m = fb.mechanism();
    let theta = [0.0, 3.0, 0.5];
    let got = engine(&m, &theta, Rate::Scalar(1.0), Rate::Scalar(0.0));
    assert_eq!(got.valid, [true, false, true], "validity at θ = {theta:?}");
    assert!(
        got.gap[1] > 0.0 && got.gap[0] == 0.0,
        "gap {} at θ = 3 (locked), {} at θ = 0",
        got.gap[1],
        got.gap[0]
    );
    assert!(
        got.margin[1].is_nan() && !got.regular[1],
        "locked sample: margin {}, regular {}",
        got.margin[1],
        got.regular[1]
    );
    assert!(
        got.joints[5..10].iter().all(|p| p.x.is_nan()),
        "locked sample's joints {:?}",
        &got.joints[5..10]
    );
    assert!(
        got.velocity[5..10].iter().all(|p| p.x.is_nan()),
        "locked sample's velocities {:?}",
        &got.velocity[5..10]
    );
    assert!(
        got.curvature[5..10].iter().all(|c| c.is_nan()),
        "locked sample's curvatures {:?}",
        &got.curvature[5..10]
    );
}

#[test]
fn go_on_stops_between_chunks() {
    let fb = catalog::hoecken::<f64>();
    let m = fb.mechanism();
    let n = 3 * SWEEP_CHUNK;
    let theta: Vec<f64> = (0..n).map(|k| k as f64 * 1e-3).collect();
    let mut b = buffers(n, m.len(), 6);
    let mut calls = 0;
    let out = SweepOutputs {
        columns: Columns::All,
        joints: &mut b.joints,
        valid: &mut b.valid,
        margin: Some(&mut b.margin),
        regular: Some(&mut b.regular),
        gap: Some(&mut b.gap),
        velocity: None,
        acceleration: None,
        centres: None,
        pairs: Pairs::All,
        centre_directions: None,
        curvature_centres: None,
        curvature: None,
    };
    let done = sweep(
        &m,
        &theta,
        Rate::Scalar(0.0),
        Rate::Scalar(0.0),
        out,
        &mut || {
            calls += 1;
            calls < 2
        },
    )
    .unwrap();
    assert_eq!(calls, 2, "go_on calls, the second saying stop");
    assert_eq!(
        done.samples,
        2 * SWEEP_CHUNK,
        "samples swept before the stop"
    );
    assert!(
        b.valid[..done.samples].iter().all(|&v| v),
        "invalid samples before the stop: {:?}",
        (0..done.samples)
            .filter(|&k| !b.valid[k])
            .collect::<Vec<_>>()
    );
    // Rows after the stop are left as they were.
    assert!(
        b.joints[done.samples * 5..].iter().all(|p| p.x == -12345.0),
        "rows after the stop at sample {} written, first at {:?}",
        done.samples,
        b.joints[done.samples * 5..]
            .iter()
            .position(|p| p.x != -12345.0)
    );
}

#[test]
fn wrong_slices_are_errors_and_nothing_is_written() {
    let m = catalog::hoecken::<f64>().mechanism();
    let theta = [0.0, 1.0];
    let omega = [1.0, 2.0, 3.0];
    for case in 0..3 {
        let mut b = buffers(2, 5, 6);
        let (joints, velocity, w) = match case {
            0 => (&mut b.joints[..9], None, Rate::Scalar(1.0)),
            1 => (
                &mut b.joints[..],
                Some(&mut b.velocity[..3]),
                Rate::Scalar(1.0),
            ),
            _ => (&mut b.joints[..], None, Rate::PerSample(&omega[..])),
        };
        let out = SweepOutputs {
            columns: Columns::All,
            joints,
            valid: &mut b.valid,
            margin: Some(&mut b.margin),
            regular: Some(&mut b.regular),
            gap: Some(&mut b.gap),
            velocity,
            acceleration: None,
            centres: None,
            pairs: Pairs::All,
            centre_directions: None,
            curvature_centres: None,
            curvature: None,
        };
        let e = sweep(&m, &theta, w, Rate::Scalar(0.0), out, &mut || true).unwrap_err();
        assert!(matches!(e, Error::BufferLength { .. }), "{e:?}");
        assert!(
            b.joints.iter().all(|p| p.x == -12345.0),
            "case {case}: joints written, first at {:?}",
            b.joints.iter().position(|p| p.x != -12345.0)
        );
        assert!(
            b.valid.iter().all(|&v| v),
            "case {case}: validity written: {:?}",
            b.valid
        );
    }
    let none = Mechanism::<f64, 2>::new();
    let mut b = buffers(0, 0, 0);
    let out = SweepOutputs {
        columns: Columns::All,
        joints: &mut b.joints,
        valid: &mut b.valid,
        margin: Some(&mut b.margin),
        regular: Some(&mut b.regular),
        gap: Some(&mut b.gap),
        velocity: None,
        acceleration: None,
        centres: None,
        pairs: Pairs::All,
        centre_directions: None,
        curvature_centres: None,
        curvature: None,
    };
    let r = sweep(
        &none,
        &[],
        Rate::Scalar(0.0),
        Rate::Scalar(0.0),
        out,
        &mut || true,
    );
    assert_eq!(r, Err(Error::NoDriver), "a mechanism without a driver");
}

/// The same engine in `f32`: positions and velocities agree with `f64` to `f32` precision.
#[test]
fn runs_in_f32() {
    let m64 = catalog::jansen::<f64>().mechanism;
    let m32 = catalog::jansen::<f32>().mechanism;
    let theta: Vec<f64> = (0..200).map(|k| 0.05 * k as f64).collect();
    let theta32: Vec<f32> = theta.iter().map(|&t| t as f32).collect();
    let got = engine(&m64, &theta, Rate::Scalar(2.0), Rate::Scalar(0.0));
    let (n, j) = (theta.len(), m32.len());
    let z = Vec2::new(0.0f32, 0.0);
    let (mut joints, mut vel) = (vec![z; n * j], vec![z; n * j]);
    let (mut valid, mut regular) = (vec![false; n], vec![false; n]);
    let (mut margin, mut gap) = (vec![0.0f32; n], vec![0.0f32; n]);
    let out = SweepOutputs {
        columns: Columns::All,
        joints: &mut joints,
        valid: &mut valid,
        margin: Some(&mut margin),
        regular: Some(&mut regular),
        gap: Some(&mut gap),
        velocity: Some(&mut vel),
        acceleration: None,
        centres: None,
        pairs: Pairs::All,
        centre_directions: None,
        curvature_centres: None,
        curvature: None,
    };
    let done: Swept = sweep(
        &m32,
        &theta32,
        Rate::Scalar(2.0),
        Rate::Scalar(0.0),
        out,
        &mut || true,
    )
    .unwrap();
    assert_eq!(done.samples, n, "f32 samples swept");
    for k in 0..n * j {
        let (p, q) = (joints[k], got.joints[k]);
        assert!(
            ((p.x as f64) - q.x).abs() < 1e-3 && ((p.y as f64) - q.y).abs() < 1e-3,
            "f32 vs f64 joint [{k}]: {p:?} vs {q:?}"
        );
        let (v, u) = (vel[k], got.velocity[k]);
        assert!(
            ((v.x as f64) - u.x).abs() < 1e-2 * (1.0 + u.x.abs()),
            "f32 vs f64 velocity [{k}]: {v:?} vs {u:?}"
        );
    }
    assert_eq!(valid, got.valid, "validity f32 vs f64");
}

/// A program copied to a smaller capacity sweeps to the same bits; too small is an error.
#[test]
fn resized_mechanism_sweeps_the_same() {
    let big = catalog::jansen::<f64>().mechanism;
    let small = big.resized::<8>().unwrap();
    assert_eq!(
        small.constructions(),
        big.constructions(),
        "constructions at capacity 8"
    );
    assert_eq!(small.driver(), big.driver(), "driver at capacity 8");
    assert_eq!(
        big.resized::<4>().unwrap_err(),
        Error::CapacityExceeded { capacity: 4 },
        "Jansen at capacity 4"
    );
    let theta: Vec<f64> = (0..3000).map(|k| 0.37 * k as f64).collect();
    let a = engine(&big, &theta, Rate::Scalar(1.0), Rate::Scalar(0.1));
    let b = engine(&small, &theta, Rate::Scalar(1.0), Rate::Scalar(0.1));
    assert!(
        same_points(&a.joints, &b.joints),
        "joints, capacity 8 vs the original: {}",
        point_difference(&a.joints, &b.joints)
    );
    assert!(
        same_points(&a.acceleration, &b.acceleration),
        "accelerations, capacity 8 vs the original: {}",
        point_difference(&a.acceleration, &b.acceleration)
    );
    assert!(
        same_points(&a.centres, &b.centres),
        "centres, capacity 8 vs the original: {}",
        point_difference(&a.centres, &b.centres)
    );
    assert!(
        same_floats(&a.curvature, &b.curvature),
        "curvatures, capacity 8 vs the original: {}",
        float_difference(&a.curvature, &b.curvature)
    );
}
