//! Roberts–Chebyshev cognates and the reversed drive: every point of a four-bar's coupler
//! curve is on each cognate's (and the reversed linkage's) at the crank angle the construction
//! says, on one of its two assemblies; random four-bars of every class, placements and points.

use linkage_core::{Assembly, FourBar, Vec2};
use proptest::prelude::*;

mod common;

/// Whether `fb` (either assembly) puts its coupler point within `1e-9·size` of `p` at `angle`,
/// or within the conditioning of its pose there: `angle` comes from a rounded pose of another
/// linkage, and near `fb`'s own toggle (margin `m`) an angle error of ε moves its joints by
/// about `ε·size/m` (16 of that allowed).
fn draws(fb: FourBar<f64>, angle: f64, p: Vec2<f64>, size: f64) -> bool {
    [Assembly::Open, Assembly::Crossed]
        .into_iter()
        .any(|assembly| {
            FourBar { assembly, ..fb }.pose(angle).is_ok_and(|q| {
                let conditioning = 16.0 * f64::EPSILON * size / q.margin.max(f64::MIN_POSITIVE);
                (q.coupler_point - p).norm() <= (1e-9 * size).max(conditioning)
            })
        })
}

fn fourbar() -> impl Strategy<Value = FourBar<f64>> {
    (
        (
            -50.0f64..50.0,
            -50.0f64..50.0,
            0.0f64..std::f64::consts::TAU,
        ),
        (0.2f64..3.0, 0.2f64..3.0, 0.2f64..3.0, 0.2f64..3.0),
        (-3.0f64..3.0, -3.0f64..3.0),
        any::<bool>(),
    )
        .prop_filter_map(
            "assembles",
            |((x, y, turn), (g, r, b, c), (u, v), crossed)| {
                let o = Vec2::new(x, y);
                let cpivot = o + Vec2::new(turn.cos(), turn.sin()) * g;
                let assembly = if crossed {
                    Assembly::Crossed
                } else {
                    Assembly::Open
                };
                let fb = FourBar::with_pivots(o, cpivot, r, b, c, (u * b, v * b), assembly).ok()?;
                // A coupler point away from A and B (a cognate's link would vanish there).
                let z = Vec2::new(u, v);
                let away = z.norm() > 1e-3 && (z - Vec2::new(1.0, 0.0)).norm() > 1e-3;
                (away && fb.pose(fb_angle(&fb)?).is_ok()).then_some(fb)
            },
        )
}

/// An angle at which `fb` assembles (mid-range), if any.
fn fb_angle(fb: &FourBar<f64>) -> Option<f64> {
    use linkage_core::InputRange;
    match fb.input_range() {
        InputRange::Full => Some(0.0),
        InputRange::Between { lo, hi } => Some(0.5 * (lo + hi)),
        InputRange::TwoIntervals {
            first: (lo, hi), ..
        } => Some(0.5 * (lo + hi)),
        InputRange::Never => None,
    }
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/cognates.txt"))]

    #[test]
    fn cognates_and_the_reversed_drive_draw_the_same_curve(fb in fourbar(), ts in prop::collection::vec(0.0f64..1.0, 24)) {
        let [first, second] = fb.cognates().unwrap();
        let reversed = fb.reversed().unwrap();
        let size = (fb.c - fb.o).norm().max(fb.crank).max(fb.coupler).max(fb.rocker)
            .max(fb.along.hypot(fb.left)) + fb.o.norm();
        prop_assert_eq!(first.o, fb.o, "the first cognate turns about O");
        prop_assert_eq!(second.o, fb.c, "the second cognate turns about C");
        prop_assert_eq!((reversed.o, reversed.c), (fb.c, fb.o), "the reversed drive swaps the pivots");
        let (lo, hi) = match fb.input_range() {
            linkage_core::InputRange::Full => (0.0, std::f64::consts::TAU),
            linkage_core::InputRange::Between { lo, hi } => (lo, hi),
            linkage_core::InputRange::TwoIntervals { first: (lo, hi), .. } => (lo, hi),
            linkage_core::InputRange::Never => unreachable!(),
        };
        for t in ts {
            let Ok(p) = fb.pose(lo + t * (hi - lo)) else { continue };
            // Toggle poses aside (the dyad's two solutions meet there, either is the pose).
            if p.margin < 1e-6 { continue }
            let (pa, pb, bc) = (p.coupler_point - p.a, p.coupler_point - p.b, p.b - fb.c);
            prop_assert!(draws(first, pa.y.atan2(pa.x), p.coupler_point, size), "first cognate {first:?} misses {:?}", p.coupler_point);
            prop_assert!(draws(second, pb.y.atan2(pb.x), p.coupler_point, size), "second cognate {second:?} misses {:?}", p.coupler_point);
            prop_assert!(draws(reversed, bc.y.atan2(bc.x), p.coupler_point, size), "reversed {reversed:?} misses {:?}", p.coupler_point);
        }
    }
}

