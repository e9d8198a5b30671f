//! Mirrors `linkage_core::motion_law`, `linkage_core::gear_train` and `linkage_core::schedule`.

use linkage_core::{Discontinuity, GearTrain, MotionLaw, Program, ScheduleTable, Segment};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::error::{linkage_error, to_py};

fn law(name: &str) -> PyResult<MotionLaw> {
    MotionLaw::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = MotionLaw::ALL.iter().map(|l| l.name()).collect();
        linkage_error(format!(
            "unknown motion law {name:?}; choose from {}",
            names.join(", ")
        ))
    })
}

fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))
}

/// Names of the motion laws.
#[pyfunction]
pub fn motion_law_names() -> Vec<&'static str> {
    MotionLaw::ALL.iter().map(|l| l.name()).collect()
}

/// `(N, 4)` displacement, velocity, acceleration, jerk of a law at `u`.
#[pyfunction]
pub fn motion_law_eval<'py>(
    py: Python<'py>,
    name: &str,
    u: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let l = law(name)?;
    let u = slice("u", &u)?;
    let out: Vec<f64> = py.detach(|| u.iter().flat_map(|&x| l.eval(x)).collect());
    Ok(PyArray1::from_vec(py, out)
        .reshape([u.len(), 4])?
        .into_any())
}

fn segments(
    durations: &[f64],
    rises: &[f64],
    laws: &[Option<String>],
) -> PyResult<Vec<Segment<f64>>> {
    if durations.len() != rises.len() || rises.len() != laws.len() {
        return Err(linkage_error(
            "segments need equally many durations, rises and laws",
        ));
    }
    durations
        .iter()
        .zip(rises)
        .zip(laws)
        .map(|((&d, &r), l)| {
            let l = l.as_deref().map(law).transpose()?;
            Segment::new(d, r, l).map_err(to_py)
        })
        .collect()
}

/// `(N, 4)` value and first three derivatives of a program at `t`.
#[pyfunction]
pub fn program_eval<'py>(
    py: Python<'py>,
    start: f64,
    durations: Vec<f64>,
    rises: Vec<f64>,
    laws: Vec<Option<String>>,
    t: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let segs = segments(&durations, &rises, &laws)?;
    let t = slice("t", &t)?;
    let p = Program {
        start,
        segments: &segs,
    };
    let out: Vec<f64> = py.detach(|| t.iter().flat_map(|&x| p.eval(x)).collect());
    Ok(PyArray1::from_vec(py, out)
        .reshape([t.len(), 4])?
        .into_any())
}

/// Jumps of velocity / acceleration / jerk at the joins: `(after, order, jump)`.
#[pyfunction]
pub fn program_discontinuities(
    start: f64,
    durations: Vec<f64>,
    rises: Vec<f64>,
    laws: Vec<Option<String>>,
    tol: f64,
) -> PyResult<Vec<(usize, usize, f64)>> {
    let segs = segments(&durations, &rises, &laws)?;
    let p = Program {
        start,
        segments: &segs,
    };
    let mut out = vec![
        Discontinuity {
            after: 0,
            order: 0,
            jump: 0.0
        };
        3 * segs.len()
    ];
    let n = p.discontinuities(tol, &mut out);
    Ok(out[..n.min(out.len())]
        .iter()
        .map(|d| (d.after, d.order, d.jump))
        .collect())
}

/// `(ratio, sign)` of a simple train given tooth counts in mesh order.
#[pyfunction]
pub fn gear_train_simple(teeth: Vec<u32>) -> PyResult<(f64, i8)> {
    let t = GearTrain::simple(&teeth).map_err(to_py)?;
    Ok((t.ratio(), t.sign()))
}

/// `(ratio, sign)` of a compound train given `(driver, driven)` meshes.
#[pyfunction]
pub fn gear_train_compound(stages: Vec<(u32, u32)>) -> PyResult<(f64, i8)> {
    let t = GearTrain::compound(&stages).map_err(to_py)?;
    Ok((t.ratio(), t.sign()))
}

/// `(N, 3)` θ, ω, α of a schedule table at `t`, evaluated in `f32` when `single` (the table
/// and times are rounded to `f32` first, as firmware would store them) or `f64`.
#[pyfunction]
pub fn schedule_eval<'py>(
    py: Python<'py>,
    dt: f64,
    advance: f64,
    theta: PyReadonlyArray1<'py, f64>,
    omega: PyReadonlyArray1<'py, f64>,
    t: PyReadonlyArray1<'py, f64>,
    single: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (th, w, t) = (
        slice("theta", &theta)?,
        slice("omega", &omega)?,
        slice("t", &t)?,
    );
    let out: Vec<f64> = if single {
        let th32: Vec<f32> = th.iter().map(|&x| x as f32).collect();
        let w32: Vec<f32> = w.iter().map(|&x| x as f32).collect();
        let table = ScheduleTable::new(dt as f32, advance as f32, &th32, &w32).map_err(to_py)?;
        py.detach(|| {
            t.iter()
                .flat_map(|&x| {
                    let (a, b, c) = table.at(x as f32);
                    [f64::from(a), f64::from(b), f64::from(c)]
                })
                .collect()
        })
    } else {
        let table = ScheduleTable::new(dt, advance, th, w).map_err(to_py)?;
        py.detach(|| {
            t.iter()
                .flat_map(|&x| {
                    let (a, b, c) = table.at(x);
                    [a, b, c]
                })
                .collect()
        })
    };
    Ok(PyArray1::from_vec(py, out)
        .reshape([t.len(), 3])?
        .into_any())
}
