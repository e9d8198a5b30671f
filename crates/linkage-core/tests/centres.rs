//! Instant centres (Aronhold–Kennedy), curvature, jerk and the Ball point.

use linkage_core::{
    catalog, instant_centre, path_curvature, Assembly, Bodies, BodyMotion, Centre, CrankRates,
    FourBar, Mechanism, Vec2,
};
use proptest::prelude::*;
use std::f64::consts::PI;

mod common;

/// Positions, velocities, accelerations and jerks of every joint.
type Rates4 = (
    Vec<Vec2<f64>>,
    Vec<Vec2<f64>>,
    Vec<Vec2<f64>>,
    Vec<Vec2<f64>>,
);

/// Rates per unit crank angle of a solved pose (velocity, acceleration, jerk).
fn rates<const N: usize>(m: &Mechanism<f64, N>, theta: f64) -> Option<Rates4> {
    let n = m.len();
    let (mut p, mut v, mut a, mut j) = (
        vec![Vec2::zeros(); n],
        vec![Vec2::zeros(); n],
        vec![Vec2::zeros(); n],
        vec![Vec2::zeros(); n],
    );
    m.pose(theta, &mut p).ok()?;
    m.rates(&p, CrankRates::unit(), &mut v, Some(&mut a), Some(&mut j))
        .ok()?
        .then_some((p, v, a, j))
}

/// Whether three centres are collinear to `tol` (relative to their spread); a centre at
/// infinity stands for its direction.
fn collinear(c: [Centre<f64>; 3], tol: f64) -> bool {
    let finite: Vec<Vec2<f64>> = c.iter().filter_map(|x| x.finite()).collect();
    let dirs: Vec<Vec2<f64>> = c
        .iter()
        .filter_map(|x| match x {
            Centre::AtInfinity(d) => Some(*d),
            _ => None,
        })
        .collect();
    let cr = |a: Vec2<f64>, b: Vec2<f64>| a.x * b.y - a.y * b.x;
    // Distances are judged against the size of the configuration (1 + the farthest centre).
    let size = 1.0 + finite.iter().map(|p| p.norm()).fold(0.0, f64::max);
    match (finite.len(), dirs.len()) {
        (3, 0) => {
            // Distance of the remaining point from the line through the two farthest apart.
            let pairs = [(0, 1, 2), (0, 2, 1), (1, 2, 0)];
            let &(i, j, k) = pairs
                .iter()
                .max_by(|x, y| {
                    let dx = (finite[x.0] - finite[x.1]).norm();
                    let dy = (finite[y.0] - finite[y.1]).norm();
                    dx.total_cmp(&dy)
                })
                .unwrap();
            let u = finite[j] - finite[i];
            let n = u.norm();
            n <= tol * size || cr(u, finite[k] - finite[i]).abs() / n <= tol * size
        }
        (2, 1) => {
            // The line through the finite two runs along the direction at infinity.
            let u = finite[1] - finite[0];
            u.norm() <= tol * size || cr(u, dirs[0]).abs() <= tol * u.norm() * size
        }
        _ => true, // two or three at infinity lie on the line at infinity
    }
}

