//! Kinetostatics: a static case by hand, Newton–Euler against the power method, and the work
//! of the driver against the change of energy.

use linkage_core::{
    Assembly, Bodies, CrankRates, Dynamics, Error, ForceSweep, FourBar, Inertia, Load, LoadSeries,
    Mechanism, Vec2,
};
use std::f64::consts::PI;

type State = (Vec<Vec2<f64>>, Vec<Vec2<f64>>, Vec<Vec2<f64>>);

fn state<const N: usize>(m: &Mechanism<f64, N>, theta: f64, omega: f64, alpha: f64) -> State {
    let n = m.len();
    let (mut p, mut v, mut a) = (
        vec![Vec2::zeros(); n],
        vec![Vec2::zeros(); n],
        vec![Vec2::zeros(); n],
    );
    m.pose(theta, &mut p).unwrap();
    m.rates(
        &p,
        CrankRates::new(omega, alpha),
        &mut v,
        Some(&mut a),
        None,
    )
    .unwrap();
    (p, v, a)
}

fn massless(n: usize) -> Vec<Inertia<f64>> {
    vec![
        Inertia {
            mass: 0.0,
            along: 0.0,
            left: 0.0,
            inertia: 0.0
        };
        n
    ]
}

/// Thesis 2 (docs/domain.md): the Hoecken leg in metres, link masses, inertias and centres of mass.
fn thesis_two() -> (FourBar<f64>, Vec<Inertia<f64>>) {
    let fb = FourBar::new(0.020, 0.010, 0.025, 0.025, (0.050, 0.0), Assembly::Open).unwrap();
    let i = |mass, along, inertia| Inertia {
        mass,
        along,
        left: 0.0,
        inertia,
    };
    let inertia = vec![
        i(0.0, 0.0, 0.0),
        i(0.0036, 0.005, 0.122432e-6),
        i(0.0210, 0.0312566, 2.17781e-6),
        i(0.0060, 0.0125, 0.774427e-6),
    ];
    (fb, inertia)
}

/// Static hand calculation: a parallelogram's coupler translates, so a load W at any coupler
/// point needs the crank torque T = W·r·cos θ (virtual work: T δθ = −F·δP, δP = δA).
#[test]
fn static_parallelogram_against_hand_calculation() {
    let fb = FourBar::new(3.0, 1.0, 3.0, 1.0, (1.5, 0.0), Assembly::Open).unwrap();
    let m = fb.mechanism();
    let dynamics = Dynamics::new(&m, &massless(4), Vec2::zeros()).unwrap();
    let coupler = Bodies::of(&m).ids().nth(2).unwrap();
    let w = 7.0;
    // (0, π): the declared assembly is the parallelogram there; past π it is the crossed one.
    for th in [0.3, 1.0, 2.2, 2.9] {
        let (p, v, a) = state(&m, th, 0.0, 0.0);
        let load = [Load {
            body: coupler,
            joint: 4,
            force: Vec2::new(0.0, -w),
            torque: 0.0,
        }];
        let sol = dynamics.solve(&p, &v, &a, &load).unwrap();
        assert!(
            (sol.torque - w * 1.0 * th.cos()).abs() < 1e-12,
            "{th}: {}",
            sol.torque
        );
        // The reactions balance the load: pins O and C carry W between them.
        let ground_pins: f64 = sol
            .reactions
            .iter()
            .filter(|r| r.joint == 0 || r.joint == 1)
            .map(|r| r.force.y)
            .sum();
        assert!(
            (ground_pins - w).abs() < 1e-12,
            "{th}: ground pins carry {ground_pins}, load {w}"
        );
    }
}

/// Newton–Euler torque equals the power-method torque at every sample, for the thesis 2 leg at
/// 20 rpm clockwise with its 0.5·9.81 N foot force, with and without gravity.
#[test]
fn newton_euler_equals_power_method() {
    let (fb, inertia) = thesis_two();
    let m = fb.mechanism();
    let coupler = Bodies::of(&m).ids().nth(2).unwrap();
    let omega = -20.0 * 2.0 * PI / 60.0;
    for gravity in [Vec2::zeros(), Vec2::new(0.0, -9.81)] {
        let dynamics = Dynamics::new(&m, &inertia, gravity).unwrap();
        let load = [Load {
            body: coupler,
            joint: 4,
            force: Vec2::new(0.5 * 9.81, 0.0),
            torque: 0.0,
        }];
        for k in 0..360 {
            let th = k as f64 * PI / 180.0;
            let (p, v, a) = state(&m, th, omega, 0.3);
            let ne = dynamics.solve(&p, &v, &a, &load).unwrap().torque;
            let pw = dynamics.power_torque(&p, &v, &a, &load);
            assert!(
                (ne - pw).abs() <= 1e-12 * (1.0 + ne.abs()),
                "{k}: {ne} vs {pw}"
            );
        }
    }
}

