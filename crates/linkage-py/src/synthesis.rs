//! Mirrors `linkage_core`'s `synthesis/`: precision points (Burmester, Freudenstein) and path
//! synthesis (atlases, circuits, distances, curve equations).

use pyo3::prelude::*;

pub mod path;
pub mod precision;

/// Adds the submodule `_core.synthesis` (precision-point and path synthesis (`linkage_core` `synthesis/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "synthesis",
        "Precision-point and path synthesis (`linkage_core` `synthesis/`).",
    )?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::burmester_centre_point,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::burmester_circle_point,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::burmester_common_pole,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::burmester_curve,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::motion_candidates,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::chebyshev_points,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::precision::function_generator,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_atlas_build,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_atlas_build,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_arc_atlas_build,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_arc_frame,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_atlas_nearest,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_descriptors,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(crate::synthesis::path::synth_frame, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_frame,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(crate::synthesis::path::synth_place, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_place,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_residuals,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_residuals,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(crate::synthesis::path::synth_errors, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_errors,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(crate::synthesis::path::synth_info, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_info,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(crate::synthesis::path::synth_arc, &m)?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_curve_equation,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::synth_slider_curve_equation,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::polyline_distance,
        &m
    )?)?;
    m.add_function(wrap_pyfunction!(
        crate::synthesis::path::polyline_distance_each,
        &m
    )?)?;
    m.add("CURVE_EQUATION_POINTS", linkage_core::CURVE_EQUATION_POINTS)?;
    m.add(
        "SLIDER_EQUATION_POINTS",
        linkage_core::SLIDER_EQUATION_POINTS,
    )?;
    m.add("ENTRY_PARAMS", linkage_core::ENTRY_PARAMS)?;
    m.add("SLIDER_ENTRY_PARAMS", linkage_core::SLIDER_ENTRY_PARAMS)?;
    m.add("ARC_ENTRY_PARAMS", linkage_core::ARC_ENTRY_PARAMS)?;
    m.add(
        "SLIDER_ARC_ENTRY_PARAMS",
        linkage_core::SLIDER_ARC_ENTRY_PARAMS,
    )?;
    m.add("ARC_FRACTIONS", linkage_core::ARC_FRACTIONS)?;
    m.add("LENGTH_RANGE", linkage_core::LENGTH_RANGE)?;
    m.add("PLACED_PARAMS", linkage_core::PLACED_PARAMS)?;
    m.add("SLIDER_PARAMS", linkage_core::SLIDER_PARAMS)?;
    m.add("QUERY_VARIANTS", linkage_core::QUERY_VARIANTS)?;
    m.add("MIN_CURVE_POINTS", linkage_core::MIN_CURVE_POINTS)?;
    m.add("MAX_POSES", linkage_core::MAX_POSES)?;
    m.add("FOOT_STARTS", linkage_core::FOOT_STARTS)?;
    Ok(())
}
