"""A ``[synthesis]`` scene's candidates as files: ``candidates.csv`` and ``candidate-<k>.toml``.

Each candidate is a row of the table (units in the headers, :func:`candidate_rows`) and a
ready-to-run ``[mechanism]`` scene in the target's frame (:func:`candidate_scene`), driven at
:data:`CANDIDATE_RPM` over the crank range it turns through. :mod:`linkage.export` re-exports
these names.
"""

from __future__ import annotations

import csv
import json
import math
import textwrap
from collections.abc import Callable
from pathlib import Path
from typing import Any, Union, cast

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._core.synthesis import polyline_distance
from linkage._shared.arrays import choices, side_of
from linkage._shared.choices import Reach, Side
from linkage._shared.version import __version__
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.slider_crank import SliderCrank
from linkage.report.figures import Result, branch_word, length_unit
from linkage.synthesis import Candidate

__all__ = [
    "CANDIDATE_COLUMNS",
    "CANDIDATE_RPM",
    "SLIDER_COLUMNS",
    "branch_points",
    "candidate_columns",
    "candidate_drive",
    "candidate_rows",
    "candidate_scene",
    "candidate_side",
    "crank_limits",
    "write_candidates_csv",
]

Array = NDArray[np.float64]
Linkage = Union[FourBar, SliderCrank]


def _digits(size: float) -> int:
    """Return the decimals that keep a length to 1e-10 of ``size``.

    The search's own precision is 1e-10 of the size at best: the exported numbers stay readable
    (20.0, not 19.99999999999998).
    """
    return 10 - math.floor(math.log10(size)) if math.isfinite(size) and size > 0 else 12


def _num_toml(x: float, decimals: int) -> str:
    return repr(round(float(x), decimals) + 0.0)


def _mechanism_of(c: Candidate[Linkage], branch: str, phase: float) -> Mechanism:
    """Build the candidate from the joints of its exported scene: the crank at ``theta + phase``.

    ``branch`` is the dyad's side (a four-bar) or the slider's reach (a slider-crank).
    """
    return Mechanism.from_joints(_joint_tables(c.linkage, branch, phase), trace="P")


def _joint_tables(lk: Linkage, branch: str, phase: float) -> list[dict[str, Any]]:
    """Return the exported scene's joints of ``lk``.

    The one construction: the scene's text is written from these tables, and the side check
    builds from them.
    """
    o = {"name": "O", "kind": "fixed", "at": lk.o}
    crank = {"name": "A", "kind": "crank", "centre": "O", "radius": lk.crank}
    crank["phase_deg"] = math.degrees(phase)
    point = {"name": "P", "kind": "point", "on": ["A", "B"], "along": lk.point[0]}
    point["left"] = lk.point[1]
    if isinstance(lk, SliderCrank):
        g = {"name": "G", "kind": "fixed", "at": lk.line_point}
        b = {"name": "B", "kind": "slider", "pivot": "A", "r": lk.coupler, "origin": "G"}
        b.update(direction=[math.cos(lk.angle), math.sin(lk.angle)], reach=branch)
        return [o, g, crank, b, point]
    c = {"name": "C", "kind": "fixed", "at": lk.c}
    b = {"name": "B", "kind": "dyad", "p1": "A", "p2": "C", "r1": lk.coupler, "r2": lk.rocker}
    b["side"] = branch
    return [o, c, crank, b, point]


def _branch(lk: Linkage) -> Side | Reach:
    """Return the side of the dyad (a four-bar's assembly) or the reach of the slider."""
    return lk.reach if isinstance(lk, SliderCrank) else side_of(lk.assembly)


def _branches(lk: Linkage) -> tuple[str, ...]:
    return choices("reach") if isinstance(lk, SliderCrank) else choices("side")


_EXACT_KEYS = {"phase_deg": 12, "direction": 12}
"""Joint keys written to fixed decimals (an angle; a unit direction), not to the target's size."""


def _toml_table(j: dict[str, Any], num: Callable[[float], str]) -> str:
    """Write a joint table as an inline TOML table, lengths by ``num``."""

    def value(key: str, v: Any) -> str:
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(value(key, x) for x in v) + "]"
        return _num_toml(v, _EXACT_KEYS[key]) if key in _EXACT_KEYS else num(v)

    return "{ " + ", ".join(f"{k} = {value(k, v)}" for k, v in j.items()) + " }"


