//! Mirrors `linkage_core::mechanism` and `linkage_core::sweep`: the mechanism builder, and
//! the sweep over numpy arrays (checked and allocated here, computed by the core).

use linkage_core::{
    Bodies, Columns, Construction, LineDirection, Mechanism as CoreMechanism, Pairs, Rate, Reach,
    Side, SweepOutputs, Vec2,
};
use numpy::{Ix1, Ix2, Ix3, PyArray, PyArrayMethods, PyReadwriteArray, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use std::sync::{Mutex, MutexGuard};

use crate::args::{choice, finite, named, Real};
use crate::error::{linkage_error, to_py};
use crate::memory;
use crate::module::CAPACITY;

pub mod bodies;

/// Reads an optional rate array: absent is `default`, length 1 is a scalar, length `n` per sample.
fn rate<'a>(
    name: &str,
    arr: &'a Option<crate::args::F64Array1<'_>>,
    n: usize,
    default: f64,
) -> PyResult<Rate<'a, f64>> {
    let Some(arr) = arr else {
        return Ok(Rate::Scalar(default));
    };
    let s = arr
        .as_slice()
        .map_err(|_| linkage_error(format!("{name} must be a contiguous float64 array")))?;
    finite(name, s)?;
    match s.len() {
        1 => Ok(Rate::Scalar(s[0])),
        len if len == n => Ok(Rate::PerSample(s)),
        len => Err(linkage_error(format!(
            "{name} must be a scalar or have one value per angle ({n}), got {len}"
        ))),
    }
}

/// A mechanism program of up to `CAPACITY` joints, addressed by index (the `linkage.Mechanism`
/// class adds names).
///
/// Frozen, with the program behind a mutex: methods take `&self`, so no call can meet a borrow
/// held by another thread or a re-entrant call (`RuntimeError: Already borrowed`). Each method
/// holds the lock only for its own short, panic-free work and never while waiting for the GIL,
/// and a sweep works on a copy taken under the lock.
#[pyclass(module = "linkage._core", frozen)]
pub struct Mechanism {
    inner: Mutex<CoreMechanism<f64, CAPACITY>>,
}

impl Mechanism {
    /// Wraps a core mechanism.
    pub fn from_core(inner: CoreMechanism<f64, CAPACITY>) -> Self {
        Mechanism {
            inner: Mutex::new(inner),
        }
    }

    /// The program, locked. Nothing panics while holding the lock, so it is never poisoned;
    /// if it were, the program itself is still whole (every change is a single `push`).
    fn lock(&self) -> MutexGuard<'_, CoreMechanism<f64, CAPACITY>> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A copy of the program as it is now.
    pub fn snapshot(&self) -> CoreMechanism<f64, CAPACITY> {
        self.lock().clone()
    }
}

#[pymethods]
impl Mechanism {
    #[new]
    fn new() -> Self {
        Mechanism::from_core(CoreMechanism::new())
    }

    fn __len__(&self) -> usize {
        self.lock().len()
    }

    /// Index of the crank joint, or None.
    #[getter]
    fn driver(&self) -> Option<usize> {
        self.lock().driver()
    }

    /// Adds a fixed joint at (x, y); returns its index.
    fn fixed(&self, x: Real, y: Real) -> PyResult<usize> {
        self.lock().fixed(Vec2::new(x.0, y.0)).map_err(to_py)
    }

    /// Adds the crank about joint `centre`; returns its index.
    #[pyo3(signature = (centre, radius, phase=0.0))]
    fn crank(
        &self,
        #[pyo3(from_py_with = named::centre)] centre: usize,
        radius: Real,
        #[pyo3(from_py_with = crate::args::real)] phase: f64,
    ) -> PyResult<usize> {
        self.lock().crank(centre, radius.0, phase).map_err(to_py)
    }

    /// Adds an RRR dyad at r1 from p1 and r2 from p2 on `side` of p1 → p2.
    fn dyad(
        &self,
        #[pyo3(from_py_with = named::p1)] p1: usize,
        #[pyo3(from_py_with = named::p2)] p2: usize,
        r1: Real,
        r2: Real,
        side: &str,
    ) -> PyResult<usize> {
        let side: Side = choice(side)?;
        self.lock().dyad(p1, p2, r1.0, r2.0, side).map_err(to_py)
    }

