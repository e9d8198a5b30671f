"""Conversion and validation of array_like arguments (shared by every public entry point)."""

from __future__ import annotations

from numbers import Real
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError

Float1D = NDArray[np.float64]


def as_angles(value: Any, name: str = "theta") -> tuple[Float1D, bool]:
    """Return ``value`` as a contiguous 1-D float64 array, and whether it was a scalar.

    Zero-copy when ``value`` already is a contiguous float64 array. Integers are accepted and
    converted; booleans, complex numbers, strings and objects raise ``TypeError``; arrays of more
    than one dimension, empty-but-not-1-D input and non-finite values raise ``LinkageError``.
    """
    arr = _as_real_array(value, name)
    scalar = arr.ndim == 0
    if arr.ndim > 1:
        raise LinkageError(f"{name} must be a scalar or 1-D, got shape {arr.shape}")
    arr = np.ascontiguousarray(arr.reshape(-1), dtype=np.float64)
    _check_finite(arr, name)
    return arr, scalar


def as_rate(value: Any, name: str, n: int) -> Float1D | None:
    """A per-sample rate (omega, alpha): None, a scalar (length-1 array) or one value per angle."""
    if value is None:
        return None
    arr = _as_real_array(value, name)
    if arr.ndim > 1 or (arr.ndim == 1 and arr.shape[0] not in (1, n)):
        raise LinkageError(
            f"{name} must be a scalar or have one value per angle ({n}), got shape {arr.shape}"
        )
    arr = np.ascontiguousarray(arr.reshape(-1), dtype=np.float64)
    _check_finite(arr, name)
    return arr


def as_length(value: Any, name: str) -> float:
    """A positive finite length, as float."""
    x = as_real(value, name)
    if not (np.isfinite(x) and x > 0.0):
        raise LinkageError(f"{name} must be a positive finite length, got {x!r}")
    return x


def as_real(value: Any, name: str) -> float:
    """A real scalar (int or float, not bool), as float; finiteness is checked by the caller."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (Real, np.integer, np.floating)
    ):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    return float(value)


def as_finite(value: Any, name: str) -> float:
    """A finite real scalar, as float."""
    x = as_real(value, name)
    if not np.isfinite(x):
        raise LinkageError(f"{name} must be finite, got {x!r}")
    return x


def as_point(value: Any, name: str) -> tuple[float, float]:
    """A finite 2-D point given as a pair."""
    try:
        seq = tuple(value)
    except TypeError:
        raise TypeError(f"{name} must be a pair (x, y), got {type(value).__name__}") from None
    if len(seq) != 2:
        raise LinkageError(f"{name} must be a pair (x, y), got {len(seq)} values")
    return as_finite(seq[0], f"{name}[0]"), as_finite(seq[1], f"{name}[1]")


def _as_real_array(value: Any, name: str) -> NDArray[Any]:
    if value is None:
        raise TypeError(f"{name} must be a real number or array of them, got None")
    try:
        arr = np.asarray(value)
    except Exception as exc:  # ragged nested sequences and the like
        raise LinkageError(f"{name} could not be read as an array: {exc}") from None
    if arr.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got dtype {arr.dtype}")
    return arr


def _check_finite(arr: Float1D, name: str) -> None:
    bad = ~np.isfinite(arr)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise LinkageError(f"{name} must be finite: {name}[{k}] is {float(arr[k])}")
