"""The data of a run for other programs: JSON summary, CSV, NPZ, and the mechanism as DXF and SVG.

``summary.json`` holds typed figures with units and error estimates (schema in
``docs/summary-schema.md``), ``data.csv`` one row per sample (units in the headers),
``data.npz`` every array. For a scene that asks for the output ``cad``, ``mechanism.dxf``
(ezdxf, imported only then; layers, units) and ``mechanism.svg`` hold the mechanism at one pose —
links, pivots, sliders and every traced path, drawn from :mod:`linkage.drawing`, the model the
plots and the HTML page draw too.

``write_data(res, folder, cad=...)`` writes them into ``folder`` (the report's folder, last, so
that the summary lists every file of the report).

A ``[synthesis]`` scene's report has no samples over time: instead ``candidates.csv`` (one row
per candidate, units in the headers), ``candidate-<k>.toml`` (each candidate as a ready-to-run
``[mechanism]`` scene in the target's frame, see :func:`candidate_scene`), ``data.npz`` (the
target and every candidate's coupler curve) and ``summary.json`` (with a ``synthesis`` object);
``cad`` draws the best candidate with its coupler curve and the target (layer ``PATH_target``).

DXF/SVG layers (a path's or leg's name is kept, with characters a DXF layer name cannot hold
replaced by ``_``):

- ``LINKS`` — every moving link of a mechanism: a bar as an open polyline through its joints,
  a plate (three or more joints off one line) as a closed one; a walker's legs instead on
  ``LEG_<name>``, one layer per leg;
- ``JOINTS`` — a small circle at every moving joint; ``PIVOTS`` — a circle at every ground
  pivot; ``GROUND`` — the ground symbol under each pivot (a triangle and hatching), and a
  walker's ground line;
- ``SLIDERS`` — a slider's block and its guide; ``BODY`` — a walker's body outline;
- ``PATH_<label>`` — each traced path (the trace point, or each foot) as polylines, one per
  run of assembled samples, at every sample of the run.
"""

from __future__ import annotations

import csv
import json
import math
import re
import textwrap
from collections.abc import Callable, Iterator, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any, Union, cast
from xml.sax.saxutils import quoteattr

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError, polyline_distance
from linkage._shared.arrays import choices, side_of
from linkage._shared.choices import Reach, Side, View
from linkage._shared.version import __version__
from linkage.drawing import Drawing, leg_angles, mechanism_drawing, walker_drawing
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.mechanism import Mechanism
from linkage.kinematics.slider_crank import SliderCrank
from linkage.report.figures import Result, Row, branch_word, length_unit, torque_unit
from linkage.synthesis import Candidate

__all__ = [
    "CANDIDATE_COLUMNS",
    "CANDIDATE_RPM",
    "INSUNITS",
    "SCHEMA",
    "SLIDER_COLUMNS",
    "branch_points",
    "candidate_columns",
    "candidate_drive",
    "candidate_rows",
    "candidate_scene",
    "candidate_side",
    "crank_limits",
    "csv_columns",
    "default_pose",
    "drawing_of",
    "figure_json",
    "layer_name",
    "summary",
    "svg_text",
    "synthesis_drawing",
    "synthesis_pose",
    "write_cad",
    "write_candidates_csv",
    "write_csv",
    "write_data",
    "write_dxf",
    "write_npz",
    "write_synthesis",
]

Array = NDArray[np.float64]

SCHEMA = "linkage-summary/1"
"""The ``schema`` field of ``summary.json`` (bumped when a field changes meaning)."""

INSUNITS = {
    "": 0,
    "in": 1,
    "inch": 1,
    "ft": 2,
    "mi": 3,
    "mm": 4,
    "cm": 5,
    "m": 6,
    "km": 7,
    "µm": 13,
    "um": 13,
    "dm": 14,
}
"""DXF ``$INSUNITS`` codes of the unit labels a scene may give (0: unitless)."""

_SVG_UNITS = {"mm": 1.0, "cm": 1.0, "in": 1.0, "m": 1000.0}
"""Units an SVG width can carry (``m`` is written as mm × 1000)."""

_LAYER_BAD = re.compile(r"[<>/\\\":;?*|=`,\s]+")


def layer_name(name: str) -> str:
    """``name`` as a DXF layer name: characters DXF forbids replaced by ``_``.

    >>> from linkage.export import layer_name
    >>> layer_name("PATH_trace P"), layer_name("LEG_L1")
    ('PATH_trace_P', 'LEG_L1')
    """
    return _LAYER_BAD.sub("_", name).strip("_") or "_"


