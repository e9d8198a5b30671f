//! Layer 4, the mechanism: the ordered program of constructions ([`program`]), its rate
//! analysis ([`joint_rates`]: velocities, accelerations and jerks of every joint), its rigid
//! bodies and mobility ([`bodies`]) and its slider lines over a sweep ([`slider_lines`]). Every
//! `impl Mechanism` is in this folder.
pub(crate) mod bodies;
pub(crate) mod joint_rates;
pub(crate) mod program;
pub(crate) mod slider_lines;
