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

The DXF/SVG drawing is :mod:`linkage.report.cad`, a synthesis's candidate files
:mod:`linkage.report.candidates`; this module re-exports their names.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.version import __version__
from linkage.kinematics.slider_crank import SliderCrank
from linkage.report.cad import (
    INSUNITS,
    default_pose,
    drawing_of,
    layer_name,
    svg_text,
    synthesis_drawing,
    synthesis_pose,
    write_cad,
    write_dxf,
)
from linkage.report.candidates import (
    CANDIDATE_COLUMNS,
    CANDIDATE_RPM,
    SLIDER_COLUMNS,
    branch_points,
    candidate_columns,
    candidate_drive,
    candidate_rows,
    candidate_scene,
    candidate_side,
    crank_limits,
    write_candidates_csv,
)
from linkage.report.figures import Result, Row, length_unit, torque_unit

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
