//! Mirrors `linkage_core::burmester` and `linkage_core::freudenstein`: precision-point
//! synthesis. Converts, calls the core, converts back; the Python API is `linkage._precision`.

use linkage_core::{
    centre_point, chebyshev_spacing, circle_point, common_pole, Assembly, BodyPose, BurmesterCurve,
    BurmesterPair, Defect, Error, FunctionGenerator, MotionCandidate, Vec2,
};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{linkage_error, to_py};
use crate::memory;

fn poses_of(poses: &[(f64, f64, f64)]) -> PyResult<Vec<BodyPose<f64>>> {
    poses
        .iter()
        .map(|&(x, y, a)| BodyPose::new(x, y, a).map_err(to_py))
        .collect()
}

fn three(poses: &[(f64, f64, f64)]) -> PyResult<[BodyPose<f64>; 3]> {
    poses_of(poses)?
        .try_into()
        .map_err(|p: Vec<_>| linkage_error(format!("needs exactly 3 poses, got {}", p.len())))
}

/// The centre point of a circle point for three poses.
#[pyfunction]
pub fn burmester_centre_point(
    poses: Vec<(f64, f64, f64)>,
    circle: (f64, f64),
) -> PyResult<(f64, f64)> {
    let p = centre_point(&three(&poses)?, Vec2::new(circle.0, circle.1)).map_err(to_py)?;
    Ok((p.centre.x, p.centre.y))
}

/// The circle point of a centre point for three poses.
#[pyfunction]
pub fn burmester_circle_point(
    poses: Vec<(f64, f64, f64)>,
    centre: (f64, f64),
) -> PyResult<(f64, f64)> {
    let p = circle_point(&three(&poses)?, Vec2::new(centre.0, centre.1)).map_err(to_py)?;
    Ok((p.circle.x, p.circle.y))
}

/// The point every pose turns about, if the poses are rotations about one point (else None);
/// raises for bad poses (not finite, coincident).
#[pyfunction]
pub fn burmester_common_pole(poses: Vec<(f64, f64, f64)>) -> PyResult<Option<(f64, f64)>> {
    let p = poses_of(&poses)?;
    Ok(common_pole(&p).map_err(to_py)?.map(|x| (x.x, x.y)))
}

/// The Burmester curves of four poses at free crank rotations `beta` (N,) to pose `free` (the
/// best-conditioned pose when None): the free pose's
/// index, centre points (N, 2, 2) and circle points (N, 2, 2) for the two solutions at each
/// (NaN where none), and the crank rotations to every pose (N, 2, 4).
#[allow(
    clippy::type_complexity,
    reason = "the Python tuple returned, spelled out where it is built"
)]
#[pyfunction]
#[pyo3(signature = (poses, beta, free=None))]
pub fn burmester_curve<'py>(
    py: Python<'py>,
    poses: Vec<(f64, f64, f64)>,
    beta: crate::args::F64Array1<'py>,
    free: Option<usize>,
) -> PyResult<(
    usize,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
)> {
    let p: [BodyPose<f64>; 4] = poses_of(&poses)?
        .try_into()
        .map_err(|p: Vec<_>| linkage_error(format!("needs exactly 4 poses, got {}", p.len())))?;
    let curve = match free {
        None => BurmesterCurve::new(&p),
        Some(k) => BurmesterCurve::with_free_pose(&p, k),
    }
    .map_err(to_py)?;
    let beta = beta.as_slice()?;
    let n = beta.len();
    let what = || format!("Burmester curves at {n} angles");
    memory::check(&what, memory::bytes_of::<f64>(16 * n as u128))?;
    let mut centres = memory::with_capacity(&what, 4 * n)?;
    let mut circles = memory::with_capacity(&what, 4 * n)?;
    let mut rotations = memory::with_capacity(&what, 8 * n)?;
    py.detach(|| {
        for &b in beta {
            for d in curve.dyads_with_rotations(b) {
                match d {
                    Some((pair, rot)) => {
                        centres.extend([pair.centre.x, pair.centre.y]);
                        circles.extend([pair.circle.x, pair.circle.y]);
                        rotations.extend(rot);
                    }
                    None => {
                        centres.extend([f64::NAN; 2]);
                        circles.extend([f64::NAN; 2]);
                        rotations.extend([f64::NAN; 4]);
                    }
                }
            }
        }
    });
    Ok((
        curve.free_pose(),
        PyArray1::from_vec(py, centres)
            .reshape([n, 2, 2])?
            .into_any(),
        PyArray1::from_vec(py, circles)
            .reshape([n, 2, 2])?
            .into_any(),
        PyArray1::from_vec(py, rotations)
            .reshape([n, 2, 4])?
            .into_any(),
    ))
}

