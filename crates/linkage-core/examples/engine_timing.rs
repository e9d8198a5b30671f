//! Times the core sweep engine on Hoecken's four-bar at 10^6 arbitrary angles (position only,
//! then with rates), in-process; bench/engine.py compares the Python API with numpy.
use linkage_core::{catalog, sweep, Columns, Rate, SweepOutputs, Vec2};
use std::time::Instant;

fn main() {
    let fb = catalog::hoecken::<f64>();
    let m = fb.mechanism();
    let n = 1_000_000;
    let j = m.len();
    // A fixed pseudo-random sequence of angles in [-π, 3π).
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let theta: Vec<f64> = (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            -std::f64::consts::PI
                + 4.0 * std::f64::consts::PI * (x >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let mut joints = vec![Vec2::zeros(); n * j];
    let mut vel = vec![Vec2::zeros(); n * j];
    let mut acc = vec![Vec2::zeros(); n * j];
    let (mut valid, mut regular) = (vec![false; n], vec![false; n]);
    let (mut margin, mut gap) = (vec![0.0; n], vec![0.0; n]);
    let only_point = std::env::args().any(|a| a == "--point");
    for rates in [false, true] {
        if only_point {
            break;
        }
        let mut times = Vec::new();
        for _ in 0..5 {
            let out = SweepOutputs {
                columns: Columns::All,
                joints: &mut joints,
                valid: &mut valid,
                margin: Some(&mut margin),
                regular: Some(&mut regular),
                gap: Some(&mut gap),
                velocity: rates.then_some(&mut vel[..]),
                acceleration: rates.then_some(&mut acc[..]),
                centres: None,
                centre_directions: None,
                curvature_centres: None,
                curvature: None,
            };
            let t = Instant::now();
            sweep(
                &m,
                &theta,
                Rate::Scalar(2.0),
                Rate::Scalar(0.5),
                out,
                &mut || true,
            )
            .unwrap();
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        println!(
            "all joints, flags, rates {rates:5}: {:7.2} ns/sample (checksum {:.6})",
            times[2] * 1e9 / n as f64,
            joints[4 * 7].x
        );
    }
    // The coupler point only, validity only: what `FourBar.sweep(θ, outputs=("point",))` asks.
    let mut point = vec![Vec2::zeros(); n];
    let mut times = Vec::new();
    for _ in 0..if only_point { 40 } else { 5 } {
        let mut out = SweepOutputs::positions(&mut point, &mut valid);
        out.columns = Columns::One(4);
        let t = Instant::now();
        sweep(
            &m,
            &theta,
            Rate::Scalar(0.0),
            Rate::Scalar(0.0),
            out,
            &mut || true,
        )
        .unwrap();
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    println!(
        "coupler point only: {:7.2} ns/sample (checksum {:.6})",
        times[2] * 1e9 / n as f64,
        point[7].x
    );
}