    /// Adds a slider dyad on the fixed direction (dx, dy) through `origin`.
    fn slider(
        &self,
        #[pyo3(from_py_with = named::pivot)] pivot: usize,
        r: Real,
        #[pyo3(from_py_with = named::origin)] origin: usize,
        dx: Real,
        dy: Real,
        reach: &str,
    ) -> PyResult<usize> {
        let reach: Reach = choice(reach)?;
        let direction = LineDirection::Fixed(Vec2::new(dx.0, dy.0));
        self.lock()
            .slider(pivot, r.0, origin, direction, reach)
            .map_err(to_py)
    }

    /// Adds a slider dyad on a line through `origin` carried by the link `from_ → to`, turned by
    /// `angle`.
    #[allow(
        clippy::too_many_arguments,
        reason = "the slider's joints, length and carrying link, as the Python call passes them"
    )]
    fn slider_on_link(
        &self,
        #[pyo3(from_py_with = named::pivot)] pivot: usize,
        r: Real,
        #[pyo3(from_py_with = named::origin)] origin: usize,
        #[pyo3(from_py_with = named::from_)] from_: usize,
        #[pyo3(from_py_with = named::to)] to: usize,
        angle: Real,
        reach: &str,
    ) -> PyResult<usize> {
        let reach: Reach = choice(reach)?;
        let direction = LineDirection::Link {
            from: from_,
            to,
            angle: angle.0,
        };
        self.lock()
            .slider(pivot, r.0, origin, direction, reach)
            .map_err(to_py)
    }

    /// Adds a point carried by the link `from_ → to` at (along, left).
    fn point(
        &self,
        #[pyo3(from_py_with = named::from_)] from_: usize,
        #[pyo3(from_py_with = named::to)] to: usize,
        along: Real,
        left: Real,
    ) -> PyResult<usize> {
        self.lock().point(from_, to, along.0, left.0).map_err(to_py)
    }

    /// Constructions as strings, one per joint in program order: each the core
    /// `Construction`'s `Debug` form, e.g. `Crank { centre: 0, radius: 10.0, phase: 0.0 }`
    /// (for display and debugging only: `constructions` gives the same as values).
    fn describe(&self) -> Vec<String> {
        self.snapshot()
            .constructions()
            .iter()
            .map(|c| format!("{c:?}"))
            .collect()
    }

    /// Constructions as dicts, one per joint in program order: `kind` (`"fixed"`, `"crank"`,
    /// `"dyad"`, `"slider"`, `"point"`) and the core `Construction`'s fields: `at` (x, y);
    /// `centre`, `radius`, `phase`; `p1`, `p2`, `r1`, `r2`, `side`; `pivot`, `r`, `origin`,
    /// `direction` (`("fixed", dx, dy)`, a unit vector, or `("link", from, to, angle)`),
    /// `reach`; `from`, `to`, `along`, `left`.
    fn constructions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let m = self.snapshot();
        let out = PyList::empty(py);
        for c in m.constructions() {
            out.append(construction(py, c)?)?;
        }
        Ok(out)
    }

    /// The unit direction of the line of slider `joint` in each sample of swept joints
    /// `(n, j, 2)` (`linkage_core::Mechanism::line_directions`): `(n, 2)`, NaN where it is
    /// undetermined (a sample that did not assemble).
    fn line_directions<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = named::joint)] joint: usize,
        joints: crate::args::F64Array3<'py>,
    ) -> PyResult<Bound<'py, PyArray<f64, Ix2>>> {
        let m = self.snapshot();
        let rows = joint_rows("joints", &joints, m.len())?;
        let n = joints.shape()[0];
        let what = || format!("line directions of {n} samples");
        memory::check(&what, memory::bytes_of::<f64>(n as u128 * 2))?;
        let out = memory::uninit::<f64, Ix2>(py, &what, &[n, 2])?;
        {
            let u = fresh_points(&out)?;
            py.detach(|| m.line_directions(joint, rows, u))
                .map_err(to_py)?;
        }
        Ok(out)
    }

    /// Body (link) members as joint index lists, the ground first.
    fn bodies(&self) -> Vec<Vec<usize>> {
        let m = self.snapshot();
        let b = Bodies::of(&m);
        b.ids()
            .map(|id| (0..m.len()).filter(|&j| b.contains(id, j)).collect())
            .collect()
    }

    /// The loop-closure residual of swept joints `(n, j, 2)` (`linkage_core::Bodies::
    /// closure_residual`): the largest change of a distance within one moving link.
    fn closure_residual(&self, joints: crate::args::F64Array3<'_>) -> PyResult<f64> {
        let m = self.snapshot();
        let rows = joint_rows("joints", &joints, m.len())?;
        Ok(Bodies::of(&m).closure_residual(rows))
    }

    /// The longest distance between two joints of one moving link in a pose `(j, 2)`.
    fn longest_link(&self, pose: crate::args::F64Array2<'_>) -> PyResult<f64> {
        let m = self.snapshot();
        let flat = pose
            .as_slice()
            .map_err(|_| linkage_error("pose must be a C-contiguous float64 array"))?;
        let rows: &[Vec2<f64>] = bytemuck::try_cast_slice(flat)
            .map_err(|e| linkage_error(format!("pose must be an aligned float64 array ({e})")))?;
        if rows.len() != m.len() {
            return Err(linkage_error(format!(
                "pose must have shape ({}, 2), got {} points",
                m.len(),
                rows.len()
            )));
        }
        Ok(Bodies::of(&m).longest_link(rows))
    }

    /// Kutzbach–Gruebler count: (links, lower pairs, higher pairs, degrees of freedom).
    fn mobility(&self) -> (usize, usize, usize, i64) {
        let m = Bodies::of(&self.snapshot()).mobility();
        (
            m.links,
            m.lower_pairs,
            m.higher_pairs,
            m.degrees_of_freedom(),
        )
    }

    /// Sweeps over `theta` (contiguous float64, 1-D). `omega`, `alpha`: None, one value, or one
    /// per angle. `column`: the one joint the per-joint outputs hold (None: every joint);
    /// `flags`: whether to return `margin`, `regular` and `gap`. Returns a dict of numpy arrays
    /// (per-joint ones shaped `(n, w, 2)` or `(n, w)`, `w` joints or 1).
    /// `pairs`: the body index pairs whose instant centres are asked for (None: every pair);
    /// `directions`: whether the directions of centres at infinity come with the centres.
    #[pyo3(signature = (theta, omega=None, alpha=None, velocity=false, acceleration=false,
                        instant_centres=false, curvature=false, column=None, flags=true,
                        pairs=None, directions=true))]
    #[allow(
        clippy::too_many_arguments,
        reason = "mirrors the keywords of Mechanism.sweep's outputs"
    )]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        theta: crate::args::F64Array1<'py>,
        omega: Option<crate::args::F64Array1<'py>>,
        alpha: Option<crate::args::F64Array1<'py>>,
        velocity: bool,
        acceleration: bool,
        instant_centres: bool,
        curvature: bool,
        column: Option<usize>,
        flags: bool,
        pairs: Option<Vec<[usize; 2]>>,
        directions: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let th = theta
            .as_slice()
            .map_err(|_| linkage_error("theta must be a contiguous float64 array"))?;
        finite("theta", th)?;
        let n = th.len();
        let (w, a) = (
            rate("omega", &omega, n, 0.0)?,
            rate("alpha", &alpha, n, 0.0)?,
        );
        // The program on arrays sized to it (the same bits at any capacity), copied under the
        // lock.
        let mech = Sweepable::of(&self.lock());
        // The bodies are counted only for every pair's centres (not on a plain sweep's path).
        let (j, nb) = mech.shape(instant_centres && pairs.is_none());
        let pairs = match pairs.as_deref() {
            None => Pairs::All,
            Some(p) => Pairs::Only(p),
        };
        let np = if instant_centres { pairs.count(nb) } else { 0 };
        let columns = match column {
            None => Columns::All,
            Some(c) if c < j => Columns::One(c),
            Some(c) => {
                return Err(linkage_error(format!(
                    "column {c} is not a joint (the mechanism has {j})"
                )))
            }
        };
        let width = columns.width(j);
        let rates = velocity || acceleration;
        // The total is checked first (a `MemoryError` naming it), then numpy allocates each
        // output (not zeroed: the core writes every element) and the core writes into it: no
        // copy, and pages are touched once.
        let (nu, wu, pu) = (n as u128, width as u128, np as u128);
        let on = |b: bool| u128::from(b);
        let floats = nu * wu * 2 * (1 + on(rates) + on(acceleration) + on(curvature))
            + nu * 2 * on(flags)
            + nu * pu * 2 * (on(instant_centres) + on(instant_centres && directions))
            + nu * wu * on(curvature);
        let what = || format!("sweep of {n} samples");
        memory::check(
            &what,
            memory::bytes_of::<f64>(floats) + (1 + on(flags)) * nu,
        )?;
        let points = |on: bool, cols: usize| -> PyResult<Option<Bound<'py, PyArray<f64, Ix3>>>> {
            on.then(|| memory::uninit(py, &what, &[n, cols, 2]))
                .transpose()
        };
        let joints = points(true, width)?.ok_or_else(|| linkage_error("internal error"))?;
        let valid = memory::uninit::<bool, Ix1>(py, &what, &[n])?;
        let flag = |on: bool| -> PyResult<_> {
            Ok(if on {
                Some((
                    memory::uninit::<f64, Ix1>(py, &what, &[n])?,
                    memory::uninit::<bool, Ix1>(py, &what, &[n])?,
                    memory::uninit::<f64, Ix1>(py, &what, &[n])?,
                ))
            } else {
                None
            })
        };
        let flag_arrays = flag(flags)?;
        let vel = points(rates, width)?;
        let acc = points(acceleration, width)?;
        let centres = points(instant_centres, np)?;
        let directions = points(instant_centres && directions, np)?;
        let curv_centres = points(curvature, width)?;
        let curv = curvature
            .then(|| memory::uninit::<f64, Ix2>(py, &what, &[n, width]))
            .transpose()?;
        {
            let out = SweepOutputs {
                columns,
                joints: fresh_points(&joints)?,
                valid: fresh(&valid)?,
                margin: flag_arrays.as_ref().map(|f| fresh(&f.0)).transpose()?,
                regular: flag_arrays.as_ref().map(|f| fresh(&f.1)).transpose()?,
                gap: flag_arrays.as_ref().map(|f| fresh(&f.2)).transpose()?,
                velocity: fresh_opt(&vel)?,
                acceleration: fresh_opt(&acc)?,
                pairs,
                centres: fresh_opt(&centres)?,
                centre_directions: fresh_opt(&directions)?,
                curvature_centres: fresh_opt(&curv_centres)?,
                curvature: curv.as_ref().map(fresh).transpose()?,
            };
            // Ctrl-C: the signal handler only sets a flag; the core calls `go_on` between
            // chunks of samples, which checks it.
            let mut stopped: Option<PyErr> = None;
            py.detach(|| {
                let mut go_on = || match Python::attach(|py| py.check_signals()) {
                    Ok(()) => true,
                    Err(e) => {
                        stopped = Some(e);
                        false
                    }
                };
                let simd = crate::simd::simd_level();
                match &mech {
                    Sweepable::S8(m) => sweep_isa(simd, m, th, (w, a), out, &mut go_on),
                    Sweepable::S16(m) => sweep_isa(simd, m, th, (w, a), out, &mut go_on),
                    Sweepable::S32(m) => linkage_core::sweep(m, th, w, a, out, &mut go_on),
                    Sweepable::S64(m) => linkage_core::sweep(m, th, w, a, out, &mut go_on),
                }
            })
            .map_err(to_py)?;
            if let Some(e) = stopped {
                return Err(e);
            }
        }
        let d = PyDict::new(py);
        d.set_item(pyo3::intern!(py, "joints"), joints)?;
        d.set_item(pyo3::intern!(py, "valid"), valid)?;
        if let Some((margin, regular, gap)) = flag_arrays {
            d.set_item(pyo3::intern!(py, "margin"), margin)?;
            d.set_item(pyo3::intern!(py, "regular"), regular)?;
            d.set_item(pyo3::intern!(py, "gap"), gap)?;
        }
        for (key, arr) in [
            (pyo3::intern!(py, "velocity"), vel),
            (pyo3::intern!(py, "acceleration"), acc),
            (pyo3::intern!(py, "instant_centres"), centres),
            (pyo3::intern!(py, "instant_centre_directions"), directions),
            (pyo3::intern!(py, "curvature_centres"), curv_centres),
        ] {
            if let Some(arr) = arr {
                d.set_item(key, arr)?;
            }
        }
        if let Some(k) = curv {
            d.set_item(pyo3::intern!(py, "curvature"), k)?;
        }
        Ok(d)
    }
}

