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
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

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
Row = tuple[str, str, str, str]


@dataclass
class Result:
    """Everything a run computed."""

    scene: Scene
    time: Array
    theta: Array
    figures: list[Row] = field(default_factory=list)
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
    arrays: dict[str, Array] = field(default_factory=dict)


def _e(x: float) -> str:
    return f"{x:.1e}"


def _f(x: float, d: int = 3) -> str:
    return f"{x:.{d}f}"


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
    """Run the stages ``scene.outputs`` need.

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
        stages[name] = time.perf_counter() - t0
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
    res = Result(scene=scene, time=t, theta=theta, mechanism=None if walker else leg, walker=walker)
    res.arrays.update(time=t, theta=theta, omega=omega, alpha=alpha)
    rows = res.figures
    rows.append(("drive", _drive_label(scene, drive), "", ""))
    rows.append(("duration / samples", f"{duration:.4g} s / {n}", "", ""))

    if walker is not None:
        per_leg = isinstance(drive, CrankSchedule)
        sim = stage("walker", lambda: walker.simulate(time=t, drive=drive, per_leg_time=per_leg))
        res.simulation = sim
        # Loop-closure residual of the legs' own kinematics over the run (zero if exact).
        closure = max(
            _rigidity(leg.linkage, leg.linkage.sweep(theta + leg.phase)) for leg in walker.legs
        )
        res.arrays["closure"] = np.array([closure])
        _walker_figures(res, sim, walker, duration, period)
        res.figures.insert(3, ("leg loop-closure residual", _e(closure), scene.units, "0 if exact"))
        if scene.wants("cam"):
            res.cam = stage("cam", lambda: _cam(res, scene))
        return _finish(res, stages)

    mech = leg
    sweep = stage("trajectory", lambda: mech.sweep(theta))
    if not sweep.valid.any():
        raise _no_assembly(scene, mech, drive, duration, n)
    res.sweep = sweep
    _trajectory_figures(res, mech, sweep)

    # Straightness reports the speed variation along the straight part, so it needs rates too.
    if scene.wants("velocity", "acceleration", "straightness"):
        rates = stage(
            "rates",
            lambda: mech.sweep(
                theta, omega=omega, alpha=alpha, outputs=("point", "velocity", "acceleration")
            ),
        )
        res.rates = rates
        _rate_figures(res, rates, t)
    if scene.wants("instant_centres", "curvature"):
        outs = tuple(o for o in ("instant_centres", "curvature") if scene.wants(o))
        geo = stage("geometry", lambda: mech.sweep(theta, outputs=("point", *outs)))
        res.geometry = geo
        _geometry_figures(res, geo, sweep)
    if scene.wants("straightness"):
        res.straight = stage("straightness", lambda: _straightness(res, mech))
    if scene.wants("torque"):
        res.forces = stage("torque", lambda: _torque(res, scene, mech, t, drive))
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
            crank = drive.train.output_speed(d["rpm"] if "rpm" in d else d["omega"])
            return f"constant {speed}{gears} (crank {crank:.3f})"
        return f"constant {speed}"
    if d["kind"] == "program":
        return f"motion program, {len(d['segments'])} segments{gears}"
    return f"crank schedule: foot {d['foot_speed']:g}/s, duty factor {d['duty_factor']:g}"


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


def _trajectory_figures(res: Result, mech: FourBar | Mechanism, s: Sweep) -> None:
    p = s.point[s.valid]
    res.arrays.update(point=s.point, joints=s.joints, valid=s.valid.astype(float), margin=s.margin)
    closure = _rigidity(mech, s)
    res.arrays["closure"] = np.array([closure])
    rows = res.figures
    rows.append(("samples assembled", f"{int(s.valid.sum())} / {len(s.valid)}", "", "exact"))
    if len(p):
        u = res.scene.units
        rows.append(
            (
                "trace x range",
                f"{_f(p[:, 0].min())} … {_f(p[:, 0].max())}",
                u,
                f"closure {_e(closure)}",
            )
        )
        rows.append(
            (
                "trace y range",
                f"{_f(p[:, 1].min())} … {_f(p[:, 1].max())}",
                u,
                f"closure {_e(closure)}",
            )
        )
    if isinstance(mech, FourBar):
        rows.append(("Grashof class", mech.grashof(), "", "exact"))


def _rate_figures(res: Result, s: Sweep, t: Array) -> None:
    v, a = s.velocity, s.acceleration
    res.arrays.update(velocity=v, acceleration=a)
    ok = s.valid
    # Derivative consistency: the analytic velocity against a central difference in time.
    fd = (s.point[2:] - s.point[:-2]) / (t[2:] - t[:-2])[:, None]
    both = ok[2:] & ok[:-2] & ok[1:-1]
    err = float(np.nanmax(np.abs(fd[both] - v[1:-1][both]))) if both.any() else math.nan
    speed = np.linalg.norm(v[ok], axis=1)
    accel = np.linalg.norm(a[ok], axis=1)
    if res.scene.wants("velocity"):
        res.figures.append(
            (
                "peak trace speed",
                _f(float(speed.max()), 2),
                f"{res.scene.units}/s",
                f"vel {_e(err)}",
            )
        )
    if res.scene.wants("acceleration"):
        afd = (v[2:] - v[:-2]) / (t[2:] - t[:-2])[:, None]
        aerr = float(np.nanmax(np.abs(afd[both] - a[1:-1][both]))) if both.any() else math.nan
        res.figures.append(
            (
                "peak trace acceleration",
                _f(float(accel.max()), 1),
                f"{res.scene.units}/s²",
                f"acc {_e(aerr)}",
            )
        )


def _geometry_figures(res: Result, g: Sweep, s: Sweep) -> None:
    if res.scene.wants("curvature"):
        c, r = g.curvature_centre, g.curvature_radius
        res.arrays.update(curvature_centre=c, curvature=g.curvature)
        fin = np.isfinite(r) & (r > 0)
        est = three_point_centres(s.point, 1)
        # Compare where the centre is a "centre of rotation" (radius below the path's extent);
        # near inflections both centres run off to infinity and their distance means nothing.
        extent = float(np.nanmax(np.ptp(s.point[s.valid], axis=0))) if s.valid.any() else 0.0
        inner = np.isfinite(est[:, 0]) & np.isfinite(c[1:-1, 0]) & (r[1:-1] < extent)
        err = (
            float(np.max(np.linalg.norm(est[inner] - c[1:-1][inner], axis=1)))
            if inner.any()
            else math.nan
        )
        smallest = _f(float(np.min(r[fin])), 4) if fin.any() else "none"
        res.figures.append(
            ("smallest radius of curvature", smallest, res.scene.units, f"3-point {_e(err)}")
        )
    if res.scene.wants("instant_centres"):
        res.arrays.update(
            instant_centres=g.instant_centres, instant_centre_directions=g.instant_centre_directions
        )
        at_inf = int(np.count_nonzero(g.instant_centre_at_infinity))
        res.figures.append(
            ("instant centres at infinity (samples × pairs)", str(at_inf), "", "flagged")
        )


def _straightness(res: Result, mech: FourBar | Mechanism) -> StraightPart | None:
    s = res.rates or res.sweep
    assert s is not None
    size = (
        max(mech.ground, mech.crank, mech.coupler, mech.rocker)
        if isinstance(mech, FourBar)
        else float(np.nanmax(np.ptp(s.point[s.valid], axis=0)))
    )
    tol = 1e-3 * size
    if not (math.isfinite(tol) and tol > 0):
        res.figures.append(("straight part within 0.1 % of size", "none", "", "no extent"))
        return None
    vel = res.rates.velocity if res.rates is not None else None
    part = straightness(s.point, tol, velocity=vel)
    if part is None:
        res.figures.append(("straight part within 0.1 % of size", "none", "", f"tol {_e(tol)}"))
        return None
    res.figures.append(
        ("straight part within 0.1 % of size", _f(part.length), "", f"tol {_e(tol)}")
    )
    res.figures.append(
        ("straight part max deviation", _e(part.max_deviation), "", "vs its LS line")
    )
    if part.speed_variation is not None:
        variation = (
            f"{100 * part.speed_variation:.1f}%"
            if math.isfinite(part.speed_variation)
            else "undefined (the trace stands still)"
        )
        res.figures.append(("speed variation along it", variation, "", "this drive"))
    return part


def _torque(res: Result, scene: Scene, mech: FourBar | Mechanism, t: Array, drive: Any) -> Forces:
    masses, loads = build_masses(scene, mech)
    f = forces(mech, time=t, drive=drive, masses=masses, gravity=scene.gravity, loads=loads)
    res.arrays.update(torque=f.torque, power_torque=f.power_torque)
    check = float(np.nanmax(np.abs(f.torque - f.power_torque)))
    res.figures.append(
        (
            "driver torque mean |T| / peak",
            f"{f.mean_abs_torque:.4g} / {f.peak_torque:.4g}",
            "",
            f"vs power {_e(check)}",
        )
    )
    return f


def _cam(res: Result, scene: Scene) -> Any:
    cam = build_cam(scene)
    p = cam.profile(721)
    res.arrays.update(cam_profile=p.profile, cam_pitch=p.pitch, cam_pressure_angle=p.pressure_angle)
    res.figures.append(
        ("cam max pressure angle", _f(math.degrees(p.max_pressure_angle), 2), "deg", "sampled 0.5°")
    )
    res.figures.append(
        (
            "cam smallest profile radius",
            _f(float(np.nanmin(np.abs(p.profile_radius))), 3),
            "",
            "sampled 0.5°",
        )
    )
    res.figures.append(("cam check", "ok" if not p.problems else "; ".join(p.problems), "", ""))
    return p


def _walker_figures(
    res: Result, sim: Simulation, walker: Walker, duration: float, period: float
) -> None:
    scene = res.scene
    res.arrays.update(
        feet=sim.feet,
        stance=sim.stance.astype(float),
        body_position=sim.body_position,
        margin=sim.margin,
    )
    rows = res.figures
    u = scene.units
    rows.append(("legs", ", ".join(sim.legs), "", ""))
    rows.append(("duty factor (per leg, mean)", _f(float(sim.duty_factor.mean())), "", "sampled"))
    rows.append(("stride", _f(float(np.nanmean(sim.stride))), u, "sampled"))
    rows.append(
        ("lift height (obstacle a foot clears)", _f(float(sim.lift_height.min())), u, "sampled")
    )
    rows.append(("body clearance", _f(walker.body_underside - sim.ground), u, "exact"))
    rows.append(
        (
            "body travel / mean speed",
            f"{_f(float(sim.body_position[-1]))} / {_f(float(sim.body_position[-1] / duration))}",
            f"{u}, {u}/s",
            "trapezoid",
        )
    )
    if scene.wants("stability"):
        rows.append(_margin_row(sim, u))
    if scene.wants("slip"):
        cycles = duration / period if period > 0 else 1.0
        rows.append(
            (
                "foot slip per cycle (all feet)",
                _e(float(sim.slip_distance.sum()) / cycles),
                u,
                "trapezoid",
            )
        )
        rows.append(
            ("largest stance-speed spread", _e(float(np.nanmax(sim.spread))), f"{u}/s", "sampled")
        )
    if scene.wants("gait"):
        rows.append(
            (
                "feet down (min / max)",
                f"{int(sim.stance.sum(1).min())} / {int(sim.stance.sum(1).max())}",
                "",
                "sampled",
            )
        )


def _margin_row(sim: Simulation, units: str) -> Row:
    """The smallest stability margin; with no foot on the ground at some samples there is no
    support polygon and no margin, which the row says instead of printing −inf."""
    unsupported = sim.margin == -np.inf
    if unsupported.any():
        k = int(np.argmax(unsupported))
        return (
            "minimum stability margin",
            f"none: no foot down at {int(unsupported.sum())} / {len(sim.margin)} samples",
            "",
            f"first at t = {sim.time[k]:.4g} s",
        )
    finite = np.isfinite(sim.margin)
    if not finite.any():
        return ("minimum stability margin", "undefined", "", "no support polygon")
    k = int(np.argmin(np.where(finite, sim.margin, np.inf)))
    return (
        "minimum stability margin",
        _f(float(sim.margin[k])),
        units,
        f"at t = {sim.time[k]:.4g} s",
    )
