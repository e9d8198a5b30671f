//! Minimal firmware: solve the Hoecken leg at every crank angle of a turn with the tracked
//! sweep and the fast table sweep, into static buffers, forever. Measures what the core costs
//! in flash and RAM.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use linkage_core::{catalog, AngleMode, Rates, Tracker, Vec2};
use panic_halt as _;

#[cfg(feature = "double")]
type F = f64;
#[cfg(not(feature = "double"))]
type F = f32;

const SAMPLES: usize = 360;

#[entry]
fn main() -> ! {
    let fb = catalog::hoecken::<F>();
    let m = fb.mechanism();
    let mut fast = [Vec2::<F>::zeros(); SAMPLES];
    let mut joints = [Vec2::<F>::zeros(); 5];
    let mut sink: F = 0.0;
    loop {
        let dt = core::f64::consts::TAU as F / SAMPLES as F;
        if fb.uniform_sweep(0.0, dt, 0, AngleMode::Table { block: 32 }, &mut fast).is_ok() {
            sink += fast[SAMPLES / 2].x;
        }
        if let Ok(mut t) = Tracker::new(&m) {
            for k in 0..SAMPLES {
                if t.step(dt * k as F, None, &mut joints, Rates::none()).is_ok() {
                    sink += joints[4].y;
                }
            }
        }
        // Keep the results observable so nothing is optimised away.
        sink = core::hint::black_box(sink);
    }
}
