"""Figures as a report prints them: rows of figure, value, unit and error estimate.

Numbers carry the digits their error supports, in the units of the scene; the sample counts at which
a run is repeated to estimate its errors are chosen here too.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Union

import numpy as np
from numpy.typing import NDArray

from linkage.drives.cam import CamProfile
from linkage.drives.drive import Drive
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.slider_crank import SliderCrank
from linkage.kinematics.sweep import Sweep
from linkage.kinetostatics.forces import Forces
from linkage.motion.geometry import StraightPart
from linkage.scene.builders import check_counts as check_counts  # its home: the run's counts
from linkage.scene.schema import Scene
from linkage.synthesis import Candidate
from linkage.walking.walker import Simulation, Walker

__all__ = [
    "SIG_MAX",
    "SIG_UNKNOWN",
    "Result",
    "Row",
    "SynthesisRun",
    "branch_text",
    "branch_word",
    "check_counts",
    "crank_phase_deg",
    "exact",
    "format_error",
    "format_number",
    "length_unit",
    "pair",
    "row",
    "sci",
    "significant_digits",
    "spread",
    "torque_unit",
    "unit_label",
    "versus",
]

Array = NDArray[np.float64]
Value = Union[float, int, str, tuple[float, ...], None]
"""A figure's typed value: a number, a pair such as a range, a word (a class), or ``None`` for
a value that is not a finite number (an infinite radius, an undefined margin)."""


class _AsText:
    """The default :attr:`Row.value`: the row's text (a word, a list of names)."""


_AS_TEXT = _AsText()


class Row(tuple[str, str, str, str]):
    """One figure of the table, as the terminal shows it and typed for the JSON summary.

    Iterable as four strings — (figure, value, unit, error estimate) — and carrying the typed
    :attr:`value`, :attr:`unit` and :attr:`error` (a number, or ``None`` when there is none).
    """

    value: Value
    error: float | None
    exact: bool

    def __new__(
        cls,
        figure: str,
        text: str,
        unit: str = "",
        note: str = "",
        value: Value | _AsText = _AS_TEXT,
        error: float | None = None,
        exact: bool = False,
    ) -> Row:
        """Make a row; ``value`` defaults to ``text`` (``None`` when it is empty)."""
        self = super().__new__(cls, (figure, text, unit, note))
        self.value = (text or None) if isinstance(value, _AsText) else value
        self.error = error
        self.exact = exact
        return self

    @property
    def figure(self) -> str:
        """The figure's name."""
        return self[0]

    @property
    def text(self) -> str:
        """The value as printed."""
        return self[1]

    @property
    def unit(self) -> str:
        """The unit as printed."""
        return self[2]

    @property
    def note(self) -> str:
        """The error estimate as printed (or a note such as ``exact``)."""
        return self[3]


@dataclass
class SynthesisRun:
    """What the search of a ``[synthesis]`` scene found: the target and the candidates."""

    target: Array
    """The target points, ``(n, 2)``, as read."""
    closed: bool
    candidates: list[Candidate[FourBar | SliderCrank]]
    """Best (smallest largest error) first; each placed in the target's frame."""
    curves: list[Array]
    """Each candidate's coupler curve over its whole circuit, ``(samples, 2)``."""
    size: float
    """The target's size: the RMS distance of its points from their centroid."""
    best: Sweep
    """The best candidate's circuit (``FourBar.circuit``): its joints for the drawings."""


