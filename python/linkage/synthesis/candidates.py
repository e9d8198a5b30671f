"""The candidates :func:`~linkage.synthesis.path` returns, checked and ranked.

Their constraints, their ranking, and what is said of them: the longest link, the distance to a
change point, why none was found.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage._shared.choices import LinkageKind
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.slider_crank import SliderCrank
from linkage.synthesis.kinds import EXACT, SLIDER, _Kind

__all__ = [
    "CHANGE_POINT_NEAR",
    "CONSTRAINT_NAMES",
    "LONG_LINK",
    "NEAR",
    "Candidate",
    "Candidates",
    "LinkageT",
    "change_point_gap",
    "largest_distance",
    "long_link",
    "longest_link",
    "source_text",
    "why_none",
]

LONG_LINK = 20.0
"""Default ``max_link`` of :func:`path`: candidates with a link longer than this many target
sizes rank after all others (a 25 mm curve drawn with links of metres is no design)."""


LinkageT = TypeVar("LinkageT", bound=Union[FourBar, SliderCrank])
"""The kind of linkage a :class:`Candidate` holds."""


@dataclass
class Candidate(Generic[LinkageT]):
    """One linkage found by :func:`path`, placed in the target's frame.

    ``linkage`` is a :class:`~linkage.FourBar` or (``kind == "slider-crank"``) a
    :class:`~linkage.SliderCrank`; both sweep (``.sweep``, ``.circuit``) and give a
    :class:`~linkage.Mechanism` (``.mechanism()``). ``error`` and ``rms`` are the largest and
    root-mean-square distance from the target points to the candidate's coupler curve (its
    circuit, traced whole), in the target's units;
    ``back`` the largest distance from the curve back to the target polygon (closed targets:
    the two together bound the Hausdorff distance; NaN for an open target, which matches a
    part of the circuit only). ``crank_range`` is the crank interval
    (radians, absolute) that traces the matched part; ``through_limit`` whether tracing it takes
    the crank through one of its limits (it must reverse there; never for a full-turn crank).
    ``grashof`` is the four-bar's Grashof class, or for a slider-crank ``"crank-slider"`` (the
    crank turns fully, ``|offset| + crank < coupler``) or ``"rocker-slider"`` (it rocks);
    ``min_transmission`` is the transmission angle's least distance from a toggle (a
    slider-crank's: the angle between the rod and the normal to the line) over the matched
    part, or over the whole turn when the crank turns fully (it is driven through all of it).
    ``source`` says where it came from: ``"equation"`` (a four-bar from the equation of the
    curve through the target points, refined), ``"atlas"`` (a match refined), ``"global"``
    (the global search) or
    ``"cognate"`` (a Roberts cognate of an exact fit, or one driven at its other pivot).
    """

    linkage: LinkageT
    error: float
    rms: float
    back: float
    crank_range: tuple[float, float]
    full_turn: bool
    grashof: str
    min_transmission: float
    through_limit: bool
    source: str
    params: NDArray[np.float64] = field(repr=False)
    kind: LinkageKind = "fourbar"

    @property
    def min_transmission_deg(self) -> float:
        """:attr:`min_transmission` in degrees."""
        return math.degrees(self.min_transmission)

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` holds an equal linkage and the same figures (NaN equal to NaN).

        The dataclass's own comparison would say a copy differs (``back`` is NaN for an open
        target) or raise (``params`` is an array).
        """
        if not isinstance(other, Candidate):
            return NotImplemented
        for name in self.__dataclass_fields__:
            a, b = getattr(self, name), getattr(other, name)
            if isinstance(a, (str, FourBar, SliderCrank)) or isinstance(
                b, (str, FourBar, SliderCrank)
            ):
                if a != b:
                    return False
            elif np.shape(a) != np.shape(b) or not np.array_equal(a, b, equal_nan=True):
                return False
        return True

    __hash__ = None  # type: ignore[assignment]  # mutable, as the dataclass is


Candidate.__module__ = "linkage.synthesis"  # as before the split: pickles and reprs name it so


CONSTRAINT_NAMES = ("full_turn", "min_transmission", "lengths", "pivots")
""":func:`path`'s constraints, in the order :attr:`Candidates.removed` names them."""


