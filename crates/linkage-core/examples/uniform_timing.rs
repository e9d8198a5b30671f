//! Times the fast four-bar sweep modes in-process (median of 7 after a warm-up); the full
//! work-precision benchmark (errors against mpmath, peers) is `make bench`.
use linkage_core::{catalog, AngleMode, Vec2};
use std::time::Instant;

fn main() {
    let fb = catalog::hoecken::<f64>();
    let n = 1_000_000;
    let dt = std::f64::consts::TAU / n as f64;
    let mut out = vec![Vec2::zeros(); n];
    for (name, mode) in [
        ("trig", AngleMode::Trig),
        ("table", AngleMode::Table { block: 64 }),
        ("recurrence", AngleMode::Recurrence { block: 64 }),
    ] {
        fb.uniform_sweep(0.0, dt, 0, mode, &mut out).unwrap();
        let mut times: Vec<f64> = (0..7)
            .map(|_| {
                let t = Instant::now();
                fb.uniform_sweep(0.0, dt, 0, mode, &mut out).unwrap();
                t.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(f64::total_cmp);
        println!(
            "{name:<11} {:6.2} ns/sample (checksum {:.6})",
            times[3] * 1e9 / n as f64,
            out[n / 3].x
        );
    }
}