CANDIDATE_RPM = 60.0
"""Motor speed of an exported candidate scene: one crank turn per second."""


def crank_limits(c: Candidate[Linkage]) -> tuple[float, float]:
    """Return the limits (radians) of the crank interval that holds a candidate's crank range.

    The linkage's input interval (``input_ranges``) that contains the matched part, moved by
    whole turns next to it; a crank that turns fully has the crank range itself.

    Examples
    --------
    A four-bar whose crank rocks, on two intervals (its two circuits), as a candidate made by
    hand whose matched part takes the crank from 57.3° to 85.9°:

    >>> import math, numpy as np, linkage
    >>> from linkage.export import crank_limits
    >>> from linkage.synthesis import Candidate
    >>> fb = linkage.FourBar(ground=20, crank=25, coupler=25, rocker=10)
    >>> [[round(math.degrees(v), 3) for v in r] for r in fb.input_ranges()]
    [[36.87, 101.537], [-101.537, -36.87]]
    >>> part = Candidate(fb, 0.0, 0.0, 0.0, (1.0, 1.5), False, "rocker-crank",
    ...                  0.4, False, "by hand", np.zeros(6))
    >>> [round(math.degrees(v), 3) for v in crank_limits(part)]
    [36.87, 101.537]
    """
    lo, hi = c.crank_range
    if c.full_turn:
        return lo, hi
    mid = 0.5 * (lo + hi)
    best = (lo, hi)
    gap = math.inf
    for a, b in c.linkage.input_ranges():
        # Move the interval by whole turns so that it holds (or comes nearest) the middle.
        k = math.floor((mid - a) / (2 * math.pi))
        a2, b2 = a + 2 * math.pi * k, b + 2 * math.pi * k
        miss = max(a2 - lo, hi - b2, 0.0)
        if miss < gap:
            best, gap = (a2, b2), miss
    return best


def candidate_drive(c: Candidate[Linkage]) -> tuple[float, float]:
    """Return the exported scene's crank phase and run time.

    The crank starts at the beginning of the candidate's crank range (``phase`` in radians, the
    scene's ``phase_deg``) and turns at :data:`CANDIDATE_RPM` over that range: one turn, or from one
    limit to the other.

    Examples
    --------
    Hoecken's four-bar as a candidate (made here by hand; :func:`linkage.synthesis.path` finds
    them), turning fully, then rocking over one radian:

    >>> import math, numpy as np, linkage
    >>> from linkage.export import candidate_drive
    >>> from linkage.synthesis import Candidate
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> turns = Candidate(fb, 0.0, 0.0, 0.0, (0.0, 2 * math.pi), True, "crank-rocker",
    ...                   0.4, False, "by hand", np.zeros(6))
    >>> [round(v, 9) for v in candidate_drive(turns)]       # one turn at 60 rpm: 1 s
    [0.0, 1.0]
    >>> rocks = Candidate(fb, 0.0, 0.0, 0.0, (-0.5, 0.5), False, "crank-rocker",
    ...                   0.4, False, "by hand", np.zeros(6))
    >>> [round(v, 6) for v in candidate_drive(rocks)]       # 1 rad at 2π rad/s
    [-0.5, 0.159155]
    """
    lo, hi = c.crank_range
    omega = CANDIDATE_RPM * 2 * math.pi / 60
    span = 2 * math.pi if c.full_turn else hi - lo
    return lo, span / omega


