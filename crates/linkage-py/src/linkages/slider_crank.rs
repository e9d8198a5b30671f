//! Mirrors `linkage_core::{slider_crank, slider_circuit}`: the offset slider-crank and its
//! circuit (see `linkage.SliderCrank` for the documented Python class).

use linkage_core::{InputRange, Reach, SliderCircuit, SliderCrank as CoreSliderCrank, Vec2};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::args::{choice, named, xy, Real, RealPair};
use crate::error::{linkage_error, to_py};
use crate::mechanism::Mechanism;
use crate::memory;
use crate::module::CAPACITY;

/// An offset slider-crank with a coupler point.
#[pyclass(module = "linkage._core", frozen)]
#[derive(Clone)]
pub struct SliderCrank {
    inner: CoreSliderCrank<f64>,
}

#[pymethods]
impl SliderCrank {
    #[new]
    #[allow(
        clippy::too_many_arguments,
        reason = "the Python constructor's arguments: pivot, line, two lengths, point, reach"
    )]
    fn new(
        o: RealPair,
        angle: Real,
        offset: Real,
        crank: Real,
        coupler: Real,
        point: RealPair,
        reach: &str,
    ) -> PyResult<Self> {
        let (o, point) = (xy(o), xy(point));
        let reach: Reach = choice(reach)?;
        CoreSliderCrank::new(
            Vec2::new(o.0, o.1),
            angle.0,
            offset.0,
            crank.0,
            coupler.0,
            point,
            reach,
        )
        .map(|inner| SliderCrank { inner })
        .map_err(to_py)
    }

    /// (ox, oy, angle, offset, crank, coupler, along, left, reach, gx, gy): `G` the line's point
    /// nearest `O`.
    #[allow(
        clippy::type_complexity,
        reason = "the Python tuple returned, spelled out where it is built"
    )]
    fn parameters(
        &self,
    ) -> (
        f64,
        f64,
        f64,
        f64,
        f64,
        f64,
        f64,
        f64,
        &'static str,
        f64,
        f64,
    ) {
        let f = &self.inner;
        let g = f.line_point();
        (
            f.o.x,
            f.o.y,
            f.angle,
            f.offset,
            f.crank,
            f.coupler,
            f.along,
            f.left,
            f.reach.name(),
            g.x,
            g.y,
        )
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

    /// Whether the rod is perpendicular to the line at one angle of a full turn.
    fn is_change_point(&self) -> bool {
        self.inner.is_change_point()
    }

    /// The transmission angle's distance from a toggle at each crank angle (NaN where it
    /// cannot assemble).
    fn transmission<'py>(
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
                    .map(|&t| f.pose(t).map_or(f64::NAN, |p| p.transmission)),
            )
        });
        Ok(PyArray1::from_vec(py, out))
    }

    /// The cognate (`SliderCrank::cognate`).
    fn cognate(&self) -> PyResult<SliderCrank> {
        let inner = self.inner.cognate().map_err(to_py)?;
        Ok(SliderCrank { inner })
    }

    /// The mechanism program (joints O, G, A, B, P).
    fn mechanism(&self) -> PyResult<Mechanism> {
        let m = self
            .inner
            .mechanism()
            .resized::<CAPACITY>()
            .map_err(to_py)?;
        Ok(Mechanism::from_core(m))
    }

    /// The circuit in `n` samples at `s = 2πk/(n − 1)` (the last repeats the first):
    /// (theta (n,), joints (n, 5, 2), margin sin μ (n,)), NaN where a sample does not assemble.
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
        Bound<'py, PyArray1<f64>>,
    )> {
        if n < 2 {
            return Err(linkage_error(format!("n must be at least 2, got {n}")));
        }
        let what = || format!("circuit of {n} samples");
        memory::check(&what, memory::bytes_of::<f64>(n as u128 * 12))?;
        let c = SliderCircuit::new(self.inner).map_err(to_py)?;
        let mut theta = memory::filled(&what, n, 0.0)?;
        let mut joints = memory::filled(&what, n * 10, f64::NAN)?;
        let mut margin = memory::filled(&what, n, f64::NAN)?;
        let j: &mut [Vec2<f64>] = bytemuck::try_cast_slice_mut(&mut joints)
            .map_err(|e| linkage_error(format!("internal error: {e}")))?;
        py.detach(|| c.sample(&mut theta, j, &mut margin))
            .map_err(to_py)?;
        let joints = PyArray1::from_vec(py, joints)
            .reshape([n, 5, 2])?
            .into_any();
        Ok((
            PyArray1::from_vec(py, theta),
            joints,
            PyArray1::from_vec(py, margin),
        ))
    }
}
