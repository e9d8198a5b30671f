//! Precision-point synthesis: Burmester motion generation and Freudenstein function generation.
//!
//! Golden values are by construction: a known four-bar's coupler poses (or input–output pairs)
//! are synthesised and the four-bar must come back exactly. Consistency tests check one
//! quantity two ways (the complex-number Burmester curve against the real bilinear condition;
//! the tracked output against the untracked one).

#![cfg(all(not(target_os = "none"), feature = "synthesis"))]

mod common;

use core::f64::consts::{PI, TAU};

use linkage_core::{
    centre_point, chebyshev_spacing, circle_point, common_pole, pole, Assembly, BodyPose,
    BurmesterCurve, BurmesterPair, Defect, Error, FourBar, Freudenstein, FunctionGenerator,
    GrashofClass, MotionCandidate, Rates, Tracker, Vec2,
};
use proptest::prelude::*;

/// The coupler's pose of `fb` at crank angle `theta` on assembly `asm`: the coupler point and
/// the angle of the coupler line `A → B`; also `A` and `B`.
fn coupler_pose(
    fb: &FourBar<f64>,
    theta: f64,
    asm: Assembly,
) -> (BodyPose<f64>, Vec2<f64>, Vec2<f64>) {
    let f = FourBar {
        assembly: asm,
        ..*fb
    };
    let p = f.pose(theta).unwrap();
    let d = p.b - p.a;
    (
        BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap(),
        p.a,
        p.b,
    )
}

/// A crank-rocker (s + l = 0.7 + 2.1 < 1.9 + 1.6... : crank shortest) on skew pivots.
fn crank_rocker() -> FourBar<f64> {
    FourBar::with_pivots(
        Vec2::new(0.3, -0.2),
        Vec2::new(2.3, 0.4),
        0.7,
        1.9,
        1.6,
        (0.8, 0.6),
        Assembly::Open,
    )
    .unwrap()
}

fn near(a: Vec2<f64>, b: Vec2<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol
}

fn same_four_bar(a: &FourBar<f64>, b: &FourBar<f64>, tol: f64) {
    assert!(near(a.o, b.o, tol) && near(a.c, b.c, tol), "{a:?} vs {b:?}");
    for (x, y) in [
        (a.crank, b.crank),
        (a.coupler, b.coupler),
        (a.rocker, b.rocker),
        (a.along, b.along),
        (a.left, b.left),
    ] {
        assert!((x - y).abs() <= tol, "{a:?} vs {b:?}");
    }
    assert_eq!(a.assembly, b.assembly, "assembly of {a:?} vs {b:?}");
}

#[test]
fn three_poses_recover_a_known_four_bar() {
    let fb = crank_rocker();
    assert_eq!(
        fb.grashof(),
        GrashofClass::CrankRocker,
        "Grashof class of crank_rocker()"
    );
    let thetas = [0.4, 1.3, 2.5];
    let mut poses = Vec::new();
    let mut a = Vec::new();
    let mut b = Vec::new();
    for &t in &thetas {
        let (p, pa, pb) = coupler_pose(&fb, t, Assembly::Open);
        poses.push(p);
        a.push(pa);
        b.push(pb);
    }
    let poses3: [BodyPose<f64>; 3] = poses.clone().try_into().unwrap();
    // Circle point → centre point (circumcentre) and back (inversion).
    let crank = centre_point(&poses3, a[0]).unwrap();
    let rocker = centre_point(&poses3, b[0]).unwrap();
    assert!(near(crank.centre, fb.o, 1e-12), "{crank:?}");
    assert!(near(rocker.centre, fb.c, 1e-12), "{rocker:?}");
    let back = circle_point(&poses3, fb.o).unwrap();
    assert!(near(back.circle, a[0], 1e-12), "{back:?}");
    let back = circle_point(&poses3, fb.c).unwrap();
    assert!(near(back.circle, b[0], 1e-12), "{back:?}");
    // Two dyads → the four-bar, swept through the poses on one circuit, in order.
    let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
    same_four_bar(&cand.four_bar, &fb, 1e-12);
    assert_eq!(cand.check.defect, None, "three poses: {:?}", cand.check);
    assert_eq!(cand.check.direction, 1.0, "three poses: {:?}", cand.check);
    assert!(cand.check.position_error <= 1e-12, "{:?}", cand.check);
    assert!(cand.check.angle_error <= 1e-12, "{:?}", cand.check);
    assert_eq!(
        cand.check.grashof,
        GrashofClass::CrankRocker,
        "three poses: {:?}",
        cand.check
    );
    for (k, &t) in thetas.iter().enumerate() {
        assert!(
            (cand.check.crank_angles[k] - t).abs() < 1e-12,
            "pose {k}: crank angle {} vs {t}",
            cand.check.crank_angles[k]
        );
    }
    assert!(
        cand.check.crank_angles[3].is_nan(),
        "crank angle of an absent fourth pose: {}",
        cand.check.crank_angles[3]
    );
    // Transmission angle: the smallest over the travel is at most that at any pose.
    let mu_fold = |t: f64| {
        let m = fb.transmission_angle(t).unwrap();
        m.min(PI - m)
    };
    let at_poses = thetas.iter().map(|&t| mu_fold(t)).fold(f64::MAX, f64::min);
    assert!(
        cand.check.min_transmission <= at_poses + 1e-12,
        "min transmission {} above {at_poses}, the least at the poses",
        cand.check.min_transmission
    );
    assert!(
        cand.check.min_transmission > 0.0,
        "min transmission {}",
        cand.check.min_transmission
    );
}

