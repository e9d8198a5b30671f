//! Mirrors `linkage_core`'s `walking/`: gaits of legs and of four-bar legs, support margins.

pub mod gait;
pub mod support;
