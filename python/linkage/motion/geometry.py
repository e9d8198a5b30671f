"""Geometry of motion: curvature, circumcentres, straight parts, foot paths and mobility.

Also the inflection circle and Ball point of a four-bar's coupler.

Vectorised like shapely: points are arrays shaped ``(..., 2)``; a degenerate configuration
gives NaN, a wrong shape raises.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import as_angles, as_count, as_finite, as_flag, as_points
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mobility import (
    Mobility as Mobility,  # re-exported: linkage.geometry.Mobility
)
from linkage.kinematics.mobility import mobility as mobility

__all__ = [
    "FootPath",
    "Inflection",
    "Mobility",
    "StraightPart",
    "circumcentre",
    "curvature_centre",
    "foot_path",
    "inflection_circle",
    "mobility",
    "straightness",
    "three_point_centres",
]

Points = NDArray[np.float64]


def _points(value: Any, name: str) -> Points:
    return as_points(value, name)


def _rows(*arrays: Points) -> tuple[tuple[int, ...], list[Points]]:
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
    except ValueError:
        raise LinkageError(
            f"point arrays do not broadcast: {', '.join(str(a.shape) for a in arrays)}"
        ) from None
    flat = [np.ascontiguousarray(np.broadcast_to(a, shape).reshape(-1, 2)) for a in arrays]
    return shape[:-1], flat


def curvature_centre(
    point: ArrayLike, velocity: ArrayLike, acceleration: ArrayLike
) -> tuple[Points, NDArray[np.float64]]:
    """Centre of curvature and signed curvature of paths from velocity and acceleration.

    ``κ = (v × a)/|v|³`` (positive when turning counter-clockwise in the direction of motion) and
    centre ``p + v⊥·|v|²/(v × a)``, the same for every timing of the same path.

    Parameters
    ----------
    point, velocity, acceleration : array_like, shape (..., 2)
        The moving point and its first two time derivatives; they broadcast together.

    Returns
    -------
    centre : ndarray, shape (..., 2)
        Centre of curvature; NaN at an inflection (curvature 0) and where the point is at rest.
    curvature : ndarray, shape (...)
        Signed curvature ``κ``; NaN where the point is at rest.

    Raises
    ------
    LinkageError
        If an argument is not shaped ``(..., 2)`` or they do not broadcast.
    TypeError
        For non-numeric arrays.

    Examples
    --------
    On a circle of radius 2 about the origin; at an inflection; at rest:

    >>> from linkage.geometry import curvature_centre
    >>> c, k = curvature_centre([[2, 0], [0, 0], [0, 0]], [[0, 3], [1, 0], [0, 0]],
    ...                         [[-4.5, 0], [0, 0], [1, 0]])
    >>> c
    array([[ 0.,  0.],
           [nan, nan],
           [nan, nan]])
    >>> k
    array([0.5, 0. , nan])
    """
    p, v, a = (
        _points(x, n)
        for x, n in ((point, "point"), (velocity, "velocity"), (acceleration, "acceleration"))
    )
    shape, (fp, fv, fa) = _rows(p, v, a)
    centres, kappa = _core.motion.curvature_centres(fp, fv, fa)
    return centres.reshape(*shape, 2), kappa.reshape(shape)


def circumcentre(p0: ArrayLike, p1: ArrayLike, p2: ArrayLike) -> Points:
    """Centre of the circle through three points.

    Parameters
    ----------
    p0, p1, p2 : array_like, shape (..., 2)
        The points; they broadcast together.

    Returns
    -------
    ndarray, shape (..., 2)
        The centres; NaN where the points are collinear or coincide.

    Raises
    ------
    LinkageError
        If a point array is not shaped ``(..., 2)`` or they do not broadcast.
    TypeError
        For non-numeric arrays.

    Examples
    --------
    The second triple is collinear:

    >>> from linkage.geometry import circumcentre
    >>> circumcentre([[1, 0], [0, 0]], [[0, 1], [1, 1]], [[-1, 0], [2, 2]])
    array([[ 0.,  0.],
           [nan, nan]])
    >>> circumcentre([1, 0, 0], [0, 1], [0, 0])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: p0 must have shape (..., 2), got (3,)
    """
    a, b, c = (_points(x, n) for x, n in ((p0, "p0"), (p1, "p1"), (p2, "p2")))
    shape, (fa, fb, fc) = _rows(a, b, c)
    out: Points = _core.motion.circumcentres(fa, fb, fc).reshape(*shape, 2)
    return out


def three_point_centres(path: ArrayLike, step: int = 1) -> Points:
    """Estimate the centres of curvature of a sampled path from three points each.

    The first source's estimate (thesis 1 §2.1.1): the circumcentre of samples ``k − step, k,
    k + step`` for each interior sample ``k``. It converges to the analytic centre
    (:attr:`Sweep.curvature_centre`) as the spacing shrinks.

    Parameters
    ----------
    path : array_like, shape (N, 2)
        The sampled path.
    step : int, default 1
        Samples between the three points.

    Returns
    -------
    ndarray, shape (N − 2·step, 2)
        The centres, aligned with ``path[step:-step]``; NaN where the three points are collinear
        (a straight stretch or an inflection).

    Raises
    ------
    LinkageError
        If ``path`` is not ``(N, 2)`` or has fewer than ``2·step + 1`` points, or ``step < 1``.

    Examples
    --------
    Every triple of a circle has the circle's centre:

    >>> import numpy as np
    >>> from linkage.geometry import three_point_centres
    >>> t = np.linspace(0, np.pi, 7)
    >>> arc = np.c_[2 * np.cos(t), 2 * np.sin(t)]
    >>> c = three_point_centres(arc)
    >>> c.shape, bool(np.abs(c).max() < 1e-12)
    ((5, 2), True)
    >>> three_point_centres(arc, step=4)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: path needs at least 9 points for step 4
    """
    p = _points(path, "path")
    if p.ndim != 2:
        raise LinkageError(f"path must have shape (N, 2), got {p.shape}")
    step = as_count(step, "step")
    if len(p) < 2 * step + 1:
        raise LinkageError(f"path needs at least {2 * step + 1} points for step {step}")
    return circumcentre(p[: -2 * step], p[step:-step], p[2 * step :])


@dataclass(frozen=True)
class StraightPart:
    """The longest run of samples within a tolerance of its best-fit line."""

    indices: NDArray[np.intp]
    """Sample indices of the run, in order (they wrap on a closed path)."""
    length: float
    """Extent of the run along its line."""
    max_deviation: float
    """Largest distance of a run sample from the line."""
    point: tuple[float, float]
    """The run's centroid, on the line."""
    direction: tuple[float, float]
    """Unit direction of the line, from the run's first sample toward its last."""
    mean_speed: float | None
    """Mean speed along the run, if velocities were given."""
    speed_variation: float | None
    """``(max − min)/mean`` of the speed along the run, if velocities were given; ``inf`` when
    the run reaches a toggle (non-finite velocity there).

    A figure of the straight run only (the part within ``tol`` of a line, any orientation).
    The walker and the leg families report another figure under the same name: ``(max −
    min)/|mean|`` of ``dx/dθ`` over the whole stance, the samples within their tolerance of the
    ground (``linkage_core::LegGait``; :data:`linkage.legs.FIGURES`). For the Hoecken leg the
    first is 4 % over its 16 mm straight part, the second 0.53 over its 44.5 mm stance."""
    lift: float | None = None
    """On a closed path: its largest distance from the line on the side the rest of the path
    lies on (0 when the run is the whole path); None on an open path."""

    @property
    def count(self) -> int:
        """Number of samples in the run."""
        return len(self.indices)


