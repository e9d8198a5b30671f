"""The result of a sweep: numpy arrays, one row per crank angle."""

from __future__ import annotations

import copy
import functools
import threading
from collections.abc import Callable, Mapping
from typing import Any, get_args

import numpy as np
from numpy.typing import NDArray

from linkage._core import RATE_MARGIN, LinkageError
from linkage._shared.arrays import UnknownNameError, as_angles, as_real
from linkage._shared.choices import Output

__all__ = [
    "OUTPUTS",
    "SWEPT_BY",
    "Sweep",
]

OUTPUTS: tuple[Output, ...] = get_args(Output)
"""Names accepted by ``outputs=``: the trace point, every joint, their rates, the instant centres
of every pair of links, and the path curvature of every joint."""


@functools.lru_cache(maxsize=256)
def _pairs(links: tuple[str, ...]) -> tuple[tuple[str, str], ...]:
    """Return the pairs ``(links[k], links[m])``, ``k < m`` (one per mechanism, not per sweep)."""
    return tuple((links[k], links[m]) for k in range(len(links)) for m in range(k + 1, len(links)))


class Sweep:
    """Positions (and, if asked, velocities and accelerations) over a sweep of crank angles.

    Every array has one row per angle, in the order given; a sample that cannot be assembled is
    NaN with ``valid`` False, and ``gap`` says by how much its lengths miss closure.

    A sweep may be read by several threads at once and copied (``copy.copy`` shares the arrays,
    ``copy.deepcopy`` copies them; each completes on its own what was left for first use). It
    pickles as what was swept: unpickling sweeps the linkage (rebuilt through its checking
    constructor) again, giving the same arrays bit for bit. Two sweeps are equal when they are
    of equal linkages with the same inputs (angles or times, rates, outputs, pairs).

    Attributes
    ----------
    theta : (N,) float64
        Crank angles, radians.
    joints : (N, J, 2) float64
        Every joint, in ``joint_names`` order.
    valid : (N,) bool
        Whether each sample assembled.
    margin : (N,) float64
        Smallest dyad assembly margin (sine of the angle between the two links at the joint):
        0 at a toggle, where velocities are unbounded. NaN where invalid.
    gap : (N,) float64
        0 where valid; how much the lengths miss closure where not (NaN when undetermined).
    regular : (N,) bool
        Valid and clear of a toggle: False where some dyad's margin is below the rate margin
        ``32·√ε`` (4.8e-7), where rates lose all their digits (relative error ``ε/margin²``);
        velocities, accelerations and curvature are NaN there, never huge numbers.
    point : (N, 2) float64
        The trace joint (``trace``).
    velocity, acceleration : (N, 2) float64
        Rates of the trace point, when requested in ``outputs``.
    joint_velocities, joint_accelerations : (N, J, 2) float64
        Rates of every joint, when requested.
    instant_centres : (N, P, 2) float64
        With ``"instant_centres"``: the instant centre of each pair of ``link_pairs`` (every
        pair of links, or those the sweep's ``pairs=`` named); NaN where
        it is at infinity (``instant_centre_at_infinity``, direction in
        ``instant_centre_directions``) or undefined.
    curvature, curvature_radius : (N,) float64
        With ``"curvature"``: signed curvature of the trace point's path (positive turning
        counter-clockwise in the direction of increasing crank angle; 0 at an inflection; NaN
        where the point is at rest) and its radius ``1/|curvature|``.
    curvature_centre : (N, 2) float64
        Centre of curvature of the trace point's path (the evolute along the sweep); NaN at an
        inflection. Computed from rates per unit crank angle: it does not depend on timing.
    """

    def __init__(
        self,
        theta: NDArray[np.float64],
        raw: dict[str, Any],
        joint_names: tuple[str, ...],
        trace: int,
        outputs: tuple[str, ...],
        scalar: bool = False,
        links: tuple[str, ...] = (),
        complete: Callable[[], dict[str, Any]] | None = None,
        link_pairs: tuple[tuple[str, str], ...] | None = None,
        source: tuple[Any, str, dict[str, Any]] | None = None,
    ) -> None:
        self.joint_names = joint_names
        self.time: NDArray[np.float64] | None = None
        """Times of the samples, for a sweep driven in time (else None)."""
        self.links = links
        """Link names, the ground first (joints of each link joined by '-')."""
        self.link_pairs = _pairs(links) if link_pairs is None else link_pairs
        """The pairs of links whose instant centres ``instant_centres`` holds, in order."""
        self.trace = joint_names[trace]
        self.outputs = outputs
        self._trace = trace
        self._scalar = scalar
        # Per-joint arrays hold every joint, or (a sweep asked for the point only) the trace
        # point alone; `complete` recomputes every joint and the flags on first use. The three
        # are one state, replaced whole (never changed in place) under the lock: a reader takes
        # it once, so threads and copies each see a whole state, before or after completion.
        self._state: tuple[dict[str, Any], bool, Callable[[], dict[str, Any]] | None] = (
            raw,
            raw["joints"].shape[-2] == len(joint_names),
            complete,
        )
        self._lock = threading.Lock()
        # What was swept: (linkage, method, its arguments), to pickle and compare a sweep by.
        self._source = source
        self.theta: NDArray[np.float64] = self._pick(theta)
        self.valid: NDArray[np.bool_] = self._pick(raw["valid"])

    @property
    def _raw(self) -> dict[str, Any]:
        return self._state[0]

    def _pick(self, a: Any) -> Any:
        return a[0] if self._scalar else a

    def _column(self, full: bool) -> int:
        return self._trace if full else 0

    def _get_raw(self, key: str, full: bool, axis: int | None = None) -> Any:
        """Return ``raw[key]``, completing a point-only sweep first when needed.

        Every joint and the flags are computed first when ``full`` is asked of a point-only
        sweep or the key is missing (the same positions, bit for bit), once, by one thread.
        With ``axis`` (the joint axis), the trace point's part only, from the same state.
        """
        raw, whole, _ = self._state
        if (full and not whole) or key not in raw:
            with self._lock:
                raw, whole, complete = self._state
                if (full and not whole) or key not in raw:
                    if complete is None:
                        raise AttributeError(f"{key} was not computed")
                    raw, whole = {**raw, **complete()}, True
                    self._state = (raw, whole, None)
        arr = self._pick(raw[key])
        if axis is None:
            return arr
        return arr[(..., self._column(whole)) + (slice(None),) * (-1 - axis)]  # a view

    # -- copies, pickling, equality ---------------------------------------------------------
    def __copy__(self) -> Sweep:
        """Return a sweep sharing the arrays, completed on its own."""
        s = type(self).__new__(type(self))
        s.__dict__.update(self.__dict__)
        s._lock = threading.Lock()
        return s

    def __deepcopy__(self, memo: dict[int, Any]) -> Sweep:
        """Return a sweep with copies of every array, completed on its own."""
        s = type(self).__new__(type(self))
        memo[id(self)] = s
        for key, value in self.__dict__.items():
            if key == "_state":
                raw, whole, complete = value
                value = (copy.deepcopy(raw, memo), whole, complete)
            elif key != "_lock":
                value = copy.deepcopy(value, memo)
            s.__dict__[key] = value
        s._lock = threading.Lock()
        return s

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as what was swept: unpickling sweeps the linkage (itself rebuilt) again.

        The same linkage and inputs give the same arrays, bit for bit; nothing of the pickled
        data is taken as a result.
        """
        if self._source is None:
            raise TypeError("this Sweep does not know what was swept: it cannot be pickled")
        linkage, method, arguments = self._source
        return (_rebuild, (linkage, method, dict(arguments), self.time))

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` is a sweep of an equal linkage with the same inputs.

        The same crank angles (or times), rates, outputs and pairs: the same arrays.
        """
        if not isinstance(other, Sweep):
            return NotImplemented
        if other is self:
            return True
        if self._source is None or other._source is None:
            return False
        (a, how, args), (b, other_how, other_args) = self._source, other._source
        return (
            how == other_how
            and a == b
            and args.keys() == other_args.keys()
            and all(_same(args[k], other_args[k]) for k in args)
            and _same(self.time, other.time)
        )

    __hash__ = None  # type: ignore[assignment]  # its arrays can be written

    @property
    def joints(self) -> NDArray[np.float64]:
        """Every joint, shape (N, J, 2), in ``joint_names`` order.

        Computed on first use when the sweep asked for the point only.
        """
        arr: NDArray[np.float64] = self._get_raw("joints", True)
        return arr

    @property
    def margin(self) -> NDArray[np.float64]:
        """Smallest dyad assembly margin per sample, shape (N,); NaN where invalid."""
        arr: NDArray[np.float64] = self._get_raw("margin", False)
        return arr

    @property
    def gap(self) -> NDArray[np.float64]:
        """0 where valid; how much the lengths miss closure where not, shape (N,)."""
        arr: NDArray[np.float64] = self._get_raw("gap", False)
        return arr

    @property
    def regular(self) -> NDArray[np.bool_]:
        """Valid and clear of the rate margin, shape (N,) (see the class)."""
        raw, _, complete = self._state
        if "regular" in raw or complete is not None:
            arr: NDArray[np.bool_] = self._get_raw("regular", False)
            return arr
        with np.errstate(invalid="ignore"):
            flags: NDArray[np.bool_] = np.asarray(self.valid) & (
                np.asarray(self.margin) >= RATE_MARGIN
            )
        return flags

    def __len__(self) -> int:
        return int(np.size(self.valid))

    def __repr__(self) -> str:
        n, ok = len(self), int(np.count_nonzero(self.valid))
        joints = ", ".join(self.joint_names)
        return f"<Sweep {n} samples ({ok} valid), joints {joints}; outputs {self.outputs}>"

    def near_toggle(self, threshold: float = 1e-6) -> NDArray[np.bool_]:
        """Flag the samples whose dyad margin is below ``threshold``.

        The rate equations' Jacobian is near singular there, and velocities and accelerations
        carry relative errors of order ``ε/margin²`` (measured: within a factor 5 of that down
        to margins of 2e-6).

        Parameters
        ----------
        threshold : float, default 1e-6
            Dyad margin below which a valid sample is flagged.

        Returns
        -------
        (N,) bool
            True where the sample is valid and its margin is below ``threshold``; False at
            invalid samples.

        Raises
        ------
        LinkageError
            When ``threshold`` is NaN.
        TypeError
            When ``threshold`` is not a real number.

        Examples
        --------
        At a double-rocker's limits the sample is placed, flagged, and its rates are NaN:

        >>> import numpy as np, linkage
        >>> dr = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20)
        >>> lo, hi = dr.input_limits()
        >>> s = dr.sweep([lo, 1.0, hi], omega=1.0, outputs=("point", "velocity"))
        >>> s.valid, s.near_toggle()
        (array([ True,  True,  True]), array([ True, False,  True]))
        >>> s.regular, np.isnan(s.velocity[:, 0])
        (array([False,  True, False]), array([ True, False,  True]))
        >>> s.near_toggle(float("nan"))
        Traceback (most recent call last):
        ...
        linkage.LinkageError: threshold must be a number, got nan
        """
        t = as_real(threshold, "threshold")
        if np.isnan(t):
            raise LinkageError("threshold must be a number, got nan")
        flags: NDArray[np.bool_] = np.asarray(self.valid) & (np.asarray(self.margin) < t)
        return flags

    def joint(self, name: str) -> NDArray[np.float64]:
        """Positions of one joint by name, shape (N, 2).

        Parameters
        ----------
        name : str
            One of ``joint_names``.

        Returns
        -------
        (N, 2) float64
            The joint's positions (every joint is computed on first use when the sweep asked
            for the point only).

        Raises
        ------
        LinkageError
            When there is no joint ``name`` (an ``UnknownNameError``, also a ``KeyError``).
        TypeError
            When ``name`` is not a str.

        Examples
        --------
        >>> import numpy as np, linkage
        >>> s = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25).sweep([0.0, np.pi / 2])
        >>> s.joint("B").round(6)
        array([[15.      , 24.494897],
               [20.      , 25.      ]])
        >>> s.joint("Q")
        Traceback (most recent call last):
        ...
        linkage._arrays.UnknownNameError: no joint 'Q'; joints are O, C, A, B, P
        """
        if not isinstance(name, str):
            raise TypeError(f"name must be a joint name (str), got {type(name).__name__}")
        try:
            i = self.joint_names.index(name)
        except ValueError:
            raise UnknownNameError(
                f"no joint {name!r}; joints are {', '.join(self.joint_names)}"
            ) from None
        return self.joints[..., i, :]

    @property
    def point(self) -> NDArray[np.float64]:
        """The trace point, shape (N, 2)."""
        raw, whole, _ = self._state
        arr: NDArray[np.float64] = self._pick(raw["joints"])[..., self._column(whole), :]
        return arr

    def _rate(self, kind: str, full: bool = False, axis: int | None = None) -> NDArray[np.float64]:
        if kind not in self.outputs or kind not in self._state[0]:
            raise AttributeError(
                f"{kind} was not computed: pass outputs=(..., {kind!r}) and omega to sweep()"
            )
        arr: NDArray[np.float64] = self._get_raw(kind, full, axis)
        return arr

    def _get(
        self, key: str, output: str, full: bool = False, axis: int | None = None
    ) -> NDArray[Any]:
        raw, _, complete = self._state
        if key not in raw and (output not in self.outputs or complete is None):
            raise AttributeError(f"{output} was not computed: pass outputs=(..., {output!r})")
        arr: NDArray[Any] = self._get_raw(key, full, axis)
        return arr

    @property
    def instant_centres(self) -> NDArray[np.float64]:
        """Finite instant centres, shape (N, P, 2); NaN at infinity or undefined."""
        return self._get("instant_centres", "instant_centres")

    @property
    def instant_centre_directions(self) -> NDArray[np.float64]:
        """Unit directions of instant centres at infinity, shape (N, P, 2); NaN elsewhere.

        Computed on first use (with every joint and the flags; the same centres, bit for bit).
        """
        return self._get("instant_centre_directions", "instant_centres")

    @property
    def instant_centre_at_infinity(self) -> NDArray[np.bool_]:
        """Whether each instant centre is at infinity (parallel lines, a translating link)."""
        d = self.instant_centre_directions
        at_inf: NDArray[np.bool_] = np.isfinite(d[..., 0])
        return at_inf

    def instant_centre(self, a: str, b: str) -> NDArray[np.float64]:
        """Instant centre of links ``a`` and ``b`` (by name), shape (N, 2).

        Parameters
        ----------
        a, b : str
            Two different names of ``links``, in either order.

        Returns
        -------
        (N, 2) float64
            The finite instant centre of the pair; NaN where it is at infinity or undefined
            (see ``instant_centre_directions``).

        Raises
        ------
        LinkageError
            When ``(a, b)`` is not a pair of ``link_pairs`` in either order: a name of no
            link, one link twice, or a pair the sweep's ``pairs=`` left out (an
            ``UnknownNameError``, also a ``KeyError``).
        TypeError
            When ``a`` or ``b`` is not a str.
        AttributeError
            When the sweep was not asked for ``"instant_centres"``.

        Examples
        --------
        Crank and rocker turn about a point of the ground line; at θ = π/2 they are parallel, so
        the coupler translates and its centre with the ground is at infinity (NaN):

        >>> import numpy as np, linkage
        >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25)
        >>> s = fb.sweep([0.0, np.pi / 2], outputs=("joints", "instant_centres"))
        >>> s.instant_centre("crank", "rocker").round(6) + 0.0
        array([[ 10.      ,   0.      ],
               [-13.333333,   0.      ]])
        >>> s.instant_centre("ground", "coupler").round(6) + 0.0
        array([[20.,  0.],
               [nan, nan]])
        """
        if not isinstance(a, str) or not isinstance(b, str):
            raise TypeError(
                f"links must be named by str, got {type(a).__name__}, {type(b).__name__}"
            )
        pair = (a, b) if (a, b) in self.link_pairs else (b, a)
        try:
            q = self.link_pairs.index(pair)
        except ValueError:
            unknown = [n for n in (a, b) if n not in self.links]
            if not unknown and a != b:
                asked = "; ".join(f"{x}, {y}" for x, y in self.link_pairs)
                raise UnknownNameError(
                    f"the centre of {a!r} and {b!r} was not computed: the sweep's pairs= "
                    f"named {asked or 'none'}"
                ) from None
            what = (
                f"no link {unknown[0]!r}"
                if len(unknown) == 1
                else f"no links {unknown[0]!r}, {unknown[1]!r}"
                if unknown
                else f"{a!r} and {b!r} are one link"
            )
            raise UnknownNameError(f"{what}; links are {', '.join(self.links)}") from None
        return self.instant_centres[..., q, :]

    @property
    def joint_curvatures(self) -> NDArray[np.float64]:
        """Signed path curvature of every joint, shape (N, J)."""
        return self._get("curvature", "curvature", full=True)

    @property
    def joint_curvature_centres(self) -> NDArray[np.float64]:
        """Centres of curvature of every joint's path, shape (N, J, 2)."""
        return self._get("curvature_centres", "curvature", full=True)

    @property
    def curvature(self) -> NDArray[np.float64]:
        """Signed curvature of the trace point's path, shape (N,)."""
        arr: NDArray[np.float64] = self._get("curvature", "curvature", axis=-1)
        return arr

    @property
    def curvature_radius(self) -> NDArray[np.float64]:
        """Radius of curvature of the trace point's path, ``1/|curvature|``, shape (N,).

        Infinite at an inflection.
        """
        with np.errstate(divide="ignore"):
            r: NDArray[np.float64] = 1.0 / np.abs(self.curvature)
        return r

    @property
    def curvature_centre(self) -> NDArray[np.float64]:
        """Centre of curvature of the trace point's path, shape (N, 2)."""
        out: NDArray[np.float64] = self._get("curvature_centres", "curvature", axis=-2)
        return out

    @property
    def velocity(self) -> NDArray[np.float64]:
        """Velocity of the trace point, shape (N, 2)."""
        return self._rate("velocity", axis=-2)

    @property
    def acceleration(self) -> NDArray[np.float64]:
        """Acceleration of the trace point, shape (N, 2)."""
        return self._rate("acceleration", axis=-2)

    @property
    def joint_velocities(self) -> NDArray[np.float64]:
        """Velocities of every joint, shape (N, J, 2)."""
        return self._rate("velocity", full=True)

    @property
    def joint_accelerations(self) -> NDArray[np.float64]:
        """Accelerations of every joint, shape (N, J, 2)."""
        return self._rate("acceleration", full=True)