def candidate_side(c: Candidate[Linkage], target: Array) -> Side | Reach:
    """Return the side of the exported scene's dyad (``B`` relative to ``A → C``), or its reach.

    The candidate's assembly (``open`` is ``left``), or a slider-crank's reach, except for a
    crank that rocks within its limits over a part of the curve traced on the other branch,
    where the other side (reach) draws the target.

    Examples
    --------
    An open Hoecken four-bar (made by hand) whose crank rocks over one radian: an arc traced by
    the open assembly is drawn on its side, one traced by the crossed assembly on the other:

    >>> import numpy as np, linkage
    >>> from linkage.export import candidate_side
    >>> from linkage.synthesis import Candidate
    >>> kw = dict(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> fb = linkage.FourBar(**kw)
    >>> rocks = Candidate(fb, 0.0, 0.0, 0.0, (-0.5, 0.5), False, "crank-rocker",
    ...                   0.4, False, "by hand", np.zeros(6))
    >>> theta = np.linspace(-0.5, 0.5, 9)
    >>> crossed = linkage.FourBar(**kw, assembly="crossed").sweep(theta).point
    >>> candidate_side(rocks, fb.sweep(theta).point), candidate_side(rocks, crossed)
    ('left', 'right')
    """
    return _drawing_branch(c, branch_points(c, target))


def _drawing_branch(c: Candidate[Linkage], counts: dict[str, int]) -> Side | Reach:
    """Return the branch that draws most target points (``counts``); a tie: the candidate's."""
    side = _branch(c.linkage)
    best = max(counts, key=lambda sd: (counts[sd], sd == side))
    return cast(Union[Side, Reach], best)


def branch_points(c: Candidate[Linkage], target: Array) -> dict[str, int]:
    """Count the target points each branch of the exported scene's drive draws.

    The branches are the dyad's sides (a four-bar) or the slider's reaches, each driven over the
    scene's crank range (:func:`candidate_drive`); a point counts for the branch whose curve
    passes nearer it. A crank that turns fully draws every point on its own branch.

    Examples
    --------
    Hoecken's four-bar rocked over one radian, as a candidate made by hand: five points of the
    open assembly's arc and four of the crossed one's:

    >>> import numpy as np, linkage
    >>> from linkage.export import branch_points
    >>> from linkage.synthesis import Candidate
    >>> kw = dict(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    >>> fb = linkage.FourBar(**kw)
    >>> rocks = Candidate(fb, 0.0, 0.0, 0.0, (-0.5, 0.5), False, "crank-rocker",
    ...                   0.4, False, "by hand", np.zeros(6))
    >>> crossed = linkage.FourBar(**kw, assembly="crossed")
    >>> target = np.vstack([fb.sweep(np.linspace(-0.5, 0.5, 5)).point,
    ...                     crossed.sweep(np.linspace(-0.4, 0.4, 4)).point])
    >>> branch_points(rocks, target)
    {'left': 5, 'right': 4}
    """
    side = _branch(c.linkage)
    pts = np.ascontiguousarray(np.asarray(target, dtype=np.float64).reshape(-1, 2))
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    if c.full_turn:
        return {sd: len(pts) if sd == side else 0 for sd in _branches(c.linkage)}
    phase, duration = candidate_drive(c)
    theta = np.linspace(0.0, duration * CANDIDATE_RPM * 2 * math.pi / 60, 721)
    gaps = []
    for sd in _branches(c.linkage):
        curve = _mechanism_of(c, sd, phase).sweep(theta, outputs=("point",)).point
        gaps.append(polyline_distance(pts, np.ascontiguousarray(curve, dtype=np.float64)))
    # Ties go to the candidate's own branch.
    own = _branches(c.linkage).index(side)
    nearer = np.argmin(gaps, axis=0) if len(pts) else np.zeros(0, dtype=int)
    nearer[gaps[0] == gaps[1]] = own
    return {sd: int(np.sum(nearer == i)) for i, sd in enumerate(_branches(c.linkage))}


