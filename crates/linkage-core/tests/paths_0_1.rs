//! Every public path `linkage_core::X` of 0.1 (lib.rs at a3e9360) still resolves, feature-gated
//! as it was: a path lost in a move fails to compile here. (`Motion`, deprecated in 0.1 for
//! `CrankRates`, is gone, as is `Mechanism::motion`.)
#![allow(unused_imports, reason = "the test is that these paths resolve")]

use linkage_core::catalog;
use linkage_core::catalog::{
    chebyshev, evans_a, evans_b, evans_c, four_bar_by_name, hart, hoecken, hoecken_pantograph,
    jansen, linkage_by_name, peaucellier, roberts, watt, Linkage, CAPACITY, FOUR_BARS, MULTI_LOOP,
};
#[cfg(feature = "std")]
use linkage_core::sweep_mechanisms;
#[cfg(feature = "synthesis")]
use linkage_core::{
    arc_frame, arc_points, candidate, centre_point, chebyshev_spacing, circle_point, common_pole,
    covering_arc, descriptor_len, fourbars_from_curve, nearest, path_errors, path_residuals,
    place_entry, place_slider_entry, pole, polyline_distances, polyline_distances_each,
    query_descriptors, slider_arc_frame, slider_arc_points, slider_candidate,
    slider_cranks_from_curve, slider_path_errors, slider_path_residuals, ArcFigures, ArcSpec,
    Atlas, AtlasSpec, BodyPose, BurmesterCurve, BurmesterPair, Circuit, CircuitPath, CurveEquation,
    Defect, Efd, EquationFit, FootSearch, Freudenstein, FunctionCheck, FunctionGenerator,
    MotionCandidate, MotionCheck, Normalisation, PathError, SliderCircuit, SliderCrank,
    SliderCrankPose, SliderEquation, SliderEquationFit, ARC_ENTRY_PARAMS, ARC_FRACTIONS,
    BRANCH_JOINT, CURVE_EQUATION_POINTS, ENTRY_PARAMS, FOOT_STARTS, LENGTH_RANGE, MAX_POSES,
    MIN_CURVE_POINTS, PLACED_PARAMS, POINT_JOINT, QUERY_VARIANTS, SLIDER_ARC_ENTRY_PARAMS,
    SLIDER_ENTRY_PARAMS, SLIDER_EQUATION_POINTS, SLIDER_PARAMS,
};
use linkage_core::{
    circumcentre, convex_hull, inflection, instant_centre, line_intersection, path_curvature,
    rate_margin, reduce_angle, relative_centre, sin_cos_f64, sin_cos_f64_slice, stability_margin,
    straight_part, support_margins, sweep, sweep_pairs, sweep_planned, triangle_area, AngleMode,
    Assembly, BatchWork, Bodies, BodyFrame, BodyId, BodyMotion, CamPoint, Centre, Columns,
    Construction, CrankRates, Derivatives, Discontinuity, Dyad, DyadFailure, DyadPose, Error,
    FlatFollower, FourBar, FourBarBatch, FourBarGait, FourBarPose, GaitScratch, GearTrain,
    GrashofClass, Inflection, InputRange, LegGait, LineDirection, Mechanism, Mobility, MotionLaw,
    Pairs, Plan, Program, Rate, Rates, Reach, RollerFollower, Sample, ScheduleTable, Segment, Side,
    SliderDyad, SliderPose, StanceSchedule, StraightPart, SweepOutputs, Swept, Tracker, Vec2,
    DEFAULT_TOGGLE_MARGIN, GO_ON_EVERY, GROUND, MAX_TABLE, SWEEP_CHUNK, SWEEP_WORK_CHUNK,
};
#[cfg(feature = "alloc")]
use linkage_core::{Dynamics, ForceSolution, ForceSweep, Inertia, Load, LoadSeries, Reaction};

#[test]
fn the_0_1_paths_resolve() {
    // Compiling this file is the test; one use so that it also runs.
    let _ = catalog::hoecken::<f64>();
    assert_eq!(
        linkage_core::GROUND,
        GROUND,
        "the flat path and the used one are one item"
    );
}
