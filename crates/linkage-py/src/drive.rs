//! Mirrors `linkage_core::motion_law`, `linkage_core::gear_train` and `linkage_core::schedule`.

use linkage_core::{Discontinuity, GearTrain, MotionLaw, Program, ScheduleTable, Segment};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

pub mod cam;

use crate::args::{count_u32, Real, Strict};
use crate::error::{linkage_error, to_py};
use crate::memory;

fn law(name: &str) -> PyResult<MotionLaw> {
    MotionLaw::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = MotionLaw::ALL.iter().map(|l| l.name()).collect();
        linkage_error(format!(
            "unknown motion law {name:?}; choose from {}",
            names.join(", ")
        ))
    })
}

fn slice<'a>(name: &str, a: &'a crate::args::F64Array1<'_>) -> PyResult<&'a [f64]> {
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
#[pyo3(name = "evaluate_motion_law")]
pub fn motion_law_eval<'py>(
    py: Python<'py>,
    name: &str,
    u: crate::args::F64Array1<'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let l = law(name)?;
    let u = slice("u", &u)?;
    let mut out = columns(u.len(), 4, "motion law values")?;
    py.detach(|| out.extend(u.iter().flat_map(|&x| l.eval(x))));
    Ok(PyArray1::from_vec(py, out)
        .reshape([u.len(), 4])?
        .into_any())
}

/// Room for `rows × cols` floats (`cols` ≤ 4), or `MemoryError` naming the size.
fn columns(rows: usize, cols: usize, what: &str) -> PyResult<Vec<f64>> {
    let what = || format!("{what} at {rows} points");
    memory::check(&what, memory::bytes_of::<f64>(rows as u128 * cols as u128))?;
    memory::with_capacity(&what, rows * cols)
}

fn segments(
    durations: &[Real],
    rises: &[Real],
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
            Segment::new(d.0, r.0, l).map_err(to_py)
        })
        .collect()
}

/// `(N, 4)` value and first three derivatives of a program at `t`.
#[pyfunction]
#[pyo3(name = "evaluate_program")]
pub fn program_eval<'py>(
    py: Python<'py>,
    start: Real,
    durations: Vec<Real>,
    rises: Vec<Real>,
    laws: Vec<Option<String>>,
    t: crate::args::F64Array1<'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let segs = segments(&durations, &rises, &laws)?;
    let t = slice("t", &t)?;
    let p = Program {
        start: start.0,
        segments: &segs,
    };
    let mut out = columns(t.len(), 4, "program values")?;
    py.detach(|| out.extend(t.iter().flat_map(|&x| p.eval(x))));
    Ok(PyArray1::from_vec(py, out)
        .reshape([t.len(), 4])?
        .into_any())
}

/// Jumps of velocity / acceleration / jerk at the joins: `(after, order, jump)`.
#[pyfunction]
pub fn program_discontinuities(
    start: Real,
    durations: Vec<Real>,
    rises: Vec<Real>,
    laws: Vec<Option<String>>,
    tol: Real,
) -> PyResult<Vec<(usize, usize, f64)>> {
    let segs = segments(&durations, &rises, &laws)?;
    let p = Program {
        start: start.0,
        segments: &segs,
    };
    // At most three jumps a join (velocity, acceleration, jerk), one join a segment.
    let what = || format!("discontinuities of {} segments", segs.len());
    let empty = Discontinuity {
        after: 0,
        order: 0,
        jump: 0.0,
    };
    let slots = segs
        .len()
        .checked_mul(3)
        .ok_or_else(|| linkage_error(format!("{} segments are too many", segs.len())))?;
    let mut out = memory::filled(&what, slots, empty)?;
    let n = p.discontinuities(tol.0, &mut out);
    Ok(out[..n.min(out.len())]
        .iter()
        .map(|d| (d.after, d.order, d.jump))
        .collect())
}

/// The ratio of a gear train (`linkage_core::GearTrain`).
#[pyclass(module = "linkage._core.drive", frozen, get_all)]
pub struct GearRatio {
    /// `|output/input|` speed ratio.
    pub ratio: f64,
    /// `+1` if the output turns with the input, `-1` against it.
    pub sign: i8,
}

