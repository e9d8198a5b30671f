//! Mirrors `linkage_core::fourbar`.

use linkage_core::{AngleMode, Assembly, FourBar as CoreFourBar, InputRange, Vec2};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::args::{choice, mid_sentence, named, xy, Real, RealPair};
use crate::error::{linkage_error, to_py};
use crate::mechanism::Mechanism;
use crate::memory;
use crate::module::CAPACITY;
use crate::simd::{simd_level, Simd};

/// Pole, inflection pole, circle centre, radius, Ball point, Ball point in the coupler frame.
type InflectionTuple = (
    (f64, f64),
    (f64, f64),
    (f64, f64),
    f64,
    (f64, f64),
    (f64, f64),
);

/// Most threads one fast sweep starts: more only add start-up time (the bits are the same for
/// any split), and an absurd request must not exhaust the system's threads.
const MAX_THREADS: usize = 256;

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
            #[allow(unsafe_code, reason = "calling a target_feature function")]
            // SAFETY: the only precondition of calling a `target_feature` function is that the
            // CPU supports those features; a `Simd` other than `Portable` comes only from
            // `simd_level`, which checked them.
            unsafe {
                fast_sweep_avx512(f, theta0, dtheta, first, mode, out)
            }
        }
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => {
            #[allow(unsafe_code, reason = "calling a target_feature function")]
            // SAFETY: as above.
            unsafe {
                fast_sweep_avx2(f, theta0, dtheta, first, mode, out)
            }
        }
        _ => f.uniform_sweep(theta0, dtheta, first, mode, out),
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
    #[allow(
        clippy::too_many_arguments,
        reason = "the Python constructor's arguments: pivots, three lengths, point, assembly"
    )]
    fn new(
        o: RealPair,
        c: RealPair,
        crank: Real,
        coupler: Real,
        rocker: Real,
        point: RealPair,
        assembly: &str,
    ) -> PyResult<Self> {
        let (o, c, point) = (xy(o), xy(c), xy(point));
        let (crank, coupler, rocker) = (crank.0, coupler.0, rocker.0);
        let assembly: Assembly = choice(assembly)?;
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
        let asm = f.assembly.name();
        (
            f.o.x, f.o.y, f.c.x, f.c.y, f.crank, f.coupler, f.rocker, f.along, f.left, asm,
        )
    }

    /// The two Roberts–Chebyshev cognates (`FourBar::cognates`).
    fn cognates(&self) -> PyResult<(FourBar, FourBar)> {
        let [a, b] = self.inner.cognates().map_err(to_py)?;
        Ok((FourBar::from_core(a), FourBar::from_core(b)))
    }

    /// The same linkage driven at its rocker (`FourBar::reversed`).
    fn reversed(&self) -> PyResult<FourBar> {
        self.inner.reversed().map(FourBar::from_core).map_err(to_py)
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
        theta: crate::args::F64Array1<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let th = theta
            .as_slice()
            .map_err(|_| linkage_error("theta must be a contiguous float64 array"))?;
        let f = self.inner;
        let mut out = memory::with_capacity(
            &|| format!("transmission angles of {} samples", th.len()),
            th.len(),
        )?;
        py.detach(|| {
            out.extend(
                th.iter()
                    .map(|&t| f.transmission_angle(t).unwrap_or(f64::NAN)),
            )
        });
        Ok(PyArray1::from_vec(py, out))
    }

    /// The mechanism program (joints O, C, A, B, P).
    fn mechanism(&self) -> PyResult<Mechanism> {
        // The program and its start angle (a change point's crank-up position).
        let m = self
            .inner
            .mechanism()
            .resized::<CAPACITY>()
            .map_err(to_py)?;
        Ok(Mechanism::from_core(m))
    }

    /// Circuit sweep of `n` samples: (theta (n,), joints (n, 5, 2), velocity per unit crank
    /// angle (n, 5, 2)).
    #[allow(
        clippy::type_complexity,
        reason = "the Python tuple returned, spelled out where it is built"
    )]
    fn circuit<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = named::n)] n: usize,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyArray1<f64>>,
    )> {
        if n < 2 {
            return Err(linkage_error(format!("n must be at least 2, got {n}")));
        }
        // theta and margin (n) + joints and velocities (n × 5 × 2 each), all f64.
        let what = || format!("circuit of {n} samples");
        memory::check(&what, memory::bytes_of::<f64>(n as u128 * 22))?;
        let mut theta = memory::filled(&what, n, 0.0)?;
        let mut margin = memory::filled(&what, n, 0.0)?;
        let mut joints = memory::filled(&what, n * 10, 0.0)?;
        let mut vel = memory::filled(&what, n * 10, 0.0)?;
        let f = self.inner;
        // Vec<f64> buffers of even length: 8-aligned, so the casts to points always succeed.
        fn cast(v: &mut [f64]) -> PyResult<&mut [Vec2<f64>]> {
            bytemuck::try_cast_slice_mut(v)
                .map_err(|e| linkage_error(format!("internal error: {e}")))
        }
        let (j, v) = (cast(&mut joints)?, cast(&mut vel)?);
        py.detach(|| f.circuit_with_margin(&mut theta, j, Some(v), Some(&mut margin)))
            .map_err(to_py)?;
        let joints = PyArray1::from_vec(py, joints)
            .reshape([n, 5, 2])?
            .into_any();
        let vel = PyArray1::from_vec(py, vel).reshape([n, 5, 2])?.into_any();
        Ok((
            PyArray1::from_vec(py, theta),
            joints,
            vel,
            PyArray1::from_vec(py, margin),
        ))
    }

    /// Inflection circle of the coupler at `theta`: (pole, inflection pole, centre, radius,
    /// Ball point, Ball point in the coupler frame), points as (x, y) with NaN where undefined;
    /// None where it cannot be formed.
    fn coupler_inflection(&self, theta: Real) -> Option<InflectionTuple> {
        let inf = self.inner.coupler_inflection(theta.0)?;
        let pose = self.inner.pose(theta.0).ok()?;
        let xy = |p: Vec2<f64>| (p.x, p.y);
        let ball = inf.ball_point.finite();
        Some((
            xy(inf.pole),
            xy(inf.inflection_pole),
            xy(inf.centre),
            inf.radius,
            ball.map_or((f64::NAN, f64::NAN), xy),
            ball.map_or((f64::NAN, f64::NAN), |p| xy(pose.to_coupler_frame(p))),
        ))
    }

    /// Coupler points `(n, 2)` at `theta0 + k·dtheta` by the fast kernel: `mode` "trig",
    /// "table" or "recurrence" (with `block`), on `threads` threads (the same bits for any
    /// count); into `out` (a writeable C-contiguous float64 `(n, 2)` array) when given.
    #[pyo3(signature = (theta0, dtheta, n, mode="table", block=64, threads=1, out=None))]
    #[allow(
        clippy::too_many_arguments,
        reason = "mirrors the Python call's keywords"
    )]
    fn uniform_sweep<'py>(
        &self,
        py: Python<'py>,
        theta0: Real,
        dtheta: Real,
        #[pyo3(from_py_with = named::n)] n: usize,
        mode: &str,
        #[pyo3(from_py_with = named::block)] block: usize,
        #[pyo3(from_py_with = named::threads)] threads: usize,
        out: Option<Bound<'py, PyArrayDyn<f64>>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (theta0, dtheta) = (theta0.0, dtheta.0);
        let mode = AngleMode::named(mode, block)
            .map_err(|e| linkage_error(format!("{e}, got {mode:?}")))?;
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
            // `count` caps n at i64::MAX, so 2·n fits usize on 64-bit; `memory` checks the bytes.
            let what = || format!("sweep of {n} samples");
            memory::check(&what, memory::bytes_of::<f64>(2 * n as u128))?;
            let mut flat = memory::filled(&what, 2 * n, 0.0_f64)?;
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
        if !out.is_aligned() {
            return Err(linkage_error(crate::args::UNALIGNED_OUT));
        }
        {
            let mut view = out.try_readwrite().map_err(|e| {
                linkage_error(format!(
                    "out must be a writeable array not in use: {}",
                    mid_sentence(e)
                ))
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
    // An `out` array can be misaligned (numpy allows it for buffers at odd offsets): refuse
    // it rather than let the cast panic.
    let points: &mut [Vec2<f64>] = bytemuck::try_cast_slice_mut(flat)
        .map_err(|e| format!("out must be an aligned float64 array ({e})"))?;
    let simd = simd_level();
    if threads <= 1 || points.len() < 2 {
        return fast_sweep(simd, f, theta0, dtheta, 0, mode, points).map_err(|e| e.to_string());
    }
    let chunk = points.len().div_ceil(threads.min(MAX_THREADS));
    // Chunks whose thread the system refused (limits, memory): swept here afterwards, which
    // gives the same bits as any thread would.
    let mut refused: Vec<(usize, usize)> = Vec::new();
    std::thread::scope(|scope| {
        let mut handles = Vec::new();
        for (t, part) in points.chunks_mut(chunk).enumerate() {
            let (first, len) = (t * chunk, part.len());
            let work = move || {
                fast_sweep(simd, f, theta0, dtheta, first, mode, part).map_err(|e| e.to_string())
            };
            match std::thread::Builder::new().spawn_scoped(scope, work) {
                Ok(h) => handles.push(h),
                Err(_) => refused.push((first, len)),
            }
        }
        handles.into_iter().try_for_each(|h| {
            // The kernel has no panicking path; a join error would be a bug, reported as one.
            h.join()
                .unwrap_or_else(|_| Err("internal error: a sweep thread panicked".into()))
        })
    })?;
    for (first, len) in refused {
        let part = &mut points[first..first + len];
        fast_sweep(simd, f, theta0, dtheta, first, mode, part).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The smallest transmission angle over a travel, folded to `[0, π/2]`, of each smallest sine
/// in `min_sine` (`linkage_core::min_transmission_angle`: `asin(min(max(s, 0), 1))`, 0 for NaN):
/// the one formula Burmester's and Freudenstein's checks, the gait figures and the Python
/// synthesis constraints share.
#[pyfunction]
pub fn min_transmission_angle<'py>(
    py: Python<'py>,
    min_sine: crate::args::F64Array1<'py>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let s = min_sine
        .as_slice()
        .map_err(|_| linkage_error("min_sine must be a contiguous float64 array"))?;
    let what = || format!("{} transmission angles", s.len());
    let mut out = memory::with_capacity(&what, s.len())?;
    out.extend(s.iter().map(|&x| linkage_core::min_transmission_angle(x)));
    Ok(PyArray1::from_vec(py, out))
}