/// Joints of a batch of sweeps, `(M, N, J, 2)`.
type Joints4<'py> = Bound<'py, PyArray<f64, numpy::ndarray::Ix4>>;

/// Sweeps mechanisms of one joint count over shared angles, positions only
/// (`linkage_core::sweep_mechanisms`): `(joints (M, N, J, 2), valid (M, N))`, the same bits for
/// any thread count.
#[pyfunction]
#[pyo3(signature = (mechanisms, theta, threads=1))]
pub fn sweep_mechanisms<'py>(
    py: Python<'py>,
    mechanisms: Vec<PyRef<'py, Mechanism>>,
    theta: crate::args::F64Array1<'py>,
    threads: usize,
) -> PyResult<(Joints4<'py>, Bound<'py, PyArray<bool, Ix2>>)> {
    let th = theta
        .as_slice()
        .map_err(|_| linkage_error("theta must be a contiguous float64 array"))?;
    finite("theta", th)?;
    let mechs: Vec<CoreMechanism<f64, CAPACITY>> =
        mechanisms.iter().map(|m| m.snapshot()).collect();
    let (m, n) = (mechs.len(), th.len());
    let j = mechs.first().map_or(0, |x| x.len());
    let what = || format!("sweep of {m} mechanisms × {n} angles");
    let floats = (m as u128) * (n as u128) * (j as u128) * 2;
    memory::check(
        &what,
        memory::bytes_of::<f64>(floats) * 2 + (m as u128) * (n as u128),
    )?;
    let joints = memory::uninit::<f64, numpy::ndarray::Ix4>(py, &what, &[m, n, j, 2])?;
    let valid = memory::uninit::<bool, Ix2>(py, &what, &[m, n])?;
    {
        let (jw, vw) = (fresh_points(&joints)?, fresh(&valid)?);
        let threads = threads.clamp(1, 256);
        py.detach(|| linkage_core::sweep_mechanisms(&mechs, th, threads, jw, vw))
            .map_err(to_py)?;
    }
    Ok((joints, valid))
}