def candidate_scene(res: Result, k: int) -> str:
    r"""Write candidate ``k`` (1 = best) of a ``[synthesis]`` run as a ``[mechanism]`` scene's text.

    The linkage as joints in the target's frame — a four-bar's ground pivots ``O``, ``C``, crank
    end ``A``, coupler–rocker joint ``B``, coupler point ``P`` traced; a slider-crank's crank
    pivot ``O``, the point ``G`` of the slider's line nearest ``O``, crank end ``A``, slider ``B``
    (a ``kind = "slider"`` joint on the line through ``G``) and ``P`` —, a constant drive over the
    crank range (one turn, or from limit to limit), its numbers kept to 1e-10 of the target's
    size, and comments with the candidate's figures. ``linkage check`` accepts it.

    Raises
    ------
    LinkageError
        If the run has no candidate ``k`` (or is not a ``[synthesis]`` run).

    Examples
    --------
    A ``[synthesis]`` run needs an atlas (see :func:`linkage.synthesis.path`); another has no
    candidates:

    >>> from linkage.export import candidate_scene
    >>> import numpy as np
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> res = Result(Scene("leg", None, ("trajectory",)), np.zeros(0), np.zeros(0))
    >>> candidate_scene(res, 1)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: no candidate 1 in this run
    """
    run = res.synthesis
    if run is None or not 1 <= k <= len(run.candidates):
        raise LinkageError(f"no candidate {k} in this run")
    c = run.candidates[k - 1]
    fb = c.linkage
    scene = res.scene
    u = length_unit(scene)
    nd = _digits(run.size)

    def num(x: float) -> str:
        return _num_toml(x, nd)

    suffix = f"-candidate-{k}"
    name = scene.name[: 64 - len(suffix)] + suffix
    phase, duration = candidate_drive(c)
    # The branch counts are two sweeps: once for the side and the comment.
    counts = branch_points(c, run.target)
    side = _drawing_branch(c, counts)
    lo, hi = (math.degrees(v) for v in c.crank_range)
    if c.full_turn:
        motion = "the crank turns fully: the scene drives one turn from the start of its range"
    else:
        a, b = (math.degrees(v) for v in crank_limits(c))
        motion = f"the crank rocks between its limits {a:.3f}° and {b:.3f}°"
        if abs(lo - a) + abs(hi - b) > 1e-9 * (1.0 + abs(a) + abs(b)):
            motion += f"; the matched part of the curve takes it from {lo:.3f}° to {hi:.3f}°"
        motion += (
            ", which the scene drives once; driven steadily, a crank's speed and acceleration "
            "grow without bound at its limits, so the scene asks for no rates"
        )
        if c.through_limit:
            key = "reach" if isinstance(fb, SliderCrank) else "side"
            other = next(b for b in counts if b != side)
            n = len(run.target)
            motion += (
                f' with {key} = "{side}"; the matched part passes a toggle at a limit and goes '
                f"on along the other branch: this scene draws {counts[side]} of the target's {n} "
                f'points, {key} = "{other}" draws the other {n - counts[side]}'
            )
    header = [
        f"Candidate {k} of the synthesis scene {scene.name!r} (linkage {__version__}).",
        f"Coupler point P passes within {c.error:.3g} {u} of the target's {len(run.target)} "
        f"points (RMS {c.rms:.3g} {u}).",
    ]
    if isinstance(fb, SliderCrank):
        dx, dy = math.cos(fb.angle), math.sin(fb.angle)
        header += [
            f"{c.grashof}, reach {fb.reach}; least transmission angle "
            f"{c.min_transmission_deg:.1f}° from a toggle (the rod square to the line).",
            f"Slider-crank: crank {fb.crank:.6g}, rod {fb.coupler:.6g} {u}, the line "
            f"{fb.offset:.6g} {u} left of O; P at ({fb.point[0]:.6g}, {fb.point[1]:.6g}) along "
            "and left of A → B.",
            f"Placed in the target's frame: O ({fb.o[0]:.6g}, {fb.o[1]:.6g}); the slider B runs "
            f"on the line through G ({fb.line_point[0]:.6g}, {fb.line_point[1]:.6g}) along "
            f"({dx:.6g}, {dy:.6g}), at {math.degrees(fb.angle):.6g}°.",
        ]
    else:
        header += [
            f"{c.grashof}, {fb.assembly} assembly; least transmission angle "
            f"{c.min_transmission_deg:.1f}° from a toggle.",
            f"Four-bar: ground {fb.ground:.6g}, crank {fb.crank:.6g}, coupler {fb.coupler:.6g}, "
            f"rocker {fb.rocker:.6g} {u}; P at ({fb.point[0]:.6g}, {fb.point[1]:.6g}) along and "
            "left of A → B.",
            f"Placed in the target's frame: O ({fb.o[0]:.6g}, {fb.o[1]:.6g}), "
            f"C ({fb.c[0]:.6g}, {fb.c[1]:.6g}).",
        ]
    header.append(motion[0].upper() + motion[1:] + ".")
    if side != _branch(fb) and not c.through_limit:
        where = "the slider is" if isinstance(fb, SliderCrank) else "B is on the"
        header.append(
            f"The target is drawn by the other {branch_word(fb)} over this range: {where} {side}."
        )
    header.append(f"Run it: linkage run candidate-{k}.toml")
    lines = [f"# {line}" for h in header for line in textwrap.wrap(h, 94)]
    description = (
        f"Candidate {k} of {scene.name}: max error {c.error:.3g} {u}, RMS {c.rms:.3g} {u}, "
        f"{c.grashof}"
    )
    lines += [
        f"name = {json.dumps(name)}",
        f"description = {json.dumps(description, ensure_ascii=False)}",
        f"units = {json.dumps(scene.units, ensure_ascii=False)}",
        (
            'outputs = ["trajectory", "velocity", "acceleration", "animation", "cad"]'
            if c.full_turn
            else 'outputs = ["trajectory", "animation", "cad"]'
        ),
        "",
        "[mechanism]",
        'trace = "P"',
        "joints = [",
        *(f"  {_toml_table(j, num)}," for j in _joint_tables(fb, side, phase)),
        "]",
        "# The synthesis target: the report draws it with P's path and gives its largest",
        "# distance from that path.",
        "reference = [",
        *(f"  [{num(float(x))}, {num(float(y))}]," for x, y in run.target),
        "]",
        "",
        "[drive]",
        'kind = "constant"',
        f"rpm = {CANDIDATE_RPM!r}",
        "cycles = 1" if c.full_turn else f"duration = {_num_toml(duration, 12)}",
        "samples = 721",
        "",
    ]
    return "\n".join(lines)


