//! Layer 7, named linkages on top of the general mechanism and its sweeps: the four-bar
//! ([`fourbar`]: Grashof class, limits, transmission angle, circuits), its uniform fast sweep
//! ([`uniform_sweep`]) and batches ([`batch`]), and the offset slider-crank ([`slider_crank`],
//! feature `synthesis`). [`crate::kinetostatics`] is a peer on this layer.
pub(crate) mod batch;
pub(crate) mod fourbar;
#[cfg(feature = "synthesis")]
pub(crate) mod slider_crank;
pub(crate) mod uniform_sweep;