#[pymethods]
impl GearRatio {
    /// The 0.1 tuple `(ratio, sign)`, kept while the flat name is.
    fn astuple<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        pyo3::types::PyTuple::new(slf.py(), [slf.getattr("ratio")?, slf.getattr("sign")?])
    }

    fn __len__(&self) -> usize {
        2
    }

    fn __getitem__<'py>(slf: &Bound<'py, Self>, index: isize) -> PyResult<Bound<'py, PyAny>> {
        Self::astuple(slf)?.as_any().get_item(index)
    }

    fn __iter__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Ok(Self::astuple(slf)?.as_any().try_iter()?.into_any())
    }
}

/// The ratio of a simple train given tooth counts in mesh order.
#[pyfunction]
#[pyo3(name = "simple_gear_train")]
pub fn gear_train_simple(teeth: Vec<Bound<'_, PyAny>>) -> PyResult<GearRatio> {
    let teeth = teeth
        .iter()
        .map(|z| count_u32("gear tooth count", z))
        .collect::<PyResult<Vec<u32>>>()?;
    let t = GearTrain::simple(&teeth).map_err(to_py)?;
    Ok(GearRatio {
        ratio: t.ratio(),
        sign: t.sign(),
    })
}

/// The ratio of a compound train given `(driver, driven)` meshes.
#[pyfunction]
#[pyo3(name = "compound_gear_train")]
#[allow(
    clippy::type_complexity,
    reason = "a list of (driver, driven) pairs, each an int converted with its own message"
)]
pub fn gear_train_compound(
    stages: Vec<Strict<(Bound<'_, PyAny>, Bound<'_, PyAny>)>>,
) -> PyResult<GearRatio> {
    let stages = stages
        .iter()
        .map(|Strict((a, b))| Ok((count_u32("driver teeth", a)?, count_u32("driven teeth", b)?)))
        .collect::<PyResult<Vec<(u32, u32)>>>()?;
    let t = GearTrain::compound(&stages).map_err(to_py)?;
    Ok(GearRatio {
        ratio: t.ratio(),
        sign: t.sign(),
    })
}

/// `(N, 3)` θ, ω, α of a schedule table at `t`, evaluated in `f32` when `single` (the table
/// and times are rounded to `f32` first, as firmware would store them) or `f64`.
#[pyfunction]
#[pyo3(name = "evaluate_schedule")]
pub fn schedule_eval<'py>(
    py: Python<'py>,
    dt: Real,
    advance: Real,
    theta: crate::args::F64Array1<'py>,
    omega: crate::args::F64Array1<'py>,
    t: crate::args::F64Array1<'py>,
    single: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (th, w, t) = (
        slice("theta", &theta)?,
        slice("omega", &omega)?,
        slice("t", &t)?,
    );
    let (dt, advance) = (dt.0, advance.0);
    let mut out = columns(t.len(), 3, "schedule values")?;
    if single {
        // `as f32` rounds (to ±inf beyond the f32 range, which the table then rejects).
        let what = || format!("an f32 copy of a schedule of {} samples", th.len());
        let mut th32 = memory::with_capacity(&what, th.len())?;
        th32.extend(th.iter().map(|&x| x as f32));
        let mut w32 = memory::with_capacity(&what, w.len())?;
        w32.extend(w.iter().map(|&x| x as f32));
        let table = ScheduleTable::new(dt as f32, advance as f32, &th32, &w32).map_err(to_py)?;
        py.detach(|| {
            out.extend(t.iter().flat_map(|&x| {
                let (a, b, c) = table.at(x as f32);
                [f64::from(a), f64::from(b), f64::from(c)]
            }))
        });
    } else {
        let table = ScheduleTable::new(dt, advance, th, w).map_err(to_py)?;
        py.detach(|| {
            out.extend(t.iter().flat_map(|&x| {
                let (a, b, c) = table.at(x);
                [a, b, c]
            }))
        });
    }
    Ok(PyArray1::from_vec(py, out)
        .reshape([t.len(), 3])?
        .into_any())
}

