//! No panic anywhere in the public API, whatever the numbers: NaN, ±∞, subnormals, ±0, values
//! near the float maximum, huge and zero counts, empty and short slices, out-of-range indices.
//! Each property calls the API with such inputs and only requires that it returns (a value or a
//! typed error); a panic fails the test. A few plain tests check that results at float extremes
//! are right or a typed error, never a silently wrong value.
//!
//! Cases per property: `LINKAGE_PROPTEST_CASES` (default 2000).

use linkage_core::{
    catalog, circumcentre, convex_hull, inflection, instant_centre, line_intersection,
    path_curvature, relative_centre, stability_margin, straight_part, triangle_area, AngleMode,
    Assembly, Bodies, BodyId, BodyMotion, Construction, CrankRates, Dyad, Dynamics, Error,
    FlatFollower, FourBar, GearTrain, Inertia, InputRange, LineDirection, Load, Mechanism,
    Mobility, MotionLaw, Program, Rates, Reach, RollerFollower, ScheduleTable, Segment, Side,
    SliderDyad, Tracker, Vec2,
};
use proptest::prelude::*;

mod common;

/// Any float, weighted toward the awkward ones.
fn real() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => Just(f64::NAN),
        3 => Just(f64::INFINITY),
        3 => Just(f64::NEG_INFINITY),
        3 => Just(0.0),
        2 => Just(-0.0),
        3 => Just(f64::MAX),
        3 => Just(1e308),
        3 => Just(-1e308),
        3 => Just(5e-324),
        2 => Just(f64::MIN_POSITIVE),
        2 => Just(1e-300),
        4 => -100.0..100.0,
        4 => any::<f64>(),
    ]
}

/// Any count or index, weighted toward 0, small, and the extremes.
fn count() -> impl Strategy<Value = usize> {
    prop_oneof![
        4 => 0..12usize,
        2 => Just(usize::MAX),
        2 => Just(usize::MAX / 2 + 1),
        2 => any::<usize>(),
    ]
}

fn point() -> impl Strategy<Value = Vec2<f64>> {
    (real(), real()).prop_map(|(x, y)| Vec2::new(x, y))
}

fn points(max: usize) -> impl Strategy<Value = Vec<Vec2<f64>>> {
    prop::collection::vec(point(), 0..max)
}

fn side() -> impl Strategy<Value = Side> {
    prop_oneof![Just(Side::Left), Just(Side::Right)]
}

fn reach() -> impl Strategy<Value = Reach> {
    prop_oneof![Just(Reach::Ahead), Just(Reach::Behind)]
}

fn assembly() -> impl Strategy<Value = Assembly> {
    prop_oneof![Just(Assembly::Open), Just(Assembly::Crossed)]
}

fn law() -> impl Strategy<Value = Option<MotionLaw>> {
    prop_oneof![
        Just(None),
        (0..MotionLaw::ALL.len()).prop_map(|i| Some(MotionLaw::ALL[i]))
    ]
}

fn construction() -> impl Strategy<Value = Construction<f64>> {
    prop_oneof![
        point().prop_map(|at| Construction::Fixed { at }),
        (count(), real(), real()).prop_map(|(centre, radius, phase)| Construction::Crank {
            centre,
            radius,
            phase
        }),
        (count(), count(), real(), real(), side()).prop_map(|(p1, p2, r1, r2, side)| {
            Construction::Dyad {
                p1,
                p2,
                dyad: Dyad { r1, r2 },
                side,
            }
        }),
        (count(), count(), point(), real(), reach()).prop_map(|(pivot, origin, u, r, reach)| {
            Construction::Slider {
                pivot,
                origin,
                direction: LineDirection::Fixed(u),
                slider: SliderDyad { r },
                reach,
            }
        }),
        (count(), count(), count(), count(), real(), real(), reach()).prop_map(
            |(pivot, origin, from, to, angle, r, reach)| Construction::Slider {
                pivot,
                origin,
                direction: LineDirection::Link { from, to, angle },
                slider: SliderDyad { r },
                reach,
            }
        ),
        (count(), count(), real(), real()).prop_map(|(from, to, along, left)| {
            Construction::Point {
                from,
                to,
                along,
                left,
            }
        }),
    ]
}

