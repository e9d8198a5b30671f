//! Layer 4, the mechanism: the ordered program of constructions ([`program`]), its rate
//! analysis ([`rates`]) and its rigid bodies and mobility ([`bodies`]).
pub(crate) mod bodies;
pub(crate) mod program;
pub(crate) mod rates;
pub(crate) mod slider_lines;