@dataclass
class Result:
    """Everything a run computed."""

    scene: Scene
    time: Array
    theta: Array
    figures: list[tuple[str, str, str, str]] = field(default_factory=list)
    """The figures table: each a :class:`Row` (four strings, with the typed value, unit and
    error as attributes); typed as plain 4-tuples so that callers may add rows of their own."""
    stages: dict[str, float] = field(default_factory=dict)
    """Seconds per stage, in the order run: only the stages the outputs needed."""
    sweep: Sweep | None = None
    rates: Sweep | None = None
    geometry: Sweep | None = None
    straight: StraightPart | None = None
    forces: Forces | None = None
    cam: CamProfile | None = None
    """The cam's profile, with the output ``cam``."""
    simulation: Simulation | None = None
    mechanism: FourBar | Mechanism | None = None
    walker: Walker | None = None
    drive: Drive | None = None
    """The drive the run used (its crank angles over time)."""
    synthesis: SynthesisRun | None = None
    """A ``[synthesis]`` scene's search (then there is no mechanism, walker or sweep, and
    ``time`` and ``theta`` are empty)."""
    arrays: dict[str, Array] = field(default_factory=dict)
    check_samples: tuple[int, ...] = ()
    """Sample counts of the runs at other resolutions that give the sampled figures their
    error estimates (:func:`check_counts`)."""


# -- numbers as the table prints them ---------------------------------------------------------

SIG_MAX = 6
"""Significant digits of a figure known to better than a millionth (exact, or nearly)."""
SIG_UNKNOWN = 4
"""Significant digits of a figure without an error estimate."""


def significant_digits(x: float, error: float | None) -> int:
    """Return the digits of ``x`` its ``error`` supports.

    Down to one digit below the error's leading digit, between 2 and :data:`SIG_MAX`
    (:data:`SIG_UNKNOWN` without an error).

    Examples
    --------
    >>> from linkage.figures import significant_digits
    >>> significant_digits(44.2523, 0.155), significant_digits(44.2523, 0.0)
    (4, 6)

    Without an error estimate (``None`` or NaN) it is :data:`SIG_UNKNOWN`; for a NaN or zero
    value, 2:

    >>> significant_digits(44.2523, None), significant_digits(44.2523, float("nan"))
    (4, 4)
    >>> significant_digits(float("nan"), 0.1), significant_digits(0.0, 0.1)
    (2, 2)
    """
    if error is None or not math.isfinite(error) or error < 0:
        return SIG_UNKNOWN
    if x == 0 or not math.isfinite(x):
        return 2
    if error == 0:
        return SIG_MAX
    digits = math.floor(math.log10(abs(x))) - math.floor(math.log10(error)) + 2
    return max(2, min(SIG_MAX, digits))


def format_number(x: float, error: float | None = None, digits: int | None = None) -> str:
    """Format ``x`` with the significant digits its ``error`` supports (or ``digits``).

    Positional from 0.001 to 10⁶, else ``1.4e-4`` style; ``∞``/``−∞``/``NaN`` spelled as such. An
    exact value (``error == 0``) gets up to :data:`SIG_MAX` digits, without trailing zeros.

    >>> from linkage.figures import format_number
    >>> format_number(44.2523, 0.155), format_number(0.0014, 1e-7), format_number(6.6e-4, 1.2e-4)
    ('44.25', '0.00140000', '6.6e-4')
    >>> format_number(12741226936709.7, None), format_number(3, 0), format_number(2 / 3, 0)
    ('1.274e13', '3', '0.666667')
    """
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "∞" if x > 0 else "−∞"
    sig = digits if digits is not None else significant_digits(x, error)
    if x == 0:
        return "0"

    def trim(text: str) -> str:
        if error == 0 and digits is None and "." in text:
            return text.rstrip("0").rstrip(".")
        return text

    mag = math.floor(math.log10(abs(x)))
    if -3 <= mag < 6:
        text = f"{x:.{max(0, sig - 1 - mag)}f}"
        if float(text) != 0 or x == 0:
            return trim(text)
    mant, _, exp = f"{x:.{sig - 1}e}".partition("e")
    return f"{trim(mant)}e{int(exp)}"


def format_error(error: float | None) -> str:
    """Format an error estimate to two significant digits (``0`` when the values agreed exactly).

    As :func:`format_number` does, an error from 100 to 10⁶ is printed positionally, whole: it
    keeps every digit of its integer part.

    Examples
    --------
    >>> from linkage.figures import format_error
    >>> format_error(0.01523), format_error(3.2e-7), format_error(0.0)
    ('0.015', '3.2e-7', '0')
    >>> format_error(None), format_error(float("nan"))
    ('unknown', 'unknown')
    >>> format_error(1234.5)
    '1234'
    """
    if error is None or not math.isfinite(error):
        return "unknown"
    return "0" if error == 0 else format_number(error, digits=2)


