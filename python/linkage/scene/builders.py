"""Build a scene's objects and validate a scene without running it.

The objects are the mechanism, walker, drive, cam, masses and a synthesis target.

The builders (:func:`build_mechanism`, :func:`build_walker`, :func:`build_drive`,
:func:`build_cam`, :func:`build_masses`, :func:`synthesis_target`, :func:`synthesis_atlas`)
turn any error into a :class:`SceneError` located at the key that caused it, and
:func:`validate` — called by :func:`linkage.scene.parse` — runs them once without computing
anything, checks the memory estimate and finds a first assembled sample (a synthesis scene: reads
its target points and atlas, without searching), so ``linkage check`` refuses whatever
``linkage run`` would.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage import catalog, synthesis
from linkage._core import LinkageError
from linkage.drives.cam import DiscCam
from linkage.drives.drive import (
    ConstantSpeed,
    CrankSchedule,
    Drive,
    Geared,
    GearTrain,
    Program,
    Segment,
    crank_schedule,
)
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import JOINT_KINDS, Mechanism
from linkage.kinetostatics.forces import LinkMass, PointLoad, joint_forces
from linkage.scene.schema import (
    CYCLES_MAX,
    MEMORY_CAP,
    POINTS_MAX,
    SAMPLES_MAX,
    SPEED_RANGE,
    TIME_RANGE,
    Scene,
    SceneError,
    _did_you_mean,
    base_folder,
    parse_only,
    read_text,
)
from linkage.walking.walker import Leg, Walker, gait_phases

__all__ = [
    "ARITHMETIC",
    "CHUNK",
    "CURVE_BYTES",
    "POINTS_FILE_MAX",
    "affordable_checks",
    "build_cam",
    "build_drive",
    "build_masses",
    "build_mechanism",
    "build_study",
    "build_walker",
    "check_counts",
    "check_legs",
    "check_memory_estimate",
    "check_synthesis_memory",
    "estimate_memory",
    "no_assembly",
    "read_scene_points",
    "reference_points",
    "run_duration",
    "sample_count",
    "synthesis_atlas",
    "synthesis_target",
    "validate",
]

Array = NDArray[np.float64]


# What `run` may raise from a stage besides LinkageError: numpy and arithmetic errors on data
# the validation did not foresee, turned into a LinkageError naming the stage.
ARITHMETIC = (ValueError, ArithmeticError, IndexError, TypeError)

CHUNK = 1 << 16
"""Samples per block when validation walks a run's crank angles (bounded memory)."""


@contextmanager
def _blame(scene: Scene, path: tuple[Any, ...], key: str) -> Iterator[None]:
    """Turn an error from building ``key`` into a located :class:`SceneError`."""
    try:
        yield
    except SceneError:
        raise
    except (LinkageError, *ARITHMETIC) as exc:
        raise scene.error(path, key, str(exc) or type(exc).__name__) from None