/// Over half a turn under a varying crank speed, the driver's work equals the change of
/// kinetic and potential energy minus the work of the external force (trapezoid rule on 20 000
/// steps: agreement to 1e-6 of the work).
#[test]
fn work_energy_balance() {
    let (fb, inertia) = thesis_two();
    let m = fb.mechanism();
    let ids: Vec<_> = Bodies::of(&m).ids().collect();
    let coupler = ids[2];
    let g = Vec2::new(0.0, -9.81);
    let dynamics = Dynamics::new(&m, &inertia, g).unwrap();
    let force = Vec2::new(0.5 * 9.81, -1.0);
    let load = [Load {
        body: coupler,
        joint: 4,
        force,
        torque: 0.0,
    }];
    // θ(t) = t + 0.3 sin(2t) over t in [0, π/2]: ω = 1 + 0.6 cos 2t, α = −1.2 sin 2t.
    let motion = |t: f64| {
        (
            t + 0.3 * (2.0 * t).sin(),
            1.0 + 0.6 * (2.0 * t).cos(),
            -1.2 * (2.0 * t).sin(),
        )
    };
    let energy = |t: f64| {
        let (th, w, al) = motion(t);
        let (p, v, a) = state(&m, th, w, al);
        let bodies = Bodies::of(&m);
        let zero = vec![Vec2::zeros(); p.len()];
        let mut e = 0.0;
        for (k, &id) in ids.iter().enumerate().skip(1) {
            let bm = linkage_core::BodyMotion::of(&bodies, id, &p, &v, &a, &zero);
            let i = inertia[k];
            let (origin, toward) = match bodies.frame(id) {
                linkage_core::BodyFrame::Link { origin, toward } => (p[origin], p[toward]),
                _ => unreachable!(),
            };
            let u = (toward - origin).normalize();
            let gpos = origin + u * i.along;
            let vg = bm.velocity_at(gpos);
            e += 0.5 * i.mass * vg.norm_squared() + 0.5 * i.inertia * bm.omega * bm.omega
                - i.mass * g.dot(&gpos);
        }
        (e, p[4], v[4])
    };
    let n = 20_000;
    let t1 = PI / 2.0;
    let (mut work_driver, mut work_ext) = (0.0, 0.0);
    let power = |t: f64| {
        let (th, w, al) = motion(t);
        let (p, v, a) = state(&m, th, w, al);
        let torque = dynamics.solve(&p, &v, &a, &load).unwrap().torque;
        (torque * w, force.dot(&v[4]))
    };
    let mut prev = power(0.0);
    for k in 1..=n {
        let t = t1 * k as f64 / n as f64;
        let cur = power(t);
        let dt = t1 / n as f64;
        work_driver += 0.5 * (prev.0 + cur.0) * dt;
        work_ext += 0.5 * (prev.1 + cur.1) * dt;
        prev = cur;
    }
    let (e0, _, _) = energy(0.0);
    let (e1, _, _) = energy(t1);
    let balance = (e1 - e0) - work_ext;
    assert!(
        (work_driver - balance).abs() < 1e-6 * work_driver.abs().max(balance.abs()),
        "driver {work_driver:e}, ΔE − W_ext {balance:e}"
    );
}

#[test]
fn wrong_inertia_count_is_an_error() {
    let (fb, inertia) = thesis_two();
    let m = fb.mechanism();
    assert!(
        Dynamics::new(&m, &inertia[..3], Vec2::zeros()).is_err(),
        "3 of {} inertias accepted",
        inertia.len()
    );
}

