//! Mirrors `linkage_core::fourbar`.

use linkage_core::{AngleMode, Assembly, FourBar as CoreFourBar, InputRange, Vec2};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArray1, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::error::{linkage_error, to_py};
use crate::mechanism::Mechanism;
use crate::CAPACITY;

/// The fast sweep, compiled again for AVX-512 and for AVX2 + FMA and chosen at run time by what
/// the CPU has: the kernel is branch-free, so wider vectors make it ~3× faster (measured from
/// Python: 6.6 → 3.9 → 2.3 ns/sample). The arithmetic is the same in every build — Rust does not
/// contract `a * b + c` into a fused multiply-add — so every path gives the same bits (tested).
/// `LINKAGE_PORTABLE=1` in the environment keeps the portable code.
fn fast_sweep(
    simd: Simd,
    f: &CoreFourBar<f64>,
    theta0: f64,
    dtheta: f64,
    first: usize,
    mode: AngleMode,
    out: &mut [Vec2<f64>],
) -> Result<(), linkage_core::Error> {
    match simd {
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => {
            #[allow(unsafe_code)]
            // SAFETY: the only precondition of calling a `target_feature` function is that the
            // CPU supports those features; a `Simd` other than `Portable` comes only from
            // `simd_level`, which checked them.
            unsafe {
                fast_sweep_avx512(f, theta0, dtheta, first, mode, out)
            }
        }
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => {
            #[allow(unsafe_code)]
            // SAFETY: as above.
            unsafe {
                fast_sweep_avx2(f, theta0, dtheta, first, mode, out)
            }
        }
        _ => f.uniform_sweep(theta0, dtheta, first, mode, out),
    }
}

/// Which build of the fast sweep runs on this CPU (only `simd_level` makes one).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Simd {
    Portable,
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    Avx2,
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    Avx512,
}

fn simd_level() -> Simd {
    // LINKAGE_PORTABLE=1 keeps the portable build's code (for comparisons and tests).
    if std::env::var_os("LINKAGE_PORTABLE").is_some_and(|v| !v.is_empty() && v != "0") {
        return Simd::Portable;
    }
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
            return Simd::Avx512;
        }
        if has!("avx2") && has!("fma") {
            return Simd::Avx2;
        }
    }
    Simd::Portable
}

/// The instruction set the fast uniform sweep uses here: `"avx512"`, `"avx2"` or `"portable"`.
#[pyfunction]
pub fn sweep_simd() -> &'static str {
    match simd_level() {
        Simd::Avx512 => "avx512",
        Simd::Avx2 => "avx2",
        Simd::Portable => "portable",
    }
}

/// The same sweep compiled with extra target features (each name is one instantiation).
macro_rules! sweep_with_features {
    ($($name:ident = $features:literal;)*) => {$(
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        fn $name(
            f: &CoreFourBar<f64>,
            theta0: f64,
            dtheta: f64,
            first: usize,
            mode: AngleMode,
            out: &mut [Vec2<f64>],
        ) -> Result<(), linkage_core::Error> {
            f.uniform_sweep(theta0, dtheta, first, mode, out)
        }
    )*};
}

sweep_with_features! {
    fast_sweep_avx512 = "avx512f,avx512dq,avx512vl,avx2,fma";
    fast_sweep_avx2 = "avx2,fma";
}

/// A four-bar linkage (see `linkage.FourBar` for the documented Python class).
#[pyclass(module = "linkage._core", frozen)]
#[derive(Clone)]
pub struct FourBar {
    inner: CoreFourBar<f64>,
}

impl FourBar {
    /// Wraps a core four-bar.
    pub fn from_core(inner: CoreFourBar<f64>) -> Self {
        FourBar { inner }
    }
}

