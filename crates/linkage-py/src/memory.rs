//! Output allocation that fails with `MemoryError` instead of aborting the process.
//!
//! Every output whose size comes from the caller is sized first (in `u128`, so the arithmetic
//! cannot overflow), checked against what the machine can hold at all (RAM + swap, read once
//! from `/proc/meminfo` where there is one), and then allocated with `try_reserve_exact`, so an
//! allocation the system refuses (an address-space limit, overcommit refusal) is a `MemoryError`
//! naming the size too. Rust's default allocation-failure handler (abort) is never reached from
//! these paths.

use std::sync::OnceLock;

use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;
use pyo3::types::PyInt;

/// Bytes `len` values of `T` take, without overflow.
pub fn bytes_of<T>(len: u128) -> u128 {
    len.saturating_mul(std::mem::size_of::<T>() as u128)
}

/// RAM + swap in bytes, if the platform says (Linux: `/proc/meminfo`).
fn machine_bytes() -> Option<u128> {
    static TOTAL: OnceLock<Option<u128>> = OnceLock::new();
    *TOTAL.get_or_init(|| {
        let text = std::fs::read_to_string("/proc/meminfo").ok()?;
        let field = |key: &str| -> Option<u128> {
            let line = text.lines().find(|l| l.starts_with(key))?;
            let kb: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kb * 1024)
        };
        Some(field("MemTotal:")? + field("SwapTotal:").unwrap_or(0))
    })
}

/// The binary units a size is worded in, largest first.
const UNITS: [(&str, u32); 5] = [
    ("EiB", 60),
    ("PiB", 50),
    ("TiB", 40),
    ("GiB", 30),
    ("MiB", 20),
];

/// A size as every `MemoryError` of the package words it: three significant digits in the
/// largest binary unit from MiB to EiB that fits, with the exact bytes; bytes alone below.
fn size_text(n: u128) -> String {
    for (unit, shift) in UNITS {
        let size = 1u128 << shift;
        if n >= size {
            return sized(n as f64 / size as f64, unit, n);
        }
    }
    format!("{n} bytes")
}

/// `v` (the size in `unit`, at least 1) to three significant digits, then the exact bytes.
fn sized(v: f64, unit: &str, exact: impl std::fmt::Display) -> String {
    // Python's `.3g` without exponent: no decimals from 100 up, one from 10, two below.
    let digits = if v >= 99.95 {
        0
    } else if v >= 9.995 {
        1
    } else {
        2
    };
    let text = format!("{v:.digits$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    format!("{text} {unit} ({exact} bytes)")
}

/// A size in bytes (any Python int) worded as every `MemoryError` words it
/// (`linkage._arrays` calls this: one wording, here).
#[pyfunction]
pub fn size_text_of(n: &Bound<'_, PyInt>) -> PyResult<String> {
    if let Ok(v) = n.extract::<u128>() {
        return Ok(size_text(v));
    }
    // Past u128 (Python's exact sizes get there: a product of huge counts) or negative: the
    // same wording from Python's int arithmetic (its true division is correctly rounded, as
    // `n as f64 / size as f64` is for a u128).
    for (unit, shift) in UNITS {
        let size = 1u128 << shift;
        if n.ge(size)? {
            let v: f64 = n.div(size)?.extract()?;
            return Ok(sized(v, unit, n.str()?));
        }
    }
    Ok(format!("{} bytes", n.str()?))
}

/// The `MemoryError` message for `what` needing `nbytes` where this process can hold `limit`.
#[pyfunction]
pub fn memory_message(
    what: &str,
    nbytes: &Bound<'_, PyInt>,
    limit: &Bound<'_, PyInt>,
) -> PyResult<String> {
    Ok(format!(
        "{what} needs {}, more than this process can hold ({})",
        size_text_of(nbytes)?,
        size_text_of(limit)?
    ))
}

/// `what needs X GiB (N bytes)` as a `MemoryError`, with the reason.
fn memory_error(what: &str, bytes: u128, why: &str) -> PyErr {
    PyMemoryError::new_err(format!("{what} needs {}{why}", size_text(bytes)))
}

/// Checks that `bytes` (the total an operation will allocate) can be held at all: it must fit
/// `isize` (Rust's and numpy's limit for one object) and the machine's RAM + swap.
pub fn check(what: &dyn Fn() -> String, bytes: u128) -> Result<(), PyErr> {
    if bytes > isize::MAX as u128 {
        return Err(memory_error(
            &what(),
            bytes,
            " (more than any address space)",
        ));
    }
    if let Some(total) = machine_bytes() {
        if bytes > total {
            return Err(memory_error(
                &what(),
                bytes,
                &format!(
                    " (this machine has {} of memory and swap)",
                    size_text(total)
                ),
            ));
        }
    }
    Ok(())
}

/// An empty vector with room for exactly `len` values, or `MemoryError` naming the size.
pub fn with_capacity<T>(what: &dyn Fn() -> String, len: usize) -> Result<Vec<T>, PyErr> {
    let bytes = bytes_of::<T>(len as u128);
    check(what, bytes)?;
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| memory_error(&what(), bytes, " (the allocation failed)"))?;
    Ok(v)
}

