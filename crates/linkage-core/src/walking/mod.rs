//! Layer 8 (a peer of [`crate::catalog`]): walking legs — gait figures of a foot path over a
//! crank turn ([`gait`]) and static stability of the stance pads ([`support`]).
pub(crate) mod gait;
pub(crate) mod support;
