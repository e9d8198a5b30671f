"""Conversion and validation of array_like arguments (shared by every public entry point)."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from numbers import Real
from typing import Any, Literal, TypeVar, cast, overload

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.choices import Assembly, Reach, Side, SweepMode

__all__ = [
    "C",
    "Float1D",
    "UnknownNameError",
    "as_angles",
    "as_choice",
    "as_count",
    "as_finite",
    "as_flag",
    "as_length",
    "as_point",
    "as_points",
    "as_rate",
    "as_real",
    "as_real_array",
    "assembly_named",
    "check_memory",
    "choices",
    "memory_limit",
    "one_of",
    "said",
    "side_of",
]

Float1D = NDArray[np.float64]
C = TypeVar("C", bound=str)


def as_angles(value: Any, name: str = "theta", finite: bool = True) -> tuple[Float1D, bool]:
    """Return ``value`` as a contiguous 1-D float64 array, and whether it was a scalar.

    Zero-copy when ``value`` already is a contiguous float64 array. Integers are accepted and
    converted; booleans, complex numbers, strings, objects and masked arrays with a masked value
    raise ``TypeError``; arrays of more
    than one dimension, empty-but-not-1-D input and (unless ``finite`` is False: the caller's
    extension checks them) non-finite values raise ``LinkageError``.
    """
    if (
        not finite
        and type(value) is np.ndarray
        and value.dtype == np.float64
        and value.ndim == 1
        and value.flags.c_contiguous
        and value.flags.aligned
    ):
        return value, False  # the common case, without the generic conversions
    arr = _as_real_array(value, name)
    scalar = arr.ndim == 0
    if arr.ndim > 1:
        raise LinkageError(f"{name} must be a scalar or 1-D, got shape {arr.shape}")
    arr = _contiguous(arr)
    if finite:
        _check_finite(arr, name)
    return arr, scalar


def as_rate(value: Any, name: str, n: int, finite: bool = True) -> Float1D | None:
    """Return a per-sample rate (omega, alpha): None, a scalar (length-1 array) or one per angle.

    Non-finite values are refused unless ``finite`` is False (the caller's extension checks them).
    """
    if value is None:
        return None
    arr = _as_real_array(value, name)
    if arr.ndim > 1 or (arr.ndim == 1 and arr.shape[0] not in (1, n)):
        raise LinkageError(
            f"{name} must be a scalar or have one value per angle ({n}), got shape {arr.shape}"
        )
    arr = _contiguous(arr)
    if finite:
        _check_finite(arr, name)
    return arr


def _contiguous(arr: NDArray[Any]) -> Float1D:
    """Return ``arr`` flat as an aligned C-contiguous float64 array (what the extension takes).

    Aligned too: an array unpickled from a buffer (Dask, pickle protocol 5) can be contiguous
    and not aligned, which ``np.ascontiguousarray`` would pass through.
    """
    return np.require(arr.reshape(-1), dtype=np.float64, requirements=["C", "A"])


def as_length(value: Any, name: str) -> float:
    """Return a positive finite length as float."""
    x = as_real(value, name)
    if not (np.isfinite(x) and x > 0.0):
        raise LinkageError(f"{name} must be a positive finite length, got {x!r}")
    return x


def as_real(value: Any, name: str) -> float:
    """Return a real scalar (int or float, not bool) as float; the caller checks finiteness.

    An integer (or fraction) too large for a float raises ``LinkageError``, not
    ``OverflowError``.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (Real, np.integer, np.floating)
    ):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    try:
        return float(value)
    except OverflowError:
        raise LinkageError(f"{name} is too large for a float: {_short(value)}") from None
    except (TypeError, ValueError, ArithmeticError) as exc:  # exotic Real subclasses
        raise TypeError(
            f"{name} must be a real number, got {type(value).__name__}: {exc}"
        ) from None


def as_finite(value: Any, name: str) -> float:
    """Return a finite real scalar as float."""
    x = as_real(value, name)
    if not np.isfinite(x):
        raise LinkageError(f"{name} must be finite, got {x!r}")
    return x


