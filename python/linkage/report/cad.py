"""The mechanism as DXF and SVG, at one pose: links, pivots, sliders and every traced path.

Drawn from :mod:`linkage.drawing` (the model the plots and the HTML page draw too); ezdxf is
imported only when a DXF is written. :mod:`linkage.export` re-exports these names.

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

import re
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.choices import View
from linkage.drawing import Drawing, leg_angles, mechanism_drawing, walker_drawing
from linkage.kinematics.slider_crank import SliderCrank
from linkage.report.figures import Result, length_unit

__all__ = [
    "INSUNITS",
    "default_pose",
    "drawing_of",
    "layer_name",
    "svg_text",
    "synthesis_drawing",
    "synthesis_pose",
    "write_cad",
    "write_dxf",
]

Array = NDArray[np.float64]


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
