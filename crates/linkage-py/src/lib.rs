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
mod motion;
mod numeric;
mod synthesis;
mod walking;

/// Maximum joints of a mechanism built from Python.
pub const CAPACITY: usize = 64;

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("LinkageError", py.get_type::<error::LinkageError>())?;
    m.add("AssemblyError", py.get_type::<error::AssemblyError>())?;
    m.add("CAPACITY", CAPACITY)?;
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
    m.add_class::<mechanism::Mechanism>()?;
    m.add_class::<linkages::fourbar::FourBar>()?;
    m.add_class::<linkages::slider_crank::SliderCrank>()?;
    m.add_function(wrap_pyfunction!(catalog::catalog_four_bar, m)?)?;
    m.add_function(wrap_pyfunction!(catalog::catalog_linkage, m)?)?;
    m.add_function(wrap_pyfunction!(catalog::catalog_names, m)?)?;
    m.add_function(wrap_pyfunction!(motion::curvature_centres, m)?)?;
    m.add_function(wrap_pyfunction!(motion::circumcentres, m)?)?;
    m.add_function(wrap_pyfunction!(motion::straight_run, m)?)?;
    m.add_function(wrap_pyfunction!(drive::motion_law_names, m)?)?;
    m.add_function(wrap_pyfunction!(drive::motion_law_eval, m)?)?;
    m.add_function(wrap_pyfunction!(drive::program_eval, m)?)?;
    m.add_function(wrap_pyfunction!(drive::program_discontinuities, m)?)?;
    m.add_function(wrap_pyfunction!(drive::gear_train_simple, m)?)?;
    m.add_function(wrap_pyfunction!(drive::gear_train_compound, m)?)?;
    m.add_function(wrap_pyfunction!(drive::schedule_eval, m)?)?;
    m.add_function(wrap_pyfunction!(drive::stance_schedule, m)?)?;
    m.add_function(wrap_pyfunction!(drive::cam::cam_geometry, m)?)?;
    m.add_function(wrap_pyfunction!(kinetostatics::forces, m)?)?;
    m.add_function(wrap_pyfunction!(mechanism::bodies::degrees_of_freedom, m)?)?;
    m.add_function(wrap_pyfunction!(walking::support::support_margins, m)?)?;
    m.add_function(wrap_pyfunction!(linkages::fourbar::sweep_simd, m)?)?;
    m.add_function(wrap_pyfunction!(linkages::batch::batch_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::burmester_centre_point, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::burmester_circle_point, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::burmester_common_pole, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::burmester_curve, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::motion_candidates, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::chebyshev_points, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::precision::function_generator, m)?)?;
    m.add_function(wrap_pyfunction!(walking::gait::leg_gait, m)?)?;
    m.add_function(wrap_pyfunction!(walking::gait::four_bar_gaits, m)?)?;
    m.add_function(wrap_pyfunction!(walking::gait::gait_columns, m)?)?;
    m.add_function(wrap_pyfunction!(mechanism::sweep_mechanisms, m)?)?;
    m.add_function(wrap_pyfunction!(numeric::reduce_angle, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_atlas_build, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_arc_atlas_build, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_arc_frame, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_atlas_nearest, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_descriptors, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_frame, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_place, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_curve_equation, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_curve_equation, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_arc, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::polyline_distance, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::polyline_distance_each, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_residuals, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_errors, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_info, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_atlas_build, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_frame, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_place, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_residuals, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_errors, m)?)?;
    m.add_function(wrap_pyfunction!(synthesis::path::synth_slider_info, m)?)?;
    Ok(())
}