class Candidates(list[Candidate[Any]]):
    """:func:`path`'s candidates, best first (a list), and what its constraints removed.

    ``removed`` maps each constraint of :data:`CONSTRAINT_NAMES` that removed a valid fit (one
    that assembles over its circuit on one branch) to the number of fits it removed (a fit
    failing two counts for each); ``closest_removed`` is the removed fit of least error, or
    None, and ``closest_fails`` the constraints it fails. When the list is empty, they say
    which constraint to loosen (:func:`why_none`).
    """

    removed: dict[str, int]
    closest_removed: Candidate[Any] | None
    closest_fails: tuple[str, ...]

    def __init__(
        self,
        found: Iterable[Candidate[Any]] = (),
        removed: dict[str, int] | None = None,
        closest_removed: Candidate[Any] | None = None,
        closest_fails: Sequence[str] = (),
    ) -> None:
        super().__init__(found)
        self.removed = {} if removed is None else removed
        self.closest_removed = closest_removed
        self.closest_fails = tuple(closest_fails)


Candidates.__module__ = "linkage.synthesis"  # as before the split: pickles and reprs name it so


def _ranked(found: list[Candidate[Any]], size: float, limit: float) -> list[Candidate[Any]]:
    """Rank candidates: links longer than ``limit`` last, then by error.

    Among exact fits (error ≤ :data:`EXACT` × size: within the refinement's own accuracy,
    where cognates and round-off differ by nothing a designer can see) a crank that turns fully
    comes first, then the transmission angle farthest from a toggle, then the error.
    """

    def key(c: Candidate[Any]) -> tuple[bool, float, bool, float, float, float]:
        exact = c.error <= EXACT * size
        return (
            _longest(c) > limit,
            0.0 if exact else c.error,
            exact and not c.full_turn,
            -c.min_transmission if exact else 0.0,
            c.error,
            c.rms,
        )

    return sorted(found, key=key)


def longest_link(c: Candidate[Any]) -> float:
    """Return a candidate's longest link.

    That is a link length, a side of its coupler triangle, or a slider-crank's offset (the frame
    must reach its line). :func:`path` ranks candidates whose longest link passes ``max_link``
    target sizes last.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.synthesis import Candidate, longest_link
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> longest_link(Candidate(fb, 0.0, 0.0, 0.0, (0.0, 6.3), True, "crank-rocker",
    ...                        0.4, False, "by hand", np.zeros(9)))   # A to P
    50.0
    """
    return _longest(c)


def source_text(source: str) -> str:
    """Word a candidate's ``source`` as the stage that found it.

    Examples
    --------
    >>> from linkage.synthesis import source_text
    >>> [source_text(s) for s in ("equation", "atlas", "global", "cognate")]
    ['curve-equation search', 'atlas search', 'global search', 'cognate search']
    """
    return f"{'curve-equation' if source == 'equation' else source} search"


def long_link(c: Candidate[Any], size: float) -> float | None:
    """Return ``c``'s longest link in target sizes when it passes :data:`LONG_LINK`, else None.

    :func:`path` ranks such candidates after the rest (its ``max_link``); the CLI table, the
    report's figure and its page say so with this ratio.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.synthesis import Candidate, long_link
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> c = Candidate(fb, 0.0, 0.0, 0.0, (0.0, 6.3), True, "crank-rocker", 0.4, False,
    ...               "by hand", np.zeros(9))
    >>> long_link(c, 2.0), long_link(c, 5.0)   # the arm A-P is 50
    (25.0, None)
    """
    ratio = _longest(c) / size
    return ratio if ratio > LONG_LINK else None


CHANGE_POINT_NEAR = 1e-3
"""A candidate whose Grashof sums (a slider-crank's ``|offset| + crank`` and rod) differ by less
than this fraction of the target's size is named near a change point (:func:`change_point_gap`)."""