# -- which pose, which drawing ----------------------------------------------------------------


def drawing_of(res: Result) -> Drawing | None:
    """Return the drawing model of the run, or ``None`` when the run has nothing to draw.

    The mechanism over its sweep, or a walker seen in its legs' plane (from the side, or from above
    when most legs work in the horizontal plane); a run always has one after
    :func:`linkage.runner.run`.

    Examples
    --------
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> d = export.drawing_of(res)
    >>> d.leg_labels, d.frame(0).shape  # four legs of six joints (the foot last)
    (('L1', 'R1', 'L2', 'R2'), (24, 2))
    """
    units = res.scene.units
    if res.synthesis is not None:
        return synthesis_drawing(res)
    if res.simulation is not None and res.walker is not None:
        leg_theta = None
        if res.scene.drive.get("kind") == "schedule" and res.drive is not None:
            leg_theta = leg_angles(res.walker, res.simulation, res.drive, per_leg_time=True)
        # The view that shows the legs' linkages in their own plane: from the side for legs in
        # vertical planes, from above for legs in the horizontal plane (the hexapod's).
        flat = sum(leg.plane == "horizontal" for leg in res.walker.legs)
        view: View = "top" if 2 * flat > len(res.walker.legs) else "side"
        return walker_drawing(res.walker, res.simulation, view, leg_theta, units=units)
    if res.sweep is not None and res.mechanism is not None:
        return mechanism_drawing(res.mechanism, res.sweep, units=units)
    return None


def default_pose(d: Drawing) -> int:
    """Return the first sample at which every joint is placed.

    Raises
    ------
    LinkageError
        If no sample assembled.

    Examples
    --------
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> export.default_pose(export.drawing_of(res))
    0
    """
    ok = np.isfinite(d.positions).all(axis=(1, 2))
    if not ok.any():
        raise LinkageError("nothing to draw: no sample assembled")
    return int(np.argmax(ok))


def _check_pose(d: Drawing, pose: int | None) -> int:
    if pose is None:
        return default_pose(d)
    if isinstance(pose, bool) or not isinstance(pose, (int, np.integer)):
        raise TypeError(f"pose must be a sample index (int), got {type(pose).__name__}")
    n = len(d)
    if not -n <= int(pose) < n:
        raise LinkageError(f"pose {pose} is not a sample of this run (0 … {n - 1})")
    k = int(pose) % n
    if not np.isfinite(d.positions[k]).all():
        raise LinkageError(f"the mechanism does not assemble at sample {k}; choose another pose")
    return k


# -- shapes at one pose, shared by DXF and SVG ------------------------------------------------


def _runs(path: Array) -> Iterator[Array]:
    """Yield the runs of consecutive finite points of ``path`` (N, 2) of two points or more."""
    finite: NDArray[np.bool_] = np.asarray(np.isfinite(path).all(axis=1))
    ok = [bool(v) for v in finite]
    k = 0
    n = len(path)
    while k < n:
        if not ok[k]:
            k += 1
            continue
        j = k
        while j < n and ok[j]:
            j += 1
        if j - k >= 2:
            yield path[k:j]
        k = j


def _symbol_size(d: Drawing) -> float:
    x0, x1, y0, y1 = d.bounds(0.0)
    return 0.02 * max(x1 - x0, y1 - y0, 1e-300)


