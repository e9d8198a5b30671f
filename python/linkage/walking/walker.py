"""Walking machines: legs on a body, gaits as crank phases, ground contact and stability.

A simulation gives support polygons, the static stability margin, body motion and foot slip.

Each leg is a one-degree-of-freedom linkage whose trace point is the foot, mounted on the body in
a vertical ("sagittal") plane — the linkage's x forward, y up — or in the horizontal plane with
a cam lifting the foot (thesis 2's hexapod). The body frame has x forward, y to the left, z up;
the body is held level at constant height, and the ground is the lowest level any foot reaches.

>>> import numpy as np, linkage
>>> w = linkage.catalog.quadruped_hoecken()
>>> sim = w.simulate(np.linspace(0, 2 * np.pi, 721))
>>> [round(float(d), 2) for d in sim.duty_factor]    # every leg: 58 % of the turn in stance
[0.58, 0.58, 0.58, 0.58]
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import (
    as_angles,
    as_choice,
    as_count,
    as_finite,
    as_flag,
    as_point,
    check_memory,
)
from linkage._shared.choices import Objective, Plane
from linkage.drives.drive import Drive, Program
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.slider_crank import SliderCrank

__all__ = [
    "GAITS",
    "PLANES",
    "Leg",
    "Simulation",
    "Walker",
    "gait_phases",
    "leg_labels",
]

Array = NDArray[np.float64]
PLANES: tuple[Plane, ...] = get_args(Plane)
"""The planes a leg's linkage can move in (``Leg.plane``)."""