#[test]
fn clockwise_order_is_found() {
    let fb = crank_rocker();
    let poses: Vec<_> = [2.5, 1.3, 0.4]
        .iter()
        .map(|&t| coupler_pose(&fb, t, Assembly::Open).0)
        .collect();
    let p3: [BodyPose<f64>; 3] = poses.clone().try_into().unwrap();
    let (_, a0, b0) = coupler_pose(&fb, 2.5, Assembly::Open);
    let cand = MotionCandidate::new(
        &poses,
        centre_point(&p3, a0).unwrap(),
        centre_point(&p3, b0).unwrap(),
    )
    .unwrap();
    assert_eq!(
        cand.check.defect, None,
        "poses in clockwise order: {:?}",
        cand.check
    );
    assert_eq!(
        cand.check.direction, -1.0,
        "poses in clockwise order: {:?}",
        cand.check
    );
}

/// The real form of the four-pose condition: a centre point `g` has a circle point iff the
/// three equations `|d_j + R_j w − g|² = |d_0 + R_0 w − g|²`, linear in `w`, are consistent:
/// `det[n_j | rhs_j] = 0`. Returned relative to the product of the rows' norms (at least 1
/// each: a centre point at a pole makes a row vanish).
fn bilinear_det(poses: &[BodyPose<f64>; 4], g: Vec2<f64>) -> f64 {
    let rt = |p: &BodyPose<f64>, v: Vec2<f64>| {
        let (s, c) = p.angle.sin_cos();
        Vec2::new(c * v.x + s * v.y, -s * v.x + c * v.y)
    };
    let base = rt(&poses[0], poses[0].origin - g);
    let r0 = (poses[0].origin - g).norm_squared();
    let rows: Vec<[f64; 3]> = (1..4)
        .map(|j| {
            let n = (rt(&poses[j], poses[j].origin - g) - base) * 2.0;
            [n.x, n.y, r0 - (poses[j].origin - g).norm_squared()]
        })
        .collect();
    let det = rows[0][0] * (rows[1][1] * rows[2][2] - rows[1][2] * rows[2][1])
        - rows[0][1] * (rows[1][0] * rows[2][2] - rows[1][2] * rows[2][0])
        + rows[0][2] * (rows[1][0] * rows[2][1] - rows[1][1] * rows[2][0]);
    let norm: f64 = rows
        .iter()
        .map(|r| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt().max(1.0))
        .product();
    det / norm
}

/// Four poses and the crank and rocker pins at them.
type Poses4 = ([BodyPose<f64>; 4], [Vec2<f64>; 4], [Vec2<f64>; 4]);

fn four_poses_of(fb: &FourBar<f64>, thetas: [f64; 4]) -> Poses4 {
    let mut p = [BodyPose::new(0.0, 0.0, 0.0).unwrap(); 4];
    let mut a = [Vec2::zeros(); 4];
    let mut b = [Vec2::zeros(); 4];
    for k in 0..4 {
        (p[k], a[k], b[k]) = coupler_pose(fb, thetas[k], fb.assembly);
    }
    (p, a, b)
}

#[test]
fn four_poses_recover_both_dyads_on_the_burmester_curves() {
    let fb = crank_rocker();
    let thetas = [0.2, 0.9, 1.7, 2.6];
    let (poses, a, b) = four_poses_of(&fb, thetas);
    let curve = BurmesterCurve::new(&poses).unwrap();
    let k = curve.free_pose();
    // The crank's own rotation to pose k must give back (O, A0); the rocker's (C, B0).
    let rocker_angle = |j: usize| {
        let d = b[j] - fb.c;
        d.y.atan2(d.x)
    };
    for (beta, want) in [
        (
            thetas[k] - thetas[0],
            BurmesterPair {
                centre: fb.o,
                circle: a[0],
            },
        ),
        (
            rocker_angle(k) - rocker_angle(0),
            BurmesterPair {
                centre: fb.c,
                circle: b[0],
            },
        ),
    ] {
        let got = curve.dyads(beta);
        let hit = got
            .iter()
            .flatten()
            .any(|p| near(p.centre, want.centre, 1e-10) && near(p.circle, want.circle, 1e-10));
        assert!(hit, "β = {beta}: {got:?}, want {want:?}");
    }
    let crank = BurmesterPair {
        centre: fb.o,
        circle: a[0],
    };
    let rocker = BurmesterPair {
        centre: fb.c,
        circle: b[0],
    };
    let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
    same_four_bar(&cand.four_bar, &fb, 1e-12);
    assert_eq!(cand.check.defect, None, "four poses: {:?}", cand.check);
    assert!(
        cand.check.position_error <= 1e-12 && cand.check.angle_error <= 1e-12,
        "four poses: {:?}",
        cand.check
    );
}

#[test]
fn burmester_curve_samples_are_exact_dyads_on_the_cubic() {
    let poses = [
        BodyPose::new(0.0, 0.0, 0.0).unwrap(),
        BodyPose::new(1.0, 0.3, 0.4).unwrap(),
        BodyPose::new(1.8, 1.1, 0.9).unwrap(),
        BodyPose::new(2.1, 2.0, 1.6).unwrap(),
    ];
    let curve = BurmesterCurve::new(&poses).unwrap();
    let mut count = 0;
    let mut worst_radius: f64 = 0.0;
    let mut worst_det: f64 = 0.0;
    for i in 0..720 {
        let beta = TAU * i as f64 / 720.0;
        for (pair, rot) in curve.dyads_with_rotations(beta).into_iter().flatten() {
            count += 1;
            let w = poses[0].to_body(pair.circle);
            let r0 = pair.radius();
            for (j, p) in poses.iter().enumerate() {
                let kj = p.to_world(w);
                worst_radius =
                    worst_radius.max(((kj - pair.centre).norm() - r0).abs() / r0.max(1.0));
                // The crank's rotation to pose j is the one reported.
                let (u, v) = (pair.circle - pair.centre, kj - pair.centre);
                let turn = (u.x * v.y - u.y * v.x).atan2(u.dot(&v));
                let diff = (turn - rot[j] + PI).rem_euclid(TAU) - PI;
                assert!(diff.abs() < 1e-8, "pose {j}: {turn} vs {}", rot[j]);
            }
            worst_det = worst_det.max(bilinear_det(&poses, pair.centre).abs());
        }
    }
    assert!(count > 500, "only {count} real samples");
    assert!(worst_radius < 1e-9, "radius spread {worst_radius:e}");
    assert!(worst_det < 1e-9, "bilinear determinant {worst_det:e}");
    // The six poles lie on the centre-point curve (the cubic through them).
    for i in 0..4 {
        for j in i + 1..4 {
            let p = pole(&poses[i], &poses[j]).finite().unwrap();
            assert!(bilinear_det(&poses, p).abs() < 1e-12, "pole {i}{j}");
        }
    }
    // A point off the curve is not on the cubic (the test can fail).
    let off = bilinear_det(&poses, Vec2::new(5.0, -3.0));
    assert!(off.abs() > 1e-3, "(5, −3) is on the cubic: det {off:e}");
}