/// A constant-foot-speed crank schedule tabulated at uniform times
/// (`linkage_core::StanceSchedule::fill`).
#[pyclass(module = "linkage._core.drive", frozen, get_all)]
pub struct StanceScheduleTable {
    /// Time step of the table (s): one period / samples.
    pub dt: f64,
    /// Crank angle at each time `k·dt` `(samples,)`.
    pub theta: Py<PyArray1<f64>>,
    /// Crank speed at each time `k·dt` `(samples,)`.
    pub omega: Py<PyArray1<f64>>,
    /// Time in stance (s).
    pub stance_time: f64,
    /// Crank angles where stance starts and ends.
    pub stance_angles: (f64, f64),
}

#[pymethods]
impl StanceScheduleTable {
    /// The 0.1 tuple `(dt, theta, omega, stance_time, stance_angles)`, kept while the flat name is.
    fn astuple<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        pyo3::types::PyTuple::new(
            slf.py(),
            [
                slf.getattr("dt")?,
                slf.getattr("theta")?,
                slf.getattr("omega")?,
                slf.getattr("stance_time")?,
                slf.getattr("stance_angles")?,
            ],
        )
    }

    fn __len__(&self) -> usize {
        5
    }

    fn __getitem__<'py>(slf: &Bound<'py, Self>, index: isize) -> PyResult<Bound<'py, PyAny>> {
        Self::astuple(slf)?.as_any().get_item(index)
    }

    fn __iter__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Ok(Self::astuple(slf)?.as_any().try_iter()?.into_any())
    }
}

/// The constant-foot-speed crank schedule (`linkage_core::StanceSchedule`) fitted to stance
/// samples `theta` (increasing crank angles) and `u` (foot speed along the stance line per
/// radian), tabulated at `samples` uniform times.
#[pyfunction]
pub fn stance_schedule<'py>(
    py: Python<'py>,
    theta: crate::args::F64Array1<'py>,
    u: crate::args::F64Array1<'py>,
    foot_speed: Real,
    duty_factor: Real,
    samples: &Bound<'py, PyAny>,
) -> PyResult<StanceScheduleTable> {
    let (th, u) = (slice("theta", &theta)?, slice("u", &u)?);
    let samples = crate::args::count("samples", samples)?;
    if samples == 0 {
        return Err(linkage_error("samples must be at least 1"));
    }
    let what = || format!("a crank schedule of {samples} samples");
    memory::check(
        &what,
        memory::bytes_of::<f64>(2 * samples as u128 + th.len() as u128),
    )?;
    let mut times = memory::filled(&what, th.len(), 0.0)?;
    let mut tab_th = memory::filled(&what, samples, 0.0)?;
    let mut tab_w = memory::filled(&what, samples, 0.0)?;
    let (dt, stance_time, angles) = py
        .detach(|| {
            let s =
                linkage_core::StanceSchedule::fit(th, u, &mut times, foot_speed.0, duty_factor.0)?;
            let dt = s.fill(&mut tab_th, &mut tab_w)?;
            Ok::<_, linkage_core::Error>((dt, s.stance_time(), s.stance_angles()))
        })
        .map_err(to_py)?;
    Ok(StanceScheduleTable {
        dt,
        theta: PyArray1::from_vec(py, tab_th).unbind(),
        omega: PyArray1::from_vec(py, tab_w).unbind(),
        stance_time,
        stance_angles: angles,
    })
}

/// Adds the submodule `_core.drive` (motion laws, programs, gear trains, schedules and cams (`linkage_core` `drive/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "drive",
        "Motion laws, programs, gear trains, schedules and cams (`linkage_core` `drive/`).",
    )?;
    m.add_class::<cam::CamGeometry>()?;
    m.add_class::<GearRatio>()?;
    m.add_class::<StanceScheduleTable>()?;
    m.add_function(wrap_pyfunction!(crate::drive::motion_law_names, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::motion_law_eval, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::program_eval, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::program_discontinuities, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::gear_train_simple, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::gear_train_compound, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::schedule_eval, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::stance_schedule, &m)?)?;
    m.add_function(wrap_pyfunction!(crate::drive::cam::cam_geometry, &m)?)?;
    Ok(())
}
