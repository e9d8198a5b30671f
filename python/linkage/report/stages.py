"""Running a scene: build the study, run only the stages its outputs need, collect figures.

The study is built by :mod:`linkage.build`; each stage's rows of the figures table are made by
:mod:`linkage.stage_figures`, and carry their error estimates (:mod:`linkage.figures`); the time
of each stage is kept. A ``[synthesis]`` scene runs one stage, the search
(:func:`linkage.synthesis.path`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from functools import partial
from typing import Any, cast

import numpy as np
from numpy.typing import NDArray

from linkage import synthesis
from linkage._core import LinkageError
from linkage._shared.choices import PathKind
from linkage.drives.cam import CamProfile
from linkage.drives.drive import CrankSchedule
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.sweep import Sweep
from linkage.kinetostatics.forces import Forces, joint_forces
from linkage.motion.geometry import StraightPart, straightness
from linkage.report.figures import (
    Result,
    Row,
    SynthesisRun,
    check_counts,
    exact,
    versus,
)
from linkage.report.stage_rows import STRAIGHT_RADIUS as STRAIGHT_RADIUS  # moved; its old home
from linkage.report.stage_rows import (
    cam_figures,
    drive_label,
    geometry_figures,
    rate_figures,
    straightness_figures,
    synthesis_figures,
    torque_figures,
    trajectory_figures,
    walker_figures,
)
from linkage.scene.builders import (
    ARITHMETIC,
    affordable_checks,
    build_cam,
    build_drive,
    build_masses,
    build_study,
    check_legs,
    check_memory_estimate,
    check_synthesis_memory,
    no_assembly,
    reference_points,
    run_duration,
    sample_count,
    synthesis_atlas,
    synthesis_target,
)
from linkage.scene.schema import Scene
from linkage.walking.walker import Walker

__all__ = ["CAM_SAMPLES", "CONSTRAINTS", "STRAIGHT_RADIUS", "run"]

Array = NDArray[np.float64]


def run(
    scene: Scene, samples: int | None = None, progress: Callable[[str], None] | None = None
) -> Result:
    r"""Run the stages ``scene.outputs`` need, and each again at other sample counts.

    The other sample counts are those of :func:`check_counts` (the stage ``second resolution``; the
    doubled run only when it fits the memory limit): the largest difference is the error estimate of
    every sampled figure.

    Raises
    ------
    LinkageError
        When the study cannot be computed (the message says why); a :class:`SceneError`,
        located at the key responsible, for a scene problem (including a run in which no
        sample assembles).

    Examples
    --------
    >>> from linkage.runner import run
    >>> from linkage.scene import parse
    >>> scene = parse('units = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...               '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n')
    >>> result = run(scene)
    >>> result.check_samples
    (36, 145)
    >>> for row in result.figures:
    ...     if row.figure in ("samples assembled", "trace x range", "trace y range"):
    ...         print(*row, sep=" | ")
    samples assembled | 73 / 73 |  | exact
    trace x range | -3.514 … 43.514 | mm | ±0.090 (vs 36 and 145 samples)
    trace y range | 40.0000 … 48.9898 | mm | ±0.0019 (vs 36 and 145 samples)
    >>> run(scene, samples=2)
    Traceback (most recent call last):
    ...
    linkage._schema.SceneError: samples must be a whole number from 8 to 1000000000, got 2
    """
    tell = progress or (lambda _: None)
    n = sample_count(scene, samples)
    stages: dict[str, float] = {}

    def stage(name: str, fn: Callable[[], Any]) -> Any:
        tell(name)
        t0 = time.perf_counter()
        try:
            out = fn()
        except (LinkageError, MemoryError):
            raise
        except ARITHMETIC as exc:
            raise LinkageError(f"stage {name!r} failed: {exc}") from None
        stages[name] = stages.get(name, 0.0) + time.perf_counter() - t0
        return out

    if scene.synthesis is not None:
        res = _synthesis(scene, n, stage)
        took = stages.get("synthesis", 0.0)
        res.figures.append(Row("search time", f"{took:.2f}", "s", "wall clock", value=took))
        return _finish(res, stages)
    study, leg = stage("build", lambda: build_study(scene))
    reference = reference_points(scene)
    check_memory_estimate(scene, study, n, given=samples is not None)
    walker = study if isinstance(study, Walker) else None
    drive, period = build_drive(scene, leg)
    duration = run_duration(scene, period)
    if walker is not None:
        check_legs(scene, walker, drive, duration, n)
    t = np.linspace(0.0, duration, n)
    theta, omega, alpha = drive.angles(t)
    ns = affordable_checks(scene, study, n)
    alts = [np.linspace(0.0, duration, k) for k in ns]
    res = Result(scene=scene, time=t, theta=theta, mechanism=None if walker else leg, walker=walker)
    res.check_samples = ns
    res.drive = drive
    res.arrays.update(time=t, theta=theta, omega=omega, alpha=alpha)
    rows = res.figures
    rows.append(Row("drive", drive_label(scene, drive)))
    rows.append(exact("duration", duration, "s"))
    rows.append(Row("samples", str(n), "", f"errors {versus(ns)}", value=n, exact=True))
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
        walker_figures(res, sim, sims, walker, duration, period, closure)
        if scene.wants("cam"):
            res.cam = stage("cam", lambda: _cam(res, scene))
        return _finish(res, stages)

    mech = leg
    sweep = stage("trajectory", lambda: mech.sweep(theta))
    if not sweep.valid.any():
        raise no_assembly(scene, mech, drive, duration, n)
    res.sweep = sweep
    angles = [drive.angles(ta) for ta in alts]
    sweeps = [stage(second, partial(mech.sweep, a[0])) for a in angles]
    trajectory_figures(res, mech, sweep, sweeps, _rigidity(mech, sweep), reference)

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
        rate_figures(res, rates, rates2)
    if scene.wants("instant_centres", "curvature"):
        geo_outs = ("point", *(o for o in ("instant_centres", "curvature") if scene.wants(o)))
        geo = stage("geometry", lambda: mech.sweep(theta, outputs=geo_outs))
        geo2 = [stage(second, partial(mech.sweep, a[0], outputs=geo_outs)) for a in angles]
        res.geometry = geo
        geometry_figures(res, geo, sweep, geo2)
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


# -- synthesis scenes ------------------------------------------------------------------------

CONSTRAINTS = ("full_turn", "min_transmission_deg", "lengths", "pivots")
"""The keys of ``[synthesis]`` that restrict the candidates (blamed when none is left)."""


def _synthesis(scene: Scene, n: int, stage: Callable[[str, Callable[[], Any]], Any]) -> Result:
    """Search for a ``[synthesis]`` scene's linkages: candidates, coupler curves and figures.

    Each candidate's coupler curve is over its circuit in ``n`` samples; the figures' errors have
    three significant digits (they are distances measured to ~1e-3 of themselves, not sampled
    quantities).
    """
    s = scene.synthesis or {}
    check_synthesis_memory(scene, n)
    closed = bool(s.get("closed", True))
    target, atlas = stage("build", lambda: (synthesis_target(scene), synthesis_atlas(scene)))
    lengths = s.get("lengths")
    pivots = s.get("pivots")

    kind = str(s.get("kind", "fourbar"))
    sought = {"fourbar": "four-bar", "slider-crank": "slider-crank"}.get(kind, "linkage")

    def search() -> synthesis.Candidates:
        return synthesis.path(
            target,
            closed=closed,
            kind=cast(PathKind, kind),
            top=int(s.get("top", 5)),
            refine=int(s.get("refine", 8)),
            atlas=atlas,
            full_turn=bool(s.get("full_turn", False)),
            min_transmission=math.radians(float(s.get("min_transmission_deg", 0.0))),
            lengths=(float(lengths[0]), float(lengths[1])) if lengths else None,
            pivots=(
                (
                    (float(pivots[0][0]), float(pivots[0][1])),
                    (float(pivots[1][0]), float(pivots[1][1])),
                )
                if pivots
                else None
            ),
            tol=float(s.get("tol", 1e-3)),
            accept=float(s["accept"]) if "accept" in s else None,
            seed=int(s.get("seed", 0)),
        )

    # A default atlas not yet in the cache is built once (seconds): its own stage, so the wait
    # shows on the progress line and in the stage times.
    given = [atlas.kind] if atlas is not None else []
    missing = synthesis.missing_atlases(cast(PathKind, kind), closed, given)
    if missing:
        stage("atlas", lambda: [synthesis.default_atlas(kind=a) for a in missing])
    try:
        found = stage("synthesis", search)
    except LinkageError as exc:
        raise scene.error(("synthesis",), "points", f"the search failed: {exc}") from None
    if not found:
        names = dict(zip(synthesis.CONSTRAINT_NAMES, CONSTRAINTS), refine="refine")
        why, blamed = synthesis.why_none(found, names, scene.units)
        key = "points" if blamed is None else names[blamed]
        raise scene.error(("synthesis",), key, f"no valid {sought} found: {why}")
    circuits = [c.linkage.circuit(n) for c in found]
    curves = [np.asarray(c.point, dtype=np.float64) for c in circuits]
    size = synthesis.target_size(target)
    empty = np.zeros(0)
    res = Result(scene=scene, time=empty, theta=empty)
    res.synthesis = SynthesisRun(target, closed, found, curves, size, circuits[0])
    res.arrays.update(target=target, curves=np.stack(curves))
    synthesis_figures(res)
    return res


def _rigidity(mech: FourBar | Mechanism, s: Sweep) -> float:
    """Return the loop-closure residual: the largest change of a link's joint distances.

    That is the largest change of any distance between two joints of one link over the sweep
    (zero for exact kinematics), computed by the core (``Bodies::closure_residual``).
    """
    m = mech.mechanism() if isinstance(mech, FourBar) else mech
    joints = np.ascontiguousarray(s.joints, dtype=np.float64).reshape(-1, len(s.joint_names), 2)
    return float(m._core.closure_residual(joints))


def _straight_size(mech: FourBar | Mechanism, s: Sweep) -> float:
    if isinstance(mech, FourBar):
        return max(mech.ground, mech.crank, mech.coupler, mech.rocker)
    return float(np.nanmax(np.ptp(s.point[s.valid], axis=0)))


def _straightness(
    res: Result, mech: FourBar | Mechanism, others: list[Sweep]
) -> StraightPart | None:
    """Find the trace's longest straight part within 0.1 % of the size, and at the check counts.

    The tolerance is 1e-3 of :func:`_straight_size`; ``others`` are the sweeps at the check counts
    (with rates when the run has them, for the speed variation along the part).
    """
    s = res.rates or res.sweep
    assert s is not None
    tol = 1e-3 * _straight_size(mech, s)
    part: StraightPart | None = None
    parts: list[StraightPart | None] = []
    if math.isfinite(tol) and tol > 0:
        vel = res.rates.velocity if res.rates is not None else None
        part = straightness(s.point, tol, velocity=vel)
        if part is not None:
            parts = [
                straightness(o.point, tol, velocity=o.velocity if res.rates is not None else None)
                for o in others
            ]
    straightness_figures(res, part, parts, tol)
    return part


def _torque(
    res: Result, scene: Scene, mech: FourBar | Mechanism, t: Array, alts: list[Array], drive: Any
) -> Forces:
    masses, loads = build_masses(scene, mech)
    f = joint_forces(mech, time=t, drive=drive, masses=masses, gravity=scene.gravity, loads=loads)
    f2 = [
        joint_forces(mech, time=ta, drive=drive, masses=masses, gravity=scene.gravity, loads=loads)
        for ta in alts
    ]
    torque_figures(res, f, f2)
    return f


CAM_SAMPLES = 721
"""Cam profile samples (every 0.5°); the error estimate compares :func:`check_counts`."""


def _cam(res: Result, scene: Scene) -> CamProfile:
    cam = build_cam(scene)
    assert cam is not None  # the stage runs only for a scene with a [cam]
    p = cam.profile(CAM_SAMPLES)
    ns = check_counts(CAM_SAMPLES)
    cam_figures(res, p, [cam.profile(k) for k in ns], ns)
    return p