/// `(code, pose)` of a defect: code −1 none, 0 branch, 1 toggle, 2 order, 3 flat position,
/// 4 input limit; pose −1 where it has none.
fn defect_code(d: Option<Defect>) -> (i64, i64) {
    match d {
        None => (-1, -1),
        Some(Defect::Branch { pose }) => (0, pose as i64),
        Some(Defect::Toggle { pose }) => (1, pose as i64),
        Some(Defect::Order) => (2, -1),
        Some(Defect::FlatPosition) => (3, -1),
        Some(Defect::InputLimit) => (4, -1),
        Some(_) => (5, -1),
    }
}

/// Whether an error concerns the poses themselves (the same for every pair), not the pair.
fn pose_error(e: &Error) -> bool {
    matches!(
        e,
        Error::TooFew { .. }
            | Error::BufferLength { .. }
            | Error::CoincidentPositions { .. }
            | Error::NotFinite {
                what: "pose x" | "pose y" | "pose angle",
                ..
            }
    )
}

/// Four-bars from pairs of dyads (rows `[centre x, centre y, circle x, circle y]` of `crank`
/// and `rocker`, M each), each checked through the poses. A dict of arrays: `ok` (M,) whether
/// the pair makes a four-bar (else `error` holds why), `params` (M, 10) `o, c, crank,
/// coupler, rocker, along, left, crossed`, `defect`/`defect_pose` (M,) codes, `direction`,
/// `crank_angles` (M, 4), `position_error`, `angle_error`, `min_transmission`, `grashof`.
#[pyfunction]
pub fn motion_candidates<'py>(
    py: Python<'py>,
    poses: Vec<(f64, f64, f64)>,
    crank: crate::args::F64Array2<'py>,
    rocker: crate::args::F64Array2<'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let p = poses_of(&poses)?;
    let rows = |name: &str, a: &crate::args::F64Array2<'py>| -> PyResult<Vec<BurmesterPair<f64>>> {
        if a.as_array().ncols() != 4 {
            return Err(linkage_error(format!("{name} must have shape (M, 4)")));
        }
        let s = a
            .as_slice()
            .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))?;
        Ok(s.chunks_exact(4)
            .map(|r| BurmesterPair {
                centre: Vec2::new(r[0], r[1]),
                circle: Vec2::new(r[2], r[3]),
            })
            .collect())
    };
    let (cr, rk) = (rows("crank", &crank)?, rows("rocker", &rocker)?);
    if cr.len() != rk.len() {
        return Err(linkage_error(format!(
            "crank and rocker must have the same number of rows, got {} and {}",
            cr.len(),
            rk.len()
        )));
    }
    let m = cr.len();
    let what = || format!("{m} motion candidates");
    memory::check(&what, memory::bytes_of::<f64>(24 * m as u128))?;
    let results: Vec<Result<MotionCandidate<f64>, Error>> = py.detach(|| {
        (0..m)
            .map(|i| MotionCandidate::new(&p, cr[i], rk[i]))
            .collect()
    });
    let mut ok = Vec::with_capacity(m);
    let mut error = Vec::with_capacity(m);
    let mut params = Vec::with_capacity(10 * m);
    let (mut code, mut pose) = (Vec::with_capacity(m), Vec::with_capacity(m));
    let mut direction = Vec::with_capacity(m);
    let mut angles = Vec::with_capacity(4 * m);
    let (mut perr, mut aerr, mut mu) = (
        Vec::with_capacity(m),
        Vec::with_capacity(m),
        Vec::with_capacity(m),
    );
    let mut grashof = Vec::with_capacity(m);
    for r in results {
        match r {
            Ok(c) => {
                let f = c.four_bar;
                let crossed = if f.assembly == Assembly::Crossed {
                    1.0
                } else {
                    0.0
                };
                params.extend([
                    f.o.x, f.o.y, f.c.x, f.c.y, f.crank, f.coupler, f.rocker, f.along, f.left,
                    crossed,
                ]);
                let (k, j) = defect_code(c.check.defect);
                code.push(k);
                pose.push(j);
                direction.push(c.check.direction);
                angles.extend(c.check.crank_angles);
                perr.push(c.check.position_error);
                aerr.push(c.check.angle_error);
                mu.push(c.check.min_transmission);
                grashof.push(c.check.grashof.name().to_string());
                ok.push(true);
                error.push(String::new());
            }
            Err(e) if pose_error(&e) => return Err(to_py(e)),
            Err(e) => {
                params.extend([f64::NAN; 10]);
                code.push(-1);
                pose.push(-1);
                direction.push(f64::NAN);
                angles.extend([f64::NAN; 4]);
                perr.push(f64::NAN);
                aerr.push(f64::NAN);
                mu.push(f64::NAN);
                grashof.push(String::new());
                ok.push(false);
                error.push(e.to_string());
            }
        }
    }
    let d = PyDict::new(py);
    d.set_item("ok", PyArray1::from_vec(py, ok))?;
    d.set_item("error", error)?;
    d.set_item("params", PyArray1::from_vec(py, params).reshape([m, 10])?)?;
    d.set_item("defect", PyArray1::from_vec(py, code))?;
    d.set_item("defect_pose", PyArray1::from_vec(py, pose))?;
    d.set_item("direction", PyArray1::from_vec(py, direction))?;
    d.set_item(
        "crank_angles",
        PyArray1::from_vec(py, angles).reshape([m, 4])?,
    )?;
    d.set_item("position_error", PyArray1::from_vec(py, perr))?;
    d.set_item("angle_error", PyArray1::from_vec(py, aerr))?;
    d.set_item("min_transmission", PyArray1::from_vec(py, mu))?;
    d.set_item("grashof", grashof)?;
    Ok(d)
}