/// The sweep gives, sample for sample, what `solve` and `power_torque` give on the posed
/// mechanism (thesis 2 leg, gravity, the foot force varying along the sweep); a sample past a
/// triple rocker's limit is NaN and not valid; wrong lengths are errors.
#[test]
fn sweep_equals_the_per_sample_solve() {
    let (fb, inertia) = thesis_two();
    let m = fb.mechanism();
    let coupler = Bodies::of(&m).ids().nth(2).unwrap();
    let dynamics = Dynamics::new(&m, &inertia, Vec2::new(0.0, -9.81)).unwrap();
    let n = 97;
    let theta: Vec<f64> = (0..n).map(|k| 0.3 + k as f64 * 0.065).collect();
    let omega: Vec<f64> = theta.iter().map(|t| -2.0 + 0.5 * t.sin()).collect();
    let alpha: Vec<f64> = theta.iter().map(|t| 0.25 * t.cos()).collect();
    let force: Vec<Vec2<f64>> = theta.iter().map(|t| Vec2::new(4.9, t.cos())).collect();
    let torque: Vec<f64> = theta.iter().map(|t| 1e-3 * t).collect();
    let loads = [LoadSeries {
        body: coupler,
        joint: 4,
        force: &force,
        torque: &torque,
    }];
    let nr = dynamics.reaction_layout().count();
    let (mut tq, mut pw, mut ok) = (vec![0.0; n], vec![0.0; n], vec![false; n]);
    let (mut re, mut co) = (vec![Vec2::zeros(); n * nr], vec![0.0; n * nr]);
    let out = ForceSweep {
        torque: &mut tq,
        power_torque: &mut pw,
        valid: &mut ok,
        reactions: &mut re,
        couples: &mut co,
    };
    dynamics.sweep(&theta, &omega, &alpha, &loads, out).unwrap();
    for k in 0..n {
        let (p, v, a) = state(&m, theta[k], omega[k], alpha[k]);
        let load = [Load {
            body: coupler,
            joint: 4,
            force: force[k],
            torque: torque[k],
        }];
        let sol = dynamics.solve(&p, &v, &a, &load).unwrap();
        assert!(ok[k], "sample {k} should solve");
        assert!(
            (tq[k] - sol.torque).abs() <= 1e-13 * (1.0 + sol.torque.abs()),
            "{k}"
        );
        let power = dynamics.power_torque(&p, &v, &a, &load);
        assert!((pw[k] - power).abs() <= 1e-13 * (1.0 + power.abs()), "{k}");
        for (q, r) in sol.reactions.iter().enumerate() {
            assert!(
                (re[k * nr + q] - r.force).norm() <= 1e-12 * (1.0 + r.force.norm()),
                "{k}"
            );
            assert_eq!(co[k * nr + q], r.couple, "{k}/{q}");
        }
    }
    // Evans C (a triple rocker, limits ±75.5°): samples past its limit are NaN, not valid.
    let evans = FourBar::new(20.0, 10.0, 10.0, 10.0, (0.0, 10.0), Assembly::Open).unwrap();
    let me = evans.mechanism();
    let de = Dynamics::new(&me, &massless(4), Vec2::zeros()).unwrap();
    let th = [0.0, 2.0, 0.5];
    let nre = de.reaction_layout().count();
    let (mut tq, mut pw, mut ok) = ([0.0; 3], [0.0; 3], [true; 3]);
    let (mut re, mut co) = (vec![Vec2::zeros(); 3 * nre], vec![0.0; 3 * nre]);
    let out = ForceSweep {
        torque: &mut tq,
        power_torque: &mut pw,
        valid: &mut ok,
        reactions: &mut re,
        couples: &mut co,
    };
    de.sweep(&th, &[1.0; 3], &[0.0; 3], &[], out).unwrap();
    assert_eq!(
        ok,
        [true, false, true],
        "valid flags at θ = {th:?} (Evans C limits ±75.5°)"
    );
    assert!(
        tq[1].is_nan() && pw[1].is_nan() && re[nre].x.is_nan(),
        "past the limit: torque {}, power torque {}, reaction {:?}",
        tq[1],
        pw[1],
        re[nre]
    );
    // One omega short: an error naming the slice, nothing solved.
    let out = ForceSweep {
        torque: &mut tq,
        power_torque: &mut pw,
        valid: &mut ok,
        reactions: &mut re,
        couples: &mut co,
    };
    let err = de.sweep(&th, &[1.0; 2], &[0.0; 3], &[], out);
    assert!(matches!(err, Err(Error::BufferLength { .. })), "{err:?}");
}
