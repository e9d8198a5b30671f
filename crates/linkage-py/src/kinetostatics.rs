//! Mirrors `linkage_core::kinetostatics`: driver torque and joint reactions along a sweep.

use linkage_core::{Bodies, BodyId, Dynamics, ForceSweep, Inertia, LoadSeries, Vec2};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;

use crate::args::{count, xy, Real, RealPair, Strict};
use crate::error::{linkage_error, to_py};
use crate::mechanism::Mechanism;
use crate::memory;

fn slice<'a>(name: &str, a: &'a crate::args::F64Array1<'_>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))
}

/// Driving torque and joint reactions of a mechanism over a sweep
/// (`linkage_core::Dynamics::sweep`), one row a sample; NaN where a sample does not assemble or
/// sits at a toggle where statics cannot decide the reactions.
#[pyclass(module = "linkage._core.kinetostatics", frozen, get_all)]
pub struct JointForces {
    /// Driving torque `(N,)` by Newton–Euler.
    pub torque: Py<PyArray1<f64>>,
    /// Driving torque `(N,)` by the power method (a check of `torque`).
    pub power_torque: Py<PyArray1<f64>>,
    /// Whether each sample was solved `(N,)`.
    pub valid: Py<PyArray1<bool>>,
    /// Reaction forces `(N, R, 2)`, in the order of `reaction_links`.
    pub reactions: Py<PyArrayDyn<f64>>,
    /// Slider couples `(N, R)`; zero at pins.
    pub couples: Py<PyArrayDyn<f64>>,
    /// `(joint, from body, to body)` of each reaction, bodies by index (ground 0).
    pub reaction_links: Vec<(usize, usize, usize)>,
}

#[pymethods]
impl JointForces {
    /// `result[key]`, the 0.1 dict's keys, kept while the flat name is.
    fn __getitem__<'py>(slf: &Bound<'py, Self>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match key {
            "torque" | "power_torque" | "valid" | "reactions" | "couples" | "reaction_links" => {
                slf.getattr(key)
            }
            _ => Err(pyo3::exceptions::PyKeyError::new_err(key.to_string())),
        }
    }
}

