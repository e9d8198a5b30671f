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
    // The three pyclasses whose `__module__` is `linkage._core` (their 0.1 home) stay here too.
    m.add_class::<mechanism::Mechanism>()?;
    m.add_class::<linkages::fourbar::FourBar>()?;
    m.add_class::<linkages::slider_crank::SliderCrank>()?;
    Ok(())
}