/// A four-bar whose public fields hold anything (no validation).
fn raw_four_bar() -> impl Strategy<Value = FourBar<f64>> {
    (
        point(),
        point(),
        (real(), real(), real()),
        (real(), real()),
        assembly(),
    )
        .prop_map(
            |(o, c, (crank, coupler, rocker), (along, left), assembly)| FourBar {
                o,
                c,
                crank,
                coupler,
                rocker,
                along,
                left,
                assembly,
            },
        )
}

/// A mechanism built from arbitrary constructions (those the builder refuses are skipped), led
/// by two fixed joints and a crank half the time so that deeper code runs too.
fn mechanism() -> impl Strategy<Value = Mechanism<f64, 8>> {
    (
        any::<bool>(),
        prop::collection::vec(construction(), 0..8),
        (real(), real()),
    )
        .prop_map(|(lead, steps, (r, g))| {
            let mut m = Mechanism::<f64, 8>::new();
            if lead {
                let _ = m.fixed(Vec2::new(0.0, 0.0));
                let _ = m.fixed(Vec2::new(g, 0.0));
                let _ = m.crank(0, r, 0.0);
            }
            for c in steps {
                let _ = m.push(c);
            }
            m
        })
}

fn exercise_four_bar(fb: &FourBar<f64>, theta: f64, first: usize, n: usize, block: usize) {
    let _ = fb.ground();
    let _ = fb.grashof();
    let _ = fb.input_range();
    let _ = fb.pose(theta);
    let _ = fb.transmission_angle(theta);
    let _ = fb.instant_centres(theta);
    let _ = fb.coupler_inflection(theta);
    let _ = fb.circuit_sample(first, n);
    let _ = fb.circuit_sample(first % 8, n % 8);
    let _ = fb.mechanism();
    let k = n % 6;
    let mut th = vec![0.0; k];
    let mut j = vec![Vec2::zeros(); 5 * k];
    let mut v = vec![Vec2::zeros(); 5 * k];
    let _ = fb.circuit(&mut th, &mut j, Some(&mut v));
    let _ = fb.circuit(&mut th, &mut j[..(5 * k).saturating_sub(1)], None);
    let mut out = vec![Vec2::zeros(); n % 300];
    for mode in [
        AngleMode::Trig,
        AngleMode::Table { block },
        AngleMode::Recurrence { block },
    ] {
        let _ = fb.uniform_sweep(theta, theta * 1e-3, first, mode, &mut out);
        let _ = fb.uniform_sweep(theta, theta * 1e-3, first % 1000, mode, &mut out);
    }
}