@dataclass(frozen=True)
class Leg:
    """One leg: a linkage whose trace point is the foot, its mount, crank phase and foot pad.

    A :class:`~linkage.SliderCrank` is taken as its :meth:`~linkage.SliderCrank.mechanism`.
    """

    name: str
    linkage: FourBar | Mechanism
    mount: tuple[float, float, float]
    """Body-frame position of the linkage's origin (x forward, y left, z up)."""
    phase: float = 0.0
    """Crank phase (rad): the leg's crank angle is the drive's plus this."""
    plane: Plane = "sagittal"
    """"sagittal": the linkage's (x, y) is the body's (x, z); "horizontal": the body's (x, y),
    with ``lift`` giving the foot height."""
    mirror: bool = False
    """Flip the linkage's y (a right-side leg of a horizontal pair, or a mirrored sagittal leg)."""
    foot_offset: tuple[float, float] = (0.0, 0.0)
    """A rigid offset from the trace point to the foot, in the linkage's plane (a vertical bar
    guided on the body, as in thesis 1's prototype)."""
    lift: Program | None = None
    """Foot height against the leg's crank angle (a cam program spanning one turn)."""
    pad: float = 0.0
    """Side of the square foot pad (0: a point foot)."""

    def __post_init__(self) -> None:
        """Check every field's type and range (a horizontal leg needs a ``lift``)."""
        if not isinstance(self.name, str):
            raise TypeError(f"a leg's name must be a str, got {type(self.name).__name__}")
        if not isinstance(self.plane, str):
            raise TypeError(
                f"leg {self.name!r}: plane must be a str, got {type(self.plane).__name__}"
            )
        as_flag(self.mirror, "mirror")
        if self.lift is not None and not isinstance(self.lift, Program):
            raise TypeError(
                f"leg {self.name!r}: lift must be a linkage.drive.Program or None, "
                f"got {type(self.lift).__name__}"
            )
        if self.plane not in PLANES:
            raise LinkageError(
                f"leg {self.name!r}: plane must be one of {PLANES}, got {self.plane!r}"
            )
        if isinstance(self.linkage, SliderCrank):
            # Its joints (the slider on its line), the coupler point traced: the foot.
            object.__setattr__(self, "linkage", self.linkage.mechanism())
        if not isinstance(self.linkage, (FourBar, Mechanism)):
            hint = (
                " (a synthesis candidate's is its .linkage)"
                if hasattr(self.linkage, "linkage")
                else ""
            )
            raise TypeError(
                f"leg {self.name!r}: linkage must be a FourBar, SliderCrank or Mechanism, "
                f"got {type(self.linkage).__name__}{hint}"
            )
        if isinstance(self.mount, (str, bytes)) or not hasattr(self.mount, "__len__"):
            raise TypeError(f"leg {self.name!r}: mount must be (x, y, z)")
        if len(self.mount) != 3:
            raise LinkageError(f"leg {self.name!r}: mount must be (x, y, z)")
        for v in self.mount:
            as_finite(v, "mount")
        as_finite(self.phase, "phase")
        as_point(self.foot_offset, "foot_offset")
        if as_finite(self.pad, "pad") < 0:
            raise LinkageError(f"leg {self.name!r}: pad must be non-negative")
        if self.plane == "horizontal" and self.lift is None:
            raise LinkageError(f"leg {self.name!r}: a horizontal leg needs a lift program")

    def feet(self, theta: Array, omega: Array) -> tuple[Array, Array]:
        """Return foot positions and velocities in the body frame, (N, 3) each.

        Parameters
        ----------
        theta : ndarray, shape (N,)
            The drive's crank angles (rad); the leg adds its phase.
        omega : ndarray, shape (N,)
            The crank's speed at each angle (rad/s).

        Returns
        -------
        feet, velocity : ndarray, shape (N, 3)
            The foot's position (the foot offset or lift included) and velocity, body frame.

        Raises
        ------
        LinkageError
            If the leg cannot be assembled at one of the angles.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> leg = linkage.catalog.quadruped_hoecken().legs[0]
        >>> feet, velocity = leg.feet(np.array([0.0, np.pi]), np.array([1.0, 1.0]))
        >>> feet.round(4), velocity.round(4) + 0.0
        (array([[ 70.    ,  50.    , -51.0102],
               [ 70.    ,  50.    , -60.    ]]), array([[ 48.9898,   0.    ,   0.    ],
               [-13.3333,   0.    ,   0.    ]]))
        """
        th = theta + self.phase
        s = self.linkage.sweep(th, omega=omega, outputs=("point", "velocity"))
        if not s.valid.all():
            raise LinkageError(f"leg {self.name!r} cannot be assembled over the whole cycle")
        side = -1.0 if self.mirror else 1.0
        px = s.point[:, 0] + self.foot_offset[0]
        py = side * (s.point[:, 1] + self.foot_offset[1])
        vx, vy = s.velocity[:, 0], side * s.velocity[:, 1]
        mx, my, mz = self.mount
        pos = np.empty((len(th), 3))
        vel = np.zeros((len(th), 3))
        if self.plane == "sagittal":
            pos[:] = np.c_[mx + px, np.full_like(px, my), mz + py]
            vel[:, 0], vel[:, 2] = vx, vy
        else:
            pos[:] = np.c_[mx + px, my + py, np.full_like(px, mz)]
            vel[:, 0], vel[:, 1] = vx, vy
        if self.lift is not None:
            h, dh, _, _ = self.lift.eval(np.mod(th, 2 * math.pi))
            pos[:, 2] += h
            vel[:, 2] += dh * omega
        return pos, vel


