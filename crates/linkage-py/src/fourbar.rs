//! Mirrors `linkage_core::fourbar`.

use linkage_core::{AngleMode, Assembly, FourBar as CoreFourBar, InputRange, Vec2};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
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
    f: &CoreFourBar<f64>,
    theta0: f64,
    dtheta: f64,
    first: usize,
    mode: AngleMode,
    out: &mut [Vec2<f64>],
) -> Result<(), linkage_core::Error> {
    // LINKAGE_PORTABLE=1 keeps the portable build's code (for comparisons and tests).
    #[cfg(target_arch = "x86_64")]
    let wide = std::env::var_os("LINKAGE_PORTABLE").is_none();
    #[cfg(target_arch = "x86_64")]
    if wide
        && std::arch::is_x86_feature_detected!("avx512f")
        && std::arch::is_x86_feature_detected!("avx512dq")
        && std::arch::is_x86_feature_detected!("avx512vl")
    {
        #[allow(unsafe_code)]
        // SAFETY: the only precondition of calling a `target_feature` function is that the CPU
        // supports those features, checked just above.
        return unsafe { fast_sweep_avx512(f, theta0, dtheta, first, mode, out) };
    }
    #[cfg(target_arch = "x86_64")]
    if wide
        && std::arch::is_x86_feature_detected!("avx2")
        && std::arch::is_x86_feature_detected!("fma")
    {
        #[allow(unsafe_code)]
        // SAFETY: the only precondition of calling a `target_feature` function is that the CPU
        // supports those features, checked just above.
        return unsafe { fast_sweep_avx2(f, theta0, dtheta, first, mode, out) };
    }
    f.uniform_sweep(theta0, dtheta, first, mode, out)
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
    /// count).
    #[pyo3(signature = (theta0, dtheta, n, mode="table", block=64, threads=1))]
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
        let flat: Vec<f64> = py
            .detach(|| {
                // The output buffer is the numpy array's: the kernel writes points straight in.
                let mut flat = vec![0.0_f64; 2 * n];
                let points: &mut [Vec2<f64>] = bytemuck::cast_slice_mut(&mut flat);
                let chunk = n.div_ceil(threads).max(1);
                std::thread::scope(|scope| {
                    let handles: Vec<_> = points
                        .chunks_mut(chunk)
                        .enumerate()
                        .map(|(t, part)| {
                            scope.spawn(move || {
                                fast_sweep(&f, theta0, dtheta, t * chunk, mode, part)
                                    .map_err(|e| e.to_string())
                            })
                        })
                        .collect();
                    handles.into_iter().try_for_each(|h| {
                        h.join().unwrap_or_else(|_| {
                            Err("internal error: a sweep thread panicked".into())
                        })
                    })
                })
                .map(|_| flat)
            })
            .map_err(linkage_error)?;
        Ok(PyArray1::from_vec(py, flat).reshape([n, 2])?.into_any())
    }
}