fn exercise_mechanism(m: &Mechanism<f64, 8>, theta: f64, omega: f64, alpha: f64, idx: usize) {
    let n = m.len();
    let mut pos = vec![Vec2::zeros(); n];
    let _ = m.pose(theta, &mut pos);
    let _ = m.pose(theta, &mut vec![Vec2::zeros(); n + 1]);
    let mut vel = vec![Vec2::zeros(); n];
    let mut acc = vec![Vec2::zeros(); n];
    let mut jerk = vec![Vec2::zeros(); n];
    let drive = CrankRates {
        omega,
        alpha,
        jerk: omega,
    };
    let _ = m.rates(&pos, drive, &mut vel, Some(&mut acc), Some(&mut jerk));
    let _ = m.rates(&pos, drive, &mut vel, None, Some(&mut jerk));
    let bodies = Bodies::of(m);
    let mob = bodies.mobility();
    let _ = mob.degrees_of_freedom();
    let ids: Vec<BodyId> = bodies.ids().collect();
    let stray = BodyId {
        joint: idx,
        slot: (idx % 256) as u8,
    };
    let _ = bodies.frame(stray);
    let _ = bodies.contains(stray, idx);
    let _ = bodies.shared_joint(stray, ids[0]);
    let _ = bodies.carrier_of(bodies.frame(stray));
    let zero = vec![Vec2::zeros(); n];
    let short = pos[..n / 2].to_vec();
    let short = &short[..];
    for &id in ids.iter().chain([&stray]) {
        let mk = BodyMotion::of(&bodies, id, &pos, &vel, &acc, &zero);
        let ms = BodyMotion::of(&bodies, id, short, short, &[], &zero);
        let _ = instant_centre(&mk, &ms);
        let _ = inflection(&mk);
        let _ = inflection(&ms);
        let _ = relative_centre(&bodies, (id, &mk), (ids[0], &ms), short);
        let _ = mk.jerk_at(Vec2::new(theta, omega));
    }
    if let Ok(mut t) = Tracker::new(m) {
        let _ = t.branch(idx);
        t.set_branch(idx, theta);
        for k in 0..4 {
            let th = theta + k as f64 * alpha;
            let _ = t.step(th, Some(drive), &mut pos, Rates::none());
            let rates = Rates::acceleration(&mut vel, &mut acc);
            let _ = t.step(th, Some(drive), &mut pos, rates);
            let rates = Rates::velocity(&mut vel);
            let _ = t.step(th, None, &mut pos, rates);
            let _ = t.step(th, None, &mut pos[..n / 2], Rates::none());
        }
    }
    let _ = Tracker::with_settings(m, theta, omega);
    let inertia = vec![
        Inertia {
            mass: omega,
            along: alpha,
            left: theta,
            inertia: 1.0,
        };
        ids.len()
    ];
    if let Ok(d) = Dynamics::new(m, &inertia, Vec2::new(0.0, -9.81)) {
        let load = Load {
            body: stray,
            joint: idx,
            force: Vec2::new(omega, alpha),
            torque: theta,
        };
        let _ = d.solve(&pos, &vel, &acc, &[load]);
        let _ = d.solve(short, &vel, &acc, &[]);
        let _ = d.power_torque(&pos, &vel, &acc, &[load]);
        let _ = d.power_torque(&pos, short, &acc, &[]);
        let _ = d.reaction_layout().count();
    }
    let _ = Dynamics::new(m, &inertia[..inertia.len() / 2], Vec2::new(theta, omega));
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/no_panic.txt"))]

    #[test]
    fn four_bars_never_panic(
        ground in real(), crank in real(), coupler in real(), rocker in real(),
        along in real(), left in real(), asm in assembly(),
        theta in real(), first in count(), n in count(), block in count(),
        o in point(), c in point(),
    ) {
        if let Ok(fb) = FourBar::new(ground, crank, coupler, rocker, (along, left), asm) {
            exercise_four_bar(&fb, theta, first, n, block);
        }
        if let Ok(fb) = FourBar::with_pivots(o, c, crank, coupler, rocker, (along, left), asm) {
            exercise_four_bar(&fb, theta, first, n, block);
        }
    }

    #[test]
    fn unvalidated_four_bars_never_panic(
        fb in raw_four_bar(), theta in real(), first in count(), n in count(), block in count(),
    ) {
        exercise_four_bar(&fb, theta, first, n, block);
    }

    #[test]
    fn mechanisms_never_panic(
        m in mechanism(), theta in real(), omega in real(), alpha in real(), idx in count(),
    ) {
        exercise_mechanism(&m, theta, omega, alpha, idx);
    }

    #[test]
    fn solvers_and_centres_never_panic(
        p in point(), q in point(), r in point(), u in point(),
        a in real(), b in real(), c in real(), s in real(),
    ) {
        let _ = triangle_area(a, b, c, s);
        let _ = Dyad { r1: a, r2: b }.solve(p, q, s);
        let _ = Dyad::velocity(p, q, r, u, p);
        let _ = Dyad::acceleration(p, q, r, u, p, q, r, u);
        let _ = SliderDyad { r: a }.solve(p, q, u, s);
        let _ = SliderDyad::velocity(p, q, r, u, u, a, p);
        let _ = SliderDyad::acceleration(p, q, r, u, p, u, a, b, r, q, c);
        let _ = circumcentre(p, q, r);
        let _ = path_curvature(p, q, r);
        let _ = line_intersection(p, q, r, u);
    }

    #[test]
    fn drives_and_cams_never_panic(
        segs in prop::collection::vec((real(), real(), law()), 0..5),
        start in real(), t in real(), tol in real(), slots in 0..20usize,
        teeth in prop::collection::vec(any::<u32>(), 0..6),
        stages in prop::collection::vec((any::<u32>(), any::<u32>()), 0..80),
        (rb, rr, e) in (real(), real(), real()), y in (real(), real(), real()),
    ) {
        for law in MotionLaw::ALL {
            let _ = law.eval(t);
        }
        // Segments as the builder accepts them, and as any public fields can hold them.
        let checked: Vec<Segment<f64>> =
            segs.iter().filter_map(|&(d, r, l)| Segment::new(d, r, l).ok()).collect();
        let raw: Vec<Segment<f64>> =
            segs.iter().map(|&(duration, rise, law)| Segment { duration, rise, law }).collect();
        for segments in [&checked, &raw] {
            let p = Program { start, segments };
            let _ = p.eval(t);
            let _ = p.period();
            let _ = p.advance();
            let mut out = vec![
                linkage_core::Discontinuity { after: 0, order: 0, jump: 0.0 };
                slots
            ];
            let _ = p.discontinuities(tol, &mut out);
            for seg in segments.iter() {
                let _ = seg.eval(t);
            }
        }
        if let Ok(g) = GearTrain::simple(&teeth) {
            let _ = g.output_speed(t);
        }
        if let Ok(g) = GearTrain::compound(&stages) {
            prop_assert!(g.ratio() > 0.0 && g.ratio().is_finite(), "ratio {} of {} stages", g.ratio(), stages.len());
            let _ = g.output_speed(t);
        }
        let th: Vec<f64> = segs.iter().map(|s| s.0).collect();
        let w: Vec<f64> = segs.iter().map(|s| s.1).collect();
        if let Ok(table) = ScheduleTable::new(tol, start, &th, &w) {
            let _ = table.at(t);
            let _ = table.period();
        }
        let _ = ScheduleTable::new(tol, start, &th, &w[..w.len() / 2]);
        if let Ok(f) = RollerFollower::new(rb, rr, e) {
            let _ = f.point(t, [y.0, y.1, y.2]);
        }
        let _ = RollerFollower { base_radius: rb, roller_radius: rr, offset: e }
            .point(t, [y.0, y.1, y.2]);
        if let Ok(f) = FlatFollower::new(rb) {
            let _ = f.point(t, [y.0, y.1, y.2]);
        }
    }

    #[test]
    fn support_and_paths_never_panic(
        pts in points(12), cg in point(), room in 0..14usize, tol in real(), closed in any::<bool>(),
    ) {
        let mut work = pts.clone();
        let mut out = vec![Vec2::zeros(); room];
        match convex_hull(&mut work, &mut out) {
            Ok(h) => {
                prop_assert!(h <= out.len(), "hull of {h} points in a buffer of {}", out.len());
                let hull = &out[..h];
                prop_assert!(hull.iter().all(|p| p.x.is_finite() && p.y.is_finite()), "hull of {pts:?} has a non-finite point: {hull:?}");
                let _ = stability_margin(cg, hull);
            }
            Err(e) => prop_assert!(matches!(e, Error::BufferLength { .. }), "{e:?}"),
        }
        let _ = stability_margin(cg, &pts);
        let _ = straight_part(&pts, tol, closed);
    }

    #[test]
    fn catalogue_never_panics(scale in real(), name in 0..12usize) {
        if let Ok(l) = catalog::hoecken_pantograph::<f64>(scale) {
            let mut j = [Vec2::zeros(); 10];
            let _ = l.mechanism.pose(0.5, &mut j);
        }
        let _ = catalog::hoecken_pantograph::<f32>(scale as f32);
        let names = catalog::FOUR_BARS.iter().chain(catalog::MULTI_LOOP.iter());
        if let Some(name) = names.clone().nth(name) {
            let _ = catalog::four_bar_by_name::<f32>(name);
            let _ = catalog::linkage_by_name::<f32>(name);
        }
    }

    #[test]
    fn mobility_never_overflows(links in count(), lower in count(), higher in count()) {
        let _ = Mobility { links, lower_pairs: lower, higher_pairs: higher }.degrees_of_freedom();
    }
}