CANDIDATE_COLUMNS = (
    ("rank", ""),
    ("error", "L"),
    ("rms", "L"),
    ("back", "L"),
    ("grashof", ""),
    ("full_turn", ""),
    ("through_limit", ""),
    ("crank_from", "deg"),
    ("crank_to", "deg"),
    ("min_transmission", "deg"),
    ("pivot_O_x", "L"),
    ("pivot_O_y", "L"),
    ("pivot_C_x", "L"),
    ("pivot_C_y", "L"),
    ("ground", "L"),
    ("crank", "L"),
    ("coupler", "L"),
    ("rocker", "L"),
    ("point_along", "L"),
    ("point_left", "L"),
    ("assembly", ""),
    ("source", ""),
    ("scene", ""),
)
"""The columns of a four-bar search's ``candidates.csv`` and their units (``L``: the scene's length
unit)."""

SLIDER_COLUMNS = (
    ("line_angle", "deg"),
    ("offset", "L"),
    ("line_point_x", "L"),
    ("line_point_y", "L"),
    ("reach", ""),
)
"""A slider-crank's own columns: its line's direction, signed distance left of ``O`` and point
nearest ``O``, and the slider's reach (a slider-crank's row leaves the four-bar's own columns,
``pivot_C_*``, ``ground``, ``rocker`` and ``assembly``, empty)."""

_FOURBAR_ONLY = ("pivot_C_x", "pivot_C_y", "ground", "rocker", "assembly")


def candidate_columns(kind: str) -> tuple[tuple[str, str], ...]:
    """Return the columns of ``candidates.csv`` for a search of ``kind`` (the scene's ``kind``).

    A four-bar search has :data:`CANDIDATE_COLUMNS`; a slider-crank search the same without the
    four-bar's own columns, with :data:`SLIDER_COLUMNS` after the pivot; ``"any"`` has both and a
    ``linkage`` column after the rank.

    Examples
    --------
    >>> from linkage.export import candidate_columns
    >>> [name for name, _ in candidate_columns("slider-crank")][10:]
    ['pivot_O_x', 'pivot_O_y', 'line_angle', 'offset', 'line_point_x', 'line_point_y', 'crank',
     'coupler', 'point_along', 'point_left', 'reach', 'source', 'scene']
    >>> [name for name, _ in candidate_columns("any")][:3]
    ['rank', 'linkage', 'error']
    """
    cols = list(CANDIDATE_COLUMNS)
    if kind != "fourbar":
        names = [name for name, _ in cols]
        # The line after the pivots, the reach after the assembly.
        at, branch = names.index("pivot_C_x"), names.index("assembly")
        cols[branch + 1 : branch + 1] = SLIDER_COLUMNS[-1:]
        cols[at:at] = SLIDER_COLUMNS[:-1]
        cols.insert(1, ("linkage", ""))
        if kind == "slider-crank":
            cols = [col for col in cols if col[0] not in (*_FOURBAR_ONLY, "linkage")]
    return tuple(cols)


