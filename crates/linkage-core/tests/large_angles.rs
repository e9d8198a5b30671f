//! Sweeps at large crank angles against an exact reduction (issue 29, item 7): every catalogue
//! mechanism, tracked and held, at θ from 10⁶ to 10³⁰⁰ gives the pose of `θ mod 2π` to within
//! 1e-13 of its size, and assembles where that angle does.

use linkage_core::catalog::{self, Linkage};
use linkage_core::{
    sweep_planned, Mechanism, Plan, Rate, Rates, Side, SweepOutputs, Tracker, Vec2,
};

/// `(θ, θ mod 2π)`: the remainder computed by mpmath at 4000 bits, rounded to f64.
const REDUCED: [(f64, f64); 11] = [
    (1e6, 5.925621140093852),
    (-1e6, 0.357564167085735),
    (1e11, 1.1908745855222387),
    (1.6e15, 3.37551698731218),
    (-1.6e15, 2.9076683198674065),
    (1e16, 2.2474252491623665),
    (1e17, 3.624696570084906),
    (1e22, 5.263007914620499),
    (1e100, 5.892699463987461),
    (1e300, 4.099312823027354),
    (-1e300, 2.1838724841522326),
];

/// Joints and validity of a sweep of `m` over `theta` by `plan`.
fn swept<const N: usize>(
    m: &Mechanism<f64, N>,
    theta: &[f64],
    plan: Plan,
) -> (Vec<Vec2<f64>>, Vec<bool>) {
    let mut joints = vec![Vec2::zeros(); theta.len() * m.len()];
    let mut valid = vec![false; theta.len()];
    let out = SweepOutputs::positions(&mut joints, &mut valid);
    sweep_planned(
        m,
        theta,
        Rate::Scalar(0.0),
        Rate::Scalar(0.0),
        out,
        &mut || true,
        plan,
    )
    .unwrap();
    (joints, valid)
}

/// The worst difference, relative to the size, between sweeps at large angles and at their
/// exact reductions, over single samples and a sample between two small ones.
fn worst_error<const N: usize>(name: &str, m: &Mechanism<f64, N>) -> f64 {
    let mut worst = 0.0f64;
    for plan in [Plan::Tracked, Plan::Held] {
        for &(big, small) in &REDUCED {
            for (at, reference) in [
                (vec![big], vec![small]),
                (vec![0.5, big, 1.0], vec![0.5, small, 1.0]),
            ] {
                let (j, v) = swept(m, &at, plan);
                let (jr, vr) = swept(m, &reference, plan);
                assert_eq!(
                    v, vr,
                    "{name} {plan:?} at {big:e}: valid {v:?}, reduced {vr:?}"
                );
                let size = jr
                    .iter()
                    .filter(|p| p.x.is_finite())
                    .map(|p| p.amax())
                    .fold(0.0, f64::max);
                for (p, q) in j.iter().zip(&jr) {
                    if q.x.is_finite() {
                        worst = worst.max((p - q).amax() / size);
                    }
                }
            }
        }
    }
    worst
}

#[test]
fn every_catalogue_mechanism_is_exact_at_large_angles() {
    for name in catalog::MULTI_LOOP {
        let l: Linkage<f64> = catalog::linkage_by_name(name).unwrap();
        let e = worst_error(name, &l.mechanism);
        assert!(e <= 1e-13, "{name}: {e:e} of the size");
    }
    for name in catalog::FOUR_BARS {
        let fb = catalog::four_bar_by_name::<f64>(name).unwrap();
        let e = worst_error(name, &fb.mechanism());
        assert!(e <= 1e-13, "{name} as a mechanism: {e:e} of the size");
    }
}

/// A crank with a phase and a parallelogram (a change point: its orientation turns at each
/// flat position, counted from the parity of `(θ + phase − β)/2`): both need the reduction.
#[test]
fn a_phased_crank_and_flat_positions_are_exact_at_large_angles() {
    let mut m = Mechanism::<f64, 5>::new();
    let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
    let c = m.fixed(Vec2::new(3.0, 1.0)).unwrap();
    let a = m.crank(o, 1.0, 0.7).unwrap();
    m.dyad(a, c, 10.0_f64.sqrt(), 1.0, Side::Left).unwrap();
    let e = worst_error("parallelogram", &m);
    assert!(e <= 1e-13, "{e:e} of the size");
}

/// `f32` reduces through `f64`: Jansen at 10³⁰ (the f32 nearest, 1.0000000150474662e30, whose
/// remainder is 4.054301589147091) agrees with its reduction to f32 accuracy.
#[test]
fn f32_sweeps_are_reduced_too() {
    let m = catalog::jansen::<f32>().mechanism;
    let (mut j, mut jr) = ([Vec2::zeros(); 8], [Vec2::zeros(); 8]);
    for (theta, out) in [(1e30, &mut j), (4.054_301_6, &mut jr)] {
        let mut t = Tracker::new(&m).unwrap();
        t.step(theta, None, &mut out[..m.len()], Rates::none())
            .unwrap();
    }
    for (p, q) in j.iter().zip(&jr) {
        assert!((p - q).amax() < 1e-4 * 100.0, "{p:?} against {q:?}");
    }
}