// Results at float extremes: right, or a typed error.

/// A Hoecken four-bar with every length multiplied by `s`.
fn hoecken(s: f64) -> FourBar<f64> {
    FourBar::new(
        20.0 * s,
        10.0 * s,
        25.0 * s,
        25.0 * s,
        (50.0 * s, 0.0),
        Assembly::Open,
    )
    .unwrap()
}

/// Evans B (a limited input range) with every length multiplied by `s`.
fn evans_b(s: f64) -> FourBar<f64> {
    FourBar::new(
        23.05 * s,
        10.0 * s,
        12.0 * s,
        11.67 * s,
        (15.0 * s, 0.0),
        Assembly::Open,
    )
    .unwrap()
}

#[test]
fn input_range_does_not_depend_on_scale() {
    let unit = evans_b(1.0).input_range();
    assert!(matches!(unit, InputRange::Between { .. }), "{unit:?}");
    // Powers of two scale exactly; 1e306 and 1e-300 round the lengths, so allow rounding.
    // (Subnormal lengths carry too few digits to expect the same range.)
    for s in [2f64.powi(1000), 1e306, 2f64.powi(-1000), 1e-300] {
        let (InputRange::Between { lo, hi }, InputRange::Between { lo: l1, hi: h1 }) =
            (evans_b(s).input_range(), unit)
        else {
            panic!("scale {s}: {:?}", evans_b(s).input_range());
        };
        assert!(
            (lo - l1).abs() < 1e-12 && (hi - h1).abs() < 1e-12,
            "scale {s}: {lo} {hi}"
        );
    }
    assert_eq!(
        hoecken(1e306).input_range(),
        InputRange::Full,
        "Hoecken at scale 1e306: input range"
    );
    assert_eq!(
        hoecken(1e306).grashof(),
        hoecken(1.0).grashof(),
        "Hoecken at scale 1e306: Grashof class"
    );
}