fn random_four_bar() -> impl Strategy<Value = (FourBar<f64>, f64)> {
    (
        (0.3f64..3.0, 0.3f64..3.0, 0.3f64..3.0, 0.3f64..3.0),
        (-2.0f64..2.0, -2.0f64..2.0),
        any::<bool>(),
        0.0..2.0 * PI,
    )
        .prop_filter_map("assembles with margin", |((g, r, c, k), pt, open, th)| {
            let asm = if open {
                Assembly::Open
            } else {
                Assembly::Crossed
            };
            let fb = FourBar::new(g, r, c, k, pt, asm).ok()?;
            let pose = fb.pose(th).ok()?;
            (pose.margin > 1e-3).then_some((fb, th))
        })
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/centres.txt"))]

    /// Kennedy: the three instant centres of any three links are collinear; the velocity-based
    /// centres equal the Aronhold–Kennedy line construction; every joint's velocity relative to
    /// another link is perpendicular to its offset from their relative centre.
    #[test]
    fn kennedy_and_velocity_perpendicularity((fb, th) in random_four_bar()) {
        let m = fb.mechanism();
        let (p, v, a, j) = rates(&m, th).unwrap();
        let bodies = Bodies::of(&m);
        let ids: Vec<_> = bodies.ids().collect();
        prop_assert_eq!(ids.len(), 4, "bodies of a four-bar");
        let motions: Vec<_> = ids.iter().map(|&id| BodyMotion::of(&bodies, id, &p, &v, &a, &j)).collect();
        let ic = |k: usize, l: usize| instant_centre(&motions[k], &motions[l]);
        for (k, l, n) in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)] {
            prop_assert!(collinear([ic(k, l), ic(l, n), ic(k, n)], 1e-9), "links {k} {l} {n}");
        }
        let geometric = fb.instant_centres(th).unwrap();
        let order = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
        for (g, &(k, l)) in geometric.iter().zip(&order) {
            match (*g, ic(k, l)) {
                (Centre::Finite(x), Centre::Finite(y)) => {
                    let scale = 1.0 + x.norm();
                    prop_assert!((x - y).norm() <= 1e-8 * scale * scale, "I{}{}: {x:?} vs {y:?}", k + 1, l + 1);
                }
                (Centre::AtInfinity(_), Centre::AtInfinity(_)) => {}
                // Nearly parallel lines: one construction may still give a far finite point.
                (Centre::Finite(x), Centre::AtInfinity(_)) | (Centre::AtInfinity(_), Centre::Finite(x)) => {
                    prop_assert!(x.norm() > 1e6, "I{}{}", k + 1, l + 1);
                }
                (g, y) => prop_assert!(false, "I{}{}: {g:?} vs {y:?}", k + 1, l + 1),
            }
        }
        // Coupler points (A, B, P) relative to the ground turn about I13.
        if let Centre::Finite(i13) = ic(0, 2) {
            for joint in [2usize, 3, 4] {
                let r = p[joint] - i13;
                let scale = r.norm() * v[joint].norm();
                prop_assert!(r.dot(&v[joint]).abs() <= 1e-9 * scale.max(1e-300), "joint {joint}: velocity {:?} not perpendicular to its offset {r:?} from I13", v[joint]);
            }
        }
    }

    /// Jerk of every joint equals a five-point difference of the analytic acceleration in θ.
    #[test]
    fn jerk_matches_difference_of_acceleration((fb, th) in random_four_bar()) {
        let m = fb.mechanism();
        let acc = |t: f64| rates(&m, t).map(|r| r.2);
        // Near a toggle the fifth derivative blows up; only check well-conditioned poses.
        prop_assume!(fb.pose(th).unwrap().margin > 0.05);
        let (_, _, a0, j0) = rates(&m, th).unwrap();
        // Five-point differences at h and h/2; their disagreement bounds the difference's own
        // truncation error (it shrinks 16× per halving).
        let fd = |h: f64| -> Option<Vec<Vec2<f64>>> {
            let (a2, a1, b1, b2) = (acc(th - 2.0 * h)?, acc(th - h)?, acc(th + h)?, acc(th + 2.0 * h)?);
            Some((0..5).map(|i| (-b2[i] + b1[i] * 8.0 - a1[i] * 8.0 + a2[i]) / (12.0 * h)).collect())
        };
        let (Some(coarse), Some(fine)) = (fd(4e-4), fd(2e-4)) else {
            return Ok(());
        };
        for i in 0..5 {
            let truncation = (coarse[i] - fine[i]).norm();
            let scale = 1.0 + j0[i].norm() + a0[i].norm();
            prop_assert!((j0[i] - fine[i]).norm() <= 2.0 * truncation + 1e-7 * scale,
                "joint {i}: {:?} vs {:?} (truncation {truncation:e})", j0[i], fine[i]);
        }
    }
}

