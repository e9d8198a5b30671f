"""The figures table's rows of each stage of a run: what the report says a stage found.

:mod:`linkage.runner` runs the stages and hands each one's output here, with the same output at
the other sample counts (:func:`linkage.figures.check_counts`); each function appends its rows to
:attr:`Result.figures <linkage.figures.Result.figures>` and its arrays to ``Result.arrays``. The
rows are made, and their numbers formatted, by :mod:`linkage.figures`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage.drawing import sagittal_pivots
from linkage.drives.cam import CamProfile
from linkage.drives.drive import Geared
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.slider_crank import SliderCrank
from linkage.kinematics.sweep import Sweep
from linkage.kinetostatics.forces import Forces
from linkage.motion.geometry import StraightPart, straightness, three_point_centres
from linkage.report.figures import (
    Result,
    Row,
    branch_text,
    branch_word,
    exact,
    format_error,
    format_number,
    length_unit,
    pair,
    row,
    sci,
    spread,
    torque_unit,
    versus,
)
from linkage.scene.schema import Scene
from linkage.synthesis import (
    CHANGE_POINT_NEAR,
    Candidate,
    change_point_gap,
    long_link,
    source_text,
)
from linkage.walking.walker import Simulation, Walker

__all__ = [
    "CHANGE_POINT_NEAR",
    "REFERENCE_LEVELS",
    "REFERENCE_NEAREST",
    "REFERENCE_SUBSAMPLES",
    "STRAIGHT_RADIUS",
    "cam_figures",
    "drive_label",
    "geometry_figures",
    "rate_figures",
    "reference_gap",
    "straightness_figures",
    "synthesis_figures",
    "torque_figures",
    "trajectory_figures",
    "walker_figures",
]

Array = NDArray[np.float64]


def drive_label(scene: Scene, drive: Any) -> str:
    """Return the text of the ``drive`` row: the scene's drive, and the crank's speed if geared.

    Examples
    --------
    >>> import linkage
    >>> from linkage.build import build_drive
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import drive_label
    >>> drive = {"kind": "constant", "rpm": 50.0, "gears": [18, 15, 14]}
    >>> scene = Scene("leg", None, (), drive=drive)
    >>> drive_label(scene, build_drive(scene, linkage.catalog.hoecken())[0])
    'constant 50 rpm through 18→15→14 gears (crank 64.2857 rpm)'
    >>> scene = Scene("leg", None, (), drive={"kind": "program", "segments": [{}, {}]})
    >>> drive_label(scene, None)
    'motion program, 2 segments'
    """
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


def synthesis_figures(res: Result) -> None:
    """Append the rows of a ``[synthesis]`` search: the target, then each candidate's figures.

    Raises
    ------
    LinkageError
        If ``res`` is not a ``[synthesis]`` run (nothing is appended).

    Examples
    --------
    A synthesis run needs an atlas (see :func:`linkage.synthesis.path`); any other run is refused:

    >>> import numpy as np
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import synthesis_figures
    >>> synthesis_figures(Result(Scene("leg", None, ()), np.zeros(0), np.zeros(0)))
    Traceback (most recent call last):
    ...
    linkage.LinkageError: not a synthesis run
    """
    run = res.synthesis
    if run is None:
        raise LinkageError("not a synthesis run")
    u = length_unit(res.scene)
    rows = res.figures
    shape = "closed curve" if run.closed else "open path"
    rows.append(Row("target", f"{len(run.target)} points, {shape}", "", value=len(run.target)))
    rows.append(
        Row(
            "target size",
            format_number(run.size, digits=3),
            u,
            "RMS distance of the points from their centroid",
            value=run.size,
        )
    )
    top = int((res.scene.synthesis or {}).get("top", 5))
    rows.append(
        Row(
            "candidates found",
            str(len(run.candidates)),
            "",
            f"best first (at most top = {top})",
            value=len(run.candidates),
            exact=True,
        )
    )
    for k, c in enumerate(run.candidates, 1):
        name = f"candidate {k}"
        rows.append(
            Row(
                f"{name}: max error",
                format_number(c.error, digits=3),
                u,
                "largest distance of a target point from the coupler curve",
                value=c.error,
            )
        )
        rows.append(
            Row(
                f"{name}: RMS error",
                format_number(c.rms, digits=3),
                u,
                "root mean square of those distances",
                value=c.rms,
            )
        )
        if run.closed:
            rows.append(
                Row(
                    f"{name}: curve → target polygon",
                    format_number(c.back, digits=3),
                    u,
                    "largest distance of the coupler curve from the target's polygon (a spur "
                    "or loop the points do not ask for)",
                    value=c.back,
                )
            )
        rows.append(
            Row(
                f"{name}: {'class' if isinstance(c.linkage, SliderCrank) else 'Grashof class'}",
                c.grashof,
                "",
                f"{branch_text(c.linkage)}, from the {source_text(c.source)}"
                f"{_long(c, run.size)}"
                f"{_near_change_point(c, run.size, u)}",
            )
        )
        # The value in full, as candidates.csv has it; the text to 0.1° (never "-0.0").
        lo, hi = (math.degrees(v) + 0.0 for v in c.crank_range)
        lo_text, hi_text = (f"{round(v, 1) + 0.0:.1f}" for v in (lo, hi))
        how = (
            ("full turn" if run.closed else "the matched part; the crank turns fully")
            if c.full_turn
            else f"rocks between its limits, through one (the {branch_word(c.linkage)} changes "
            "there)"
            if c.through_limit
            else "rocks within its limits"
        )
        rows.append(
            Row(f"{name}: crank range", f"{lo_text} … {hi_text}", "deg", how, value=(lo, hi))
        )
        mu = c.min_transmission_deg + 0.0
        rows.append(
            Row(
                f"{name}: min transmission angle",
                f"{round(mu, 1) + 0.0:.1f}",
                "deg",
                "least distance from a toggle over the "
                + ("whole turn" if c.full_turn else "matched part"),
                value=mu,
            )
        )


def _long(c: Candidate[FourBar | SliderCrank], size: float) -> str:
    """Return a note for a candidate with a link over ``LONG_LINK`` target sizes, else "".

    Such a link (``linkage.synthesis.LONG_LINK``, 20) makes no practical design.
    """
    ratio = long_link(c, size)
    if ratio is None:
        return ""
    return f"; its longest link is {ratio:.0f}× the target's size"


def _near_change_point(c: Candidate[FourBar | SliderCrank], size: float, unit: str) -> str:
    """Return a note for a candidate within :data:`CHANGE_POINT_NEAR` of a change point, else "".

    A fit pushed against the full-turn condition ends on it: a "crank-rocker" whose ``s + l``
    is ``p + q`` to 1e-5 mm turns fully on paper but can flip branch where its links lie flat.
    """
    near = change_point_gap(c, size)
    if near is None:
        return ""
    gap, law = near
    return (
        f"; {format_number(gap, digits=2)} {unit} from a change point ({law}): it can flip "
        "branch where its links lie flat"
    )


def _ranges(s: Sweep) -> tuple[tuple[float, float], tuple[float, float]] | None:
    p = s.point[s.valid]
    if not len(p):
        return None
    return (
        (float(p[:, 0].min()), float(p[:, 0].max())),
        (float(p[:, 1].min()), float(p[:, 1].max())),
    )


def trajectory_figures(
    res: Result,
    mech: FourBar | Mechanism,
    s: Sweep,
    others: list[Sweep],
    closure: float,
    reference: NDArray[np.float64] | None = None,
) -> None:
    """Append the rows of the trajectory stage: its sweep ``s``, ``others`` at the check counts.

    ``closure`` is the sweep's loop-closure residual: the largest change of a link's joint
    distances over it (0 if exact). ``reference``, the scene's reference points (a synthesis
    target), adds their largest distance from the traced path (its samples joined by
    straight lines, broken where the linkage does not assemble).

    Examples
    --------
    Evans' linkage B rocks between its toggles: driven round, it assembles at 34 of 73 samples.

    >>> import numpy as np, linkage
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import trajectory_figures
    >>> res = Result(Scene("leg", None, (), units="mm"), np.zeros(0), np.zeros(0))
    >>> res.check_samples = (37,)                      # the other resolution's sample count
    >>> evans = linkage.catalog.evans_b()
    >>> turn = np.linspace(0, 2 * np.pi, 73), np.linspace(0, 2 * np.pi, 37)
    >>> trajectory_figures(res, evans, evans.sweep(turn[0]), [evans.sweep(turn[1])], 0.0)
    >>> for row in res.figures:
    ...     print(*row[:3], sep=" | ")
    samples assembled | 34 / 73 |
    loop-closure residual | 0 | mm
    trace x range | 13.071 … 21.704 | mm
    trace y range | -1.902 … 12.771 | mm
    Grashof class | triple-rocker |
    """
    res.arrays.update(point=s.point, joints=s.joints, valid=s.valid.astype(float), margin=s.margin)
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
            sci(closure),
            u,
            "0 if exact",
            value=closure,
            error=closure,
            exact=True,
        )
    )
    fine, alt = _ranges(s), [_ranges(o) for o in others]
    if fine is not None:
        rows.append(pair("trace x range", fine[0], u, [a[0] if a else None for a in alt], ns))
        rows.append(pair("trace y range", fine[1], u, [a[1] if a else None for a in alt], ns))
    if reference is not None:
        res.arrays["reference"] = reference
        gap = reference_gap(mech, s, reference)
        coarse: list[float | None] = [reference_gap(mech, o, reference) for o in others]
        rows.append(
            row(
                "reference points to the trace",
                gap,
                u,
                coarse,
                ns,
                f"largest distance of the {len(reference)} points from the traced path"
                if len(reference) > 1
                else "distance of the point from the traced path",
            )
        )
    if isinstance(mech, FourBar):
        rows.append(Row("Grashof class", mech.grashof(), "", "exact", exact=True))


REFERENCE_SUBSAMPLES = 32
"""Samples of the trace's path in each of :data:`REFERENCE_LEVELS` narrowings around a reference
point (:func:`reference_gap`)."""
REFERENCE_LEVELS = 3
"""Narrowings of the path around each reference point (:func:`reference_gap`)."""
REFERENCE_NEAREST = 4
"""Nearest samples of the run around which :func:`reference_gap` sweeps for each point."""


def reference_gap(mech: FourBar | Mechanism, s: Sweep, reference: Array) -> float:
    """Return the largest distance of the ``reference`` points from the path ``s`` traces.

    Around each point the path is swept again: :data:`REFERENCE_SUBSAMPLES` samples from the
    sample before each of the :data:`REFERENCE_NEAREST` nearest of ``s`` to the sample after
    it, then as many between the neighbours of the nearest of those, :data:`REFERENCE_LEVELS`
    times in all; the distance is to the last of them as a polyline, whose step is 16³ times
    finer than the run's, so its chords stray 16⁶ times less (a candidate's 5e-7 mm fit had
    read as 5.8e-4 mm at 360 samples). ∞ when no sample assembles.

    Examples
    --------
    Points on Hoecken's coupler curve between a coarse run's samples, then one moved 1 mm
    along the normal there:

    >>> import numpy as np, linkage
    >>> from linkage.stage_figures import reference_gap
    >>> fb = linkage.catalog.hoecken()
    >>> s = fb.sweep(np.linspace(0, 2 * np.pi, 73))
    >>> on = fb.sweep(np.array([0.03, 1.0, 4.0]), omega=1.0, outputs=("point", "velocity"))
    >>> reference_gap(fb, s, on.point) < 1e-8   # 1.4e-9: 3e-11 of the curve's size
    True
    >>> t = on.velocity[1] / np.linalg.norm(on.velocity[1])
    >>> off = on.point[1] + np.array([-t[1], t[0]])
    >>> print(f"{reference_gap(fb, s, off[None]):.6f}")
    1.000000
    """
    from scipy.spatial import cKDTree  # type: ignore[import-untyped]  # noqa: PLC0415

    ok = np.flatnonzero(s.valid)
    if not len(ok):
        return math.inf
    # Around each of the nearest few samples: a closed path's first and last samples are one
    # point, and a path passing near itself has near samples on both passes.
    k = min(REFERENCE_NEAREST, len(ok))
    nearest = ok[cKDTree(s.point[ok]).query(reference, k=k)[1].reshape(len(reference), k)]
    nearest = nearest.ravel()
    ref = np.repeat(reference, k, axis=0)
    last = len(s.theta) - 1
    a = s.theta[np.maximum(nearest - 1, 0)]
    b = s.theta[np.minimum(nearest + 1, last)]
    steps = np.arange(REFERENCE_SUBSAMPLES + 1) / REFERENCE_SUBSAMPLES
    rows = np.arange(len(ref))
    for level in range(REFERENCE_LEVELS):
        theta = a[:, None] + (b - a)[:, None] * steps[None, :]
        dense = mech.sweep(theta.ravel(), outputs=("point",))
        pts = np.where(dense.valid[:, None], dense.point, np.nan).reshape(len(ref), -1, 2)
        if level == REFERENCE_LEVELS - 1:
            break
        d = np.linalg.norm(pts - ref[:, None, :], axis=2)
        j = np.where(np.isnan(d), np.inf, d).argmin(axis=1)
        a = theta[rows, np.maximum(j - 1, 0)]
        b = theta[rows, np.minimum(j + 1, REFERENCE_SUBSAMPLES)]
    # Each point's distance from the polyline of its own last samples (broken where one does
    # not assemble), the least over its nearest samples, the largest over the points.
    each = _core.synthesis.polyline_distance_each(
        np.ascontiguousarray(ref, dtype=np.float64),
        np.ascontiguousarray(pts.reshape(-1, 2), dtype=np.float64),
        pts.shape[1],
    )
    return float(each.reshape(len(reference), k).min(axis=1).max())


def _lowest_pivot(walker: Walker, sim: Simulation) -> float | None:
    """Return the height above the ground of the lowest fixed pivot of the sagittal legs.

    None when no leg is sagittal (a horizontal leg's pivots lie in the body's plane).
    """
    pins = sagittal_pivots(walker, sim)
    if not len(pins):
        return None
    return float(pins[:, 2].min() - sim.ground)


def _peaks(s: Sweep) -> tuple[float, float]:
    """Return the run's peak trace speed and acceleration.

    Both are ``inf`` when the run reaches a toggle (a valid sample whose dyad margin is below
    1e-6, :meth:`Sweep.near_toggle`): there the rates of a steadily driven input grow without
    bound, and the sampled ones are NaN or round-off (a rocking crank driven to its limits had
    printed 1.2e8 mm/s ±0 on a 27 mm linkage).
    """
    ok = s.valid
    if np.any(s.near_toggle()):
        return math.inf, math.inf
    speed = np.linalg.norm(s.velocity[ok], axis=1)
    accel = np.linalg.norm(s.acceleration[ok], axis=1)
    return (
        float(speed.max()) if len(speed) else math.nan,
        float(accel.max()) if len(accel) else math.nan,
    )


def rate_figures(res: Result, s: Sweep, others: list[Sweep]) -> None:
    """Append the peak speed and acceleration rows (those the scene's outputs ask for).

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import rate_figures
    >>> res = Result(Scene("leg", None, ("velocity",), units="mm"), np.zeros(0), np.zeros(0))
    >>> res.check_samples = (37,)                      # the other resolution's sample count
    >>> hoecken, outs = linkage.catalog.hoecken(), ("point", "velocity", "acceleration")
    >>> s, s2 = (hoecken.sweep(np.linspace(0, 2 * np.pi, n), omega=1.0, outputs=outs)
    ...          for n in (73, 37))
    >>> rate_figures(res, s, [s2])              # the speed only: the scene asks for no more
    >>> for row in res.figures:
    ...     print(*row[:3], sep=" | ")
    peak trace speed | 48.9898 | mm/s
    """
    res.arrays.update(velocity=s.velocity, acceleration=s.acceleration)
    (speed, accel), alt = _peaks(s), [_peaks(o) for o in others]
    u = length_unit(res.scene)
    ns = res.check_samples
    toggle = "unbounded (the run reaches a toggle)"
    if res.scene.wants("velocity"):
        if math.isinf(speed):
            res.figures.append(Row("peak trace speed", toggle, f"{u}/s"))
        else:
            others_ = [a[0] if math.isfinite(a[0]) else None for a in alt]
            res.figures.append(row("peak trace speed", speed, f"{u}/s", others_, ns))
    if res.scene.wants("acceleration"):
        if math.isinf(accel):
            res.figures.append(Row("peak trace acceleration", toggle, f"{u}/s²"))
        else:
            others_ = [a[1] if math.isfinite(a[1]) else None for a in alt]
            res.figures.append(row("peak trace acceleration", accel, f"{u}/s²", others_, ns))


STRAIGHT_RADIUS = 1e6
"""A path whose every radius of curvature exceeds this many times its extent is straight: its
radius is reported as ∞ (the finite values are round-off of an exact line)."""


def _on_a_line(p: Array, extent: float) -> bool:
    """Say whether every point of ``p`` lies within 1e-9 × ``extent`` of one line.

    On a straight path the radius is ∞ even where the point stops and turns back, where the sampled
    radius ``|v|³/|v × a|`` is 0/0.
    """
    if len(p) < 3 or not extent > 0:
        return False
    # The core's least-squares line (linkage_core::straight_part): the whole path is one run.
    run = straightness(p, tol=1e-9 * extent)
    return run is not None and len(run.indices) == len(p)


def _smallest_radius(g: Sweep, s: Sweep) -> float:
    """Return the smallest radius of curvature over the run; ``inf`` for a straight path."""
    r = g.curvature_radius
    fin = np.isfinite(r) & (r >= 0)
    p = s.point[s.valid]
    extent = float(np.nanmax(np.ptp(p, axis=0))) if len(p) else 0.0
    if not fin.any() or _on_a_line(p, extent):
        return math.inf
    smallest = float(np.min(r[fin]))
    return math.inf if smallest > STRAIGHT_RADIUS * max(extent, 1e-300) else smallest


def geometry_figures(res: Result, g: Sweep, s: Sweep, others: list[Sweep]) -> None:
    """Append the curvature and instant-centre rows of geometry sweep ``g`` (trajectory ``s``).

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import geometry_figures
    >>> scene = Scene("leg", None, ("curvature", "instant_centres"), units="mm")
    >>> res = Result(scene, np.zeros(0), np.zeros(0))
    >>> res.check_samples = (37,)                      # the other resolution's sample count
    >>> hoecken, outs = linkage.catalog.hoecken(), ("point", "instant_centres", "curvature")
    >>> g, g2 = (hoecken.sweep(np.linspace(0, 2 * np.pi, n), outputs=outs) for n in (73, 37))
    >>> geometry_figures(res, g, hoecken.sweep(np.linspace(0, 2 * np.pi, 73)), [g2])
    >>> for row in res.figures:
    ...     print(*row[:3], sep=" | ")
    smallest radius of curvature | 0.503556 | mm
    instant centres at infinity (samples × pairs) | 1 |
    """
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
            f"3-point check {sci(float(np.max(np.linalg.norm(est[inner] - c[1:-1][inner], 1))))}"
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
                row(
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


def straightness_figures(
    res: Result, part: StraightPart | None, others: list[StraightPart | None], tol: float
) -> None:
    """Append the rows of the straightness stage: the longest straight part within ``tol``.

    ``others`` are the parts found at the check counts. ``part`` is ``None`` when there is none,
    and when ``tol`` is not a positive number (the trace has no extent; nothing was searched).

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.geometry import straightness
    >>> from linkage.stage_figures import straightness_figures
    >>> res = Result(Scene("leg", None, (), units="mm"), np.zeros(0), np.zeros(0))
    >>> res.check_samples = (361,)                      # the other resolution's sample count
    >>> hoecken = linkage.catalog.hoecken()
    >>> part, part2 = (straightness(hoecken.sweep(np.linspace(0, 2 * np.pi, n)).point, 0.025)
    ...                for n in (721, 361))
    >>> straightness_figures(res, part, [part2], 0.025)
    >>> for row in res.figures:
    ...     print(*row[:3], row.note.split(";")[0], sep=" | ")
    straight part within 0.1 % of size | 16.10 | mm | ±0.11 (vs 361 samples)
    straight part max deviation | 0.02454 | mm | ±7.8e-4 (vs 361 samples)

    A trace without extent (a tolerance of 0) is not searched:

    >>> res = Result(Scene("leg", None, (), units="mm"), np.zeros(0), np.zeros(0))
    >>> res.check_samples = (361,)                      # the other resolution's sample count
    >>> straightness_figures(res, None, [], 0.0)
    >>> [tuple(row) for row in res.figures]
    [('straight part within 0.1 % of size', 'none', '', 'no extent')]
    """
    u = length_unit(res.scene)
    name = "straight part within 0.1 % of size"
    if not (math.isfinite(tol) and tol > 0):
        res.figures.append(Row(name, "none", "", "no extent"))
        return
    if part is None:
        res.figures.append(Row(name, "none", "", f"tolerance {sci(tol)} {u}"))
        return
    ns = res.check_samples
    res.figures.append(
        row(
            name,
            part.length,
            u,
            [p.length if p else None for p in others],
            ns,
            f"tolerance {sci(tol)}",
        )
    )
    res.figures.append(
        row(
            "straight part max deviation",
            part.max_deviation,
            u,
            [p.max_deviation if p else None for p in others],
            ns,
            "from its least-squares line",
        )
    )
    if part.speed_variation is not None:
        if math.isfinite(part.speed_variation):
            alt = [p.speed_variation if p else None for p in others]
            res.figures.append(
                row(
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


def torque_figures(res: Result, f: Forces, others: list[Forces]) -> None:
    """Append the driver torque rows of the torque stage (``others`` at the check counts).

    The note gives how closely the power method's torque agrees with the joint forces'.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.forces import LinkMass, joint_forces
    >>> from linkage.stage_figures import torque_figures
    >>> res = Result(Scene("leg", None, (), units="m"), np.zeros(0), np.zeros(0))
    >>> res.check_samples = (37,)                      # the other resolution's sample count
    >>> leg = linkage.FourBar(ground=0.02, crank=0.01, coupler=0.025, rocker=0.025, point=(0.05, 0))
    >>> masses = {"crank": LinkMass(0.1, (0.005, 0.0), 1e-5),
    ...           "coupler": LinkMass(0.2, (0.0125, 0.0), 1e-4),
    ...           "rocker": LinkMass(0.2, (0.0125, 0.0), 1e-4)}
    >>> f, f2 = (joint_forces(leg, np.linspace(0, 2 * np.pi, n), omega=5.0, masses=masses)
    ...          for n in (73, 37))
    >>> torque_figures(res, f, [f2])
    >>> for row in res.figures:
    ...     print(row.figure, "|", round(row.value, 5), row.unit, "|", row.note.split(";")[0])
    driver torque mean |T| | 0.01579 N·m | ±7.8e-5 (vs 37 samples)
    driver torque peak |T| | 0.04062 N·m | ±0 (vs 37 samples)
    """
    res.arrays.update(torque=f.torque, power_torque=f.power_torque)
    check = float(np.nanmax(np.abs(f.torque - f.power_torque)))
    unit = torque_unit(res.scene)
    ns = res.check_samples
    note = f"power method agrees to {sci(check)}"
    mean = [g.mean_abs_torque for g in others]
    res.figures.append(row("driver torque mean |T|", f.mean_abs_torque, unit, mean, ns, note))
    peak = [g.peak_torque for g in others]
    res.figures.append(row("driver torque peak |T|", f.peak_torque, unit, peak, ns, note))


def _cam_values(p: CamProfile) -> tuple[float, float]:
    return math.degrees(p.max_pressure_angle), float(np.nanmin(np.abs(p.profile_radius)))


def cam_figures(
    res: Result, p: CamProfile, others: Sequence[CamProfile], ns: Sequence[int]
) -> None:
    r"""Append the rows of the cam stage: profile ``p``, ``others`` at the ``ns`` sample counts.

    Examples
    --------
    Thesis 2's leg-lift cam, then a cam whose base circle is too small for its rise:

    >>> import math
    >>> import numpy as np
    >>> from linkage.cam import DiscCam, leg_lift_cam
    >>> from linkage.drive import Program, Segment
    >>> from linkage.figures import Result, check_counts
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import cam_figures
    >>> ns = check_counts(181)
    >>> res = Result(Scene("cam", None, (), units="mm"), np.zeros(0), np.zeros(0))
    >>> cam = leg_lift_cam()
    >>> cam_figures(res, cam.profile(181), [cam.profile(k) for k in ns], ns)
    >>> for row in res.figures:
    ...     print(*row[:3], sep=" | ")
    cam max pressure angle | 8.6738 | deg
    cam profile's smallest radius of curvature | 5.71732 | mm
    cam check | ok |
    >>> up, down = Segment(math.pi / 2, 10.0, "cycloidal"), Segment(math.pi / 2, -10.0, "cycloidal")
    >>> small = DiscCam(Program(0.0, [up, down, Segment(math.pi)]), 5.0, roller_radius=2.0)
    >>> res.figures.clear()
    >>> cam_figures(res, small.profile(181), [small.profile(k) for k in ns], ns)
    >>> print(res.figures[-1].text.replace("; ", ";\n"))
    pressure angle 48.9° exceeds the limit 30.0° at cam angle 38.0°;
    enlarge the base circle or lengthen the rise
    """
    alt = [_cam_values(o) for o in others]
    res.arrays.update(cam_profile=p.profile, cam_pitch=p.pitch, cam_pressure_angle=p.pressure_angle)
    angle, radius = _cam_values(p)
    res.figures.append(row("cam max pressure angle", angle, "deg", [a[0] for a in alt], ns))
    name = "cam profile's smallest radius of curvature"
    unit = length_unit(res.scene)
    res.figures.append(row(name, radius, unit, [a[1] for a in alt], ns))
    res.figures.append(Row("cam check", "ok" if not p.problems else "; ".join(p.problems)))


def _walker_values(sim: Simulation, duration: float, period: float) -> dict[str, float]:
    """Return the sampled walker figures of one simulation (compared between two resolutions)."""
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


def walker_figures(
    res: Result,
    sim: Simulation,
    others: list[Simulation],
    walker: Walker,
    duration: float,
    period: float,
    closure: float,
) -> None:
    """Append the rows of the walker stage: the simulation ``sim``, ``others`` at the check counts.

    ``closure`` is the largest loop-closure residual of the legs' own kinematics over the run.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> from linkage.stage_figures import walker_figures
    >>> res = Result(Scene("leg", None, (), units="mm"), np.zeros(0), np.zeros(0))
    >>> res.check_samples = (37,)                      # the other resolution's sample count
    >>> quadruped = linkage.catalog.quadruped_hoecken()
    >>> sim, sim2 = (quadruped.simulate(np.linspace(0, 2 * np.pi, n), omega=2 * np.pi)
    ...              for n in (73, 37))
    >>> walker_figures(res, sim, [sim2], quadruped, 1.0, 1.0, 0.0)
    >>> for row in res.figures[:5]:
    ...     print(*row, sep=" | ")
    leg loop-closure residual | 0 | mm | 0 if exact
    legs | A, B, C, D |  |
    duty factor (per leg, mean) | 0.568 | of the cycle | ±0.013 (vs 37 samples)
    stride | 43.182 | mm | ±0 (vs 37 samples)
    lift height (obstacle a foot clears) | 8.98979 | mm | ±0 (vs 37 samples)
    """
    scene = res.scene
    res.arrays["closure"] = np.array([closure])
    res.figures.append(
        Row(
            "leg loop-closure residual",
            sci(closure),
            length_unit(scene),
            "0 if exact",
            value=closure,
            error=closure,
            exact=True,
        )
    )
    res.arrays.update(
        feet=sim.feet,
        stance=sim.stance.astype(float),
        body_position=sim.body_position,
        margin=sim.margin,
    )
    a = _walker_values(sim, duration, period)
    alt = [_walker_values(o, duration, period) for o in others]
    ns = res.check_samples

    def walker_row(figure: str, key: str, unit: str, note: str = "") -> Row:
        return row(figure, a[key], unit, [b[key] for b in alt], ns, note)

    rows = res.figures
    u = length_unit(scene)
    rows.append(Row("legs", ", ".join(sim.legs)))
    rows.append(walker_row("duty factor (per leg, mean)", "duty", "of the cycle"))
    rows.append(walker_row("stride", "stride", u))
    rows.append(walker_row("lift height (obstacle a foot clears)", "lift", u))
    rows.append(exact("body clearance", walker.body_underside - sim.ground, u))
    low = _lowest_pivot(walker, sim)
    if low is not None:
        # A leg's frame below the ground: a synthesized leg exported as drawn (its foot path
        # above its pivots) had put the body 40 mm underground with no word.
        note = "exact" if low >= 0 else "exact; below the ground: the leg's frame digs in"
        rows.append(exact("lowest leg pivot above the ground", low, u, note))
    rows.append(walker_row("body travel", "travel", u, "trapezoid"))
    rows.append(walker_row("mean body speed", "speed", f"{u}/s"))
    if scene.wants("stability"):
        rows.append(_margin_row(sim, u, [b["margin"] for b in alt], ns))
    if scene.wants("slip"):
        rows.append(walker_row("foot slip per cycle (all feet)", "slip", u, "trapezoid"))
        rows.append(walker_row("largest stance-speed spread", "spread", f"{u}/s"))
    if scene.wants("gait"):
        lo, hi = int(a["down_min"]), int(a["down_max"])
        e0 = spread(a["down_min"], [b["down_min"] for b in alt]) or 0.0
        e1 = spread(a["down_max"], [b["down_max"] for b in alt]) or 0.0
        rows.append(
            Row(
                "feet down (min / max)",
                f"{lo} / {hi}",
                "feet",
                f"±{format_error(max(e0, e1))} ({versus(ns)})",
                value=(lo, hi),
                error=max(e0, e1),
            )
        )


def _margin_row(sim: Simulation, units: str, others: list[float], ns: Sequence[int]) -> Row:
    """Make the row of the smallest stability margin.

    With no foot on the ground at some samples there is no support polygon and no margin, which the
    row says instead of printing −inf.
    """
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
    return row(
        "minimum stability margin",
        float(sim.margin[k]),
        units,
        [o if math.isfinite(o) else None for o in others],
        ns,
        f"at t = {format_number(float(sim.time[k]), digits=4)} s",
    )
