"""Precision-point synthesis: Burmester motion generation and Freudenstein function generation.

Every linkage returned is checked by sweeping it with the branch tracker through its precision
positions, and says whether it reaches them all on one circuit, in order, without a toggle
(``reaches``) — a candidate that would switch branch is flagged, never passed silently.

>>> import numpy as np, linkage
>>> from linkage.synthesis import motion
>>> fb = linkage.FourBar(ground=2, crank=0.7, coupler=1.9, rocker=1.6, point=(0.8, 0.6))
>>> s = fb.sweep([0.4, 1.3, 2.5])
>>> a, b = s.joints[:, 2], s.joints[:, 3]
>>> poses = np.column_stack([s.point, np.arctan2(*(b - a).T[::-1])])
>>> best = motion(poses, circle_points=[a[0], b[0]])[0]
>>> best.reaches, round(best.linkage.crank, 12), round(best.linkage.rocker, 12)
(True, 0.7, 1.6)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, SupportsFloat, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import (
    as_count,
    as_finite,
    as_point,
    as_real_array,
    assembly_named,
    check_memory,
    said,
)
from linkage._shared.choices import Spacing
from linkage._shared.size import rms_size
from linkage.kinematics.fourbar import FourBar

__all__ = [
    "Dyad",
    "FunctionGenerator",
    "MotionCandidate",
    "centre_point_curve",
    "chebyshev_points",
    "circle_point_curve",
    "function",
    "motion",
]

_DEFECTS = ("branch", "toggle", "order", "flat-position", "input-limit")


@dataclass(frozen=True)
class Dyad:
    """A revolute dyad of Burmester theory: its fixed pivot and its moving pivot.

    ``centre`` is the fixed pivot, ``circle`` the moving pivot where it lies at the first pose.
    """

    centre: tuple[float, float]
    circle: tuple[float, float]

    @property
    def radius(self) -> float:
        """Crank length ``|circle − centre|``."""
        return math.hypot(self.circle[0] - self.centre[0], self.circle[1] - self.centre[1])


Dyad.__module__ = "linkage._precision"  # as before the split: pickles and reprs name it so


@dataclass(frozen=True)
class MotionCandidate:
    """A four-bar that carries the body through the poses, with the check of its sweep.

    ``linkage`` is driven by ``crank`` (its pivot ``o``) with ``rocker`` (pivot ``c``); its
    coupler point is the body's reference point. ``reaches`` is True when turning the crank one
    way (``direction``: +1 counter-clockwise, −1 clockwise) carries the body through every pose
    in order on one circuit; else ``defect`` says why: ``"branch"`` (pose ``defect_pose`` is on
    the other assembly: a circuit defect), ``"toggle"`` (the crank meets an input limit on the
    way to pose ``defect_pose``), ``"order"`` (the poses come in another order) or
    ``"flat-position"`` (the motion passes a change-point linkage's flat position).
    ``crank_angles`` are the crank angles at the poses along the travel (NaN past a defect);
    ``position_error``/``angle_error`` the largest mismatch of the tracked sweep at the poses;
    ``min_transmission_angle`` the smallest transmission angle over the travel, folded to
    [0, π/2]. Those three are NaN when the candidate does not reach (``reaches`` False): a
    figure over the part of the travel before the defect (pose 0 alone, say) would read as a
    perfect linkage. ``longest_link`` is its longest link or coupler side. ``beta_pose``
    (four poses only, else None) is the pose ``k`` (1, 2 or 3) whose crank rotation from pose 0
    is the ``beta`` the dyads were found at: the crank turns by ``crank_angles[k] −
    crank_angles[0]`` (≡ ``beta`` mod 2π) from pose 0 to pose ``k``.
    """

    linkage: FourBar
    crank: Dyad
    rocker: Dyad
    reaches: bool
    defect: str | None
    defect_pose: int | None
    direction: int
    crank_angles: NDArray[np.float64]
    position_error: float
    angle_error: float
    min_transmission_angle: float
    grashof: str
    beta_pose: int | None = None

    @property
    def longest_link(self) -> float:
        """Return the longest link: ground, crank, coupler, rocker or a coupler side.

        The coupler's sides are those to the body's reference point (``|P − A|``, ``|P − B|``:
        the body must reach both moving pivots), as :func:`linkage.synthesis.longest_link`
        measures a path candidate.
        """
        return _longest_link(self.linkage)


MotionCandidate.__module__ = (
    "linkage._precision"  # as before the split: pickles and reprs name it so
)


def _longest_link(fb: FourBar) -> float:
    along, left = fb.point
    arms = (math.hypot(along, left), math.hypot(fb.coupler - along, left))
    return max(fb.ground, fb.crank, fb.coupler, fb.rocker, *arms)


# Default ``max_link`` of :func:`motion`: that of :func:`linkage.synthesis.path`
# (``linkage.synthesis.LONG_LINK``, which imports this module, so not importable here).
_LONG_LINK = 20.0

# Pose angles beyond this magnitude (radians) are legal but most likely degrees given by mistake.
_DEGREES_HINT = 2.0 * math.pi


@dataclass(frozen=True)
class FunctionGenerator:
    """A four-bar whose output angle follows ``y = f(x)`` (Freudenstein's equation).

    The input ``x`` maps linearly to the crank angle over ``crank_range`` and ``y`` to the
    rocker angle (from the ground line ``o → c``) over ``psi_range`` plus ``output_offset``
    (0, or π when the output link points opposite). ``structural_error`` is the largest
    ``|ψ(x) − ψ_desired(x)|`` over ``x`` (radians of output angle; ``structural_error_y`` in
    ``y`` units), from the tracked sweep; ``error`` its samples. ``precision_points`` holds the
    ``(x, y)`` pairs met, ``precision_angles`` their ``(φ, ψ)``. ``reaches`` / ``defect`` as for
    :class:`MotionCandidate` (``"branch"``, ``"input-limit"``, ``"flat-position"``).
    ``structural_error`` is NaN when the linkage does not reach the whole range: then
    ``x_reached`` is the part of ``[x0, x1]`` it follows from ``x0`` on (sampled, NaN when not
    even ``x0``) and ``structural_error_reached`` the largest error there (both the whole range
    and ``structural_error`` otherwise).
    """

    linkage: FourBar
    structural_error: float
    structural_error_y: float
    precision_points: NDArray[np.float64]
    precision_angles: NDArray[np.float64]
    k: tuple[float, float, float]
    crank_range: tuple[float, float]
    psi_range: tuple[float, float]
    output_offset: float
    x: NDArray[np.float64]
    error: NDArray[np.float64]
    reaches: bool
    defect: str | None
    min_transmission_angle: float
    grashof: str
    x_reached: tuple[float, float] = (math.nan, math.nan)
    structural_error_reached: float = math.nan


FunctionGenerator.__module__ = (
    "linkage._precision"  # as before the split: pickles and reprs name it so
)


def _poses(
    poses: Any, counts: Sequence[int], stacklevel: int = 3
) -> list[tuple[float, float, float]]:
    arr = np.asarray(as_real_array(poses, "poses"), dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise LinkageError(f"poses must have shape (k, 3) of (x, y, angle), got {arr.shape}")
    k = arr.shape[0]
    if k < min(counts):
        raise LinkageError(f"needs at least {min(counts)} poses, got {k}")
    if k not in counts:
        raise LinkageError(
            f"precision-point synthesis takes {' or '.join(map(str, counts))} poses, got {k}"
        )
    if not np.all(np.isfinite(arr)):
        raise LinkageError("poses must be finite")
    big = np.flatnonzero(np.abs(arr[:, 2]) > _DEGREES_HINT)
    if big.size:
        # A warning, not an error: an angle is legal modulo 2π (an unwrapped one may exceed it).
        i = int(big[0])
        warnings.warn(
            f"poses: {big.size} of {k} pose angles exceed 2π in magnitude (pose {i}: "
            f"{arr[i, 2]:g}): pose angles are radians. Degrees given by mistake? "
            "np.radians converts them",
            UserWarning,
            stacklevel=stacklevel,
        )
    return [(float(x), float(y), float(a)) for x, y, a in arr]


def _points(value: Any, name: str) -> NDArray[np.float64]:
    arr = np.asarray(as_real_array(value, name), dtype=np.float64)
    if arr.ndim == 1 and arr.shape == (2,):
        arr = arr.reshape(1, 2)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise LinkageError(f"{name} must have shape (m, 2), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise LinkageError(f"{name} must be finite")
    return arr


def _beta_pose(value: Any) -> int | None:
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"beta_pose must be an int (1, 2 or 3), got {type(value).__name__}")
    k = int(value)
    if k not in (1, 2, 3):
        raise LinkageError(
            f"beta_pose must be 1, 2 or 3 (the pose beta turns the crank to, from pose 0), got {k}"
        )
    return k


def _not_one_rotation(p: list[tuple[float, float, float]]) -> None:
    """Raise when the poses are rotations about one point: no four-bar guides them."""
    try:
        centre = _core.synthesis.burmester_common_pole(p)
    except LinkageError as exc:  # coincident poses: name the argument, not a chosen point
        raise LinkageError(f"poses: {exc}") from None
    if centre is not None:
        x, y = (f"{v:.6g}" for v in centre)
        raise LinkageError(
            f"the {len(p)} poses are rotations about one point, ({x}, {y}): every body point "
            f"moves on a circle about it, so every dyad's fixed pivot is that point and any two "
            f"dyads would share it (a ground link of length zero). One link pinned at ({x}, {y}) "
            "guides the body; a four-bar needs poses that also move that point"
        )


_CURVE_SAMPLE_BYTES = 128
"""Bytes per rotation sampled on the Burmester curves: the angle, two centre and two circle
points, and the core's working copies (16 float64)."""

_PAIR_BYTES = 3000
"""Bytes per ordered pair of dyads in :func:`motion`: the core's figures of the pair and its
candidate (measured: the process grew 3.2 kB per pair from n = 100 to 200)."""


def _rotations(n: Any) -> NDArray[np.float64]:
    """``n`` crank rotations evenly spaced over a turn, refused before allocating if too many."""
    count = as_count(n, "n")
    check_memory(count * _CURVE_SAMPLE_BYTES, f"n = {count} rotations on the Burmester curves")
    return 2.0 * np.pi * np.arange(count, dtype=np.float64) / count


def _curve(
    poses: Any, n: Any, beta_pose: Any
) -> tuple[int, NDArray[np.float64], NDArray[np.float64]]:
    p = _poses(poses, (4,), stacklevel=4)
    free_pose = _beta_pose(beta_pose)
    _not_one_rotation(p)
    beta = _rotations(n)
    free, centres, circles, _ = _core.synthesis.burmester_curve(p, beta, free_pose)
    return int(free), centres, circles


def centre_point_curve(
    poses: ArrayLike, n: int = 360, *, beta_pose: int | None = None
) -> NDArray[np.float64]:
    """Sample the centre-point (Burmester) curve of four poses: ``(2n, 2)``.

    The curve is parametrised by the crank's rotation ``β`` from pose 0 to pose ``beta_pose``
    (1, 2 or 3; by default the one that conditions the compatibility equation best, which
    :func:`motion` reports as ``beta_pose``), sampled at ``β = 2πi/n``; rows
    ``[0, n)`` hold the first solution at each ``β``, rows ``[n, 2n)`` the second, NaN where
    the curve has no real point at that ``β``. Plotting each half as a line gives the curve
    (NaN rows break it).

    Raises
    ------
    LinkageError
        Not 4 poses, non-finite or coincident poses, or poses without a Burmester curve (pure
        translations, rotations about one point).
    MemoryError
        ``n`` beyond what this process can hold (named, before anything is allocated).

    Examples
    --------
    >>> import numpy as np
    >>> from linkage import synthesis
    >>> poses = [(1.0, 1.1, 0.4), (0.3, 1.7, 0.3), (-0.6, 1.5, 0.5), (-1.0, 1.0, 0.9)]
    >>> cp = synthesis.centre_point_curve(poses, n=8)
    >>> cp.shape, np.flatnonzero(np.isnan(cp[:, 0]))  # rows where the curve has no real point
    ((16, 2), array([1, 8, 9]))
    >>> synthesis.centre_point_curve(poses[:3])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: needs at least 4 poses, got 3
    """
    _, centres, _ = _curve(poses, n, beta_pose)
    return np.concatenate([centres[:, 0], centres[:, 1]])


def circle_point_curve(
    poses: ArrayLike, n: int = 360, *, beta_pose: int | None = None
) -> NDArray[np.float64]:
    """Sample the circle-point curve of four poses (the moving pivots where they lie at pose 0).

    Sampled as :func:`centre_point_curve` (same ``n`` and ``beta_pose``): row ``i`` pairs with
    row ``i`` of that curve.

    Examples
    --------
    >>> import numpy as np
    >>> from linkage import synthesis
    >>> slide = [(0, 0, 0), (1, 0, 0), (2, 1, 0), (3, 0, 0)]  # translations only
    >>> synthesis.circle_point_curve(slide)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: degenerate synthesis: the four poses have no Burmester curve: ...
    """
    _, _, circles = _curve(poses, n, beta_pose)
    return np.concatenate([circles[:, 0], circles[:, 1]])


def _dyads_three(
    p: list[tuple[float, float, float]], circle_points: Any, centre_points: Any
) -> tuple[list[Dyad], list[str]]:
    dyads: list[Dyad] = []
    names: list[str] = []
    if circle_points is not None:
        for i, (x, y) in enumerate(_points(circle_points, "circle_points")):
            try:
                g = _core.synthesis.burmester_centre_point(p, (float(x), float(y)))
            except LinkageError as exc:
                raise LinkageError(f"circle_points[{i}]: {exc}") from None
            dyads.append(Dyad(centre=(g[0], g[1]), circle=(float(x), float(y))))
            names.append(f"circle_points[{i}]")
    if centre_points is not None:
        for i, (x, y) in enumerate(_points(centre_points, "centre_points")):
            try:
                k = _core.synthesis.burmester_circle_point(p, (float(x), float(y)))
            except LinkageError as exc:
                raise LinkageError(f"centre_points[{i}]: {exc}") from None
            dyads.append(Dyad(centre=(float(x), float(y)), circle=(k[0], k[1])))
            names.append(f"centre_points[{i}]")
    return dyads, names


def _dyads_four(
    p: list[tuple[float, float, float]], beta: Any, n: Any, beta_pose: int | None
) -> tuple[list[Dyad], int]:
    if beta is None:
        b = _rotations(n)
    else:
        b = np.ascontiguousarray(np.atleast_1d(as_real_array(beta, "beta")), dtype=np.float64)
        if b.ndim != 1 or not np.all(np.isfinite(b)):
            raise LinkageError("beta must be finite angles, a scalar or 1-D")
    free, centres, circles, _ = _core.synthesis.burmester_curve(p, b, beta_pose)
    out = []
    for g, k in zip(centres.reshape(-1, 2), circles.reshape(-1, 2)):
        if np.all(np.isfinite(g)) and np.all(np.isfinite(k)):
            out.append(Dyad(centre=(float(g[0]), float(g[1])), circle=(float(k[0]), float(k[1]))))
    if len(out) < 2:
        # Not "too few dyads" alone: say why, the curves' gaps at the rotations asked for.
        at = (
            f"beta = {', '.join(f'{math.degrees(x):.6g}°' for x in b[:4])}"
            f"{', ...' if b.size > 4 else ''}"
            if beta is not None
            else f"the n = {b.size} rotations sampled"
        )
        raise LinkageError(
            f"the Burmester curves have {'no real point' if not out else 'one real point only'} "
            f"at {at} (the crank's rotation from pose 0 to pose {int(free)}): a four-bar needs "
            "two dyads. centre_point_curve(poses, beta_pose=...) shows where the curves are real"
        )
    return out, int(free)


def _placed(q: Sequence[float]) -> FourBar:
    """Return the four-bar of the extension's placed parameters.

    ``q`` is ``[ox, oy, cx, cy, crank, coupler, rocker, along, left, crossed]``.
    """
    return FourBar(
        crank=q[4],
        coupler=q[5],
        rocker=q[6],
        point=(q[7], q[8]),
        assembly=assembly_named(bool(q[9])),
        o=(q[0], q[1]),
        c=(q[2], q[3]),
    )


def motion(
    poses: ArrayLike,
    *,
    circle_points: ArrayLike | None = None,
    centre_points: ArrayLike | None = None,
    beta: ArrayLike | None = None,
    n: int = 36,
    beta_pose: int | None = None,
    top: int | None = None,
    lengths: tuple[float, float] | None = None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None = None,
    max_link: float | None = _LONG_LINK,
) -> list[MotionCandidate]:
    """Four-bars that carry a body through 3 or 4 poses (Burmester motion generation).

    Parameters
    ----------
    poses : array_like (k, 3)
        ``(x, y, angle)`` of the body's reference point and angle (radians), k = 3 or 4. The
        reference point becomes the coupler point.
    circle_points, centre_points : array_like (m, 2), three poses only
        Moving pivots (where they lie at pose 0) and/or fixed pivots of the dyads wanted: each
        gives one dyad (its centre point is the circumcentre of its three positions; a centre
        point's circle point comes by kinematic inversion). At least two dyads in all.
    beta, n : four poses only
        The dyads at crank rotations ``beta`` along the Burmester curve (see
        :func:`centre_point_curve`), or at ``n`` rotations evenly spaced over a turn.
    beta_pose : {1, 2, 3}, optional, four poses only
        The pose that ``beta`` is the crank's rotation to, from pose 0. By default the one that
        conditions the compatibility equation best; either way each candidate reports it as
        ``beta_pose``. To ask for "the crank that turns 40° from pose 0 to pose 1", give
        ``beta=np.radians(40), beta_pose=1``.
    top : int, optional
        Return only the first ``top`` candidates.
    lengths : (least, greatest), optional
        Keep only the candidates whose ground, crank, coupler and rocker lengths are all within
        ``[least, greatest]`` and whose coupler sides to the body's reference point are at most
        ``greatest`` (as :func:`linkage.synthesis.path` filters).
    pivots : ((xmin, ymin), (xmax, ymax)), optional
        Keep only the candidates with both fixed pivots inside this box.
    max_link : float or None
        Candidates whose :attr:`MotionCandidate.longest_link` is longer than ``max_link`` times
        the task's size (:func:`linkage.synthesis.target_size` of the poses' points: their RMS
        distance from their centroid) rank after the others that reach (default 20, as for
        :func:`linkage.synthesis.path`: a pose set a few centimetres across met by links of
        metres is no design). Not removed; ``None`` ranks by reach and transmission alone, and
        it is ignored when ``lengths`` is given (that filters instead). A small value (2 or 3)
        puts the compact designs first; ``longest_link`` says how long each is.

    Returns
    -------
    list of MotionCandidate
        One per ordered pair of distinct dyads (first drives) that makes a four-bar and passes
        the filters: those that reach every pose on one circuit in order first (by
        ``max_link``, then largest smallest transmission angle), then the others, those
        reaching more poses first. The list is empty when the filters remove every candidate,
        with a ``UserWarning`` that counts what each filter removed.

    Raises
    ------
    LinkageError
        Bad poses (shape, count, NaN, coincident), poses that are rotations about one point
        (every dyad's fixed pivot is that point, so no two make a four-bar), a chosen point
        whose dyad is degenerate (its centre at infinity or not unique), poses without a
        Burmester curve, fewer than two dyads (for four poses: the curves have no real point
        at the ``beta`` given), dyads no two of which make a four-bar, or bad ``lengths``,
        ``pivots`` or ``max_link``.
    TypeError
        Points chosen for four poses, or ``beta`` / ``beta_pose`` for three.
    MemoryError
        ``n`` rotations, or the ordered pairs of the dyads (their number squared: about 3 kB
        each), beyond what this process can hold; nothing is allocated first.

    Warns
    -----
    UserWarning
        A pose angle beyond 2π in magnitude: legal, but most likely degrees given by mistake.

    Examples
    --------
    Three poses of a known four-bar's coupler, with its moving pivots chosen:

    >>> import numpy as np, linkage
    >>> from linkage import synthesis
    >>> fb = linkage.FourBar(ground=2, crank=0.7, coupler=1.9, rocker=1.6, point=(0.8, 0.6))
    >>> s = fb.sweep([0.4, 1.3, 2.5, 3.2])
    >>> a, b = s.joints[:, 2], s.joints[:, 3]
    >>> poses = np.column_stack([s.point, np.arctan2(*(b - a).T[::-1])])  # (x, y, angle)
    >>> found = synthesis.motion(poses[:3], circle_points=[a[0], b[0]])
    >>> [(c.reaches, c.defect) for c in found]
    [(True, None), (False, 'branch')]
    >>> synthesis.motion(poses[:3])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: three poses leave two free choices per dyad: give circle_points= ...
    """
    p = _poses(poses, (3, 4))
    box = _box(pivots)
    span = None if lengths is None else _span(lengths)
    if max_link is not None:
        max_link = as_finite(max_link, "max_link")
        if max_link <= 0:
            raise LinkageError(f"max_link must be positive, got {max_link}")
    dyads, names, free = _motion_dyads(p, circle_points, centre_points, beta, n, beta_pose)
    pairs, r = _pairs_solved(p, dyads, names)
    count = None if top is None else as_count(top, "top")
    out, removed = _motion_candidates(p, dyads, pairs, r, span, box, free)
    if max_link is None or span is not None:
        limit = math.inf
    else:
        limit = max_link * rms_size(np.array([xy[:2] for xy in p]))

    def rank(c: MotionCandidate) -> tuple[bool, bool, float]:
        if c.reaches:
            return (False, c.longest_link > limit, -c.min_transmission_angle)
        # Not reaching: those that get further first (their figures are NaN).
        return (True, False, -float(np.count_nonzero(np.isfinite(c.crank_angles))))

    out.sort(key=rank)
    if not out:
        # An empty list says which filter emptied it (a candidate may fail both).
        told = ", ".join(f"{k} {n}" for k, n in removed.items() if n)
        warnings.warn(
            f"motion: the filters removed all {int(np.count_nonzero(r['ok']))} four-bars "
            f"(removed by {told}): loosen them",
            stacklevel=2,
        )
    return out if count is None else out[:count]


def _motion_dyads(
    p: list[tuple[float, float, float]],
    circle_points: ArrayLike | None,
    centre_points: ArrayLike | None,
    beta: ArrayLike | None,
    n: int,
    beta_pose: int | None,
) -> tuple[list[Dyad], list[str], int | None]:
    """Return :func:`motion`'s dyads, their names in messages, and the free pose (four poses)."""
    free: int | None = None
    if len(p) == 3:
        if beta is not None or beta_pose is not None:
            name = "beta" if beta is not None else "beta_pose"
            raise TypeError(f"{name} applies to four poses; three take circle_points/centre_points")
        # Coincident poses first: "give circle_points=" would not help them.
        _not_one_rotation(p)
        if circle_points is None and centre_points is None:
            raise LinkageError(
                "three poses leave two free choices per dyad: give circle_points= and/or "
                "centre_points= (at least two dyads)"
            )
        dyads, names = _dyads_three(p, circle_points, centre_points)
    else:
        if circle_points is not None or centre_points is not None:
            raise TypeError(
                "four poses fix the dyads to the Burmester curves: choose them by beta= or n="
            )
        free_pose = _beta_pose(beta_pose)
        _not_one_rotation(p)
        dyads, free = _dyads_four(p, beta, n, free_pose)
        names = [f"dyad {i}" for i in range(len(dyads))]
    return dyads, names, free


def _pairs_solved(
    p: list[tuple[float, float, float]], dyads: list[Dyad], names: list[str]
) -> tuple[list[tuple[int, int]], Any]:
    """Return every ordered pair of ``dyads`` and the core's four-bars of them (arrays by name)."""
    if len(dyads) < 2:
        raise LinkageError(f"needs at least 2 dyads to make a four-bar, got {len(dyads)}")
    # Every ordered pair is a candidate: the cost grows as the square of the dyads.
    check_memory(
        len(dyads) * (len(dyads) - 1) * _PAIR_BYTES,
        f"the {len(dyads) * (len(dyads) - 1)} ordered pairs of {len(dyads)} dyads",
    )
    pairs = [(i, j) for i in range(len(dyads)) for j in range(len(dyads)) if i != j]
    row = [[*dyads[i].centre, *dyads[i].circle] for i, _ in pairs]
    crank = np.ascontiguousarray(row, dtype=np.float64).reshape(-1, 4)
    row = [[*dyads[j].centre, *dyads[j].circle] for _, j in pairs]
    rocker = np.ascontiguousarray(row, dtype=np.float64).reshape(-1, 4)
    r = _core.synthesis.motion_candidates(p, crank, rocker)
    if not np.any(r["ok"]):
        i, j = pairs[0]
        raise LinkageError(
            f"no two of the {len(dyads)} dyads make a four-bar: {names[i]} driving {names[j]}: "
            f"{r['error'][0]}"
        )
    return pairs, r


def _motion_candidates(
    p: list[tuple[float, float, float]],
    dyads: list[Dyad],
    pairs: list[tuple[int, int]],
    r: Any,
    span: tuple[float, float] | None,
    box: Any,
    free: int | None,
) -> tuple[list[MotionCandidate], dict[str, int]]:
    """Return the four-bars of ``pairs`` within ``span`` and ``box``, and how many each removed."""
    out = []
    removed = {"lengths": 0, "pivots": 0}
    for m, (i, j) in enumerate(pairs):
        if not r["ok"][m]:
            continue
        q = r["params"][m]
        fb = _placed(q)
        if not _meets(fb, span, box):
            removed["lengths"] += not _meets(fb, span, None)
            removed["pivots"] += not _meets(fb, None, box)
            continue
        code = int(r["defect"][m])
        pose = int(r["defect_pose"][m])
        reaches = code < 0
        # Figures over the poses reached only would make a failed candidate look perfect.
        mismatch, tilt, mu = (
            (float(r[k][m]) for k in ("position_error", "angle_error", "min_transmission"))
            if reaches
            else (math.nan,) * 3
        )
        out.append(
            MotionCandidate(
                linkage=fb,
                crank=dyads[i],
                rocker=dyads[j],
                reaches=reaches,
                defect=None if reaches else _DEFECTS[code],
                defect_pose=None if pose < 0 else pose,
                direction=int(r["direction"][m]),
                crank_angles=np.array(r["crank_angles"][m][: len(p)]),
                position_error=mismatch,
                angle_error=tilt,
                min_transmission_angle=mu,
                grashof=str(r["grashof"][m]),
                beta_pose=free,
            )
        )
    return out, removed


def _span(value: Any) -> tuple[float, float]:
    if isinstance(value, (str, bytes)) or np.ndim(value) != 1:
        raise TypeError(f"lengths must be a pair (least, greatest), got {type(value).__name__}")
    if len(value) != 2:
        raise LinkageError(f"lengths must be a pair (least, greatest), got {len(value)} values")
    least, greatest = as_finite(value[0], "lengths[0]"), as_finite(value[1], "lengths[1]")
    if not 0 < least < greatest:
        raise LinkageError(
            f"lengths must be (least, greatest) with 0 < least < greatest, got {value}"
        )
    return least, greatest


def _box(value: Any) -> tuple[tuple[float, float], tuple[float, float]] | None:
    if value is None:
        return None
    if isinstance(value, (str, bytes)) or np.ndim(value) == 0 or len(value) != 2:
        raise TypeError("pivots must be ((xmin, ymin), (xmax, ymax))")
    (x0, y0), (x1, y1) = as_point(value[0], "pivots[0]"), as_point(value[1], "pivots[1]")
    if not (x0 < x1 and y0 < y1):
        raise LinkageError(f"pivots must be ((xmin, ymin), (xmax, ymax)), got {value}")
    return (x0, y0), (x1, y1)


def _meets(
    fb: FourBar,
    span: tuple[float, float] | None,
    box: tuple[tuple[float, float], tuple[float, float]] | None,
) -> bool:
    """Whether ``fb`` passes the ``lengths`` and ``pivots`` filters of :func:`motion`."""
    if span is not None:
        least, greatest = span
        if not all(least <= v <= greatest for v in (fb.ground, fb.crank, fb.coupler, fb.rocker)):
            return False
        if _longest_link(fb) > greatest:  # the coupler's sides to the reference point
            return False
    if box is not None:
        (x0, y0), (x1, y1) = box
        if not all(x0 <= x <= x1 and y0 <= y <= y1 for x, y in (fb.o, fb.c)):
            return False
    return True


def chebyshev_points(x0: float, x1: float, n: int) -> NDArray[np.float64]:
    """Return ``n`` Chebyshev precision points on ``[x0, x1]``, increasing.

    ``(x0 + x1)/2 − (x1 − x0)/2 · cos((2j + 1)π / 2n)``.

    >>> from linkage.synthesis import chebyshev_points
    >>> chebyshev_points(0.0, 1.0, 3).round(6)
    array([0.066987, 0.5     , 0.933013])
    """
    a, b = as_finite(x0, "x0"), as_finite(x1, "x1")
    pts: NDArray[np.float64] = _core.synthesis.chebyshev_points(a, b, as_count(n, "n"))
    return pts


def _pair(value: Any, name: str) -> tuple[float, float]:
    if isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, np.ndarray)):
        raise TypeError(f"{name} must be a pair (start, end), got {type(value).__name__}")
    if len(value) != 2:
        raise LinkageError(f"{name} must be a pair (start, end), got {len(value)} values")
    a, b = as_finite(value[0], f"{name}[0]"), as_finite(value[1], f"{name}[1]")
    if a == b:
        raise LinkageError(f"{name} must have distinct ends, got {a} twice")
    return a, b


