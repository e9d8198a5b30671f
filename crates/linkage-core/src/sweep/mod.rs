//! Layer 6, sweeping a mechanism over many crank angles: the branch [`tracker`], the sweep
//! [`engine`] and its output [`layout`], and the block kernels of the held pass
//! ([`block_poses`]: poses and rates; [`block_centres`]: centres and curvatures).
pub(crate) mod block_centres;
pub(crate) mod block_poses;
pub(crate) mod engine;
pub(crate) mod layout;
pub(crate) mod tracker;
