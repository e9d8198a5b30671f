//! Argument conversion with the package's exceptions: counts and indices that are negative or
//! too large raise `LinkageError` naming the argument (never `OverflowError`, never a silent
//! wrap), and a Python int too large for a float raises `LinkageError` too.

use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyAnyMethods;

use crate::error::{linkage_error, LinkageError};

/// The largest count or index accepted: numpy dimensions are signed 64-bit (`npy_intp`), so
/// nothing larger could ever be an array length.
pub const MAX_COUNT: u64 = i64::MAX as u64;

/// A short `repr` of `obj` for messages (long ints are cut in the middle).
fn short_repr(obj: &Bound<'_, PyAny>) -> String {
    let r = obj
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "<unprintable>".into());
    if r.chars().count() > 40 {
        let head: String = r.chars().take(18).collect();
        let tail: String = r.chars().skip(r.chars().count() - 18).collect();
        format!("{head}…{tail} ({} digits)", r.len())
    } else {
        r
    }
}

/// A non-negative integer argument (a count or an index) as `usize`.
///
/// Accepts Python ints and anything with `__index__` (numpy integers). Errors: `TypeError`
/// naming `name` for a non-integer; `LinkageError` naming `name` for a negative value or one
/// above `i64::MAX` (which no array length or index can reach).
pub fn count(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    let v: i128 = match obj.extract::<i128>() {
        Ok(v) => v,
        Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => {
            return Err(linkage_error(format!(
                "{name} = {} is too large (at most {MAX_COUNT})",
                short_repr(obj)
            )))
        }
        Err(e) if e.is_instance_of::<PyTypeError>(obj.py()) => {
            let ty = obj
                .get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_else(|_| "?".into());
            return Err(PyTypeError::new_err(format!(
                "{name} must be an integer, got {ty}"
            )));
        }
        Err(e) => return Err(e),
    };
    if v < 0 {
        return Err(linkage_error(format!("{name} must be ≥ 0, got {v}")));
    }
    if v > i128::from(MAX_COUNT) {
        return Err(linkage_error(format!(
            "{name} = {v} is too large (at most {MAX_COUNT})"
        )));
    }
    usize::try_from(v)
        .map_err(|_| linkage_error(format!("{name} = {v} does not fit this platform's usize")))
}

/// A non-negative integer argument that must also fit `u32` (gear tooth counts).
pub fn count_u32(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    let v = count(name, obj)?;
    u32::try_from(v)
        .map_err(|_| linkage_error(format!("{name} = {v} is too large (at most {})", u32::MAX)))
}

