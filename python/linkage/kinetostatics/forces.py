"""Kinetostatics: driver torque and joint reactions from masses, inertias, gravity and loads.

Solved by Newton–Euler (every joint force) and, as a cross-check, by the power method.

>>> import numpy as np, linkage
>>> from linkage.forces import LinkMass, PointLoad, joint_forces
>>> leg = linkage.FourBar(ground=0.020, crank=0.010, coupler=0.025, rocker=0.025, point=(0.050, 0))
>>> f = joint_forces(leg, np.radians(np.arange(360.0)), omega=-20 * 2 * np.pi / 60,
...                  masses={"crank": LinkMass(0.0036, (0.005, 0), 0.122432e-6),
...                          "coupler": LinkMass(0.0210, (0.0312566, 0), 2.17781e-6),
...                          "rocker": LinkMass(0.0060, (0.0125, 0), 0.774427e-6)},
...                  gravity=(0, 0), loads=[PointLoad("coupler", "P", (0.5 * 9.81, 0))])
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
from linkage._core import LinkageError
from linkage._shared.arrays import (
    UnknownNameError,
    as_angles,
    as_finite,
    as_point,
    as_rate,
    as_real_array,
)
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Drive, Mechanism

__all__ = ["Forces", "LinkMass", "PointLoad", "joint_forces"]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class LinkMass:
    """Mass properties of a link: its ``mass``, centre of mass and moment of inertia.

    The centre of mass ``centre = (along, left)`` is in the link's frame (from its first joint
    toward its second, as in ``Mechanism.link_members``); ``inertia`` is the moment about it.
    """

    mass: float
    centre: tuple[float, float] = (0.0, 0.0)
    inertia: float = 0.0

    def __post_init__(self) -> None:
        """Check that mass and inertia are finite and non-negative, the centre a finite pair."""
        m = as_finite(self.mass, "mass")
        if m < 0:
            raise LinkageError(f"mass must be non-negative, got {m}")
        as_point(self.centre, "centre")
        if as_finite(self.inertia, "inertia") < 0:
            raise LinkageError(f"inertia must be non-negative, got {self.inertia}")


@dataclass(frozen=True)
class PointLoad:
    """An external force on ``link`` applied at its joint ``joint``, and an optional torque.

    The force is a pair ``(fx, fy)`` or an ``(N, 2)`` array, one per sample; the torque acts on the
    link.
    """

    link: str
    joint: str
    force: ArrayLike = (0.0, 0.0)
    torque: ArrayLike = 0.0


@dataclass
class Forces:
    """Driver torque and joint reactions along a sweep.

    NaN where it cannot assemble or the statics are singular (``valid`` False).
    """

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
        """Return the force at ``joint`` on the link ``to``, per sample.

        Parameters
        ----------
        joint : str
            The joint's name.
        to : str, optional
            The link the force acts on; needed only where the joint joins more than two links
            (else the first reaction at the joint, as listed in :attr:`reaction_links`).

        Returns
        -------
        ndarray, shape (N, 2)
            The force; NaN at samples that are not :attr:`valid`.

        Raises
        ------
        LinkageError
            (also a ``KeyError``) When there is no reaction at ``joint`` on ``to``.

        Examples
        --------
        >>> import linkage
        >>> from linkage.forces import LinkMass, joint_forces
        >>> m = {name: LinkMass(1.0) for name in ("crank", "coupler", "rocker")}
        >>> f = joint_forces(linkage.catalog.hoecken(), [0.0], omega=1.0, masses=m)
        >>> f.reaction_links[2], f.reaction("A", "coupler")
        (('A', 'crank', 'coupler'), array([[-10.  ,   9.81]]))
        >>> f.reaction("Z")
        Traceback (most recent call last):
        ...
        linkage._arrays.UnknownNameError: no reaction at joint 'Z'
        """
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
        """Mean of ``|torque|`` over the valid samples (the thesis 2 'average torque').

        NaN when no sample is valid.
        """
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


def joint_forces(
    linkage_obj: FourBar | Mechanism,
    theta: ArrayLike | None = None,
    omega: ArrayLike | None = None,
    alpha: ArrayLike = 0.0,
    *,
    time: ArrayLike | None = None,
    drive: Drive | None = None,
    masses: Mapping[str, LinkMass | tuple[float, tuple[float, float], float]],
    gravity: Sequence[float] = (0.0, -9.81),
    loads: Sequence[PointLoad] = (),
) -> Forces:
    """Joint reactions and driver torque of a one-degree-of-freedom linkage along a sweep.

    Kinetostatics by Newton–Euler: at each sample the links' inertial forces (from the analytic
    accelerations), gravity and the loads are balanced by the joint reactions and the torque on
    the crank. The torque is also found by the power method (``Forces.power_torque``, no joint
    forces), a cross-check that agrees to round-off.

    Parameters
    ----------
    linkage_obj : FourBar or Mechanism
        The linkage, driven by its crank.
    theta : array_like, optional
        Crank angles (radians), shape ``(N,)`` or a scalar; give ``omega`` with them.
    omega, alpha : array_like, optional
        Crank speed (rad/s) and acceleration (rad/s²), scalars or one per angle; ``alpha``
        defaults to 0.
    time : array_like, optional
        Times (s) at which ``drive`` gives the crank's angle, speed and acceleration; instead of
        ``theta``/``omega``/``alpha``.
    drive : Drive, optional
        A drive (:mod:`linkage.drive`), with ``time``.
    masses : mapping of str to LinkMass or tuple
        Every moving link's name (``linkage_obj.links`` minus the ground; a FourBar's are
        crank, coupler, rocker) to a :class:`LinkMass` or a tuple ``(mass, (along, left),
        inertia)``; none may be left out — use ``LinkMass(0)`` for a massless link.
    gravity : pair of float, default (0, -9.81)
        The acceleration of gravity, in the linkage's units.
    loads : sequence of PointLoad, default ()
        External forces and torques.

    Returns
    -------
    Forces
        Driver torque, power-method torque and joint reactions per sample. A sample where the
        linkage cannot be assembled (or the statics are singular) is NaN with ``valid`` False.

    Raises
    ------
    LinkageError
        For a missing or unknown link in ``masses``, a load on an unknown link or joint, a
        wrong shape or a non-finite value, or both or neither of ``theta`` and ``time``.
    TypeError
        For arguments of the wrong type (a linkage that is not a FourBar or Mechanism, a drive
        without ``angles``, a load that is not a :class:`PointLoad`).

    Examples
    --------
    Evans B turns only within ±1.42 rad: at 3 rad it cannot be assembled and its row is NaN.

    >>> import linkage
    >>> from linkage.forces import LinkMass, joint_forces
    >>> m = {name: LinkMass(1.0) for name in ("crank", "coupler", "rocker")}
    >>> f = joint_forces(linkage.catalog.evans_b(), [0.0, 3.0], omega=1.0, masses=m)
    >>> f.torque.round(6), f.valid
    (array([98.1,  nan]), array([ True, False]))
    >>> f.reaction("B")
    array([[ 0., -0.],
           [nan, nan]])

    Every moving link needs a mass:

    >>> joint_forces(linkage.catalog.evans_b(), [0.0], omega=1.0, masses={"crank": LinkMass(1.0)})
    Traceback (most recent call last):
    ...
    linkage.LinkageError: masses missing for links ['coupler', 'rocker']: give every moving link ...
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
    core_loads = _core_loads(loads, mech, n)
    raw = _core.kinetostatics.forces(
        mech._core, th, np.ascontiguousarray(w), np.ascontiguousarray(a), inertia, g, core_loads
    )
    names = mech.joint_names
    return Forces(
        theta=th,
        torque=raw.torque,
        power_torque=raw.power_torque,
        valid=raw.valid,
        reactions=raw.reactions,
        reaction_links=[(names[j], links[f], links[t]) for j, f, t in raw.reaction_links],
        time=times,
    )


def _core_loads(
    loads: Sequence[PointLoad], mech: Mechanism, n: int
) -> list[tuple[int, int, Array, Array]]:
    """Return the point loads checked, as the core takes them (link, joint, force, torque)."""
    links = mech.links
    core_loads: list[tuple[int, int, Array, Array]] = []
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
    return core_loads


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"LinkMass": LinkMass, "PointLoad": PointLoad, "Forces": Forces}
for _cls in __test__.values():
    _cls.__module__ = "linkage.forces"
