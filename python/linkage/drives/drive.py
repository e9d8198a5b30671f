"""Drives: motion laws, piecewise programs, gear trains, and crank-speed schedules.

A drive turns time into crank angle, speed and acceleration (``drive.angles(t)`` gives
``θ, ω, α`` arrays); pass it to ``sweep(time=..., drive=...)`` to get a linkage against time.

>>> import numpy as np
>>> from linkage.drive import Program, Segment, GearTrain
>>> train = GearTrain.simple([18, 15, 14])              # thesis 1's train
>>> round(train.ratio, 6), round(train.output_speed(50.0), 3)
(1.285714, 64.286)
>>> p = Program(np.radians(91), [Segment(1.0, np.pi, "3-4-5"), Segment(1.0, np.pi, "3-4-5")])
>>> theta, omega, alpha = p.angles(np.array([0.5]))
>>> round(float(np.degrees(omega[0])), 6)               # peak 180°·15/8
337.5
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import (
    as_angles,
    as_count,
    as_finite,
    as_flag,
    as_length,
    check_memory,
)
from linkage._shared.choices import Law
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Drive as Drive  # its home: what the kinematics takes
from linkage.kinematics.mechanism import Mechanism
from linkage.motion.geometry import foot_path

__all__ = [
    "LAWS",
    "ConstantSpeed",
    "CrankSchedule",
    "Drive",
    "GearTrain",
    "Geared",
    "Program",
    "Segment",
    "StanceProfile",
    "crank_schedule",
    "motion_law",
    "stance_profile",
]

Array = NDArray[np.float64]
LAWS: tuple[str, ...] = tuple(_core.drive.motion_law_names())
"""Names of the motion laws."""


def motion_law(name: Law, u: ArrayLike) -> tuple[Array, Array, Array, Array]:
    """Evaluate a dimensionless rise law on ``u ∈ [0, 1]``: ``(s, s', s'', s''')``.

    The derivatives are in ``u``. A rise ``L`` over ``β`` scales them as ``L·s``, ``L·s'/β``,
    ``L·s''/β²``, ``L·s'''/β³``.

    Parameters
    ----------
    name : str
        One of :data:`LAWS`: constant-velocity, constant-acceleration, simple-harmonic,
        cycloidal, 3-4-5, 4-5-6-7, modified-trapezoid.
    u : array_like
        Positions within the rise, scalar or 1-D; outside ``[0, 1]`` the law holds its end
        value (a dwell).

    Returns
    -------
    s, ds, d2s, d3s : ndarray, shape (n,)
        The law and its first three derivatives at ``u``.

    Raises
    ------
    LinkageError
        For an unknown law or a non-finite ``u``.
    TypeError
        If ``name`` is not a str.

    Examples
    --------
    >>> import numpy as np
    >>> from linkage.drive import motion_law
    >>> s, v, a, j = motion_law("cycloidal", [0.25])
    >>> round(float(a[0]), 12) == round(2 * np.pi, 12)   # peak 2π·L/β²
    True

    Beyond the rise the output dwells at its end:

    >>> s, v, a, j = motion_law("cycloidal", [0.0, 0.5, 1.0, 1.5])
    >>> s, v
    (array([0. , 0.5, 1. , 1. ]), array([0., 2., 0., 0.]))
    >>> motion_law("cycloidal", [np.nan])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: u must be finite: u[0] is nan
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    uu, _scalar = as_angles(u, "u")
    out = _core.drive.evaluate_motion_law(name, uu)
    cols = tuple(out[:, k] for k in range(4))
    return cols  # type: ignore[return-value]


@dataclass(frozen=True)
class Segment:
    """One segment of a motion program: over ``duration`` the output moves by ``rise``.

    The motion follows ``law``; a segment is a dwell when ``law`` is None or ``rise`` is 0.
    """

    duration: float
    rise: float = 0.0
    law: Law | None = None

    def __post_init__(self) -> None:
        """Check the duration (positive), the rise (finite) and the law (a name of :data:`LAWS`)."""
        as_length(self.duration, "duration")
        as_finite(self.rise, "rise")
        if self.law is not None and not isinstance(self.law, str):
            raise TypeError(
                f"law must be a motion law name (str) or None, got {type(self.law).__name__}"
            )
        if self.law is not None and self.law not in LAWS:
            raise LinkageError(f"unknown motion law {self.law!r}; choose from {', '.join(LAWS)}")


class Program:
    """A piecewise motion program: ``start`` then ``segments`` in sequence, repeating.

    The output advances by the sum of the rises each period. As a drive its output is the crank
    angle in radians against time in seconds.

    >>> from linkage.drive import Program, Segment
    >>> rdr = Program(0.0, [Segment(1.0, 2.0, "simple-harmonic"), Segment(0.5),
    ...                     Segment(1.0, -2.0, "simple-harmonic"), Segment(0.5)])
    >>> [(after, order) for after, order, _ in rdr.discontinuities()]
    [(0, 2), (1, 2), (2, 2), (3, 2)]
    """

    def __init__(self, start: float, segments: Sequence[Segment]) -> None:
        self.start = as_finite(start, "start")
        segs = list(segments)
        if not segs:
            raise LinkageError("a program needs at least one segment")
        for s in segs:
            if not isinstance(s, Segment):
                raise TypeError(f"segments must be Segment, got {type(s).__name__}")
        # Each duration and rise is finite; their sums must be too, or every time maps to one
        # period and the program is meaningless.
        if not math.isfinite(_sum(float(s.duration) for s in segs)):
            raise LinkageError("the program's period (sum of the durations) overflows a float")
        if not math.isfinite(_sum(float(s.rise) for s in segs)):
            raise LinkageError("the program's net rise (sum of the rises) overflows a float")
        self.segments = tuple(segs)

    def _args(self) -> tuple[float, list[float], list[float], list[str | None]]:
        return (
            self.start,
            [float(s.duration) for s in self.segments],
            [float(s.rise) for s in self.segments],
            [s.law for s in self.segments],
        )

    @property
    def period(self) -> float:
        """Duration of one period."""
        return _sum(float(s.duration) for s in self.segments)

    def eval(self, t: ArrayLike) -> tuple[Array, Array, Array, Array]:
        """Evaluate the program's value and first three derivatives at ``t``.

        Parameters
        ----------
        t : array_like
            Times (or cam angles), scalar or 1-D; the program repeats with :attr:`period`.

        Returns
        -------
        value, rate, second, third : ndarray, shape (n,)
            The output and its first three derivatives.

        Raises
        ------
        LinkageError
            For a non-finite ``t``, or where an output is not representable in float64.

        Examples
        --------
        A rise of 2 over 1 s, then a dwell of 0.5 s; the next period starts 2 higher:

        >>> from linkage.drive import Program, Segment
        >>> p = Program(0.0, [Segment(1.0, 2.0, "simple-harmonic"), Segment(0.5)])
        >>> value, rate, _, _ = p.eval([0.0, 0.5, 1.25, 1.5])
        >>> value, rate.round(6)
        (array([0., 1., 2., 2.]), array([0.      , 3.141593, 0.      , 0.      ]))
        """
        tt, _ = as_angles(t, "t")
        out = _core.drive.evaluate_program(*self._args(), tt)
        _check_rows(out, tt, ("value", "rate", "second derivative", "third derivative"))
        return out[:, 0], out[:, 1], out[:, 2], out[:, 3]

    def angles(self, t: ArrayLike) -> tuple[Array, Array, Array]:
        """Return ``(θ, ω, α)`` at times ``t``: :meth:`eval` without the third derivative.

        Examples
        --------
        A rise of 2 rad over 1 s and a dwell of 0.5 s; the next period starts 2 rad further:

        >>> from linkage.drive import Program, Segment
        >>> p = Program(0.0, [Segment(1.0, 2.0, "simple-harmonic"), Segment(0.5)])
        >>> theta, omega, alpha = p.angles([0.5, 1.25, 2.0])
        >>> theta, omega.round(6), alpha.round(6) + 0.0
        (array([1., 2., 3.]), array([3.141593, 0.      , 3.141593]), array([0., 0., 0.]))
        """
        y, v, a, _ = self.eval(t)
        return y, v, a

    def discontinuities(self, tol: float = 1e-9) -> list[tuple[int, int, float]]:
        """Return the jumps at the joins (the last to the first included).

        Each is ``(after segment, order, jump)`` with order 1 velocity, 2 acceleration, 3 jerk.

        Examples
        --------
        Simple-harmonic rises jump in acceleration at both ends, cycloidal ones only in jerk:

        >>> from linkage.drive import Program, Segment
        >>> harmonic = Program(0.0, [Segment(1.0, 2.0, "simple-harmonic"), Segment(0.5)])
        >>> [(after, order, round(jump, 6)) for after, order, jump in harmonic.discontinuities()]
        [(0, 2, -9.869604), (1, 2, -9.869604)]
        >>> cycloidal = Program(0.0, [Segment(1.0, 2.0, "cycloidal"), Segment(0.5)])
        >>> [(after, order) for after, order, _ in cycloidal.discontinuities()]
        [(0, 3), (1, 3)]
        """
        raw = _core.drive.program_discontinuities(*self._args(), as_finite(tol, "tol"))
        return [(int(after), int(order), float(jump)) for after, order, jump in raw]


@dataclass(frozen=True)
class ConstantSpeed:
    """Constant crank speed ``omega`` (rad/s) from ``theta0``."""

    omega: float
    theta0: float = 0.0

    def angles(self, t: ArrayLike) -> tuple[Array, Array, Array]:
        """Return ``(θ, ω, α)`` at times ``t``.

        Parameters
        ----------
        t : array_like
            Times (s), scalar or 1-D.

        Returns
        -------
        theta, omega, alpha : ndarray, shape (n,)
            ``θ0 + ω·t``, ``ω`` and 0.

        Raises
        ------
        LinkageError
            For a non-finite time, or a crank angle that overflows a float.

        Examples
        --------
        >>> from linkage.drive import ConstantSpeed
        >>> ConstantSpeed(2.0).angles([0.0, 1.0])
        (array([0., 2.]), array([2., 2.]), array([0., 0.]))
        >>> ConstantSpeed(2.0).angles([1e308])
        Traceback (most recent call last):
        ...
        linkage.LinkageError: the crank angle overflows a float at t = 1e+308
        """
        tt, _ = as_angles(t, "t")
        w = as_finite(self.omega, "omega")
        with np.errstate(over="ignore", invalid="ignore"):
            theta = as_finite(self.theta0, "theta0") + w * tt
        _check_angles(theta, tt)
        return theta, np.full_like(tt, w), np.zeros_like(tt)


class GearTrain:
    """External spur gears: speed ratio ``output/input`` and sense."""

    def __init__(self, ratio: float, sign: int) -> None:
        self.ratio = as_finite(ratio, "ratio")
        if not self.ratio > 0:
            raise LinkageError(f"ratio must be positive, got {self.ratio!r}")
        if isinstance(sign, (bool, np.bool_)) or not isinstance(sign, (int, np.integer)):
            raise TypeError(f"sign must be the int 1 or -1, got {type(sign).__name__}")
        if sign not in (1, -1):
            raise LinkageError(f"sign must be 1 or -1, got {sign}")
        self.sign = int(sign)

    @classmethod
    def simple(cls, teeth: Sequence[int]) -> GearTrain:
        """Build a simple train: gears in mesh order, one per shaft.

        The ratio is ``z_first/z_last`` (the idlers cancel); each mesh reverses the sense.

        Parameters
        ----------
        teeth : sequence of int
            Tooth counts in mesh order, at least two, each positive.

        Returns
        -------
        GearTrain
            The ratio ``output/input`` and the sense.

        Raises
        ------
        LinkageError
            For fewer than two gears or a tooth count below 1.
        TypeError
            For a tooth count that is not an int.

        Examples
        --------
        Thesis 1's train: two meshes, so the output turns the motor's way:

        >>> from linkage.drive import GearTrain
        >>> GearTrain.simple([18, 15, 14])
        GearTrain(ratio=1.28571, sign=+1)
        >>> GearTrain.simple([18, 0])
        Traceback (most recent call last):
        ...
        linkage.LinkageError: tooth counts must be positive, got 0
        """
        train = _core.drive.simple_gear_train([_teeth(z) for z in teeth])
        return cls(train.ratio, train.sign)

    @classmethod
    def compound(cls, stages: Sequence[tuple[int, int]]) -> GearTrain:
        """Build a compound train of ``(driver, driven)`` meshes.

        The driven gear of one mesh and the driver of the next share a shaft; the ratio is the
        product of ``driver/driven`` and each mesh reverses the sense.

        Parameters
        ----------
        stages : sequence of (int, int)
            ``(driver, driven)`` tooth counts, one pair per mesh.

        Returns
        -------
        GearTrain
            The ratio ``output/input`` and the sense.

        Raises
        ------
        LinkageError
            For a stage that is not a pair, or a tooth count below 1.
        TypeError
            For a stage or tooth count of the wrong type.

        Examples
        --------
        >>> from linkage.drive import GearTrain
        >>> GearTrain.compound([(10, 30), (12, 36)])
        GearTrain(ratio=0.111111, sign=+1)
        """
        pairs = []
        for stage in stages:
            if isinstance(stage, (str, bytes)) or not hasattr(stage, "__len__"):
                raise TypeError(
                    f"stages must be (driver, driven) pairs, got {type(stage).__name__}"
                )
            if len(stage) != 2:
                raise LinkageError(
                    f"stages must be (driver, driven) pairs, got {len(stage)} values"
                )
            pairs.append((_teeth(stage[0]), _teeth(stage[1])))
        train = _core.drive.compound_gear_train(pairs)
        return cls(train.ratio, train.sign)

    def output_speed(self, input_speed: float) -> float:
        """Return the signed output speed for an input speed.

        Parameters
        ----------
        input_speed : float
            The input shaft's speed (any unit).

        Returns
        -------
        float
            ``input_speed × ratio × sign``.

        Raises
        ------
        LinkageError
            If the input is not finite or the output overflows a float.

        Examples
        --------
        >>> from linkage.drive import GearTrain
        >>> GearTrain.simple([10, 20]).output_speed(50.0)     # one mesh: reversed
        -25.0
        """
        out = as_finite(input_speed, "input_speed") * self.ratio * self.sign
        if not math.isfinite(out):
            raise LinkageError(f"output speed overflows: {input_speed!r} × {self.ratio!r}")
        return out

    def __repr__(self) -> str:
        """Return ``GearTrain(ratio=..., sign=...)``."""
        return f"GearTrain(ratio={self.ratio:g}, sign={self.sign:+d})"


def _check_angles(theta: Array, t: Array) -> None:
    bad = ~np.isfinite(theta)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise LinkageError(f"the crank angle overflows a float at t = {float(t[k])!r}")


def _sum(values: Iterable[float]) -> float:
    """Exact sum (``math.fsum``), ±inf when it overflows instead of ``OverflowError``."""
    vals = list(values)
    try:
        return math.fsum(vals)
    except OverflowError:
        return math.copysign(math.inf, sum(math.copysign(1.0, v) for v in vals))


def _check_rows(out: Array, t: Array, what: tuple[str, ...]) -> None:
    """Check that a drive's outputs at finite times are finite.

    Times beyond what float64 can represent of the drive (e.g. the whole turns at t = 1e308) are a
    ``LinkageError``, never inf/NaN.
    """
    bad = ~np.isfinite(out)
    if bad.any():
        k, col = (int(i) for i in np.argwhere(bad)[0])
        raise LinkageError(
            f"the {what[col]} at t = {float(t[k])!r} is not representable in float64 "
            f"(got {float(out[k, col])})"
        )


def _teeth(z: Any) -> int:
    if isinstance(z, bool) or not isinstance(z, (int, np.integer)):
        raise TypeError(f"tooth counts must be ints, got {type(z).__name__}")
    if z <= 0:
        raise LinkageError(f"tooth counts must be positive, got {z}")
    return int(z)


@dataclass(frozen=True)
class Geared:
    """A motor drive seen through a gear train.

    The crank turns ``train.ratio`` times as fast (with the train's sense).
    """

    motor: Drive
    train: GearTrain

    def angles(self, t: ArrayLike) -> tuple[Array, Array, Array]:
        """Return ``(θ, ω, α)`` of the crank at times ``t``: the motor's times the train's ratio.

        Parameters
        ----------
        t : array_like
            Times (s), scalar or 1-D.

        Returns
        -------
        theta, omega, alpha : ndarray, shape (n,)
            The crank's angle, speed and acceleration.

        Raises
        ------
        LinkageError
            For a non-finite time, or an output that overflows a float.

        Examples
        --------
        >>> from linkage.drive import ConstantSpeed, Geared, GearTrain
        >>> Geared(ConstantSpeed(50.0), GearTrain.simple([18, 15, 14])).angles([1.0])
        (array([64.28571429]), array([64.28571429]), array([0.]))
        """
        th, w, a = self.motor.angles(t)
        k = self.train.ratio * self.train.sign
        with np.errstate(over="ignore", invalid="ignore"):
            out = k * np.asarray(th), k * np.asarray(w), k * np.asarray(a)
        for arr, what in zip(out, ("angle", "speed", "acceleration")):
            if not np.isfinite(arr).all():
                raise LinkageError(f"the geared crank {what} overflows a float (ratio {k:g})")
        return out


@dataclass(frozen=True)
class CrankSchedule:
    """A periodic crank schedule ``θ(t)`` for one crank turn per period.

    It is stored as a compact table of crank angle and speed at uniform times (see
    :func:`crank_schedule`).

    ``theta`` and ``omega`` are ``float32`` — the arrays to put in firmware, interpolated there
    by ``linkage_core::ScheduleTable`` (cubic Hermite: θ and ω continuous).
    """

    dt: float
    """Time between table entries (s)."""
    theta: NDArray[np.float32]
    """Crank angle at ``k·dt`` (rad), starting at the stance's first angle."""
    omega: NDArray[np.float32]
    """Crank speed at ``k·dt`` (rad/s)."""
    foot_speed: float
    """The target foot speed along the stance line."""
    duty_factor: float
    """Share of the period in stance."""
    stance_angles: tuple[float, float]
    """Crank angles where stance starts and ends (the end may exceed 2π)."""
    speed_ripple: float
    """``(max − min)/target`` of the foot speed along the stance line in stance, with the
    table interpolated in f64."""
    peak_alpha: float
    """Largest crank acceleration over the period (rad/s²)."""

    @property
    def period(self) -> float:
        """One period (s)."""
        return self.dt * len(self.theta)

    def angles(self, t: ArrayLike, single: bool = False) -> tuple[Array, Array, Array]:
        """Return ``(θ, ω, α)`` at times ``t``.

        Interpolated by the core in f64, or in f32 as firmware would (``single=True``).

        Parameters
        ----------
        t : array_like
            Times (s), scalar or 1-D; the schedule repeats with :attr:`period`, the crank one
            turn further each period.
        single : bool, default False
            Interpolate in f32, as ``linkage_core::ScheduleTable`` does on a microcontroller.

        Returns
        -------
        theta, omega, alpha : ndarray, shape (n,)
            The crank's angle, speed and acceleration.

        Raises
        ------
        LinkageError
            For a non-finite time, or an output not representable in float64.

        Examples
        --------
        One period later the crank is a turn further; f32 interpolation stays within 1e-6 rad:

        >>> import numpy as np, linkage
        >>> sched = linkage.drive.crank_schedule(linkage.catalog.hoecken(), 80.0, 0.6)
        >>> theta, omega, _ = sched.angles([0.0, sched.period])
        >>> round(float(theta[1] - theta[0]), 6), bool(omega[0] == omega[1])
        (6.283185, True)
        >>> bool(np.abs(sched.angles([0.3], single=True)[0] - sched.angles([0.3])[0]).max() < 1e-6)
        True
        """
        tt, _ = as_angles(t, "t")
        out = _core.drive.evaluate_schedule(
            self.dt,
            2 * np.pi,
            np.asarray(self.theta, dtype=np.float64),
            np.asarray(self.omega, dtype=np.float64),
            tt,
            as_flag(single, "single"),
        )
        _check_rows(out, tt, ("crank angle", "crank speed", "crank acceleration"))
        return out[:, 0], out[:, 1], out[:, 2]


@dataclass(frozen=True)
class StanceProfile:
    """A leg's stance as a crank schedule needs it (see :func:`stance_profile`).

    It is the same for every foot speed and duty factor, so a search over them finds it once.
    """

    theta: NDArray[np.float64]
    """Stance crank angles (rad), increasing (unwrapped across 2π)."""
    u: NDArray[np.float64]
    """The foot's speed along the stance line per radian of crank at each angle."""
    direction: NDArray[np.float64]
    """Unit direction of the stance line."""


def stance_profile(
    leg: FourBar | Mechanism, tol: float | None = None, resolution: int = 7201
) -> StanceProfile:
    """Find the stance of ``leg``: the straight part of its foot path.

    The foot path is sampled at ``resolution`` crank angles over a turn and its straight part
    found by :func:`linkage.foot_path`.

    Parameters
    ----------
    leg : FourBar or Mechanism
        The leg; its trace point is the foot.
    tol : float, optional
        Straightness tolerance of the stance; default 0.2 % of the foot path's extent.
    resolution : int, default 7201
        Crank angles over the turn (at least 16).

    Returns
    -------
    StanceProfile
        The stance's crank angles (increasing), the foot's speed along the stance line per
        radian of crank there, and the line's direction.

    Raises
    ------
    LinkageError
        When the leg does not assemble over a whole turn, the foot path has no straight part,
        or for bad numbers.
    TypeError
        If ``leg`` is not a FourBar or Mechanism.
    MemoryError
        When the samples would not fit in memory.

    Examples
    --------
    The Hoecken leg's stance spans the crank angles 75.2° to 287°:

    >>> import numpy as np, linkage
    >>> st = linkage.drive.stance_profile(linkage.catalog.hoecken())
    >>> np.degrees(st.theta[[0, -1]]).round(3)
    array([ 75.2, 287. ])

    A leg with a limited crank range has no stance to schedule:

    >>> linkage.drive.stance_profile(linkage.catalog.evans_b())
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the leg must assemble over a whole crank turn
    """
    if not isinstance(leg, (FourBar, Mechanism)):
        raise TypeError(f"leg must be a FourBar or Mechanism, got {type(leg).__name__}")
    resolution = as_count(resolution, "resolution", 16)
    if tol is not None:
        tol = as_finite(tol, "tol")
    # Per resolution sample: angle, joints and joint velocities, flags.
    joints = 5 if isinstance(leg, FourBar) else max(1, len(leg))
    check_memory(resolution * 8 * (8 + 4 * joints), f"a crank schedule at resolution {resolution}")
    theta = np.linspace(0.0, 2 * np.pi, resolution)
    s = leg.sweep(theta, omega=1.0, outputs=("point", "velocity"))
    if not s.valid.all():
        raise LinkageError("the leg must assemble over a whole crank turn")
    path, vel = s.point[:-1], s.velocity[:-1]
    extent = float(np.ptp(path, axis=0).max())
    fp = foot_path(path, tol if tol is not None else 2e-3 * extent)
    idx = fp.stance.indices
    d = np.asarray(fp.stance.direction, dtype=np.float64)
    # Stance crank angles, unwrapped so they increase.
    th_st = np.ascontiguousarray(theta[idx] + 2 * np.pi * (idx < idx[0]))
    u = np.ascontiguousarray(np.abs(vel[idx] @ d))
    return StanceProfile(theta=th_st, u=u, direction=d)


def crank_schedule(
    leg: FourBar | Mechanism,
    foot_speed: float,
    duty_factor: float,
    samples: int = 720,
    tol: float | None = None,
    resolution: int = 7201,
    stance: StanceProfile | None = None,
) -> CrankSchedule:
    """Design a crank schedule that keeps a leg's foot at constant speed along its stance line.

    In stance (the straight part of the foot path within ``tol``, default 0.2 % of the path's
    extent: :func:`stance_profile`, or ``stance`` when given) the crank runs at
    ``ω(θ) = V/|u(θ)|``, ``u`` the foot's velocity along the stance line per radian of crank,
    so the stance lasts ``stride/V``. With duty factor ``β`` the period is ``T = stride/(V·β)``;
    the swing covers the remaining crank angle in ``(1 − β)T`` with a speed that starts and ends
    at the stance speeds (continuous ω) plus a parabolic bump sized to close the turn — bounded
    acceleration (the core's ``StanceSchedule``).

    Parameters
    ----------
    leg : FourBar or Mechanism
        The leg; its trace point is the foot.
    foot_speed : float
        ``V``, the foot's speed along the stance line (positive; length units per second).
    duty_factor : float
        ``β``, the share of the period in stance (strictly between 0 and 1).
    samples : int, default 720
        Entries of the table over one period (at least 8).
    tol, resolution
        The stance's tolerance and sampling, as :func:`stance_profile`.
    stance : StanceProfile, optional
        The leg's stance, found once for many schedules; else found here.

    Returns
    -------
    CrankSchedule
        The float32 table, with the foot-speed ripple it delivers and its peak crank
        acceleration.

    Raises
    ------
    LinkageError
        For bad numbers, a foot path with no straight part, or a swing that would need the crank
        to stop or reverse (duty factor too low for that stance).
    TypeError
        If ``leg`` is not a FourBar or Mechanism, or ``stance`` not a StanceProfile.
    MemoryError
        When the table's checks would not fit in memory.

    Examples
    --------
    >>> import linkage
    >>> leg = linkage.catalog.hoecken()
    >>> sched = linkage.drive.crank_schedule(leg, 80.0, 0.6)
    >>> round(sched.period, 4), sched.speed_ripple < 1e-3, sched.theta.dtype
    (0.9314, True, dtype('float32'))

    Too short a swing would need the crank to run backwards:

    >>> linkage.drive.crank_schedule(leg, 80.0, 0.3)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the duty factor needs the crank to stop during the swing ...
    """
    if not isinstance(leg, (FourBar, Mechanism)):
        raise TypeError(f"leg must be a FourBar or Mechanism, got {type(leg).__name__}")
    v_target = as_length(foot_speed, "foot_speed")
    beta = as_finite(duty_factor, "duty_factor")
    if not 0 < beta < 1:
        raise LinkageError(f"duty_factor must be between 0 and 1, got {beta}")
    samples = as_count(samples, "samples", 8)
    # Per table sample: 20 checked times with their angles, speeds and a sweep.
    joints = 5 if isinstance(leg, FourBar) else max(1, len(leg))
    check_memory(samples * 20 * 8 * (12 + 4 * joints), f"a crank schedule of {samples} samples")
    if stance is None:
        stance = stance_profile(leg, tol, resolution)
    elif not isinstance(stance, StanceProfile):
        raise TypeError(f"stance must be a StanceProfile, got {type(stance).__name__}")
    th_st, u, d = stance.theta, stance.u, stance.direction
    # The schedule itself (stance at V/u, a swing closing the turn) is the core's
    # StanceSchedule; here only the stance is found and the result measured.
    table = _core.drive.stance_schedule(th_st, u, v_target, beta, samples)
    dt, th_tab, w_tab = table.dt, table.theta, table.omega
    stance_time, stance_angles = table.stance_time, table.stance_angles
    period = dt * samples
    sched = CrankSchedule(
        dt=dt,
        theta=th_tab.astype(np.float32),
        omega=w_tab.astype(np.float32),
        foot_speed=v_target,
        duty_factor=beta,
        stance_angles=stance_angles,
        speed_ripple=0.0,
        peak_alpha=0.0,
    )
    # Measure what the table delivers: foot speed along the stance line in stance, and the
    # crank acceleration over the period, with the table interpolated in f64.
    t_fine = np.linspace(0.0, period, 20 * samples, endpoint=False)
    th_f, w_f, a_f = sched.angles(t_fine)
    in_stance = t_fine <= stance_time
    sv = leg.sweep(th_f[in_stance], omega=w_f[in_stance], outputs=("point", "velocity"))
    speed = sv.velocity @ d
    ripple = float((speed.max() - speed.min()) / v_target)
    return CrankSchedule(
        dt=dt,
        theta=sched.theta,
        omega=sched.omega,
        foot_speed=v_target,
        duty_factor=beta,
        stance_angles=sched.stance_angles,
        speed_ripple=ripple,
        peak_alpha=float(np.abs(a_f).max()),
    )


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {
    "Segment": Segment,
    "Program": Program,
    "ConstantSpeed": ConstantSpeed,
    "GearTrain": GearTrain,
    "Geared": Geared,
    "CrankSchedule": CrankSchedule,
    "StanceProfile": StanceProfile,
}
for _cls in __test__.values():
    _cls.__module__ = "linkage.drive"