/// A coupler point at a pin has no cognate (a link of no length): an error, not a panic.
#[test]
fn a_point_at_a_pin_has_no_cognates() {
    let degenerate = Err(linkage_core::Error::Degenerate {
        what: "coupler point at A or B: a cognate's link would have no length",
    });
    let at_a = FourBar::new(20.0, 10.0, 25.0, 25.0, (0.0, 0.0), Assembly::Open).unwrap();
    assert_eq!(at_a.cognates(), degenerate, "P at A");
    let at_b = FourBar::new(20.0, 10.0, 25.0, 25.0, (25.0, 0.0), Assembly::Open).unwrap();
    assert_eq!(at_b.cognates(), degenerate, "P at B");
    let never = FourBar::new(20.0, 1.0, 2.0, 2.0, (1.0, 1.0), Assembly::Open).unwrap();
    assert!(
        never.cognates().is_err() && never.reversed().is_err(),
        "never assembles"
    );
}

/// A rhombus (a change point, flat along the ground line) has cognates and a reversed drive:
/// the pose they are taken from is square to the ground line, not on a flat position.
#[test]
fn a_rhombus_has_cognates() {
    let fb = FourBar::new(1.0, 1.0, 1.0, 1.0, (0.3, 0.2), Assembly::Open).unwrap();
    assert!(fb.cognates().is_ok(), "{:?}", fb.cognates());
    assert!(fb.reversed().is_ok(), "{:?}", fb.reversed());
}

/// At scales 1e±200 a cognate is the unit linkage's scaled (relative error ~ε), not a point
/// that underflowed to zero or overflowed to NaN; reversing swaps the lengths exactly.
#[test]
fn cognates_at_extreme_scales() {
    let unit = FourBar::new(2.0_f64, 1.0, 2.5, 2.5, (5.0, 0.7), Assembly::Open).unwrap();
    let [u1, u2] = unit.cognates().unwrap();
    for s in [1e-200_f64, 1e200] {
        let fb = FourBar::new(
            2.0 * s,
            s,
            2.5 * s,
            2.5 * s,
            (5.0 * s, 0.7 * s),
            Assembly::Open,
        )
        .unwrap();
        let [c1, c2] = fb.cognates().unwrap();
        for (c, u) in [(c1, u1), (c2, u2)] {
            for (got, want) in [
                (c.crank, u.crank),
                (c.coupler, u.coupler),
                (c.rocker, u.rocker),
                (c.along, u.along),
                (c.left, u.left),
                (c.c.x, u.c.x),
                (c.c.y, u.c.y),
            ] {
                assert!(
                    (got / s - want).abs() <= 1e-14 * (1.0 + want.abs()),
                    "scale {s}: {got} against {want}"
                );
            }
            assert_eq!(c.assembly, u.assembly, "scale {s}");
        }
        let r = fb.reversed().unwrap();
        assert_eq!(
            r.assembly,
            unit.reversed().unwrap().assembly,
            "scale {s}: reversed assembly"
        );
        assert_eq!(
            (r.crank, r.coupler, r.rocker),
            (fb.rocker, fb.coupler, fb.crank),
            "scale {s}"
        );
    }
}

/// A random offset slider-crank at any place, line and reach, its coupler point away from `A`.
fn slider_crank() -> impl Strategy<Value = linkage_core::SliderCrank<f64>> {
    use linkage_core::{Reach, SliderCrank};
    (
        (-50.0f64..50.0, -50.0f64..50.0, -3.2f64..3.2),
        (0.2f64..3.0, 0.2f64..4.0, -0.95f64..0.95),
        (-1.5f64..2.5, -2.0f64..2.0),
        any::<bool>(),
    )
        .prop_filter_map(
            "moves, a coupler point away from A",
            |((x, y, angle), (r, l, e), (u, v), behind)| {
                let reach = if behind { Reach::Behind } else { Reach::Ahead };
                let (along, left) = (u * l, v * l);
                let away = along.hypot(left) > 1e-3 * l;
                let sc = SliderCrank::new(
                    Vec2::new(x, y),
                    angle,
                    e * (r + l),
                    r,
                    l,
                    (along, left),
                    reach,
                )
                .ok()?;
                away.then_some(sc)
            },
        )
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/cognates.txt"))]

    /// Every coupler point of a slider-crank is its cognate's at the crank angle `arg(B − A) +
    /// arg ζ` (the original's rod turned), on one of the cognate's reaches.
    #[test]
    fn a_slider_crank_and_its_cognate_draw_the_same_curve(sc in slider_crank()) {
        use linkage_core::Reach;
        let cog = sc.cognate().unwrap();
        let size = sc.crank + sc.coupler + sc.offset.abs() + sc.along.hypot(sc.left);
        let alpha = sc.left.atan2(sc.along);
        for k in 0..64 {
            let theta = std::f64::consts::TAU * f64::from(k) / 64.0;
            let Some(p) = sc.pose(theta) else { continue };
            let rod = p.b - p.a;
            let turned = rod.y.atan2(rod.x) + alpha;
            let drawn = [Reach::Ahead, Reach::Behind].into_iter().any(|reach| {
                linkage_core::SliderCrank { reach, ..cog }.pose(turned).is_some_and(|q| {
                    // Near the cognate's toggle its pose is conditioned like the original's
                    // rod angle there: allow the rounding of the turned angle, scaled.
                    let slack = (q.transmission.cos().abs()).max(1e-12);
                    (q.coupler_point - p.coupler_point).norm()
                        <= (1e-9 * size).max(16.0 * f64::EPSILON * size / slack)
                })
            });
            prop_assert!(drawn, "θ = {theta}: {:?} not drawn by the cognate {cog:?}", p.coupler_point);
        }
    }
}