/// [`linkage_core::sweep`] compiled again for AVX-512 and for AVX2 + FMA and chosen at run time
/// (as the fast uniform sweep, see `fourbar.rs`): the core poses blocks of samples with a
/// branch-free kernel (`held.rs`) that these builds vectorise wider. The arithmetic is the
/// same in every build, so are the bits. Only the small capacities (up to 16 joints: four-bars,
/// six-bars, Jansen's and Klann's legs) carry the extra builds.
fn sweep_isa<const N: usize>(
    simd: crate::simd::Simd,
    m: &CoreMechanism<f64, N>,
    theta: &[f64],
    (omega, alpha): (Rate<'_, f64>, Rate<'_, f64>),
    out: SweepOutputs<'_, f64>,
    go_on: &mut dyn FnMut() -> bool,
) -> Result<linkage_core::Swept, linkage_core::Error> {
    use crate::simd::Simd;
    match simd {
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => {
            #[allow(unsafe_code, reason = "calling a target_feature function")]
            // SAFETY: a `Simd` other than `Portable` comes only from `simd_level`, which checked
            // that the CPU has these features.
            unsafe {
                sweep_avx512(m, theta, omega, alpha, out, go_on)
            }
        }
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => {
            #[allow(unsafe_code, reason = "calling a target_feature function")]
            // SAFETY: as above.
            unsafe {
                sweep_avx2(m, theta, omega, alpha, out, go_on)
            }
        }
        _ => linkage_core::sweep(m, theta, omega, alpha, out, go_on),
    }
}

