"""``FourBar``: the four-bar linkage with its classical analyses."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any, Union, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.arrays import (
    as_angles,
    as_count,
    as_finite,
    as_length,
    as_point,
    choices,
    one_of,
)
from linkage._shared.choices import Assembly, Output, SweepMode
from linkage.kinematics.mechanism import BASES, DEFAULT_OUTPUTS, Drive, Mechanism
from linkage.kinematics.sweep import SWEPT_BY, Sweep

__all__ = [
    "JOINTS",
    "LINKS",
    "ArrayOrFloat",
    "FourBar",
    "named_joint",
]

JOINTS = ("O", "C", "A", "B", "P")
LINKS = ("ground", "crank", "coupler", "rocker")
ArrayOrFloat = Union[float, NDArray[np.float64]]


def named_joint(exc: _core.AssemblyError, joints: tuple[str, ...]) -> _core.AssemblyError:
    """Return the core's assembly error with its joint named from ``joints``.

    The core numbers joints: "joint 3 cannot be assembled" is B's for a four-bar and a
    slider-crank alike.
    """
    joint = exc.joint
    if not isinstance(joint, int) or not 0 <= joint < len(joints):
        return exc
    named = _core.AssemblyError(f"joint {joints[joint]} {exc.reason}")
    named.joint, named.gap, named.reason = joints[joint], exc.gap, exc.reason
    return named


class FourBar:
    """A four-bar linkage with a coupler point.

    Crank ``O A`` about ground pivot ``O``, coupler ``A B``, rocker ``C B`` about ground pivot
    ``C``, and a coupler point ``P``.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths (any consistent unit). ``ground`` may be omitted when ``c`` is given.
    point : (along, left)
        Coupler point in coupler coordinates: distance along ``A → B`` and to its left.
    assembly : {"open", "crossed"}
        ``B`` left ("open") or right ("crossed") of the diagonal ``A → C``; sweeps follow that
        branch. For a change-point linkage (``grashof()`` says so: parallelograms, kites) the
        two circuits meet at the flat positions (crank along the ground line) and the side of
        ``B`` flips along a circuit: the assembly then names the branch with the crank up
        (perpendicular to the ground line, to the left of ``O → C``), and a sweep reaches its
        first sample from there — so an open parallelogram stays a parallelogram wherever and
        in whichever order it is sampled.
    o, c : (x, y)
        Ground pivots; default ``o = (0, 0)``, ``c = o + (ground, 0)``.

    Examples
    --------
    >>> import linkage
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> fb.grashof()
    'crank-rocker'
    >>> fb.input_limits() is None
    True
    >>> fb.sweep([0.5 * 3.141592653589793]).point.round(9)
    array([[40., 40.]])

    Four-bars of equal parameters are equal (and hash alike); one pickles as its parameters,
    checked again by this constructor when unpickled:

    >>> import pickle
    >>> fb == linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    True
    >>> pickle.loads(pickle.dumps(fb)) == fb
    True
    >>> linkage.FourBar(ground=20, crank=10, coupler=-25, rocker=25)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: coupler must be a positive finite length, got -25.0
    """

    def __init__(
        self,
        ground: float | None = None,
        crank: float | None = None,
        coupler: float | None = None,
        rocker: float | None = None,
        point: Sequence[float] = (0.0, 0.0),
        assembly: Assembly = "open",
        o: Sequence[float] = (0.0, 0.0),
        c: Sequence[float] | None = None,
    ) -> None:
        for name, v in (("crank", crank), ("coupler", coupler), ("rocker", rocker)):
            if v is None:
                raise TypeError(f"FourBar() missing the {name} length")
        ox, oy = as_point(o, "o")
        if c is None:
            if ground is None:
                raise TypeError("FourBar() needs ground (or the rocker pivot c)")
            g = as_length(ground, "ground")
            cx, cy = ox + g, oy
        else:
            cx, cy = as_point(c, "c")
            if ground is not None:
                g = as_length(ground, "ground")
                actual = math.hypot(cx - ox, cy - oy)
                if abs(actual - g) > 1e-12 * max(g, actual):
                    raise LinkageError(f"ground {g} contradicts |c - o| = {actual}")
        if not isinstance(assembly, str) or assembly not in choices("assembly"):
            raise LinkageError(f"assembly must be {one_of('assembly')}, got {assembly!r}")
        r = as_length(crank, "crank")
        b = as_length(coupler, "coupler")
        k = as_length(rocker, "rocker")
        along, left = as_point(point, "point")
        self._core = _core.FourBar((ox, oy), (cx, cy), r, b, k, (along, left), assembly)
        self._sweeper: Mechanism | None = None

    @classmethod
    def _from_core(cls, core: Any) -> FourBar:
        fb = cls.__new__(cls)
        fb._core = core
        fb._sweeper = None
        return fb

    # -- copies, pickling, equality ---------------------------------------------------------
    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as the constructor's arguments: unpickling checks them again."""
        p = self._p()
        return (
            type(self),
            (None, p[4], p[5], p[6], (p[7], p[8]), p[9], (p[0], p[1]), (p[2], p[3])),
        )

    def __copy__(self) -> FourBar:
        return type(self)._from_core(self._core)  # the core cannot be changed: shared

    def __deepcopy__(self, memo: dict[int, Any]) -> FourBar:
        return self.__copy__()

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` is a four-bar of the same pivots, lengths, point and assembly."""
        if not isinstance(other, FourBar):
            return NotImplemented
        return self._p() == other._p()

    def __hash__(self) -> int:
        return hash(self._p())

    # -- parameters -----------------------------------------------------------------------
    def _p(self) -> tuple[Any, ...]:
        return tuple(self._core.parameters())

    @property
    def o(self) -> tuple[float, float]:
        """Crank pivot."""
        p = self._p()
        return (p[0], p[1])

    @property
    def c(self) -> tuple[float, float]:
        """Rocker pivot."""
        p = self._p()
        return (p[2], p[3])

    @property
    def ground(self) -> float:
        """Distance between the ground pivots."""
        p = self._p()
        return math.hypot(p[2] - p[0], p[3] - p[1])

    @property
    def crank(self) -> float:
        """Crank length."""
        return float(self._p()[4])

    @property
    def coupler(self) -> float:
        """Coupler length."""
        return float(self._p()[5])

    @property
    def rocker(self) -> float:
        """Rocker length."""
        return float(self._p()[6])

    @property
    def point(self) -> tuple[float, float]:
        """Coupler point (along, left)."""
        p = self._p()
        return (p[7], p[8])

    @property
    def assembly(self) -> Assembly:
        """Assembly: "open" or "crossed"."""
        return cast(Assembly, str(self._p()[9]))

    def __repr__(self) -> str:
        return (
            f"FourBar(ground={self.ground:g}, crank={self.crank:g}, coupler={self.coupler:g}, "
            f"rocker={self.rocker:g}, point={self.point}, assembly={self.assembly!r}, "
            f"o={self.o}, c={self.c})"
        )

    # -- analyses -------------------------------------------------------------------------
    def cognates(self) -> tuple[FourBar, FourBar]:
        """Return the two Roberts–Chebyshev cognates, placed in the same frame.

        They are the other four-bars whose coupler point draws this one's coupler curve. The
        third pivot is ``D = O + z (C − O)``, ``z = (P − A)/(B − A)`` as complex numbers
        (triangle ``O C D`` similar to the coupler triangle ``A B P``). The first cognate turns
        about ``O`` and ``D``: its crank turns with this coupler (parallel to ``P − A``). The
        second turns about ``C`` and ``D``: its crank is parallel to ``P − B``. A cognate's
        crank is another link than this crank, so its Grashof class is its own; one that rocks
        may turn fully driven at its other pivot (:meth:`reversed`). A cognate whose crank rocks
        over two intervals may draw the curve on the circuit of its second one, where
        :meth:`circuit` traces the first.

        Returns
        -------
        (FourBar, FourBar)
            The cognate about ``O`` and ``D``, then the one about ``C`` and ``D``.

        Raises
        ------
        LinkageError
            When the coupler point is at ``A`` or ``B`` (a cognate's link would have no length)
            or the linkage never assembles.

        Examples
        --------
        Hoecken's crank-rocker has a cognate that is Chebyshev's lambda mechanism, driven at its
        other pivot:

        >>> import linkage
        >>> fb = linkage.catalog.hoecken()
        >>> first, second = fb.cognates()
        >>> first.grashof(), first.o, first.c
        ('double-rocker', (0.0, 0.0), (40.0, 0.0))
        >>> lam = second.reversed()
        >>> lam.grashof(), lam.o, lam.c, round(lam.crank, 9), round(lam.coupler, 9)
        ('crank-rocker', (40.0, 0.0), (20.0, 0.0), 10.0, 25.0)
        """
        a, b = self._core.cognates()
        return FourBar._from_core(a), FourBar._from_core(b)

    def reversed(self) -> FourBar:
        """Return the same linkage driven at its rocker: crank pivot ``C``, rocker pivot ``O``.

        Crank and rocker lengths swap and the coupler point stays where it is; the assembly is
        the one that keeps the linkage as it is in one assembled pose. A four-bar whose crank
        rocks does not say which of its circuits it is on (:meth:`circuit` traces the first
        input interval's), so reversing one twice may give the other circuit's assembly.

        Raises
        ------
        LinkageError
            When the linkage never assembles.

        Examples
        --------
        >>> import linkage
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
        >>> r = fb.reversed()
        >>> r.o, r.c, r.crank, r.rocker, r.grashof()
        ((20.0, 0.0), (0.0, 0.0), 25.0, 10.0, 'rocker-crank')
        """
        return FourBar._from_core(self._core.reversed())

    def grashof(self) -> str:
        """Grashof class of the linkage.

        Returns
        -------
        str
            "crank-rocker", "double-crank", "rocker-crank", "double-rocker", "change-point"
            (s + l = p + q) or "triple-rocker" (non-Grashof).

        Examples
        --------
        >>> import linkage
        >>> linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25).grashof()
        'crank-rocker'
        >>> linkage.FourBar(ground=20, crank=10, coupler=20, rocker=10).grashof()  # parallelogram
        'change-point'
        >>> linkage.FourBar(ground=10, crank=30, coupler=8, rocker=9).grashof()
        'triple-rocker'
        """
        return str(self._core.grashof())

    def input_ranges(self) -> list[tuple[float, float]]:
        """Every interval of crank angles (radians) at which the linkage assembles.

        ``[(θ0, θ0 + 2π)]`` for a full-turn crank (θ0 the ground direction); one interval
        between toggle positions; two mirror intervals (separate circuits); ``[]`` if never.

        Returns
        -------
        list of (float, float)
            The intervals ``(lo, hi)``, radians: none, one or two.

        Examples
        --------
        A full-turn crank, a double-rocker's two circuits, and a linkage that never closes:

        >>> import linkage
        >>> linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25).input_ranges()
        [(0.0, 6.283185307179586)]
        >>> dr = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20)
        >>> [(round(lo, 6), round(hi, 6)) for lo, hi in dr.input_ranges()]
        [(0.505361, 2.046915), (-2.046915, -0.505361)]
        >>> linkage.FourBar(ground=10, crank=30, coupler=8, rocker=9).input_ranges()
        []
        """
        r = self._core.input_range()
        if r is None:
            base = math.atan2(self.c[1] - self.o[1], self.c[0] - self.o[0])
            return [(base, base + 2 * math.pi)]
        if isinstance(r, str):
            return []
        first, second = r
        if isinstance(first, tuple) and isinstance(second, tuple):
            return [(float(first[0]), float(first[1])), (float(second[0]), float(second[1]))]
        assert isinstance(first, float) and isinstance(second, float)
        return [(first, second)]

    def input_limits(self) -> tuple[float, float] | None:
        """None for a full-turn crank, else the crank angles (lo, hi) of the toggle positions.

        Computed as ``atan2(4·Area, r² + g² − d²)`` from Kahan's triangle area, so it stays
        accurate where ``acos`` of a cosine near ±1 would lose half the digits. For a linkage
        with two circuits, the counter-clockwise one (see :meth:`input_ranges`).

        Returns
        -------
        (float, float) or None
            The toggle angles ``(lo, hi)`` (radians), or None for a full-turn crank.

        Raises
        ------
        LinkageError
            When the linkage cannot be assembled at any angle.

        Examples
        --------
        >>> import linkage
        >>> dr = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20)
        >>> [round(a, 6) for a in dr.input_limits()]
        [0.505361, 2.046915]
        >>> linkage.FourBar(ground=10, crank=30, coupler=8, rocker=9).input_limits()
        Traceback (most recent call last):
        ...
        linkage.LinkageError: the linkage cannot be assembled at any crank angle
        """
        ranges = self.input_ranges()
        if not ranges:
            raise LinkageError("the linkage cannot be assembled at any crank angle")
        if self._core.input_range() is None:
            return None
        return ranges[0]

    def transmission_angle(self, theta: ArrayLike) -> ArrayOrFloat:
        """Angle at ``B`` between coupler and rocker, in [0, π].

        Best at π/2, fails at 0 and π; NaN where the linkage cannot be assembled. Scalar in,
        scalar out.

        Parameters
        ----------
        theta : float or array_like of float
            Crank angles (radians), finite, scalar or 1-D.

        Returns
        -------
        float or (N,) float64
            The transmission angle (radians) at each crank angle; a float for a scalar
            ``theta``.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25)
        >>> np.degrees(fb.transmission_angle([0, np.pi / 2, np.pi])).round(4)
        array([23.0739, 53.1301, 73.7398])
        >>> linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20).transmission_angle(np.pi)
        nan
        """
        th, scalar = as_angles(theta, "theta")
        mu = self._core.transmission_angle(th)
        return float(mu[0]) if scalar else mu

    # -- sweeping -------------------------------------------------------------------------
    def mechanism(self) -> Mechanism:
        """Return the linkage as a :class:`Mechanism`.

        Its joints are O, C, A, B, P and its links ground, crank, coupler, rocker.

        Returns
        -------
        Mechanism
            A new mechanism on each call, traced at ``P``.

        Examples
        --------
        >>> import linkage
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
        >>> m = fb.mechanism()
        >>> m.joint_names, m.trace, m.links
        (('O', 'C', 'A', 'B', 'P'), 'P', ('ground', 'crank', 'coupler', 'rocker'))
        """
        return Mechanism._from_core(self._core.mechanism(), JOINTS, 4, LINKS, base=self)

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
        """Solve at each crank angle, or at each time of a drive; see :meth:`Mechanism.sweep`.

        ``s.point`` is the coupler point, ``s.joints`` holds O, C, A, B, P.

        Parameters
        ----------
        theta, omega, alpha, outputs, time, drive, pairs
            As for :meth:`Mechanism.sweep`; ``pairs`` names links ground, crank, coupler,
            rocker.

        Returns
        -------
        Sweep
            The sweep, with links ground, crank, coupler, rocker.

        Examples
        --------
        A double-rocker's crank rocks between 0.505 and 2.047 rad: outside, NaN rows with a gap.

        >>> import numpy as np, linkage
        >>> dr = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20)
        >>> s = dr.sweep([0.0, 1.0, np.pi], omega=1.0, outputs=("point", "velocity"))
        >>> s.valid, s.gap
        (array([False,  True, False]), array([5., 0., 5.]))
        >>> s.velocity.round(6)
        array([[       nan,        nan],
               [-12.622065,   8.104535],
               [       nan,        nan]])

        The two secondary instant centres only (Kennedy: the four others are the pins):

        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25)
        >>> s = fb.sweep([0.0], outputs=("instant_centres",),
        ...              pairs=[("ground", "coupler"), ("crank", "rocker")])
        >>> s.instant_centres.round(6) + 0.0
        array([[[20.,  0.],
                [10.,  0.]]])
        """
        sweeper = self._sweeper
        if sweeper is None:
            # A private copy, never handed out (a Mechanism can be extended by its owner).
            sweeper = self._sweeper = self.mechanism()
        return sweeper.sweep(theta, omega, alpha, outputs, time=time, drive=drive, pairs=pairs)

    def uniform_sweep(
        self,
        theta0: float,
        dtheta: float,
        n: int,
        mode: SweepMode = "table",
        block: int = 64,
        threads: int = 1,
        out: NDArray[np.float64] | None = None,
    ) -> NDArray[np.float64]:
        """Compute coupler points ``(n, 2)`` at ``theta0 + k·dtheta`` by the fast path.

        The points are on the declared assembly (no branch tracking — for cranks that turn fully
        without a toggle), NaN where it cannot assemble.

        ``mode`` makes the crank directions: ``"trig"`` (sin/cos of every angle), ``"table"``
        (exact anchors every ``block`` samples times a table of the step's multiples) or
        ``"recurrence"`` (rotation by the step, re-anchored every ``block``). ``threads`` splits
        the samples; every mode gives the same bits for any thread count. ``out``, a writeable
        C-contiguous float64 ``(n, 2)`` array, receives the points instead of a new array (and is
        returned): reusing one saves allocating (5–10 % of the time at 10⁶ samples, measured).
        On an error ``out`` is left as it was.

        Parameters
        ----------
        theta0 : float
            First crank angle (radians), finite.
        dtheta : float
            Step between crank angles (radians), finite.
        n : int
            Number of samples, at least 1.
        mode : {"trig", "table", "recurrence"}, default "table"
            How the crank directions are made (above).
        block : int, default 64
            Samples between exact anchors in the "table" and "recurrence" modes, at least 1
            (at most 256 for "table").
        threads : int, default 1
            Threads the samples are split over, at least 1.
        out : (n, 2) float64 ndarray, optional
            Writeable C-contiguous array that receives the points.

        Returns
        -------
        (n, 2) float64 ndarray
            The coupler points: ``out`` itself when given.

        Raises
        ------
        LinkageError
            For an unknown ``mode``, a count out of range, an ``out`` of the wrong shape or
            layout or not writeable, or when the path crosses a flat position of a change-point
            linkage (where the motion would switch assembly).
        TypeError
            For arguments of the wrong type, or an ``out`` that is not a float64 numpy array.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
        >>> fb.uniform_sweep(0.0, np.pi / 2, 4).round(6) + 0.0
        array([[20.      , 48.989795],
               [40.      , 40.      ],
               [20.      , 40.      ],
               [ 0.      , 40.      ]])
        >>> fb.uniform_sweep(0.0, 0.1, 4, mode="fast")
        Traceback (most recent call last):
        ...
        linkage.LinkageError: mode must be 'trig', 'table' or 'recurrence', got "fast"
        """
        n, block, threads = (
            as_count(v, k) for k, v in (("n", n), ("block", block), ("threads", threads))
        )
        if not isinstance(mode, str):
            raise TypeError(f"mode must be a str, got {type(mode).__name__}")
        # The extension checks out's shape, layout and writeability; only the type is ours.
        if out is not None and (not isinstance(out, np.ndarray) or out.dtype != np.float64):
            raise TypeError(
                f"out must be a float64 numpy array, got {getattr(out, 'dtype', type(out))}"
            )
        points: NDArray[np.float64] = self._core.uniform_sweep(
            as_finite(theta0, "theta0"),
            as_finite(dtheta, "dtheta"),
            int(n),
            mode,
            int(block),
            int(threads),
            out,
        )
        return points

    @staticmethod
    def uniform_sweep_isa() -> str:
        """Return the instruction set :meth:`uniform_sweep` runs on this CPU.

        Returns
        -------
        str
            ``"avx512"``, ``"avx2"`` (builds of the same kernel chosen at run time, same bits)
            or ``"portable"`` — also when the environment sets ``LINKAGE_PORTABLE=1``.

        Examples
        --------
        >>> import linkage
        >>> linkage.FourBar.uniform_sweep_isa() in ("avx512", "avx2", "portable")
        True
        """
        return str(_core.sweep.instruction_set())

    def circuit(self, n: int = 721) -> Sweep:
        """Trace the whole coupler curve of the circuit in ``n`` samples.

        A full-turn crank sweeps one turn on its assembly; a limited crank goes from limit to
        limit on its assembly and back on the other, both halves including the toggle
        positions, so the curve closes (the last sample repeats the first). Limited ranges are
        spaced as ``(1 − cos πs)/2`` so the square-root motion at the toggles is evenly sampled.
        ``s.theta`` holds the angles used; ``s.velocity`` is per unit crank angle (ω = 1).

        Parameters
        ----------
        n : int, default 721
            Number of samples, at least 2.

        Returns
        -------
        Sweep
            The circuit, with outputs "point", "joints" and "velocity" (joints O, C, A, B, P).

        Examples
        --------
        A double-rocker goes from limit to limit on its assembly and back on the other:

        >>> import numpy as np, linkage
        >>> c = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20).circuit(5)
        >>> c.theta.round(6)
        array([0.505361, 1.276138, 2.046915, 2.046915, 0.505361])
        >>> bool(np.allclose(c.point[0], c.point[-1])), bool(c.valid.all())
        (True, True)
        """
        # The margin is the tracker's: |sin| of the transmission angle at B.
        count = as_count(n, "n", 2)
        try:
            theta, joints, velocity, margin = self._core.circuit(count)
        except _core.AssemblyError as exc:
            raise named_joint(exc, JOINTS) from None
        valid = np.isfinite(joints[:, 4, 0])
        raw = {
            "joints": joints,
            "valid": valid,
            "margin": margin,
            "gap": np.where(valid, 0.0, np.nan),
            "velocity": velocity,
        }
        return Sweep(
            theta,
            raw,
            JOINTS,
            4,
            ("point", "joints", "velocity"),
            links=LINKS,
            source=(self, "circuit", {"n": count}),
        )


# A pickled mechanism may be built from a FourBar's; a pickled sweep may be its circuit.
BASES.append(FourBar)
SWEPT_BY[FourBar] = "circuit"


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"FourBar": FourBar}
for _cls in __test__.values():
    _cls.__module__ = "linkage._fourbar"