def unit_label(units: str) -> str:
    """Return a length unit as printed: ``units``, or ``length units`` when it is empty.

    Examples
    --------
    >>> from linkage.figures import unit_label
    >>> unit_label("mm"), unit_label("")
    ('mm', 'length units')
    """
    return units or "length units"


def branch_word(lk: FourBar | SliderCrank) -> str:
    """Return what names a linkage's branch: a four-bar's ``assembly``, a slider's ``reach``.

    Examples
    --------
    >>> import linkage
    >>> from linkage.figures import branch_word
    >>> branch_word(linkage.catalog.hoecken()), branch_word(linkage.SliderCrank(2, 5))
    ('assembly', 'reach')
    """
    return "reach" if isinstance(lk, SliderCrank) else "assembly"


def branch_text(lk: FourBar | SliderCrank) -> str:
    """Return the branch a linkage is on, in words: ``open assembly``, ``slider ahead``.

    Examples
    --------
    >>> import linkage
    >>> from linkage.figures import branch_text
    >>> branch_text(linkage.catalog.hoecken()), branch_text(linkage.SliderCrank(2, 5))
    ('open assembly', 'slider ahead')
    """
    return f"slider {lk.reach}" if isinstance(lk, SliderCrank) else f"{lk.assembly} assembly"


def length_unit(scene: Scene) -> str:
    """Return the scene's length unit, or ``length units`` when the scene names none.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.figures import length_unit
    >>> length_unit(Scene("leg", None, (), units="mm")), length_unit(Scene("leg", None, ()))
    ('mm', 'length units')
    """
    return unit_label(scene.units)


def crank_phase_deg(scene: Scene) -> float:
    """Return the phase of a ``[mechanism]`` scene's crank joint in degrees (0 if none).

    The crank is at the drive angle θ plus it: an exported synthesis candidate's is the start of
    its crank range.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.figures import crank_phase_deg
    >>> crank = {"kind": "crank", "name": "A", "centre": "O", "radius": 1, "phase_deg": 180}
    >>> crank_phase_deg(Scene("leg", None, (), mechanism={"joints": [crank]}))
    180.0
    >>> crank_phase_deg(Scene("leg", None, (), mechanism={"catalog": "hoecken"}))
    0.0
    """
    joints = (scene.mechanism or {}).get("joints", [])
    return next((float(j.get("phase_deg", 0.0)) for j in joints if j.get("kind") == "crank"), 0.0)


def torque_unit(scene: Scene) -> str:
    """Return the unit of a torque: force × length, with masses in kg and times in s.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.figures import torque_unit
    >>> [torque_unit(Scene("leg", None, (), units=u)) for u in ("m", "mm", "")]
    ['N·m', 'kg·mm²/s²', 'kg·(length unit)²/s²']
    """
    if scene.units == "m":
        return "N·m"
    if scene.units:
        return f"kg·{scene.units}²/s²"
    return "kg·(length unit)²/s²"


def sci(x: float) -> str:
    """Format ``x`` to two significant digits (see :func:`format_number`).

    A value from 100 to 10⁶ is printed positionally, whole (``1234``, not ``1.2e3``).

    Examples
    --------
    >>> from linkage.figures import sci
    >>> sci(0.0123456), sci(1.23456e-5), sci(-2.5e9)
    ('0.012', '1.2e-5', '-2.5e9')
    >>> sci(float("nan")), sci(float("inf"))
    ('NaN', '∞')
    >>> sci(1234.5), sci(2.5e6)
    ('1234', '2.5e6')
    """
    return format_number(x, digits=2)