def _shapes(d: Drawing, k: int) -> Iterator[tuple[str, str, Array]]:
    """Yield ``(layer, kind, points)`` of everything drawn at sample ``k``.

    Kind ``"open"`` or ``"closed"`` (polylines), ``"circle"`` (points = [[cx, cy, r]]).
    """
    p = d.positions[k]
    size = _symbol_size(d)
    legs = d.legs
    pivots = set(d.pivots)
    for link in d.links:
        if link.kind == "ground":
            continue
        layer = "LINKS" if link.leg is None else layer_name(f"LEG_{legs[link.leg]}")
        kind = "closed" if link.kind == "plate" else "open"
        yield layer, kind, p[list(link.joints)]
    moving = {j for link in d.links if link.kind != "ground" for j in link.joints}
    for j in sorted(moving - pivots):
        yield "JOINTS", "circle", np.array([[p[j, 0], p[j, 1], 0.5 * size]])
    for j in d.pivots:
        x, y = p[j]
        yield "PIVOTS", "circle", np.array([[x, y, 0.8 * size]])
        h = 2.5 * size
        tri = np.array([[x, y], [x - h, y - 1.5 * h], [x + h, y - 1.5 * h]])
        yield "GROUND", "closed", tri
        for t in np.linspace(-1.0, 1.0, 5):
            a = np.array([x + t * h, y - 1.5 * h])
            yield "GROUND", "open", np.array([a, a + np.array([-0.6 * h, -0.6 * h])])
    for sl in d.sliders:
        c = p[sl.joint]
        u = sl.direction[k]
        if not np.isfinite(u).all():
            continue
        n = np.array([-u[1], u[0]])
        w, h = 2.0 * size, 1.2 * size
        block = np.array(
            [c - w * u - h * n, c + w * u - h * n, c + w * u + h * n, c - w * u + h * n]
        )
        yield "SLIDERS", "closed", block
        o = p[sl.origin]
        reach = float(np.linalg.norm(c - o)) + 4 * w
        yield "SLIDERS", "open", np.array([o - 0.2 * reach * u, o + reach * u])
    if d.body is not None:
        yield "BODY", "closed", d.body[:-1] if len(d.body) > 1 else d.body
    if d.ground is not None:
        x0, x1, _, _ = d.bounds()
        yield "GROUND", "open", np.array([[x0, d.ground], [x1, d.ground]])
    for label, path in d.paths.items():
        for run in _runs(np.asarray(path, dtype=float)):
            yield layer_name(f"PATH_{label}"), "open", run


# -- DXF --------------------------------------------------------------------------------------

_COLOURS = {"LINKS": 7, "JOINTS": 7, "PIVOTS": 1, "GROUND": 8, "SLIDERS": 5, "BODY": 8}
_DXF_PATH_COLOURS = (5, 3, 6, 4, 30, 140, 210, 94, 172, 12, 52, 232)
"""ACI colours of the path and leg layers: distinct, none yellow (unreadable on white)."""


def _drawn(res: Result, pose: int | None, drawing: Drawing | None) -> tuple[Drawing, int]:
    """Return the drawing to export (``drawing``, else built from ``res``) and the checked pose."""
    d = drawing or drawing_of(res)
    if d is None:
        raise LinkageError("nothing to draw: the run has no mechanism or walker")
    return d, _check_pose(d, pose)


def write_dxf(
    res: Result, path: Path, pose: int | None = None, drawing: Drawing | None = None
) -> int:
    r"""Write the mechanism at sample ``pose`` and every traced path as ``path``; return the pose.

    ``pose`` defaults to the first assembled sample; the file is DXF R2010, with ``$INSUNITS`` from
    the scene's units.

    Raises
    ------
    LinkageError
        If the run has nothing to draw or ``pose`` is not an assembled sample.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.export import write_dxf
    >>> from linkage.runner import run
    >>> from linkage.scene import parse
    >>> scene = parse('units = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...               '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n')
    >>> res = run(scene)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_dxf(res, Path(tmp) / "hoecken.dxf"), write_dxf(res, Path(tmp) / "at.dxf", pose=9)
    (0, 9)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_dxf(res, Path(tmp) / "bad.dxf", pose=73)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: pose 73 is not a sample of this run (0 … 72)
    """
    from ezdxf.filemanagement import new as new_dxf  # noqa: PLC0415 (ezdxf only for the cad output)

    d, k = _drawn(res, pose, drawing)
    doc = new_dxf("R2010")
    doc.header["$INSUNITS"] = INSUNITS.get(res.scene.units.strip(), 0)
    doc.header["$MEASUREMENT"] = 0 if res.scene.units in ("in", "inch", "ft", "mi") else 1
    msp = doc.modelspace()
    made: set[str] = set()
    for layer, kind, pts in _shapes(d, k):
        if layer not in made:
            c = _COLOURS.get(layer, _DXF_PATH_COLOURS[len(made) % len(_DXF_PATH_COLOURS)])
            doc.layers.add(layer, color=c)
            made.add(layer)
        attribs = {"layer": layer}
        if kind == "circle":
            cx, cy, r = (float(v) for v in pts[0])
            msp.add_circle((cx, cy), r, dxfattribs=attribs)
        else:
            # All vertices in one array: ezdxf's add_lwpolyline appends them one at a time, each
            # append copying those before it (200,000 samples took a minute, now 0.3 s).
            polyline = msp.add_lwpolyline([], close=kind == "closed", dxfattribs=attribs)
            vertices = np.zeros((len(pts), 5))  # x, y, start width, end width, bulge
            vertices[:, :2] = np.asarray(pts, dtype=np.float64)[:, :2]
            polyline.lwpoints.extend(vertices)
    doc.saveas(path)
    return k


