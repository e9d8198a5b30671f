"""The data of a run for other programs: ``summary.json`` (typed figures with units and error
estimates; schema in ``docs/summary-schema.md``), ``data.csv`` (one row per sample, units in
the headers), ``data.npz`` (every array) and the mechanism at one pose as ``mechanism.dxf``
(ezdxf; layers, units) and ``mechanism.svg`` — links, pivots, sliders and every traced path,
drawn from :mod:`linkage.drawing`, the model the plots and the HTML page draw too.

``write_data(res, folder)`` writes them all into ``folder`` (the report's folder, last, so that
the summary lists every file of the report).

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

import json
import math
import re
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import numpy as np
from numpy.typing import NDArray

from linkage import __version__
from linkage._core import LinkageError
from linkage.drawing import Drawing, leg_angles, mechanism_drawing, walker_drawing
from linkage.figures import Result, Row, length_unit, torque_unit

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

    >>> layer_name("PATH_trace P"), layer_name("LEG_L1")
    ('PATH_trace_P', 'LEG_L1')
    """
    return _LAYER_BAD.sub("_", name).strip("_") or "_"


# -- which pose, which drawing ----------------------------------------------------------------


def drawing_of(res: Result) -> Drawing | None:
    """The drawing model of the run: the mechanism over its sweep, or a walker seen in its legs'
    plane (from the side, or from above when most legs work in the horizontal plane); ``None``
    when the run has neither (it always has one after :func:`linkage.runner.run`)."""
    units = res.scene.units
    if res.simulation is not None and res.walker is not None:
        leg_theta = None
        if res.scene.drive.get("kind") == "schedule" and res.drive is not None:
            leg_theta = leg_angles(res.walker, res.simulation, res.drive, per_leg_time=True)
        # The view that shows the legs' linkages in their own plane: from the side for legs in
        # vertical planes, from above for legs in the horizontal plane (the hexapod's).
        flat = sum(leg.plane == "horizontal" for leg in res.walker.legs)
        view = "top" if 2 * flat > len(res.walker.legs) else "side"
        return walker_drawing(res.walker, res.simulation, view, leg_theta, units=units)
    if res.sweep is not None and res.mechanism is not None:
        return mechanism_drawing(res.mechanism, res.sweep, units=units)
    return None


def default_pose(d: Drawing) -> int:
    """The first sample at which every joint is placed.

    Raises
    ------
    LinkageError
        If no sample assembled.
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
    """The runs of consecutive finite points of ``path`` (N, 2), each of two points or more."""
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
    """``(layer, kind, points)`` of everything drawn at sample ``k``: kind ``"open"`` or
    ``"closed"`` (polylines), ``"circle"`` (points = [[cx, cy, r]])."""
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
    """The drawing to export (``drawing``, else built from ``res``) and the checked pose."""
    d = drawing or drawing_of(res)
    if d is None:
        raise LinkageError("nothing to draw: the run has no mechanism or walker")
    return d, _check_pose(d, pose)


def write_dxf(
    res: Result, path: Path, pose: int | None = None, drawing: Drawing | None = None
) -> int:
    """Write the mechanism at sample ``pose`` (default: the first assembled one) and every traced
    path as ``path`` (DXF R2010, ``$INSUNITS`` from the scene's units); returns the pose.

    Raises
    ------
    LinkageError
        If the run has nothing to draw or ``pose`` is not an assembled sample.
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
            msp.add_lwpolyline(
                [(float(x), float(y)) for x, y in pts], close=kind == "closed", dxfattribs=attribs
            )
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
    """The SVG of the mechanism at sample ``pose`` (default: the first assembled one) with every
    traced path, in the scene's coordinates (y up, by a flip of the whole drawing): each layer
    a ``<g id="layer-NAME" data-layer="NAME">``; returns the text and the pose.

    Raises
    ------
    LinkageError
        If the run has nothing to draw or ``pose`` is not an assembled sample.
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
    """The unit of ``res.arrays[key]`` (per element)."""
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
    """The per-sample columns of ``data.csv``, by header (``name [unit]``): time and crank
    angles, the trace point, every joint, rates, curvature, torque; a walker's feet (x, y, z per
    leg), stance flags and body travel. Arrays not sampled over the run's time (the cam's
    profile, over the cam angle) and the instant centres (many pairs; in the NPZ) are left
    out."""
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
    """Write ``data.csv`` (one row per sample, a header of ``name [unit]``); returns the
    headers."""
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
    """Write every array of the run into ``data.npz`` (compressed)."""
    arrays = {k: np.asarray(v) for k, v in res.arrays.items()}
    np.savez_compressed(path, **arrays)  # type: ignore[arg-type]


# -- summary.json -----------------------------------------------------------------------------


def _json_number(x: Any) -> Any:
    """A finite number as an int or float, anything not finite as ``None``."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    f = float(x)
    return f if math.isfinite(f) else None


def figure_json(row: Sequence[str]) -> dict[str, Any]:
    """One figure of the table as a JSON object (see ``docs/summary-schema.md``)."""
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


def summary(res: Result, files: Sequence[str], columns: Sequence[str], pose: int | None) -> Any:
    """The ``summary.json`` object of a run."""

    scene = res.scene
    pose_info = None
    if pose is not None:
        pose_info = {
            "sample": pose,
            "time_s": _json_number(res.time[pose]),
            "theta_rad": _json_number(res.theta[pose]),
        }
    return {
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


# -- all together -----------------------------------------------------------------------------


def write_cad(res: Result, folder: Path, pose: int | None = None) -> tuple[list[Path], int | None]:
    """Write ``mechanism.dxf`` and ``mechanism.svg`` at sample ``pose`` into ``folder``; returns
    the files and the pose drawn (no files and ``None`` for a run with nothing to draw)."""
    d = drawing_of(res)
    if d is None:
        return [], None
    dxf, svg = folder / "mechanism.dxf", folder / "mechanism.svg"
    k = write_dxf(res, dxf, pose, d)
    text, _ = svg_text(res, k, d)
    svg.write_text(text, encoding="utf-8")
    return [dxf, svg], k


def write_data(res: Result, folder: Path, pose: int | None = None, cad: bool = True) -> list[Path]:
    """Write the run's data into ``folder``: ``mechanism.dxf`` and ``mechanism.svg`` (with
    ``cad``), ``data.npz``, ``data.csv`` and, last, ``summary.json`` listing every file in the
    folder; returns the files written.

    Raises
    ------
    LinkageError
        If ``pose`` is not an assembled sample of the run.
    """
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