def as_point(value: Any, name: str) -> tuple[float, float]:
    """Return a finite 2-D point given as a pair."""
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a pair (x, y), got {type(value).__name__}")
    try:
        seq = tuple(value)
    except TypeError:
        raise TypeError(f"{name} must be a pair (x, y), got {type(value).__name__}") from None
    if len(seq) != 2:
        raise LinkageError(f"{name} must be a pair (x, y), got {len(seq)} values")
    return as_finite(seq[0], f"{name}[0]"), as_finite(seq[1], f"{name}[1]")


def as_points(value: Any, name: str) -> NDArray[np.float64]:
    """Return points shaped ``(..., 2)`` as a float64 array (not necessarily contiguous).

    Non-finite values are kept (they give NaN results).
    """
    arr = _as_real_array(value, name)
    if arr.ndim == 0 or arr.shape[-1] != 2:
        raise LinkageError(f"{name} must have shape (..., 2), got {arr.shape}")
    return np.asarray(arr, dtype=np.float64)


def as_count(value: Any, name: str, minimum: int = 1) -> int:
    """Return a count: an int (not bool) of at least ``minimum``.

    A count beyond what an index can hold (``sys.maxsize``) cannot be represented: ``LinkageError``.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an int, got {type(value).__name__}")
    v = int(value)
    if v < minimum:
        raise LinkageError(f"{name} must be an int ≥ {minimum}, got {v}")
    if v > sys.maxsize:
        raise LinkageError(f"{name} = {v} is too large to be represented (at most {sys.maxsize})")
    return v


def as_flag(value: Any, name: str) -> bool:
    """Return a yes/no argument (bool, numpy bool, or the ints 0 and 1) as bool."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)) and int(value) in (0, 1):
        return bool(value)
    raise TypeError(f"{name} must be True or False, got {_short(value)}")


@overload
def choices(kind: Literal["assembly"]) -> tuple[Assembly, ...]: ...
@overload
def choices(kind: Literal["side"]) -> tuple[Side, ...]: ...
@overload
def choices(kind: Literal["reach"]) -> tuple[Reach, ...]: ...
@overload
def choices(kind: Literal["mode"]) -> tuple[SweepMode, ...]: ...
@overload
def choices(kind: str) -> tuple[str, ...]: ...
def choices(kind: str) -> tuple[str, ...]:
    """Return the names of one of the core's string choices, in the core's order.

    ``kind`` is ``"assembly"``, ``"side"``, ``"reach"`` or ``"mode"``: the names are defined once,
    by the core's enums (``Assembly::NAMES`` …), and mirrored by the extension. Typed as the
    ``linkage._choices`` alias of the kind.

    >>> choices("assembly")
    ('open', 'crossed')
    """
    return tuple(_core.CHOICES[kind])


def side_of(assembly: Assembly) -> Side:
    """Return the dyad side (``"left"``/``"right"``) a four-bar's ``assembly`` puts ``B`` on.

    The core's rule (``Assembly::side``), mirrored by the extension.

    >>> side_of("open"), side_of("crossed")
    ('left', 'right')
    """
    return cast(Side, _core.ASSEMBLY_SIDES[assembly])


def assembly_named(crossed: bool) -> Assembly:
    """Return the name of the assembly whose crossed flag (the extension's) is ``crossed``.

    The core's ``Assembly::NAMES`` are in declaration order, ``Open`` then ``Crossed``.

    >>> assembly_named(False), assembly_named(True)
    ('open', 'crossed')
    """
    return choices("assembly")[1 if crossed else 0]


def one_of(kind: str) -> str:
    """Return the names of one of the core's string choices as a message says them.

    >>> one_of("mode")
    "'trig', 'table' or 'recurrence'"
    """
    return said(choices(kind))


def said(names: Sequence[str]) -> str:
    """Return ``names`` as a message says them: quoted, the last after "or".

    >>> said(("side", "top")), said(("only",))
    ("'side' or 'top'", "'only'")
    """
    quoted = [repr(n) for n in names]
    return f"{', '.join(quoted[:-1])} or {quoted[-1]}" if len(quoted) > 1 else quoted[0]


def as_choice(value: Any, name: str, allowed: tuple[C, ...]) -> C:
    """Return ``value`` if it is one of the names ``allowed``.

    A str that is not one of them is a ``LinkageError``, anything else a ``TypeError``.
    """
    if not isinstance(value, str):
        raise TypeError(f"{name} must be one of {allowed}, got {type(value).__name__}")
    if value not in allowed:
        raise LinkageError(f"{name} must be one of {', '.join(map(repr, allowed))}, got {value!r}")
    return value