# -- SVG --------------------------------------------------------------------------------------

_SVG_STYLE = {
    "LINKS": 'stroke="#222" stroke-width="2.2" fill="#9ab" fill-opacity="0.35"',
    "JOINTS": 'stroke="#222" stroke-width="1" fill="#fff"',
    "PIVOTS": 'stroke="#222" stroke-width="1.2" fill="#fff"',
    "GROUND": 'stroke="#555" stroke-width="1" fill="none"',
    "SLIDERS": 'stroke="#225" stroke-width="1.2" fill="#dde"',
    "BODY": 'stroke="#444" stroke-width="1.5" fill="#ccc" fill-opacity="0.4"',
}
_PATH_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf")


def _num(x: float) -> str:
    return f"{x:.10g}"


def svg_text(
    res: Result, pose: int | None = None, drawing: Drawing | None = None
) -> tuple[str, int]:
    """Draw the mechanism at sample ``pose`` with every traced path as SVG; return text and pose.

    ``pose`` defaults to the first assembled sample. The drawing is in the scene's coordinates (y
    up, by a flip of the whole drawing), each layer a ``<g id="layer-NAME" data-layer="NAME">``.

    Raises
    ------
    LinkageError
        If the run has nothing to draw or ``pose`` is not an assembled sample.

    Examples
    --------
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> svg, pose = export.svg_text(res)
    >>> pose, svg.count("<polyline") > 0, svg.rstrip().endswith("</svg>")
    (0, True, True)
    >>> export.svg_text(res, pose=99)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: pose 99 is not a sample of this run (0 … 36)
    """
    d, k = _drawn(res, pose, drawing)
    x0, x1, y0, y1 = d.bounds()
    w, h = x1 - x0, y1 - y0
    unit = res.scene.units.strip()
    if unit in _SVG_UNITS:
        f = _SVG_UNITS[unit]
        size = f'width="{_num(w * f)}{"mm" if unit == "m" else unit}" '
        size += f'height="{_num(h * f)}{"mm" if unit == "m" else unit}"'
    else:
        size = f'width="800" height="{_num(800 * h / w)}"'
    layers: dict[str, list[str]] = {}
    for layer, kind, pts in _shapes(d, k):
        if kind == "circle":
            cx, cy, r = pts[0]
            el = f'<circle cx="{_num(cx)}" cy="{_num(cy)}" r="{_num(r)}"/>'
        else:
            tag = "polygon" if kind == "closed" else "polyline"
            coords = " ".join(f"{_num(x)},{_num(y)}" for x, y in pts)
            el = f'<{tag} points="{coords}"/>'
        layers.setdefault(layer, []).append(el)
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" {size} '
        f'viewBox="{_num(x0)} {_num(-y1)} {_num(w)} {_num(h)}">',
        f"<title>{_escape(res.scene.name)} at sample {k} ({length_unit(res.scene)})</title>",
        '<g transform="scale(1,-1)">',
    ]
    colour = 0
    for layer, els in layers.items():
        if layer in _SVG_STYLE:
            style = _SVG_STYLE[layer]
        else:
            style = f'stroke="{_PATH_COLOURS[colour % len(_PATH_COLOURS)]}" stroke-width="1.2"'
            style += ' fill="none"'
            colour += 1
        out.append(
            f"<g id={quoteattr('layer-' + layer)} data-layer={quoteattr(layer)} {style} "
            'vector-effect="non-scaling-stroke" stroke-linejoin="round">'
        )
        out.extend(e.replace("/>", ' vector-effect="non-scaling-stroke"/>') for e in els)
        out.append("</g>")
    out += ["</g>", "</svg>", ""]
    return "\n".join(out), k


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


# -- CSV, NPZ ---------------------------------------------------------------------------------


