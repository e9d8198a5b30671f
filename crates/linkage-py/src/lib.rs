//! Python bindings of `linkage-core`: the `linkage._core` extension module.
//!
//! Thin by design: each module converts Python arguments, calls the core with the GIL released,
//! and converts results to numpy arrays. Validation messages for Python users that need Python
//! context (argument names, dtypes) live in the pure-Python package `linkage`.

// kurbo's: every `allow` says why, every assertion says what failed.
#![warn(
    clippy::allow_attributes_without_reason,
    clippy::missing_assert_message
)]

use pyo3::prelude::*;

mod args;
mod catalog;
mod drive;
mod error;
mod kinetostatics;
mod linkages;
mod mechanism;
mod memory;
mod module;
mod motion;
mod numeric;
mod simd;
mod sweep;
mod synthesis;
mod walking;

/// The 0.1 flat names of `_core` and the submodule attribute each is (the same object), kept
/// until the Python call sites use the submodules. `flat_names.tsv` is this table.
const FLAT_NAMES: [(&str, &str); 53] = [
    ("reduce_angle", "numeric.reduce_angle"),
    ("degrees_of_freedom", "mechanism.degrees_of_freedom"),
    ("curvature_centres", "motion.curvature_centres"),
    ("circumcentres", "motion.circumcentres"),
    ("straight_run", "motion.straight_run"),
    ("sweep_mechanisms", "sweep.sweep_mechanisms"),
    ("sweep_simd", "sweep.instruction_set"),
    ("batch_sweep", "linkages.sweep_four_bar_batch"),
    ("motion_law_names", "drive.motion_law_names"),
    ("motion_law_eval", "drive.evaluate_motion_law"),
    ("program_eval", "drive.evaluate_program"),
    ("program_discontinuities", "drive.program_discontinuities"),
    ("gear_train_simple", "drive.simple_gear_train"),
    ("gear_train_compound", "drive.compound_gear_train"),
    ("schedule_eval", "drive.evaluate_schedule"),
    ("stance_schedule", "drive.stance_schedule"),
    ("cam_geometry", "drive.cam_geometry"),
    ("forces", "kinetostatics.forces"),
    ("catalog_four_bar", "catalog.four_bar"),
    ("catalog_linkage", "catalog.linkage"),
    ("catalog_names", "catalog.names"),
    ("leg_gait", "walking.leg_gait"),
    ("four_bar_gaits", "walking.four_bar_gaits"),
    ("gait_columns", "walking.gait_columns"),
    ("support_margins", "walking.support_margins"),
    ("burmester_centre_point", "synthesis.burmester_centre_point"),
    ("burmester_circle_point", "synthesis.burmester_circle_point"),
    ("burmester_common_pole", "synthesis.burmester_common_pole"),
    ("burmester_curve", "synthesis.burmester_curve"),
    ("motion_candidates", "synthesis.motion_candidates"),
    ("chebyshev_points", "synthesis.chebyshev_points"),
    ("function_generator", "synthesis.function_generator"),
    ("synth_atlas_build", "synthesis.build_atlas"),
    ("synth_slider_atlas_build", "synthesis.build_slider_atlas"),
    ("synth_arc_atlas_build", "synthesis.build_arc_atlas"),
    ("synth_arc_frame", "synthesis.arc_entry_frame"),
    ("synth_atlas_nearest", "synthesis.nearest_entries"),
    ("synth_descriptors", "synthesis.query_descriptors"),
    ("synth_frame", "synthesis.circuit_frame"),
    ("synth_slider_frame", "synthesis.slider_circuit_frame"),
    ("synth_place", "synthesis.place_entry"),
    ("synth_slider_place", "synthesis.place_slider_entry"),
    ("synth_residuals", "synthesis.residuals"),
    ("synth_slider_residuals", "synthesis.slider_residuals"),
    ("synth_errors", "synthesis.path_errors"),
    ("synth_slider_errors", "synthesis.slider_path_errors"),
    ("synth_info", "synthesis.circuit_info"),
    ("synth_slider_info", "synthesis.slider_circuit_info"),
    ("synth_arc", "synthesis.covering_arc"),
    ("synth_curve_equation", "synthesis.fourbars_from_curve"),
    (
        "synth_slider_curve_equation",
        "synthesis.slider_cranks_from_curve",
    ),
    ("polyline_distance", "synthesis.polyline_distance"),
    ("polyline_distance_each", "synthesis.polyline_distance_each"),
];