#[test]
fn program_with_overflowing_period_evaluates_where_asked() {
    // Two rises of 1 over 1e308 each: the period (2e308) overflows, but every time has a value.
    let segs = [
        Segment::new(1e308, 1.0, Some(MotionLaw::Cycloidal)).unwrap(),
        Segment::new(1e308, 1.0, Some(MotionLaw::Cycloidal)).unwrap(),
    ];
    let p = Program {
        start: 10.0,
        segments: &segs,
    };
    let at = |t: f64| p.eval(t)[0];
    assert_eq!(at(0.0), 10.0, "value at the start, t = 0");
    assert!((at(0.5e308) - 10.5).abs() < 1e-12, "{}", at(0.5e308));
    assert!((at(1.5e308) - 11.5).abs() < 1e-12, "{}", at(1.5e308));
    // Before the start: the end of the previous period, 0.5e308 before its end.
    assert!((at(-0.5e308) - 9.5).abs() < 1e-12, "{}", at(-0.5e308));
    let at_nan = p.eval(f64::NAN);
    assert!(at_nan.iter().all(|v| v.is_nan()), "at t = NaN: {at_nan:?}");
}

#[test]
fn segment_rates_at_tiny_durations_are_not_nan() {
    // d² and d³ underflow to 0 for d = 1e-200: a zero acceleration must stay 0, not 0/0.
    let s = Segment::new(1e-200_f64, 1.0, Some(MotionLaw::ConstantVelocity)).unwrap();
    let [y, v, a, j] = s.eval(0.5e-200);
    assert!((y - 0.5).abs() < 1e-15, "position at mid-segment: {y}");
    assert!(
        (v - 1e200).abs() < 1e185,
        "velocity {v:e} vs rise / duration = 1e200"
    );
    assert_eq!(
        (a, j),
        (0.0, 0.0),
        "acceleration and jerk of constant velocity at duration 1e-200"
    );
}