def spread(x: float, others: Sequence[float | None]) -> float | None:
    """Return the largest difference between ``x`` and the same figure at the other resolutions.

    A missing figure (``None``) is skipped; ``None`` when none is left or a difference is not
    finite.

    Examples
    --------
    >>> from linkage.figures import spread
    >>> round(spread(1.0, [1.1, None, 0.95]), 12)
    0.1
    >>> spread(1.0, [None]), spread(1.0, [float("nan")]), spread(float("inf"), [1.0])
    (None, None, None)
    """
    diffs = [abs(x - o) for o in others if o is not None]
    if not diffs or not all(math.isfinite(d) for d in diffs):
        return None
    return max(diffs)


def versus(ns: Sequence[int]) -> str:
    """Say which sample counts an error estimate compares with: ``vs 360 and 1441 samples``.

    Examples
    --------
    >>> from linkage.figures import versus
    >>> versus([360, 1441])
    'vs 360 and 1441 samples'
    >>> versus([])
    'no second resolution within the memory limit'
    """
    if not ns:
        return "no second resolution within the memory limit"
    return f"vs {' and '.join(map(str, ns))} samples"


def row(
    figure: str,
    x: float,
    unit: str,
    others: Sequence[float | None],
    ns: Sequence[int],
    note: str = "",
) -> Row:
    """Make the row of a sampled figure: ``x`` at the run's samples, with its error estimate.

    The error is estimated as the largest difference from ``others``, the same figure at ``ns``
    samples.

    Examples
    --------
    >>> from linkage.figures import row
    >>> r = row("stride", 44.2523, "mm", [44.1, 44.3], [360, 1441])
    >>> tuple(r), round(r.error, 4)
    (('stride', '44.25', 'mm', '±0.15 (vs 360 and 1441 samples)'), 0.1523)

    A NaN figure has neither value nor error:

    >>> r = row("stride", float("nan"), "mm", [44.1], [360])
    >>> tuple(r), r.value, r.error
    (('stride', 'NaN', 'mm', '±unknown (vs 360 samples)'), None, None)
    """
    err = spread(x, others) if math.isfinite(x) else None
    told = f"±{format_error(err)} ({versus(ns)})"
    return Row(
        figure,
        format_number(x, err),
        unit,
        f"{told}; {note}" if note else told,
        value=x if math.isfinite(x) else None,
        error=err,
    )


def exact(figure: str, x: float, unit: str, note: str = "exact", error: float = 0.0) -> Row:
    """Make the row of a figure that does not depend on the sampling (``error``: its round-off).

    Examples
    --------
    >>> from linkage.figures import exact
    >>> r = exact("duration", 2 / 3, "s")
    >>> tuple(r), r.exact
    (('duration', '0.666667', 's', 'exact'), True)
    """
    return Row(figure, format_number(x, error), unit, note, value=x, error=error, exact=True)


def pair(
    figure: str,
    pair: tuple[float, float],
    unit: str,
    others: Sequence[tuple[float, float] | None],
    ns: Sequence[int],
    sep: str = " … ",
) -> Row:
    """Make the row of a pair of sampled figures (a range, min/max): the larger error of the two.

    Examples
    --------
    >>> from linkage.figures import pair
    >>> tuple(pair("x range", (1.0, 2.0), "mm", [(1.01, 2.0)], [360]))
    ('x range', '1.000 … 2.000', 'mm', '±0.010 (vs 360 samples)')

    Without the other resolution's pair the error is unknown:

    >>> tuple(pair("x range", (1.0, 2.0), "mm", [None], [360]))
    ('x range', '1.000 … 2.000', 'mm', '±unknown (vs 360 samples)')
    """
    e0 = spread(pair[0], [o[0] if o else None for o in others])
    e1 = spread(pair[1], [o[1] if o else None for o in others])
    err = None if e0 is None or e1 is None else max(e0, e1)
    text = sep.join(format_number(v, err) for v in pair)
    return Row(
        figure,
        text,
        unit,
        f"±{format_error(err)} ({versus(ns)})",
        value=tuple(float(v) for v in pair),
        error=err,
    )


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Row": Row, "SynthesisRun": SynthesisRun, "Result": Result}
for _cls in __test__.values():
    _cls.__module__ = "linkage.figures"