def change_point_gap(c: Candidate[Any], size: float) -> tuple[float, str] | None:
    """Return ``c``'s distance from a change point and its law, within :data:`CHANGE_POINT_NEAR`.

    The gap between a four-bar's Grashof sums ``s + l`` and ``p + q`` (a slider-crank's
    ``|offset| + crank`` and rod), when less than ``CHANGE_POINT_NEAR · size`` and ``c`` is not
    classed a change point already; else None. Such a linkage turns fully on paper but can flip
    branch where its links lie flat.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.synthesis import Candidate, change_point_gap
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=15.000001)  # 30 vs 30.000001
    >>> c = Candidate(fb, 0.0, 0.0, 0.0, (0.0, 6.3), True, fb.grashof(), 0.0, False, "",
    ...               np.zeros(9))
    >>> gap, law = change_point_gap(c, 30.0)
    >>> print(f"{gap:.1e}", law)
    1.0e-06 s + l = p + q
    >>> change_point_gap(c, 1e-4) is None
    True
    """
    lk = c.linkage
    if isinstance(lk, SliderCrank):
        gap = abs(lk.coupler - (abs(lk.offset) + lk.crank))
        law = "|offset| + crank = rod"
    else:
        short, p, q, long = sorted((lk.ground, lk.crank, lk.coupler, lk.rocker))
        gap = abs(p + q - (short + long))
        law = "s + l = p + q"
    if c.grashof == "change-point" or not gap < CHANGE_POINT_NEAR * size:
        return None
    return gap, law


def _links(fb: FourBar | SliderCrank) -> tuple[float, ...]:
    """Return the link lengths ``lengths`` bounds: a four-bar's four, a slider-crank's two."""
    if isinstance(fb, SliderCrank):
        return fb.crank, fb.coupler
    return fb.ground, fb.crank, fb.coupler, fb.rocker


def _pins(fb: FourBar | SliderCrank) -> tuple[tuple[float, float], ...]:
    """Return the fixed pivots ``pivots`` bounds: a four-bar's O and C, a slider-crank's O."""
    return (fb.o,) if isinstance(fb, SliderCrank) else (fb.o, fb.c)


def _arms(fb: FourBar | SliderCrank) -> tuple[float, float]:
    """Return the coupler triangle's sides to the point: from A and from B (the slider's pin)."""
    along, left = fb.point
    return math.hypot(along, left), math.hypot(fb.coupler - along, left)


def _longest(c: Candidate[Any]) -> float:
    fb: FourBar | SliderCrank = c.linkage
    arms = _arms(fb)
    if isinstance(fb, SliderCrank):
        # The line's distance from the crank pivot counts as a link: the frame must reach it.
        return max(abs(fb.offset), fb.crank, fb.coupler, *arms)
    return max(fb.ground, fb.crank, fb.coupler, fb.rocker, *arms)


def _third_pivot(c: Candidate[Any]) -> complex:
    """Roberts' third pivot ``D``: the triangle ``O C D`` is directly similar to ``A B P``."""
    fb = c.linkage
    assert isinstance(fb, FourBar)
    o, cc = complex(*fb.o), complex(*fb.c)
    return o + (cc - o) * complex(*fb.point) / fb.coupler


def _cognates(a: Candidate[Any], b: Candidate[Any], tol: float) -> bool:
    """Whether ``b``'s ground pivots are those of one of ``a``'s Roberts cognates (four-bars)."""
    if not (isinstance(a.linkage, FourBar) and isinstance(b.linkage, FourBar)):
        return False
    o, c, d = complex(*a.linkage.o), complex(*a.linkage.c), _third_pivot(a)
    mine = (complex(*b.linkage.o), complex(*b.linkage.c))
    for pair in ((o, d), (c, d)):
        for p, q in (pair, pair[::-1]):
            if abs(mine[0] - p) <= tol and abs(mine[1] - q) <= tol:
                return True
    return False


def _same_pivots(a: Candidate[Any], b: Candidate[Any], tol: float) -> bool:
    """Whether two four-bars turn about the same two ground pivots (in either order)."""
    if not (isinstance(a.linkage, FourBar) and isinstance(b.linkage, FourBar)):
        return False
    pa = (complex(*a.linkage.o), complex(*a.linkage.c))
    pb = (complex(*b.linkage.o), complex(*b.linkage.c))
    return any(abs(pb[0] - p) <= tol and abs(pb[1] - q) <= tol for p, q in (pa, pa[::-1]))


