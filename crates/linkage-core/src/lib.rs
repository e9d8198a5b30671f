//! Closed-form kinematics of planar linkages.
//!
//! A linkage is an ordered program of [`Construction`]s — fixed joints, a crank, RRR dyads,
//! RRP slider dyads and points carried by links — held in a [`Mechanism`]. Each construction
//! places one joint from joints placed before it, in closed form, so solving a pose is a single
//! pass with no iteration. A [`Tracker`] sweeps a mechanism over crank angles and keeps every
//! dyad on its assembly branch by geometry (the orientation of the dyad), never by angle ranges.
//! [`FourBar`] adds the classical four-bar vocabulary: Grashof class, input limits at the
//! toggle positions, transmission angle and circuit sweeps. [`catalog`] holds the straight-line
//! linkages of the project's source documents.
//!
//! The crate is `no_std`: solving and sweeping need no heap (fixed capacity `N` joints per
//! mechanism, caller-provided output slices). All numerics are generic over
//! [`nalgebra::RealField`] so that `f32` firmware and `f64` analysis share one code path.
//!
//! # Conventions
//! - Units are whatever the caller uses for lengths (mm or m, consistently); angles are radians.
//! - Angles are measured from the +x axis, counter-clockwise positive. Angular velocities and
//!   accelerations are counter-clockwise positive too.
//! - "Left of A→B" is the side a counter-clockwise quarter turn of A→B points to.
//! - Points and vectors are [`Vec2`] (`nalgebra::Vector2`).
//!
//! # Features
//! - `std` (default): use the platform's math library.
//! - `libm`: use `libm` for targets without `std` (e.g. `thumbv7em-none-eabihf`).
//! - `alloc` (implied by `std`): kinetostatics, which needs a dense linear solve sized by the
//!   linkage. Firmware builds without it carry none of it.
//! - `synthesis` (default, implies `std`): dimensional synthesis — Burmester motion
//!   generation ([`BurmesterCurve`], [`centre_point`], [`MotionCandidate`]), Freudenstein
//!   function generation ([`FunctionGenerator`]) and path synthesis ([`Efd`] elliptic Fourier
//!   descriptors, the [`Atlas`] of four-bars or slider-cranks, the [`Circuit`]s of four-bars
//!   ([`CircuitPath`]) and of offset slider-cranks ([`SliderCrank`], [`SliderCircuit`])).
//!
//! # Example
//! ```
//! use linkage_core::{FourBar, Assembly, GrashofClass};
//! // Hoecken straight-line linkage, mm (docs/domain.md): ground 20, crank 10, coupler 25, rocker 25,
//! // foot on the coupler line 50 from A.
//! let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
//! assert_eq!(fb.grashof(), GrashofClass::CrankRocker);
//! let pose = fb.pose(0.0).unwrap();
//! assert!(((pose.coupler_point - pose.a).norm() - 50.0).abs() < 1e-12);
//! ```
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
// kurbo's: every `allow` says why, every assertion in library code says what failed.
#![warn(
    clippy::allow_attributes_without_reason,
    clippy::missing_assert_message
)]
// glam's: every public function that can panic or fail says when.
#![warn(clippy::missing_panics_doc, clippy::missing_errors_doc)]

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!("linkage-core needs a math backend: enable the `std` feature or the `libm` feature");

#[cfg(feature = "alloc")]
extern crate alloc;

// The layers, lowest first (ARCHITECTURE.md; `.ci/layers.py` checks that a module imports only
// from lower ones): numeric -> error -> choice -> constructions, drive -> mechanism -> motion
// -> sweep -> linkages, kinetostatics -> catalog, walking -> synthesis.
mod choice;
mod constructions;
mod drive;
mod error;
#[cfg(feature = "alloc")]
mod kinetostatics;
mod linkages;
mod mechanism;
mod motion;
mod numeric;
mod sweep;
mod walking;

/// The repository README's Rust examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

pub mod catalog;
#[cfg(feature = "synthesis")]
pub mod synthesis;