def memory_limit() -> int:
    """Return the bytes this process can hold at most.

    That is physical memory, or the address-space limit (``RLIMIT_AS``) when one is set lower.
    """
    limit = 1 << 62
    try:
        limit = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, OSError, ValueError):  # pragma: no cover - not POSIX
        pass
    try:
        import resource  # noqa: PLC0415 (POSIX only)

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft != resource.RLIM_INFINITY and 0 < soft < limit:
            limit = soft
    except (ImportError, OSError, ValueError):  # pragma: no cover - not POSIX
        pass
    return int(limit)


def check_memory(nbytes: int, what: str) -> None:
    """Raise ``MemoryError`` naming the size when ``nbytes`` is more than this process can hold.

    ``nbytes`` is an exact int (no overflow); the limit is :func:`memory_limit`.
    """
    limit = memory_limit()
    if nbytes > limit:
        raise MemoryError(_core.memory_message(what, nbytes, limit))


def _bytes(n: int) -> str:
    """Word a size as every MemoryError does (the core's wording, ``_core.size_text_of``)."""
    return _core.size_text_of(n)


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


class UnknownNameError(LinkageError, KeyError):
    """A name (joint, link) that is not there: a ``LinkageError`` that is also a ``KeyError``."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


def as_real_array(value: Any, name: str) -> NDArray[Any]:
    """``value`` as an array of real numbers (int, uint or float dtype) of any shape.

    A masked array with a masked value raises ``TypeError`` (one without is taken as its data).

    >>> import numpy as np
    >>> as_real_array(np.ma.masked_array([1.0, 2.0, 3.0], mask=[0, 1, 0]), "theta")
    Traceback (most recent call last):
    ...
    TypeError: theta is a masked array with 1 masked value(s) (first at flat index 1): masked \
arrays are not taken: drop the masked values (.compressed() for 1-D) or choose theirs \
(.filled(value))
    """
    return _as_real_array(value, name)


def _as_real_array(value: Any, name: str) -> NDArray[Any]:
    if value is None:
        raise TypeError(f"{name} must be a real number or array of them, got None")
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must hold real numbers, got {type(value).__name__}")
    if isinstance(value, np.ma.MaskedArray):
        # np.asarray drops the mask and keeps the hidden values: they would be computed as if
        # valid. A masked value has no position to give, so it is refused, not guessed.
        mask = np.ma.getmaskarray(value)
        if mask.any():
            k = int(np.flatnonzero(mask)[0])
            where = "" if value.ndim == 0 else f" (first at flat index {k})"
            raise TypeError(
                f"{name} is a masked array with {int(mask.sum())} masked value(s){where}: "
                "masked arrays are not taken: drop the masked values (.compressed() for 1-D) "
                "or choose theirs (.filled(value))"
            )
        value = np.ma.getdata(value)
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError, OverflowError) as exc:  # ragged nested sequences and the like
        raise LinkageError(f"{name} could not be read as an array: {exc}") from None
    if arr.dtype.kind == "O":
        # None inside an object array would become NaN: name it rather than report a NaN.
        flat = arr.reshape(-1)
        missing = [k for k in range(flat.size) if flat[k] is None]
        if missing:
            where = "" if arr.ndim == 0 else f"[{missing[0]}]"
            raise TypeError(f"{name} must hold real numbers, got None at {name}{where}")
        # Python ints beyond 64 bits and the like: convert, or say why not.
        try:
            arr = arr.astype(np.float64)
        except OverflowError:
            raise LinkageError(f"{name} holds a number too large for a float") from None
        except (ValueError, TypeError):
            raise TypeError(f"{name} must hold real numbers, got dtype object") from None
    if arr.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got dtype {arr.dtype}")
    return arr


def _check_finite(arr: Float1D, name: str) -> None:
    bad = ~np.isfinite(arr)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise LinkageError(f"{name} must be finite: {name}[{k}] is {float(arr[k])}")


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"UnknownNameError": UnknownNameError}
for _cls in __test__.values():
    _cls.__module__ = "linkage._arrays"
