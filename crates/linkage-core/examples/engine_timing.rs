//! Times the core sweep engine on Hoecken's four-bar at 10^6 arbitrary angles (position only,
//! then with rates), in-process; bench/engine.py compares the Python API with numpy.
use linkage_core::{catalog, sweep, Columns, Pairs, Rate, SweepOutputs, Vec2};
use std::time::Instant;

/// The median over `runs` calls of `run`, in ns a sample of `n`.
fn median_ns(runs: usize, n: usize, mut run: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            run();
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times.get(runs / 2).map_or(f64::NAN, |t| t * 1e9 / n as f64)
}

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
    // `--centres`: only the instant-centre and curvature cases (for a profiler).
    let only_centres = std::env::args().any(|a| a == "--centres");
    for rates in [false, true] {
        if only_point || only_centres {
            break;
        }
        let ns = median_ns(5, n, || {
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
                pairs: Pairs::All,
                centre_directions: None,
                curvature_centres: None,
                curvature: None,
            };
            let (w, a) = (Rate::Scalar(2.0), Rate::Scalar(0.5));
            sweep(&m, &theta, w, a, out, &mut || true).unwrap();
        });
        println!(
            "all joints, flags, rates {rates:5}: {ns:7.2} ns/sample (checksum {:.6})",
            joints[4 * 7].x
        );
    }
    // The coupler point only, validity only: what `FourBar.sweep(θ, outputs=("point",))` asks.
    let mut point = vec![Vec2::zeros(); n];
    if !only_centres {
        let ns = median_ns(if only_point { 40 } else { 5 }, n, || {
            let mut out = SweepOutputs::positions(&mut point, &mut valid);
            out.columns = Columns::One(4);
            let zero = Rate::Scalar(0.0);
            sweep(&m, &theta, zero, zero, out, &mut || true).unwrap();
        });
        println!(
            "coupler point only: {ns:7.2} ns/sample (checksum {:.6})",
            point[7].x
        );
    }
    if only_point {
        return;
    }
    // The point with instant centres (every pair, or the two secondary ones: ground–coupler
    // and crank–rocker) and/or its path curvature, into warm buffers.
    let two = [[0, 2], [1, 3]];
    let mut centres = vec![Vec2::zeros(); 6 * n];
    let mut dirs = vec![Vec2::zeros(); 6 * n];
    let mut curv_centre = vec![Vec2::zeros(); n];
    let mut curv = vec![0.0; n];
    for (name, pairs, with_centres, with_curvature) in [
        ("point + curvature", Pairs::All, false, true),
        ("point + 2 centres", Pairs::Only(&two), true, false),
        (
            "point + 2 centres + curvature",
            Pairs::Only(&two),
            true,
            true,
        ),
        ("point + 6 centres + curvature", Pairs::All, true, true),
    ] {
        let np = pairs.count(4);
        let ns = median_ns(7, n, || {
            let mut out = SweepOutputs::positions(&mut point, &mut valid);
            out.columns = Columns::One(4);
            out.pairs = pairs;
            if with_centres {
                out.centres = Some(&mut centres[..np * n]);
                out.centre_directions = Some(&mut dirs[..np * n]);
            }
            if with_curvature {
                out.curvature = Some(&mut curv);
                out.curvature_centres = Some(&mut curv_centre);
            }
            let zero = Rate::Scalar(0.0);
            sweep(&m, &theta, zero, zero, out, &mut || true).unwrap();
        });
        println!("{name:>30}: {ns:7.2} ns/sample");
    }
}