/// Kennedy collinearity on the multi-loop catalogue, for every triple of links.
#[test]
fn kennedy_on_multi_loop_linkages() {
    for (l, theta) in [
        (catalog::peaucellier::<f64>(), 0.7),
        (catalog::hart::<f64>(), 0.8),
        (catalog::hoecken_pantograph::<f64>(2.0).unwrap(), 2.0),
        (catalog::jansen::<f64>(), 1.0),
    ] {
        let m = &l.mechanism;
        let (p, v, a, j) = rates(m, theta).unwrap();
        let bodies = Bodies::of(m);
        let motions: Vec<_> = bodies
            .ids()
            .map(|id| BodyMotion::of(&bodies, id, &p, &v, &a, &j))
            .collect();
        let n = motions.len();
        let mut triples = 0;
        for k in 0..n {
            for q in k + 1..n {
                for r in q + 1..n {
                    let c = [
                        instant_centre(&motions[k], &motions[q]),
                        instant_centre(&motions[q], &motions[r]),
                        instant_centre(&motions[k], &motions[r]),
                    ];
                    assert!(collinear(c, 1e-8), "{}: links {k} {q} {r}: {c:?}", l.name);
                    triples += 1;
                }
            }
        }
        assert!(triples >= 20, "{}: only {triples} triples of links", l.name);
    }
}