NEAR = 0.05
"""Two candidates whose placed parameters all agree to this fraction of the target's size, or of
their longest link when both are longer (a slider line's direction to this many radians), are
one design: only the better is listed. A drawing of the whole linkage shows them alike."""


def _apart(a: NDArray[np.float64], b: NDArray[np.float64], kind: _Kind, size: float) -> float:
    """Return the largest difference of two placed parameter vectors of ``kind``, as a length.

    A slider line's direction counts its turn (modulo a full turn) times ``size``.
    """
    d = np.abs(a - b)
    if kind is SLIDER:
        turn = float(d[2]) % (2 * math.pi)
        d[2] = min(turn, 2 * math.pi - turn) * size
    return float(np.max(d, initial=0.0))


def _forms(c: Candidate[Any]) -> list[tuple[Any, NDArray[np.float64]]]:
    """Return ``c``'s linkage and parameters, and the other forms of the same linkage.

    For a four-bar the same driven at its rocker; for a slider-crank whose crank rocks (its
    circuit passes both reaches) the same with its line reversed (direction turned by π, offset
    negated).
    """
    forms: list[tuple[Any, NDArray[np.float64]]] = [(c.linkage, c.params)]
    if isinstance(c.linkage, SliderCrank):
        if not c.linkage.full_turn:
            x = c.params.copy()
            x[2] += math.pi
            x[3] = -x[3]
            forms.append((c.linkage, x))
        return forms
    if isinstance(c.linkage, FourBar):
        try:
            r = c.linkage.reversed()
        except LinkageError:
            return forms
        forms.append((r, _params_of(r)))
    return forms


def _params_of(fb: FourBar) -> NDArray[np.float64]:
    """``fb`` as a placed parameter vector (:data:`FOURBAR`'s layout; its assembly apart)."""
    return np.array(fb._p()[:9], dtype=np.float64)


