"""``SliderCrank``: the offset slider-crank with a coupler point."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike

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
from linkage._shared.choices import Output, Reach
from linkage.kinematics.fourbar import ArrayOrFloat, named_joint
from linkage.kinematics.mechanism import BASES, DEFAULT_OUTPUTS, Mechanism
from linkage.kinematics.sweep import SWEPT_BY, Sweep

__all__ = [
    "JOINTS",
    "LINKS",
    "SliderCrank",
]

JOINTS = ("O", "G", "A", "B", "P")
LINKS = ("ground", "crank", "coupler", "slider")


class SliderCrank:
    """An offset slider-crank with a coupler point.

    Crank ``O A`` about the pivot ``O``, coupler (connecting rod) ``A B``, slider ``B`` on a
    line, and a coupler point ``P`` rigid with the coupler. The line has the direction
    ``angle`` and passes at the signed distance ``offset`` to the left of ``O`` (looking along
    it), through ``G = O + offset·(−sin angle, cos angle)``. With ``φ = θ − angle`` the slider
    sits ``r cos φ ± √(l² − (r sin φ − e)²)`` along the line from ``O``'s foot: ``+`` for
    ``reach="ahead"``, ``−`` for ``"behind"`` (the same linkage as ``"ahead"`` with the line
    reversed, ``angle + π`` and ``−offset``). The crank turns fully iff
    ``|offset| + crank ≤ coupler``; otherwise it rocks between the positions where the rod is
    perpendicular to the line. The mathematics is the core's (``linkage_core::SliderCrank``).
    Slider-cranks of equal parameters are equal (and hash alike); one pickles as its parameters,
    checked again by this constructor when unpickled.

    Parameters
    ----------
    crank, coupler : float
        Crank and coupler lengths, positive and finite.
    offset : float, default 0.0
        Signed distance of the line from ``O`` (positive: to the left of its direction).
    point : (along, left), default (0, 0)
        Coupler point in coupler coordinates: distance along ``A → B`` and to its left.
    o : (x, y), default (0, 0)
        Crank pivot.
    angle : float, default 0.0
        Direction of the line (radians, counter-clockwise from +x).
    reach : {"ahead", "behind"}, default "ahead"
        Which of the two slider positions; sweeps follow it.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> sc = linkage.SliderCrank(crank=2, coupler=5, offset=1, point=(2.5, 0))
    >>> sc.full_turn, sc.input_ranges()
    (True, [(0.0, 6.283185307179586)])
    >>> sc.sweep(0.0).joint("B").round(12)  # x = r cos θ + √(l² − (r sin θ − e)²)
    array([6.89897949, 1.        ])
    >>> linkage.SliderCrank(crank=2, coupler=2.5, offset=1).input_ranges()  # doctest: +ELLIPSIS
    [(-0.848062078981..., 3.98965473257...)]
    >>> linkage.SliderCrank(crank=2, coupler=-1)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: coupler must be a positive finite length, got -1.0
    """

    def __init__(
        self,
        crank: float,
        coupler: float,
        offset: float = 0.0,
        point: Sequence[float] = (0.0, 0.0),
        o: Sequence[float] = (0.0, 0.0),
        angle: float = 0.0,
        reach: Reach = "ahead",
    ) -> None:
        ox, oy = as_point(o, "o")
        if not isinstance(reach, str) or reach not in choices("reach"):
            raise LinkageError(f"reach must be {one_of('reach')}, got {reach!r}")
        self._core = _core.SliderCrank(
            (ox, oy),
            as_finite(angle, "angle"),
            as_finite(offset, "offset"),
            as_length(crank, "crank"),
            as_length(coupler, "coupler"),
            as_point(point, "point"),
            reach,
        )

    # -- copies, pickling, equality ---------------------------------------------------------
    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as the constructor's arguments: unpickling checks them again."""
        p = self._p()
        return (type(self), (p[4], p[5], p[3], (p[6], p[7]), (p[0], p[1]), p[2], p[8]))

    def __copy__(self) -> SliderCrank:
        out = type(self).__new__(type(self))
        out._core = self._core  # the core cannot be changed: shared
        return out

    def __deepcopy__(self, memo: dict[int, Any]) -> SliderCrank:
        return self.__copy__()

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` is a slider-crank of the same pivot, line, lengths, point, reach."""
        if not isinstance(other, SliderCrank):
            return NotImplemented
        return self._p()[:9] == other._p()[:9]

    def __hash__(self) -> int:
        return hash(self._p()[:9])

    # -- parameters -----------------------------------------------------------------------
    def _p(self) -> tuple[Any, ...]:
        return tuple(self._core.parameters())

    @property
    def o(self) -> tuple[float, float]:
        """Crank pivot."""
        p = self._p()
        return (p[0], p[1])

    @property
    def angle(self) -> float:
        """Direction of the slider's line (radians)."""
        return float(self._p()[2])

    @property
    def offset(self) -> float:
        """Signed distance of the line from ``O`` (positive: left of its direction)."""
        return float(self._p()[3])

    @property
    def crank(self) -> float:
        """Crank length."""
        return float(self._p()[4])

    @property
    def coupler(self) -> float:
        """Coupler (connecting rod) length."""
        return float(self._p()[5])

    @property
    def point(self) -> tuple[float, float]:
        """Coupler point ``(along, left)`` in coupler coordinates."""
        p = self._p()
        return (p[6], p[7])

    @property
    def reach(self) -> Reach:
        """``"ahead"`` or ``"behind"``."""
        return cast(Reach, str(self._p()[8]))

    @property
    def line_point(self) -> tuple[float, float]:
        """The line's point ``G`` nearest the crank pivot."""
        p = self._p()
        return (p[9], p[10])

    def __repr__(self) -> str:
        return (
            f"SliderCrank(crank={self.crank!r}, coupler={self.coupler!r}, "
            f"offset={self.offset!r}, point={self.point!r}, o={self.o!r}, "
            f"angle={self.angle!r}, reach={self.reach!r})"
        )

    # -- analyses -------------------------------------------------------------------------
    @property
    def full_turn(self) -> bool:
        """Whether the crank turns fully (``|offset| + crank ≤ coupler``)."""
        return self._core.input_range() is None

    def is_change_point(self) -> bool:
        """Whether ``|offset| + crank = coupler``.

        The rod then stands perpendicular to the line at one angle of a full turn, where the
        two reaches meet.

        Examples
        --------
        >>> import linkage
        >>> linkage.SliderCrank(crank=2, coupler=3, offset=1).is_change_point()  # 1 + 2 = 3
        True
        >>> linkage.SliderCrank(crank=2, coupler=5, offset=1).is_change_point()
        False
        """
        return bool(self._core.is_change_point())

    def input_ranges(self) -> list[tuple[float, float]]:
        """Every interval of crank angles (radians, absolute) at which the linkage assembles.

        ``[(angle, angle + 2π)]`` for a full turn; one interval between the toggle positions
        (rod perpendicular to the line); two mirror intervals (separate circuits), the first
        with the crank pin ahead of ``O`` along the line; ``[]`` if never.

        Examples
        --------
        >>> import linkage
        >>> rocking = linkage.SliderCrank(crank=2, coupler=2.5, offset=1)
        >>> [(round(lo, 6), round(hi, 6)) for lo, hi in rocking.input_ranges()]
        [(-0.848062, 3.989655)]
        >>> linkage.SliderCrank(crank=2, coupler=0.5, offset=5).input_ranges()  # never reaches
        []
        """
        r = self._core.input_range()
        if r is None:
            return [(self.angle, self.angle + 2 * np.pi)]
        if isinstance(r, str):
            return []
        first, second = r
        if isinstance(first, tuple) and isinstance(second, tuple):
            return [(float(first[0]), float(first[1])), (float(second[0]), float(second[1]))]
        assert isinstance(first, float) and isinstance(second, float)
        return [(first, second)]

    def transmission_angle(self, theta: ArrayLike) -> ArrayOrFloat:
        """Angle between the rod and the normal to the line, in ``[0, π/2]``.

        ``π/2`` with the rod along the line (best), ``0`` at a toggle (rod perpendicular to
        the line); NaN where the linkage cannot be assembled. Scalar in, scalar out.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> rocking = linkage.SliderCrank(crank=2, coupler=2.5, offset=1)
        >>> round(rocking.transmission_angle(0.0), 6), rocking.transmission_angle(1.5 * np.pi)
        (1.159279, nan)
        """
        th, scalar = as_angles(theta, "theta")
        mu = self._core.transmission(th)
        return float(mu[0]) if scalar else mu

    def cognate(self) -> SliderCrank:
        """Return the cognate: the other slider-crank whose coupler point draws the same curve.

        It keeps the crank pivot ``O``; with ``ζ = (along + i·left)/coupler`` its crank is
        ``|AP|``, its rod ``|ζ|·crank``, its line the original's turned by ``arg ζ`` about ``O``
        and scaled by ``|ζ|`` (offset ``|ζ|·offset``), and its coupler point
        ``crank·(cos arg ζ, −sin arg ζ)``. Crank and rod trade roles, so the cognate of a
        crank-slider is a rocker-slider (whose circuit passes both reaches), and conversely when
        the crank keeps to one side of the line's normal through ``O``. The mathematics is the
        core's (``linkage_core::SliderCrank::cognate``).

        Raises
        ------
        LinkageError
            When the coupler point is at the crank pin ``A`` (the cognate's crank would vanish).

        Examples
        --------
        >>> import numpy as np, linkage
        >>> sc = linkage.SliderCrank(crank=10, coupler=32, offset=6, point=(12, 9))
        >>> cog = sc.cognate()
        >>> [round(v, 9) for v in (cog.crank, cog.coupler, cog.offset, *cog.point)]
        [15.0, 4.6875, 2.8125, 8.0, -6.0]
        >>> a, b = sc.circuit(721), cog.circuit(20001)
        >>> bool(linkage.synthesis.largest_distance(a.point[a.valid], b.point[b.valid]) < 1e-5)
        True
        >>> linkage.SliderCrank(crank=10, coupler=32).cognate()
        Traceback (most recent call last):
        ...
        linkage.LinkageError: degenerate synthesis: the coupler point is at the crank pin A
        """
        out = SliderCrank.__new__(SliderCrank)
        out._core = self._core.cognate()
        return out

    # -- sweeping -------------------------------------------------------------------------
    def mechanism(self) -> Mechanism:
        """Return the linkage as a :class:`Mechanism` (joints O, G, A, B, P; traced at P).

        Examples
        --------
        >>> import linkage
        >>> m = linkage.SliderCrank(crank=2, coupler=5).mechanism()
        >>> m.joint_names, m.links
        (('O', 'G', 'A', 'B', 'P'), ('ground', 'crank', 'coupler', 'slider'))
        """
        return Mechanism._from_core(self._core.mechanism(), JOINTS, 4, LINKS, base=self)

    def sweep(
        self,
        theta: ArrayLike,
        omega: ArrayLike | None = None,
        alpha: ArrayLike | None = None,
        outputs: Iterable[Output] = DEFAULT_OUTPUTS,
    ) -> Sweep:
        """Solve at each crank angle, tracking the reach (see :meth:`Mechanism.sweep`).

        Examples
        --------
        >>> import numpy as np, linkage
        >>> sc = linkage.SliderCrank(crank=2, coupler=5, offset=1, point=(2.5, 0))
        >>> s = sc.sweep([0.0, np.pi], omega=1.0, outputs=("point", "velocity"))
        >>> s.joint("B").round(6), s.velocity.round(6)
        (array([[6.898979, 1.      ],
               [2.898979, 1.      ]]), array([[ 0.204124,  1.      ],
               [-0.204124, -1.      ]]))
        >>> linkage.SliderCrank(crank=2, coupler=2.5, offset=1).sweep([0.0, 4.0]).valid
        array([ True, False])
        """
        return self.mechanism().sweep(theta, omega, alpha, outputs)

    def circuit(self, n: int = 721) -> Sweep:
        """Trace the whole coupler curve of the circuit in ``n`` samples (closed form).

        A full-turn crank sweeps one turn on its reach; a limited crank goes from limit to
        limit on its reach and back on the other, spaced as ``(1 − cos πs)/2`` (as
        :meth:`FourBar.circuit`), so the curve closes (the last sample repeats the first).
        For two circuits, the first of :meth:`input_ranges`.

        Raises
        ------
        LinkageError
            When the linkage never assembles, or ``n < 2``.

        Examples
        --------
        >>> import linkage
        >>> c = linkage.SliderCrank(crank=2, coupler=2.5, offset=1).circuit(5)
        >>> c.theta.round(6)
        array([-0.848062,  1.570796,  3.989655,  1.570796, -0.848062])
        >>> linkage.SliderCrank(crank=2, coupler=5).circuit(1)
        Traceback (most recent call last):
        ...
        linkage.LinkageError: n must be an int ≥ 2, got 1
        """
        count = as_count(n, "n", 2)
        try:
            theta, joints, margin = self._core.circuit(count)
        except _core.AssemblyError as exc:
            raise named_joint(exc, JOINTS) from None
        valid = np.isfinite(joints[:, 4, 0])
        raw = {
            "joints": joints,
            "valid": valid,
            "margin": margin,
            "gap": np.where(valid, 0.0, np.nan),
        }
        return Sweep(
            theta,
            raw,
            JOINTS,
            4,
            ("point", "joints"),
            links=LINKS,
            source=(self, "circuit", {"n": count}),
        )


# A pickled mechanism may be built from a SliderCrank's; a pickled sweep may be its circuit.
BASES.append(SliderCrank)
SWEPT_BY[SliderCrank] = "circuit"


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"SliderCrank": SliderCrank}
for _cls in __test__.values():
    _cls.__module__ = "linkage._slider_crank"