/// The core constants the submodules export, also at `_core` top level.
const FLAT_CONSTANTS: [(&str, &str); 18] = [
    ("FOUR_BARS", "catalog.FOUR_BARS"),
    ("MULTI_LOOP", "catalog.MULTI_LOOP"),
    ("DEFAULT_TOGGLE_MARGIN", "sweep.DEFAULT_TOGGLE_MARGIN"),
    ("MAX_TABLE", "linkages.MAX_TABLE"),
    ("CURVE_EQUATION_POINTS", "synthesis.CURVE_EQUATION_POINTS"),
    ("SLIDER_EQUATION_POINTS", "synthesis.SLIDER_EQUATION_POINTS"),
    ("ENTRY_PARAMS", "synthesis.ENTRY_PARAMS"),
    ("SLIDER_ENTRY_PARAMS", "synthesis.SLIDER_ENTRY_PARAMS"),
    ("ARC_ENTRY_PARAMS", "synthesis.ARC_ENTRY_PARAMS"),
    (
        "SLIDER_ARC_ENTRY_PARAMS",
        "synthesis.SLIDER_ARC_ENTRY_PARAMS",
    ),
    ("ARC_FRACTIONS", "synthesis.ARC_FRACTIONS"),
    ("LENGTH_RANGE", "synthesis.LENGTH_RANGE"),
    ("PLACED_PARAMS", "synthesis.PLACED_PARAMS"),
    ("SLIDER_PARAMS", "synthesis.SLIDER_PARAMS"),
    ("QUERY_VARIANTS", "synthesis.QUERY_VARIANTS"),
    ("MIN_CURVE_POINTS", "synthesis.MIN_CURVE_POINTS"),
    ("MAX_POSES", "synthesis.MAX_POSES"),
    ("FOOT_STARTS", "synthesis.FOOT_STARTS"),
];

/// `parent.<flat>` bound to the submodule attribute `module.name` (`"module.name"`).
fn add_flat(parent: &Bound<'_, PyModule>, flat: &str, dotted: &str) -> PyResult<()> {
    let (module, name) = dotted
        .split_once('.')
        .ok_or_else(|| error::linkage_error(format!("internal error: {dotted} has no module")))?;
    parent.add(flat, parent.getattr(module)?.getattr(name)?)
}

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("LinkageError", py.get_type::<error::LinkageError>())?;
    m.add("AssemblyError", py.get_type::<error::AssemblyError>())?;
    error::register(m)?;
    m.add("CAPACITY", module::CAPACITY)?;
    // Below this assembly margin rates are NaN (`linkage_core::rate_margin`): one value, the
    // core's, for the Python checks too.
    m.add("RATE_MARGIN", linkage_core::rate_margin::<f64>())?;
    // The names of the core's string choices, so that Python checks them against one list.
    let choices = pyo3::types::PyDict::new(py);
    choices.set_item("assembly", linkage_core::Assembly::NAMES.to_vec())?;
    choices.set_item("side", linkage_core::Side::NAMES.to_vec())?;
    choices.set_item("reach", linkage_core::Reach::NAMES.to_vec())?;
    choices.set_item("mode", linkage_core::AngleMode::NAMES.to_vec())?;
    m.add("CHOICES", choices)?;
    // The dyad side each assembly puts the coupler–rocker joint on (the core's Assembly::side).
    let sides = pyo3::types::PyDict::new(py);
    for a in [
        linkage_core::Assembly::Open,
        linkage_core::Assembly::Crossed,
    ] {
        sides.set_item(a.name(), a.side().name())?;
    }
    m.add("ASSEMBLY_SIDES", sides)?;
    // One wording of sizes and memory errors, the Python checks' too.
    m.add_function(wrap_pyfunction!(memory::size_text_of, m)?)?;
    m.add_function(wrap_pyfunction!(memory::memory_message, m)?)?;
    // Lowest layer first, as the core's folders.
    numeric::register(m)?;
    drive::register(m)?;
    mechanism::register(m)?;
    motion::register(m)?;
    sweep::register(m)?;
    linkages::register(m)?;
    kinetostatics::register(m)?;
    catalog::register(m)?;
    walking::register(m)?;
    synthesis::register(m)?;
    m.add_class::<mechanism::Mechanism>()?;
    m.add_class::<linkages::fourbar::FourBar>()?;
    m.add_class::<linkages::slider_crank::SliderCrank>()?;
    for (flat, dotted) in FLAT_NAMES.iter().chain(FLAT_CONSTANTS.iter()) {
        add_flat(m, flat, dotted)?;
    }
    Ok(())
}