#[test]
fn gear_ratio_underflow_is_an_error() {
    let stages = [(1u32, 4_000_000_000u32); 40];
    let r = GearTrain::compound(&stages);
    assert!(
        matches!(r, Err(Error::NotRepresentable { .. })),
        "40 stages of 1:4e9: {r:?}"
    );
}

#[test]
fn pantograph_at_huge_scale_is_an_error_not_a_panic() {
    // 30·scale overflows: the arms cannot be built.
    for scale in [1e308, f64::MAX] {
        let r = catalog::hoecken_pantograph::<f64>(scale);
        assert!(
            matches!(r, Err(Error::NotRepresentable { .. })),
            "scale {scale:e}: {:?}",
            r.as_ref().map(|l| l.name)
        );
    }
    assert!(
        catalog::hoecken_pantograph::<f32>(1e38).is_err(),
        "an f32 pantograph at scale 1e38 was accepted"
    );
}

#[test]
fn hull_of_huge_coordinates_is_right() {
    // Orientation tests of these points overflow without scaling (differences of 2e308).
    let mut pts = [
        Vec2::new(1e308, 1e308),
        Vec2::new(-1e308, -1e308),
        Vec2::new(1e308, -1e308),
        Vec2::new(-1e308, 1e308),
        Vec2::new(0.0, 0.0),
        Vec2::new(f64::NAN, 1.0),
    ];
    let mut out = [Vec2::zeros(); 7];
    let h = convex_hull(&mut pts, &mut out).unwrap();
    assert_eq!(h, 4, "hull {:?}", &out[..h]);
    let m = stability_margin(Vec2::new(0.0, 0.0), &out[..h]).unwrap();
    assert_eq!(m, 1e308, "margin of the origin in the hull {:?}", &out[..h]);
    let m = stability_margin(Vec2::new(-1e308, 0.0), &out[..h]).unwrap();
    assert_eq!(m, 0.0, "margin of (−1e308, 0) in the hull {:?}", &out[..h]);
    // Too small an output buffer is an error, not a write past its end.
    let r = convex_hull(&mut pts, &mut out[..3]);
    assert!(
        matches!(r, Err(Error::BufferLength { .. })),
        "a 4-point hull into 3 slots: {r:?}"
    );
}

#[test]
fn sweep_index_overflow_is_an_error() {
    let mut out = [Vec2::zeros(); 4];
    let r = hoecken(1.0).uniform_sweep(0.0, 0.1, usize::MAX - 1, AngleMode::Trig, &mut out);
    assert!(
        matches!(r, Err(Error::CountOverflow { .. })),
        "4 samples from index usize::MAX − 1: {r:?}"
    );
    // Indices that end just below `usize::MAX`: the last anchor block would end past it (a
    // debug-build overflow before). The angles are ~1e18 rad, so the points are only finite.
    for mode in [
        AngleMode::Trig,
        AngleMode::Table { block: 256 },
        AngleMode::Recurrence { block: 256 },
    ] {
        let mut out = [Vec2::zeros(); 4];
        hoecken(1.0)
            .uniform_sweep(0.0, 0.1, usize::MAX - 4, mode, &mut out)
            .unwrap();
        assert!(out.iter().all(|p| p.x.is_finite()), "{mode:?}: {out:?}");
    }
}