def _array_unit(res: Result, key: str) -> str:
    """Return the unit of ``res.arrays[key]`` (per element)."""
    u = length_unit(res.scene)
    walker = res.simulation is not None
    return {
        "time": "s",
        "theta": "rad",
        "omega": "rad/s",
        "alpha": "rad/s²",
        "point": u,
        "joints": u,
        "valid": "1 = assembled",
        "margin": u if walker else "sine of the dyad angle",
        "velocity": f"{u}/s",
        "acceleration": f"{u}/s²",
        "curvature_centre": u,
        "curvature": f"1/{u}" if res.scene.units else "1/length unit",
        "instant_centres": u,
        "instant_centre_directions": "1",
        "torque": torque_unit(res.scene),
        "power_torque": torque_unit(res.scene),
        "feet": u,
        "stance": "1 = down",
        "body_position": u,
        "closure": u,
        "cam_profile": u,
        "cam_pitch": u,
        "cam_pressure_angle": "rad",
    }.get(key, "")


_CSV_NAMES = {"point": "trace"}
"""Column stems that differ from the array names (the trace point is ``trace_x``…)."""


def csv_columns(res: Result) -> dict[str, Array]:
    """Return the per-sample columns of ``data.csv``, by header (``name [unit]``).

    Time and crank angles, the trace point, every joint, rates, curvature, torque; a walker's feet
    (x, y, z per leg), stance flags and body travel. Arrays not sampled over the run's time (the
    cam's profile, over the cam angle) and the instant centres (many pairs; in the NPZ) are left
    out.

    Examples
    --------
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> cols = export.csv_columns(res)
    >>> list(cols)[:6]
    ['time [s]', 'theta [rad]', 'omega [rad/s]', 'alpha [rad/s²]', 'foot_A_x [mm]', 'foot_A_y [mm]']
    >>> cols["stance_A [1 = down]"][:8]
    array([0., 0., 0., 0., 1., 1., 1., 1.])
    """
    n = len(res.time)
    cols: dict[str, Array] = {}
    names = list(res.sweep.joint_names) if res.sweep is not None else []
    legs = list(res.simulation.legs) if res.simulation is not None else []

    def head(stem: str, key: str) -> str:
        unit = _array_unit(res, key)
        return f"{stem} [{unit}]" if unit else stem

    for key, raw in res.arrays.items():
        if key.startswith("cam_") or key.startswith("instant_centre") or key == "closure":
            continue
        v = np.asarray(raw, dtype=float)
        if v.shape[:1] != (n,):
            continue
        stem = _CSV_NAMES.get(key, key)
        if key == "margin":
            stem = "stability_margin" if res.simulation is not None else "dyad_margin"
        if v.ndim == 1:
            cols[head(stem, key)] = v
        elif v.ndim == 2 and v.shape[1] == 2 and key != "stance":
            cols[head(f"{stem}_x", key)] = v[:, 0]
            cols[head(f"{stem}_y", key)] = v[:, 1]
        elif v.ndim == 2:
            labels = legs if key == "stance" and len(legs) == v.shape[1] else None
            for i in range(v.shape[1]):
                cols[head(f"{stem}_{labels[i] if labels else i}", key)] = v[:, i]
        elif v.ndim == 3 and v.shape[2] in (2, 3):
            labels = (names if key == "joints" else legs if key == "feet" else []) or [
                str(i) for i in range(v.shape[1])
            ]
            stem = "foot" if key == "feet" else "joint" if key == "joints" else stem
            for i in range(v.shape[1]):
                for c, axis in enumerate("xyz"[: v.shape[2]]):
                    cols[head(f"{stem}_{labels[i]}_{axis}", key)] = v[:, i, c]
    return cols


def write_csv(res: Result, path: Path) -> list[str]:
    """Write ``data.csv`` (one row per sample, a header of ``name [unit]``); return the headers.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     headers = export.write_csv(res, Path(tmp) / "data.csv")
    >>> headers[:3]
    ['time [s]', 'theta [rad]', 'omega [rad/s]']
    """
    cols = csv_columns(res)
    for h in cols:
        if "," in h or '"' in h:  # pragma: no cover - names come from joints and legs
            raise LinkageError(f"column {h!r} cannot be a CSV header")
    header = ",".join(cols)
    np.savetxt(
        path,
        np.column_stack(list(cols.values())) if cols else np.empty((0, 0)),
        delimiter=",",
        header=header,
        comments="",
        fmt="%.17g",
    )
    return list(cols)


def write_npz(res: Result, path: Path) -> None:
    """Write every array of the run into ``data.npz`` (compressed).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     export.write_npz(res, Path(tmp) / "data.npz")
    ...     print(sorted(np.load(Path(tmp) / "data.npz").files))
    ['alpha', 'body_position', 'closure', 'feet', 'margin', 'omega', 'stance', 'theta', 'time']
    """
    arrays = {k: np.asarray(v) for k, v in res.arrays.items()}
    np.savez_compressed(path, **arrays)  # type: ignore[arg-type]