/// A vector of `len` copies of `value`, or `MemoryError` naming the size.
pub fn filled<T: Clone>(what: &dyn Fn() -> String, len: usize, value: T) -> Result<Vec<T>, PyErr> {
    let mut v = with_capacity(what, len)?;
    v.resize(len, value); // within the capacity: no reallocation
    Ok(v)
}

/// A new zero-filled numpy array of `shape` and element type `T`, made by numpy itself (so the
/// result owns numpy memory a sweep writes straight into), or `MemoryError` naming the size.
///
/// Call [`check`] on the total first; this then catches what only the allocation itself can
/// tell (an address-space limit): numpy's `MemoryError` is replaced by one naming `what`.
/// (`PyArray::zeros` would panic on that failure instead of raising.)
pub fn zeros<'py, T: numpy::Element, D: numpy::ndarray::Dimension>(
    py: pyo3::Python<'py>,
    what: &dyn Fn() -> String,
    shape: &[usize],
) -> Result<pyo3::Bound<'py, numpy::PyArray<T, D>>, PyErr> {
    allocate(py, what, shape, true)
}

/// As [`zeros`], but the elements are left as the allocator gives them: only for outputs the
/// core writes element by element before anyone reads them (a sweep writes every element of
/// every output slice; on an error the array is dropped unseen). Filling 17 MB of zeros that
/// are then overwritten cost 1–2 ns a sample of a fast sweep (measured), when numpy's memory
/// comes back from the heap rather than fresh from the system.
pub fn uninit<'py, T: numpy::Element, D: numpy::ndarray::Dimension>(
    py: pyo3::Python<'py>,
    what: &dyn Fn() -> String,
    shape: &[usize],
) -> Result<pyo3::Bound<'py, numpy::PyArray<T, D>>, PyErr> {
    allocate(py, what, shape, false)
}

fn allocate<'py, T: numpy::Element, D: numpy::ndarray::Dimension>(
    py: pyo3::Python<'py>,
    what: &dyn Fn() -> String,
    shape: &[usize],
    zeroed: bool,
) -> Result<pyo3::Bound<'py, numpy::PyArray<T, D>>, PyErr> {
    use numpy::npyffi::{npy_intp, PY_ARRAY_API};
    use numpy::PyArrayDescrMethods;
    use pyo3::prelude::*;
    let len = shape
        .iter()
        .fold(1u128, |a, &s| a.saturating_mul(s as u128));
    let bytes = bytes_of::<T>(len);
    let mut dims = [0 as npy_intp; 8];
    if shape.len() != D::NDIM.unwrap_or(shape.len()) || shape.len() > dims.len() {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "internal error: array rank",
        ));
    }
    for (d, &s) in dims.iter_mut().zip(shape) {
        // `check` has bounded the total by isize::MAX, so each extent fits npy_intp.
        *d = npy_intp::try_from(s).map_err(|_| memory_error(&what(), bytes, ""))?;
    }
    #[allow(
        unsafe_code,
        reason = "numpy's C API: rust-numpy has no safe call for an uninitialised array"
    )]
    // SAFETY: `dims` holds `shape.len()` extents; PyArray_Zeros/Empty steal the reference to the
    // descriptor `into_dtype_ptr` gives it, and returns a new reference or null with an
    // exception set. A non-null result is an array of element type `T` and rank `D`.
    let arr = unsafe {
        let nd = shape.len() as std::os::raw::c_int;
        let descr = T::get_dtype(py).into_dtype_ptr();
        let ptr = if zeroed {
            PY_ARRAY_API.PyArray_Zeros(py, nd, dims.as_mut_ptr(), descr, 0)
        } else {
            PY_ARRAY_API.PyArray_Empty(py, nd, dims.as_mut_ptr(), descr, 0)
        };
        Bound::from_owned_ptr_or_err(py, ptr)
            .map(|a| a.cast_into_unchecked::<numpy::PyArray<T, D>>())
    };
    arr.map_err(|e| {
        if e.is_instance_of::<PyMemoryError>(py) {
            memory_error(&what(), bytes, " (the allocation failed)")
        } else {
            e
        }
    })
}

#[cfg(test)]
mod tests {
    use super::size_text;

    #[test]
    fn sizes_read_as_the_python_package_writes_them() {
        // linkage._arrays._bytes: f"{n / size:.3g} {unit} ({n} bytes)".
        assert_eq!(
            size_text(160_000_000_000_000),
            "146 TiB (160000000000000 bytes)"
        );
        assert_eq!(size_text(3 << 30), "3 GiB (3221225472 bytes)");
        assert_eq!(size_text(25_276_502_016), "23.5 GiB (25276502016 bytes)");
        assert_eq!(size_text(1_610_612_736), "1.5 GiB (1610612736 bytes)");
        assert_eq!(size_text(384_000_000), "366 MiB (384000000 bytes)");
        assert_eq!(size_text(1000), "1000 bytes");
    }
}