#[test]
fn string_choices_round_trip() {
    for a in [Assembly::Open, Assembly::Crossed] {
        assert_eq!(
            a.name().parse::<Assembly>(),
            Ok(a),
            "{a:?} parsed from its name"
        );
        assert_eq!(a.to_string(), a.name(), "{a:?}: Display vs name");
    }
    for s in [Side::Left, Side::Right] {
        assert_eq!(
            s.name().parse::<Side>(),
            Ok(s),
            "{s:?} parsed from its name"
        );
        assert_eq!(s.to_string(), s.name(), "{s:?}: Display vs name");
    }
    // Exact names only: no case folding, no trimming.
    for bad in ["Open", " open", "", "left"] {
        let r = bad.parse::<Assembly>();
        assert!(
            matches!(
                r,
                Err(Error::InvalidChoice {
                    what: "assembly",
                    ..
                })
            ),
            "{bad:?}: {r:?}"
        );
    }
    let e = "up".parse::<Side>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "side must be 'left' or 'right'",
        "message of an invalid side"
    );
}

#[test]
fn periodic_drives_at_huge_times_keep_the_time_within_the_period() {
    // Schedule of period 0.2 (two samples 0.1 apart): at t = 1e17 + 0.05 the crank is a
    // quarter of a sample past a sample point; the rates must be those of that local time.
    let (theta, omega) = ([0.0, 1.0], [1.0, 1.0]);
    let table = ScheduleTable::new(0.1, core::f64::consts::TAU, &theta, &omega).unwrap();
    let t = 1e17_f64;
    let local = t % 0.2;
    let (_, w, a) = table.at(t);
    let (_, w0, a0) = table.at(local);
    assert_eq!(
        (w, a),
        (w0, a0),
        "rates at t = 1e17 vs at local time {local}"
    );
    // Beyond the float range the angle overflows (±∞), but the rates stay those of local time.
    let (th, w, a) = table.at(1e308);
    let (_, w0, a0) = table.at(1e308 % 0.2);
    assert!(th == f64::INFINITY && (w, a) == (w0, a0), "{th} {w} {a}");
    // A program of period 3 at t = 3e15 + 1.5 is in the middle of its second segment.
    let segs = [
        Segment::new(1.0, 1.0, Some(MotionLaw::Cycloidal)).unwrap(),
        Segment::new(2.0, -1.0, Some(MotionLaw::Cycloidal)).unwrap(),
    ];
    let p = Program {
        start: 0.0,
        segments: &segs,
    };
    let [_, v, _, _] = p.eval(3e15 + 1.5);
    let [_, v0, _, _] = p.eval(1.5);
    assert_eq!(v, v0, "velocity at t = 3e15 + 1.5 vs at 1.5");
}

