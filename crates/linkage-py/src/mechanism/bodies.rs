//! Mirrors `linkage_core::bodies`: the Kutzbach–Gruebler count.

use linkage_core::Mobility;
use pyo3::prelude::*;

use crate::args::count;
use crate::error::linkage_error;

/// `F = 3(n − 1) − 2·j1 − j2` for `links` (ground included), lower and higher pairs.
#[pyfunction]
pub fn degrees_of_freedom(
    links: &Bound<'_, PyAny>,
    lower_pairs: &Bound<'_, PyAny>,
    higher_pairs: &Bound<'_, PyAny>,
) -> PyResult<i64> {
    let m = Mobility {
        links: count("links", links)?,
        lower_pairs: count("lower_pairs", lower_pairs)?,
        higher_pairs: count("higher_pairs", higher_pairs)?,
    };
    m.checked_degrees_of_freedom().ok_or_else(|| {
        linkage_error(format!(
            "mobility out of range: 3({} − 1) − 2·{} − {} does not fit in 64 bits",
            m.links, m.lower_pairs, m.higher_pairs
        ))
    })
}