def largest_distance(points: ArrayLike, path: ArrayLike) -> float:
    """Return the largest distance from the finite ``points`` (n, 2) to the polyline ``path``.

    A sample of ``path`` that is not finite breaks the polyline (no segment is drawn across
    it; ``linkage_core::polyline_distances``); ∞ when no point or no path sample is finite.

    >>> import linkage
    >>> linkage.synthesis.largest_distance([[1.0, 1.0], [float("nan"), 0.0]], [[0, 0], [2, 0]])
    1.0
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    p = np.ascontiguousarray(p[np.all(np.isfinite(p), axis=1)])
    d = _core.synthesis.polyline_distance(
        p, np.ascontiguousarray(path, dtype=np.float64).reshape(-1, 2)
    )
    return float(d.max()) if len(d) else math.inf


def _crossed(c: Candidate[Any]) -> bool:
    """Whether ``c`` is a four-bar in its crossed assembly (the flag its parameters go with)."""
    return isinstance(c.linkage, FourBar) and c.linkage.assembly == "crossed"


def _linkage_of(x: NDArray[np.float64], crossed: bool, kind: _Kind) -> FourBar | SliderCrank:
    """Return the linkage of the placed parameters ``x`` of ``kind``."""
    if kind is SLIDER:
        ox, oy, angle, offset, crank, coupler, along, left = (float(v) for v in x)
        return SliderCrank(crank, coupler, offset, (along, left), (ox, oy), angle)
    return FourBar(
        crank=x[4],
        coupler=x[5],
        rocker=x[6],
        point=(x[7], x[8]),
        assembly="crossed" if crossed else "open",
        o=(x[0], x[1]),
        c=(x[2], x[3]),
    )


def _turned(lo: float, hi: float) -> tuple[float, float]:
    """Return the crank range ``(lo, hi)`` moved by whole turns to start in [-180°, 180°).

    ``lo`` in [-180.05°, 179.95°): it reads in [-180.0°, 180.0°) to the 0.1° reports print. The
    same crank angles (a fit's angles may have turned past a full turn); every report and
    exported scene then shows ranges near zero (179.99999797° had read "180.0 … 540.0").
    """
    half = math.radians(0.05)
    k = math.floor((lo + math.pi + half) / (2 * math.pi))
    return lo - 2 * math.pi * k, hi - 2 * math.pi * k


def _failed(
    c: Candidate[Any],
    full_turn: bool,
    min_transmission: float,
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
) -> list[str]:
    """Return the names (:data:`CONSTRAINT_NAMES`) of the constraints ``c`` fails."""
    failed = []
    if full_turn and not c.full_turn:
        failed.append("full_turn")
    if c.min_transmission < min_transmission:
        failed.append("min_transmission")
    fb = c.linkage
    if lengths is not None:
        # The coupler triangle's sides to the point are links too (a foot bar): at most the
        # greatest length (a point may lie at a joint, so no least).
        links = _links(fb)
        if any(not (lengths[0] <= v <= lengths[1]) for v in links) or max(_arms(fb)) > lengths[1]:
            failed.append("lengths")
    if pivots is not None:
        (x0, y0), (x1, y1) = pivots
        if any(not (x0 <= px <= x1 and y0 <= py <= y1) for px, py in _pins(fb)):
            failed.append("pivots")
    return failed


def _kept(
    found: Sequence[Candidate[Any]],
    full_turn: bool,
    min_transmission: float,
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
    removed: Candidates | None = None,
) -> tuple[list[Candidate[Any]], Candidates]:
    """Split ``found`` by the constraints.

    Return the candidates that meet them, and an empty :class:`Candidates` that says what the
    constraints removed; ``removed`` (an earlier search's result) adds its own.
    """
    ok: list[Candidate[Any]] = []
    counts: dict[str, int] = dict(removed.removed) if removed is not None else {}
    out = [removed.closest_removed] if removed is not None and removed.closest_removed else []
    for c in found:
        failed = _failed(c, full_turn, min_transmission, lengths, pivots)
        if not failed:
            ok.append(c)
            continue
        out.append(c)
        for name in failed:
            counts[name] = counts.get(name, 0) + 1
    closest = min(out, key=lambda c: c.error, default=None)
    fails = (
        () if closest is None else _failed(closest, full_turn, min_transmission, lengths, pivots)
    )
    counts = {k: counts[k] for k in CONSTRAINT_NAMES if k in counts}
    return ok, Candidates((), counts, closest, fails)


def why_none(found: Candidates, names: dict[str, str], unit: str = "") -> tuple[str, str | None]:
    """Say why :func:`path` returned no candidate, naming the constraints by ``names``.

    Return the sentence and the constraint to blame (of :data:`CONSTRAINT_NAMES`: the first
    the closest removed fit fails), or None when no fit was valid at all. ``names`` maps
    :data:`CONSTRAINT_NAMES` and ``"refine"`` to what the caller calls them.

    Examples
    --------
    >>> from linkage.synthesis import Candidates, why_none
    >>> why_none(Candidates(), {})
    ('every linkage tried failed to assemble over its circuit or switched branch', None)
    """
    gone = found.closest_removed
    if gone is None:
        return "every linkage tried failed to assemble over its circuit or switched branch", None
    fails = found.closest_fails
    counts = ", ".join(f"{names[k]}: {n}" for k, n in found.removed.items())
    u = f" {unit}" if unit else ""
    # How far the closest fit is from each constraint it fails: how far to loosen.
    lk = gone.linkage
    links = _links(lk)
    values = {
        "full_turn": f"its crank rocks, {gone.grashof}",
        "min_transmission": f"μ {gone.min_transmission_deg:.1f}°",
        "lengths": f"links {min(links):.3g} … {max(*links, *_arms(lk)):.3g}{u}",
        "pivots": "pivots " + ", ".join(f"({x:.3g}, {y:.3g})" for x, y in _pins(lk)),
    }
    failed = [f"{names[k]} ({values[k]})" for k in fails]
    which = failed[0] if len(failed) == 1 else ", ".join(failed[:-1]) + " and " + failed[-1]
    return (
        f"every valid fit fails a constraint (fits failing {counts}); the closest, error "
        f"{gone.error:.3g}{u}, fails {which}: loosen {'it' if len(fails) == 1 else 'them'}, "
        f"or refine more atlas matches ({names.get('refine', 'refine')})",
        fails[0],
    )
