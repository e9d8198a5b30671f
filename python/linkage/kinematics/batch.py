"""Batches of four-bars swept over shared crank angles: the evaluator for synthesis and search.

>>> import numpy as np
>>> from linkage.batch import sweep_fourbars
>>> points, valid = sweep_fourbars(20, [10, 12], 25, 25, (50, 0), np.radians([0, 90, 180]))
>>> points.shape, valid.shape, bool(valid.all())
((2, 3, 2), (2, 3), True)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import (
    as_angles,
    as_count,
    as_real_array,
    assembly_named,
    choices,
    one_of,
)
from linkage._shared.choices import Assembly
from linkage.kinematics.mechanism import Mechanism

_ASSEMBLIES = choices("assembly")


def sweep_fourbars(
    ground: ArrayLike | None = None,
    crank: ArrayLike | None = None,
    coupler: ArrayLike | None = None,
    rocker: ArrayLike | None = None,
    point: ArrayLike = (0.0, 0.0),
    theta: ArrayLike | None = None,
    assembly: Assembly | Sequence[Assembly] | NDArray[np.str_] = "open",
    threads: int = 1,
    *,
    o: ArrayLike | None = None,
    c: ArrayLike | None = None,
    out: tuple[NDArray[np.float64], NDArray[np.bool_]] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Coupler points of ``M`` four-bars at ``N`` shared crank angles.

    Each linkage gives what ``FourBar(...).sweep(theta).point`` gives: the branch the tracked
    sweep follows (through flat positions of change-point linkages too), NaN where it cannot
    assemble, and the same points to rounding (within about 5e-16 of the linkage's size of the
    exact ones; the same bits next to a toggle). Linkages with no flat position among the swept
    angles (every linkage that is not a change point) take a branch-free closed form with one
    square root and one division a sample and ``sin``/``cos`` of each angle computed once for
    the whole batch; the others are tracked.

    Parameters
    ----------
    ground, crank, coupler, rocker : array_like
        Link lengths, scalars or shape ``(M,)``, broadcast together (shapely-style). ``ground``
        puts the rocker pivot at ``o + (ground, 0)``; give ``c`` instead for explicit pivots.
    point : array_like
        Coupler point ``(along, left)`` in coupler coordinates, shape ``(2,)`` or ``(M, 2)``.
    theta : array_like
        Crank angles in radians, scalar or shape ``(N,)``, in sweep order (any spacing).
    assembly : str or array_like of str
        ``"open"`` or ``"crossed"``, one for all or one per linkage.
    threads : int
        Threads the linkages are split over; the results are the same bits for any count.
    o, c : array_like, optional
        Crank and rocker pivots, shape ``(2,)`` or ``(M, 2)``; ``o`` defaults to the origin.
    out : (ndarray, ndarray), optional
        C-contiguous writeable float64 ``(M, N, 2)`` and bool ``(M, N)`` arrays that receive the
        results instead of new arrays (and are returned): a search that evaluates batch after
        batch saves allocating and first touching the output each time.

    Returns
    -------
    points : ndarray, shape (M, N, 2)
        Coupler points, NaN where a linkage cannot assemble.
    valid : ndarray of bool, shape (M, N)
        Whether each sample assembled.

    Raises
    ------
    LinkageError
        A length that is not positive and finite, coincident pivots, a non-finite angle or
        coordinate, shapes that do not broadcast, an unknown assembly; the message names the
        argument (and the linkage's index).
    TypeError
        A non-numeric argument, or neither ``ground`` nor ``c``.
    MemoryError
        When ``M·N`` samples do not fit in memory (the message gives the size).

    Examples
    --------
    A parallelogram swept through its flat position keeps its shape, like ``FourBar.sweep``:

    >>> import numpy as np
    >>> from linkage.batch import sweep_fourbars
    >>> p, ok = sweep_fourbars(3, 1, 3, 1, (1.5, 0.5), [2.0, np.pi, 4.0])
    >>> a = np.stack([np.cos([2.0, np.pi, 4.0]), np.sin([2.0, np.pi, 4.0])], axis=-1)
    >>> bool(np.allclose(p[0], a + (1.5, 0.5)))
    True

    Reusing the outputs:

    >>> buf = (np.empty((1, 3, 2)), np.empty((1, 3), dtype=bool))
    >>> p2, ok2 = sweep_fourbars(3, 1, 3, 1, (1.5, 0.5), [2.0, np.pi, 4.0], out=buf)
    >>> p2 is buf[0] and bool((p2 == p).all())
    True

    A linkage that cannot reach gives NaN, flagged:

    >>> p, ok = sweep_fourbars([20, 20], [10, 10], [25, 4], [25, 4], (0, 0), 0.0)
    >>> ok.tolist(), bool(np.isnan(p[1, 0]).all())
    ([[True], [False]], True)

    while a length that no linkage can have is an error naming the linkage:

    >>> sweep_fourbars(20, [10, -1], 25, 25, (0, 0), 0.0)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: crank[1] must be a positive finite length, got -1.0
    """
    if crank is None or coupler is None or rocker is None:
        raise TypeError("sweep_fourbars() needs crank, coupler and rocker lengths")
    if theta is None:
        raise TypeError("sweep_fourbars() needs theta (crank angles)")
    nthreads = as_count(threads, "threads")
    th, _ = as_angles(theta, "theta")
    lengths = {
        name: _real(value, name)
        for name, value in (("crank", crank), ("coupler", coupler), ("rocker", rocker))
    }
    pt = _pair(point, "point")
    po = _pair((0.0, 0.0) if o is None else o, "o")
    pc = None if c is None else _pair(c, "c")
    if pc is None:
        if ground is None:
            raise TypeError("sweep_fourbars() needs ground (or the rocker pivot c)")
        lengths["ground"] = _real(ground, "ground")
    elif ground is not None:
        raise LinkageError("give either ground or the rocker pivot c, not both")
    crossed = _assembly(assembly)
    m = _common_length(lengths, pt, po, pc, crossed)

    def flat(a: NDArray[Any], dtype: Any = np.float64) -> NDArray[Any]:
        return np.ascontiguousarray(np.broadcast_to(a, (m,)), dtype=dtype)

    def pts(a: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.ascontiguousarray(np.broadcast_to(a, (m, 2)), dtype=np.float64)

    # Each parameter broadcast once, checked, and passed on as it is.
    lens = {name: flat(v) for name, v in lengths.items()}
    for name in ("crank", "coupler", "rocker", "ground"):
        if name in lens:
            # A scalar given for all linkages is checked, and named, as the scalar.
            _check_lengths(lengths[name] if lengths[name].ndim == 0 else lens[name], name)
    pm, o_m = pts(pt), pts(po)
    c_given = None if pc is None else pts(pc)
    for name, arr in (("point", pm), ("o", o_m), ("c", c_given)):
        if arr is not None:
            _check_finite(arr, name)
    c_m = _rocker_pivots(lens, o_m, c_given)
    _check_out(out)
    points, valid = _core.linkages.sweep_four_bar_batch(
        o_m,
        c_m,
        lens["crank"],
        lens["coupler"],
        lens["rocker"],
        np.ascontiguousarray(pm[:, 0]),
        np.ascontiguousarray(pm[:, 1]),
        flat(crossed, np.bool_),
        th,
        nthreads,
        out,
    )
    return points, valid


def _check_out(out: Any) -> None:
    """Refuse an ``out=`` that is not a pair (float64 array, bool array)."""
    if out is not None and not (
        isinstance(out, tuple)
        and len(out) == 2
        and isinstance(out[0], np.ndarray)
        and out[0].dtype == np.float64
        and isinstance(out[1], np.ndarray)
        and out[1].dtype == np.bool_
    ):
        got = (
            ", ".join(f"{getattr(a, 'dtype', type(a).__name__)} {type(a).__name__}" for a in out)
            if isinstance(out, tuple)
            else type(out).__name__
        )
        raise TypeError(f"out must be a pair (float64 array, bool array), got ({got})")


def _common_length(
    lengths: dict[str, NDArray[np.float64]],
    pt: NDArray[np.float64],
    po: NDArray[np.float64],
    pc: NDArray[np.float64] | None,
    crossed: NDArray[Any],
) -> int:
    """Return ``M``, the one length every linkage parameter broadcasts to."""
    shapes = {k: v.shape for k, v in lengths.items()}
    shapes.update({"point": pt.shape[:-1], "o": po.shape[:-1], "assembly": crossed.shape})
    if pc is not None:
        shapes["c"] = pc.shape[:-1]
    try:
        (m,) = np.broadcast_shapes(*shapes.values(), (1,))
    except ValueError:
        described = ", ".join(f"{k} {s}" for k, s in shapes.items())
        raise LinkageError(
            f"the linkage parameters must broadcast to one shape (M,): {described}"
        ) from None
    return int(m)


def _rocker_pivots(
    lens: dict[str, NDArray[Any]], o_m: NDArray[np.float64], c_given: NDArray[np.float64] | None
) -> NDArray[np.float64]:
    """Return each linkage's rocker pivot: given, or ``ground`` along x from ``o`` (not on it)."""
    if c_given is None:
        g = lens["ground"]
        c_m = np.ascontiguousarray(o_m + np.stack([g, np.zeros_like(g)], axis=-1))
    else:
        c_m = c_given
        same = np.all(c_m == o_m, axis=-1)
        if same.any():
            k = int(np.flatnonzero(same)[0])
            raise LinkageError(f"o and c coincide (ground length 0) for linkage {k}")
    return c_m


def sweep_mechanisms(
    mechanisms: Sequence[Mechanism], theta: ArrayLike, threads: int = 1
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Every joint of ``M`` mechanisms of one joint count at ``N`` shared crank angles.

    Each row is what ``mechanisms[i].sweep(theta, outputs=("joints",))`` gives (the same
    branch tracking, the same bits); the mechanisms are split over ``threads`` threads, with the
    same bits for any count. The batch evaluator for families of multi-loop legs: build one
    :class:`~linkage.Mechanism` per parameter vector, sweep them all in one call.

    Parameters
    ----------
    mechanisms : sequence of Mechanism
        Mechanisms with the same number of joints (the same program with other numbers).
    theta : array_like
        Crank angles in radians, scalar or shape ``(N,)``, finite.
    threads : int
        Threads the mechanisms are split over (at most 256 are started).

    Returns
    -------
    joints : ndarray, shape (M, N, J, 2)
        Every joint, NaN where a sample does not assemble.
    valid : ndarray of bool, shape (M, N)
        Whether each sample assembled.

    Raises
    ------
    TypeError
        If an element of ``mechanisms`` is not a Mechanism.
    LinkageError
        For mechanisms of different joint counts, one without a crank, or non-finite angles.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.batch import sweep_mechanisms
    >>> legs = [linkage.FourBar(ground=20, crank=10, coupler=c, rocker=25).mechanism()
    ...         for c in (25, 28)]
    >>> joints, valid = sweep_mechanisms(legs, np.radians([0, 90]))
    >>> joints.shape, valid.tolist()
    ((2, 2, 5, 2), [[True, True], [True, True]])
    >>> sweep_mechanisms(legs + [linkage.catalog.jansen()], [0.0])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: joints of every mechanism of a batch must have length 5, got 8
    """
    ms = list(mechanisms)
    for k, m in enumerate(ms):
        if not isinstance(m, Mechanism):
            raise TypeError(f"mechanisms[{k}] must be a Mechanism, got {type(m).__name__}")
    th, _ = as_angles(theta, "theta")
    n = as_count(threads, "threads")
    joints, valid = _core.sweep.sweep_mechanisms([m._core for m in ms], th, n)
    return joints, valid


def _real(value: Any, name: str) -> NDArray[np.float64]:
    arr = np.asarray(as_real_array(value, name), dtype=np.float64)
    if arr.ndim > 1:
        raise LinkageError(f"{name} must be a scalar or 1-D, got shape {arr.shape}")
    return arr


def _pair(value: Any, name: str) -> NDArray[np.float64]:
    arr = np.asarray(as_real_array(value, name), dtype=np.float64)
    if arr.ndim not in (1, 2) or arr.shape[-1] != 2:
        raise LinkageError(f"{name} must have shape (2,) or (M, 2), got {arr.shape}")
    return arr


def _assembly(value: Any) -> NDArray[np.bool_]:
    if isinstance(value, str):
        values = np.asarray([value])
        shape: tuple[int, ...] = ()
    else:
        values = np.asarray(value)
        if values.ndim > 1 or values.dtype.kind not in "U":
            got = (
                f"{values.dtype} {values.shape}"
                if isinstance(value, np.ndarray)
                else f"{type(value).__name__} {value!r:.60}"
            )
            raise TypeError(
                f"assembly must be {one_of('assembly')} or a 1-D array of them, got {got}"
            )
        shape = values.shape
    bad = ~np.logical_or.reduce([values == a for a in _ASSEMBLIES])
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        where = "" if isinstance(value, str) else f"[{k}]"
        raise LinkageError(
            f"assembly{where} must be {one_of('assembly')}, got {str(values.reshape(-1)[k])!r}"
        )
    crossed: NDArray[np.bool_] = np.asarray(values == assembly_named(True), dtype=np.bool_).reshape(
        shape
    )
    return crossed


def _check_lengths(arr: NDArray[np.float64], name: str) -> None:
    # Two reductions with no temporaries (a NaN makes the minimum NaN, failing the test); only
    # a bad array is searched for the first bad length.
    if arr.size == 0 or (arr.min() > 0.0 and arr.max() < np.inf):
        return
    bad = ~(np.isfinite(arr) & (arr > 0.0))
    if arr.ndim == 0:
        raise LinkageError(f"{name} must be a positive finite length, got {float(arr)}")
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise LinkageError(f"{name}[{k}] must be a positive finite length, got {float(arr[k])}")


def _check_finite(arr: NDArray[np.float64], name: str) -> None:
    # One pass over the flat array; the reduction over the last axis of 2 (slow in numpy) only
    # for an array that holds a non-finite value.
    if np.isfinite(arr).all():
        return
    bad = ~np.isfinite(arr).all(axis=-1)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise LinkageError(f"{name}[{k}] must be finite, got {arr[k].tolist()}")


__all__ = ["sweep_fourbars", "sweep_mechanisms"]
