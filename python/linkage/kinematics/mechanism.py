"""``Mechanism``: a linkage as a named program of closed-form constructions."""

from __future__ import annotations

import functools
import math
import threading
from collections.abc import Callable, Iterable, Mapping, Sequence
from collections.abc import Set as AbstractSet
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import (
    UnknownNameError,
    as_angles,
    as_choice,
    as_finite,
    as_length,
    as_point,
    as_rate,
    choices,
)
from linkage._shared.choices import Output, Reach, Side
from linkage.kinematics.mobility import Mobility
from linkage.kinematics.sweep import OUTPUTS, SWEPT_BY, Sweep


# The drives (linkage.drive) are one layer up; what the kinematics takes of one is this protocol.
class Drive(Protocol):
    """Anything that gives crank angle, speed and acceleration against time."""

    def angles(
        self, t: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Return ``(θ, ω, α)``, crank angle, speed and acceleration, at times ``t``.

        Examples
        --------
        Every drive of this module is one, e.g. :class:`ConstantSpeed`:

        >>> from linkage.drive import ConstantSpeed
        >>> ConstantSpeed(omega=2.0, theta0=1.0).angles([0.0, 0.5])
        (array([1., 2.]), array([2., 2.]), array([0., 0.]))
        """
        ...


DEFAULT_OUTPUTS: tuple[Output, ...] = ("point", "joints")


@functools.lru_cache(maxsize=64)
def _asked(out: tuple[str, ...]) -> dict[str, bool]:
    """Return the extension's keywords for ``out`` (computed once per set of outputs)."""
    return dict(
        velocity="velocity" in out,
        acceleration="acceleration" in out,
        instant_centres="instant_centres" in out,
        curvature="curvature" in out,
    )


@functools.lru_cache(maxsize=64)
def _known_outputs(out: tuple[str, ...], has_omega: bool) -> tuple[str, ...]:
    return _check_outputs(out, has_omega)


def _drive_angles(
    theta: ArrayLike | None,
    omega: ArrayLike | None,
    alpha: ArrayLike | None,
    time: ArrayLike | None,
    drive: Drive | None,
) -> tuple[ArrayLike, ArrayLike | None, ArrayLike | None, NDArray[np.float64] | None, bool | None]:
    """Return ``Mechanism.sweep``'s ``theta, omega, alpha``, its times and whether they are scalar.

    With ``time`` and ``drive``, the angles and rates come from ``drive.angles(times)``;
    otherwise ``theta, omega, alpha`` are returned as given, with no times (and None for
    whether the times are scalar).

    Raises
    ------
    LinkageError
        For ``time`` and ``drive`` given alone or with ``theta``, ``omega`` or ``alpha``.
    TypeError
        For a ``drive`` without an ``angles`` method, or with neither ``theta`` nor a drive.
    """
    if drive is not None or time is not None:
        if drive is None or time is None:
            raise LinkageError("a sweep in time needs both time= and drive=")
        if theta is not None or omega is not None or alpha is not None:
            raise LinkageError("give either theta (with omega, alpha) or time= and drive=")
        if not hasattr(drive, "angles"):
            raise TypeError(f"drive must have an angles(t) method, got {type(drive).__name__}")
        times, scalar_time = as_angles(time, "time")
        theta, omega, alpha = drive.angles(times)
        return theta, omega, alpha, times, scalar_time
    if theta is None:
        raise TypeError("sweep() needs theta (crank angles) or time= and drive=")
    return theta, omega, alpha, None, None


def _angles_rates(
    theta: ArrayLike, omega: ArrayLike | None, alpha: ArrayLike | None, scalar_time: bool | None
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None, NDArray[np.float64] | None, bool]:
    """Return ``Mechanism.sweep``'s angles and rates as arrays, and whether the sweep is scalar.

    ``scalar_time`` (None unless the sweep is in time) overrides whether ``theta`` is a scalar.
    """
    # Non-finite angles and rates are refused by the extension, with the same messages.
    th, scalar = as_angles(theta, "theta", finite=False)
    if scalar_time is not None:
        scalar = scalar_time
    n = th.shape[0]
    w = as_rate(omega, "omega", n, finite=False)
    a = as_rate(alpha, "alpha", n, finite=False)
    return th, w, a, scalar


def _asked_pairs(
    out: tuple[str, ...], pairs: Iterable[tuple[str, str]] | None, links: tuple[str, ...]
) -> tuple[dict[str, Any], tuple[tuple[str, str], ...] | None]:
    """Return the extension's keywords for ``out`` and ``pairs``, and the checked link pairs.

    Raises
    ------
    LinkageError
        For ``pairs`` without ``"instant_centres"`` in ``out``, or as :func:`check_pairs` does.
    """
    asked: dict[str, Any] = _asked(out)
    if pairs is None:
        return asked, None
    if not asked["instant_centres"]:
        raise LinkageError("pairs= names instant centres: add 'instant_centres' to outputs")
    link_pairs, index = check_pairs(pairs, links)
    return {**asked, "pairs": index}, link_pairs


def _same_as_before(raw: Mapping[str, Any], more: Mapping[str, Any], column: int | None) -> None:
    """Check a completion (``more``, every joint and flag) against what the sweep returned.

    The completion sweeps the caller's ``theta``, ``omega`` and ``alpha`` arrays again (a copy of
    each at every sweep would cost more than a point-only sweep); the same inputs give the same
    bits, so an output that differs means the caller changed those arrays since.

    Raises
    ------
    LinkageError
        Naming the output that differs, when it does.
    """
    for key, old in raw.items():
        new = more.get(key)
        if new is None or key in ("margin", "regular", "gap"):
            continue
        if column is not None and key in PER_JOINT:
            new = new[:, column : column + 1]
        if new.shape != old.shape or not np.array_equal(new, old, equal_nan=True):
            raise LinkageError(
                f"cannot compute the rest of this sweep: its {key} came out different, so the "
                "theta, omega or alpha array given to sweep() was changed since. Sweep a copy "
                "(theta.copy()), or ask for what you need in outputs at once"
            )


PER_JOINT = ("joints", "velocity", "acceleration", "curvature", "curvature_centres")
"""The outputs with a joint axis (one column in a point-only sweep)."""


def check_pairs(
    pairs: Iterable[tuple[str, str]], links: tuple[str, ...]
) -> tuple[tuple[tuple[str, str], ...], list[tuple[int, int]]]:
    """Validate ``pairs=``: pairs of two different link names; return them and their indices.

    Raises
    ------
    TypeError
        When ``pairs`` is not an iterable of pairs of str.
    LinkageError
        When a pair does not hold two names, names no link (an ``UnknownNameError``, also a
        ``KeyError``) or names one link twice.

    Examples
    --------
    >>> from linkage.kinematics.mechanism import check_pairs
    >>> links = ("ground", "crank", "coupler", "rocker")
    >>> check_pairs([("ground", "coupler"), ("rocker", "crank")], links)
    ((('ground', 'coupler'), ('rocker', 'crank')), [(0, 2), (3, 1)])
    >>> check_pairs([("ground", "frame")], links)
    Traceback (most recent call last):
    ...
    linkage._arrays.UnknownNameError: pairs[0]: no link 'frame'; links are ground, crank, ...
    """
    # Ordered collections only: the centres come in the order of the pairs (no set, no dict).
    unordered = (str, bytes, Mapping, AbstractSet)
    if isinstance(pairs, unordered) or not isinstance(pairs, Iterable):
        raise TypeError(
            f"pairs must be a sequence of (link, link) name pairs, got {type(pairs).__name__}"
        )
    names: list[tuple[str, str]] = []
    index: list[tuple[int, int]] = []
    where = {name: k for k, name in enumerate(links)}
    for q, pair in enumerate(pairs):
        if isinstance(pair, (str, bytes)) or not isinstance(pair, (Sequence, np.ndarray)):
            raise TypeError(f"pairs[{q}] must be a (link, link) pair of names, got {pair!r}")
        two = tuple(pair)
        if len(two) != 2:
            raise LinkageError(f"pairs[{q}] must hold two link names, got {len(two)}")
        a, b = two
        if isinstance(a, np.str_) and isinstance(b, np.str_):
            a, b = str(a), str(b)
        if not isinstance(a, str) or not isinstance(b, str):
            raise TypeError(
                f"pairs[{q}]: links must be named by str, got {type(a).__name__}, "
                f"{type(b).__name__}"
            )
        unknown = [x for x in (a, b) if x not in where]
        if unknown:
            what = ", ".join(repr(x) for x in dict.fromkeys(unknown))
            raise UnknownNameError(
                f"pairs[{q}]: no link{'s' if len(set(unknown)) > 1 else ''} {what}; "
                f"links are {', '.join(links)}"
            )
        if a == b:
            raise LinkageError(f"pairs[{q}]: {a!r} and {b!r} are one link; give two links")
        names.append((a, b))
        index.append((where[a], where[b]))
    return tuple(names), index


def check_outputs(outputs: Iterable[str], omega: Any) -> tuple[str, ...]:
    """Validate ``outputs=``: known names only, and rates only with ``omega``."""
    if type(outputs) is tuple and all(type(o) is str for o in outputs):
        return _known_outputs(outputs, omega is not None)  # the common case, cached
    return _check_outputs(outputs, omega is not None)


def _check_outputs(outputs: Iterable[str], has_omega: bool) -> tuple[str, ...]:
    if isinstance(outputs, str):
        outputs = (outputs,)
    try:
        out = tuple(outputs)
    except TypeError:
        raise TypeError(
            f"outputs must be a sequence of names, got {type(outputs).__name__}"
        ) from None
    for o in out:
        if not isinstance(o, str):
            raise TypeError(f"outputs must be names (str), got {type(o).__name__}")
        if o not in OUTPUTS:
            raise LinkageError(f"unknown output {o!r}; choose from {', '.join(OUTPUTS)}")
    wants_rates = "velocity" in out or "acceleration" in out
    if wants_rates and not has_omega:
        raise LinkageError("outputs 'velocity'/'acceleration' need omega (crank speed, rad/s)")
    return out


class Mechanism:
    r"""A planar linkage built as an ordered program of constructions.

    Each construction places one named joint from joints placed before it, in closed form.

    Constructions: :meth:`fixed` joints, one :meth:`crank` (the driver), RRR :meth:`dyad`\ s,
    RRP :meth:`slider`\ s and :meth:`point`\ s carried by links. A sweep tracks each dyad's
    assembly branch by continuity (see :meth:`sweep`).

    Examples
    --------
    The Hoecken straight-line linkage, foot 50 along the coupler:

    >>> import numpy as np, linkage
    >>> m = linkage.Mechanism()
    >>> m.fixed("O", (0, 0)); m.fixed("C", (20, 0))
    >>> m.crank("A", "O", radius=10)
    >>> m.dyad("B", "A", "C", 25, 25, side="left")
    >>> m.point("P", on=("A", "B"), at=(50, 0))
    >>> s = m.sweep(np.pi)
    >>> s.point.round(12)
    array([20., 40.])
    >>> m.dyad("Q", "A", "C", 1, 1)  # cannot reach: only fails when solved
    >>> bool(m.sweep(0.0).valid)
    False

    A sweep is of the mechanism as it is when called: a joint added later (by this thread or
    another) is not in it, not even in what it computes on first use. Copies (``copy.copy``,
    ``copy.deepcopy``) are independent programs; a mechanism pickles as its program (built
    again through the methods above, which check it) and compares equal to one of the same
    program, names, trace and links (mutable: not hashable):

    >>> import copy, pickle
    >>> pickle.loads(pickle.dumps(m)) == m, copy.deepcopy(m) == m, m == linkage.Mechanism()
    (True, True, False)
    """

    def __init__(self) -> None:
        self._core = _core.Mechanism()
        self._names: list[str] = []
        self._trace: str | None = None
        self._link_names: tuple[str, ...] | None = None
        self._base: Any = None
        self._added: list[tuple[Any, ...]] = []
        self._ops: list[tuple[str, tuple[Any, ...]]] = []
        self._shared = False
        self._lock = threading.RLock()

    @classmethod
    def _from_core(
        cls,
        core: Any,
        names: Sequence[str],
        trace: int,
        links: Sequence[str] | None = None,
        base: Any = None,
    ) -> Mechanism:
        """Wrap a core program made elsewhere.

        ``base`` is the ``FourBar`` or ``SliderCrank`` whose ``mechanism()`` makes ``core``
        again; without one, the program is read back from the core (exactly: a catalogue
        linkage has no slider, whose direction the core normalises).
        """
        m = cls.__new__(cls)  # no empty core program to build and throw away
        m._core = core
        m._names = list(names)
        m._trace = m._names[trace]
        m._link_names = tuple(links) if links is not None else None
        m._base = base
        program = [] if base is not None else core.constructions()
        m._added = _calls(program, m._names)
        m._ops = _ops(program)
        m._shared = False
        m._lock = threading.RLock()
        return m

    # -- copies, pickling, equality ---------------------------------------------------------
    # The core program is shared by copies and by sweeps (whose lazy outputs sweep it again),
    # and copied on write: the next joint added to a mechanism whose core is shared is added
    # to a core rebuilt from the program, so a sweep or a copy never sees a joint added after.
    def __copy__(self) -> Mechanism:
        with self._lock:
            m = type(self).__new__(type(self))
            m.__dict__.update(self.__dict__)
            m._names, m._added, m._ops = list(self._names), list(self._added), list(self._ops)
            m._lock = threading.RLock()
            self._shared = m._shared = True
            return m

    def __deepcopy__(self, memo: dict[int, Any]) -> Mechanism:
        """Return an independent mechanism (its program is copied when either is extended)."""
        return self.__copy__()

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as the program: unpickling builds it again through the building methods."""
        with self._lock:
            return (_rebuild, (self._base, tuple(self._added), self._trace))

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` is a mechanism of the same program, names, trace and links."""
        if not isinstance(other, Mechanism):
            return NotImplemented
        if other is self:
            return True
        return self._value() == other._value()

    def _value(self) -> tuple[Any, ...]:
        """Return what equality compares, as one consistent state."""
        with self._lock:
            return (self.joint_names, self.trace, self.links, self._core.constructions())

    __hash__ = None  # type: ignore[assignment]  # mutable: joints can be added

    # -- building -------------------------------------------------------------------------
    @property
    def joint_names(self) -> tuple[str, ...]:
        """Joint names in program order."""
        return tuple(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __repr__(self) -> str:
        return f"<Mechanism joints {', '.join(self._names)}; trace {self.trace!r}>"

    @property
    def links(self) -> tuple[str, ...]:
        """Names of the rigid links, the ground first: each link's joints joined by '-'.

        A crank is one link, an RRR dyad two (one from each base joint), a slider two (its rod
        and its block, named ``"<joint>-block"``); a carried point joins the link holding its
        frame joints.
        """
        if self._link_names is not None:
            return self._link_names
        with self._lock:
            bodies, joint = self._core.bodies(), list(self._names)
        names = []
        for k, members in enumerate(bodies):
            if k == 0:
                names.append("ground")
            elif len(members) == 1:
                names.append(f"{joint[members[0]]}-block")
            else:
                names.append("-".join(joint[j] for j in members))
        return tuple(names)

    def link_members(self) -> tuple[tuple[str, ...], ...]:
        """Return the joints of each link in :attr:`links`, by name.

        The ground's are its fixed joints.

        Returns
        -------
        tuple of tuple of str
            One tuple of joint names per link, in the order of :attr:`links`.

        Examples
        --------
        >>> import linkage
        >>> m = linkage.catalog.hoecken().mechanism()  # a four-bar: O, C, A, B and the point P
        >>> m.link_members()
        (('O', 'C'), ('O', 'A'), ('A', 'B', 'P'), ('C', 'B'))
        """
        with self._lock:
            bodies, joint = self._core.bodies(), list(self._names)
        return tuple(tuple(joint[j] for j in ms) for ms in bodies)

    def mobility(self) -> Mobility:
        """Kutzbach–Gruebler count of the program's links and pairs (see :func:`mobility`).

        Every construction program with one crank and rigid carried points has one degree of
        freedom, the number of drivers the constructive solver needs; a point framed by joints
        of two different links is counted as a new link pinned to both (over-constrained).

        Returns
        -------
        Mobility
            The counts of links and pairs, and the ``degrees_of_freedom``.

        Examples
        --------
        >>> import linkage
        >>> linkage.catalog.hoecken().mechanism().mobility()
        Mobility(links=4, lower_pairs=4, higher_pairs=0, degrees_of_freedom=1)
        """
        links, lower, higher, dof = self._core.mobility()
        return Mobility(links, lower, higher, dof)

    @property
    def trace(self) -> str | None:
        """Name of the joint reported as ``Sweep.point`` (default: the last joint)."""
        return (
            self._trace if self._trace is not None else (self._names[-1] if self._names else None)
        )

    @trace.setter
    def trace(self, name: str) -> None:
        self._index(name, "trace")
        self._trace = name

    def _index(self, name: Any, role: str) -> int:
        if not isinstance(name, str):
            raise TypeError(f"{role} must be a joint name (str), got {type(name).__name__}")
        try:
            return self._names.index(name)
        except ValueError:
            known = ", ".join(self._names) or "none yet"
            raise LinkageError(
                f"{role}: unknown joint {name!r} (defined so far: {known})"
            ) from None

    def _add(self, name: Any, op: tuple[str, tuple[Any, ...]], call: tuple[Any, ...]) -> None:
        """Add the joint ``name`` by the core's method and arguments ``op``.

        ``call`` is the building method's name and arguments, which pickle it.
        """
        if not isinstance(name, str) or not name:
            raise TypeError(f"joint name must be a non-empty str, got {name!r}")
        with self._lock:
            if name in self._names:
                raise LinkageError(f"joint {name!r} is already defined")
            if self._shared:
                self._core = self._fresh_core()
                self._shared = False
            try:
                getattr(self._core, op[0])(*op[1])
            except LinkageError as exc:
                raise type(exc)(f"joint {name!r}: {exc}") from None
            self._names.append(name)
            self._added.append((call[0], name, *call[1:]))
            self._ops.append(op)

    def _fresh_core(self) -> Any:
        """Return a new core program equal to this one's (the same calls, the same bits)."""
        core = _core.Mechanism() if self._base is None else self._base.mechanism()._core
        for method, args in self._ops:
            getattr(core, method)(*args)
        return core

    def fixed(self, name: str, at: Sequence[float]) -> None:
        """Add a joint fixed to the frame at ``at = (x, y)``.

        Parameters
        ----------
        name : str
            Name of the new joint (non-empty, not already defined).
        at : (x, y)
            Its finite position.

        Examples
        --------
        >>> import linkage
        >>> m = linkage.Mechanism()
        >>> m.fixed("O", (0, 0))
        >>> m.fixed("O", (1, 0))
        Traceback (most recent call last):
        ...
        linkage.LinkageError: joint 'O' is already defined
        """
        x, y = as_point(at, "at")
        self._add(name, ("fixed", (x, y)), ("fixed", (x, y)))

    def crank(self, name: str, centre: str, radius: float, phase: float = 0.0) -> None:
        """Add the driven crank: ``centre + radius·(cos(θ+phase), sin(θ+phase))``.

        Parameters
        ----------
        name : str
            Name of the new joint, the crank pin.
        centre : str
            Centre of the crank's circle, a joint defined before.
        radius : float
            Crank length, positive and finite.
        phase : float, default 0.0
            Angle added to the crank angle ``θ`` of a sweep (radians).

        Examples
        --------
        >>> import numpy as np, linkage
        >>> m = linkage.Mechanism()
        >>> m.fixed("O", (0, 0)); m.crank("A", "O", radius=2, phase=np.pi / 2)
        >>> m.sweep(0.0).point.round(12) + 0.0
        array([0., 2.])
        >>> m.crank("B", "X", radius=1)
        Traceback (most recent call last):
        ...
        linkage.LinkageError: centre: unknown joint 'X' (defined so far: O, A)
        """
        c = self._index(centre, "centre")
        r = as_length(radius, "radius")
        ph = as_finite(phase, "phase")
        self._add(name, ("crank", (c, r, ph)), ("crank", centre, r, ph))

    def dyad(self, name: str, p1: str, p2: str, r1: float, r2: float, side: Side = "left") -> None:
        """Add an RRR dyad: the joint at ``r1`` from ``p1`` and ``r2`` from ``p2``.

        It is initially on ``side`` ("left" or "right") of the directed line ``p1 → p2``.

        Parameters
        ----------
        name : str
            Name of the new joint.
        p1, p2 : str
            Two different joints, defined before.
        r1, r2 : float
            Distances from ``p1`` and ``p2`` (the two links' lengths), positive and finite.
        side : {"left", "right"}, default "left"
            Side of the directed line ``p1 → p2`` the joint starts on.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> m = linkage.Mechanism()
        >>> m.fixed("O", (0, 0)); m.fixed("C", (2, 0)); m.crank("A", "O", 1)
        >>> m.dyad("B", "A", "C", 2, 2, side="right")
        >>> m.sweep(np.pi / 2).point.round(6)
        array([ 0.25838, -0.98324])
        >>> m.dyad("D", "A", "C", 1, 1, side="up")
        Traceback (most recent call last):
        ...
        linkage.LinkageError: side must be one of 'left', 'right', got 'up'
        """
        i, j = self._index(p1, "p1"), self._index(p2, "p2")
        a, b = as_length(r1, "r1"), as_length(r2, "r2")
        side = as_choice(side, "side", choices("side"))
        self._add(name, ("dyad", (i, j, a, b, side)), ("dyad", p1, p2, a, b, side))

    def slider(
        self,
        name: str,
        pivot: str,
        r: float,
        origin: str,
        direction: Sequence[float] | None = None,
        link: tuple[str, str] | None = None,
        angle: float = 0.0,
        reach: Reach = "ahead",
    ) -> None:
        """Add an RRP slider dyad: the joint at ``r`` from ``pivot`` on a line through ``origin``.

        The line has a fixed ``direction`` (dx, dy) or is carried by ``link = (from, to)`` turned
        by ``angle``; ``reach`` "ahead"/"behind" picks the intersection along the direction.

        Parameters
        ----------
        name : str
            Name of the new joint.
        pivot : str
            Joint at distance ``r`` from the new one, defined before.
        r : float
            Distance from ``pivot``, positive and finite.
        origin : str
            Joint the line passes through, defined before.
        direction : (dx, dy), optional
            Fixed direction of the line (not zero). Give exactly one of ``direction`` and
            ``link``.
        link : (from, to), optional
            Two different joints: the line has the direction ``from → to`` turned by ``angle``.
        angle : float, default 0.0
            Angle (radians, counter-clockwise) from ``from → to`` to the line; used with
            ``link``.
        reach : {"ahead", "behind"}, default "ahead"
            Which intersection of the circle about ``pivot`` with the line, along its direction.

        Examples
        --------
        A slider-crank: ``B`` slides along the x axis through ``O``.

        >>> import numpy as np, linkage
        >>> m = linkage.Mechanism()
        >>> m.fixed("O", (0, 0)); m.crank("A", "O", 1)
        >>> m.slider("B", "A", 3, origin="O", direction=(1, 0))
        >>> m.sweep([0.0, np.pi]).point.round(12) + 0.0
        array([[4., 0.],
               [2., 0.]])
        >>> m.slider("D", "A", 3, origin="O")
        Traceback (most recent call last):
        ...
        linkage.LinkageError: slider needs exactly one of direction=(dx, dy) or link=(from, to)
        """
        p, o = self._index(pivot, "pivot"), self._index(origin, "origin")
        length = as_length(r, "r")
        reach = as_choice(reach, "reach", choices("reach"))
        if (direction is None) == (link is None):
            raise LinkageError("slider needs exactly one of direction=(dx, dy) or link=(from, to)")
        if direction is not None:
            dx, dy = as_point(direction, "direction")
            self._add(
                name,
                ("slider", (p, length, o, dx, dy, reach)),
                ("slider", pivot, length, origin, (dx, dy), None, 0.0, reach),
            )
        else:
            assert link is not None
            if len(link) != 2:
                raise LinkageError("link must be a pair of joint names (from, to)")
            f, t = self._index(link[0], "link[0]"), self._index(link[1], "link[1]")
            ang = as_finite(angle, "angle")
            self._add(
                name,
                ("slider_on_link", (p, length, o, f, t, ang, reach)),
                ("slider", pivot, length, origin, None, (link[0], link[1]), ang, reach),
            )

    def point(self, name: str, on: tuple[str, str], at: Sequence[float]) -> None:
        """Add a point carried by the link ``on = (from, to)`` at ``at = (along, left)``.

        The point is ``along`` the direction from → to (length units) and ``left`` of it.

        Parameters
        ----------
        name : str
            Name of the new joint.
        on : (from, to)
            Two different joints, defined before, that frame the carrying link.
        at : (along, left)
            Finite coordinates of the point in that frame.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> m = linkage.Mechanism()
        >>> m.fixed("O", (0, 0)); m.crank("A", "O", 1)
        >>> m.point("P", on=("O", "A"), at=(2, 1))  # 2 along the crank, 1 to its left
        >>> m.sweep(np.pi / 2).point.round(12) + 0.0
        array([-1.,  2.])
        """
        if isinstance(on, str) or len(on) != 2:
            raise LinkageError("on must be a pair of joint names (from, to)")
        f, t = self._index(on[0], "on[0]"), self._index(on[1], "on[1]")
        along, left = as_point(at, "at")
        self._add(
            name,
            ("point", (f, t, along, left)),
            ("point", (on[0], on[1]), (along, left)),
        )

    def add_joint(self, joint: Mapping[str, Any]) -> None:
        """Add one joint given as a scene's joint table (the one reader of that form).

        ``{"kind": "fixed", "name", "at"}``, ``{"kind": "crank", "name", "centre", "radius",
        "phase_deg"?}``, ``{"kind": "dyad", "name", "p1", "p2", "r1", "r2", "side"?}``,
        ``{"kind": "slider", "name", "pivot", "r", "origin", "direction"? | "link"?,
        "angle_deg"?, "reach"?}`` (:meth:`slider`) or ``{"kind": "point", "name", "on", "along",
        "left"?}``.

        Parameters
        ----------
        joint : mapping
            One joint table of the forms above (``?`` marks an optional key); ``phase_deg`` and
            ``angle_deg`` are in degrees, ``side`` defaults to "left", ``reach`` to "ahead" and
            ``left`` to 0. A slider gives exactly one of ``direction`` (a fixed line) and
            ``link`` (a line carried by that link, turned by ``angle_deg``).

        Raises
        ------
        LinkageError
            For an unknown ``"kind"``, or as the building method of that kind raises.
        KeyError
            When a required key is missing.

        Examples
        --------
        >>> import linkage
        >>> m = linkage.Mechanism()
        >>> m.add_joint({"kind": "fixed", "name": "O", "at": (0, 0)})
        >>> m.add_joint({"kind": "crank", "name": "A", "centre": "O", "radius": 1, "phase_deg": 90})
        >>> m.sweep([0.0], outputs=("joints",)).joint("A").round(12).tolist()
        [[0.0, 1.0]]
        >>> m.add_joint({"kind": "slider", "name": "B", "pivot": "A", "r": 2, "origin": "O",
        ...              "direction": (1, 0)})
        >>> m.sweep([0.0], outputs=("joints",)).joint("B").round(12).tolist()
        [[1.732050807569, 0.0]]
        >>> m.add_joint({"kind": "prism", "name": "Q"})
        Traceback (most recent call last):
        ...
        linkage.LinkageError: unknown joint kind 'prism' (fixed, crank, dyad, slider, point)
        """
        kind = joint.get("kind")
        if not isinstance(kind, str) or kind not in JOINT_KINDS:
            raise LinkageError(f"unknown joint kind {kind!r} ({', '.join(JOINT_KINDS)})")
        JOINT_KINDS[kind].add(self, joint)

    @classmethod
    def from_joints(
        cls, joints: Iterable[Mapping[str, Any]], trace: str | None = None
    ) -> Mechanism:
        """Build a mechanism from joint tables (:meth:`add_joint`), traced at ``trace`` if given.

        Parameters
        ----------
        joints : iterable of mapping
            Joint tables, in program order.
        trace : str, optional
            Joint reported as ``Sweep.point`` (default: the last joint).

        Returns
        -------
        Mechanism
            The new mechanism.

        Examples
        --------
        >>> import linkage
        >>> m = linkage.Mechanism.from_joints(
        ...     [
        ...         {"kind": "fixed", "name": "O", "at": (0, 0)},
        ...         {"kind": "crank", "name": "A", "centre": "O", "radius": 1},
        ...         {"kind": "point", "name": "P", "on": ("O", "A"), "along": 2},
        ...     ],
        ...     trace="A",
        ... )
        >>> m.joint_names, m.trace
        (('O', 'A', 'P'), 'A')
        """
        m = cls()
        for j in joints:
            m.add_joint(j)
        if trace is not None:
            m.trace = trace
        return m

    # -- solving --------------------------------------------------------------------------
    def sweep(
        self,
        theta: ArrayLike | None = None,
        omega: ArrayLike | None = None,
        alpha: ArrayLike | None = None,
        outputs: Iterable[Output] = DEFAULT_OUTPUTS,
        *,
        time: ArrayLike | None = None,
        drive: Drive | None = None,
        pairs: Iterable[tuple[str, str]] | None = None,
    ) -> Sweep:
        """Solve the mechanism at each crank angle of ``theta`` (radians, scalar or 1-D).

        Branches are tracked along the samples in the order given: each dyad keeps its
        orientation, except near a toggle, where the branch that continues the motion smoothly
        is taken. Those choices are made on a fixed grid of crank angles (1024 per turn, walked
        between samples), never by the sampling: inserting or removing samples between two
        samples does not change the branch at either, and a jump of any number of turns costs a
        few turns of work. A sample that cannot be assembled is NaN with ``valid`` False.
        Within the rate margin of a toggle (``32·√ε``: the rates' relative error ``ε/margin²``
        would exceed 2⁻¹⁰) velocities, accelerations and curvature are NaN and ``regular`` is
        False; positions stay exact. Long sweeps can be interrupted with Ctrl-C.

        ``outputs`` names what to compute besides positions: ``"velocity"`` and
        ``"acceleration"`` need ``omega`` (rad/s; scalar or one per angle); ``alpha`` (rad/s²)
        defaults to 0, constant crank speed. Position-only sweeps do no rate work.
        ``"instant_centres"`` holds every pair of links, or only the ``pairs`` named (a
        four-bar's two secondary centres, say): only those are computed and stored.

        In time: ``sweep(time=t, drive=d)`` takes ``θ, ω, α`` from a drive
        (:mod:`linkage.drive`) at the times ``t``; ``s.time`` keeps them.

        Parameters
        ----------
        theta : float or array_like of float, optional
            Crank angles (radians), scalar or 1-D; needed unless ``time`` and ``drive`` are
            given.
        omega : float or array_like of float, optional
            Crank speed (rad/s), scalar or one per angle; needed for ``"velocity"`` and
            ``"acceleration"``.
        alpha : float or array_like of float, optional
            Crank angular acceleration (rad/s²), scalar or one per angle; default 0.
        outputs : iterable of str, default ("point", "joints")
            Names from ``OUTPUTS``: "point", "joints", "velocity", "acceleration",
            "instant_centres", "curvature". Without "joints", every joint and the ``margin``,
            ``gap`` and ``regular`` flags are computed on first use, as are the directions of
            centres at infinity (``instant_centre_directions``) always.
        time : float or array_like of float, optional
            Times of the samples (keyword only), scalar or 1-D; given with ``drive``, instead of
            ``theta``, ``omega`` and ``alpha``.
        drive : Drive, optional
            A :class:`linkage.drive.Drive`: anything whose ``angles(t)`` method returns
            ``θ, ω, α`` at the times ``t`` (keyword only), such as ``ConstantSpeed``, a
            ``Program`` or a ``CrankSchedule``.
        pairs : iterable of (str, str), optional
            With ``"instant_centres"``: the pairs of :attr:`links` (by name, keyword only) whose
            instant centres to compute, in this order; ``s.link_pairs`` holds them. Default:
            every pair.

        Returns
        -------
        Sweep
            One sample per angle (or time), in the order given; for a scalar ``theta`` the
            arrays have no sample axis.

        Raises
        ------
        LinkageError
            For a mechanism without joints, an unknown output, ``"velocity"`` or
            ``"acceleration"`` without ``omega``, angles or rates of the wrong shape or not
            finite, ``time`` and ``drive`` given alone or with ``theta``, ``omega`` or
            ``alpha``, or ``pairs`` without ``"instant_centres"``, naming no link or one
            link twice.
        TypeError
            When neither ``theta`` nor ``time`` and ``drive`` are given, for a ``drive``
            without an ``angles`` method, or for arguments of the wrong type.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> from linkage.drive import ConstantSpeed
        >>> m = linkage.catalog.hoecken().mechanism()
        >>> s = m.sweep(time=[0.0, 0.25], drive=ConstantSpeed(omega=2 * np.pi))  # a turn a second
        >>> s.time, s.theta.round(6), s.point.round(6)
        (array([0.  , 0.25]), array([0.      , 1.570796]), array([[20.      , 48.989795],
               [40.      , 40.      ]]))

        Only the coupler's centre with the ground (its pole) and the crank's with the rocker:

        >>> pairs = [("ground", "coupler"), ("crank", "rocker")]
        >>> s = m.sweep([0.0, 1.0], outputs=("instant_centres",), pairs=pairs)
        >>> s.link_pairs, s.instant_centres.shape
        ((('ground', 'coupler'), ('crank', 'rocker')), (2, 2, 2))
        >>> s.instant_centre("coupler", "ground").round(6)
        array([[20.      ,  0.      ],
               [27.861847, 43.392256]])
        >>> m.sweep(0.0, outputs=("point", "velocity"))
        Traceback (most recent call last):
        ...
        linkage.LinkageError: outputs 'velocity'/'acceleration' need omega (crank speed, rad/s)
        """
        # One consistent state (program, names, links) though another thread adds joints: a
        # joint added later goes to a new core (see _add), never to the one swept here.
        frozen = self.__copy__()
        core, names, links = frozen._core, tuple(frozen._names), frozen.links
        if not names:
            raise LinkageError("the mechanism has no joints")
        theta, omega, alpha, times, scalar_time = _drive_angles(theta, omega, alpha, time, drive)
        out = check_outputs(outputs, omega)
        asked, link_pairs = _asked_pairs(out, pairs, links)
        th, w, a, scalar = _angles_rates(theta, omega, alpha, scalar_time)
        trace = frozen._index(frozen.trace, "trace")
        # Without "joints" the per-joint outputs hold the trace point only, and the margin,
        # gap and regular flags are left out: every joint and the flags are computed on first
        # use (Sweep.joints, .margin, ...), with the same positions bit for bit.
        full = "joints" in out
        # The directions of centres at infinity are computed on first use too (a centre at
        # infinity is already NaN in instant_centres): a sweep of a few centres then writes
        # half the memory.
        raw = core.sweep(
            th, w, a, **asked, column=None if full else trace, flags=full, directions=False
        )

        def complete() -> dict[str, Any]:
            more: dict[str, Any] = core.sweep(th, w, a, **asked, column=None, flags=True)
            _same_as_before(raw, more, None if full else trace)
            return more

        inputs = {
            "theta": th.reshape(()) if scalar else th,
            "omega": w,
            "alpha": a,
            "outputs": out,
            "pairs": link_pairs,
        }
        s = Sweep(
            th,
            raw,
            names,
            trace,
            out,
            scalar,
            links=links,
            complete=complete,
            link_pairs=link_pairs,
            source=(frozen, "sweep", inputs),
        )
        s.time = None if times is None else times.reshape(()) if scalar else times
        return s


def _calls(constructions: list[dict[str, Any]], names: list[str]) -> list[tuple[Any, ...]]:
    """Return a core program as the building calls that make it (for ``_from_core``)."""
    calls: list[tuple[Any, ...]] = []
    for name, c in zip(names, constructions):
        kind = c["kind"]
        if kind == "fixed":
            calls.append(("fixed", name, tuple(c["at"])))
        elif kind == "crank":
            calls.append(("crank", name, names[c["centre"]], c["radius"], c["phase"]))
        elif kind == "dyad":
            p1, p2 = names[c["p1"]], names[c["p2"]]
            calls.append(("dyad", name, p1, p2, c["r1"], c["r2"], c["side"]))
        elif kind == "slider":
            d = c["direction"]
            line = (
                ((d[1], d[2]), None, 0.0)
                if d[0] == "fixed"
                else (None, (names[d[1]], names[d[2]]), d[3])
            )
            calls.append(
                ("slider", name, names[c["pivot"]], c["r"], names[c["origin"]], *line, c["reach"])
            )
        elif kind == "point":
            on = (names[c["from"]], names[c["to"]])
            calls.append(("point", name, on, (c["along"], c["left"])))
        else:  # pragma: no cover - a construction this module does not know
            raise LinkageError(f"cannot copy a construction of kind {kind!r}")
    return calls


def _ops(constructions: list[dict[str, Any]]) -> list[tuple[str, tuple[Any, ...]]]:
    """Return a core program as the core's calls that make it again (for ``_from_core``)."""
    ops: list[tuple[str, tuple[Any, ...]]] = []
    for c in constructions:
        kind = c["kind"]
        if kind == "fixed":
            ops.append(("fixed", tuple(c["at"])))
        elif kind == "crank":
            ops.append(("crank", (c["centre"], c["radius"], c["phase"])))
        elif kind == "dyad":
            ops.append(("dyad", (c["p1"], c["p2"], c["r1"], c["r2"], c["side"])))
        elif kind == "slider":
            d, head = c["direction"], (c["pivot"], c["r"], c["origin"])
            if d[0] == "fixed":
                ops.append(("slider", (*head, d[1], d[2], c["reach"])))
            else:
                ops.append(("slider_on_link", (*head, d[1], d[2], d[3], c["reach"])))
        elif kind == "point":
            ops.append(("point", (c["from"], c["to"], c["along"], c["left"])))
        else:  # pragma: no cover - a construction this module does not know
            raise LinkageError(f"cannot copy a construction of kind {kind!r}")
    return ops


_ARITY = {"fixed": 3, "crank": 5, "dyad": 7, "slider": 9, "point": 4}
"""Length of each kind of building call ``(kind, name, *arguments)`` in a pickled program."""


BASES: list[type] = []
"""The linkage types whose ``mechanism()`` a pickled mechanism may start from (``FourBar``,
``SliderCrank``: their modules add them, as they import this one)."""


def _rebuild(base: Any, calls: Any, trace: Any) -> Mechanism:
    """Build a mechanism again from a pickled program, through the building methods.

    ``base`` is None or the ``FourBar``/``SliderCrank`` it came from, ``calls`` the building
    calls ``(kind, name, *arguments)`` made since, ``trace`` the trace joint (None: the last).
    Nothing is trusted: every value is checked again as the methods check a user's.

    Raises
    ------
    LinkageError
        For a program that is not one (an unknown kind, a wrong number of arguments), or as
        the building methods raise.
    TypeError
        As the building methods raise.
    """
    if base is None:
        m = Mechanism()
    elif any(isinstance(base, t) for t in BASES):
        m = base.mechanism()
    else:
        raise TypeError(f"not a pickled Mechanism: it is based on a {type(base).__name__}")
    if not isinstance(calls, tuple) or len(calls) > _core.CAPACITY:
        raise LinkageError("not a pickled Mechanism: its program is not a tuple of joints")
    for k, call in enumerate(calls):
        if not (
            isinstance(call, tuple)
            and call
            and isinstance(call[0], str)
            and _ARITY.get(call[0]) == len(call)
        ):
            raise LinkageError(f"not a pickled Mechanism: joint {k} is not a building call")
        getattr(m, call[0])(*call[1:])
    if trace is not None:
        m.trace = trace
    return m


@dataclass(frozen=True)
class JointKind:
    """One kind of joint of a scene's joint table: its keys and how it is added.

    The one registry of joint kinds (:data:`JOINT_KINDS`): the scene schema checks keys against
    it, :meth:`Mechanism.add_joint` adds through it, and a failed build blames its ``blame`` key.
    """

    required: tuple[str, ...]
    """Keys a joint of this kind must have (besides ``name`` and ``kind``)."""
    optional: tuple[str, ...]
    """Keys it may have."""
    blame: str
    """The key a scene's error names when building the joint fails."""
    add: Callable[[Mechanism, Mapping[str, Any]], None]
    """Adds the joint to a mechanism."""


def _add_crank(m: Mechanism, j: Mapping[str, Any]) -> None:
    phase = math.radians(as_finite(j.get("phase_deg", 0.0), "phase_deg"))
    m.crank(j["name"], j["centre"], j["radius"], phase)


def _add_slider(m: Mechanism, j: Mapping[str, Any]) -> None:
    link = j.get("link")
    m.slider(
        j["name"],
        j["pivot"],
        j["r"],
        j["origin"],
        direction=j.get("direction"),
        link=(link[0], link[1]) if link is not None and len(link) == 2 else link,
        angle=math.radians(as_finite(j.get("angle_deg", 0.0), "angle_deg")),
        reach=j.get("reach", "ahead"),
    )


JOINT_KINDS: dict[str, JointKind] = {
    "fixed": JointKind(("at",), (), "at", lambda m, j: m.fixed(j["name"], j["at"])),
    "crank": JointKind(("centre", "radius"), ("phase_deg",), "radius", _add_crank),
    "dyad": JointKind(
        ("p1", "p2", "r1", "r2"),
        ("side",),
        "r2",
        lambda m, j: m.dyad(j["name"], j["p1"], j["p2"], j["r1"], j["r2"], j.get("side", "left")),
    ),
    "slider": JointKind(
        ("pivot", "r", "origin"), ("direction", "link", "angle_deg", "reach"), "r", _add_slider
    ),
    "point": JointKind(
        ("on", "along"),
        ("left",),
        "on",
        lambda m, j: m.point(j["name"], tuple(j["on"]), (j["along"], j.get("left", 0.0))),
    ),
}
"""Every joint kind of a scene's joint table, by name (see :class:`JointKind`)."""

SWEPT_BY[Mechanism] = "sweep"

__all__ = ["JOINT_KINDS", "JointKind", "Mechanism", "check_outputs", "check_pairs"]


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Mechanism": Mechanism, "JointKind": JointKind}
for _cls in __test__.values():
    _cls.__module__ = "linkage._mechanism"
__test__["Drive"] = Drive  # the protocol of linkage.drive, which re-exports it
Drive.__module__ = "linkage.drive"
_rebuild.__module__ = "linkage._mechanism"  # what its pickles name, as 0.1's did
