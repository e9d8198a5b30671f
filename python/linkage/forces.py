"""Kinetostatics: driver torque and joint reactions from link masses, inertias, gravity and
external loads — by Newton–Euler (every joint force) and, as a cross-check, by the power method.

>>> import numpy as np, linkage
>>> from linkage.forces import LinkMass, PointLoad, forces
>>> leg = linkage.FourBar(ground=0.020, crank=0.010, coupler=0.025, rocker=0.025, point=(0.050, 0))
>>> f = forces(leg, np.radians(np.arange(360.0)), omega=-20 * 2 * np.pi / 60,
...            masses={"crank": LinkMass(0.0036, (0.005, 0), 0.122432e-6),
...                    "coupler": LinkMass(0.0210, (0.0312566, 0), 2.17781e-6),
...                    "rocker": LinkMass(0.0060, (0.0125, 0), 0.774427e-6)},
...            gravity=(0, 0), loads=[PointLoad("coupler", "P", (0.5 * 9.81, 0))])
>>> bool(np.allclose(f.torque, f.power_torque, atol=1e-12))
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._arrays import (
    UnknownNameError,
    as_angles,
    as_finite,
    as_point,
    as_rate,
    as_real_array,
)
from linkage._core import LinkageError
from linkage._fourbar import FourBar
from linkage._mechanism import Mechanism
from linkage.drive import Drive

Array = NDArray[np.float64]


@dataclass(frozen=True)
class LinkMass:
    """Mass properties of a link: ``mass``, centre of mass ``centre = (along, left)`` in the
    link's frame (from its first joint toward its second, as in ``Mechanism.link_members``), and
    the moment of ``inertia`` about the centre of mass."""

    mass: float
    centre: tuple[float, float] = (0.0, 0.0)
    inertia: float = 0.0

    def __post_init__(self) -> None:
        m = as_finite(self.mass, "mass")
        if m < 0:
            raise LinkageError(f"mass must be non-negative, got {m}")
        as_point(self.centre, "centre")
        if as_finite(self.inertia, "inertia") < 0:
            raise LinkageError(f"inertia must be non-negative, got {self.inertia}")


@dataclass(frozen=True)
class PointLoad:
    """An external force on ``link`` applied at its joint ``joint`` — a pair ``(fx, fy)`` or an
    ``(N, 2)`` array, one per sample — and an optional torque on the link."""

    link: str
    joint: str
    force: ArrayLike = (0.0, 0.0)
    torque: ArrayLike = 0.0


@dataclass
class Forces:
    """Driver torque and joint reactions along a sweep (NaN where it cannot assemble or the
    statics are singular, ``valid`` False)."""

    theta: Array
    torque: Array
    """Driver torque on the crank (Newton–Euler), per sample."""
    power_torque: Array
    """Driver torque by the power method (no joint forces), per sample."""
    valid: NDArray[np.bool_]
    reactions: Array
    """Force on the ``to`` link from the ``from`` link at each joint, shape (N, R, 2)."""
    reaction_links: list[tuple[str, str, str]]
    """``(joint, from, to)`` for each reaction column."""
    time: Array | None = field(default=None)

    def reaction(self, joint: str, to: str | None = None) -> Array:
        """Force at ``joint`` (on link ``to``, if the joint joins more than two), shape (N, 2)."""
        cols = [
            k for k, (j, _, t) in enumerate(self.reaction_links) if j == joint and to in (None, t)
        ]
        if not cols:
            raise UnknownNameError(
                f"no reaction at joint {joint!r}" + (f" on {to!r}" if to else "")
            )
        return self.reactions[:, cols[0]]

    @property
    def mean_abs_torque(self) -> float:
        """Mean of ``|torque|`` over the valid samples (the thesis 2 'average torque'); NaN when
        no sample is valid."""
        t = np.abs(self.torque[self.valid])
        return float(np.mean(t)) if t.size else math.nan

    @property
    def peak_torque(self) -> float:
        """Largest ``|torque|`` over the valid samples; NaN when no sample is valid."""
        t = np.abs(self.torque[self.valid])
        return float(np.max(t)) if t.size else math.nan


def _rate(value: Any, name: str, n: int) -> Array:
    arr = as_rate(value, name, n)
    if arr is None:
        raise LinkageError(f"{name} is required")
    return arr


def forces(
    linkage_obj: FourBar | Mechanism,
    theta: ArrayLike | None = None,
    omega: ArrayLike | None = None,
    alpha: ArrayLike = 0.0,
    *,
    time: ArrayLike | None = None,
    drive: Drive | None = None,
    masses: Mapping[str, LinkMass | Sequence[Any]],
    gravity: Sequence[float] = (0.0, -9.81),
    loads: Sequence[PointLoad] = (),
) -> Forces:
    """Newton–Euler kinetostatics of a one-degree-of-freedom linkage along a sweep.

    Give crank angles with ``omega`` (rad/s, scalar or per angle) and ``alpha``, or ``time=``
    with ``drive=``. ``masses`` maps every moving link's name (``linkage_obj.links`` minus the
    ground; a FourBar's are crank, coupler, rocker) to a :class:`LinkMass` or a tuple
    ``(mass, (along, left), inertia)``; none may be left out — use ``LinkMass(0)`` for a
    massless link.
    """
    mech = linkage_obj.mechanism() if isinstance(linkage_obj, FourBar) else linkage_obj
    if not isinstance(mech, Mechanism):
        raise TypeError(f"expected a FourBar or Mechanism, got {type(linkage_obj).__name__}")
    times = None
    if drive is not None or time is not None:
        if drive is None or time is None or theta is not None or omega is not None:
            raise LinkageError("give either theta with omega, or time= with drive=")
        if not hasattr(drive, "angles"):
            raise TypeError(f"drive must have an angles(t) method, got {type(drive).__name__}")
        times, _ = as_angles(time, "time")
        theta, omega, alpha = drive.angles(times)
    if theta is None or omega is None:
        raise LinkageError("forces need crank angles and speeds: theta with omega, or a drive")
    th, _ = as_angles(theta, "theta")
    n = len(th)
    w = np.broadcast_to(_rate(omega, "omega", n), (n,)).astype(np.float64)
    a = np.broadcast_to(_rate(alpha, "alpha", n), (n,)).astype(np.float64)
    links = mech.links
    if not isinstance(masses, Mapping):
        raise TypeError(
            f"masses must be a mapping of link name to LinkMass, got {type(masses).__name__}"
        )
    unknown = sorted(set(masses) - set(links[1:]))
    if unknown:
        raise LinkageError(
            f"masses given for unknown links {unknown}; links are {', '.join(links[1:])}"
        )
    missing = [name for name in links[1:] if name not in masses]
    if missing:
        raise LinkageError(
            f"masses missing for links {missing}: give every moving link (LinkMass(0) if massless)"
        )
    inertia = [(0.0, 0.0, 0.0, 0.0)]
    for name in links[1:]:
        mm = masses[name]
        lm = mm if isinstance(mm, LinkMass) else LinkMass(*mm)
        inertia.append(
            (float(lm.mass), float(lm.centre[0]), float(lm.centre[1]), float(lm.inertia))
        )
    g = as_point(gravity, "gravity")
    core_loads = []
    for load in loads:
        if not isinstance(load, PointLoad):
            raise TypeError(f"loads must be PointLoad, got {type(load).__name__}")
        if not isinstance(load.link, str) or not isinstance(load.joint, str):
            raise TypeError("a load's link and joint must be names (str)")
        if load.link not in links:
            raise LinkageError(f"load on unknown link {load.link!r}; links are {', '.join(links)}")
        if load.joint not in mech.joint_names:
            raise LinkageError(f"load at unknown joint {load.joint!r}")
        f = as_real_array(load.force, "load force").astype(np.float64)
        if f.shape not in ((2,), (n, 2)) or not np.isfinite(f).all():
            raise LinkageError(
                f"load force must be a finite pair or ({n}, 2) array, got shape {f.shape}"
            )
        tq0 = as_real_array(load.torque, "load torque").astype(np.float64)
        if tq0.shape not in ((), (1,), (n,)):
            raise LinkageError(
                f"load torque must be a scalar or have one value per angle ({n}), "
                f"got shape {tq0.shape}"
            )
        tq = np.broadcast_to(tq0, (n,))
        if not np.isfinite(tq).all():
            raise LinkageError("load torque must be finite")
        core_loads.append(
            (
                links.index(load.link),
                mech.joint_names.index(load.joint),
                np.ascontiguousarray(np.broadcast_to(f, (n, 2))),
                np.ascontiguousarray(tq),
            )
        )
    raw = _core.forces(
        mech._core, th, np.ascontiguousarray(w), np.ascontiguousarray(a), inertia, g, core_loads
    )
    names = mech.joint_names
    return Forces(
        theta=th,
        torque=raw["torque"],
        power_torque=raw["power_torque"],
        valid=raw["valid"],
        reactions=raw["reactions"],
        reaction_links=[(names[j], links[f], links[t]) for j, f, t in raw["reaction_links"]],
        time=times,
    )