def straightness(
    path: ArrayLike, tol: float, closed: bool = False, velocity: ArrayLike | None = None
) -> StraightPart | None:
    """Find the near-straight part of a path, or None.

    The longest run of consecutive samples that stays within ``tol`` of its own least-squares line
    (at least 3 samples). The scan is O(n log n) (a queue of two convex hulls) with the result of
    the direct search.

    Parameters
    ----------
    path : array_like, shape (N, 2)
        The sampled path. NaN samples break runs.
    tol : float
        Largest distance of a run sample from the run's line (non-negative).
    closed : bool, default False
        Let the run wrap from the last sample to the first (pass a closed curve without
        repeating its first sample).
    velocity : array_like, shape (N, 2), optional
        The path's velocity (e.g. a sweep at constant crank speed): the speed along the run is
        summarised too.

    Returns
    -------
    StraightPart or None
        The longest run, or None when no 3 consecutive samples are within ``tol`` of a line.

    Raises
    ------
    LinkageError
        For a path not shaped ``(N, 2)``, a negative or non-finite ``tol``, or a ``velocity``
        of another shape.

    Examples
    --------
    >>> import numpy as np
    >>> from linkage.geometry import straightness
    >>> x = np.linspace(0, 10, 11)
    >>> part = straightness(np.c_[x, 0.01 * (x - 5) ** 2], tol=0.1)
    >>> part.count, round(part.length, 4)
    (9, 8.0016)

    A NaN sample breaks the run; a circle has no straight part at a tight tolerance:

    >>> y = np.zeros(11)
    >>> y[5] = np.nan
    >>> straightness(np.c_[x, y], tol=0.1).indices
    array([0, 1, 2, 3, 4])
    >>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> straightness(np.c_[np.cos(t), np.sin(t)], tol=1e-6) is None
    True
    """
    p = _points(path, "path")
    if p.ndim != 2:
        raise LinkageError(f"path must have shape (N, 2), got {p.shape}")
    t = as_finite(tol, "tol")
    if t < 0:
        raise LinkageError(f"tol must be non-negative, got {t}")
    v = None
    if velocity is not None:
        v = _points(velocity, "velocity")
        if v.shape != p.shape:
            raise LinkageError(f"velocity must have the shape of path {p.shape}, got {v.shape}")
        v = np.ascontiguousarray(v)
    closed = as_flag(closed, "closed")
    # The run, and its speed figures from the velocities (linkage_core::StraightPart::speed).
    run = _core.motion.straight_run(np.ascontiguousarray(p), t, closed, v)
    if run is None:
        return None
    idx = (run.start + np.arange(run.count)) % len(p)
    mean = None if v is None else run.mean_speed
    var = None if v is None else run.speed_variation
    return StraightPart(
        indices=idx,
        length=run.length,
        max_deviation=run.max_deviation,
        point=run.point,
        direction=run.direction,
        mean_speed=mean,
        speed_variation=var,
        lift=run.lift,
    )