def _call(f: Callable[[float], Any], x: float) -> float:
    try:
        y = f(x)
    except (ValueError, ArithmeticError) as exc:  # e.g. math.sqrt outside its domain
        raise LinkageError(f"f({x}) failed: {type(exc).__name__}: {exc}") from exc
    try:
        v = float(y)
    except (TypeError, ValueError):
        raise TypeError(f"f({x}) must be a real number, got {type(y).__name__}") from None
    if not math.isfinite(v):
        raise LinkageError(f"f({x}) = {v} is not finite")
    return v


# What function() holds per precision point (x, y, φ, ψ and the two (m, 2) arrays returned, plus
# a temporary of the linear maps) and per check sample (x, y, φ, the output, the error, and
# temporaries), in bytes: the memory check's estimate.
_BYTES_PER_POINT = 8 * 10
_BYTES_PER_SAMPLE = 8 * 8


def _values(f: Callable[[float], Any], xs: NDArray[np.float64]) -> NDArray[np.float64]:
    """``f`` at each of ``xs``, written straight into one float64 array (no list of floats)."""
    return np.fromiter((_call(f, float(x)) for x in xs), dtype=np.float64, count=xs.size)


def _distinct(xs: NDArray[np.float64]) -> None:
    """Raise naming two equal ``x`` values among the precision points (O(m log m))."""
    order = np.argsort(xs, kind="stable")
    same = np.flatnonzero(xs[order][1:] == xs[order][:-1])
    if same.size:
        i, j = sorted((int(order[same[0]]), int(order[same[0] + 1])))
        raise LinkageError(
            f"points[{i}] and points[{j}] are the same x = {float(xs[i])!r}: precision points "
            "must be distinct"
        )


