//! Mirrors `linkage_core`'s `linkages/`: the four-bar (uniform sweep, batch) and the slider-crank.

pub mod batch;
pub mod fourbar;
pub mod slider_crank;
