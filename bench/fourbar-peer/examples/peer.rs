//! Coupler-curve generation per sample: the `four-bar` crate's `curve_by` against
//! linkage-core's uniform sweep, same Hoecken linkage and angles, in one process (median of 7
//! timed runs after a warm-up). Prints one `name ns_per_sample max_error` line per method; the
//! errors are against linkage-core's `Trig` mode (the benchmark's mpmath check covers it).
use four_bar::mech::{fb::UnNorm, CurveGen, FourBar, NormFourBar, Stat};
use linkage_core::{catalog, AngleMode, Vec2};
use std::time::Instant;

fn median<F: FnMut()>(mut f: F) -> f64 {
    f();
    let mut t: Vec<f64> = (0..7)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[3]
}

fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(1_000_000);
    let dt = std::f64::consts::TAU / n as f64;
    let theta: Vec<f64> = (0..n).map(|k| dt * k as f64).collect();
    let ours = catalog::hoecken::<f64>();
    let peer = FourBar::new(
        UnNorm { p1x: 0.0, p1y: 0.0, a: 0.0, l2: 10.0 },
        NormFourBar { l1: 20.0, l3: 25.0, l4: 25.0, l5: 50.0, g: 0.0, stat: Stat::C1B1 },
    );
    let mut reference = vec![Vec2::zeros(); n];
    ours.uniform_sweep(0.0, dt, 0, AngleMode::Trig, &mut reference).unwrap();
    let mut curve = Vec::new();
    let t_peer = median(|| curve = peer.curve_by(&theta));
    // The peer's branch convention may mirror ours: compare against either assembly.
    let mirrored = |p: [f64; 2], q: Vec2<f64>| ((p[0] - q.x).hypot(p[1] - q.y)).min((p[0] - q.x).hypot(p[1] + q.y));
    let err_peer = curve.iter().zip(&reference).map(|(p, q)| mirrored(*p, *q)).fold(0.0, f64::max);
    println!("four-bar-crate {:.3} {:.3e}", t_peer * 1e9 / n as f64, err_peer);
    let mut out = vec![Vec2::zeros(); n];
    for (name, mode) in [
        ("linkage-trig", AngleMode::Trig),
        ("linkage-table", AngleMode::Table { block: 64 }),
        ("linkage-recurrence", AngleMode::Recurrence { block: 64 }),
    ] {
        let t = median(|| ours.uniform_sweep(0.0, dt, 0, mode, &mut out).unwrap());
        let err = out.iter().zip(&reference).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
        println!("{name} {:.3} {:.3e}", t * 1e9 / n as f64, err);
    }
}