/// Chebyshev precision points: `n` values on `[x0, x1]`.
#[pyfunction]
pub fn chebyshev_points<'py>(
    py: Python<'py>,
    x0: f64,
    x1: f64,
    n: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let n = crate::args::count("n", n)?;
    let what = || format!("{n} Chebyshev points");
    let mut out = memory::with_capacity(&what, n)?;
    out.extend((0..n).map(|j| chebyshev_spacing(x0, x1, n, j)));
    Ok(PyArray1::from_vec(py, out))
}

/// Freudenstein synthesis through precision points `(phi, psi)` with ground `ground`, then the
/// tracked sweep of the input samples `samples`. A dict: `k` (K1, K2, K3), `params` (10,) as in
/// [`motion_candidates`], `input_offset`, `output_offset`, `output` (N,) the output angles,
/// `defect`/`defect_pose`, `precision_error`, `min_transmission`, `grashof`.
#[pyfunction]
pub fn function_generator<'py>(
    py: Python<'py>,
    phi: crate::args::F64Array1<'py>,
    psi: crate::args::F64Array1<'py>,
    ground: f64,
    samples: crate::args::F64Array1<'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let (phi, psi) = (phi.as_slice()?, psi.as_slice()?);
    let samples = samples.as_slice()?;
    let n = samples.len();
    let mut out = memory::filled(&|| format!("{n} output angles"), n, f64::NAN)?;
    let (gen, check) = py
        .detach(|| {
            let gen = FunctionGenerator::synthesise(phi, psi, ground)?;
            let check = gen.sweep(samples, &mut out, phi, psi)?;
            Ok::<_, Error>((gen, check))
        })
        .map_err(to_py)?;
    let f = gen.four_bar;
    let crossed = if f.assembly == Assembly::Crossed {
        1.0
    } else {
        0.0
    };
    let (code, pose) = defect_code(check.defect);
    let d = PyDict::new(py);
    let k = gen.freudenstein;
    d.set_item("k", (k.k1, k.k2, k.k3))?;
    d.set_item(
        "params",
        PyArray1::from_vec(
            py,
            vec![
                f.o.x, f.o.y, f.c.x, f.c.y, f.crank, f.coupler, f.rocker, f.along, f.left, crossed,
            ],
        ),
    )?;
    d.set_item("input_offset", gen.input_offset)?;
    d.set_item("output_offset", gen.output_offset)?;
    d.set_item("output", PyArray1::from_vec(py, out))?;
    d.set_item("defect", code)?;
    d.set_item("defect_pose", pose)?;
    d.set_item("precision_error", check.precision_error)?;
    d.set_item("min_transmission", check.min_transmission)?;
    d.set_item("grashof", check.grashof.name())?;
    Ok(d)
}