/// A float argument. Like `f64` extraction (ints, floats, `__float__`), but an int too large
/// for a float is a `LinkageError` rather than an `OverflowError`; pyo3 notes which argument.
#[derive(Clone, Copy, Debug)]
pub struct Real(pub f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Real {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> Result<Self, Self::Error> {
        match obj.extract::<f64>() {
            Ok(x) => Ok(Real(x)),
            Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => Err(linkage_error(format!(
                "{} is too large for a float",
                short_repr(&obj.to_owned())
            ))),
            Err(e) => Err(e),
        }
    }
}

/// A tuple (or other extractable value) whose extraction `ValueError`s — pyo3's "expected tuple
/// of length 2, but got tuple of length 4" — become `LinkageError`s, so only the package's
/// exceptions leave the extension.
#[derive(Clone, Copy, Debug)]
pub struct Strict<T>(pub T);

impl<'a, 'py, T> FromPyObject<'a, 'py> for Strict<T>
where
    T: FromPyObject<'a, 'py>,
{
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> Result<Self, Self::Error> {
        let py = obj.py();
        T::extract(obj).map(Strict).map_err(|e| {
            let e: PyErr = e.into();
            if e.is_instance_of::<PyValueError>(py) && !e.is_instance_of::<LinkageError>(py) {
                linkage_error(e.value(py).to_string())
            } else {
                e
            }
        })
    }
}

/// A pair of floats (a point).
pub type RealPair = Strict<(Real, Real)>;

/// `(x, y)` of a pair of floats.
pub fn xy(p: RealPair) -> (f64, f64) {
    (p.0 .0 .0, p.0 .1 .0)
}

/// Extractors for `#[pyo3(from_py_with = ...)]`, one per argument name, so the messages of
/// [`count`] name the argument.
pub mod named {
    use pyo3::prelude::*;

    macro_rules! counts {
        ($($f:ident = $name:literal;)*) => {$(
            #[doc = concat!("The count or index argument `", $name, "`.")]
            pub fn $f(obj: &Bound<'_, PyAny>) -> PyResult<usize> {
                super::count($name, obj)
            }
        )*};
    }

    counts! {
        n = "n";
        block = "block";
        threads = "threads";
        centre = "centre";
        p1 = "p1";
        p2 = "p2";
        pivot = "pivot";
        origin = "origin";
        from_ = "from_";
        to = "to";
        joint = "joint";
    }
}

/// A name of one of the core's string choices ([`linkage_core::Assembly`],
/// [`linkage_core::Side`]): parsed by the core's `FromStr`, so the names and the message
/// (`assembly must be 'open' or 'crossed', got "sideways"`) are defined once, there.
pub fn choice<T>(name: &str) -> PyResult<T>
where
    T: std::str::FromStr<Err = linkage_core::Error>,
{
    name.parse()
        .map_err(|e| linkage_error(format!("{e}, got {name:?}")))
}

/// [`Real`] for `#[pyo3(from_py_with = ...)]`, where a default must stay a plain literal.
pub fn real(obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    obj.extract::<Real>().map(|r| r.0)
}

/// Refuses a non-finite value of `values` with the message the Python layer gives
/// (`theta must be finite: theta[3] is nan`): the check is done here, once, rather than by
/// two numpy passes in Python (a few µs of a one-sample call).
pub fn finite(name: &str, values: &[f64]) -> PyResult<()> {
    // Chunks folded without early exit (a loop that vectorises), then the first bad one.
    let bad_chunk = values
        .chunks(256)
        .position(|c| !c.iter().fold(true, |ok, v| ok & v.is_finite()));
    let first = bad_chunk.and_then(|b| {
        let tail = values.get(b * 256..)?;
        tail.iter()
            .position(|v| !v.is_finite())
            .map(|k| b * 256 + k)
    });
    match first {
        None => Ok(()),
        Some(k) => {
            let v = values[k];
            let shown = if v.is_nan() {
                "nan"
            } else if v > 0.0 {
                "inf"
            } else {
                "-inf"
            };
            Err(linkage_error(format!(
                "{name} must be finite: {name}[{k}] is {shown}"
            )))
        }
    }
}

/// `e`'s message with its first letter in lower case, to follow a colon mid-sentence
/// (rust-numpy's borrow errors start with a capital).
pub fn mid_sentence(e: impl std::fmt::Display) -> String {
    let s = e.to_string();
    let mut chars = s.chars();
    match chars.next() {
        Some(first) => first.to_lowercase().chain(chars).collect(),
        None => s,
    }
}

/// The message for an `out` array that numpy holds unaligned: results are written in place,
/// so no copy can stand in for it.
pub const UNALIGNED_OUT: &str = "out is an unaligned float64 array (a view of a buffer at an \
     offset that is not a multiple of 8 bytes), which results cannot be written into: pass an \
     aligned array, e.g. np.empty_like(out)";

/// A float64 numpy array argument that the core can borrow as a slice: the caller's array when
/// numpy holds it aligned, else an aligned copy made once by numpy. An array viewing a byte
/// buffer at an odd offset (`np.frombuffer(b, dtype=np.float64, offset=1)`) is C-contiguous
/// but unaligned, and no Rust slice may point into it: it used to be refused as "not a
/// contiguous float64 array". Dereferences to the `PyReadonlyArray` it holds.
pub struct F64Array<'py, D: numpy::ndarray::Dimension>(numpy::PyReadonlyArray<'py, f64, D>);

/// A 1-D [`F64Array`].
pub type F64Array1<'py> = F64Array<'py, numpy::Ix1>;
/// A 2-D [`F64Array`].
pub type F64Array2<'py> = F64Array<'py, numpy::Ix2>;
/// A 3-D [`F64Array`].
pub type F64Array3<'py> = F64Array<'py, numpy::Ix3>;

impl<'py, D: numpy::ndarray::Dimension> std::ops::Deref for F64Array<'py, D> {
    type Target = numpy::PyReadonlyArray<'py, f64, D>;

    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl<'a, 'py, D: numpy::ndarray::Dimension + 'a> FromPyObject<'a, 'py> for F64Array<'py, D> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> Result<Self, Self::Error> {
        use numpy::PyUntypedArrayMethods;
        let array = obj.extract::<numpy::PyReadonlyArray<'py, f64, D>>()?;
        if array.is_aligned() {
            return Ok(F64Array(array));
        }
        // numpy's copy is aligned (and C-contiguous): one copy, read element by element by
        // numpy, which handles unaligned data.
        let copy = obj.call_method1("copy", ("C",))?;
        let copy = copy.extract::<numpy::PyReadonlyArray<'py, f64, D>>()?;
        if copy.is_aligned() {
            Ok(F64Array(copy))
        } else {
            Err(linkage_error(
                "an unaligned float64 array could not be copied aligned: pass np.array(a) instead",
            ))
        }
    }
}