# -- summary.json -----------------------------------------------------------------------------


def _json_number(x: Any) -> Any:
    """Return a finite number as an int or float, anything not finite as ``None``."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    f = float(x)
    return f if math.isfinite(f) else None


def figure_json(row: Sequence[str]) -> dict[str, Any]:
    """One figure of the table as a JSON object (see ``docs/summary-schema.md``).

    Examples
    --------
    >>> from linkage import export, figures
    >>> export.figure_json(figures.exact("crank", 10.0, "mm"))
    {'figure': 'crank', 'value': 10.0, 'text': '10', 'unit': 'mm', 'error': 0.0,
     'error_note': 'exact', 'exact': True}
    >>> export.figure_json(["note", "n/a", "", ""])  # a plain row: its text only
    {'figure': 'note', 'value': 'n/a', 'text': 'n/a', 'unit': '', 'error': None,
     'error_note': '', 'exact': False}
    """
    figure, text, unit, note = row
    if isinstance(row, Row):
        value: Any = row.value
        error = row.error
        exact = row.exact
    else:  # a plain 4-tuple: only its text is known
        value, error, exact = text or None, None, False
    if isinstance(value, tuple):
        value = [_json_number(v) for v in value]
    elif value is not None and not isinstance(value, str):
        value = _json_number(value)
    return {
        "figure": figure,
        "value": value,
        "text": text,
        "unit": unit,
        "error": None if error is None else _json_number(error),
        "error_note": note,
        "exact": exact,
    }


def summary(
    res: Result, files: Sequence[str], columns: Sequence[str], pose: int | None
) -> dict[str, Any]:
    """Return the ``summary.json`` object of a run.

    Examples
    --------
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> s = export.summary(res, ["data.csv"], list(export.csv_columns(res)), 0)
    >>> s["schema"], s["scene"], s["samples"], s["check_samples"]
    ('linkage-summary/1', 'quadruped-hoecken', 37, [18, 73])
    >>> s["pose"]
    {'sample': 0, 'time_s': 0.0, 'theta_rad': 0.0}
    """
    scene = res.scene
    pose_info = None
    run = res.synthesis
    if pose is not None and run is not None:
        pose_info = {
            "sample": pose,
            "time_s": None,
            "theta_rad": _json_number(run.best.theta[pose]),
        }
    elif pose is not None:
        pose_info = {
            "sample": pose,
            "time_s": _json_number(res.time[pose]),
            "theta_rad": _json_number(res.theta[pose]),
        }
    out = {
        "schema": SCHEMA,
        "tool": "linkage",
        "version": str(__version__),
        "scene": scene.name,
        "description": scene.description,
        "units": scene.units,
        "length_unit": length_unit(scene),
        "outputs": list(scene.outputs),
        "samples": len(res.time),
        "check_samples": list(res.check_samples),
        "figures": [figure_json(r) for r in res.figures],
        "stages_s": {k: _json_number(v) for k, v in res.stages.items()},
        "pose": pose_info,
        "csv_columns": list(columns),
        "files": sorted(files),
    }
    if run is not None:
        out["samples"] = len(run.best.theta)
        out["synthesis"] = _synthesis_json(res)
    return out


# -- all together -----------------------------------------------------------------------------


def write_cad(res: Result, folder: Path, pose: int | None = None) -> tuple[list[Path], int | None]:
    r"""Write ``mechanism.dxf`` and ``mechanism.svg`` at sample ``pose`` into ``folder``.

    Returns the files and the pose drawn (no files and ``None`` for a run with nothing to draw).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.export import write_cad
    >>> from linkage.runner import run
    >>> from linkage.scene import parse
    >>> scene = parse('units = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...               '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n')
    >>> res = run(scene)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     files, pose = write_cad(res, Path(tmp), pose=12)
    ...     [f.name for f in files], pose, "<svg" in files[1].read_text(encoding="utf-8")
    (['mechanism.dxf', 'mechanism.svg'], 12, True)
    """
    d = drawing_of(res)
    if d is None:
        return [], None
    dxf, svg = folder / "mechanism.dxf", folder / "mechanism.svg"
    k = write_dxf(res, dxf, pose, d)
    text, _ = svg_text(res, k, d)
    svg.write_text(text, encoding="utf-8")
    return [dxf, svg], k


# -- synthesis scenes ------------------------------------------------------------------------


def synthesis_drawing(res: Result) -> Drawing:
    r"""Draw the best candidate of a ``[synthesis]`` run over its circuit.

    Its coupler curve (``trace P``) and the target (``target``, closed when the target is) are its
    paths.

    Raises
    ------
    LinkageError
        If ``res`` is not a ``[synthesis]`` run.

    Examples
    --------
    A ``[synthesis]`` run needs an atlas (see :func:`linkage.synthesis.path`); another is
    refused:

    >>> from linkage.export import synthesis_drawing
    >>> import numpy as np
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> res = Result(Scene("leg", None, ("trajectory",)), np.zeros(0), np.zeros(0))
    >>> synthesis_drawing(res)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: not a synthesis run
    """
    run = res.synthesis
    if run is None:
        raise LinkageError("not a synthesis run")
    best = run.candidates[0].linkage
    mech = best.mechanism() if isinstance(best, SliderCrank) else best
    d = mechanism_drawing(mech, run.best, res.scene.units)
    target = np.asarray(run.target, dtype=float)
    if run.closed and len(target):
        target = np.vstack([target, target[:1]])
    return replace(d, paths={**d.paths, "target": target})


def synthesis_pose(d: Drawing) -> int:
    """Return the sample a synthesis report draws the best candidate at.

    A sixth of its circuit in (a crank along the ground line at the start hides it), or the first
    assembled one.

    Examples
    --------
    >>> import numpy as np, linkage
    >>> from linkage.drawing import mechanism_drawing
    >>> from linkage.export import synthesis_pose
    >>> theta = np.linspace(0, 2 * np.pi, 13)
    >>> fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25)
    >>> synthesis_pose(mechanism_drawing(fb, fb.sweep(theta)))      # 13 // 6
    2

    A four-bar that assembles only with its crank along the ground (coupler and rocker of 5
    just reach across the ground of 20 from the crank end at 10) is drawn there:

    >>> flat = linkage.FourBar(ground=20, crank=10, coupler=5, rocker=5)
    >>> d = mechanism_drawing(flat, flat.sweep(theta))
    >>> np.isfinite(d.positions).all(axis=(1, 2)).nonzero()[0].tolist(), synthesis_pose(d)
    ([0, 12], 0)
    """
    ok = np.asarray(np.isfinite(d.positions).all(axis=(1, 2)), dtype=bool)
    k = ok.shape[0] // 6
    return k if bool(ok[k]) else default_pose(d)


def _digits(size: float) -> int:
    """Return the decimals that keep a length to 1e-10 of ``size``.

    The search's own precision is 1e-10 of the size at best: the exported numbers stay readable
    (20.0, not 19.99999999999998).
    """
    return 10 - math.floor(math.log10(size)) if math.isfinite(size) and size > 0 else 12


def _num_toml(x: float, decimals: int) -> str:
    return repr(round(float(x), decimals) + 0.0)


Linkage = Union[FourBar, SliderCrank]


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


def _synthesis_json(res: Result) -> dict[str, Any]:
    run = res.synthesis
    assert run is not None
    s = res.scene.synthesis or {}
    points = s.get("points")
    cands = []
    for k, c in enumerate(run.candidates, 1):
        lk = c.linkage
        entry: dict[str, Any] = {
            "rank": k,
            "linkage": c.kind,
            "error": _json_number(c.error),
            "rms": _json_number(c.rms),
            "back": _json_number(c.back),
            "grashof": c.grashof,
            "full_turn": bool(c.full_turn),
            "through_limit": bool(c.through_limit),
            "crank_range_deg": [_json_number(math.degrees(v)) for v in c.crank_range],
            "min_transmission_deg": _json_number(c.min_transmission_deg),
            "o": [_json_number(v) for v in lk.o],
        }
        if isinstance(lk, SliderCrank):
            entry.update(
                line_angle_deg=_json_number(math.degrees(lk.angle)),
                offset=_json_number(lk.offset),
                line_point=[_json_number(v) for v in lk.line_point],
                crank=_json_number(lk.crank),
                coupler=_json_number(lk.coupler),
                point=[_json_number(v) for v in lk.point],
                reach=lk.reach,
            )
        else:
            entry.update(
                c=[_json_number(v) for v in lk.c],
                ground=_json_number(lk.ground),
                crank=_json_number(lk.crank),
                coupler=_json_number(lk.coupler),
                rocker=_json_number(lk.rocker),
                point=[_json_number(v) for v in lk.point],
                assembly=lk.assembly,
            )
        entry.update(source=c.source, scene=f"candidate-{k}.toml")
        cands.append(entry)
    return {
        "kind": str(s.get("kind", "fourbar")),
        "target": {
            "points": len(run.target),
            "closed": run.closed,
            "size": _json_number(run.size),
            "file": points if isinstance(points, str) else None,
        },
        "constraints": {
            "full_turn": bool(s.get("full_turn", False)),
            "min_transmission_deg": _json_number(s.get("min_transmission_deg", 0.0)),
            "lengths": [_json_number(v) for v in s["lengths"]] if "lengths" in s else None,
            "pivots": (
                [[_json_number(v) for v in corner] for corner in s["pivots"]]
                if "pivots" in s
                else None
            ),
        },
        "candidates": cands,
    }


def write_synthesis(res: Result, folder: Path, cad: bool = True) -> list[Path]:
    r"""Write a ``[synthesis]`` run's files into ``folder``; return the files written.

    ``candidate-<k>.toml`` for every candidate, ``candidates.csv``, ``mechanism.dxf`` and
    ``mechanism.svg`` of the best (with ``cad``), ``data.npz`` and, last, ``summary.json``.

    Raises
    ------
    LinkageError
        If ``res`` is not a ``[synthesis]`` run (nothing is written).

    Examples
    --------
    A ``[synthesis]`` run needs an atlas (see :func:`linkage.synthesis.path`); another is
    refused:

    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.export import write_synthesis
    >>> import numpy as np
    >>> from linkage.figures import Result
    >>> from linkage.scene import Scene
    >>> res = Result(Scene("leg", None, ("trajectory",)), np.zeros(0), np.zeros(0))
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_synthesis(res, Path(tmp))
    Traceback (most recent call last):
    ...
    linkage.LinkageError: not a synthesis run
    """
    folder = Path(folder)
    run = res.synthesis
    if run is None:
        raise LinkageError("not a synthesis run")
    written: list[Path] = []
    for k in range(1, len(run.candidates) + 1):
        path = folder / f"candidate-{k}.toml"
        path.write_text(candidate_scene(res, k), encoding="utf-8")
        written.append(path)
    table = folder / "candidates.csv"
    columns = write_candidates_csv(res, table)
    written.append(table)
    drawn = None
    if cad:
        d = synthesis_drawing(res)
        files, drawn = write_cad(res, folder, synthesis_pose(d))
        written += files
    npz, js = folder / "data.npz", folder / "summary.json"
    write_npz(res, npz)
    written.append(npz)
    names = {p.name for p in folder.iterdir() if not p.name.startswith(".")} | {js.name}
    js.write_text(
        json.dumps(summary(res, sorted(names), columns, drawn), indent=2, allow_nan=False) + "\n",
        encoding="utf-8",
    )
    written.append(js)
    return written


def write_data(res: Result, folder: Path, pose: int | None = None, cad: bool = True) -> list[Path]:
    """Write the run's data into ``folder``; return the files written.

    ``mechanism.dxf`` and ``mechanism.svg`` (with ``cad``), ``data.npz``, ``data.csv`` and, last,
    ``summary.json`` listing every file in the folder.

    Raises
    ------
    LinkageError
        If ``pose`` is not an assembled sample of the run.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage import export, runner, scene
    >>> res = runner.run(scene.parse(scene.DEFAULT_SCENE), samples=37)  # the quadruped
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     print([f.name for f in export.write_data(res, Path(tmp), cad=False)])
    ['data.npz', 'data.csv', 'summary.json']
    """
    if res.synthesis is not None:
        return write_synthesis(res, folder, cad)
    folder = Path(folder)
    written: list[Path] = []
    drawn = None
    if cad:
        files, drawn = write_cad(res, folder, pose)
        written += files
    npz, csv, js = folder / "data.npz", folder / "data.csv", folder / "summary.json"
    write_npz(res, npz)
    columns = write_csv(res, csv)
    written += [npz, csv]
    names = {p.name for p in folder.iterdir() if not p.name.startswith(".")} | {js.name}
    js.write_text(
        json.dumps(summary(res, sorted(names), columns, drawn), indent=2, allow_nan=False) + "\n",
        encoding="utf-8",
    )
    written.append(js)
    return written