/// The sweep compiled with extra target features (each name is one instantiation).
macro_rules! sweep_with_features {
    ($($name:ident = $features:literal;)*) => {$(
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        fn $name<const N: usize>(
            m: &CoreMechanism<f64, N>,
            theta: &[f64],
            omega: Rate<'_, f64>,
            alpha: Rate<'_, f64>,
            out: SweepOutputs<'_, f64>,
            go_on: &mut dyn FnMut() -> bool,
        ) -> Result<linkage_core::Swept, linkage_core::Error> {
            linkage_core::sweep(m, theta, omega, alpha, out, go_on)
        }
    )*};
}

sweep_with_features! {
    sweep_avx512 = "avx512f,avx512dq,avx512vl,avx2,fma";
    sweep_avx2 = "avx2,fma";
}

/// A copy of a program at the least capacity of 8, 16, 32, 64 that holds it: a sweep's arrays
/// (tracker history, rate scratch) are sized to the linkage, not to [`CAPACITY`]. (On the
/// stack: boxing the small ones would cost an allocation per call.)
#[allow(
    clippy::large_enum_variant,
    reason = "lives on the stack for one call; boxing the small ones would allocate per call"
)]
enum Sweepable {
    S8(CoreMechanism<f64, 8>),
    S16(CoreMechanism<f64, 16>),
    S32(CoreMechanism<f64, 32>),
    S64(Box<CoreMechanism<f64, CAPACITY>>),
}

