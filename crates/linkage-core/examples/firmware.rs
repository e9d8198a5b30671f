//! Firmware-style use of the core: a Hoecken leg solved and swept in `f32` and `f64` with no
//! `std` and no heap (fixed-capacity mechanism, stack buffers). Built as a static library for
//! `thumbv7em-none-eabihf` in CI, which proves both precisions compile for the target.
#![cfg_attr(not(feature = "std"), no_std)]

use linkage_core::{catalog, FourBar, Rates, ScheduleTable, Tracker, Vec2};
use nalgebra::RealField;

/// Foot height of the Hoecken leg at crank angle `theta` (mm), `NaN` if it cannot assemble.
pub fn foot_height_f32(theta: f32) -> f32 {
    catalog::hoecken::<f32>()
        .pose(theta)
        .map(|p| p.coupler_point.y)
        .unwrap_or(f32::NAN)
}

/// Largest foot x over a tracked sweep of `n` angles in one turn (mm).
fn sweep_extent<T: RealField + Copy>(n: u32) -> T {
    let m = catalog::hoecken::<T>().mechanism();
    let Ok(mut tracker) = Tracker::new(&m) else {
        return T::zero();
    };
    let mut joints = [Vec2::zeros(); 5];
    let mut best = T::zero();
    for k in 0..n {
        let theta = T::two_pi() * T::from_subset(&(k as f64)) / T::from_subset(&(n as f64));
        if tracker
            .step(theta, None, &mut joints, Rates::none())
            .is_ok()
        {
            best = best.max(joints[FourBar::<T>::P].x);
        }
    }
    best
}

/// [`sweep_extent`] in `f32`.
pub fn sweep_extent_f32(n: u32) -> f32 {
    sweep_extent::<f32>(n)
}

/// [`sweep_extent`] in `f64`.
pub fn sweep_extent_f64(n: u32) -> f64 {
    sweep_extent::<f64>(n)
}

/// A crank-speed schedule as firmware keeps it: two `f32` arrays in flash (here a constant
/// 2π rad/s over a 1 s period in 8 entries; `linkage.drive.crank_schedule` writes real ones).
static SCHEDULE_THETA: [f32; 8] = [
    0.0, 0.785_398, 1.570_796, 2.356_194, 3.141_593, 3.926_991, 4.712_389, 5.497_787,
];
static SCHEDULE_OMEGA: [f32; 8] = [6.283_185; 8];

/// Crank angle set-point and feed-forward speed at time `t` (s) from the schedule table.
pub fn crank_setpoint(t: f32) -> (f32, f32) {
    match ScheduleTable::new(
        0.125,
        core::f32::consts::TAU,
        &SCHEDULE_THETA,
        &SCHEDULE_OMEGA,
    ) {
        Ok(table) => {
            let (theta, omega, _) = table.at(t);
            (theta, omega)
        }
        Err(_) => (f32::NAN, f32::NAN),
    }
}

#[cfg(not(feature = "std"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