#[test]
fn centres_do_not_depend_on_scale() {
    let c = |s: f64| circumcentre(Vec2::new(s, 0.0), Vec2::new(0.0, s), Vec2::new(-s, 0.0));
    for s in [1.0, 1e308, 5e-324, 1e-300, 1e300] {
        assert_eq!(
            c(s),
            linkage_core::Centre::Finite(Vec2::new(0.0, 0.0)),
            "scale {s}"
        );
    }
    // A needle triangle: measured from the wrong vertex its cross product cancels 9 digits.
    let c = circumcentre(
        Vec2::new(1e-9_f64, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(0.0, 0.0),
    );
    let linkage_core::Centre::Finite(c) = c else {
        panic!("{c:?}")
    };
    assert!((c - Vec2::new(5e-10, 1.0 - 5e-10)).amax() < 1e-15, "{c:?}");
    // A circle of radius 2e300 about the origin, traversed at speed 3e300.
    let (k, centre) = path_curvature(
        Vec2::new(2e300_f64, 0.0),
        Vec2::new(0.0, 3e300),
        Vec2::new(-4.5e300, 0.0),
    );
    assert!((k * 2e300 - 1.0).abs() < 1e-15, "{k}");
    let linkage_core::Centre::Finite(p) = centre else {
        panic!("{centre:?}")
    };
    assert!(p.amax() < 1e285, "{p:?}"); // (2e300 to the rounding of its digits)
    let (k, _) = path_curvature(
        Vec2::new(2e-300_f64, 0.0),
        Vec2::new(0.0, 3e-300),
        Vec2::new(-4.5e-300, 0.0),
    );
    assert!((k * 2e-300 - 1.0).abs() < 1e-15, "{k}");
}

#[test]
fn stability_margin_does_not_depend_on_scale() {
    let square = [
        Vec2::new(0.0_f64, 0.0),
        Vec2::new(2.0, 0.0),
        Vec2::new(2.0, 2.0),
        Vec2::new(0.0, 2.0),
    ];
    for s in [1.0, 1e-200, 1e200, 1e-300] {
        let mut pts = square.map(|p| p * s);
        let mut out = [Vec2::zeros(); 5];
        let h = convex_hull(&mut pts, &mut out).unwrap();
        assert_eq!(h, 4, "scale {s}");
        let m = stability_margin(Vec2::new(0.5, 1.0) * s, &out[..h]).unwrap();
        assert!((m / s - 0.5).abs() < 1e-15, "scale {s}: {m}");
    }
}

#[test]
fn rates_scale_with_the_linkage() {
    // Hoecken as a program at scale s, with a slider on the coupler line to reach rates.rs's
    // slider path too: velocities and accelerations per unit crank speed scale by s.
    let rates = |s: f64| {
        let mut m = Mechanism::<f64, 8>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let c = m.fixed(Vec2::new(20.0 * s, 0.0)).unwrap();
        let a = m.crank(o, 10.0 * s, 0.0).unwrap();
        let b = m.dyad(a, c, 25.0 * s, 25.0 * s, Side::Left).unwrap();
        let p = m.point(a, b, 50.0 * s, 0.0).unwrap();
        let dir = LineDirection::Fixed(Vec2::new(1.0, 0.0));
        m.slider(p, 60.0 * s, o, dir, Reach::Ahead).unwrap();
        let mut t = Tracker::new(&m).unwrap();
        let (mut pos, mut vel, mut acc) =
            ([Vec2::zeros(); 6], [Vec2::zeros(); 6], [Vec2::zeros(); 6]);
        let rates = Rates::acceleration(&mut vel, &mut acc);
        t.step(1.0, Some(CrankRates::new(1.0, 0.5)), &mut pos, rates)
            .unwrap();
        (vel, acc)
    };
    let (v0, a0) = rates(1.0);
    for s in [1e200, 1e-200, 1e300] {
        let (v, a) = rates(s);
        for k in 0..6 {
            for (got, want) in [(v[k] / s, v0[k]), (a[k] / s, a0[k])] {
                assert!(
                    (got - want).amax() <= 1e-12 * (1.0 + want.amax()),
                    "scale {s} joint {k}: {got:?} vs {want:?}"
                );
            }
        }
    }
}

#[test]
fn inflection_circle_beyond_the_float_range_is_none() {
    // D12: a subnormal crank made the inflection pole and radius infinite. A subnormal length
    // is refused now (issue 29); the smallest normal crank is the extreme left.
    assert!(
        matches!(
            FourBar::new(1.0_f64, 5e-324, 1.0, 1.0, (0.0, 0.0), Assembly::Open),
            Err(linkage_core::Error::SubnormalLength { .. })
        ),
        "a subnormal crank is refused"
    );
    let fb = FourBar::new(
        1.0_f64,
        f64::MIN_POSITIVE,
        1.0,
        1.0,
        (0.0, 0.0),
        Assembly::Open,
    )
    .unwrap();
    if let Some(i) = fb.coupler_inflection(0.0) {
        assert!(
            i.radius.is_finite() && i.centre.x.is_finite() && i.inflection_pole.y.is_finite(),
            "subnormal crank: radius {}, centre {:?}, inflection pole {:?}",
            i.radius,
            i.centre,
            i.inflection_pole
        );
    }
    assert!(
        hoecken(1.0).coupler_inflection(0.3).is_some(),
        "Hoecken at θ = 0.3 has no inflection circle"
    );
}