#[test]
fn pure_translation_between_two_poses_is_fine() {
    // Pole P01 at infinity: the dyad equation does not form poles.
    let poses = [
        BodyPose::new(0.0, 0.0, 0.3).unwrap(),
        BodyPose::new(1.0, 0.0, 0.3).unwrap(),
        BodyPose::new(1.5, 0.8, 1.0).unwrap(),
        BodyPose::new(0.7, 1.6, 1.7).unwrap(),
    ];
    let curve = BurmesterCurve::new(&poses).unwrap();
    let n = (0..360)
        .flat_map(|i| curve.dyads(TAU * i as f64 / 360.0))
        .flatten()
        .count();
    assert!(n > 100, "only {n} real dyads over 360 samples");
}

#[test]
fn bad_input_gets_specific_errors() {
    let p = |x: f64, y: f64, a: f64| BodyPose {
        origin: Vec2::new(x, y),
        angle: a,
    };
    // NaN.
    let r = BodyPose::new(f64::NAN, 0.0, 0.0);
    assert!(
        matches!(r, Err(Error::NotFinite { what: "pose x", .. })),
        "pose x NaN: {r:?}"
    );
    let r = centre_point(
        &[p(0.0, 0.0, 0.0), p(1.0, 0.0, f64::NAN), p(0.0, 1.0, 0.0)],
        Vec2::zeros(),
    );
    assert!(
        matches!(r, Err(Error::NotFinite { .. })),
        "a NaN pose angle: {r:?}"
    );
    // Coincident poses.
    let three = [p(0.0, 0.0, 0.1), p(1.0, 0.5, 0.4), p(0.0, 0.0, 0.1)];
    assert_eq!(
        centre_point(&three, Vec2::new(0.3, 0.3)),
        Err(Error::CoincidentPositions {
            first: 0,
            second: 2
        }),
        "poses 0 and 2 coincide"
    );
    let four = [
        p(0.0, 0.0, 0.1),
        p(1.0, 0.5, 0.4),
        p(2.0, 0.0, 0.7),
        p(1.0, 0.5, 0.4),
    ];
    assert_eq!(
        BurmesterCurve::new(&four),
        Err(Error::CoincidentPositions {
            first: 1,
            second: 3
        }),
        "poses 1 and 3 coincide"
    );
    // Three translations along a line: every circle point moves on a line (centre at infinity).
    let line = [p(0.0, 0.0, 0.5), p(1.0, 1.0, 0.5), p(3.0, 3.0, 0.5)];
    let r = centre_point(&line, Vec2::new(0.2, -0.7));
    assert!(
        matches!(r, Err(Error::Degenerate { .. })),
        "translations along a line: {r:?}"
    );
    // A circle point at the pole of poses 0 and 1: its centre is not unique.
    let three = [p(0.0, 0.0, 0.0), p(2.0, 0.0, PI / 2.0), p(0.5, 2.0, 1.0)];
    let p01 = pole(&three[0], &three[1]).finite().unwrap();
    let r = centre_point(&three, p01);
    assert!(
        matches!(r, Err(Error::Degenerate { .. })),
        "circle point at the pole P01 {p01:?}: {r:?}"
    );
    // Four pure translations: no Burmester curve.
    let four = [
        p(0.0, 0.0, 0.2),
        p(1.0, 0.0, 0.2),
        p(1.0, 1.0, 0.2),
        p(0.0, 2.0, 0.2),
    ];
    let r = BurmesterCurve::new(&four);
    assert!(
        matches!(r, Err(Error::Degenerate { .. })),
        "four pure translations: {r:?}"
    );
    // Fewer than three poses; too many.
    let d = BurmesterPair {
        centre: Vec2::zeros(),
        circle: Vec2::new(1.0, 0.0),
    };
    let e = BurmesterPair {
        centre: Vec2::new(3.0, 0.0),
        circle: Vec2::new(2.0, 1.0),
    };
    assert_eq!(
        MotionCandidate::new(&[p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0)], d, e),
        Err(Error::TooFew {
            what: "poses",
            needed: 3,
            got: 2
        }),
        "two poses"
    );
    let five = [
        p(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.1),
        p(2.0, 0.0, 0.2),
        p(3.0, 0.0, 0.3),
        p(4.0, 0.0, 0.4),
    ];
    let r = MotionCandidate::new(&five, d, e);
    assert!(
        matches!(r, Err(Error::BufferLength { .. })),
        "five poses: {r:?}"
    );
    // Dyads that make no four-bar: a circle point on its centre (zero crank).
    let z = BurmesterPair {
        centre: Vec2::zeros(),
        circle: Vec2::zeros(),
    };
    let ok3 = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.1), p(2.0, 0.5, 0.2)];
    let r = MotionCandidate::new(&ok3, z, e);
    assert!(
        matches!(r, Err(Error::InvalidLength { .. })),
        "a zero crank: {r:?}"
    );
    // Freudenstein: too few points, coincident points, a singular system, no real coupler.
    assert_eq!(
        Freudenstein::fit(&[0.1, 0.2], &[1.0, 1.1]),
        Err(Error::TooFew {
            what: "precision points",
            needed: 3,
            got: 2
        }),
        "Freudenstein fit of two points"
    );
    assert_eq!(
        Freudenstein::fit(&[0.1, 0.2, 0.1], &[1.0, 1.1, 1.0]),
        Err(Error::CoincidentPositions {
            first: 0,
            second: 2
        }),
        "Freudenstein fit with points 0 and 2 coinciding"
    );
    let r = Freudenstein::fit(&[0.1, 0.1, 0.1], &[1.0, 1.1, 1.2]);
    assert!(
        matches!(r, Err(Error::Degenerate { .. })),
        "three equal input angles: {r:?}"
    );
    let r = Freudenstein::fit(&[0.1, f64::NAN, 0.3], &[1.0, 1.1, 1.2]);
    assert!(
        matches!(r, Err(Error::NotFinite { .. })),
        "a NaN input angle: {r:?}"
    );
    let k = Freudenstein {
        k1: 1.0,
        k2: 1.0,
        k3: 10.0,
    };
    let r = FunctionGenerator::new(k, 1.0, 0.0, 0.0);
    assert!(
        matches!(r, Err(Error::NoSolution { .. })),
        "K3 = 10, no real coupler: {r:?}"
    );
    let k = Freudenstein {
        k1: 0.0,
        k2: 1.0,
        k3: 1.0,
    };
    let r = FunctionGenerator::new(k, 1.0, 0.0, 0.0);
    assert!(matches!(r, Err(Error::Degenerate { .. })), "K1 = 0: {r:?}");
}