def build_mechanism(scene: Scene) -> FourBar | Mechanism:
    """Build the scene's mechanism.

    Raises
    ------
    SceneError
        Located at the key that made the build fail.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import build_mechanism
    >>> fb = build_mechanism(Scene("leg", None, (), mechanism={"catalog": "hoecken", "scale": 2.0}))
    >>> fb.ground, fb.crank, fb.coupler, fb.rocker, fb.point
    (40.0, 20.0, 50.0, 50.0, (100.0, 0.0))
    >>> build_mechanism(Scene("leg", None, (), mechanism={"catalog": "hoeken"}))
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [mechanism] catalog: unknown catalogue linkage 'hoeken'; ...
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
        with _blame(scene, ("mechanism", "joints", idx), JOINT_KINDS[j["kind"]].blame):
            mech.add_joint(j)
    if "trace" in m:
        with _blame(scene, sec, "trace"):
            mech.trace = m["trace"]
    return mech


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
    """Build a one-turn program (a cam, a lift) from ``duration_deg``/``rise``/``law`` segments."""
    segs = [
        Segment(math.radians(s["duration_deg"]), s.get("rise", 0.0), s.get("law")) for s in segments
    ]
    return Program(0.0, segs)


def build_walker(scene: Scene) -> Walker:
    """Build the scene's walker: a catalogue model, or legs built from catalogue four-bars.

    Raises
    ------
    SceneError
        Located at the key that made the build fail.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import build_walker
    >>> walker = build_walker(Scene("quadruped", None, (), walker={"model": "quadruped_hoecken"}))
    >>> [leg.name for leg in walker.legs], walker.leg_labels()
    (['A', 'B', 'C', 'D'], ('L1', 'R1', 'L2', 'R2'))
    """
    w = scene.walker or {}
    sec = ("walker",)
    if "model" in w:
        with _blame(scene, sec, "model"):
            walker: Walker = catalog.WALKERS[w["model"]]()
    else:
        legs = []
        for idx, spec in enumerate(w["legs"]):
            lp = ("walker", "legs", idx)
            fb: FourBar | Mechanism
            if "scene" in spec:
                fb = _leg_scene(scene, lp, spec["scene"])
            else:
                with _blame(scene, lp, "catalog"):
                    got = catalog.get(spec["catalog"])
                if not isinstance(got, FourBar):
                    raise scene.error(lp, "catalog", f"{spec['catalog']!r} is not a four-bar")
                fb = got
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


def build_drive(scene: Scene, leg: FourBar | Mechanism) -> tuple[Drive, float]:
    """Build the scene's drive and return it with its natural duration.

    The natural duration is one crank cycle or one program period.

    Raises
    ------
    SceneError
        Located at the key that made the build fail.

    Examples
    --------
    Thesis 1's drive, a motor at 50 rpm through an 18/15/14 gear train: the crank turns once in
    0.933 s:

    >>> from linkage.scene import Scene
    >>> from linkage.build import build_drive, build_mechanism
    >>> scene = Scene("leg", None, (), mechanism={"catalog": "hoecken"},
    ...               drive={"kind": "constant", "rpm": 50.0, "gears": [18, 15, 14]})
    >>> drive, period = build_drive(scene, build_mechanism(scene))
    >>> type(drive).__name__, round(period, 6)
    ('Geared', 0.933333)
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
        drive: Drive = ConstantSpeed(motor)
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
        except (LinkageError, *ARITHMETIC) as exc:
            key = "duty_factor" if "duty" in str(exc) else "foot_speed"
            raise scene.error(sec, key, f"no crank schedule: {exc}") from None
        period = drive.period
    if train is not None and kind != "schedule":
        drive = Geared(drive, train)
    return drive, period


