//! Layer 6, sweeping a mechanism over many crank angles: the branch [`tracker`], the sweep
//! [`engine`] and its outputs, and the block kernels of the held pass ([`held`] poses and rates,
//! [`held_centres`] centres and curvatures).
pub(crate) mod engine;
pub(crate) mod held;
pub(crate) mod held_centres;
pub(crate) mod layout;
pub(crate) mod tracker;
