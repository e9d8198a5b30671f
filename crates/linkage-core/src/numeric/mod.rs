//! Layer 0, the numeric floor: scalar helpers and the vector type, trigonometry of crank angles,
//! exact reduction of angles to two turns, rescaling by powers of two ([`pow2`]) and the
//! fixed-order work split among threads. It imports nothing else of the crate.
#[cfg(feature = "std")]
pub(crate) mod parallel;
pub(crate) mod pow2;
pub(crate) mod scalar;
pub(crate) mod trig;
pub(crate) mod turns;