def _same(a: Any, b: Any) -> bool:
    """Whether two inputs of a sweep are equal: arrays of one shape and the same values."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)):
            return False
        return a.shape == b.shape and bool(np.array_equal(a, b, equal_nan=True))
    return bool(a == b)


SWEPT_BY: dict[type, str] = {}
"""The linkage types a pickled sweep may be of, each with its method that sweeps it again.

Registered by their modules (which import this one): ``Mechanism.sweep``, ``FourBar.circuit``,
``SliderCrank.circuit``.
"""


def _rebuild(linkage: Any, method: Any, arguments: Any, time: Any) -> Sweep:
    """Sweep again what a pickled sweep was of, through the public methods (which check it).

    Raises
    ------
    LinkageError
        For a pickle that is not a sweep's (another method, unknown arguments, times that do
        not match the samples), or as the sweep raises.
    TypeError
        For a linkage that is none, or as the sweep raises.
    """
    keys = {"sweep": {"theta", "omega", "alpha", "outputs", "pairs"}, "circuit": {"n"}}
    if not (
        isinstance(method, str)
        and method in keys
        and any(isinstance(linkage, t) and m == method for t, m in SWEPT_BY.items())
        and isinstance(arguments, Mapping)
        and set(arguments) == keys[method]
    ):
        raise LinkageError("not a pickled Sweep: unknown linkage, method or arguments")
    s: Sweep = getattr(linkage, method)(**arguments)
    if time is not None:
        t, scalar = as_angles(time, "time")
        if t.shape[0] != len(s) or scalar != s._scalar:
            raise LinkageError("not a pickled Sweep: its times do not match its samples")
        s.time = t.reshape(()) if scalar else t
    return s


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Sweep": Sweep}
for _cls in __test__.values():
    _cls.__module__ = "linkage._sweep"
_rebuild.__module__ = "linkage._sweep"  # what its pickles name, as 0.1's did
