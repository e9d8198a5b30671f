//! Layer 3 (a peer of [`crate::constructions`]): what drives a crank or a follower — rise laws
//! and motion programs, gear trains, crank-speed schedules, disc cams. Built on the numeric
//! floor and the error type only.
pub(crate) mod cam;
pub(crate) mod gear_train;
pub(crate) mod motion_law;
pub(crate) mod schedule;
