"""Running a scene: build the study, run only the stages its outputs need, collect figures with
their error estimates and the time of each stage.

The builders (:func:`build_mechanism`, :func:`build_walker`, :func:`build_drive`,
:func:`build_cam`, :func:`build_masses`) turn any error into a :class:`SceneError` located at
the key that caused it, and :func:`validate` — called by :func:`linkage.scene.parse` — runs them
once without computing anything, checks the memory estimate and finds a first assembled sample,
so ``linkage check`` refuses whatever ``linkage run`` would.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import partial
from typing import Any, Union

import numpy as np
from numpy.typing import NDArray

from linkage import catalog
from linkage._core import LinkageError
from linkage._fourbar import FourBar
from linkage._mechanism import Mechanism
from linkage._sweep import Sweep
from linkage.drive import (
    ConstantSpeed,
    CrankSchedule,
    Geared,
    GearTrain,
    Program,
    Segment,
    crank_schedule,
)
from linkage.forces import Forces, LinkMass, PointLoad, forces
from linkage.geometry import StraightPart, straightness, three_point_centres
from linkage.scene import (
    CYCLES_MAX,
    MEMORY_CAP,
    SAMPLES_MAX,
    SPEED_RANGE,
    TIME_RANGE,
    Scene,
    SceneError,
    _did_you_mean,
)
from linkage.walker import Simulation, Walker, gait_phases

Array = NDArray[np.float64]
Value = Union[float, int, str, tuple[float, ...], None]
"""A figure's typed value: a number, a pair such as a range, a word (a class), or ``None`` for
a value that is not a finite number (an infinite radius, an undefined margin)."""


class _AsText:
    """The default :attr:`Row.value`: the row's text (a word, a list of names)."""


_AS_TEXT = _AsText()


class Row(tuple[str, str, str, str]):
    """One figure of the table: iterable as four strings — (figure, value, unit, error
    estimate) — as the terminal shows them, and carrying the typed :attr:`value`, :attr:`unit`
    and :attr:`error` (a number, or ``None`` when there is none) for the JSON summary.
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
        self = super().__new__(cls, (figure, text, unit, note))
        self.value = (text or None) if isinstance(value, _AsText) else value
        self.error = error
        self.exact = exact
        return self

    @property
    def figure(self) -> str:
        return self[0]

    @property
    def text(self) -> str:
        return self[1]

    @property
    def unit(self) -> str:
        return self[2]

    @property
    def note(self) -> str:
        return self[3]


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
    cam: Any = None
    simulation: Simulation | None = None
    mechanism: FourBar | Mechanism | None = None
    walker: Walker | None = None
    drive: Any = None
    """The drive the run used (its crank angles over time)."""
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
    """Digits of ``x`` its ``error`` supports: down to one digit below the error's leading
    digit, between 2 and :data:`SIG_MAX` (:data:`SIG_UNKNOWN` without an error)."""
    if error is None or not math.isfinite(error) or error < 0:
        return SIG_UNKNOWN
    if x == 0 or not math.isfinite(x):
        return 2
    if error == 0:
        return SIG_MAX
    digits = math.floor(math.log10(abs(x))) - math.floor(math.log10(error)) + 2
    return max(2, min(SIG_MAX, digits))


def format_number(x: float, error: float | None = None, digits: int | None = None) -> str:
    """``x`` with the significant digits its ``error`` supports (or ``digits``): positional
    from 0.001 to 10⁶, else ``1.4e-4`` style; ``∞``/``−∞``/``NaN`` spelled as such. An exact
    value (``error == 0``) gets up to :data:`SIG_MAX` digits, without trailing zeros.

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
    """An error estimate to two significant digits (``0`` when the values agreed exactly)."""
    if error is None or not math.isfinite(error):
        return "unknown"
    return "0" if error == 0 else format_number(error, digits=2)


def unit_label(units: str) -> str:
    """A length unit as printed: ``units``, or ``length units`` when it is empty."""
    return units or "length units"


def length_unit(scene: Scene) -> str:
    """The scene's length unit, or ``length units`` when the scene names none."""
    return unit_label(scene.units)


def torque_unit(scene: Scene) -> str:
    """The unit of a torque: force × length, with masses in kg and times in s."""
    if scene.units == "m":
        return "N·m"
    if scene.units:
        return f"kg·{scene.units}²/s²"
    return "kg·(length unit)²/s²"


def _e(x: float) -> str:
    return format_number(x, digits=2)


def _spread(x: float, others: Sequence[float | None]) -> float | None:
    """The largest difference between ``x`` and the same figure at the other resolutions."""
    diffs = [abs(x - o) for o in others if o is not None]
    if not diffs or not all(math.isfinite(d) for d in diffs):
        return None
    return max(diffs)


def _vs(ns: Sequence[int]) -> str:
    if not ns:
        return "no second resolution within the memory limit"
    return f"vs {' and '.join(map(str, ns))} samples"


def _row(
    figure: str,
    x: float,
    unit: str,
    others: Sequence[float | None],
    ns: Sequence[int],
    note: str = "",
) -> Row:
    """A sampled figure: ``x`` at the run's samples, its error estimated as the largest
    difference from ``others``, the same figure at ``ns`` samples."""
    err = _spread(x, others) if math.isfinite(x) else None
    told = f"±{format_error(err)} ({_vs(ns)})"
    return Row(
        figure,
        format_number(x, err),
        unit,
        f"{told}; {note}" if note else told,
        value=x if math.isfinite(x) else None,
        error=err,
    )


def _exact(figure: str, x: float, unit: str, note: str = "exact", error: float = 0.0) -> Row:
    """A figure that does not depend on the sampling (``error`` its round-off, if known)."""
    return Row(figure, format_number(x, error), unit, note, value=x, error=error, exact=True)


def _pair(
    figure: str,
    pair: tuple[float, float],
    unit: str,
    others: Sequence[tuple[float, float] | None],
    ns: Sequence[int],
    sep: str = " … ",
) -> Row:
    """A pair of sampled figures (a range, min/max), the error the larger of the two."""
    e0 = _spread(pair[0], [o[0] if o else None for o in others])
    e1 = _spread(pair[1], [o[1] if o else None for o in others])
    err = None if e0 is None or e1 is None else max(e0, e1)
    text = sep.join(format_number(v, err) for v in pair)
    return Row(
        figure,
        text,
        unit,
        f"±{format_error(err)} ({_vs(ns)})",
        value=tuple(float(v) for v in pair),
        error=err,
    )