#[pymethods]
impl FourBar {
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        o: (f64, f64),
        c: (f64, f64),
        crank: f64,
        coupler: f64,
        rocker: f64,
        point: (f64, f64),
        assembly: &str,
    ) -> PyResult<Self> {
        let assembly = match assembly {
            "open" => Assembly::Open,
            "crossed" => Assembly::Crossed,
            other => {
                return Err(linkage_error(format!(
                    "assembly must be 'open' or 'crossed', got {other:?}"
                )))
            }
        };
        CoreFourBar::with_pivots(
            Vec2::new(o.0, o.1),
            Vec2::new(c.0, c.1),
            crank,
            coupler,
            rocker,
            point,
            assembly,
        )
        .map(FourBar::from_core)
        .map_err(to_py)
    }

    /// (ox, oy, cx, cy, crank, coupler, rocker, along, left, assembly)
    fn parameters(&self) -> (f64, f64, f64, f64, f64, f64, f64, f64, f64, &'static str) {
        let f = &self.inner;
        let asm = match f.assembly {
            Assembly::Open => "open",
            Assembly::Crossed => "crossed",
        };
        (
            f.o.x, f.o.y, f.c.x, f.c.y, f.crank, f.coupler, f.rocker, f.along, f.left, asm,
        )
    }

    /// Grashof class name.
    fn grashof(&self) -> &'static str {
        self.inner.grashof().name()
    }

    /// None (full turn), (lo, hi), ((lo, hi), (lo, hi)) for two circuits, or "never".
    fn input_range(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(match self.inner.input_range() {
            InputRange::Full => py.None(),
            InputRange::Between { lo, hi } => (lo, hi).into_pyobject(py)?.into_any().unbind(),
            InputRange::TwoIntervals { first, second } => {
                (first, second).into_pyobject(py)?.into_any().unbind()
            }
            InputRange::Never => "never".into_pyobject(py)?.into_any().unbind(),
        })
    }

    /// Transmission angle at each crank angle (NaN where it cannot assemble).
    fn transmission_angle<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let th = theta
            .as_slice()
            .map_err(|_| linkage_error("theta must be a contiguous float64 array"))?;
        let f = self.inner;
        let out: Vec<f64> = py.detach(|| {
            th.iter()
                .map(|&t| f.transmission_angle(t).unwrap_or(f64::NAN))
                .collect()
        });
        Ok(PyArray1::from_vec(py, out))
    }

    /// The mechanism program (joints O, C, A, B, P).
    fn mechanism(&self) -> PyResult<Mechanism> {
        let mut m = linkage_core::Mechanism::<f64, CAPACITY>::new();
        for c in self.inner.mechanism().constructions() {
            m.push(*c).map_err(to_py)?;
        }
        Ok(Mechanism::from_core(m))
    }

    /// Circuit sweep of `n` samples: (theta (n,), joints (n, 5, 2), velocity per unit crank
    /// angle (n, 5, 2)).
    #[allow(clippy::type_complexity)]
    fn circuit<'py>(
        &self,
        py: Python<'py>,
        n: usize,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
    )> {
        if n < 2 {
            return Err(linkage_error(format!("n must be at least 2, got {n}")));
        }
        let f = self.inner;
        let (theta, joints, vel) = py
            .detach(|| {
                let mut theta = vec![0.0; n];
                let mut joints = vec![Vec2::zeros(); 5 * n];
                let mut vel = vec![Vec2::zeros(); 5 * n];
                f.circuit(&mut theta, &mut joints, Some(&mut vel))
                    .map(|_| (theta, joints, vel))
            })
            .map_err(to_py)?;
        let flat = |v: Vec<Vec2<f64>>| -> Vec<f64> { v.iter().flat_map(|p| [p.x, p.y]).collect() };
        let joints = PyArray1::from_vec(py, flat(joints))
            .reshape([n, 5, 2])?
            .into_any();
        let vel = PyArray1::from_vec(py, flat(vel))
            .reshape([n, 5, 2])?
            .into_any();
        Ok((PyArray1::from_vec(py, theta), joints, vel))
    }

    /// Inflection circle of the coupler at `theta`: (pole, inflection pole, centre, radius,
    /// Ball point), points as (x, y) with NaN where undefined; None where it cannot be formed.
    #[allow(clippy::type_complexity)]
    fn coupler_inflection(
        &self,
        theta: f64,
    ) -> Option<((f64, f64), (f64, f64), (f64, f64), f64, (f64, f64))> {
        let inf = self.inner.coupler_inflection(theta)?;
        let xy = |p: Vec2<f64>| (p.x, p.y);
        let ball = inf.ball_point.finite().map_or((f64::NAN, f64::NAN), xy);
        Some((
            xy(inf.pole),
            xy(inf.inflection_pole),
            xy(inf.centre),
            inf.radius,
            ball,
        ))
    }

    /// Coupler points `(n, 2)` at `theta0 + k·dtheta` by the fast kernel: `mode` "trig",
    /// "table" or "recurrence" (with `block`), on `threads` threads (the same bits for any
    /// count); into `out` (a writeable C-contiguous float64 `(n, 2)` array) when given.
    #[pyo3(signature = (theta0, dtheta, n, mode="table", block=64, threads=1, out=None))]
    #[allow(clippy::too_many_arguments)]
    fn uniform_sweep<'py>(
        &self,
        py: Python<'py>,
        theta0: f64,
        dtheta: f64,
        n: usize,
        mode: &str,
        block: usize,
        threads: usize,
        out: Option<Bound<'py, PyArrayDyn<f64>>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let mode = match mode {
            "trig" => AngleMode::Trig,
            "table" => AngleMode::Table { block },
            "recurrence" => AngleMode::Recurrence { block },
            other => {
                return Err(linkage_error(format!(
                    "mode must be 'trig', 'table' or 'recurrence', got {other:?}"
                )))
            }
        };
        if threads == 0 {
            return Err(linkage_error("threads must be at least 1"));
        }
        let f = self.inner;
        if n > 0 {
            // Checked for the whole path before any thread writes, so `out` stays untouched.
            f.check_fixed_assembly_path(theta0, theta0 + dtheta * (n - 1) as f64)
                .map_err(to_py)?;
        }
        let Some(out) = out else {
            // The kernel writes points straight into the buffer the numpy array then owns.
            let mut flat = vec![0.0_f64; 2 * n];
            py.detach(|| fill(&f, theta0, dtheta, mode, threads, &mut flat))
                .map_err(linkage_error)?;
            return Ok(PyArray1::from_vec(py, flat).reshape([n, 2])?.into_any());
        };
        if out.shape() != [n, 2] {
            let got: Vec<String> = out.shape().iter().map(usize::to_string).collect();
            return Err(linkage_error(format!(
                "out must have shape ({n}, 2), got ({})",
                got.join(", ")
            )));
        }
        // `as_slice_mut` also accepts Fortran order, whose memory order is not (x, y) pairs.
        if !out.is_c_contiguous() {
            return Err(linkage_error("out must be C-contiguous"));
        }
        {
            let mut view = out.try_readwrite().map_err(|e| {
                linkage_error(format!("out must be a writeable array not in use: {e}"))
            })?;
            let flat = view
                .as_slice_mut()
                .map_err(|_| linkage_error("out must be C-contiguous"))?; // checked above
            py.detach(|| fill(&f, theta0, dtheta, mode, threads, flat))
                .map_err(linkage_error)?;
        }
        Ok(out.into_any())
    }
}

/// Fills `flat` (x, y pairs) with the fast sweep from sample 0, split over `threads` threads
/// (the calling thread when one).
fn fill(
    f: &CoreFourBar<f64>,
    theta0: f64,
    dtheta: f64,
    mode: AngleMode,
    threads: usize,
    flat: &mut [f64],
) -> Result<(), String> {
    let points: &mut [Vec2<f64>] = bytemuck::cast_slice_mut(flat);
    let simd = simd_level();
    if threads <= 1 || points.len() < 2 {
        return fast_sweep(simd, f, theta0, dtheta, 0, mode, points).map_err(|e| e.to_string());
    }
    let chunk = points.len().div_ceil(threads);
    std::thread::scope(|scope| {
        let handles: Vec<_> = points
            .chunks_mut(chunk)
            .enumerate()
            .map(|(t, part)| {
                scope.spawn(move || {
                    fast_sweep(simd, f, theta0, dtheta, t * chunk, mode, part)
                        .map_err(|e| e.to_string())
                })
            })
            .collect();
        handles.into_iter().try_for_each(|h| {
            h.join()
                .unwrap_or_else(|_| Err("internal error: a sweep thread panicked".into()))
        })
    })
}