#[test]
fn circuit_defect_is_flagged() {
    // Poses 0 and 1 on the open circuit of a crank-rocker, pose 2 on the crossed one: both
    // dyads are exact for the three poses, but no motion of the linkage joins them.
    let fb = crank_rocker();
    let (p0, a0, b0) = coupler_pose(&fb, 0.4, Assembly::Open);
    let (p1, ..) = coupler_pose(&fb, 1.3, Assembly::Open);
    let (p2, ..) = coupler_pose(&fb, 2.5, Assembly::Crossed);
    let poses = [p0, p1, p2];
    let crank = centre_point(&poses, a0).unwrap();
    let rocker = centre_point(&poses, b0).unwrap();
    assert!(
        near(crank.centre, fb.o, 1e-12) && near(rocker.centre, fb.c, 1e-12),
        "crank centre {:?} vs O {:?}, rocker centre {:?} vs C {:?}",
        crank.centre,
        fb.o,
        rocker.centre,
        fb.c
    );
    let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
    assert_eq!(
        cand.check.defect,
        Some(Defect::Branch { pose: 2 }),
        "pose 2 on the crossed circuit: {:?}",
        cand.check
    );
}

/// A parallelogram's coupler translates through three poses; driven from either pivot the
/// two dyads are the same parallelogram, and both must carry the body through the poses. The
/// driven-from-the-other-pivot one used to be built on its antiparallelogram branch whenever
/// pose 0's crank angle lay a flat position away from its start angle (a change point's
/// declared assembly names the branch there), and was flagged a branch defect at pose 0.
#[test]
fn parallelogram_reaches_driven_from_either_pivot() {
    let (g, r) = (40.0, 50.0);
    let mut checked = 0;
    for ground_dir in [0.0, 0.7, PI, -2.0] {
        let o = Vec2::new(30.0, -40.0);
        let c = o + Vec2::new(ground_dir.cos(), ground_dir.sin()) * g;
        // Three crank angles inside one open half-turn between the flat positions (crank along
        // the ground line), either way round, starting on either side of the ground line.
        for side in [0.0, PI] {
            for start in [0.5, 1.2, 2.6] {
                for step in [0.2, -0.2] {
                    let th0 = ground_dir + side + start;
                    let thetas = [th0, th0 + step, th0 + 2.0 * step];
                    let at = |t: f64| {
                        let u = Vec2::new(t.cos(), t.sin()) * r;
                        let (a, b) = (o + u, c + u);
                        (a, b, a + Vec2::new(-7.0, 11.0))
                    };
                    let poses =
                        thetas.map(|t| BodyPose::new(at(t).2.x, at(t).2.y, ground_dir).unwrap());
                    let (a0, b0, _) = at(thetas[0]);
                    let left = centre_point(&poses, a0).unwrap();
                    let right = centre_point(&poses, b0).unwrap();
                    for (crank, rocker) in [(left, right), (right, left)] {
                        let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
                        assert_eq!(
                            cand.four_bar.grashof(),
                            GrashofClass::ChangePoint,
                            "{cand:?}"
                        );
                        assert_eq!(
                            cand.check.defect, None,
                            "ground {ground_dir}, crank angles {thetas:?}, driven from {:?}: {:?}",
                            crank.centre, cand
                        );
                        assert!(independently_reaches(&cand, &poses), "{cand:?}");
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 4 * 2 * 3 * 2 * 2, "pose sets checked");
}

/// Poses on either side of a parallelogram's flat position (crank along the ground line, where
/// it may go on as an antiparallelogram) are flagged, from exact pivots too: a tracker that
/// knows the orientations in closed form does not report the flip it places there.
#[test]
fn parallelogram_passing_its_flat_position_is_flagged() {
    let (o, c, r) = (Vec2::new(30.0, -40.0), Vec2::new(70.0, -40.0), 50.0);
    let at = |t: f64| {
        let u = Vec2::new(t.cos(), t.sin()) * r;
        (o + u, c + u)
    };
    for thetas in [[2.6, 3.0, 3.4], [-0.4, 0.1, 0.5]] {
        let poses = thetas.map(|t| BodyPose::new(at(t).0.x - 7.0, at(t).0.y + 11.0, 0.0).unwrap());
        let (a0, b0) = at(thetas[0]);
        let left = BurmesterPair {
            centre: o,
            circle: a0,
        };
        let right = BurmesterPair {
            centre: c,
            circle: b0,
        };
        for (crank, rocker) in [(left, right), (right, left)] {
            let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
            assert_eq!(
                cand.check.defect,
                Some(Defect::FlatPosition),
                "{thetas:?}: {cand:?}"
            );
        }
        // Short of the flat position, the same linkage passes.
        let flat = if thetas[0] > 0.0 { PI } else { 0.0 };
        let near = [thetas[0], (thetas[0] + flat) / 2.0, flat - 0.05];
        let poses = near.map(|t| BodyPose::new(at(t).0.x - 7.0, at(t).0.y + 11.0, 0.0).unwrap());
        let cand = MotionCandidate::new(&poses, left, right).unwrap();
        assert_eq!(cand.check.defect, None, "{near:?}: {cand:?}");
    }
}

#[test]
fn order_defect_is_flagged() {
    let fb = crank_rocker();
    let (poses, a, b) = four_poses_of(&fb, [0.0, 3.0, 1.5, 4.5]);
    let cand = MotionCandidate::new(
        &poses,
        BurmesterPair {
            centre: fb.o,
            circle: a[0],
        },
        BurmesterPair {
            centre: fb.c,
            circle: b[0],
        },
    )
    .unwrap();
    assert_eq!(
        cand.check.defect,
        Some(Defect::Order),
        "poses out of crank order: {:?}",
        cand.check
    );
}

#[test]
fn toggle_defect_is_flagged() {
    // A triple-rocker (one circuit through both assemblies): going from pose 1 back to pose 2
    // on the other assembly needs the crank to pass its limit and reverse.
    let fb = FourBar::new(2.0, 1.0, 1.2, 1.1, (0.5, 0.3), Assembly::Open).unwrap();
    assert_eq!(
        fb.grashof(),
        GrashofClass::TripleRocker,
        "Grashof class of (2, 1, 1.2, 1.1)"
    );
    let (p0, a0, b0) = coupler_pose(&fb, 0.2, Assembly::Open);
    let (p1, ..) = coupler_pose(&fb, 0.5, Assembly::Open);
    let (p2, ..) = coupler_pose(&fb, 0.3, Assembly::Crossed);
    let poses = [p0, p1, p2];
    let cand = MotionCandidate::new(
        &poses,
        centre_point(&poses, a0).unwrap(),
        centre_point(&poses, b0).unwrap(),
    )
    .unwrap();
    assert_eq!(
        cand.check.defect,
        Some(Defect::Toggle { pose: 1 }),
        "{:?}",
        cand.check
    );
}

#[test]
fn chebyshev_spacing_formula() {
    // n = 3 on [0, 1]: 1/2 ∓ (√3/2)/2 and 1/2 (cos π/6 = √3/2).
    let h = 3.0_f64.sqrt() / 4.0;
    let want = [0.5 - h, 0.5, 0.5 + h];
    for (j, w) in want.iter().enumerate() {
        let x = chebyshev_spacing(0.0, 1.0, 3, j);
        assert!((x - w).abs() < 1e-15, "j = {j}: {x} vs {w}");
    }
    // Symmetric about the middle; inside the interval; n = 1 is the midpoint; j ≥ n is NaN.
    for n in 1..9 {
        for j in 0..n {
            let (x, y) = (
                chebyshev_spacing(2.0_f64, 5.0, n, j),
                chebyshev_spacing(2.0, 5.0, n, n - 1 - j),
            );
            assert!(
                (x + y - 7.0).abs() < 1e-14 && x > 2.0 && x < 5.0,
                "n = {n} j = {j}: {x} and its mirror {y} on [2, 5]"
            );
        }
    }
    assert_eq!(chebyshev_spacing(2.0, 5.0, 1, 0), 3.5, "n = 1 on [2, 5]");
    let beyond = chebyshev_spacing(2.0_f64, 5.0, 3, 3);
    assert!(beyond.is_nan(), "j = n = 3: {beyond}");
}

/// The output angle of `fb` (from the ground line) at crank angle `theta`.
fn rocker_angle(fb: &FourBar<f64>, theta: f64) -> f64 {
    let b = fb.pose(theta).unwrap().b - fb.c;
    b.y.atan2(b.x)
}

#[test]
fn freudenstein_recovers_a_known_linkage() {
    let (d, a, b, c) = (1.0, 0.45, 1.1, 0.8);
    let fb = FourBar::new(d, a, b, c, (0.0, 0.0), Assembly::Open).unwrap();
    let k = Freudenstein::of_lengths(d, a, b, c).unwrap();
    assert_eq!(k.k1, d / a, "K1 = d/a");
    assert_eq!(k.k2, d / c, "K2 = d/c");
    let (lo, hi) = (0.5, 2.2);
    let phi: Vec<f64> = (0..3).map(|j| chebyshev_spacing(lo, hi, 3, j)).collect();
    let psi: Vec<f64> = phi.iter().map(|&t| rocker_angle(&fb, t)).collect();
    for (&f, &s) in phi.iter().zip(&psi) {
        let r = k.residual(f, s);
        assert!(r.abs() < 1e-14, "φ = {f}, ψ = {s}: residual {r:e}");
    }
    let fit = Freudenstein::fit(&phi, &psi).unwrap();
    for (x, y) in [(fit.k1, k.k1), (fit.k2, k.k2), (fit.k3, k.k3)] {
        assert!((x - y).abs() < 1e-12, "{fit:?} vs {k:?}");
    }
    let gen = FunctionGenerator::synthesise(&phi, &psi, d).unwrap();
    same_four_bar(&gen.four_bar, &fb, 1e-12);
    assert_eq!(
        (gen.input_offset, gen.output_offset),
        (0.0, 0.0),
        "input and output offsets"
    );
    // The linkage generates its own function exactly: zero structural error over the range.
    let xs: Vec<f64> = (0..201)
        .map(|i| lo + (hi - lo) * i as f64 / 200.0)
        .collect();
    let mut out = vec![0.0; xs.len()];
    let check = gen.sweep(&xs, &mut out, &phi, &psi).unwrap();
    assert_eq!(check.defect, None, "{check:?}");
    assert!(
        check.precision_error < 1e-12,
        "precision error {:e}",
        check.precision_error
    );
    let worst = xs
        .iter()
        .zip(&out)
        .map(|(&x, &y)| (y - rocker_angle(&fb, x)).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "{worst:e}");
    // Least squares over more points of the same function is exact too.
    let phi7: Vec<f64> = (0..7).map(|j| chebyshev_spacing(lo, hi, 7, j)).collect();
    let psi7: Vec<f64> = phi7.iter().map(|&t| rocker_angle(&fb, t)).collect();
    let gen7 = FunctionGenerator::synthesise(&phi7, &psi7, d).unwrap();
    same_four_bar(&gen7.four_bar, &fb, 1e-12);
}

#[test]
fn freudenstein_negative_link_is_a_half_turn_offset() {
    // Input angles measured from the opposite direction (φ = θ − π): K1 < 0, and the generator
    // turns its crank by π to meet them; the same linkage comes back.
    let (d, a, b, c) = (1.0, 0.45, 1.1, 0.8);
    let fb = FourBar::new(d, a, b, c, (0.0, 0.0), Assembly::Open).unwrap();
    let theta = [0.7, 1.4, 2.0];
    let phi: Vec<f64> = theta.iter().map(|t| t - PI).collect();
    let psi: Vec<f64> = theta.iter().map(|&t| rocker_angle(&fb, t)).collect();
    let gen = FunctionGenerator::synthesise(&phi, &psi, d).unwrap();
    assert!(
        gen.freudenstein.k1 < 0.0,
        "K1 = {} for φ = θ − π",
        gen.freudenstein.k1
    );
    assert_eq!(gen.input_offset, PI, "input offset for φ = θ − π");
    same_four_bar(&gen.four_bar, &fb, 1e-12);
    for (&f, &s) in phi.iter().zip(&psi) {
        let out = gen.output(f).unwrap();
        assert!((out - s).abs() < 1e-12, "φ = {f}: output {out} vs ψ = {s}");
    }
}

#[test]
fn structural_error_of_an_approximate_generator() {
    // y = log10 x on [1, 2]: φ from 45° over 60°, ψ from 135° over 90° (a classic set-up; the
    // numbers here are measured, not quoted). The structural error vanishes at the precision
    // points and the tracked output agrees with the untracked one everywhere (two ways).
    let (x0, x1) = (1.0_f64, 2.0_f64);
    let (f0, df) = (45f64.to_radians(), 60f64.to_radians());
    let (s0, ds) = (135f64.to_radians(), 90f64.to_radians());
    let phi_of = |x: f64| f0 + (x - x0) / (x1 - x0) * df;
    let psi_of = |x: f64| s0 + (x.log10() - x0.log10()) / (x1.log10() - x0.log10()) * ds;
    let xs: Vec<f64> = (0..3).map(|j| chebyshev_spacing(x0, x1, 3, j)).collect();
    let phi: Vec<f64> = xs.iter().map(|&x| phi_of(x)).collect();
    let psi: Vec<f64> = xs.iter().map(|&x| psi_of(x)).collect();
    let gen = FunctionGenerator::synthesise(&phi, &psi, 1.0).unwrap();
    let grid: Vec<f64> = (0..=400)
        .map(|i| x0 + (x1 - x0) * i as f64 / 400.0)
        .collect();
    let gphi: Vec<f64> = grid.iter().map(|&x| phi_of(x)).collect();
    let mut out = vec![0.0; grid.len()];
    let check = gen.sweep(&gphi, &mut out, &phi, &psi).unwrap();
    assert_eq!(check.defect, None, "{check:?}");
    assert!(
        check.precision_error < 1e-12,
        "precision error {:e}",
        check.precision_error
    );
    let mut worst: f64 = 0.0;
    for ((&x, &f), &o) in grid.iter().zip(&gphi).zip(&out) {
        let untracked = gen.output(f).unwrap();
        assert!(
            ((untracked - o + PI).rem_euclid(TAU) - PI).abs() < 1e-12,
            "x = {x}: untracked {untracked} vs tracked {o}"
        );
        worst = worst.max((o - psi_of(x)).abs());
    }
    // An approximation: a real, small error (less than a degree over a 90° output swing).
    assert!(worst > 1e-6 && worst < 1f64.to_radians(), "{worst}");
}

/// Independent check of a candidate reported as defect-free: a fresh tracker over its crank
/// angles, in small steps, keeps the branch and meets every pose.
fn independently_reaches(cand: &MotionCandidate<f64>, poses: &[BodyPose<f64>]) -> bool {
    let m = cand.four_bar.mechanism();
    let mut t = Tracker::new(&m).unwrap();
    let mut j = [Vec2::zeros(); 5];
    let angles = &cand.check.crank_angles[..poses.len()];
    // The orientation at pose 0: a change point's declared one holds at its start angle.
    if t.step(angles[0], None, &mut j, Rates::none()).is_err() {
        return false;
    }
    let s0 = t.branch(FourBar::<f64>::B);
    for (k, &th) in angles.iter().enumerate() {
        let from = if k == 0 { th } else { angles[k - 1] };
        for s in 0..=50 {
            let x = from + (th - from) * s as f64 / 50.0;
            if t.step(x, None, &mut j, Rates::none()).is_err() || t.branch(FourBar::<f64>::B) != s0
            {
                return false;
            }
        }
        let f = &cand.four_bar;
        let size = f
            .ground()
            .max(f.crank)
            .max(f.coupler)
            .max(f.rocker)
            .max(1.0);
        if (j[FourBar::<f64>::P] - poses[k].origin).norm() > 1e-9 * size {
            return false;
        }
    }
    true
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/precision.txt"))]

    /// Poses of a random four-bar, each on a random assembly, synthesised back from the
    /// pivots: the result either passes every pose on one circuit (checked independently) or
    /// is flagged; poses on one assembly of a crank-rocker, in crank order, are never flagged.
    #[test]
    fn every_candidate_passes_or_is_flagged(
        lens in (0.3f64..3.0, 0.3f64..3.0, 0.3f64..3.0, 0.3f64..3.0),
        pt in (-1.0f64..1.0, -1.0f64..1.0),
        start in 0.0f64..TAU,
        steps in prop::collection::vec(0.2f64..1.5, 3),
        asm in prop::collection::vec(any::<bool>(), 4),
        four in any::<bool>(),
        crank_rocker in any::<bool>(),
        mixed in any::<bool>(),
    ) {
        // Half the cases every pose on one assembly, the rest each on a random one.
        let asm: Vec<bool> = if mixed { asm } else { vec![asm[0]; 4] };
        // Half the cases a crank-rocker (crank 0.2…0.5, the others 1.6…2.4: s + l < p + q),
        // the rest any lengths (every Grashof class).
        let (g, r, b, c) = if crank_rocker {
            (1.6 + lens.0 * 0.3, 0.2 + lens.1 * 0.1, 1.6 + lens.2 * 0.3, 1.6 + lens.3 * 0.3)
        } else {
            lens
        };
        let fb = FourBar::new(g, r, b, c, pt, Assembly::Open).unwrap();
        let n = if four { 4 } else { 3 };
        let mut th = vec![start];
        for s in &steps[..n - 1] {
            th.push(th.last().unwrap() + s);
        }
        let mut poses = Vec::new();
        let mut ab = Vec::new();
        for k in 0..n {
            let a = if asm[k] { Assembly::Open } else { Assembly::Crossed };
            let f = FourBar { assembly: a, ..fb };
            let Ok(p) = f.pose(th[k]) else { return Ok(()) };
            if p.margin < 1e-3 { return Ok(()); }
            let d = p.b - p.a;
            poses.push(BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap());
            ab.push((p.a, p.b));
        }
        let crank = BurmesterPair { centre: fb.o, circle: ab[0].0 };
        let rocker = BurmesterPair { centre: fb.c, circle: ab[0].1 };
        let Ok(cand) = MotionCandidate::new(&poses, crank, rocker) else { return Ok(()) };
        if cand.check.defect.is_none() {
            prop_assert!(independently_reaches(&cand, &poses), "{:?}", cand.check);
            prop_assert!(cand.check.position_error < 1e-9, "position error {:e}: {:?}", cand.check.position_error, cand.check);
        }
        let same = asm[..n].iter().all(|&x| x == asm[0]);
        let total: f64 = steps[..n - 1].iter().sum();
        if fb.grashof() == GrashofClass::CrankRocker && total < TAU - 0.01 {
            if same {
                prop_assert_eq!(cand.check.defect, None, "poses on one assembly of a crank-rocker: {:?}", cand.check);
            } else {
                // Two assemblies of a crank-rocker are two circuits.
                prop_assert!(cand.check.defect.is_some(), "assemblies {:?} of a crank-rocker not flagged: {:?}", &asm[..n], cand.check);
            }
        }
    }

    /// Four random poses: every pair of sampled Burmester dyads makes a four-bar that either
    /// passes the poses on one circuit (checked independently) or is flagged.
    #[test]
    fn burmester_pairs_pass_or_are_flagged(
        q in prop::collection::vec((-2.0f64..2.0, -2.0f64..2.0, -1.5f64..1.5), 4),
        b1 in 0.0f64..TAU,
        b2 in 0.0f64..TAU,
    ) {
        let poses: Vec<BodyPose<f64>> =
            q.iter().map(|&(x, y, a)| BodyPose::new(x, y, a).unwrap()).collect();
        let p4: [BodyPose<f64>; 4] = poses.clone().try_into().unwrap();
        let Ok(curve) = BurmesterCurve::new(&p4) else { return Ok(()) };
        let d1: Vec<_> = curve.dyads(b1).into_iter().flatten().collect();
        let d2: Vec<_> = curve.dyads(b2).into_iter().flatten().collect();
        for x in &d1 {
            for y in &d2 {
                let Ok(cand) = MotionCandidate::new(&poses, *x, *y) else { continue };
                if cand.check.defect.is_none() {
                    prop_assert!(independently_reaches(&cand, &poses), "{:?}", cand.check);
                }
            }
        }
    }
}

#[test]
fn generic_over_f32() {
    let fb = FourBar::<f32>::with_pivots(
        Vec2::new(0.3, -0.2),
        Vec2::new(2.3, 0.4),
        0.7,
        1.9,
        1.6,
        (0.8, 0.6),
        Assembly::Open,
    )
    .unwrap();
    let mut poses = Vec::new();
    let mut pins = Vec::new();
    for t in [0.4_f32, 1.3, 2.5] {
        let p = fb.pose(t).unwrap();
        let d = p.b - p.a;
        poses.push(BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap());
        pins.push((p.a, p.b));
    }
    let p3: [BodyPose<f32>; 3] = poses.clone().try_into().unwrap();
    let crank = centre_point(&p3, pins[0].0).unwrap();
    let rocker = centre_point(&p3, pins[0].1).unwrap();
    assert!(
        (crank.centre - fb.o).norm() < 1e-4 && (rocker.centre - fb.c).norm() < 1e-4,
        "f32: crank centre {:?} vs O {:?}, rocker centre {:?} vs C {:?}",
        crank.centre,
        fb.o,
        rocker.centre,
        fb.c
    );
    let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
    assert_eq!(cand.check.defect, None, "f32: {:?}", cand.check);
    assert!(
        cand.check.position_error < 1e-4,
        "f32: position error {:e}",
        cand.check.position_error
    );
    let f = FourBar::<f32>::new(1.0, 0.45, 1.1, 0.8, (0.0, 0.0), Assembly::Open).unwrap();
    let phi = [0.6_f32, 1.3, 2.0];
    let psi = phi.map(|t| {
        let b = f.pose(t).unwrap().b - f.c;
        b.y.atan2(b.x)
    });
    let gen = FunctionGenerator::synthesise(&phi, &psi, 1.0).unwrap();
    assert!(
        (gen.four_bar.crank - 0.45).abs() < 1e-4 && (gen.four_bar.rocker - 0.8).abs() < 1e-4,
        "f32 Freudenstein: crank {} vs 0.45, rocker {} vs 0.8",
        gen.four_bar.crank,
        gen.four_bar.rocker
    );
}

/// Three poses turning about one point (the trial's case: a body pinned at the origin): every
/// circle point's centre is that point, so two dyads share their fixed pivot. Before the ground
/// check, `MotionCandidate::new` assembled a four-bar with a ground of 3.5e-16 and passed it.
#[test]
fn rotations_about_one_point_make_no_four_bar() {
    let p = |x: f64, y: f64, a: f64| BodyPose::new(x, y, a).unwrap();
    let poses = [p(0.0, 0.0, 0.0), p(0.0, 0.0, 0.5), p(0.0, 0.0, 1.0)];
    assert_eq!(
        common_pole(&poses),
        Ok(Some(Vec2::zeros())),
        "pure rotation"
    );
    let crank = centre_point(&poses, Vec2::new(1.0, 0.0)).unwrap();
    let rocker = centre_point(&poses, Vec2::new(0.0, 1.0)).unwrap();
    let r = MotionCandidate::new(&poses, crank, rocker);
    assert!(
        matches!(r, Err(Error::Degenerate { .. })),
        "dyads sharing their fixed pivot: {r:?}"
    );
    // About an off-origin point, built with rounding: the pole is found to rounding.
    let about = Vec2::new(1.5, -2.0);
    let turned = |a: f64| {
        let d = about + nalgebra::Rotation2::new(a) * (-about);
        p(d.x, d.y, a)
    };
    let x = common_pole(&[turned(0.1), turned(0.7), turned(1.9)])
        .unwrap()
        .expect("rotations about (1.5, -2)");
    assert!((x - about).norm() < 1e-12, "pole {x:?}");
    // A body that also moves its pole has none in common; a pure translation has none.
    let moved = [turned(0.1), turned(0.7), p(0.3, 0.0, 1.9)];
    assert_eq!(common_pole(&moved), Ok(None), "not one rotation");
    let slide = [p(0.0, 0.0, 0.2), p(1.0, 0.0, 0.2), p(2.0, 1.0, 0.2)];
    assert_eq!(common_pole(&slide), Ok(None), "translations");
    assert!(
        matches!(
            common_pole(&[poses[0], poses[0], poses[1]]),
            Err(Error::CoincidentPositions {
                first: 0,
                second: 1
            })
        ),
        "coincident poses"
    );
}

/// The free pose can be chosen: at the crank's own rotation to that pose, the crank dyad of the
/// four-bar the poses came from is on the curve, for each of poses 1, 2 and 3.
#[test]
fn burmester_curve_at_a_chosen_free_pose() {
    let fb = crank_rocker();
    let thetas = [0.2, 0.9, 1.7, 2.6];
    let poses = thetas.map(|t| coupler_pose(&fb, t, Assembly::Open).0);
    let a0 = coupler_pose(&fb, thetas[0], Assembly::Open).1;
    for k in 1..=3 {
        let curve = BurmesterCurve::with_free_pose(&poses, k).unwrap();
        assert_eq!(curve.free_pose(), k, "free pose");
        let found = curve.dyads(thetas[k] - thetas[0]);
        let near = |d: &BurmesterPair<f64>| (d.centre - fb.o).norm() + (d.circle - a0).norm();
        let best = found
            .iter()
            .flatten()
            .map(near)
            .fold(f64::INFINITY, f64::min);
        assert!(
            best < 1e-10,
            "free pose {k}: nearest dyad {best:e} from the crank"
        );
    }
    for k in [0, 4] {
        assert!(
            matches!(
                BurmesterCurve::with_free_pose(&poses, k),
                Err(Error::InvalidChoice { .. })
            ),
            "free pose {k}"
        );
    }
}

/// More than three precision points are a least-squares fit in O(m): a repeated point weighs
/// twice instead of being searched for pairwise (which took ~1 s at 30 000 points through
/// Python, growing as m²), and the fit of a linkage's own function stays exact.
#[test]
fn freudenstein_fit_of_many_points_is_linear_time() {
    let fb = FourBar::new(1.0_f64, 0.45, 1.1, 0.8, (0.0, 0.0), Assembly::Open).unwrap();
    let out = |t: f64| {
        let b = fb.pose(t).unwrap().b - fb.c;
        b.y.atan2(b.x)
    };
    let m = 200_000;
    let phi: Vec<f64> = (0..m)
        .map(|j| 0.5 + 1.7 * j as f64 / (m - 1) as f64)
        .collect();
    let mut psi: Vec<f64> = phi.iter().map(|&t| out(t)).collect();
    let (phi, psi) = {
        let mut phi = phi;
        phi.push(phi[0]); // a repeated point
        psi.push(psi[0]);
        (phi, psi)
    };
    let start = std::time::Instant::now();
    let k = Freudenstein::fit(&phi, &psi).unwrap();
    let took = start.elapsed().as_secs_f64();
    let (d, a, b, c) = (1.0, 0.45, 1.1, 0.8);
    let want = [
        d / a,
        d / c,
        (a * a - b * b + c * c + d * d) / (2.0 * a * c),
    ];
    for (got, want) in [k.k1, k.k2, k.k3].into_iter().zip(want) {
        assert!((got - want).abs() < 1e-9, "K {got} vs {want}");
    }
    // Linear: milliseconds; the pairwise search needed 2·10¹⁰ steps (tens of seconds).
    assert!(took < 2.0, "fit of {m} points took {took} s");
}
