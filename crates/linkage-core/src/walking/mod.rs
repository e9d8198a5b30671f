//! Layer 8 (a peer of [`crate::catalog`]): walking legs — gait figures of a foot path over a
//! crank turn ([`gait`]) and static stability of the stance pads ([`support`]).
//!
//! `FourBar::gait` and `FourBarBatch::gaits` are defined here, not in [`crate::linkages`] with
//! the other methods of their types: they return and fill the gait types of this layer, which
//! the four-bar's layer may not import.
pub(crate) mod gait;
pub(crate) mod support;