def _candidate_cells(c: Candidate[Linkage], k: int) -> dict[str, Any]:
    """Every column's value for candidate ``k`` (the columns of the other kind absent)."""
    lk = c.linkage
    lo, hi = (math.degrees(v) for v in c.crank_range)
    cells: dict[str, Any] = {
        "rank": k,
        "linkage": c.kind,
        "error": c.error,
        "rms": c.rms,
        "back": c.back,
        "grashof": c.grashof,
        "full_turn": str(c.full_turn).lower(),
        "through_limit": str(c.through_limit).lower(),
        "crank_from": lo,
        "crank_to": hi,
        "min_transmission": c.min_transmission_deg,
        "pivot_O_x": lk.o[0],
        "pivot_O_y": lk.o[1],
        "crank": lk.crank,
        "coupler": lk.coupler,
        "point_along": lk.point[0],
        "point_left": lk.point[1],
        "source": c.source,
        "scene": f"candidate-{k}.toml",
    }
    if isinstance(lk, SliderCrank):
        cells.update(
            line_angle=math.degrees(lk.angle),
            offset=lk.offset,
            line_point_x=lk.line_point[0],
            line_point_y=lk.line_point[1],
            reach=lk.reach,
        )
    else:
        cells.update(pivot_C_x=lk.c[0], pivot_C_y=lk.c[1], ground=lk.ground, rocker=lk.rocker)
        cells["assembly"] = lk.assembly
    return cells


def candidate_rows(res: Result) -> tuple[list[str], list[list[Any]]]:
    r"""Return the header (``name [unit]``) and one row per candidate of ``candidates.csv``.

    Raises
    ------
    LinkageError
        If ``res`` is not a ``[synthesis]`` run.

    Examples
    --------
    A ``[synthesis]`` run needs an atlas (see :func:`linkage.synthesis.path`); another is
    refused:

    >>> from linkage.export import candidate_rows
    >>> import numpy as np
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> res = Result(Scene("leg", None, ("trajectory",)), np.zeros(0), np.zeros(0))
    >>> candidate_rows(res)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: not a synthesis run
    """
    run = res.synthesis
    if run is None:
        raise LinkageError("not a synthesis run")
    u = length_unit(res.scene)
    columns = candidate_columns(str((res.scene.synthesis or {}).get("kind", "fourbar")))
    head = [f"{name} [{u if unit == 'L' else unit}]" if unit else name for name, unit in columns]
    rows = []
    for k, c in enumerate(run.candidates, 1):
        cells = _candidate_cells(c, k)
        rows.append([cells.get(name, "") for name, _ in columns])
    return head, rows


def write_candidates_csv(res: Result, path: Path) -> list[str]:
    r"""Write ``candidates.csv`` (full precision, units in the headers); returns the headers.

    Raises
    ------
    LinkageError
        If ``res`` is not a ``[synthesis]`` run (nothing is written).

    Examples
    --------
    A ``[synthesis]`` run needs an atlas (see :func:`linkage.synthesis.path`); another is
    refused before the file is opened:

    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.export import write_candidates_csv
    >>> import numpy as np
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> res = Result(Scene("leg", None, ("trajectory",)), np.zeros(0), np.zeros(0))
    >>> tmp = tempfile.TemporaryDirectory()
    >>> write_candidates_csv(res, Path(tmp.name) / "candidates.csv")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: not a synthesis run
    >>> (Path(tmp.name) / "candidates.csv").exists()
    False
    >>> tmp.cleanup()
    """
    head, rows = candidate_rows(res)
    with open(path, "w", encoding="utf-8", newline="") as fh:
        out = csv.writer(fh, lineterminator="\n")
        out.writerow(head)
        for row in rows:
            out.writerow([repr(float(v)) if isinstance(v, float) else v for v in row])
    return head
