//! Mirrors `linkage_core::kinetostatics`: driver torque and joint reactions along a sweep.

use linkage_core::{Bodies, BodyId, Dynamics, Inertia, Load, Motion, Rates, Tracker, Vec2};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{linkage_error, to_py};
use crate::mechanism::Mechanism;
use crate::CAPACITY;

fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))
}

/// Kinetostatics along a sweep.
///
/// `inertia`: `(mass, along, left, inertia)` per body, ground first; `loads`: `(body index,
/// joint, force (N, 2), torque (N,))`. Returns torque (Newton–Euler) and power-method torque
/// (N,), reactions (N, R, 2), couples (N, R), `reaction_links` [(joint, from, to)] and valid (N,).
#[pyfunction]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn forces<'py>(
    py: Python<'py>,
    mech: &Mechanism,
    theta: PyReadonlyArray1<'py, f64>,
    omega: PyReadonlyArray1<'py, f64>,
    alpha: PyReadonlyArray1<'py, f64>,
    inertia: Vec<(f64, f64, f64, f64)>,
    gravity: (f64, f64),
    loads: Vec<(
        usize,
        usize,
        PyReadonlyArray2<'py, f64>,
        PyReadonlyArray1<'py, f64>,
    )>,
) -> PyResult<Bound<'py, PyDict>> {
    let th = slice("theta", &theta)?;
    let n = th.len();
    let (w, a) = (slice("omega", &omega)?, slice("alpha", &alpha)?);
    if w.len() != n || a.len() != n {
        return Err(linkage_error("omega and alpha need one value per angle"));
    }
    let m = mech.inner.clone();
    let ids: Vec<BodyId> = Bodies::of(&m).ids().collect();
    let mut load_data = Vec::with_capacity(loads.len());
    for (body, joint, force, torque) in &loads {
        let f = force
            .as_slice()
            .map_err(|_| linkage_error("load force must be a contiguous float64 array"))?;
        let t = slice("load torque", torque)?;
        if f.len() != 2 * n || t.len() != n {
            return Err(linkage_error("load arrays need one row per angle"));
        }
        let id = *ids
            .get(*body)
            .ok_or_else(|| linkage_error(format!("load body index {body} out of range")))?;
        if *joint >= m.len() {
            return Err(linkage_error(format!(
                "load joint index {joint} out of range"
            )));
        }
        load_data.push((id, *joint, f, t));
    }
    let inertia: Vec<Inertia<f64>> = inertia
        .iter()
        .map(|&(mass, along, left, inertia)| Inertia {
            mass,
            along,
            left,
            inertia,
        })
        .collect();
    let g = Vec2::new(gravity.0, gravity.1);
    let dynamics = Dynamics::new(&m, &inertia, g).map_err(to_py)?;
    let result = py.detach(|| {
        let j = m.len();
        let mut tracker = Tracker::new(&m)?;
        let (mut p, mut v, mut ac) = (
            [Vec2::zeros(); CAPACITY],
            [Vec2::zeros(); CAPACITY],
            [Vec2::zeros(); CAPACITY],
        );
        let mut torque = vec![f64::NAN; n];
        let mut power = vec![f64::NAN; n];
        let mut valid = vec![false; n];
        let mut reactions: Vec<Vec<(usize, BodyId, BodyId, Vec2<f64>, f64)>> = vec![Vec::new(); n];
        let mut sample_loads = Vec::with_capacity(load_data.len());
        for k in 0..n {
            let rates = Rates::acceleration(&mut v[..j], &mut ac[..j]);
            if tracker
                .step(th[k], Some(Motion::new(w[k], a[k])), &mut p[..j], rates)
                .is_err()
            {
                continue;
            }
            sample_loads.clear();
            sample_loads.extend(load_data.iter().map(|(id, joint, f, t)| Load {
                body: *id,
                joint: *joint,
                force: Vec2::new(f[2 * k], f[2 * k + 1]),
                torque: t[k],
            }));
            let Ok(sol) = dynamics.solve(&p[..j], &v[..j], &ac[..j], &sample_loads) else {
                continue;
            };
            valid[k] = true;
            torque[k] = sol.torque;
            power[k] = dynamics.power_torque(&p[..j], &v[..j], &ac[..j], &sample_loads);
            reactions[k] = sol
                .reactions
                .iter()
                .map(|r| (r.joint, r.from, r.to, r.force, r.couple))
                .collect();
        }
        Ok::<_, linkage_core::Error>((torque, power, valid, reactions))
    });
    let (torque, power, valid, reactions) = result.map_err(to_py)?;
    let layout: Vec<(usize, usize, usize)> = reactions
        .iter()
        .find(|r| !r.is_empty())
        .map(|r| {
            r.iter()
                .map(|&(joint, from, to, _, _)| {
                    let idx = |b: BodyId| ids.iter().position(|&x| x == b).unwrap_or(0);
                    (joint, idx(from), idx(to))
                })
                .collect()
        })
        .unwrap_or_default();
    let nr = layout.len();
    let mut forces = vec![f64::NAN; n * nr * 2];
    let mut couples = vec![f64::NAN; n * nr];
    for (k, r) in reactions.iter().enumerate() {
        for (q, &(_, _, _, f, c)) in r.iter().enumerate() {
            forces[(k * nr + q) * 2] = f.x;
            forces[(k * nr + q) * 2 + 1] = f.y;
            couples[k * nr + q] = c;
        }
    }
    let d = PyDict::new(py);
    d.set_item("torque", PyArray1::from_vec(py, torque))?;
    d.set_item("power_torque", PyArray1::from_vec(py, power))?;
    d.set_item("valid", PyArray1::from_vec(py, valid))?;
    d.set_item(
        "reactions",
        PyArray1::from_vec(py, forces).reshape([n, nr, 2])?,
    )?;
    d.set_item("couples", PyArray1::from_vec(py, couples).reshape([n, nr])?)?;
    d.set_item("reaction_links", layout)?;
    Ok(d)
}