@dataclass
class Simulation:
    """A walker over one or more cycles: every array has one row per sample."""

    theta: Array
    """The drive's crank angle."""
    time: Array
    """Time of each sample (crank angle / ω for a constant-speed sweep by angle)."""
    legs: tuple[str, ...]
    feet: Array
    """Foot positions in the body frame, (N, L, 3)."""
    foot_velocity: Array
    """Foot velocities in the body frame, (N, L, 3)."""
    stance: NDArray[np.bool_]
    """Which feet are on the ground, (N, L)."""
    ground: float
    """Ground height in the body frame (the lowest foot level)."""
    body_velocity: Array
    """Forward body speed: minus the mean stance-foot velocity along x (NaN with no foot
    down)."""
    body_position: Array
    """Forward body travel since the first sample."""
    support: Array
    """Support polygon (convex hull of the stance pads) per sample, counter-clockwise,
    NaN-padded, (N, K, 2) in the ground plane (x, y)."""
    support_count: NDArray[np.uint64]
    """Vertices of each support polygon."""
    margin: Array
    """Signed distance of the centre of gravity's ground projection from the support polygon's
    boundary: positive inside (statically stable), negative outside, ``-inf`` with no foot on
    the ground."""
    slip_velocity: Array
    """Velocity over the ground of each stance foot along x: foot velocity plus body velocity,
    (N, L); NaN in swing. Zero when every stance foot moves alike."""
    spread: Array
    """Largest minus smallest stance-foot velocity along x, per sample (0 with < 2 feet down)."""
    cycle: float = field(default=2 * math.pi)
    gaits: tuple[dict[str, float], ...] = ()
    """Per leg, the core's leg figures (``linkage_core::LegGait``: stance count and runs, duty
    factor, stride, lift, straightness, speed variation, peak torque) of its foot path in the
    sagittal plane ``(x, z)`` with this simulation's ground and tolerance; the stance mask,
    duty factor, stride and lift height above come from them (one implementation)."""

    @property
    def min_margin(self) -> float:
        """The smallest stability margin."""
        return float(np.nanmin(self.margin))

    @property
    def min_margin_at(self) -> float:
        """Crank angle of the smallest stability margin."""
        return float(self.theta[int(np.nanargmin(self.margin))])

    @property
    def duty_factor(self) -> Array:
        """Share of the samples each leg spends in stance."""
        return np.array([g["duty_factor"] for g in self.gaits], dtype=float)

    @property
    def pr_ratio(self) -> Array:
        """Protraction (swing) to retraction (stance) time ratio p/r per leg."""
        d = self.duty_factor
        with np.errstate(divide="ignore"):
            r: Array = (1 - d) / d
        return r

    @property
    def stride(self) -> Array:
        """Foot travel along x during stance (the body's advance per step), per leg."""
        return np.array([g["stride"] for g in self.gaits], dtype=float)

    @property
    def lift_height(self) -> Array:
        """Highest foot point above the ground, per leg: the obstacle it can step over."""
        return np.array([g["lift"] for g in self.gaits], dtype=float)

    @property
    def slip_distance(self) -> Array:
        """Distance each foot slides over the ground while in stance, over the simulation."""
        dt = np.gradient(self.time) if len(self.time) > 1 else np.zeros(len(self.time))
        s = np.where(self.stance, np.abs(np.nan_to_num(self.slip_velocity)), 0.0)
        d: Array = (s * dt[:, None]).sum(axis=0)
        return d

    def gait_diagram(self) -> list[tuple[str, list[tuple[float, float]]]]:
        """Stance bars per leg: ``(leg, [(start, end), ...])`` in time (the source's Fig. 4.4).

        Examples
        --------
        >>> import numpy as np, linkage
        >>> sim = linkage.catalog.quadruped_hoecken().simulate(np.linspace(0, 2 * np.pi, 9))
        >>> bars = dict(sim.gait_diagram())  # stance from the 3rd to the 7th sample, or split:
        >>> [(round(a, 4), round(b, 4)) for a, b in bars["A"]]
        [(1.5708, 4.7124)]
        >>> [(round(a, 4), round(b, 4)) for a, b in bars["B"]]
        [(0.0, 1.5708), (4.7124, 6.2832)]
        """
        out = []
        for i, name in enumerate(self.legs):
            s = np.r_[False, self.stance[:, i], False].astype(int)
            starts = np.flatnonzero(np.diff(s) == 1)
            ends = np.flatnonzero(np.diff(s) == -1) - 1
            out.append(
                (name, [(float(self.time[a]), float(self.time[b])) for a, b in zip(starts, ends)])
            )
        return out


