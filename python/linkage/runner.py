"""Running a scene: build the study, run only the stages its outputs need, collect figures with
their error estimates and the time of each stage."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage import catalog
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
from linkage.scene import Scene, SceneError
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


def build_mechanism(scene: Scene) -> FourBar | Mechanism:
    """The scene's mechanism."""
    m = scene.mechanism or {}
    if "catalog" in m:
        item = catalog.get(m["catalog"])
        scale = float(m.get("scale", 1.0))
        if scale != 1.0:
            if not isinstance(item, FourBar):
                raise SceneError(
                    "[mechanism] scale: only catalogue four-bars can be scaled, "
                    f"not {m['catalog']!r}"
                )
            item = _scaled(item, scale)
        return item
    if "ground" in m:
        return FourBar(
            ground=m["ground"],
            crank=m["crank"],
            coupler=m["coupler"],
            rocker=m["rocker"],
            point=tuple(m.get("point", (0.0, 0.0))),
            assembly=m.get("assembly", "open"),
        )
    mech = Mechanism()
    for j in m["joints"]:
        kind = j["kind"]
        if kind == "fixed":
            mech.fixed(j["name"], j["at"])
        elif kind == "crank":
            mech.crank(j["name"], j["centre"], j["radius"], math.radians(j.get("phase_deg", 0.0)))
        elif kind == "dyad":
            mech.dyad(j["name"], j["p1"], j["p2"], j["r1"], j["r2"], j.get("side", "left"))
        else:
            mech.point(j["name"], tuple(j["on"]), (j["along"], j.get("left", 0.0)))
    if "trace" in m:
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


def build_walker(scene: Scene) -> Walker:
    """The scene's walker: a catalogue model, or legs built from catalogue four-bars."""
    from dataclasses import replace

    from linkage.walker import Leg

    w = scene.walker or {}
    if "model" in w:
        walker: Walker = getattr(catalog, w["model"])()
    else:
        legs = []
        for spec in w["legs"]:
            fb = catalog.get(spec["catalog"])
            assert isinstance(fb, FourBar)
            k = float(spec.get("scale", 1.0))
            if k != 1.0:
                fb = _scaled(fb, k)
            lift = None
            if "lift" in spec:
                segs = [
                    Segment(math.radians(s["duration_deg"]), s.get("rise", 0.0), s.get("law"))
                    for s in spec["lift"]
                ]
                lift = Program(0.0, segs)
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
        walker = Walker(legs)
    names = [leg.name for leg in walker.legs]
    if "gait" in w:
        walker = walker.with_phases([float(p) for p in gait_phases(w["gait"], names)])
    if "phases_deg" in w:
        if len(w["phases_deg"]) != len(names):
            raise SceneError(f"[walker] phases_deg: need {len(names)} phases ({', '.join(names)})")
        walker = walker.with_phases([math.radians(p) for p in w["phases_deg"]])
    if "pad" in w:
        walker = Walker(
            [replace(leg, pad=float(w["pad"])) for leg in walker.legs],
            walker.cg,
            walker.ground_tol,
            walker.body_underside,
        )
    if "cg" in w or "ground_tol" in w:
        walker = Walker(
            walker.legs,
            cg=tuple(w.get("cg", walker.cg)),
            ground_tol=w.get("ground_tol", walker.ground_tol),
            body_underside=walker.body_underside,
        )
    return walker


def build_drive(scene: Scene, leg: FourBar | Mechanism) -> tuple[Any, float]:
    """The scene's drive and its natural duration (one crank cycle or program period)."""
    d = scene.drive
    train = GearTrain.simple(d["gears"]) if "gears" in d else None
    kind = d["kind"]
    if kind == "constant":
        motor = d["rpm"] * 2 * math.pi / 60 if "rpm" in d else d["omega"]
        drive: Any = ConstantSpeed(motor)
        crank = motor * (train.ratio * train.sign if train else 1.0)
        period = 2 * math.pi / abs(crank)
    elif kind == "program":
        segs = [
            Segment(s["duration"], math.radians(s.get("rise_deg", 0.0)), s.get("law"))
            for s in d["segments"]
        ]
        drive = Program(math.radians(d.get("start_deg", 0.0)), segs)
        period = drive.period
    else:
        drive = crank_schedule(leg, d["foot_speed"], d["duty_factor"])
        period = drive.period
    if train is not None and kind != "schedule":
        drive = Geared(drive, train)
    return drive, period


def run(
    scene: Scene, samples: int | None = None, progress: Callable[[str], None] | None = None
) -> Result:
    """Run the stages ``scene.outputs`` need.

    Raises
    ------
    LinkageError
        When the study cannot be computed (the message says why).
    """
    tell = progress or (lambda _: None)
    d = scene.drive
    n = int(samples if samples is not None else d.get("samples", 721))
    stages: dict[str, float] = {}

    def stage(name: str, fn: Callable[[], Any]) -> Any:
        tell(name)
        t0 = time.perf_counter()
        out = fn()
        stages[name] = time.perf_counter() - t0
        return out

    if scene.walker is not None:
        walker = stage("build", lambda: build_walker(scene))
        leg = walker.legs[0].linkage
    else:
        walker = None
        leg = stage("build", lambda: build_mechanism(scene))
    drive, period = build_drive(scene, leg)
    duration = float(d.get("duration", period * d.get("cycles", 1.0)))
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
        return _finish(res, stages)

    mech = leg
    sweep = stage("trajectory", lambda: mech.sweep(theta))
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
        res.figures.append(
            ("speed variation along it", f"{100 * part.speed_variation:.1f}%", "", "this drive")
        )
    return part


def _torque(res: Result, scene: Scene, mech: FourBar | Mechanism, t: Array, drive: Any) -> Forces:
    masses = {
        k: LinkMass(v["mass"], tuple(v.get("centre", (0.0, 0.0))), v.get("inertia", 0.0))
        for k, v in (scene.masses or {}).items()
    }
    loads = [
        PointLoad(ld["link"], ld["joint"], tuple(ld["force"]), ld.get("torque", 0.0))
        for ld in scene.loads
    ]
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
    from linkage.cam import DiscCam

    c = scene.cam or {}
    segs = [
        Segment(math.radians(s["duration_deg"]), s.get("rise", 0.0), s.get("law"))
        for s in c["segments"]
    ]
    cam = DiscCam(
        Program(0.0, segs),
        c["base_radius"],
        roller_radius=c.get("roller_radius"),
        offset=c.get("offset", 0.0),
        pressure_limit=math.radians(c.get("pressure_limit_deg", 30.0)),
    )
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
        rows.append(
            (
                "minimum stability margin",
                _f(sim.min_margin),
                u,
                f"at t = {sim.time[int(np.nanargmin(sim.margin))]:.4g} s",
            )
        )
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
