//! Dimensional synthesis (feature `synthesis`), the top layer: precision points (Burmester
//! motion generation, Freudenstein function generation), path synthesis (elliptic Fourier
//! descriptors, the atlases of four-bars and slider-cranks and their arcs, the circuits of a
//! four-bar or slider-crank and the distances to them) and the linkages of a coupler curve's
//! equation. Every name is also at the crate root (`linkage_core::Atlas`), as in 0.1.
pub(crate) mod arc_atlas;
pub(crate) mod atlas;
pub(crate) mod burmester;
pub(crate) mod circuit;
pub(crate) mod curve_equation;
pub(crate) mod efd;
pub(crate) mod freudenstein;
pub(crate) mod slider_arc_atlas;
pub(crate) mod slider_circuit;
pub(crate) mod slider_equation;

pub use arc_atlas::{arc_frame, arc_points, ArcSpec, ARC_ENTRY_PARAMS, ARC_FRACTIONS};
pub use atlas::{
    candidate, nearest, slider_candidate, Atlas, AtlasSpec, ENTRY_PARAMS, LENGTH_RANGE,
    SLIDER_ENTRY_PARAMS,
};
pub use burmester::{
    centre_point, circle_point, common_pole, pole, BodyPose, BurmesterCurve, BurmesterPair, Defect,
    MotionCandidate, MotionCheck, MAX_POSES,
};
pub use circuit::{
    covering_arc, path_errors, path_residuals, place_entry, polyline_distances,
    polyline_distances_each, ArcFigures, Circuit, CircuitPath, FootSearch, PathError, BRANCH_JOINT,
    FOOT_STARTS, PLACED_PARAMS, POINT_JOINT,
};
pub use curve_equation::{fourbars_from_curve, CurveEquation, EquationFit, CURVE_EQUATION_POINTS};
pub use efd::{
    descriptor_len, query_descriptors, Efd, Normalisation, MIN_CURVE_POINTS, QUERY_VARIANTS,
};
pub use freudenstein::{chebyshev_spacing, Freudenstein, FunctionCheck, FunctionGenerator};
pub use slider_arc_atlas::{slider_arc_frame, slider_arc_points, SLIDER_ARC_ENTRY_PARAMS};
pub use slider_circuit::{
    place_slider_entry, slider_path_errors, slider_path_residuals, SliderCircuit, SLIDER_PARAMS,
};
pub use slider_equation::{
    slider_cranks_from_curve, SliderEquation, SliderEquationFit, SLIDER_EQUATION_POINTS,
};
