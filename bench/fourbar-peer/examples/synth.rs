//! Path synthesis by the `four-bar` crate (AGPL-3.0; used here only to measure it), for
//! `bench/synthesis.py`:
//! - `synth atlas N`: build its atlas of N entries (its defaults: 720 points, 20 harmonics);
//!   prints `atlas N seconds`.
//! - `synth path FILE.csv closed|open GENS POP`: its differential-evolution synthesis of the
//!   curve in FILE (x,y lines); prints `time seconds` then the best linkage's coupler curve as
//!   `p x y` lines (3600 points), so the caller measures its error with its own metric.
use four_bar::{atlas, mh, syn, FourBar};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("atlas") => {
            let n: usize = args[2].parse().expect("N");
            let t = Instant::now();
            let a = atlas::FbAtlas::make(atlas::Cfg::new().size(n).seed(0u64.into()));
            println!("atlas {} {:.6}", a.len(), t.elapsed().as_secs_f64());
        }
        Some("path") => {
            let text = std::fs::read_to_string(&args[2]).expect("curve file");
            let pts: Vec<[f64; 2]> = text
                .lines()
                .filter_map(|l| {
                    let mut it = l.split(',').map(|c| c.trim().parse::<f64>());
                    match (it.next(), it.next()) {
                        (Some(Ok(x)), Some(Ok(y))) => Some([x, y]),
                        _ => None,
                    }
                })
                .collect();
            let mode = if args[3] == "open" { syn::Mode::Open } else { syn::Mode::Closed };
            let gens: u64 = args[4].parse().expect("GENS");
            let pop: usize = args[5].parse().expect("POP");
            let t = Instant::now();
            let func = syn::FbSyn::from_curve(&pts[..], mode);
            let s = mh::Solver::build(mh::De::default(), func)
                .task(|ctx| ctx.gen == gens)
                .pop_num(pop)
                .seed(0u64)
                .solve();
            let fb: FourBar = s.into_result();
            println!("time {:.6}", t.elapsed().as_secs_f64());
            for p in fb.curve(3600) {
                println!("p {} {}", p[0], p[1]);
            }
        }
        _ => eprintln!("usage: synth atlas N | synth path FILE.csv closed|open GENS POP"),
    }
}