def _affordable_checks(
    scene: Scene, study: FourBar | Mechanism | Walker, n: int
) -> tuple[int, ...]:
    """:func:`check_counts` within the memory limit, with every run alive at once: both when
    they fit, else the half only, else none (the figures then carry no error estimate)."""
    half, double = check_counts(n)
    if estimate_memory(scene, study, n + half + double) <= MEMORY_CAP:
        return (half, double)
    if estimate_memory(scene, study, n + half) <= MEMORY_CAP:
        return (half,)
    return ()


def check_counts(n: int, double: bool = True) -> tuple[int, ...]:
    """The sample counts a run of ``n`` samples is checked at: about half as many, on a grid
    that shares only its ends with the run's (``n_half − 1`` coprime to ``n − 1``, so that no
    extreme is found again at a shared sample), and — when ``double`` — twice as many, on the
    run's grid refined (every sample and the midpoints). The first catches aliasing (a
    figure that depends on where the samples fall), the second the slow convergence of
    extremes; a figure's error estimate is its largest difference from the two.

    >>> check_counts(721), check_counts(8, double=False)
    ((360, 1441), (4,))
    """
    half = max(3, (n - 1) // 2 + 1)
    while half > 3 and math.gcd(half - 1, n - 1) != 1:
        half -= 1
    return (half, 2 * n - 1) if double else (half,)


# What `run` may raise from a stage besides LinkageError: numpy and arithmetic errors on data
# the validation did not foresee, turned into a LinkageError naming the stage.
_ARITHMETIC = (ValueError, ArithmeticError, IndexError, TypeError)

CHUNK = 1 << 16
"""Samples per block when validation walks a run's crank angles (bounded memory)."""


@contextmanager
def _blame(scene: Scene, path: tuple[Any, ...], key: str) -> Iterator[None]:
    """Turn an error from building ``key`` into a located :class:`SceneError`."""
    try:
        yield
    except SceneError:
        raise
    except (LinkageError, *_ARITHMETIC) as exc:
        raise scene.error(path, key, str(exc) or type(exc).__name__) from None


def build_mechanism(scene: Scene) -> FourBar | Mechanism:
    """The scene's mechanism.

    Raises
    ------
    SceneError
        Located at the key that made the build fail.
    """
    m = scene.mechanism or {}
    sec = ("mechanism",)
    if "catalog" in m:
        with _blame(scene, sec, "catalog"):
            item = catalog.get(m["catalog"])
        scale = float(m.get("scale", 1.0))
        if scale != 1.0:
            if not isinstance(item, FourBar):
                raise scene.error(
                    sec, "scale", f"only catalogue four-bars can be scaled, not {m['catalog']!r}"
                )
            with _blame(scene, sec, "scale"):
                item = _scaled(item, scale)
        return item
    if "ground" in m:
        with _blame(scene, sec, "ground"):
            return FourBar(
                ground=m["ground"],
                crank=m["crank"],
                coupler=m["coupler"],
                rocker=m["rocker"],
                point=tuple(m.get("point", (0.0, 0.0))),
                assembly=m.get("assembly", "open"),
            )
    mech = Mechanism()
    for idx, j in enumerate(m["joints"]):
        with _blame(scene, ("mechanism", "joints", idx), JOINT_KEY[j["kind"]]):
            _add_joint(mech, j)
    if "trace" in m:
        with _blame(scene, sec, "trace"):
            mech.trace = m["trace"]
    return mech


JOINT_KEY = {"fixed": "at", "crank": "radius", "dyad": "r2", "point": "on"}
"""The key blamed when building a joint of each kind fails."""


def _scaled(fb: FourBar, k: float) -> FourBar:
    """``fb`` with every length, its pivots and its coupler point multiplied by ``k``."""
    return FourBar(
        o=(fb.o[0] * k, fb.o[1] * k),
        c=(fb.c[0] * k, fb.c[1] * k),
        crank=fb.crank * k,
        coupler=fb.coupler * k,
        rocker=fb.rocker * k,
        point=(fb.point[0] * k, fb.point[1] * k),
        assembly=fb.assembly,
    )


def _turn_program(segments: Any) -> Program:
    """A program over one turn from ``duration_deg``/``rise``/``law`` segments (a cam, a lift)."""
    segs = [
        Segment(math.radians(s["duration_deg"]), s.get("rise", 0.0), s.get("law")) for s in segments
    ]
    return Program(0.0, segs)


def build_walker(scene: Scene) -> Walker:
    """The scene's walker: a catalogue model, or legs built from catalogue four-bars.

    Raises
    ------
    SceneError
        Located at the key that made the build fail.
    """
    from dataclasses import replace

    from linkage.walker import Leg

    w = scene.walker or {}
    sec = ("walker",)
    if "model" in w:
        with _blame(scene, sec, "model"):
            walker: Walker = getattr(catalog, w["model"])()
    else:
        legs = []
        for idx, spec in enumerate(w["legs"]):
            lp = ("walker", "legs", idx)
            with _blame(scene, lp, "catalog"):
                fb = catalog.get(spec["catalog"])
            if not isinstance(fb, FourBar):
                raise scene.error(lp, "catalog", f"{spec['catalog']!r} is not a four-bar")
            k = float(spec.get("scale", 1.0))
            if k != 1.0:
                with _blame(scene, lp, "scale"):
                    fb = _scaled(fb, k)
            lift = None
            if "lift" in spec:
                with _blame(scene, lp, "lift"):
                    lift = _turn_program(spec["lift"])
            with _blame(scene, lp, "name"):
                legs.append(
                    Leg(
                        spec["name"],
                        fb,
                        mount=tuple(float(v) for v in spec["mount"]),  # type: ignore[arg-type]
                        phase=math.radians(spec.get("phase_deg", 0.0)),
                        plane=spec.get("plane", "sagittal"),
                        mirror=bool(spec.get("mirror", False)),
                        foot_offset=tuple(spec.get("foot_offset", (0.0, 0.0))),
                        lift=lift,
                        pad=float(spec.get("pad", 0.0)),
                    )
                )
        with _blame(scene, sec, "legs"):
            walker = Walker(legs)
    names = [leg.name for leg in walker.legs]
    if "gait" in w:
        with _blame(scene, sec, "gait"):
            walker = walker.with_phases([float(p) for p in gait_phases(w["gait"], names)])
    if "phases_deg" in w:
        if len(w["phases_deg"]) != len(names):
            raise scene.error(
                sec,
                "phases_deg",
                f"need {len(names)} phases, one per leg ({', '.join(names)}), "
                f"got {len(w['phases_deg'])}",
            )
        with _blame(scene, sec, "phases_deg"):
            walker = walker.with_phases([math.radians(p) for p in w["phases_deg"]])
    if "pad" in w:
        with _blame(scene, sec, "pad"):
            walker = Walker(
                [replace(leg, pad=float(w["pad"])) for leg in walker.legs],
                walker.cg,
                walker.ground_tol,
                walker.body_underside,
            )
    if "cg" in w or "ground_tol" in w:
        with _blame(scene, sec, "cg" if "cg" in w else "ground_tol"):
            walker = Walker(
                walker.legs,
                cg=tuple(w.get("cg", walker.cg)),
                ground_tol=w.get("ground_tol", walker.ground_tol),
                body_underside=walker.body_underside,
            )
    return walker


def build_drive(scene: Scene, leg: FourBar | Mechanism) -> tuple[Any, float]:
    """The scene's drive and its natural duration (one crank cycle or program period).

    Raises
    ------
    SceneError
        Located at the key that made the build fail.
    """
    d = scene.drive
    sec = ("drive",)
    train = None
    if "gears" in d:
        with _blame(scene, sec, "gears"):
            train = GearTrain.simple(d["gears"])
    kind = d["kind"]
    if kind == "constant":
        key = "rpm" if "rpm" in d else "omega"
        motor = d["rpm"] * 2 * math.pi / 60 if "rpm" in d else d["omega"]
        drive: Any = ConstantSpeed(motor)
        crank = motor * (train.ratio * train.sign if train else 1.0)
        lo, hi = SPEED_RANGE
        if not lo <= abs(crank) <= hi:
            raise scene.error(
                sec,
                "gears" if train else key,
                f"the crank turns at {abs(crank):.3g} rad/s"
                + (" through the gears" if train else "")
                + f"; it must be between {lo:g} and {hi:g} rad/s",
            )
        period = 2 * math.pi / abs(crank)
    elif kind == "program":
        with _blame(scene, sec, "segments"):
            segs = [
                Segment(s["duration"], math.radians(s.get("rise_deg", 0.0)), s.get("law"))
                for s in d["segments"]
            ]
        with _blame(scene, sec, "start_deg"):
            drive = Program(math.radians(d.get("start_deg", 0.0)), segs)
        period = drive.period
    else:
        try:
            drive = crank_schedule(leg, d["foot_speed"], d["duty_factor"])
        except SceneError:
            raise
        except (LinkageError, *_ARITHMETIC) as exc:
            key = "duty_factor" if "duty" in str(exc) else "foot_speed"
            raise scene.error(sec, key, f"no crank schedule: {exc}") from None
        period = drive.period
    if train is not None and kind != "schedule":
        drive = Geared(drive, train)
    return drive, period


def run_duration(scene: Scene, period: float) -> float:
    """The run's length in seconds: ``duration``, or ``cycles`` (default 1) times ``period``.

    Raises
    ------
    SceneError
        When it is not a positive finite time of at most a million cycles.
    """
    d = scene.drive
    key = "duration" if "duration" in d else "cycles"
    duration = float(d.get("duration", period * d.get("cycles", 1.0)))
    if not (math.isfinite(duration) and TIME_RANGE[0] <= duration):
        raise scene.error(
            ("drive",),
            key,
            f"the run lasts {duration:.3g} s; it must be at least {TIME_RANGE[0]:g} s",
        )
    if not math.isfinite(period) or period <= 0 or duration / period > CYCLES_MAX:
        raise scene.error(
            ("drive",),
            key,
            f"the run lasts {duration:.3g} s, {duration / period:.3g} cycles of {period:.3g} s; "
            f"at most {CYCLES_MAX:g} cycles",
        )
    return duration


def build_cam(scene: Scene) -> Any:
    """The scene's disc cam (None without a [cam] section).

    Raises
    ------
    SceneError
        Located at the key that made the build fail.
    """
    from linkage.cam import DiscCam

    if scene.cam is None:
        return None
    c = scene.cam
    sec = ("cam",)
    with _blame(scene, sec, "segments"):
        program = _turn_program(c["segments"])
    with _blame(scene, sec, "base_radius"):
        return DiscCam(
            program,
            c["base_radius"],
            roller_radius=c.get("roller_radius"),
            offset=c.get("offset", 0.0),
            pressure_limit=math.radians(c.get("pressure_limit_deg", 30.0)),
        )


def build_masses(
    scene: Scene, mech: FourBar | Mechanism
) -> tuple[dict[str, LinkMass], list[PointLoad]]:
    """The scene's link masses and point loads, checked against the mechanism's links and
    joints.

    Raises
    ------
    SceneError
        Located at the link or load that is wrong.
    """
    m = mech.mechanism() if isinstance(mech, FourBar) else mech
    links = m.links
    moving = list(links[1:])
    masses: dict[str, LinkMass] = {}
    for name, v in (scene.masses or {}).items():
        if name not in moving:
            raise scene.error(
                ("masses",),
                name,
                f"unknown link {name!r}{_did_you_mean(name, moving)}; "
                f"the moving links are {', '.join(moving)}",
            )
        with _blame(scene, ("masses", name), "mass"):
            masses[name] = LinkMass(
                v["mass"], tuple(v.get("centre", (0.0, 0.0))), v.get("inertia", 0.0)
            )
    if scene.wants("torque"):
        missing = [name for name in moving if name not in masses]
        if missing:
            raise scene.error(
                (),
                "masses",
                f"missing for links {', '.join(missing)}: 'torque' needs every moving link "
                "(mass = 0 for a massless one)",
            )
    loads = []
    for k, ld in enumerate(scene.loads):
        if ld["link"] not in links:
            raise scene.error(
                ("loads", k),
                "link",
                f"unknown link {ld['link']!r}{_did_you_mean(ld['link'], links)}; "
                f"links are {', '.join(links)}",
            )
        if ld["joint"] not in m.joint_names:
            raise scene.error(
                ("loads", k),
                "joint",
                f"unknown joint {ld['joint']!r}{_did_you_mean(ld['joint'], m.joint_names)}; "
                f"joints are {', '.join(m.joint_names)}",
            )
        with _blame(scene, ("loads", k), "force"):
            loads.append(
                PointLoad(ld["link"], ld["joint"], tuple(ld["force"]), ld.get("torque", 0.0))
            )
    return masses, loads


# -- validation: everything `run` would reject, found without running ------------------------


def validate(scene: Scene, samples: int | None = None) -> None:
    """Build the scene's study without running it, so that whatever :func:`run` would reject
    is rejected first, located at the key that causes it: the linkage or walker, the drive and
    the run's length, the masses and loads, the cam, the memory estimate (at most
    :data:`~linkage.scene.MEMORY_CAP`), and — walking the run's crank angles in blocks — a first
    assembled sample (a walker's legs must assemble at every one).

    Raises
    ------
    SceneError
        For the first problem found.
    """
    study, leg = _build_study(scene)
    n = _samples(scene, samples)
    check_memory_estimate(scene, study, n, given=samples is not None)
    drive, period = build_drive(scene, leg)
    duration = run_duration(scene, period)
    if scene.cam is not None:
        build_cam(scene)
    if isinstance(study, Walker):
        with _blame(scene, ("drive",), "kind"):
            _check_legs(scene, study, drive, duration, n)
        return
    if scene.masses is not None or scene.loads:
        masses, loads = build_masses(scene, study)
        if scene.wants("torque"):
            with _blame(scene, (), "masses"):
                forces(
                    study,
                    theta=np.zeros(2),
                    omega=1.0,
                    masses=masses,
                    gravity=scene.gravity,
                    loads=loads,
                )
    with _blame(scene, ("drive",), "kind"):
        for t in _blocks(n, duration):
            theta = drive.angles(t)[0]
            if study.sweep(theta, outputs=("point",)).valid.any():
                return
    raise _no_assembly(scene, study, drive, duration, n)


def _build_study(scene: Scene) -> tuple[FourBar | Mechanism | Walker, FourBar | Mechanism]:
    if scene.walker is not None:
        walker = build_walker(scene)
        return walker, walker.legs[0].linkage
    mech = build_mechanism(scene)
    return mech, mech


def _samples(scene: Scene, samples: int | None) -> int:
    n = samples if samples is not None else scene.drive.get("samples", 721)
    if isinstance(n, bool) or not isinstance(n, int) or not 8 <= n <= SAMPLES_MAX:
        raise SceneError(f"samples must be a whole number from 8 to {SAMPLES_MAX}, got {n!r}")
    return n


def _blocks(n: int, duration: float) -> Iterator[Array]:
    """The run's sample times ``np.linspace(0, duration, n)``, in blocks of :data:`CHUNK`."""
    step = duration / (n - 1)
    for a in range(0, n, CHUNK):
        b = min(n, a + CHUNK)
        t = np.arange(a, b, dtype=np.float64) * step
        if b == n:
            t[-1] = duration
        yield t


def _check_legs(scene: Scene, walker: Walker, drive: Any, duration: float, n: int) -> None:
    """Every leg must assemble at every crank angle of the run (else `simulate` refuses)."""
    per_leg = isinstance(drive, CrankSchedule)
    for idx, leg in enumerate(walker.legs):
        for t in _blocks(n, duration):
            if per_leg:
                theta = drive.angles(t + leg.phase / (2 * math.pi) * drive.period)[0]
            else:
                theta = drive.angles(t)[0] + leg.phase
            ok = leg.linkage.sweep(theta, outputs=("point",)).valid
            if not ok.all():
                bad = float(theta[int(np.argmin(ok))])
                where: tuple[tuple[Any, ...], str] = (
                    (("walker", "legs", idx), "catalog")
                    if scene.walker and "legs" in scene.walker
                    else (("walker",), "model")
                )
                raise scene.error(
                    *where,
                    f"leg {leg.name!r} cannot be assembled at crank angle "
                    f"{math.degrees(bad) % 360:.1f}° (a leg must assemble at every sample)",
                )


def _no_assembly(
    scene: Scene, mech: FourBar | Mechanism, drive: Any, duration: float, n: int
) -> SceneError:
    """The error for a run in which no sample assembles, with the reason."""
    m = scene.mechanism or {}
    t0 = np.zeros(1)
    theta0 = float(drive.angles(t0)[0][0])
    if isinstance(mech, FourBar):
        ranges = mech.input_ranges()
        key = "ground" if "ground" in m else "catalog"
        if not ranges:
            g = math.dist(mech.o, mech.c)
            near, far = abs(g - mech.crank), g + mech.crank
            lo, hi = abs(mech.coupler - mech.rocker), mech.coupler + mech.rocker
            gap = near - hi if near > hi else lo - far
            return scene.error(
                ("mechanism",),
                key,
                f"no sample assembles: the crank end stays {near:.6g} … {far:.6g} from the "
                f"rocker pivot, the coupler and rocker reach {lo:.6g} … {hi:.6g} "
                f"(closure gap {gap:.3g})",
            )
        spans = ", ".join(f"{math.degrees(a):.1f}° … {math.degrees(b):.1f}°" for a, b in ranges)
        return scene.error(
            ("drive",),
            "start_deg" if "start_deg" in scene.drive else "kind",
            f"no sample assembles: the drive never turns the crank to where the linkage "
            f"assembles ({spans}); it starts at {math.degrees(theta0):.1f}°",
        )
    if "joints" in m:
        failed = _first_unplaced(m["joints"], theta0)
        if failed is not None:
            idx, j, pos = failed
            if j["kind"] == "dyad":
                dist = math.dist(pos[j["p1"]], pos[j["p2"]])
                r1, r2 = j["r1"], j["r2"]
                gap = dist - (r1 + r2) if dist > r1 + r2 else abs(r1 - r2) - dist
                return scene.error(
                    ("mechanism", "joints", idx),
                    "r1",
                    f"no sample assembles: at the first sample {j['p1']!r} and {j['p2']!r} are "
                    f"{dist:.6g} apart, r1 and r2 reach {abs(r1 - r2):.6g} … {r1 + r2:.6g} "
                    f"(closure gap {gap:.3g})",
                )
            return scene.error(
                ("mechanism", "joints", idx),
                JOINT_KEY[j["kind"]],
                f"no sample assembles: joint {j['name']!r} cannot be placed at the first sample",
            )
    return scene.error(
        ("mechanism",),
        next(iter(m), "catalog"),
        f"no sample assembles over the run's {n} samples",
    )


def _add_joint(mech: Mechanism, j: dict[str, Any]) -> None:
    kind = j["kind"]
    if kind == "fixed":
        mech.fixed(j["name"], j["at"])
    elif kind == "crank":
        mech.crank(j["name"], j["centre"], j["radius"], math.radians(j.get("phase_deg", 0.0)))
    elif kind == "dyad":
        mech.dyad(j["name"], j["p1"], j["p2"], j["r1"], j["r2"], j.get("side", "left"))
    else:
        mech.point(j["name"], tuple(j["on"]), (j["along"], j.get("left", 0.0)))


def _first_unplaced(
    joints: list[dict[str, Any]], theta: float
) -> tuple[int, dict[str, Any], dict[str, Any]] | None:
    """The first joint of a joint program that cannot be placed at crank angle ``theta``, and
    the positions of the joints before it (found by solving ever longer prefixes)."""
    crank = next(k for k, j in enumerate(joints) if j["kind"] == "crank")
    placed: dict[str, Any] = {}
    for k in range(crank + 1, len(joints) + 1):
        mech = Mechanism()
        for j in joints[:k]:
            _add_joint(mech, j)
        s = mech.sweep(np.array([theta]), outputs=("joints",))
        if not s.valid[0]:
            return k - 1, joints[k - 1], placed
        placed = {name: tuple(s.joints[0, i]) for i, name in enumerate(s.joint_names)}
    return None


def estimate_memory(scene: Scene, study: FourBar | Mechanism | Walker, samples: int) -> int:
    """Bytes a run of ``samples`` samples is estimated to need: 8 bytes × the numbers it keeps
    per sample × 2 (the arrays and the temporaries of the stage that makes them, or their copy
    in the report's table), plus 64 MiB for the interpreter and the plots.

    Numbers per sample: time, angle, speed, acceleration (4); a mechanism's trajectory (2 per
    joint + 4), rates (6 per joint + 6), instant centres (5 per link pair) and curvature (4),
    torque (8 per joint + 4); a walker's feet (12 per leg) plus one leg's sweep (2 per joint +
    8). Calibrated on peak resident memory (``/usr/bin/time``, 2e5 → 6e5 samples): the Hoecken
    example without straightness and animation grows by 1065 bytes per sample, estimated 1408;
    the hexapod by 1210, estimated 1504 — an estimate about 1.3 times the measured growth.
    """
    per = 4
    if isinstance(study, Walker):
        legs = len(study.legs)
        joints = max(_joints(leg.linkage) for leg in study.legs)
        per += 12 * legs + 2 * joints + 8
    else:
        j = _joints(study)
        per += 2 * j + 4
        if scene.wants("velocity", "acceleration", "straightness"):
            per += 6 * j + 6
        if scene.wants("instant_centres", "curvature"):
            links = len((study.mechanism() if isinstance(study, FourBar) else study).links)
            per += 5 * links * (links - 1) // 2 + 4
        if scene.wants("torque"):
            per += 8 * j + 4
    return 8 * per * samples * 2 + (64 << 20)


def _joints(mech: FourBar | Mechanism) -> int:
    return 5 if isinstance(mech, FourBar) else len(mech.joint_names)


def check_memory_estimate(
    scene: Scene, study: FourBar | Mechanism | Walker, samples: int, given: bool = False
) -> None:
    """Refuse a run whose :func:`estimate_memory` exceeds :data:`~linkage.scene.MEMORY_CAP`.

    Raises
    ------
    SceneError
        Located at ``[drive] samples`` (unlocated when ``samples`` was given by the caller).
    """
    need = estimate_memory(scene, study, samples)
    if need <= MEMORY_CAP:
        return
    per = (need - (64 << 20)) / samples
    most = int((MEMORY_CAP - (64 << 20)) / per)
    problem = (
        f"{samples} samples would need about {need / 2**30:.3g} GiB (estimated), more than the "
        f"{MEMORY_CAP / 2**30:g} GiB limit; at most {most} samples for these outputs"
    )
    if given:
        raise SceneError(f"samples: {problem}")
    raise scene.error(("drive",), "samples", problem)


def run(
    scene: Scene, samples: int | None = None, progress: Callable[[str], None] | None = None
) -> Result:
    """Run the stages ``scene.outputs`` need, and each again at the sample counts of
    :func:`check_counts` (the stage ``second resolution``; the doubled run only when it fits
    the memory limit): the largest difference is the error estimate of every sampled figure.

    Raises
    ------
    LinkageError
        When the study cannot be computed (the message says why); a :class:`SceneError`,
        located at the key responsible, for a scene problem (including a run in which no
        sample assembles).
    """
    tell = progress or (lambda _: None)
    n = _samples(scene, samples)
    stages: dict[str, float] = {}

    def stage(name: str, fn: Callable[[], Any]) -> Any:
        tell(name)
        t0 = time.perf_counter()
        try:
            out = fn()
        except (LinkageError, MemoryError):
            raise
        except _ARITHMETIC as exc:
            raise LinkageError(f"stage {name!r} failed: {exc}") from None
        stages[name] = stages.get(name, 0.0) + time.perf_counter() - t0
        return out

    study, leg = stage("build", lambda: _build_study(scene))
    check_memory_estimate(scene, study, n, given=samples is not None)
    walker = study if isinstance(study, Walker) else None
    drive, period = build_drive(scene, leg)
    duration = run_duration(scene, period)
    if walker is not None:
        _check_legs(scene, walker, drive, duration, n)
    t = np.linspace(0.0, duration, n)
    theta, omega, alpha = drive.angles(t)
    ns = _affordable_checks(scene, study, n)
    alts = [np.linspace(0.0, duration, k) for k in ns]
    res = Result(scene=scene, time=t, theta=theta, mechanism=None if walker else leg, walker=walker)
    res.check_samples = ns
    res.drive = drive
    res.arrays.update(time=t, theta=theta, omega=omega, alpha=alpha)
    rows = res.figures
    rows.append(Row("drive", _drive_label(scene, drive)))
    rows.append(_exact("duration", duration, "s"))
    rows.append(Row("samples", str(n), "", f"errors {_vs(ns)}", value=n, exact=True))
    second = "second resolution"

    if walker is not None:
        per_leg = isinstance(drive, CrankSchedule)
        sim = stage("walker", lambda: walker.simulate(time=t, drive=drive, per_leg_time=per_leg))
        sims = [
            stage(second, partial(walker.simulate, time=ta, drive=drive, per_leg_time=per_leg))
            for ta in alts
        ]
        res.simulation = sim
        # Loop-closure residual of the legs' own kinematics over the run (zero if exact).
        closure = max(
            _rigidity(leg.linkage, leg.linkage.sweep(theta + leg.phase)) for leg in walker.legs
        )
        res.arrays["closure"] = np.array([closure])
        rows.append(
            Row(
                "leg loop-closure residual",
                _e(closure),
                length_unit(scene),
                "0 if exact",
                value=closure,
                error=closure,
                exact=True,
            )
        )
        _walker_figures(res, sim, sims, walker, duration, period)
        if scene.wants("cam"):
            res.cam = stage("cam", lambda: _cam(res, scene))
        return _finish(res, stages)

    mech = leg
    sweep = stage("trajectory", lambda: mech.sweep(theta))
    if not sweep.valid.any():
        raise _no_assembly(scene, mech, drive, duration, n)
    res.sweep = sweep
    angles = [drive.angles(ta) for ta in alts]
    sweeps = [stage(second, partial(mech.sweep, a[0])) for a in angles]
    _trajectory_figures(res, mech, sweep, sweeps)

    # Straightness reports the speed variation along the straight part, so it needs rates too.
    rates2: list[Sweep] = []
    if scene.wants("velocity", "acceleration", "straightness"):
        outs = ("point", "velocity", "acceleration")
        rates = stage("rates", lambda: mech.sweep(theta, omega=omega, alpha=alpha, outputs=outs))
        rates2 = [
            stage(second, partial(mech.sweep, a[0], omega=a[1], alpha=a[2], outputs=outs))
            for a in angles
        ]
        res.rates = rates
        _rate_figures(res, rates, rates2)
    if scene.wants("instant_centres", "curvature"):
        geo_outs = ("point", *(o for o in ("instant_centres", "curvature") if scene.wants(o)))
        geo = stage("geometry", lambda: mech.sweep(theta, outputs=geo_outs))
        geo2 = [stage(second, partial(mech.sweep, a[0], outputs=geo_outs)) for a in angles]
        res.geometry = geo
        _geometry_figures(res, geo, sweep, geo2)
    if scene.wants("straightness"):
        res.straight = stage("straightness", lambda: _straightness(res, mech, rates2 or sweeps))
    if scene.wants("torque"):
        res.forces = stage("torque", lambda: _torque(res, scene, mech, t, alts, drive))
    if scene.wants("cam"):
        res.cam = stage("cam", lambda: _cam(res, scene))
    return _finish(res, stages)


def _finish(res: Result, stages: dict[str, float]) -> Result:
    res.stages = stages
    return res


def _drive_label(scene: Scene, drive: Any) -> str:
    d = scene.drive
    gears = f" through {'→'.join(map(str, d['gears']))} gears" if "gears" in d else ""
    if d["kind"] == "constant":
        speed = f"{d['rpm']:g} rpm" if "rpm" in d else f"{d['omega']:g} rad/s"
        if isinstance(drive, Geared):
            # The train scales the speed in whatever unit the scene gave it.
            crank = drive.train.output_speed(d["rpm"] if "rpm" in d else d["omega"])
            unit = "rpm" if "rpm" in d else "rad/s"
            return f"constant {speed}{gears} (crank {format_number(crank, 0)} {unit})"
        return f"constant {speed}"
    if d["kind"] == "program":
        return f"motion program, {len(d['segments'])} segments{gears}"
    u = length_unit(scene)
    return f"crank schedule: foot {d['foot_speed']:g} {u}/s, duty factor {d['duty_factor']:g}"


def _rigidity(mech: FourBar | Mechanism, s: Sweep) -> float:
    """Largest change of any distance between two joints of one link over the sweep: the
    loop-closure residual (zero for exact kinematics)."""
    m = mech.mechanism() if isinstance(mech, FourBar) else mech
    names = s.joint_names
    worst = 0.0
    j = s.joints[s.valid]
    for members in m.link_members()[1:]:
        idx = [names.index(x) for x in members]
        for a in range(len(idx)):
            for b in range(a + 1, len(idx)):
                dist = np.linalg.norm(j[:, idx[a]] - j[:, idx[b]], axis=1)
                if len(dist):
                    worst = max(worst, float(np.ptp(dist)))
    return worst


def _ranges(s: Sweep) -> tuple[tuple[float, float], tuple[float, float]] | None:
    p = s.point[s.valid]
    if not len(p):
        return None
    return (
        (float(p[:, 0].min()), float(p[:, 0].max())),
        (float(p[:, 1].min()), float(p[:, 1].max())),
    )


def _trajectory_figures(
    res: Result, mech: FourBar | Mechanism, s: Sweep, others: list[Sweep]
) -> None:
    res.arrays.update(point=s.point, joints=s.joints, valid=s.valid.astype(float), margin=s.margin)
    closure = _rigidity(mech, s)
    res.arrays["closure"] = np.array([closure])
    rows = res.figures
    ns = res.check_samples
    u = length_unit(res.scene)
    ok = int(s.valid.sum())
    rows.append(
        Row("samples assembled", f"{ok} / {len(s.valid)}", "", "exact", value=ok, exact=True)
    )
    rows.append(
        Row(
            "loop-closure residual",
            _e(closure),
            u,
            "0 if exact",
            value=closure,
            error=closure,
            exact=True,
        )
    )
    fine, alt = _ranges(s), [_ranges(o) for o in others]
    if fine is not None:
        rows.append(_pair("trace x range", fine[0], u, [a[0] if a else None for a in alt], ns))
        rows.append(_pair("trace y range", fine[1], u, [a[1] if a else None for a in alt], ns))
    if isinstance(mech, FourBar):
        rows.append(Row("Grashof class", mech.grashof(), "", "exact", exact=True))


def _peaks(s: Sweep) -> tuple[float, float]:
    ok = s.valid
    speed = np.linalg.norm(s.velocity[ok], axis=1)
    accel = np.linalg.norm(s.acceleration[ok], axis=1)
    return (
        float(speed.max()) if len(speed) else math.nan,
        float(accel.max()) if len(accel) else math.nan,
    )


def _rate_figures(res: Result, s: Sweep, others: list[Sweep]) -> None:
    res.arrays.update(velocity=s.velocity, acceleration=s.acceleration)
    (speed, accel), alt = _peaks(s), [_peaks(o) for o in others]
    u = length_unit(res.scene)
    ns = res.check_samples
    if res.scene.wants("velocity"):
        res.figures.append(_row("peak trace speed", speed, f"{u}/s", [a[0] for a in alt], ns))
    if res.scene.wants("acceleration"):
        res.figures.append(
            _row("peak trace acceleration", accel, f"{u}/s²", [a[1] for a in alt], ns)
        )


STRAIGHT_RADIUS = 1e6
"""A path whose every radius of curvature exceeds this many times its extent is straight: its
radius is reported as ∞ (the finite values are round-off of an exact line)."""


def _on_a_line(p: Array, extent: float) -> bool:
    """Whether every point of ``p`` lies within 1e-9 × ``extent`` of one line (a straight
    path: its radius is ∞ even where the point stops and turns back, where the sampled
    radius ``|v|³/|v × a|`` is 0/0)."""
    if len(p) < 3 or not extent > 0:
        return False
    d = p - p.mean(axis=0)
    _, _, vt = np.linalg.svd(d, full_matrices=False)
    off = np.abs(d @ vt[-1])
    return bool(off.max() <= 1e-9 * extent)


def _smallest_radius(g: Sweep, s: Sweep) -> float:
    """The smallest radius of curvature over the run; ``inf`` for a straight path."""
    r = g.curvature_radius
    fin = np.isfinite(r) & (r >= 0)
    p = s.point[s.valid]
    extent = float(np.nanmax(np.ptp(p, axis=0))) if len(p) else 0.0
    if not fin.any() or _on_a_line(p, extent):
        return math.inf
    smallest = float(np.min(r[fin]))
    return math.inf if smallest > STRAIGHT_RADIUS * max(extent, 1e-300) else smallest


def _geometry_figures(res: Result, g: Sweep, s: Sweep, others: list[Sweep]) -> None:
    u = length_unit(res.scene)
    if res.scene.wants("curvature"):
        res.arrays.update(curvature_centre=g.curvature_centre, curvature=g.curvature)
        c, rad = g.curvature_centre, g.curvature_radius
        est = three_point_centres(s.point, 1)
        # The core's centres against circles through three neighbouring samples, where the
        # centre is a "centre of rotation" (radius below the path's extent); near inflections
        # both run off to infinity and their distance means nothing.
        extent = float(np.nanmax(np.ptp(s.point[s.valid], axis=0))) if s.valid.any() else 0.0
        inner = np.isfinite(est[:, 0]) & np.isfinite(c[1:-1, 0]) & (rad[1:-1] < extent)
        check = (
            f"3-point check {_e(float(np.max(np.linalg.norm(est[inner] - c[1:-1][inner], 1))))}"
            if inner.any()
            else ""
        )
        r, alt = _smallest_radius(g, s), [_smallest_radius(o, o) for o in others]
        if math.isinf(r):
            res.figures.append(
                Row(
                    "smallest radius of curvature",
                    "∞ (straight path)",
                    u,
                    "the path is a line to 1e-9 of its extent, or every radius exceeds "
                    f"{STRAIGHT_RADIUS:g} × it",
                    value=None,
                    error=None,
                )
            )
        else:
            res.figures.append(
                _row(
                    "smallest radius of curvature",
                    r,
                    u,
                    [a if math.isfinite(a) else None for a in alt],
                    res.check_samples,
                    check,
                )
            )
    if res.scene.wants("instant_centres"):
        res.arrays.update(
            instant_centres=g.instant_centres, instant_centre_directions=g.instant_centre_directions
        )
        at_inf = int(np.count_nonzero(g.instant_centre_at_infinity))
        res.figures.append(
            Row(
                "instant centres at infinity (samples × pairs)",
                str(at_inf),
                "",
                "flagged",
                value=at_inf,
            )
        )


def _straight_size(mech: FourBar | Mechanism, s: Sweep) -> float:
    if isinstance(mech, FourBar):
        return max(mech.ground, mech.crank, mech.coupler, mech.rocker)
    return float(np.nanmax(np.ptp(s.point[s.valid], axis=0)))


def _straightness(
    res: Result, mech: FourBar | Mechanism, others: list[Sweep]
) -> StraightPart | None:
    s = res.rates or res.sweep
    assert s is not None
    u = length_unit(res.scene)
    size = _straight_size(mech, s)
    tol = 1e-3 * size
    name = "straight part within 0.1 % of size"
    if not (math.isfinite(tol) and tol > 0):
        res.figures.append(Row(name, "none", "", "no extent"))
        return None
    vel = res.rates.velocity if res.rates is not None else None
    part = straightness(s.point, tol, velocity=vel)
    if part is None:
        res.figures.append(Row(name, "none", "", f"tolerance {_e(tol)} {u}"))
        return None
    parts = [
        straightness(o.point, tol, velocity=o.velocity if res.rates is not None else None)
        for o in others
    ]
    ns = res.check_samples
    res.figures.append(
        _row(
            name,
            part.length,
            u,
            [p.length if p else None for p in parts],
            ns,
            f"tolerance {_e(tol)}",
        )
    )
    res.figures.append(
        _row(
            "straight part max deviation",
            part.max_deviation,
            u,
            [p.max_deviation if p else None for p in parts],
            ns,
            "from its least-squares line",
        )
    )
    if part.speed_variation is not None:
        if math.isfinite(part.speed_variation):
            alt = [p.speed_variation if p else None for p in parts]
            res.figures.append(
                _row(
                    "speed variation along it",
                    100 * part.speed_variation,
                    "%",
                    [100 * v if v is not None and math.isfinite(v) else None for v in alt],
                    ns,
                    "this drive",
                )
            )
        else:
            why = (
                "unbounded (the run reaches a toggle)"
                if math.isinf(part.speed_variation)
                else "undefined (the trace stands still)"
            )
            res.figures.append(Row("speed variation along it", why, "%"))
    return part


def _torque(
    res: Result, scene: Scene, mech: FourBar | Mechanism, t: Array, alts: list[Array], drive: Any
) -> Forces:
    masses, loads = build_masses(scene, mech)
    f = forces(mech, time=t, drive=drive, masses=masses, gravity=scene.gravity, loads=loads)
    f2 = [
        forces(mech, time=ta, drive=drive, masses=masses, gravity=scene.gravity, loads=loads)
        for ta in alts
    ]
    res.arrays.update(torque=f.torque, power_torque=f.power_torque)
    check = float(np.nanmax(np.abs(f.torque - f.power_torque)))
    unit = torque_unit(scene)
    ns = res.check_samples
    note = f"power method agrees to {_e(check)}"
    mean = [g.mean_abs_torque for g in f2]
    res.figures.append(_row("driver torque mean |T|", f.mean_abs_torque, unit, mean, ns, note))
    peak = [g.peak_torque for g in f2]
    res.figures.append(_row("driver torque peak |T|", f.peak_torque, unit, peak, ns, note))
    return f


CAM_SAMPLES = 721
"""Cam profile samples (every 0.5°); the error estimate compares :func:`check_counts`."""


def _cam_values(p: Any) -> tuple[float, float]:
    return math.degrees(p.max_pressure_angle), float(np.nanmin(np.abs(p.profile_radius)))


def _cam(res: Result, scene: Scene) -> Any:
    cam = build_cam(scene)
    p = cam.profile(CAM_SAMPLES)
    ns = check_counts(CAM_SAMPLES)
    alt = [_cam_values(cam.profile(k)) for k in ns]
    res.arrays.update(cam_profile=p.profile, cam_pitch=p.pitch, cam_pressure_angle=p.pressure_angle)
    angle, radius = _cam_values(p)
    res.figures.append(_row("cam max pressure angle", angle, "deg", [a[0] for a in alt], ns))
    res.figures.append(
        _row("cam smallest profile radius", radius, length_unit(scene), [a[1] for a in alt], ns)
    )
    res.figures.append(Row("cam check", "ok" if not p.problems else "; ".join(p.problems)))
    return p


def _walker_values(sim: Simulation, duration: float, period: float) -> dict[str, float]:
    """The sampled walker figures of one simulation (compared between two resolutions)."""
    cycles = duration / period if period > 0 else 1.0
    down = sim.stance.sum(1)
    travel = float(sim.body_position[-1])
    return {
        "duty": float(sim.duty_factor.mean()),
        "stride": float(np.nanmean(sim.stride)),
        "lift": float(sim.lift_height.min()),
        "travel": travel,
        "speed": travel / duration,
        "slip": float(sim.slip_distance.sum()) / cycles,
        "spread": float(np.nanmax(sim.spread)),
        "down_min": float(down.min()),
        "down_max": float(down.max()),
        "margin": float(np.min(np.where(np.isfinite(sim.margin), sim.margin, np.inf))),
    }


def _walker_figures(
    res: Result,
    sim: Simulation,
    others: list[Simulation],
    walker: Walker,
    duration: float,
    period: float,
) -> None:
    scene = res.scene
    res.arrays.update(
        feet=sim.feet,
        stance=sim.stance.astype(float),
        body_position=sim.body_position,
        margin=sim.margin,
    )
    a = _walker_values(sim, duration, period)
    alt = [_walker_values(o, duration, period) for o in others]
    ns = res.check_samples

    def row(figure: str, key: str, unit: str, note: str = "") -> Row:
        return _row(figure, a[key], unit, [b[key] for b in alt], ns, note)

    rows = res.figures
    u = length_unit(scene)
    rows.append(Row("legs", ", ".join(sim.legs)))
    rows.append(row("duty factor (per leg, mean)", "duty", "of the cycle"))
    rows.append(row("stride", "stride", u))
    rows.append(row("lift height (obstacle a foot clears)", "lift", u))
    rows.append(_exact("body clearance", walker.body_underside - sim.ground, u))
    rows.append(row("body travel", "travel", u, "trapezoid"))
    rows.append(row("mean body speed", "speed", f"{u}/s"))
    if scene.wants("stability"):
        rows.append(_margin_row(sim, u, [b["margin"] for b in alt], ns))
    if scene.wants("slip"):
        rows.append(row("foot slip per cycle (all feet)", "slip", u, "trapezoid"))
        rows.append(row("largest stance-speed spread", "spread", f"{u}/s"))
    if scene.wants("gait"):
        lo, hi = int(a["down_min"]), int(a["down_max"])
        e0 = _spread(a["down_min"], [b["down_min"] for b in alt]) or 0.0
        e1 = _spread(a["down_max"], [b["down_max"] for b in alt]) or 0.0
        rows.append(
            Row(
                "feet down (min / max)",
                f"{lo} / {hi}",
                "feet",
                f"±{format_error(max(e0, e1))} ({_vs(ns)})",
                value=(lo, hi),
                error=max(e0, e1),
            )
        )


def _margin_row(sim: Simulation, units: str, others: list[float], ns: Sequence[int]) -> Row:
    """The smallest stability margin; with no foot on the ground at some samples there is no
    support polygon and no margin, which the row says instead of printing −inf."""
    unsupported = sim.margin == -np.inf
    if unsupported.any():
        k = int(np.argmax(unsupported))
        return Row(
            "minimum stability margin",
            f"none: no foot down at {int(unsupported.sum())} / {len(sim.margin)} samples",
            "",
            f"first at t = {format_number(float(sim.time[k]), digits=4)} s",
            value=None,
        )
    finite = np.isfinite(sim.margin)
    if not finite.any():
        return Row("minimum stability margin", "undefined", "", "no support polygon", value=None)
    k = int(np.argmin(np.where(finite, sim.margin, np.inf)))
    return _row(
        "minimum stability margin",
        float(sim.margin[k]),
        units,
        [o if math.isfinite(o) else None for o in others],
        ns,
        f"at t = {format_number(float(sim.time[k]), digits=4)} s",
    )