impl Sweepable {
    fn of(m: &CoreMechanism<f64, CAPACITY>) -> Self {
        // `resized` fails only for a program longer than the capacity asked for.
        if let Ok(s) = m.resized::<8>() {
            Sweepable::S8(s)
        } else if let Ok(s) = m.resized::<16>() {
            Sweepable::S16(s)
        } else if let Ok(s) = m.resized::<32>() {
            Sweepable::S32(s)
        } else {
            Sweepable::S64(Box::new(m.clone()))
        }
    }

    /// Joints and (when `bodies`, else 0) bodies, the ground included.
    fn shape(&self, bodies: bool) -> (usize, usize) {
        let (j, b) = match self {
            Sweepable::S8(m) => (m.len(), bodies.then(|| Bodies::of(m).count())),
            Sweepable::S16(m) => (m.len(), bodies.then(|| Bodies::of(m).count())),
            Sweepable::S32(m) => (m.len(), bodies.then(|| Bodies::of(m).count())),
            Sweepable::S64(m) => (m.len(), bodies.then(|| Bodies::of(m.as_ref()).count())),
        };
        (j, b.unwrap_or(0))
    }
}

/// A writeable numpy array's elements as a slice (the arrays here are made C-contiguous).
pub(crate) fn as_slice<'a, T: numpy::Element, D: numpy::ndarray::Dimension>(
    a: &'a mut PyReadwriteArray<'_, T, D>,
) -> PyResult<&'a mut [T]> {
    a.as_slice_mut()
        .map_err(|_| linkage_error("internal error: output not contiguous"))
}

/// One construction as the dict `Mechanism.constructions` describes.
fn construction<'py>(py: Python<'py>, c: &Construction<f64>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match *c {
        Construction::Fixed { at } => {
            d.set_item("kind", "fixed")?;
            d.set_item("at", (at.x, at.y))?;
        }
        Construction::Crank {
            centre,
            radius,
            phase,
        } => {
            d.set_item("kind", "crank")?;
            d.set_item("centre", centre)?;
            d.set_item("radius", radius)?;
            d.set_item("phase", phase)?;
        }
        Construction::Dyad { p1, p2, dyad, side } => {
            d.set_item("kind", "dyad")?;
            d.set_item("p1", p1)?;
            d.set_item("p2", p2)?;
            d.set_item("r1", dyad.r1)?;
            d.set_item("r2", dyad.r2)?;
            d.set_item("side", side.name())?;
        }
        Construction::Slider {
            pivot,
            origin,
            direction,
            slider,
            reach,
        } => {
            d.set_item("kind", "slider")?;
            d.set_item("pivot", pivot)?;
            d.set_item("r", slider.r)?;
            d.set_item("origin", origin)?;
            match direction {
                LineDirection::Fixed(u) => d.set_item("direction", ("fixed", u.x, u.y))?,
                LineDirection::Link { from, to, angle } => {
                    d.set_item("direction", ("link", from, to, angle))?
                }
            }
            d.set_item("reach", reach.name())?;
        }
        Construction::Point {
            from,
            to,
            along,
            left,
        } => {
            d.set_item("kind", "point")?;
            d.set_item("from", from)?;
            d.set_item("to", to)?;
            d.set_item("along", along)?;
            d.set_item("left", left)?;
        }
    }
    Ok(d)
}