/// A parallelogram's coupler translates: I13 is at infinity (OA ∥ CB), not a huge number.
#[test]
fn parallelogram_centre_at_infinity() {
    let fb = FourBar::new(3.0, 1.0, 3.0, 1.0, (1.0, 0.0), Assembly::Open).unwrap();
    let th = 1.1;
    let geometric = fb.instant_centres(th).unwrap();
    assert!(
        matches!(geometric[1], Centre::AtInfinity(_)),
        "I13 of a parallelogram: {:?}",
        geometric[1]
    );
    let m = fb.mechanism();
    let (p, v, a, j) = rates(&m, th).unwrap();
    let bodies = Bodies::of(&m);
    let ids: Vec<_> = bodies.ids().collect();
    let g = BodyMotion::of(&bodies, ids[0], &p, &v, &a, &j);
    let c = BodyMotion::of(&bodies, ids[2], &p, &v, &a, &j);
    match instant_centre(&g, &c) {
        Centre::AtInfinity(d) => {
            // Perpendicular to the coupler's velocity, i.e. along the crank.
            let crank = (p[2] - p[0]).normalize();
            assert!(
                (d.x * crank.y - d.y * crank.x).abs() < 1e-12,
                "I13 direction {d:?} not along the crank {crank:?}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// The crank pin's path is a circle: centre O, radius = crank, from analytic rates.
#[test]
fn crank_pin_curvature_is_the_crank() {
    let fb = catalog::hoecken::<f64>();
    let m = fb.mechanism();
    for k in 0..36 {
        let (p, v, a, _) = rates(&m, k as f64 * 0.17).unwrap();
        let (kappa, centre) = path_curvature(p[2], v[2], a[2]);
        assert!(
            (1.0 / kappa - 10.0).abs() < 1e-12,
            "θ = {}: radius of curvature {} vs crank 10",
            k as f64 * 0.17,
            1.0 / kappa
        );
        assert!(
            centre.finite().unwrap().norm() < 1e-12,
            "θ = {}: centre of curvature {centre:?}, not O",
            k as f64 * 0.17
        );
    }
}

/// A centre near the end of the float range, seen from a point far out: the offset from the
/// point alone passes the range (1.8e308) while the centre (1.7e308) does not, so the centre
/// is finite and scales with the point, velocity and acceleration (found by hypothesis in
/// tests/test_fuzz_api.py::test_circumcentre_scale_invariance).
#[test]
fn curvature_centre_near_the_float_range_end_is_finite() {
    let (p, v, a) = (
        Vec2::new(0.0_f64, -1.0),
        Vec2::new(0.9375, 0.33203125),
        Vec2::new(0.9375, 0.38671875),
    );
    let (k0, c0) = path_curvature(p, v, a);
    let c0 = c0.finite().unwrap();
    let s = 1e307;
    let (k1, c1) = path_curvature(p * s, v * s, a * s);
    let c1 = c1
        .finite()
        .unwrap_or_else(|| panic!("centre of curvature at scale {s:e}: {c1:?}, not finite"));
    assert!(
        (c1 / s - c0).norm() < 1e-12 * c0.norm(),
        "{c1:?} vs {c0:?} × {s:e}"
    );
    assert!(
        (k1 * s - k0).abs() < 1e-9 * k0.abs(),
        "κ {k1:e} vs {k0:e} / {s:e}"
    );
}

/// Ball point: on the inflection circle, and the path of a coupler point placed there has zero
/// curvature and zero curvature derivative at that crank angle (checked along a sweep).
#[test]
fn ball_point_has_stationary_zero_curvature() {
    let base = catalog::hoecken::<f64>();
    for th0 in [0.4, 1.3, 2.5, 4.0] {
        let inf = base.coupler_inflection(th0).unwrap();
        let ball = inf.ball_point.finite().unwrap();
        assert!(
            ((ball - inf.centre).norm() - inf.radius).abs() < 1e-9 * inf.radius,
            "θ = {th0}: Ball point {ball:?} is {} from the inflection circle's centre, radius {}",
            (ball - inf.centre).norm(),
            inf.radius
        );
        assert!(
            ((inf.pole - inf.centre).norm() - inf.radius).abs() < 1e-9 * inf.radius,
            "θ = {th0}: pole {:?} is {} from the inflection circle's centre, radius {}",
            inf.pole,
            (inf.pole - inf.centre).norm(),
            inf.radius
        );
        // The Ball point in coupler coordinates at th0.
        let pose = base.pose(th0).unwrap();
        let u = (pose.b - pose.a).normalize();
        let r = ball - pose.a;
        let local = (r.dot(&u), u.x * r.y - u.y * r.x);
        let fb = FourBar::new(20.0, 10.0, 25.0, 25.0, local, Assembly::Open).unwrap();
        let m = fb.mechanism();
        let kappa = |t: f64| {
            let (p, v, a, _) = rates(&m, t).unwrap();
            path_curvature(p[4], v[4], a[4]).0
        };
        let scale = 1.0 / inf.radius;
        assert!(kappa(th0).abs() < 1e-9 * scale, "κ = {}", kappa(th0));
        // Another point of the inflection circle, the inflection pole J, has zero curvature but
        // not a stationary one: its derivative sets the scale.
        let r = inf.inflection_pole - pose.a;
        let local = (r.dot(&u), u.x * r.y - u.y * r.x);
        let fb2 = FourBar::new(20.0, 10.0, 25.0, 25.0, local, Assembly::Open).unwrap();
        let m2 = fb2.mechanism();
        let k2 = |t: f64| {
            let (p, v, a, _) = rates(&m2, t).unwrap();
            path_curvature(p[4], v[4], a[4]).0
        };
        let k0 = k2(th0);
        assert!(
            k0.abs() < 1e-9 * scale,
            "θ = {th0}: inflection pole's path has κ = {k0}"
        );
        let generic = ((k2(th0 + 1e-4) - k2(th0 - 1e-4)) / 2e-4).abs();
        assert!(generic > 1e-3 * scale, "generic dκ/dθ {generic:e}");
        // At the Ball point dκ/dθ by central differences vanishes like h² (pure truncation):
        // the derivative itself is zero.
        let dk = |h: f64| (kappa(th0 + h) - kappa(th0 - h)) / (2.0 * h);
        let (d3, d4, d5) = (dk(1e-3), dk(1e-4), dk(1e-5));
        assert!(
            d5.abs() < 1e-4 * generic,
            "dκ/dθ = {d5:e} vs generic {generic:e}"
        );
        assert!(
            d4.abs() < 0.02 * d3.abs() || d3.abs() < 1e-9 * generic,
            "{d3:e} {d4:e}"
        );
    }
}
