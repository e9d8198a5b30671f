"""Walking-leg families: parametrised leg generators and their figures from the core.

Each family has documented bounds and the design a source chose; figures come from the core's leg
figures (``linkage_core::gait``).

A family builds a candidate as scene joint constructions (trace ``F``, the foot), so every
candidate is also a :class:`linkage.Mechanism` and a ready-to-run scene. Four-bar legs are
evaluated by the core's batched leg figures (:func:`linkage._core.walking.four_bar_gaits`),
multi-loop legs by a sweep and :func:`linkage._core.walking.leg_gait`. Used by
:mod:`linkage.design` (the search) and :mod:`linkage.catalog` (the reference legs); needs no
optional package.

>>> import numpy as np
>>> from linkage.legs import FIGURES, Settings, family
>>> fam = family("fourbar")
>>> figs = dict(zip(FIGURES, fam.evaluate(np.array([fam.reference]), Settings())[0]))
>>> round(float(figs["duty_factor"]), 3), round(float(figs["min_transmission"]), 2)
(0.586, 23.07)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage.kinematics.mechanism import Mechanism

__all__ = [
    "CRANK",
    "FAMILIES",
    "FIGURES",
    "GUIDED_REF",
    "JANSEN_HOLY",
    "KLANN_REF",
    "OBJECTIVES",
    "UNITS",
    "Family",
    "Settings",
    "family",
]

Array = NDArray[np.float64]

# -- figures ------------------------------------------------------------------------------

FIGURES: tuple[str, ...] = (
    "full_turn",
    "min_transmission",
    "duty_factor",
    "stride",
    "lift",
    "straightness",
    "speed_variation",
    "peak_torque",
    "stance_runs",
    "hip_depth",
)
"""Columns of a family's figures: ``full_turn`` (1/0), ``min_transmission`` (degrees),
``duty_factor``, ``stride``, ``lift``, ``straightness``, ``peak_torque`` (length units:
torque per unit foot force), ``speed_variation`` (``(max − min)/|mean|`` of ``dx/dθ`` over the
stance: not :attr:`linkage.geometry.StraightPart.speed_variation`, which is over the straight
part only), ``stance_runs`` (count) and
``hip_depth`` (how far the ground lies below the crank pivot, the hip, foot bar included)."""

OBJECTIVES: dict[str, int] = {
    "stride": +1,
    "duty_factor": +1,
    "lift": +1,
    "straightness": -1,
    "speed_variation": -1,
    "peak_torque": -1,
    "min_transmission": +1,
}
"""Figures a study may optimise: +1 maximised, −1 minimised."""

UNITS: dict[str, str] = {
    "stride": "length",
    "duty_factor": "fraction of the turn",
    "lift": "length",
    "straightness": "length",
    "speed_variation": "(max − min)/mean",
    "peak_torque": "torque per unit foot force (length)",
    "min_transmission": "degrees",
}


@dataclass(frozen=True)
class Settings:
    """How a candidate's figures are measured: samples, stance tolerance and foot bar.

    ``samples`` per turn, the stance tolerance (a fraction of the foot path's extent) and a rigid
    vertical foot bar (thesis 1's guided legs: the foot ``foot_bar`` below the trace point).
    """

    samples: int = 360
    stance_tol: float = 2.5e-3
    foot_bar: float = 0.0


@dataclass(frozen=True)
class Family:
    """A parametrised leg generator, with bounds and a reference design.

    Parameter names, documented bounds, the reference design and how to build one candidate
    (``joints``: scene joint constructions, trace ``"F"``).
    """

    name: str
    params: tuple[str, ...]
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    reference: tuple[float, ...]
    reference_name: str
    doc: str
    joints: Callable[[Any], list[dict[str, Any]]] = field(repr=False)
    scale: float = 1.0
    """A typical foot-path size: length constraints are scaled by it for the optimiser."""
    batched: bool = False
    units: str = "mm"
    """The unit of the family's lengths (its reference's)."""

    def bounds(self) -> dict[str, tuple[float, float]]:
        """``{parameter: (lower, upper)}``.

        Examples
        --------
        >>> from linkage.legs import family
        >>> b = family("fourbar").bounds()
        >>> list(b)[:3], b["ground"]
        (['ground', 'ground_angle', 'coupler'], (12.0, 40.0))
        """
        return {p: (lo, hi) for p, lo, hi in zip(self.params, self.lower, self.upper)}

    def mechanism(self, x: ArrayLike) -> Mechanism:
        """Build candidate ``x`` as a :class:`linkage.Mechanism` whose trace ``F`` is the foot.

        Examples
        --------
        >>> import numpy as np
        >>> from linkage.legs import family
        >>> fam = family("fourbar")
        >>> m = fam.mechanism(fam.reference)      # Hoecken's leg
        >>> m.joint_names, m.trace
        (('O', 'C', 'A', 'B', 'F'), 'F')
        >>> m.sweep(np.array([0.0, np.pi / 2])).point.round(4)   # the foot, 50 along A → B
        array([[20.    , 48.9898],
               [40.    , 40.    ]])
        """
        return Mechanism.from_joints(self.joints(x), trace="F")

    def evaluate(self, x: Array, settings: Settings, threads: int = 1) -> Array:
        """Compute the figures ``(M, len(FIGURES))`` of the candidates ``x`` ``(M, len(params))``.

        A candidate that does not turn fully has ``full_turn = 0`` and NaN figures.

        Examples
        --------
        Hoecken's leg, and one whose coupler and rocker (5) cannot reach across the ground (20):

        >>> import numpy as np
        >>> from linkage.legs import FIGURES, Settings, family
        >>> fam = family("fourbar")
        >>> x = np.array([fam.reference, [20.0, 0.0, 5.0, 5.0, 50.0, 0.0]])
        >>> figs = fam.evaluate(x, Settings(samples=64))
        >>> for name in ("full_turn", "stride", "stance_runs"):
        ...     print(name, [round(float(v), 3) for v in figs[:, FIGURES.index(name)]])
        full_turn [1.0, 0.0]
        stride [43.53, nan]
        stance_runs [1.0, 0.0]
        >>> fam.evaluate(x[:, :4], Settings())
        Traceback (most recent call last):
        ...
        linkage.LinkageError: family 'fourbar' takes 6 parameters, got 4
        """
        x = np.ascontiguousarray(np.atleast_2d(np.asarray(x, dtype=np.float64)))
        if x.shape[1] != len(self.params):
            raise LinkageError(
                f"family {self.name!r} takes {len(self.params)} parameters, got {x.shape[1]}"
            )
        if self.batched:
            return _four_bar_figures(x, settings, threads)
        return np.array([_mechanism_figures(self, row, settings) for row in x]).reshape(
            len(x), len(FIGURES)
        )


def _four_bar_figures(x: Array, s: Settings, threads: int) -> Array:
    """Compute the four-bar family's figures by the core's batched leg figures."""
    # Fresh contiguous columns (a one-row column view is "contiguous" to numpy but strided).
    ground, angle, coupler, rocker, along, left = (x[:, k].copy() for k in range(6))
    m = len(x)
    o = np.zeros((m, 2))
    c = np.ascontiguousarray(np.stack([ground * np.cos(angle), ground * np.sin(angle)], axis=1))
    raw = _core.walking.four_bar_gaits(
        o,
        c,
        np.full(m, CRANK),
        coupler,
        rocker,
        along,
        left,
        np.zeros(m, dtype=bool),
        s.samples,
        s.stance_tol,
        threads=threads,
    )
    col = {n: raw[:, k] for k, n in enumerate(_core.walking.gait_columns())}
    return _assemble(col, s.foot_bar)


def _assemble(col: dict[str, Array], foot_bar: float) -> Array:
    out = np.empty((len(col["full_turn"]), len(FIGURES)))
    for k, name in enumerate(FIGURES):
        if name == "min_transmission":
            out[:, k] = np.degrees(col["min_transmission"])
        elif name == "hip_depth":
            # The hip (crank pivot) is at y = 0; the foot hangs foot_bar below the trace point.
            out[:, k] = -(col["ground"] - foot_bar)
        else:
            out[:, k] = col[name]
    return out


def _mechanism_figures(family: Family, x: Array, s: Settings) -> Array:
    """Compute a multi-loop leg's figures: sweep it over a turn, figures by the core's leg_gait."""
    nan = np.full(len(FIGURES), np.nan)
    nan[FIGURES.index("full_turn")] = 0.0
    try:
        m = family.mechanism(x)
    except LinkageError:
        return nan
    theta = np.linspace(0.0, 2 * math.pi, s.samples, endpoint=False)
    sw = m.sweep(theta, omega=1.0, outputs=("velocity",))
    if not sw.valid.all():
        return nan
    path, rate = np.ascontiguousarray(sw.point), np.ascontiguousarray(sw.velocity)
    if not (np.isfinite(path).all() and np.isfinite(rate).all()):
        return nan
    extent = float(np.ptp(path, axis=0).max())
    g, _ = _core.walking.leg_gait(path, rate, s.stance_tol * extent)
    # Transmission angle of every dyad: the angle between its two links at the joint.
    joints = sw.joints
    names = m.joint_names
    worst = 1.0
    for j in family.joints(x):
        if j["kind"] != "dyad":
            continue
        k, a, b = names.index(j["name"]), names.index(j["p1"]), names.index(j["p2"])
        u, w = joints[:, k] - joints[:, a], joints[:, k] - joints[:, b]
        sin = np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]) / (j["r1"] * j["r2"])
        worst = min(worst, float(sin.min()))
    col = {k: np.array([float(v)]) for k, v in g.items()}
    col["full_turn"] = np.array([1.0])
    col["min_transmission"] = np.array([math.asin(min(worst, 1.0))])
    row: Array = _assemble(col, s.foot_bar)[0]
    return row


# -- families -----------------------------------------------------------------------------

CRANK = 10.0
"""Crank length of the four-bar family (its scale: thesis 1's Hoecken crank, mm)."""


def _four_bar_joints(x: Sequence[float]) -> list[dict[str, Any]]:
    ground, angle, coupler, rocker, along, left = (float(v) for v in x)
    return [
        {"name": "O", "kind": "fixed", "at": [0.0, 0.0]},
        {
            "name": "C",
            "kind": "fixed",
            "at": [ground * math.cos(angle), ground * math.sin(angle)],
        },
        {"name": "A", "kind": "crank", "centre": "O", "radius": CRANK},
        {
            "name": "B",
            "kind": "dyad",
            "p1": "A",
            "p2": "C",
            "r1": coupler,
            "r2": rocker,
            "side": "left",
        },
        {"name": "F", "kind": "point", "on": ["A", "B"], "along": along, "left": left},
    ]


JANSEN_HOLY = (38.0, 7.8, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49.0, 50.0, 61.9)
"""Jansen's "holy numbers" a, l, b, c, d, e, f, g, h, i, j, k (crank m = 15 fixed)."""


def _jansen_joints(x: Sequence[float]) -> list[dict[str, Any]]:
    a, l_, b, c, d, e, f, g, h, i, j, k = (float(v) for v in x)
    return [
        {"name": "O", "kind": "fixed", "at": [0.0, 0.0]},
        {"name": "Q", "kind": "fixed", "at": [-a, -l_]},
        {"name": "A", "kind": "crank", "centre": "O", "radius": 15.0},
        {"name": "B", "kind": "dyad", "p1": "A", "p2": "Q", "r1": j, "r2": b, "side": "right"},
        {"name": "C", "kind": "dyad", "p1": "A", "p2": "Q", "r1": k, "r2": c, "side": "left"},
        {"name": "D", "kind": "dyad", "p1": "B", "p2": "Q", "r1": e, "r2": d, "side": "right"},
        {"name": "E", "kind": "dyad", "p1": "D", "p2": "C", "r1": f, "r2": g, "side": "right"},
        {"name": "F", "kind": "dyad", "p1": "E", "p2": "C", "r1": h, "r2": i, "side": "right"},
    ]


KLANN_REF = (28.0, 94.0, 76.0, 80.5157, 39.6566, 91.0, 2.1, -10.6073, 95.0, 48.4410, 37.4648, 11.0)
"""Klann-type reference (not the patent's figures, which we could not consult here): the
optimised Klann leg of Bastien & Birglen, "Power Efficient Design of a Compliant Robotic Leg
Based on Klann's Linkage", IEEE/ASME Trans. Mechatronics 2022 — crank 28, frame pivots
A at 94 and B at 76 from A at 80.5°, rocker 39.66, coupler 91, M at 2.1 coupler lengths at
−10.6°, leg 95, rocker 48.44, foot at 2.1 leg lengths at 37.46°, and a tilt of the frame."""


def _klann_joints(x: Sequence[float]) -> list[dict[str, Any]]:
    crank, l4, l8, ab_deg, l2, l3, rho, alpha_deg, l7, l6, mem_deg, tilt_deg = (float(v) for v in x)
    t = math.radians(tilt_deg)

    def rot(p: tuple[float, float]) -> list[float]:
        return [p[0] * math.cos(t) - p[1] * math.sin(t), p[0] * math.sin(t) + p[1] * math.cos(t)]

    pa = (-l4, 0.0)
    ab = math.radians(ab_deg)
    pb = (-l4 + l8 * math.cos(ab), l8 * math.sin(ab))
    al, me = math.radians(alpha_deg), math.radians(mem_deg)
    return [
        {"name": "O", "kind": "fixed", "at": [0.0, 0.0]},
        {"name": "PA", "kind": "fixed", "at": rot(pa)},
        {"name": "PB", "kind": "fixed", "at": rot(pb)},
        {"name": "C", "kind": "crank", "centre": "O", "radius": crank},
        {"name": "D", "kind": "dyad", "p1": "C", "p2": "PA", "r1": l3, "r2": l2, "side": "right"},
        {
            "name": "M",
            "kind": "point",
            "on": ["C", "D"],
            "along": rho * l3 * math.cos(al),
            "left": rho * l3 * math.sin(al),
        },
        {"name": "E", "kind": "dyad", "p1": "M", "p2": "PB", "r1": l7, "r2": l6, "side": "left"},
        {
            "name": "F",
            "kind": "point",
            "on": ["E", "M"],
            "along": rho * l7 * math.cos(me),
            "left": rho * l7 * math.sin(me),
        },
    ]


GUIDED_REF = (20.0, 0.0, 25.0, 25.0, 50.0, 0.0, 25.0, 90.0, 55.0, 25.0, 0.0, 0.0)
"""The guided Hoecken leg's reference: thesis 1's Hoecken four-bar (ground 20, crank 10,
coupler and rocker 25, coupler point P 50 along the coupler) with a guide link from P: a link
of 25 from P to E, E hung 55 from a frame pivot G = (25, 90) above the crank, the foot F on
P → E at P itself — so its foot path is thesis 1's, and the search moves the foot along the
guided link and reshapes the guide."""


def _guided_joints(x: Sequence[float]) -> list[dict[str, Any]]:
    ground, angle, coupler, rocker, along, left, gx, gy, guide, link, f_along, f_left = (
        float(v) for v in x
    )
    joints = _four_bar_joints((ground, angle, coupler, rocker, along, left))
    joints[-1] = {**joints[-1], "name": "P"}
    return [
        *joints,
        {"name": "G", "kind": "fixed", "at": [gx, gy]},
        {
            "name": "E",
            "kind": "dyad",
            "p1": "P",
            "p2": "G",
            "r1": link,
            "r2": guide,
            "side": "left",
        },
        {"name": "F", "kind": "point", "on": ["P", "E"], "along": f_along, "left": f_left},
    ]


def _around(ref: Sequence[float], rel: float) -> tuple[tuple[float, ...], tuple[float, ...]]:
    lo = tuple(v - rel * abs(v) if v else -1.0 for v in ref)
    hi = tuple(v + rel * abs(v) if v else 1.0 for v in ref)
    return lo, hi


FAMILIES: dict[str, Family] = {
    "fourbar": Family(
        name="fourbar",
        params=("ground", "ground_angle", "coupler", "rocker", "along", "left"),
        # Crank 10 (the scale). Ground 12–40 and coupler/rocker 10–50 span Grashof
        # crank-rockers and non-Grashof legs alike; the coupler point anywhere within 80 of A;
        # the ground line tilted up to ±0.1 rad (±5.7°: the stance is horizontal, so a leg
        # is mounted with its straight part level; wider tilts only waste evaluations).
        lower=(12.0, -0.1, 10.0, 10.0, -20.0, -30.0),
        upper=(40.0, 0.1, 50.0, 50.0, 80.0, 30.0),
        reference=(20.0, 0.0, 25.0, 25.0, 50.0, 0.0),
        reference_name="Hoecken (thesis 1: 20 / 10 / 25 / 25, foot 50 along the coupler)",
        doc="Four-bar with a coupler-point foot, the Hoecken family (crank 10).",
        joints=_four_bar_joints,
        scale=50.0,
        batched=True,
    ),
    "jansen": Family(
        name="jansen",
        params=("a", "l", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k"),
        # Each length within ±15 % of the holy number (crank m = 15 fixed).
        lower=_around(JANSEN_HOLY, 0.15)[0],
        upper=_around(JANSEN_HOLY, 0.15)[1],
        reference=JANSEN_HOLY,
        reference_name="Jansen's holy numbers",
        doc="Theo Jansen's eight-bar Strandbeest leg (crank 15).",
        joints=_jansen_joints,
        scale=70.0,
        units="holy-number units",
    ),
    "klann": Family(
        name="klann",
        params=(
            "crank",
            "ground",
            "pivot_b",
            "pivot_b_angle",
            "rocker",
            "coupler",
            "rho",
            "alpha",
            "leg",
            "leg_rocker",
            "foot_angle",
            "tilt",
        ),
        # A Stephenson III six-bar (the Klann topology): lengths within ±15 % of the
        # reference, angles (degrees) within ±15 % or ±1 (tilt, degrees: ±30).
        lower=(*_around(KLANN_REF, 0.15)[0][:-1], -30.0),
        upper=(*_around(KLANN_REF, 0.15)[1][:-1], 30.0),
        reference=KLANN_REF,
        reference_name="Klann-type leg (Bastien & Birglen 2022 proportions, not the patent)",
        doc="Klann-type Stephenson III six-bar leg.",
        joints=_klann_joints,
        scale=150.0,
    ),
    "guided": Family(
        name="guided",
        params=(
            "ground",
            "ground_angle",
            "coupler",
            "rocker",
            "along",
            "left",
            "guide_x",
            "guide_y",
            "guide",
            "link",
            "foot_along",
            "foot_left",
        ),
        # A Stephenson III six-bar of another kind than Klann's: the Hoecken four-bar within
        # ±15 % (tilt ±0.1 rad), its coupler point P guided by a dyad P–E–G hung from a frame
        # pivot G anywhere above the crank, the foot anywhere within 30 of P on P → E.
        lower=(17.0, -0.1, 21.25, 21.25, 42.5, -7.5, 0.0, 70.0, 40.0, 15.0, -30.0, -20.0),
        upper=(23.0, 0.1, 28.75, 28.75, 57.5, 7.5, 50.0, 120.0, 70.0, 35.0, 30.0, 20.0),
        reference=GUIDED_REF,
        reference_name="Hoecken with a guided link (foot at the coupler point: thesis 1's path)",
        doc="Hoecken four-bar whose coupler point is guided by a hung dyad (Stephenson III).",
        joints=_guided_joints,
        scale=50.0,
    ),
}


def family(name: str) -> Family:
    """Return a leg family by name (``fourbar``, ``jansen``, ``klann``, ``guided``).

    Examples
    --------
    >>> from linkage.legs import family
    >>> fam = family("klann")
    >>> fam.name, len(fam.params), fam.units
    ('klann', 12, 'mm')
    >>> family("hexapod")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: unknown leg family 'hexapod'; choose from fourbar, jansen, klann, guided
    """
    if not isinstance(name, str):
        raise TypeError(f"family must be a str, got {type(name).__name__}")
    if name not in FAMILIES:
        raise LinkageError(f"unknown leg family {name!r}; choose from {', '.join(FAMILIES)}")
    return FAMILIES[name]


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Settings": Settings, "Family": Family}
for _cls in __test__.values():
    _cls.__module__ = "linkage.legs"