def run_duration(scene: Scene, period: float) -> float:
    """Return the run's length in seconds: ``duration``, or ``cycles`` (default 1) times ``period``.

    Raises
    ------
    SceneError
        When it is not a positive finite time of at most a million cycles.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import run_duration
    >>> run_duration(Scene("leg", None, (), drive={"cycles": 2}), 0.5)
    1.0
    >>> run_duration(Scene("leg", None, (), drive={}), float("inf"))
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [drive] cycles: the run lasts inf s; it must be at least 1e-09 s
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


def build_cam(scene: Scene) -> DiscCam | None:
    """Build the scene's disc cam (None without a [cam] section).

    Raises
    ------
    SceneError
        Located at the key that made the build fail.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import build_cam
    >>> rise = {"duration_deg": 180.0, "rise": 10.0, "law": "cycloidal"}
    >>> fall = {"duration_deg": 180.0, "rise": -10.0, "law": "cycloidal"}
    >>> cam = {"base_radius": 20.0, "roller_radius": 5.0, "segments": [rise, fall]}
    >>> type(build_cam(Scene("cam", None, (), cam=cam))).__name__
    'DiscCam'
    >>> build_cam(Scene("no cam", None, ())) is None
    True
    >>> build_cam(Scene("half", None, (), cam={**cam, "segments": [rise]}))
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [cam] base_radius: a cam program must span one turn (2π rad)...
    """
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
    """Build the scene's link masses and point loads, checked against the mechanism.

    Masses must name the mechanism's links, loads its links and joints.

    Raises
    ------
    SceneError
        Located at the link or load that is wrong.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> import linkage
    >>> from linkage.build import build_masses
    >>> hoecken = linkage.catalog.hoecken()
    >>> masses, loads = build_masses(Scene("leg", None, (), masses={"crank": {"mass": 0.1}}),
    ...                              hoecken)
    >>> masses["crank"].mass, loads
    (0.1, [])
    >>> build_masses(Scene("leg", None, (), masses={"arm": {"mass": 0.1}}), hoecken)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [masses] arm: unknown link 'arm'; the moving links are crank, ...
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
    """Build the scene's study without running it, to reject first what :func:`run` would.

    Every refusal is located at the key that causes it: the linkage or walker, the drive and the
    run's length, the masses and loads, the cam, the memory estimate (at most
    :data:`~linkage.scene.MEMORY_CAP`), and — walking the run's crank angles in blocks — a first
    assembled sample (a walker's legs must assemble at every one).

    Raises
    ------
    SceneError
        For the first problem found.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import validate
    >>> drive = {"kind": "constant", "rpm": 50.0}
    >>> validate(Scene("leg", None, ("trajectory",), mechanism={"catalog": "hoecken"}, drive=drive))
    >>> short = {"ground": 20, "crank": 10, "coupler": 4, "rocker": 4}
    >>> validate(Scene("leg", None, ("trajectory",), mechanism=short, drive=drive))
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [mechanism] ground: no sample assembles: ... (closure gap 2)
    """
    if scene.synthesis is not None:
        # The search itself is the run's work: here only its inputs.
        check_synthesis_memory(scene, sample_count(scene, samples))
        synthesis_target(scene)
        synthesis_atlas(scene)
        return
    study, leg = build_study(scene)
    reference_points(scene)
    n = sample_count(scene, samples)
    check_memory_estimate(scene, study, n, given=samples is not None)
    drive, period = build_drive(scene, leg)
    duration = run_duration(scene, period)
    if scene.cam is not None:
        build_cam(scene)
    if isinstance(study, Walker):
        with _blame(scene, ("drive",), "kind"):
            check_legs(scene, study, drive, duration, n)
        return
    if scene.masses is not None or scene.loads:
        masses, loads = build_masses(scene, study)
        if scene.wants("torque"):
            with _blame(scene, (), "masses"):
                joint_forces(
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
    raise no_assembly(scene, study, drive, duration, n)


def build_study(scene: Scene) -> tuple[FourBar | Mechanism | Walker, FourBar | Mechanism]:
    """Build the scene's study and the linkage it is made of.

    Returns the walker and its first leg's linkage, or the mechanism twice.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import build_study
    >>> study, leg = build_study(Scene("leg", None, (), mechanism={"catalog": "hoecken"}))
    >>> study is leg, leg.crank
    (True, 10.0)
    >>> study, leg = build_study(Scene("quad", None, (), walker={"model": "quadruped_hoecken"}))
    >>> type(study).__name__, leg is study.legs[0].linkage
    ('Walker', True)
    """
    if scene.walker is not None:
        walker = build_walker(scene)
        return walker, walker.legs[0].linkage
    mech = build_mechanism(scene)
    return mech, mech


def sample_count(scene: Scene, samples: int | None) -> int:
    """Return the run's sample count: ``samples`` if given, else the scene's (default 721).

    Raises
    ------
    SceneError
        When it is not a whole number from 8 to :data:`SAMPLES_MAX`.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import sample_count
    >>> scene = Scene("leg", None, (), drive={"samples": 73})
    >>> sample_count(scene, None), sample_count(scene, 181), sample_count(Scene("", None, ()), None)
    (73, 181, 721)
    >>> sample_count(scene, 4)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: samples must be a whole number from 8 to 1000000000, got 4
    """
    n = samples if samples is not None else scene.drive.get("samples", 721)
    if isinstance(n, bool) or not isinstance(n, int) or not 8 <= n <= SAMPLES_MAX:
        raise SceneError(f"samples must be a whole number from 8 to {SAMPLES_MAX}, got {n!r}")
    return n


def _blocks(n: int, duration: float) -> Iterator[Array]:
    """Yield the run's sample times ``np.linspace(0, duration, n)`` in blocks of :data:`CHUNK`."""
    step = duration / (n - 1)
    for a in range(0, n, CHUNK):
        b = min(n, a + CHUNK)
        t = np.arange(a, b, dtype=np.float64) * step
        if b == n:
            t[-1] = duration
        yield t


def check_legs(scene: Scene, walker: Walker, drive: Drive, duration: float, n: int) -> None:
    """Every leg must assemble at every crank angle of the run (else `simulate` refuses).

    Examples
    --------
    Evans' linkage B rocks between its toggles: as a walker's leg, driven round, it fails:

    >>> from linkage.scene import Scene
    >>> import math, linkage
    >>> from linkage.build import check_legs
    >>> from linkage.drive import ConstantSpeed
    >>> from linkage.walker import Leg, Walker
    >>> scene = Scene("walker", None, (), walker={"model": "by hand"})
    >>> turn = (ConstantSpeed(1.0), 2 * math.pi, 9)     # drive, duration, samples
    >>> check_legs(scene, linkage.catalog.quadruped_hoecken(), *turn)    # assembles: None
    >>> check_legs(scene, Walker([Leg("E", linkage.catalog.evans_b(), (0, 0, 0))]), *turn)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [walker] model: leg 'E' cannot be assembled at crank angle 90.0° ...
    """
    for idx, leg in enumerate(walker.legs):
        for t in _blocks(n, duration):
            if isinstance(drive, CrankSchedule):  # one motor per leg, shifted in time
                theta = drive.angles(t + leg.phase / (2 * math.pi) * drive.period)[0]
            else:
                theta = drive.angles(t)[0] + leg.phase
            ok = leg.linkage.sweep(theta, outputs=("point",)).valid
            if not ok.all():
                bad = float(theta[int(np.argmin(ok))])
                where: tuple[tuple[Any, ...], str] = (("walker",), "model")
                named = ""
                if scene.walker and "legs" in scene.walker:
                    spec = scene.walker["legs"][idx]
                    key = "scene" if "scene" in spec else "catalog"
                    where = (("walker", "legs", idx), key)
                    named = f" ({spec['scene']})" if key == "scene" else ""
                raise scene.error(
                    *where,
                    f"leg {leg.name!r}{named} cannot be assembled at crank angle "
                    f"{math.degrees(bad) % 360:.1f}° (a leg must assemble at every sample)",
                )


def no_assembly(
    scene: Scene, mech: FourBar | Mechanism, drive: Drive, duration: float, n: int
) -> SceneError:
    r"""Return the error for a run in which no sample assembles, with the reason.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> import linkage
    >>> from linkage.build import no_assembly
    >>> from linkage.drive import ConstantSpeed
    >>> short = {"ground": 20, "crank": 10, "coupler": 4, "rocker": 4}
    >>> err = no_assembly(Scene("leg", None, (), mechanism=short), linkage.FourBar(**short),
    ...                   ConstantSpeed(1.0), 1.0, 9)
    >>> print(str(err).replace(", ", ",\n"))
    [mechanism] ground: no sample assembles: the crank end stays 10 … 30 from the rocker pivot,
    the coupler and rocker reach 0 … 8 (closure gap 2)
    """
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
            if j["kind"] == "slider":
                (px, py), (ox, oy) = pos[j["pivot"]], pos[j["origin"]]
                if "direction" in j:
                    dx, dy = j["direction"]
                else:
                    (fx, fy), (tx, ty) = pos[j["link"][0]], pos[j["link"][1]]
                    if (fx, fy) == (tx, ty):
                        return scene.error(
                            ("mechanism", "joints", idx),
                            "link",
                            f"no sample assembles: at the first sample {j['link'][0]!r} and "
                            f"{j['link'][1]!r} coincide, so the line they carry has no direction",
                        )
                    turn = math.radians(j.get("angle_deg", 0.0))
                    ux, uy = tx - fx, ty - fy
                    dx = ux * math.cos(turn) - uy * math.sin(turn)
                    dy = ux * math.sin(turn) + uy * math.cos(turn)
                dist = abs((px - ox) * dy - (py - oy) * dx) / math.hypot(dx, dy)
                return scene.error(
                    ("mechanism", "joints", idx),
                    "r",
                    f"no sample assembles: at the first sample {j['pivot']!r} is {dist:.6g} from "
                    f"the slider's line, r reaches {j['r']:.6g} (closure gap "
                    f"{dist - j['r']:.3g})",
                )
            return scene.error(
                ("mechanism", "joints", idx),
                JOINT_KINDS[j["kind"]].blame,
                f"no sample assembles: joint {j['name']!r} cannot be placed at the first sample",
            )
    return scene.error(
        ("mechanism",),
        next(iter(m), "catalog"),
        f"no sample assembles over the run's {n} samples",
    )


def _first_unplaced(
    joints: list[dict[str, Any]], theta: float
) -> tuple[int, dict[str, Any], dict[str, Any]] | None:
    """Find the first joint of a joint program that cannot be placed at crank angle ``theta``.

    Returns its index, the joint and the positions of the joints before it (found by solving ever
    longer prefixes), or None when every joint is placed.
    """
    crank = next(k for k, j in enumerate(joints) if j["kind"] == "crank")
    placed: dict[str, Any] = {}
    for k in range(crank + 1, len(joints) + 1):
        mech = Mechanism()
        for j in joints[:k]:
            mech.add_joint(j)
        s = mech.sweep(np.array([theta]), outputs=("joints",))
        if not s.valid[0]:
            return k - 1, joints[k - 1], placed
        placed = {name: tuple(s.joints[0, i]) for i, name in enumerate(s.joint_names)}
    return None


def estimate_memory(scene: Scene, study: FourBar | Mechanism | Walker, samples: int) -> int:
    """Estimate the bytes a run of ``samples`` samples needs.

    That is 8 bytes × the numbers it keeps per sample × 2 (the arrays and the temporaries of the
    stage that makes them, or their copy in the report's table), plus 64 MiB for the interpreter and
    the plots.

    Numbers per sample: time, angle, speed, acceleration (4); a mechanism's trajectory (2 per
    joint + 4), rates (6 per joint + 6), instant centres (5 per link pair) and curvature (4),
    torque (8 per joint + 4); a walker's feet (12 per leg) plus one leg's sweep (2 per joint +
    8). Calibrated on peak resident memory (``/usr/bin/time``, 2e5 → 6e5 samples): the Hoecken
    example without straightness and animation grows by 1065 bytes per sample, estimated 1408;
    the hexapod by 1210, estimated 1504 — an estimate about 1.3 times the measured growth.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> import linkage
    >>> from linkage.build import estimate_memory
    >>> scene = Scene("leg", None, ("trajectory",))
    >>> small = estimate_memory(scene, linkage.catalog.hoecken(), 721)
    >>> big = estimate_memory(scene, linkage.catalog.hoecken(), 7201)
    >>> 0 < small < big
    True
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

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> import linkage
    >>> from linkage.build import check_memory_estimate
    >>> scene = Scene("leg", None, ("trajectory",))
    >>> check_memory_estimate(scene, linkage.catalog.hoecken(), 721, given=True)
    >>> check_memory_estimate(scene, linkage.catalog.hoecken(), 10**8, given=True)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: samples: 100000000 samples would need about ... the 2 GiB limit...
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


def check_counts(n: int, double: bool = True) -> tuple[int, ...]:
    """Return the sample counts a run of ``n`` samples is checked at.

    About half as many, on a grid that shares only its ends with the run's (``n_half − 1`` coprime
    to ``n − 1``, so that no extreme is found again at a shared sample), and — when ``double`` —
    twice as many, on the run's grid refined (every sample and the midpoints). The first catches
    aliasing (a figure that depends on where the samples fall), the second the slow convergence of
    extremes; a figure's error estimate is its largest difference from the two.

    >>> from linkage.figures import check_counts
    >>> check_counts(721), check_counts(8, double=False)
    ((360, 1441), (4,))
    """
    half = max(3, (n - 1) // 2 + 1)
    while half > 3 and math.gcd(half - 1, n - 1) != 1:
        half -= 1
    return (half, 2 * n - 1) if double else (half,)


def affordable_checks(scene: Scene, study: FourBar | Mechanism | Walker, n: int) -> tuple[int, ...]:
    """Return the sample counts of :func:`check_counts` that fit in memory with every run alive.

    Both when they fit, else the half only, else none (the figures then carry no error estimate).

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> import linkage
    >>> from linkage.build import affordable_checks
    >>> scene = Scene("leg", None, ("trajectory",))
    >>> affordable_checks(scene, linkage.catalog.hoecken(), 721)
    (360, 1441)
    >>> affordable_checks(scene, linkage.catalog.hoecken(), 7_000_000)    # none fits: no estimate
    ()
    """
    half, double = check_counts(n)
    if estimate_memory(scene, study, n + half + double) <= MEMORY_CAP:
        return (half, double)
    if estimate_memory(scene, study, n + half) <= MEMORY_CAP:
        return (half,)
    return ()


# -- synthesis scenes -------------------------------------------------------------------------

POINTS_FILE_MAX = synthesis.POINTS_FILE_MAX
"""Largest target points file (4 MiB: :data:`~linkage.scene.POINTS_MAX` lines of two numbers
take about 0.4 MiB); :func:`linkage.synthesis.read_points` holds every file to it."""


CURVE_BYTES = 2 * 8 * (5 * 2 + 2 + 2 + 1)
"""Bytes per sample of a candidate's circuit as a synthesis run keeps it (joints, velocity,
point, angle) and their temporaries (× 2)."""


def check_synthesis_memory(scene: Scene, samples: int) -> None:
    """Refuse a ``[synthesis]`` run whose curves would need more than the memory cap.

    The curves are ``top`` candidates' circuits in ``samples`` samples (only ``--samples`` sets it);
    the cap is :data:`~linkage.scene.MEMORY_CAP`.

    Raises
    ------
    SceneError
        Naming ``samples`` and the largest count that fits.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import check_synthesis_memory
    >>> scene = Scene("fit", None, ("synthesis",), synthesis={"top": 5})
    >>> check_synthesis_memory(scene, 721)
    >>> check_synthesis_memory(scene, 10**9)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: samples: 1000000000 samples of 5 coupler curves would need about...
    """
    top = int((scene.synthesis or {}).get("top", 5))
    need = top * samples * CURVE_BYTES + (64 << 20)
    if need <= MEMORY_CAP:
        return
    most = (MEMORY_CAP - (64 << 20)) // (top * CURVE_BYTES)
    raise SceneError(
        f"samples: {samples} samples of {top} coupler curves would need about "
        f"{need / 2**30:.3g} GiB (estimated), more than the {MEMORY_CAP / 2**30:g} GiB limit; "
        f"at most {most} samples"
    )


def synthesis_target(scene: Scene) -> Array:
    """Read and check the target points of a ``[synthesis]`` scene, ``(n, 2)``.

    They are read from its CSV file (relative to the scene's folder) or given inline, and checked as
    :func:`linkage.synthesis.path` will check them — at least :data:`~linkage.synthesis.MIN_POINTS`
    distinct points, not all on one line for a closed target — so that ``check`` refuses a target
    the search would.

    Raises
    ------
    SceneError
        Located at ``[synthesis] points``, naming the file as the scene gives it.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import synthesis_target
    >>> square = [[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 1.2]]
    >>> synthesis_target(Scene("fit", None, ("synthesis",), synthesis={"points": square})).shape
    (5, 2)
    >>> synthesis_target(Scene("fit", None, ("synthesis",), synthesis={"points": square[:4]}))
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [synthesis] points: ... needs at least 5 distinct points, got 4
    """
    s = scene.synthesis or {}
    sec = ("synthesis",)
    points, name = read_scene_points(scene, sec, "points", s["points"])
    closed = bool(s.get("closed", True))
    # As linkage.synthesis.path cleans them (one function).
    try:
        synthesis.clean_target(points, closed)
    except LinkageError as exc:
        raise scene.error(sec, "points", f"{name}: {exc}") from None
    return points


def _leg_scene(scene: Scene, lp: tuple[Any, ...], name: str) -> FourBar | Mechanism:
    """Build a walker leg's linkage from the ``[mechanism]`` scene file it names.

    Its trace point is the foot; a synthesis candidate's exported scene is one. A problem in
    that file is located at the leg's ``scene`` key, with the file's own ``file:line``.
    """
    path = base_folder(scene) / name
    if not path.is_file():
        why = "a folder" if path.is_dir() else "not found" if not path.exists() else "not a file"
        raise scene.error(lp, "scene", f"{name!r} (relative to this scene's folder): {why}")
    try:
        other = parse_only(read_text(path), path)
        if other.mechanism is None:
            raise SceneError(f"{path}: has no [mechanism] section (a leg is a linkage)")
        return build_mechanism(other)
    except SceneError as exc:
        # The file as this scene names it, then its own line.
        raise scene.error(lp, "scene", str(exc).replace(str(path), name)) from None


def reference_points(scene: Scene) -> Array | None:
    """Read a ``[mechanism]`` scene's ``reference`` points, ``(n, 2)``, or None without them.

    They are the path the trace should pass through (a synthesis candidate's scene carries its
    target so): from a CSV file relative to the scene's folder, or inline.

    Raises
    ------
    SceneError
        Located at ``[mechanism] reference``.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import reference_points
    >>> m = {"catalog": "hoecken", "reference": [[0, 0], [1, 0.5]]}
    >>> reference_points(Scene("leg", None, ("trajectory",), mechanism=m)).tolist()
    [[0.0, 0.0], [1.0, 0.5]]
    """
    m = scene.mechanism or {}
    if "reference" not in m:
        return None
    sec = ("mechanism",)
    points, name = read_scene_points(scene, sec, "reference", m["reference"])
    if not len(points):
        raise scene.error(
            sec,
            "reference",
            f"{name}: no points" if name != "the points" else "is empty: give [[x, y], …]",
        )
    return points


def read_scene_points(scene: Scene, sec: tuple[str, ...], key: str, raw: Any) -> tuple[Array, str]:
    """Read a scene's points: a CSV file of x, y relative to its folder, or ``[[x, y], …]``.

    Return them (at most :data:`POINTS_MAX`) and how a message names them (the file as the
    scene gives it).
    """
    points, name = _scene_points(scene, sec, key, raw)
    if len(points) > POINTS_MAX:
        raise scene.error(sec, key, f"{name}: at most {POINTS_MAX} points, got {len(points)}")
    return points, name


def _scene_points(scene: Scene, sec: tuple[str, ...], key: str, raw: Any) -> tuple[Array, str]:
    if isinstance(raw, str):
        where = base_folder(scene) / raw
        try:
            info = where.stat()
        except OSError as exc:
            raise scene.error(
                sec,
                key,
                f"cannot read {raw!r} (relative to the scene's folder): {exc.strerror or exc}",
            ) from None
        if where.is_dir():
            raise scene.error(sec, key, f"{raw!r} is a folder, not a CSV file of x, y")
        if not where.is_file():  # a device or a pipe: it may never end
            raise scene.error(sec, key, f"{raw!r} is not a regular file, not a CSV file of x, y")
        if info.st_size > POINTS_FILE_MAX:
            raise scene.error(
                sec,
                key,
                f"{raw!r} is larger than {POINTS_FILE_MAX >> 20} MiB: not a file of points",
            )
        try:
            points = synthesis.read_points(where)
        except LinkageError as exc:
            raise scene.error(sec, key, str(exc).replace(str(where), raw)) from None
        except (ValueError, TypeError):  # rows of different lengths
            raise scene.error(sec, key, f"{raw}: every row must hold two numbers (x, y)") from None
        return points, raw
    with _blame(scene, sec, key):
        points = synthesis.read_points(np.array(raw, dtype=np.float64).reshape(-1, 2))
    return points, "the points"


def synthesis_atlas(scene: Scene) -> synthesis.Atlas | None:
    """Open the atlas a ``[synthesis]`` scene names (relative to its folder), memory-mapped.

    None for the default one (built on first use into the cache folder by the search).

    Raises
    ------
    SceneError
        Located at ``[synthesis] atlas`` when the folder is not an atlas.

    Examples
    --------
    >>> from linkage.scene import Scene
    >>> from linkage.build import synthesis_atlas
    >>> synthesis_atlas(Scene("fit", None, ("synthesis",), synthesis={})) is None    # the default
    True
    >>> synthesis_atlas(Scene("fit", None, ("synthesis",), synthesis={"atlas": "no-such-atlas"}))
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: [synthesis] atlas: no atlas in 'no-such-atlas' ...
    """
    s = scene.synthesis or {}
    if "atlas" not in s:
        return None
    raw = s["atlas"]
    folder = base_folder(scene) / raw
    if not (folder / "meta.json").is_file():
        raise scene.error(
            ("synthesis",),
            "atlas",
            f"no atlas in {raw!r} (relative to the scene's folder): a folder written by "
            "linkage.synthesis.Atlas.save holds meta.json, descriptors.npy and params.npy",
        )
    try:
        atlas = synthesis.Atlas.load(folder)
    except LinkageError as exc:
        # Every field is checked on load: the message names the file or field, located here.
        raise scene.error(
            ("synthesis",), "atlas", str(exc).replace(str(folder), repr(raw))
        ) from None
    kind = str(s.get("kind", "fourbar"))
    serves = {
        "fourbar": ("fourbar", "fourbar-arcs"),
        "slider-crank": ("slider-crank", "slider-crank-arcs"),
    }
    if atlas.kind not in serves.get(kind, (atlas.kind,)):
        raise scene.error(
            ("synthesis",),
            "atlas",
            f"{raw!r} holds a {atlas.kind} atlas, but the scene seeks kind = {kind!r}: name an "
            f"atlas of {' or '.join(serves[kind])}, or set kind",
        )
    return atlas