// Steps of the atlas search and the placement of its entries (`candidate`, `nearest`,
// `place_entry`, `query_descriptors`, ...) and the `go_on` cadence (`GO_ON_EVERY`,
// `SWEEP_WORK_CHUNK`) are re-exported flat as in 0.1 for the binding, but are
// `#[doc(hidden)]` where they are defined: internals, not API.

#[cfg(feature = "synthesis")]
pub use linkages::slider_crank::{SliderCrank, SliderCrankPose};
#[cfg(feature = "synthesis")]
pub use synthesis::{
    arc_frame, arc_points, candidate, centre_point, chebyshev_spacing, circle_point, common_pole,
    covering_arc, descriptor_len, fourbars_from_curve, nearest, path_errors, path_residuals,
    place_entry, place_slider_entry, pole, polyline_distances, polyline_distances_each,
    query_descriptors, slider_arc_frame, slider_arc_points, slider_candidate,
    slider_cranks_from_curve, slider_path_errors, slider_path_residuals, ArcFigures, ArcSpec,
    Atlas, AtlasSpec, BodyPose, BurmesterCurve, BurmesterPair, Circuit, CircuitPath, CurveEquation,
    Defect, Efd, EquationFit, FootSearch, Freudenstein, FunctionCheck, FunctionGenerator,
    MotionCandidate, MotionCheck, Normalisation, PathError, SliderCircuit, SliderEquation,
    SliderEquationFit, ARC_ENTRY_PARAMS, ARC_FRACTIONS, BRANCH_JOINT, CURVE_EQUATION_POINTS,
    ENTRY_PARAMS, FOOT_STARTS, LENGTH_RANGE, MAX_POSES, MIN_CURVE_POINTS, PLACED_PARAMS,
    POINT_JOINT, QUERY_VARIANTS, SLIDER_ARC_ENTRY_PARAMS, SLIDER_ENTRY_PARAMS,
    SLIDER_EQUATION_POINTS, SLIDER_PARAMS,
};

pub use constructions::dyad::{triangle_area, Dyad, DyadFailure, DyadPose, Side};
pub use constructions::slider::{LineDirection, Reach, SliderDyad, SliderPose};
pub use drive::cam::{CamPoint, FlatFollower, RollerFollower};
pub use drive::gear_train::GearTrain;
pub use drive::motion_law::{Derivatives, Discontinuity, MotionLaw, Program, Segment};
pub use drive::schedule::{ScheduleTable, StanceSchedule};
pub use error::Error;
#[cfg(feature = "alloc")]
pub use kinetostatics::{Dynamics, ForceSolution, ForceSweep, Inertia, Load, LoadSeries, Reaction};
pub use linkages::batch::{BatchWork, FourBarBatch, GO_ON_EVERY};
pub use linkages::fourbar::{
    min_transmission_angle, Assembly, FourBar, FourBarPose, GrashofClass, InputRange,
};
pub use linkages::uniform_sweep::{AngleMode, MAX_TABLE};
pub use mechanism::bodies::{Bodies, BodyFrame, BodyId, Mobility, GROUND};
pub use mechanism::joint_rates::rate_margin;
pub use mechanism::program::{Construction, CrankRates, Mechanism};
pub use motion::centres::{
    circumcentre, instant_centre, line_intersection, path_curvature, relative_centre, BodyMotion,
    Centre,
};
pub use motion::inflection::{inflection, Inflection};
pub use motion::straightness::{straight_part, StraightPart};
pub use numeric::scalar::Vec2;
pub use numeric::trig::{sin_cos_f64, sin_cos_f64_slice};
pub use numeric::turns::reduce_angle;
#[cfg(feature = "std")]
pub use sweep::engine::sweep_mechanisms;
pub use sweep::engine::{
    sweep, sweep_pairs, sweep_planned, Plan, Rate, SweepOutputs, Swept, SWEEP_CHUNK,
    SWEEP_WORK_CHUNK,
};
pub use sweep::layout::{Columns, Pairs};
pub use sweep::tracker::{Rates, Sample, Tracker, DEFAULT_TOGGLE_MARGIN};
pub use walking::gait::{FourBarGait, GaitScratch, LegGait};
pub use walking::support::{convex_hull, stability_margin, support_margins};
