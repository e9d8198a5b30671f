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

mod batch;
mod bodies;
#[cfg(feature = "synthesis")]
mod burmester;
mod cam;
mod catalog_impl;
mod centres;
mod choice;
mod dyad;
mod error;
mod fourbar;
#[cfg(feature = "synthesis")]
mod freudenstein;
mod gait;
mod gear_train;
mod held;
mod held_centres;
mod inflection;
#[cfg(feature = "alloc")]
mod kinetostatics;
mod mechanism;
mod motion_law;
#[cfg(feature = "std")]
mod parallel;
mod rates;
mod scalar;
mod schedule;
mod slider;
mod straightness;
mod support;
mod sweep;
mod tracker;
mod trig;
mod turns;
mod uniform_sweep;

// Path synthesis (feature `synthesis`, needs `std` for its threads).
#[cfg(feature = "synthesis")]
mod arc_atlas;
#[cfg(feature = "synthesis")]
mod atlas;
#[cfg(feature = "synthesis")]
mod curve_equation;
#[cfg(feature = "synthesis")]
mod efd;
#[cfg(feature = "synthesis")]
mod path_synthesis;
#[cfg(feature = "synthesis")]
mod slider_arc_atlas;
#[cfg(feature = "synthesis")]
mod slider_circuit;
#[cfg(feature = "synthesis")]
mod slider_crank;
#[cfg(feature = "synthesis")]
mod slider_equation;
#[cfg(feature = "synthesis")]
pub use arc_atlas::{arc_frame, arc_points, ArcSpec, ARC_ENTRY_PARAMS, ARC_FRACTIONS};
#[cfg(feature = "synthesis")]
pub use atlas::{
    candidate, nearest, slider_candidate, Atlas, AtlasSpec, ENTRY_PARAMS, LENGTH_RANGE,
    SLIDER_ENTRY_PARAMS,
};
#[cfg(feature = "synthesis")]
pub use curve_equation::{fourbars_from_curve, CurveEquation, EquationFit, CURVE_EQUATION_POINTS};
#[cfg(feature = "synthesis")]
pub use efd::{
    descriptor_len, query_descriptors, Efd, Normalisation, MIN_CURVE_POINTS, QUERY_VARIANTS,
};
#[cfg(feature = "synthesis")]
pub use path_synthesis::{
    covering_arc, path_errors, path_residuals, place_entry, polyline_distances,
    polyline_distances_each, ArcFigures, Circuit, CircuitPath, FootSearch, PathError, BRANCH_JOINT,
    FOOT_STARTS, PLACED_PARAMS, POINT_JOINT,
};
#[cfg(feature = "synthesis")]
pub use slider_arc_atlas::{slider_arc_frame, slider_arc_points, SLIDER_ARC_ENTRY_PARAMS};
#[cfg(feature = "synthesis")]
pub use slider_circuit::{
    place_slider_entry, slider_path_errors, slider_path_residuals, SliderCircuit, SLIDER_PARAMS,
};
#[cfg(feature = "synthesis")]
pub use slider_crank::{SliderCrank, SliderCrankPose};
#[cfg(feature = "synthesis")]
pub use slider_equation::{
    slider_cranks_from_curve, SliderEquation, SliderEquationFit, SLIDER_EQUATION_POINTS,
};

/// The repository README's Rust examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The straight-line linkages of the source documents (docs/domain.md), ready to sweep.
pub mod catalog {
    pub use crate::catalog_impl::*;
}

pub use batch::{BatchWork, FourBarBatch, GO_ON_EVERY};
pub use bodies::{Bodies, BodyFrame, BodyId, Mobility, GROUND};
#[cfg(feature = "synthesis")]
pub use burmester::{
    centre_point, circle_point, common_pole, pole, BodyPose, BurmesterCurve, BurmesterPair, Defect,
    MotionCandidate, MotionCheck, MAX_POSES,
};
pub use cam::{CamPoint, FlatFollower, RollerFollower};
pub use centres::{
    circumcentre, instant_centre, line_intersection, path_curvature, relative_centre, BodyMotion,
    Centre,
};
pub use dyad::{triangle_area, Dyad, DyadFailure, DyadPose, Side};
pub use error::Error;
pub use fourbar::{Assembly, FourBar, FourBarPose, GrashofClass, InputRange};
#[cfg(feature = "synthesis")]
pub use freudenstein::{chebyshev_spacing, Freudenstein, FunctionCheck, FunctionGenerator};
pub use gait::{FourBarGait, GaitScratch, LegGait};
pub use gear_train::GearTrain;
pub use inflection::{inflection, Inflection};
#[cfg(feature = "alloc")]
pub use kinetostatics::{Dynamics, ForceSolution, ForceSweep, Inertia, Load, LoadSeries, Reaction};
#[allow(
    deprecated,
    reason = "the old name of CrankRates, kept for one release"
)]
pub use mechanism::Motion;
pub use mechanism::{Construction, CrankRates, Mechanism};
pub use motion_law::{Derivatives, Discontinuity, MotionLaw, Program, Segment};
pub use rates::rate_margin;
pub use scalar::Vec2;
pub use schedule::{ScheduleTable, StanceSchedule};
pub use slider::{LineDirection, Reach, SliderDyad, SliderPose};
pub use straightness::{straight_part, StraightPart};
pub use support::{convex_hull, stability_margin, support_margins};
#[cfg(feature = "std")]
pub use sweep::sweep_mechanisms;
pub use sweep::{
    sweep, sweep_pairs, sweep_planned, Columns, Pairs, Plan, Rate, SweepOutputs, Swept,
    SWEEP_CHUNK, SWEEP_WORK_CHUNK,
};
pub use tracker::{Rates, Sample, Tracker, DEFAULT_TOGGLE_MARGIN};
pub use trig::{sin_cos_f64, sin_cos_f64_slice};
pub use turns::reduce_angle;
pub use uniform_sweep::{AngleMode, MAX_TABLE};