class Walker:
    """A body carrying legs, all driven by one crank drive (each leg at its own phase).

    Parameters
    ----------
    legs : sequence of Leg
    cg : (x, y)
        Ground projection of the centre of gravity in the body frame.
    ground_tol : float, optional
        A foot within this height of the ground is in stance; default 0.25 % of the largest
        foot-path extent.
    body_underside : float, optional
        Height of the body's underside in the body frame, for the body clearance (default: the
        lowest mount).
    """

    def __init__(
        self,
        legs: Sequence[Leg],
        cg: Sequence[float] = (0.0, 0.0),
        ground_tol: float | None = None,
        body_underside: float | None = None,
    ) -> None:
        if isinstance(legs, (str, bytes)) or not hasattr(legs, "__iter__"):
            raise TypeError(f"legs must be a sequence of Leg, got {type(legs).__name__}")
        self.legs = tuple(legs)
        if not self.legs:
            raise LinkageError("a walker needs at least one leg")
        for leg in self.legs:
            if not isinstance(leg, Leg):
                raise TypeError(f"legs must be Leg, got {type(leg).__name__}")
        names = [leg.name for leg in self.legs]
        if len(set(names)) != len(names):
            raise LinkageError(f"leg names must be unique, got {names}")
        for leg in self.legs:
            if not isinstance(leg, Leg):
                raise TypeError(f"legs must be Leg, got {type(leg).__name__}")
        self.cg = as_point(cg, "cg")
        self.ground_tol = None if ground_tol is None else as_finite(ground_tol, "ground_tol")
        self.body_underside = (
            min(leg.mount[2] for leg in self.legs)
            if body_underside is None
            else as_finite(body_underside, "body_underside")
        )

    def with_phases(self, phases: Sequence[float]) -> Walker:
        """Return the same walker with new crank phases (one per leg).

        Parameters
        ----------
        phases : sequence of float
            Each leg's crank phase (rad), in leg order.

        Returns
        -------
        Walker
            A new walker; this one is unchanged.

        Raises
        ------
        LinkageError
            For a wrong number of phases or a non-finite phase.
        TypeError
            If ``phases`` is not a sequence of numbers.

        Examples
        --------
        Thesis 1's quadruped in a crawl instead of its trot, which it cannot hold statically:

        >>> import numpy as np, linkage
        >>> q = linkage.catalog.quadruped_hoecken()
        >>> crawl = q.with_phases(linkage.gait_phases("crawl", ["A", "B", "C", "D"]))
        >>> round(crawl.simulate(np.linspace(0, 2 * np.pi, 721)).min_margin, 3)
        -40.0
        >>> q.with_phases([0.0, 1.0])
        Traceback (most recent call last):
        ...
        linkage.LinkageError: need 4 phases, got 2
        """
        if isinstance(phases, (str, bytes)) or not hasattr(phases, "__len__"):
            raise TypeError(f"phases must be a sequence of numbers, got {type(phases).__name__}")
        if len(phases) != len(self.legs):
            raise LinkageError(f"need {len(self.legs)} phases, got {len(phases)}")
        legs = [
            replace(leg, phase=as_finite(p, f"phases[{k}]"))
            for k, (leg, p) in enumerate(zip(self.legs, phases))
        ]
        return Walker(legs, self.cg, self.ground_tol, self.body_underside)

    @property
    def phases(self) -> Array:
        """Crank phase of each leg."""
        return np.array([leg.phase for leg in self.legs])

    def leg_labels(self) -> tuple[str, ...]:
        """Name each leg by side and position, in leg order (see :func:`leg_labels`).

        Returns
        -------
        tuple of str
            ``L1``, ``R1``, … for the legs in order.

        Examples
        --------
        >>> import linkage
        >>> linkage.catalog.quadruped_hoecken().leg_labels()   # legs A, B, C, D
        ('L1', 'R1', 'L2', 'R2')
        """
        return leg_labels([leg.mount for leg in self.legs])

    def simulate(
        self,
        theta: ArrayLike | None = None,
        omega: float = 1.0,
        *,
        time: ArrayLike | None = None,
        drive: Drive | None = None,
        per_leg_time: bool = False,
    ) -> Simulation:
        """Simulate at crank angles ``theta`` or at times ``time`` of a ``drive``.

        At crank angles, the crank turns at the constant speed ``omega`` (rad/s).

        With ``per_leg_time`` (a periodic drive with a ``period``, such as a crank schedule),
        each leg runs the drive shifted in time by its phase's share of the period instead of
        adding the phase to the angle: how one would run one motor per leg on the same schedule.

        Parameters
        ----------
        theta : array_like, optional
            Crank angles (rad) of the drive, scalar or 1-D; or give ``time`` and ``drive``.
        omega : float, default 1.0
            Constant crank speed (rad/s, non-zero) with ``theta``: the times are ``theta/omega``.
        time : array_like, optional
            Times (s), with ``drive``.
        drive : Drive, optional
            The crank's drive (:mod:`linkage.drive`), with ``time``.
        per_leg_time : bool, default False
            Shift each leg's drive in time by its phase (a periodic drive only).

        Returns
        -------
        Simulation
            Feet, stance, ground, support polygons, stability margins, body motion and slip per
            sample.

        Raises
        ------
        LinkageError
            If a leg cannot be assembled at a sample (a walker's legs must turn fully), for
            ``omega`` 0, both or neither of ``theta`` and ``time``, no sample, or
            ``per_leg_time`` with a drive that has no period.
        TypeError
            With neither ``theta`` nor ``time`` and ``drive``, or a drive without ``angles``.
        MemoryError
            When the simulation would not fit in memory.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> q = linkage.catalog.quadruped_hoecken()
        >>> sim = q.simulate(np.linspace(0, 2 * np.pi, 721))
        >>> sim.feet.shape, round(sim.min_margin, 3)
        ((721, 4, 3), 3.997)

        A leg that cannot turn fully cannot walk:

        >>> evans = linkage.Walker([linkage.Leg("E", linkage.catalog.evans_b(), (0, 0, 0))])
        >>> evans.simulate(np.linspace(0, 2 * np.pi, 9))
        Traceback (most recent call last):
        ...
        linkage.LinkageError: leg 'E' cannot be assembled over the whole cycle
        """
        per_leg_time = as_flag(per_leg_time, "per_leg_time")
        if drive is not None or time is not None:
            if drive is None or time is None or theta is not None:
                raise LinkageError("give either theta, or time= with drive=")
            if not hasattr(drive, "angles"):
                raise TypeError(f"drive must have an angles(t) method, got {type(drive).__name__}")
            t, _ = as_angles(time, "time")
            self._check_size(len(t))
            th, w, _ = drive.angles(t)
        else:
            if theta is None:
                raise TypeError("simulate() needs theta or time= and drive=")
            th, _ = as_angles(theta, "theta")
            w0 = as_finite(omega, "omega")
            if w0 == 0:
                raise LinkageError("omega must be non-zero")
            self._check_size(len(th))
            with np.errstate(over="ignore"):
                t, w = th / w0, np.full_like(th, w0)
            if not np.isfinite(t).all():
                raise LinkageError(f"times theta/omega overflow a float (omega = {w0!r})")
        if len(th) == 0:
            raise LinkageError("simulate() needs at least one sample")
        period = 0.0
        if per_leg_time:
            if drive is None or not hasattr(drive, "period"):
                raise LinkageError("per_leg_time needs a periodic drive (with a period)")
            period = as_finite(drive.period, "drive.period")
        n, m = len(th), len(self.legs)
        feet = np.empty((n, m, 3))
        vel = np.empty((n, m, 3))
        for i, leg in enumerate(self.legs):
            if per_leg_time:
                shift = leg.phase / (2 * math.pi) * period
                assert drive is not None  # checked above with per_leg_time
                thi, wi, _ = drive.angles(t + shift)
                feet[:, i], vel[:, i] = replace(leg, phase=0.0).feet(thi, wi)
            else:
                feet[:, i], vel[:, i] = leg.feet(th, w)
        return self._evaluate(th, t, feet, vel)

    def _evaluate(self, th: Array, t: Array, feet: Array, vel: Array) -> Simulation:
        """Ground contact, body motion, support polygons, margins and slip from foot tracks."""
        n, m = feet.shape[:2]
        bad = ~(np.isfinite(feet).all(axis=2) & np.isfinite(vel).all(axis=2))
        if bad.any():
            k, i = (int(x) for x in np.argwhere(bad)[0])
            raise LinkageError(
                f"leg {self.legs[i].name!r}: the foot's position or velocity is not finite at "
                f"crank angle {float(th[k])!r} (not representable in float64 at this scale)"
            )
        z = feet[:, :, 2]
        ground = float(z.min())
        extent = float(np.ptp(feet.reshape(-1, 3), axis=0).max())
        tol = self.ground_tol if self.ground_tol is not None else 2.5e-3 * extent
        # Stance by the core's leg figures (the same code as the design search's).
        stance = np.empty((n, m), dtype=bool)
        gaits = []
        for i in range(m):
            path = np.ascontiguousarray(np.stack([feet[:, i, 0], z[:, i]], axis=1))
            rate = np.ascontiguousarray(np.stack([vel[:, i, 0], vel[:, i, 2]], axis=1))
            g, stance[:, i] = _core.walking.leg_gait(path, rate, tol, ground)
            gaits.append(g)
        vx = np.where(stance, vel[:, :, 0], np.nan)
        with np.errstate(invalid="ignore"), _quiet():
            body_v = -np.nanmean(vx, axis=1)
            spread = np.where(
                stance.sum(axis=1) >= 2, np.nanmax(vx, axis=1) - np.nanmin(vx, axis=1), 0.0
            )
        bv = np.nan_to_num(body_v)
        with np.errstate(over="ignore", invalid="ignore"):
            body_x = np.r_[0.0, np.cumsum((0.5 * bv[1:] + 0.5 * bv[:-1]) * np.diff(t))]
        if not np.isfinite(body_x).all():
            k = int(np.argmin(np.isfinite(body_x)))
            raise LinkageError(
                f"the body's travel is not representable in float64 by crank angle "
                f"{float(th[k])!r} (times {float(t[0])!r} … {float(t[-1])!r}): sample a shorter "
                f"span of the crank"
            )
        # Support polygon: pad corners of every stance foot.
        half = np.array([leg.pad / 2 for leg in self.legs])
        corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float)
        pts = feet[:, :, None, :2] + corners[None, None] * half[None, :, None, None]
        pts = np.where(stance[:, :, None, None], pts, np.nan).reshape(n, 4 * m, 2)
        cg = np.ascontiguousarray(np.broadcast_to(np.asarray(self.cg), (n, 2)))
        margin, hull, count = _core.walking.support_margins(np.ascontiguousarray(pts), cg)
        # No foot on the ground: no support at all, the worst possible margin.
        margin = np.where(count == 0, -np.inf, margin)
        return Simulation(
            theta=th,
            time=t,
            legs=tuple(leg.name for leg in self.legs),
            feet=feet,
            foot_velocity=vel,
            stance=stance,
            ground=ground,
            body_velocity=body_v,
            body_position=body_x,
            support=hull,
            support_count=count,
            margin=margin,
            slip_velocity=vx + body_v[:, None],
            spread=spread,
            gaits=tuple(gaits),
        )

    def body_clearance(self, samples: int = 721) -> float:
        """Height of the body's underside above the ground (the obstacle the body clears).

        Parameters
        ----------
        samples : int, default 721
            Crank angles over one turn at which the ground (the lowest foot) is found.

        Returns
        -------
        float
            ``body_underside`` minus the ground's height.

        Raises
        ------
        LinkageError
            For ``samples`` below 1 or a leg that does not assemble.

        Examples
        --------
        >>> import linkage
        >>> linkage.catalog.quadruped_hoecken().body_clearance()
        60.0
        """
        samples = as_count(samples, "samples")
        self._check_size(samples)
        sim = self.simulate(np.linspace(0, 2 * math.pi, samples))
        return float(self.body_underside - sim.ground)

    def search_phases(
        self,
        objective: Objective = "margin",
        step: float = math.radians(15.0),
        samples: int = 360,
        rounds: int = 3,
        max_evals: int = 5000,
    ) -> tuple[Array, float]:
        """Search the crank phases that maximise the stability margin or minimise the foot slip.

        The same as :func:`linkage.gait_search.search_phases` with this walker; see there.

        Parameters
        ----------
        objective, step, samples, rounds, max_evals
            As :func:`linkage.gait_search.search_phases`.

        Returns
        -------
        phases : ndarray, shape (legs,)
            The best crank phases found (radians).
        value : float
            Their minimum stability margin or foot slip per cycle.

        Raises
        ------
        LinkageError, TypeError
            As :func:`linkage.gait_search.search_phases`.

        Examples
        --------
        >>> import math, numpy as np, linkage
        >>> q = linkage.catalog.quadruped_hoecken()
        >>> phases, slip = q.search_phases("slip", step=math.pi / 2, samples=64)
        >>> np.degrees(phases).round(6), round(slip, 3)
        (array([  0., 180., 180.,   0.]), 4.229)
        >>> q.search_phases("speed")
        Traceback (most recent call last):
        ...
        linkage.LinkageError: objective must be one of 'margin', 'slip', got 'speed'
        """
        objective = as_choice(objective, "objective", get_args(Objective))
        step = as_finite(step, "step")
        samples = as_count(samples, "samples")
        rounds = as_count(rounds, "rounds", 0)
        max_evals = as_count(max_evals, "max_evals", 0)
        turns = 2 * math.pi / step if step > 0 else math.inf
        if not (math.isfinite(turns) and turns < 2**53):
            raise LinkageError(
                f"step must divide a full turn into at most 2**53 parts, got {step!r}"
            )
        g = round(turns)
        if g < 2 or abs(g * step - 2 * math.pi) > 1e-9:
            raise LinkageError("step must divide a full turn (2π/step a whole number ≥ 2)")
        per = max(1, -(-samples // g))
        n = g * per
        self._check_size(n)
        theta = np.linspace(0, 2 * math.pi, n, endpoint=False)
        # Every leg's track at phase 0 over one turn; a phase on the grid is a cyclic shift.
        base = [replace(leg, phase=0.0).feet(theta, np.ones(n)) for leg in self.legs]
        t = theta.copy()

        def score(k: Sequence[int]) -> float:
            feet = np.stack([np.roll(base[i][0], -k[i] * per, axis=0) for i in range(len(k))], 1)
            vel = np.stack([np.roll(base[i][1], -k[i] * per, axis=0) for i in range(len(k))], 1)
            sim = self._evaluate(theta, t, feet, vel)
            if objective == "margin":
                return sim.min_margin
            if sim.min_margin < 0:
                return -math.inf
            return -float(sim.slip_distance.sum())

        start = [round(p / step) % g for p in self.phases]
        free = len(self.legs) - 1
        exhaustive = g**free <= max_evals
        if not exhaustive and rounds * free * g > max(max_evals, 1):
            # Bounded time: the coordinate search tries every grid phase of every leg per round.
            raise LinkageError(
                f"step {step:g} gives {g} phases per leg: the search would need "
                f"{rounds * free * g} evaluations, more than max_evals = {max_evals}"
            )
        if exhaustive:
            # Exhaustive over the grid (the first leg fixed).
            best_k, best_val = start, score(start)
            for combo in itertools.product(range(g), repeat=free):
                k = [start[0], *combo]
                v = score(k)
                if v > best_val + 1e-12:
                    best_k, best_val = k, v
        else:
            best_k, best_val = start, score(start)
            for _ in range(rounds):
                improved = False
                for i in range(1, len(self.legs)):
                    for c in range(g):
                        k = list(best_k)
                        k[i] = c
                        v = score(k)
                        if v > best_val + 1e-12:
                            best_k, best_val, improved = k, v, True
                if not improved:
                    break
        phases = np.array([k * step for k in best_k])
        return phases, best_val if objective == "margin" else -best_val

    def _check_size(self, n: int) -> None:
        """Refuse a simulation of ``n`` samples that cannot fit in memory.

        Per sample and leg: positions, velocities, support corners and the sweep's arrays (about
        60 float64 values).
        """
        legs = len(self.legs)
        check_memory(n * max(1, legs) * 8 * 60, f"a walker simulation of {n} samples × {legs} legs")


def leg_labels(mounts: Sequence[Sequence[float]]) -> tuple[str, ...]:
    """Name legs by side and position from their body-frame mounts ``(x, y, z)``.

    ``L`` for a mount left of the midline (y > 0), ``R`` right of it (y < 0), ``M`` on it; numbered
    1, 2, … from the front (largest x) to the rear on each side. Mounts at the same x keep their
    given order.

    Parameters
    ----------
    mounts : sequence of (x, y, z)
        The legs' mounts in the body frame (x forward, y left).

    Returns
    -------
    tuple of str
        One label per mount, in the given order.

    Raises
    ------
    LinkageError
        For a mount that is not three finite numbers.

    Examples
    --------
    >>> from linkage.walker import leg_labels
    >>> leg_labels([(0.04, 0.02, 0), (-0.02, 0.02, 0), (0.04, -0.02, 0), (-0.08, 0.02, 0)])
    ('L1', 'L2', 'R1', 'L3')
    >>> leg_labels([(0, 0)])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: mounts[0] must be (x, y, z), got (0, 0)
    """
    sides = []
    for k, m in enumerate(mounts):
        if isinstance(m, (str, bytes)) or len(m) != 3:
            raise LinkageError(f"mounts[{k}] must be (x, y, z), got {m!r}")
        y = as_finite(m[1], f"mounts[{k}][1]")
        sides.append("L" if y > 0 else "R" if y < 0 else "M")
    labels = [""] * len(sides)
    for side in "LRM":
        ks = [k for k, s in enumerate(sides) if s == side]
        ks.sort(key=lambda k: -as_finite(mounts[k][0], f"mounts[{k}][0]"))
        for pos, k in enumerate(ks, start=1):
            labels[k] = f"{side}{pos}"
    return tuple(labels)


class _quiet:
    """Silence numpy's all-NaN slice warnings (swing-only samples are expected)."""

    def __enter__(self) -> None:

        self._w = warnings.catch_warnings()
        self._w.__enter__()
        warnings.simplefilter("ignore", RuntimeWarning)

    def __exit__(self, *exc: Any) -> None:
        self._w.__exit__(*exc)


GAITS = {
    "tripod": {"L1": 0.0, "R2": 0.0, "L3": 0.0, "R1": 0.5, "L2": 0.5, "R3": 0.5},
    # Wilson's rules: a wave of protractions runs hind to front on each side, contralateral
    # legs of a segment in antiphase. Wave: one leg swings at a time (duty factor 5/6).
    "wave": {"L3": 0.0, "L2": 1 / 6, "L1": 2 / 6, "R3": 3 / 6, "R2": 4 / 6, "R1": 5 / 6},
    # Ripple: the wave on each side with a third of a cycle between neighbours.
    "ripple": {"L3": 0.0, "L2": 1 / 3, "L1": 2 / 3, "R3": 0.5, "R2": 5 / 6, "R1": 1 / 6},
    # Quadrupeds, legs A (left front), B (right front), C (left hind), D (right hind).
    "diagonal": {"A": 0.0, "D": 0.0, "B": 0.5, "C": 0.5},
    "crawl": {"C": 0.0, "A": 0.25, "D": 0.5, "B": 0.75},
}
"""The named gaits of :func:`gait_phases`: by gait, each leg's share of the cycle by name."""


def gait_phases(gait: str, legs: Sequence[str]) -> Array:
    """Crank phases (rad) of a named gait for the given leg names.

    Gaits: "tripod" ({L1, R2, L3} against {R1, L2, R3}), "wave" and "ripple" (Wilson's rules),
    for legs L1–L3 / R1–R3 front to hind; "diagonal" (trot: A & D against B & C, thesis 1) and
    "crawl" for quadruped legs A–D. A leg's phase is ``−2π × (its share of the cycle)``: a leg
    whose protraction comes later runs behind.

    Parameters
    ----------
    gait : str
        One of :data:`GAITS`: ``"tripod"``, ``"wave"``, ``"ripple"``, ``"diagonal"``,
        ``"crawl"``.
    legs : sequence of str
        Leg names, as the gait's table names them.

    Returns
    -------
    ndarray, shape (len(legs),)
        The phases (rad), in the order of ``legs``.

    Raises
    ------
    LinkageError
        For an unknown gait or a leg the gait has no phase for.
    TypeError
        For a gait or leg name that is not a str.

    Examples
    --------
    >>> import linkage
    >>> linkage.gait_phases("diagonal", ["A", "B", "C", "D"]).round(6)
    array([-0.      , -3.141593, -3.141593, -0.      ])
    >>> linkage.gait_phases("tripod", ["A"])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: gait 'tripod' has no phase for legs ['A']
    """
    if not isinstance(gait, str):
        raise TypeError(f"gait must be a name (str), got {type(gait).__name__}")
    if isinstance(legs, (str, bytes)) or not hasattr(legs, "__iter__"):
        raise TypeError(f"legs must be a sequence of leg names, got {type(legs).__name__}")
    legs = list(legs)
    for leg in legs:
        if not isinstance(leg, str):
            raise TypeError(f"leg names must be str, got {type(leg).__name__}")
    if gait not in GAITS:
        raise LinkageError(f"unknown gait {gait!r}; choose from {', '.join(GAITS)}")
    table = GAITS[gait]
    missing = [leg for leg in legs if leg not in table]
    if missing:
        raise LinkageError(f"gait {gait!r} has no phase for legs {missing}")
    return np.array([-2 * math.pi * table[leg] for leg in legs])


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Leg": Leg, "Simulation": Simulation, "Walker": Walker}
for _cls in __test__.values():
    _cls.__module__ = "linkage.walker"
