//! Layer 3, the closed-form constructions a mechanism program is made of: the RRR dyad and the
//! RRP slider dyad. They place one joint from known ones and know nothing of the program that
//! orders them (that is [`crate::mechanism`], one layer up).
pub(crate) mod dyad;
pub(crate) mod slider;