/// Kinetostatics along a sweep.
///
/// `inertia`: `(mass, along, left, inertia)` per body, ground first; `loads`: `(body index,
/// joint, force (N, 2), torque (N,))`. Returns torque (Newton–Euler) and power-method torque
/// (N,), reactions (N, R, 2), couples (N, R), `reaction_links` [(joint, from, to)] and valid (N,).
#[pyfunction]
#[allow(
    clippy::too_many_arguments,
    clippy::type_complexity,
    reason = "mirrors the Python call: drive, masses, gravity and loads in, a tuple of arrays out"
)]
pub fn forces<'py>(
    py: Python<'py>,
    mech: &Mechanism,
    theta: crate::args::F64Array1<'py>,
    omega: crate::args::F64Array1<'py>,
    alpha: crate::args::F64Array1<'py>,
    inertia: Vec<Strict<(Real, Real, Real, Real)>>,
    gravity: RealPair,
    loads: Vec<
        Strict<(
            Bound<'py, PyAny>,
            Bound<'py, PyAny>,
            crate::args::F64Array2<'py>,
            crate::args::F64Array1<'py>,
        )>,
    >,
) -> PyResult<JointForces> {
    let th = slice("theta", &theta)?;
    let n = th.len();
    let (w, a) = (slice("omega", &omega)?, slice("alpha", &alpha)?);
    if w.len() != n || a.len() != n {
        return Err(linkage_error("omega and alpha need one value per angle"));
    }
    let m = mech.snapshot();
    let ids: Vec<BodyId> = Bodies::of(&m).ids().collect();
    let mut load_data = Vec::with_capacity(loads.len());
    for Strict((body, joint, force, torque)) in &loads {
        let body = count("load body index", body)?;
        let joint = count("load joint index", joint)?;
        let f = force
            .as_slice()
            .map_err(|_| linkage_error("load force must be a contiguous float64 array"))?;
        let t = slice("load torque", torque)?;
        if f.len() / 2 != n || f.len() % 2 != 0 || t.len() != n {
            return Err(linkage_error("load arrays need one row per angle"));
        }
        let id = *ids
            .get(body)
            .ok_or_else(|| linkage_error(format!("load body index {body} out of range")))?;
        if joint >= m.len() {
            return Err(linkage_error(format!(
                "load joint index {joint} out of range"
            )));
        }
        let f: Vec<Vec2<f64>> = f.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect();
        load_data.push((id, joint, f, t));
    }
    let inertia: Vec<Inertia<f64>> = inertia
        .iter()
        .map(|&Strict((mass, along, left, inertia))| Inertia {
            mass: mass.0,
            along: along.0,
            left: left.0,
            inertia: inertia.0,
        })
        .collect();
    let (gx, gy) = xy(gravity);
    let g = Vec2::new(gx, gy);
    let dynamics = Dynamics::new(&m, &inertia, g).map_err(to_py)?;
    // The reactions' layout is fixed by the mechanism: size every output before solving.
    let idx = |b: BodyId| ids.iter().position(|&x| x == b).unwrap_or(0);
    let layout: Vec<(usize, usize, usize)> = dynamics
        .reaction_layout()
        .map(|(joint, from, to)| (joint, idx(from), idx(to)))
        .collect();
    let nr = layout.len();
    let what = || format!("forces of {n} samples × {nr} reactions");
    // torque, power (n each), reactions n × nr × 2 (twice: the core's and numpy's), couples
    // n × nr, the loads' forces n × 2 each; valid one byte a sample.
    let (nu, ru, lu) = (n as u128, nr as u128, loads.len() as u128);
    memory::check(
        &what,
        memory::bytes_of::<f64>(2 * nu + 5 * nu * ru + 2 * nu * lu) + nu,
    )?;
    let mut torque = memory::filled(&what, n, f64::NAN)?;
    let mut power = memory::filled(&what, n, f64::NAN)?;
    let mut valid = memory::filled(&what, n, false)?;
    let mut reactions = memory::filled(&what, n * nr, Vec2::new(f64::NAN, f64::NAN))?;
    let mut couples = memory::filled(&what, n * nr, f64::NAN)?;
    let result = py.detach(|| {
        let series: Vec<LoadSeries<'_, f64>> = load_data
            .iter()
            .map(|(body, joint, force, torque)| LoadSeries {
                body: *body,
                joint: *joint,
                force,
                torque,
            })
            .collect();
        let out = ForceSweep {
            torque: &mut torque,
            power_torque: &mut power,
            valid: &mut valid,
            reactions: &mut reactions,
            couples: &mut couples,
        };
        dynamics.sweep(th, w, a, &series, out)
    });
    result.map_err(to_py)?;
    let forces: Vec<f64> = reactions.iter().flat_map(|r| [r.x, r.y]).collect();
    Ok(JointForces {
        torque: PyArray1::from_vec(py, torque).unbind(),
        power_torque: PyArray1::from_vec(py, power).unbind(),
        valid: PyArray1::from_vec(py, valid).unbind(),
        reactions: PyArray1::from_vec(py, forces)
            .reshape(vec![n, nr, 2])?
            .unbind(),
        couples: PyArray1::from_vec(py, couples)
            .reshape(vec![n, nr])?
            .unbind(),
        reaction_links: layout,
    })
}

/// Adds the submodule `_core.kinetostatics` (joint forces and driving torque over a sweep (`linkage_core::kinetostatics`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "kinetostatics",
        "Joint forces and driving torque over a sweep (`linkage_core::kinetostatics`).",
    )?;
    m.add_class::<JointForces>()?;
    m.add_function(wrap_pyfunction!(crate::kinetostatics::forces, &m)?)?;
    Ok(())
}