@dataclass(frozen=True)
class FootPath:
    """A closed foot path split into its straight stance and curved swing."""

    stance: StraightPart
    """The straight part (the foot on the ground)."""
    swing: NDArray[np.intp]
    """Sample indices of the curved part (the foot in the air)."""
    stride: float
    """Length of the stance: how far the body moves per step."""
    lift_height: float
    """Largest distance of the swing from the stance line, on the swing's side: the obstacle
    height a leg can step over."""
    stance_fraction: float
    """Share of the samples in stance (of the crank turn, for samples uniform in crank angle)."""

    @property
    def swing_fraction(self) -> float:
        """Share of the samples in swing."""
        return 1.0 - self.stance_fraction


def foot_path(path: ArrayLike, tol: float, velocity: ArrayLike | None = None) -> FootPath:
    """Split one closed cycle of a foot path (without a repeated end sample) into stance and swing.

    Stance is :func:`straightness` on the closed path, swing the rest.

    Parameters
    ----------
    path : array_like, shape (N, 2)
        One cycle of the foot path, its first sample not repeated at the end.
    tol : float
        Straightness tolerance of the stance (see :func:`straightness`).
    velocity : array_like, shape (N, 2), optional
        The foot's velocity, for the stance's speed figures.

    Returns
    -------
    FootPath
        Stance, swing indices, stride, lift height and the stance's share of the samples.

    Raises
    ------
    LinkageError
        If the path has no straight part within ``tol``, or is not shaped ``(N, 2)``.

    Examples
    --------
    The Hoecken leg's foot path within 0.025 mm:

    >>> import numpy as np, linkage
    >>> from linkage.geometry import foot_path
    >>> s = linkage.catalog.hoecken().sweep(np.linspace(0, 2 * np.pi, 360, endpoint=False))
    >>> fp = foot_path(s.point, 0.025)
    >>> round(fp.stride, 3), round(fp.lift_height, 3), fp.stance.count
    (16.215, 8.987, 71)
    >>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> foot_path(np.c_[np.cos(t), np.sin(t)], 1e-9)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the path has no straight part within tol = 1e-09
    """
    p = _points(path, "path")
    if p.ndim != 2:
        raise LinkageError(f"path must have shape (N, 2), got {p.shape}")
    if not np.isfinite(p).all(axis=1).any():
        raise LinkageError("the path has no finite sample (the linkage never assembled?)")
    stance = straightness(p, tol, closed=True, velocity=velocity)
    if stance is None:
        raise LinkageError(f"the path has no straight part within tol = {tol}")
    n = len(p)
    mask = np.ones(n, dtype=bool)
    mask[stance.indices] = False
    swing = np.flatnonzero(mask)
    # The swing's height above the stance line (linkage_core::StraightPart::lift), which the
    # run of a closed path always carries.
    lift = stance.lift
    assert lift is not None, "a closed path's straight run has its lift"
    return FootPath(
        stance=stance,
        swing=swing,
        stride=stance.length,
        lift_height=lift,
        stance_fraction=stance.count / n,
    )