/// Rows of `j` joints from a C-contiguous `(n, j, 2)` float64 array.
fn joint_rows<'a>(
    what: &str,
    a: &'a crate::args::F64Array3<'_>,
    j: usize,
) -> PyResult<&'a [Vec2<f64>]> {
    let shape = a.shape();
    if shape[1] != j || shape[2] != 2 {
        return Err(linkage_error(format!(
            "{what} must have shape (n, {j}, 2), got {shape:?}"
        )));
    }
    let flat = a
        .as_slice()
        .map_err(|_| linkage_error(format!("{what} must be a C-contiguous float64 array")))?;
    bytemuck::try_cast_slice(flat)
        .map_err(|e| linkage_error(format!("{what} must be an aligned float64 array ({e})")))
}

/// An array this call has just allocated, as a mutable slice, without numpy's borrow
/// tracking (a few hundred ns a call, which a one-sample sweep feels).
#[allow(
    clippy::mut_from_ref,
    reason = "the array is new and unseen: its data has no other reference (see SAFETY)"
)]
fn fresh<'a, T: numpy::Element, D: numpy::ndarray::Dimension>(
    a: &'a Bound<'_, PyArray<T, D>>,
) -> PyResult<&'a mut [T]> {
    #[allow(
        unsafe_code,
        reason = "numpy's slice of an array nobody else can see yet"
    )]
    // SAFETY: `a` was created by `memory::uninit` in this call (C-contiguous, owned by numpy
    // for the array's lifetime) and has not been returned to Python yet: no other reference
    // to its data exists, so one mutable slice of it is the only access while it lives.
    let s = unsafe { a.as_slice_mut() };
    s.map_err(|_| linkage_error("internal error: output not contiguous"))
}

/// [`fresh`] of a `(…, 2)` float64 array, as points.
fn fresh_points<'a, D: numpy::ndarray::Dimension>(
    a: &'a Bound<'_, PyArray<f64, D>>,
) -> PyResult<&'a mut [Vec2<f64>]> {
    bytemuck::try_cast_slice_mut(fresh(a)?)
        .map_err(|e| linkage_error(format!("internal error: output misaligned ({e})")))
}

/// [`fresh_points`] of an optional output.
fn fresh_opt<'a>(
    a: &'a Option<Bound<'_, PyArray<f64, Ix3>>>,
) -> PyResult<Option<&'a mut [Vec2<f64>]>> {
    a.as_ref().map(fresh_points).transpose()
}

/// A writeable `(…, 2)` float64 array as points.
pub(crate) fn as_points<'a, D: numpy::ndarray::Dimension>(
    a: &'a mut PyReadwriteArray<'_, f64, D>,
) -> PyResult<&'a mut [Vec2<f64>]> {
    bytemuck::try_cast_slice_mut(as_slice(a)?)
        .map_err(|e| linkage_error(format!("internal error: output misaligned ({e})")))
}

/// Adds the submodule `_core.mechanism` (the mechanism builder and its mobility (`linkage_core` `mechanism/`)).
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = crate::module::submodule(
        parent,
        "mechanism",
        "The mechanism builder and its mobility (`linkage_core` `mechanism/`).",
    )?;
    m.add_class::<crate::mechanism::Mechanism>()?;
    m.add_function(wrap_pyfunction!(
        crate::mechanism::bodies::degrees_of_freedom,
        &m
    )?)?;
    // Maximum joints of a mechanism built from Python.
    m.add("CAPACITY", crate::module::CAPACITY)?;
    // Below this assembly margin rates are NaN (`linkage_core::rate_margin`).
    m.add("RATE_MARGIN", linkage_core::rate_margin::<f64>())?;
    Ok(())
}