def function(
    f: Callable[[float], SupportsFloat],
    x_range: Sequence[float],
    phi_range: Sequence[float],
    psi_range: Sequence[float],
    points: int | Sequence[float] = 3,
    spacing: Spacing = "chebyshev",
    *,
    ground: float = 1.0,
    y_range: Sequence[float] | None = None,
    n_check: int = 1001,
) -> FunctionGenerator:
    """Design a four-bar function generator for ``y = f(x)`` by Freudenstein's equation.

    ``x`` over ``x_range`` maps linearly to the input angle over ``phi_range`` and ``y`` over
    ``y_range`` (default ``(f(x0), f(x1))``) to the output angle over ``psi_range`` (radians,
    both from the ground line, which runs from ``o = (0, 0)`` to ``c = (ground, 0)``).

    Parameters
    ----------
    points : int or sequence of float
        Number of precision points, at least 3 (3: exact; more: least squares on
        Freudenstein's equation), or the ``x`` values themselves (at least 3, distinct).
    spacing : {"chebyshev", "uniform"}
        Where ``points`` precision points go: Chebyshev spacing, or evenly with both ends.
    n_check : int
        Samples of ``x`` for the structural error (tracked sweep of the linkage), at least 2.

    Time and memory grow linearly with ``points`` and ``n_check`` (``f`` is called once at
    each); a count whose arrays cannot fit in memory is refused before any work.

    Raises
    ------
    LinkageError
        Bad ranges, fewer than 3 or coincident precision points, a singular system, no real
        linkage (a link of infinite or imaginary length), ``f`` not finite.
    TypeError
        ``f`` not callable or not returning a real number; ``points`` or ``n_check`` a float
        (a count is an int; ``x`` values are a sequence).
    MemoryError
        ``points`` or ``n_check`` too large for this machine's memory.

    Examples
    --------
    A log10 generator over ``x ∈ [1, 2]`` (input 45°…105°, output 135°…225°):

    >>> import math, numpy as np
    >>> from linkage import synthesis
    >>> g = synthesis.function(math.log10, (1, 2), np.radians((45, 105)), np.radians((135, 225)))
    >>> g.reaches, g.grashof, f"{g.structural_error_y:.2g}", g.precision_points[:, 0].round(6)
    (True, 'triple-rocker', '0.00056', array([1.066987, 1.5     , 1.933013]))
    >>> synthesis.function(math.log10, (1, 2), (0, 1), (1, 2), points=2)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: points must be an int ≥ 3, got 2
    """
    if not callable(f):
        raise TypeError(f"f must be callable, got {type(f).__name__}")
    x0, x1 = _pair(x_range, "x_range")
    phi0, phi1 = _pair(phi_range, "phi_range")
    psi0, psi1 = _pair(psi_range, "psi_range")
    y0, y1 = _pair(y_range, "y_range") if y_range is not None else (_call(f, x0), _call(f, x1))
    if y0 == y1:
        raise LinkageError(f"f(x0) = f(x1) = {y0}: give y_range to scale the output")
    count = as_count(n_check, "n_check", minimum=2)
    if isinstance(points, (int, np.integer, bool, np.bool_)) or np.ndim(points) == 0:
        if isinstance(points, (bool, np.bool_)) or not isinstance(points, (int, np.integer)):
            raise TypeError(
                "points must be an int (how many precision points, at least 3) or a sequence of "
                f"x values, got {type(points).__name__}"
            )
        m = as_count(points, "points", minimum=3)
        check_memory(
            m * _BYTES_PER_POINT + count * _BYTES_PER_SAMPLE,
            f"function generation at {m} precision points and {count} samples",
        )
        if spacing == "chebyshev":
            xs = chebyshev_points(x0, x1, m)
        elif spacing == "uniform":
            xs = np.linspace(x0, x1, m)
        else:
            raise LinkageError(f"spacing must be {said(get_args(Spacing))}, got {spacing!r}")
    else:
        xs = np.asarray(as_real_array(points, "points"), dtype=np.float64).reshape(-1)
        if xs.size < 3:
            raise LinkageError(f"needs at least 3 precision points, got {xs.size}")
        if not np.all(np.isfinite(xs)):
            raise LinkageError("precision points must be finite")
        _distinct(xs)
        check_memory(
            xs.size * _BYTES_PER_POINT + count * _BYTES_PER_SAMPLE,
            f"function generation at {xs.size} precision points and {count} samples",
        )
    g = as_finite(ground, "ground")
    ys = _values(f, xs)

    def phi_of(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return phi0 + (x - x0) / (x1 - x0) * (phi1 - phi0)

    def psi_of(y: NDArray[np.float64]) -> NDArray[np.float64]:
        return psi0 + (y - y0) / (y1 - y0) * (psi1 - psi0)

    phi, psi = phi_of(xs), psi_of(ys)
    grid = np.linspace(x0, x1, count)
    r = _core.synthesis.function_generator(phi, psi, g, np.ascontiguousarray(phi_of(grid)))
    q = r["params"]
    fb = _placed(q)
    want = psi_of(_values(f, grid))
    err = np.asarray(r["output"], dtype=np.float64) - want
    err = (err + np.pi) % (2 * np.pi) - np.pi
    worst = float(np.max(np.abs(err))) if np.all(np.isfinite(err)) else math.nan
    # The part of the range it follows from x0 on, and the error there: a linkage that stops
    # at a toggle short of x1 still serves up to there.
    gone = np.flatnonzero(~np.isfinite(err))
    upto = len(err) if gone.size == 0 else int(gone[0])
    reached = (float(grid[0]), float(grid[upto - 1])) if upto else (math.nan, math.nan)
    worst_reached = float(np.max(np.abs(err[:upto]))) if upto else math.nan
    code = int(r["defect"])
    off = float(r["input_offset"])
    return FunctionGenerator(
        linkage=fb,
        structural_error=worst,
        structural_error_y=worst * abs((y1 - y0) / (psi1 - psi0)),
        precision_points=np.column_stack([xs, ys]),
        precision_angles=np.column_stack([phi, psi]),
        k=(float(r["k"][0]), float(r["k"][1]), float(r["k"][2])),
        crank_range=(phi0 + off, phi1 + off),
        psi_range=(psi0, psi1),
        output_offset=float(r["output_offset"]),
        x=grid,
        error=err,
        reaches=code < 0,
        defect=None if code < 0 else _DEFECTS[code],
        min_transmission_angle=float(r["min_transmission"]),
        grashof=str(r["grashof"]),
        x_reached=reached,
        structural_error_reached=worst_reached,
    )