@dataclass(frozen=True)
class Inflection:
    """Inflection circle and Ball point of a four-bar's coupler at one crank angle."""

    pole: tuple[float, float]
    """Instant centre of the coupler relative to the ground (velocity pole)."""
    inflection_pole: tuple[float, float]
    """The point of the circle diametrically opposite the pole."""
    centre: tuple[float, float]
    """Centre of the inflection circle."""
    radius: float
    """Radius of the inflection circle."""
    ball_point: tuple[float, float]
    """The Ball point (NaN if undefined): on the circle, its path has stationary zero
    curvature — locally the best straight-line point of the coupler."""
    ball_point_coupler: tuple[float, float]
    """The Ball point in coupler coordinates (along A → B, to its left), ready for
    ``FourBar(point=...)``."""


def inflection_circle(fb: FourBar, theta: float) -> Inflection:
    """Inflection circle (Euler–Savary) and Ball point of ``fb``'s coupler at crank angle ``theta``.

    The inflection circle is the locus of coupler points whose paths have zero curvature at this
    instant; it passes through the velocity pole. The Ball point is the point of the circle whose
    path also has stationary curvature, the best straight-line point of the coupler there.
    Computed from the linkage's third-order analytic rates, not by differencing.

    Parameters
    ----------
    fb : FourBar
        The linkage; its coupler is the moving plane.
    theta : float
        One crank angle (radians).

    Returns
    -------
    Inflection
        Pole, inflection pole, centre and radius of the circle, and the Ball point in the fixed
        frame and in coupler coordinates (NaN where the Ball point is undefined).

    Raises
    ------
    AssemblyError
        Where the linkage cannot be assembled at ``theta``.
    LinkageError
        At a toggle or where the coupler is instantaneously translating (no finite pole), or
        when ``theta`` is not one angle.
    TypeError
        If ``fb`` is not a :class:`~linkage.FourBar`.

    Examples
    --------
    The Ball point lies on the circle:

    >>> import numpy as np, linkage
    >>> from linkage.geometry import inflection_circle
    >>> inf = inflection_circle(linkage.catalog.hoecken(), 3.14159)
    >>> round(float(np.hypot(*np.subtract(inf.ball_point, inf.centre))) - inf.radius, 9)
    0.0

    A parallelogram's coupler only translates, so it has no inflection circle:

    >>> inflection_circle(linkage.FourBar(ground=10, crank=4, coupler=10, rocker=4), 1.0)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: no inflection circle at theta = 1.0: ... the coupler is translating

    Outside its input range a linkage cannot be assembled:

    >>> inflection_circle(linkage.catalog.evans_b(), 3.0)
    Traceback (most recent call last):
    ...
    linkage.AssemblyError: the linkage cannot be assembled at theta = 3.0
    """
    if not isinstance(fb, FourBar):
        raise TypeError(f"fb must be a FourBar, got {type(fb).__name__}")
    angles, scalar = as_angles(theta, "theta")
    if not scalar:
        raise LinkageError(f"theta must be one crank angle (a scalar), got shape {angles.shape}")
    th = float(angles[0])
    joints = fb.sweep(th).joints
    if not np.isfinite(joints).all():
        raise _core.AssemblyError(f"the linkage cannot be assembled at theta = {th}")
    res = fb._core.coupler_inflection(th)
    if res is None:
        raise LinkageError(
            f"no inflection circle at theta = {th}: a toggle, or the coupler is translating"
        )
    pole, jpole, centre, radius, ball, local = res
    if not np.isfinite([*pole, *jpole, *centre, radius]).all():
        raise LinkageError(
            f"the inflection circle at theta = {th} is not representable in float64 "
            f"(radius {radius!r}): the coupler is nearly translating"
        )
    return Inflection(pole, jpole, centre, float(radius), ball, local)


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {
    "StraightPart": StraightPart,
    "FootPath": FootPath,
    "Inflection": Inflection,
}
for _cls in __test__.values():
    _cls.__module__ = "linkage.geometry"
