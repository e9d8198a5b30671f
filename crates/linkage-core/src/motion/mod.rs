//! Layer 5, the motion of a mechanism's bodies at one pose: instant centres and path
//! curvature ([`centres`]), the inflection circle ([`inflection`]) and the straight parts of a
//! traced path ([`straightness`]).
pub(crate) mod centres;
pub(crate) mod inflection;
pub(crate) mod straightness;
