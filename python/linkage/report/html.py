"""The report's page, ``index.html``: one self-contained file a browser opens from the disk.

It holds the animated mechanism as inline SVG (play/pause, a speed control, a slider that scrubs
the run, and a read-out of the current sample's values with the scene's units), the figures
table and every plot image of the report, embedded as ``data:`` URIs. Nothing is loaded from
the network: no scripts, styles, fonts or images from anywhere but the file itself.

The page's data is a JSON block the script reads: for each view (the mechanism; a walker's side
and top views) the shapes to draw — bars, plates, hatched ground pivots, slider blocks, joints,
the trace path, the ground line, stance feet, the support polygon and the centre of gravity —
and the positions of their points at each frame, in page units (the view's larger side is
1000 units, y down) rounded to 0.1 unit, which is below a screen's pixel. At most
:data:`MAX_FRAMES` frames are embedded, taken evenly from the run's samples.

A ``[synthesis]`` scene's page has no motion: the figures table, the candidates (lengths,
pivots, errors, the scene file of each) and the plot; no script.
"""

from __future__ import annotations

import base64
import html
import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage.drawing import Drawing, leg_angles, mechanism_drawing, walker_drawing
from linkage.drives.drive import CrankSchedule
from linkage.kinematics.slider_crank import SliderCrank
from linkage.report.figures import Result, branch_text, crank_phase_deg, format_number, length_unit
from linkage.scene.builders import build_drive
from linkage.synthesis import Candidate, long_link, rounded_to

__all__ = ["MAX_FRAMES", "PAGE_SIZE", "PATH_POINTS", "frames", "page", "write_index"]

Array = NDArray[np.float64]

MAX_FRAMES = 720
"""Most frames the page embeds; a longer run is subsampled evenly."""

PAGE_SIZE = 1000.0
"""Page units along a view's larger side."""

_MIME = {
    ".png": "image/png",
    ".gif": "image/gif",
    ".jpg": "image/jpeg",
    ".jpeg": "image/jpeg",
    ".svg": "image/svg+xml",
    ".webp": "image/webp",
}


def write_index(
    res: Result,
    folder: Path,
    images: Sequence[Path],
    drawings: Sequence[Drawing] | None = None,
) -> Path:
    r"""Write ``folder / "index.html"`` for the run ``res`` and return its path.

    ``images`` are the report's plot files (already written), embedded in the order given;
    files of a type a browser cannot show inline are listed by name instead. ``drawings`` are
    the run's drawings (:class:`~linkage.drawing.Drawing`) if the caller has them: the
    mechanism's, or a walker's side and top views, over all samples; given, they are not built
    again.

    Raises
    ------
    LinkageError
        If a drawing given does not have one sample per sample of the run.

    Examples
    --------
    A PDF cannot be shown inline, so it is listed by name:

    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.html_report import write_index
    >>> from linkage.runner import run
    >>> from linkage.scene import parse
    >>> scene = parse('units = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...               '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n', name="hoecken")
    >>> res = run(scene)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     path = write_index(res, Path(tmp), [Path(tmp) / "notes.pdf"])
    ...     path.name, "notes.pdf" in path.read_text(encoding="utf-8")
    ('index.html', True)
    """
    path = Path(folder) / "index.html"
    path.write_text(page(res, images, drawings), encoding="utf-8")
    return path


def page(
    res: Result, images: Sequence[Path] = (), drawings: Sequence[Drawing] | None = None
) -> str:
    r"""Return the text of the report's ``index.html`` (see :func:`write_index`).

    Examples
    --------
    >>> import re
    >>> import numpy as np
    >>> from linkage.drawing import mechanism_drawing
    >>> from linkage.html_report import page
    >>> from linkage.runner import run
    >>> from linkage.scene import parse
    >>> scene = parse('units = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...               '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n', name="hoecken")
    >>> res = run(scene)
    >>> text = page(res)
    >>> re.search(r"<title>(.*?)</title>", text).group(1), re.findall(r"(?:src|href)=.http", text)
    ('hoecken — linkage report', [])

    A drawing given must cover the run's samples:

    >>> d = mechanism_drawing(res.mechanism, res.mechanism.sweep(np.linspace(0.0, 1.0, 5)))
    >>> page(res, drawings=[d])
    Traceback (most recent call last):
    ...
    linkage.LinkageError: a drawing of 5 samples for a run of 73
    """
    scene = res.scene
    if res.synthesis is not None:
        return _synthesis_page(res, images)
    data = {
        "name": scene.name,
        "units": length_unit(scene),
        "views": _views(res, drawings),
        "readout": _readout(res, frames(len(res.time))),
        "stance": _stance(res),
        "duration": float(res.time[-1] - res.time[0]) if len(res.time) > 1 else 0.0,
    }
    title = html.escape(scene.name or "linkage report")
    description = getattr(scene, "description", "") or ""
    units = (
        f"Lengths in {html.escape(scene.units)}"
        if scene.units
        else "Lengths in the scene's units (the scene does not name them)"
    )
    return _TEMPLATE.format(
        title=title,
        description=f"<p class=desc>{html.escape(description)}</p>" if description else "",
        units=units,
        css=_CSS,
        js=_JS,
        data=_json_script(data),
        figures=_figures_table(res),
        plots=_plots(images),
    )


def _synthesis_page(res: Result, images: Sequence[Path]) -> str:
    """Return the page of a ``[synthesis]`` run: figures, candidates, plots."""
    scene = res.scene
    title = html.escape(scene.name or "linkage report")
    description = getattr(scene, "description", "") or ""
    units = (
        f"Lengths in {html.escape(scene.units)}"
        if scene.units
        else "Lengths in the scene's units (the scene does not name them)"
    )
    return _SYNTHESIS_TEMPLATE.format(
        title=title,
        description=f"<p class=desc>{html.escape(description)}</p>" if description else "",
        units=units,
        css=_CSS,
        figures=_figures_table(res),
        candidates=_candidates_table(res),
        plots=_plots(images),
        sought=_SOUGHT[str((scene.synthesis or {}).get("kind", "fourbar"))],
    )


_SOUGHT = {
    "fourbar": "four-bars",
    "slider-crank": "slider-cranks",
    "any": "four-bars and slider-cranks",
}
"""What a synthesis page says its scene searched, by the scene's ``kind``."""


def _candidates_table(res: Result) -> str:
    """Return the candidates as an HTML table.

    Rank, errors, class, crank range, transmission, pivots (and a slider's line), lengths, coupler
    point and assembly (or reach); the columns name the lengths of the kind the scene searched
    (``"any"``: each cell names its own). Candidate ``k``'s scene file, ``candidate-k.toml``, is
    named in the note above the table.
    """
    run = res.synthesis
    assert run is not None
    u = html.escape(length_unit(res.scene))

    def n(x: float, digits: int | None = None) -> str:
        # Coordinates and lengths to 1e-6 of the target's size without trailing zeros (an exact
        # fit's round-off reads 0); errors to ``digits``.
        if digits is None:
            return html.escape(format_number(rounded_to(x, run.size, 6), 0))
        return html.escape(format_number(float(x), None, digits))

    def pair(x: float, y: float) -> str:
        # A point never breaks across lines; the cells holding several break between them.
        return f"<span class=nb>({n(x)}, {n(y)})</span>"

    kind = str((res.scene.synthesis or {}).get("kind", "fourbar"))
    if kind == "fourbar":
        frame, links, branch = "pivots O, C", f"ground, crank, coupler, rocker ({u})", "assembly"
    elif kind == "slider-crank":
        frame, links, branch = "pivot O; slider line", f"crank, rod; offset ({u})", "reach"
    else:
        frame, links, branch = "pivots; slider line", f"links ({u})", "branch"
    # A closed target's candidates also say how far their curve strays from the target's
    # polygon (a spur or a loop the points never asked for), which the error cannot show.
    back = f"<th>curve → polygon ({u})</th>" if run.closed else ""
    head = (
        f"<tr><th>#</th><th>max error ({u})</th><th>RMS ({u})</th>{back}<th>class</th>"
        f"<th>crank range (°)</th><th>min transmission (°)</th><th>{frame}</th>"
        f"<th>{links}</th><th>coupler point</th><th>{branch}</th></tr>"
    )
    # Given length bounds replace the ranking of long-linked candidates after the rest.
    bounded = "lengths" in (res.scene.synthesis or {})
    rows = []
    for k, c in enumerate(run.candidates, 1):
        lk = c.linkage
        lo, hi = (math.degrees(v) for v in c.crank_range)
        # An open target's range is the matched part of a crank that may turn fully.
        full = "(full turn)" if run.closed else "(crank turns fully)"
        turn = f" <span class=nb>{full}</span>" if c.full_turn else ""
        o = pair(*lk.o)
        if isinstance(lk, SliderCrank):
            g = pair(*lk.line_point)
            at = html.escape(format_number(round(math.degrees(lk.angle), 6) + 0.0, 0, 6))
            where = f"{o}; through {g} at {at}°"
            lengths = f"{n(lk.crank)}, {n(lk.coupler)}; {n(lk.offset)}"
            side = lk.reach if kind == "slider-crank" else branch_text(lk)
        else:
            where = f"{o}, {pair(*lk.c)}"
            lengths = f"{n(lk.ground)}, {n(lk.crank)}, {n(lk.coupler)}, {n(lk.rocker)}"
            side = lk.assembly if kind == "fourbar" else branch_text(lk)
        if kind == "any":
            where = f"O {where}" if isinstance(lk, SliderCrank) else f"O, C {where}"
            names = (
                "crank, rod; offset"
                if isinstance(lk, SliderCrank)
                else "ground, crank, coupler, rocker"
            )
            lengths = f"{names}: {lengths}"
        rows.append(
            f"<tr><td>{k}</td><td class=num>{n(c.error, 3)}</td><td class=num>{n(c.rms, 3)}</td>"
            + (f"<td class=num>{n(c.back, 3)}</td>" if run.closed else "")
            + f"<td>{html.escape(c.grashof)}{'' if bounded else _ranked_after(c, run.size)}</td>"
            f"<td class='num wrap'><span class=nb>{round(lo, 1) + 0.0:.1f} … "
            f"{round(hi, 1) + 0.0:.1f}</span>{turn}</td>"
            f"<td class=num>{c.min_transmission_deg:.1f}</td>"
            f"<td class='num wrap'>{where}</td><td class='num wrap'>{lengths}</td>"
            f"<td class=num>{pair(*lk.point)}</td>"
            f"<td>{html.escape(side)}</td></tr>"
        )
    return (
        f"<table class=figures id=candidates><thead>{head}</thead><tbody>"
        + "".join(rows)
        + "</tbody></table>"
    )


def _ranked_after(c: Candidate[Any], size: float) -> str:
    """Return the note of a candidate ranked last for a link over ``LONG_LINK`` sizes, or ""."""
    k = long_link(c, size)
    if k is None:
        return ""
    return f" <span class=nb>(link {k:.0f}× the size: ranked after)</span>"


def frames(n: int, most: int = MAX_FRAMES) -> NDArray[np.intp]:
    """Return the indices of the samples the page embeds.

    All ``n``, or ``most`` spread evenly: the first and the last included (only the first when
    ``most`` is 1; none when it is 0).

    Examples
    --------
    >>> from linkage.html_report import frames
    >>> frames(5).tolist(), frames(1000, most=5).tolist(), frames(0).tolist()
    ([0, 1, 2, 3, 4], [0, 250, 500, 749, 999], [])
    >>> frames(10, most=1).tolist(), frames(10, most=0).tolist()
    ([0], [])
    """
    if n <= most:
        return np.arange(n)
    idx: NDArray[np.intp] = np.unique(np.round(np.linspace(0, n - 1, most)).astype(np.intp))
    return idx


# -- the data ---------------------------------------------------------------------------------


class _Frame:
    """Map from a view's world coordinates (y up) to page units (y down).

    The larger side is :data:`PAGE_SIZE` page units; heights are multiplied by ``stretch`` (1: to
    scale).
    """

    def __init__(self, bounds: tuple[float, float, float, float], stretch: float = 1.0) -> None:
        x0, x1, y0, y1 = bounds
        self.x0, self.y1 = x0, y1
        self.stretch = stretch
        span = max(x1 - x0, (y1 - y0) * stretch)
        self.scale = PAGE_SIZE / span if math.isfinite(span) and span > 0 else 1.0
        self.size = (
            math.ceil((x1 - x0) * self.scale),
            math.ceil((y1 - y0) * stretch * self.scale),
        )

    def __call__(self, p: Array) -> Array:
        """Page coordinates of world points ``(..., 2)``, rounded to whole page units.

        NaN where not finite.
        """
        p = np.asarray(p, dtype=float)
        q = np.empty(p.shape, dtype=np.float64)
        q[..., 0] = (p[..., 0] - self.x0) * self.scale
        q[..., 1] = (self.y1 - p[..., 1]) * self.scale * self.stretch
        with np.errstate(invalid="ignore"):
            out: Array = np.asarray(np.round(np.clip(q, -1e6, 1e6)), dtype=np.float64)
        return out


def _ints(q: Array) -> list[int]:
    """Finite page coordinates as a flat list of ints."""
    out: list[int] = q.reshape(-1).astype(np.int64).tolist()
    return out


def _points(q: Array) -> tuple[dict[str, list[int]], list[int], list[list[int] | None]]:
    """Page positions ``(F, P, 2)`` of a view's points as the page stores them.

    The points that never move once (``{index: [x, y]}``), the indices of the others, and their flat
    positions per frame, ``None`` at a frame where any is missing (a sample that did not assemble).
    A row that follows a row (not ``None``) holds the change from it; the first row and a row after
    ``None`` hold positions.
    """
    finite: NDArray[np.bool_] = np.asarray(np.isfinite(q).all(axis=2), dtype=bool)
    still = np.zeros(q.shape[1], dtype=bool)
    fixed: dict[str, list[int]] = {}
    for j in range(q.shape[1]):
        col = q[finite[:, j], j]
        if len(col) and finite[:, j].all() and not np.ptp(col, axis=0).any():
            still[j] = True
            fixed[str(j)] = _ints(col[0])
    moving = np.flatnonzero(~still)
    rows: list[list[int] | None] = []
    last = None
    for f in range(q.shape[0]):
        if not finite[f, moving].all():
            rows.append(None)
            last = None
            continue
        here = q[f, moving]
        rows.append(_ints(here if last is None else here - last))
        last = here
    return fixed, [int(j) for j in moving], rows


PATH_POINTS = 2000
"""Most points of a traced path on the page (a longer one is subsampled evenly)."""


def _path(q: Array) -> str:
    """Return an SVG path through page points ``(N, 2)``.

    At most :data:`PATH_POINTS` are taken, evenly; the path is broken where a point is not finite,
    repeated points dropped.
    """
    q = q[frames(len(q), PATH_POINTS)]
    parts: list[str] = []
    pen = "M"
    last = None
    for x, y in q:
        if not (math.isfinite(x) and math.isfinite(y)):
            pen = "M"
            continue
        here = (int(x), int(y))
        if here == last and pen == "L":
            continue
        parts.append(f"{pen}{here[0]} {here[1]}")
        last, pen = here, "L"
    return "".join(parts)


def _views(res: Result, drawings: Sequence[Drawing] | None = None) -> list[dict[str, Any]]:
    """Return the page's views of the run: the mechanism, or a walker's side and top views."""
    idx = frames(len(res.time))
    units = res.scene.units
    given = list(drawings or ())
    for d in given:
        if len(d) != len(res.time):
            raise LinkageError(f"a drawing of {len(d)} samples for a run of {len(res.time)}")
    if res.walker is not None and res.simulation is not None:
        walker, sim = res.walker, res.simulation
        side_top = [
            next((d for d in given if d.feet is not None and d.axes[1] == ax), None)
            for ax in ("z", "y")
        ]
        if side_top[0] is None or side_top[1] is None:
            drive, _ = build_drive(res.scene, walker.legs[0].linkage)
            theta = leg_angles(walker, sim, drive, isinstance(drive, CrankSchedule))
            side_top = [walker_drawing(walker, sim, v, theta, units) for v in ("side", "top")]
        side, top = side_top
        assert side is not None and top is not None
        shift = np.asarray(sim.body_position, dtype=float)[idx]
        sagittal = any(leg.plane == "sagittal" for leg in walker.legs)
        views = [
            _view(side, idx, "side view", to_scale=sagittal, shift=shift),
            _view(top, idx, "top view"),
        ]
        return views if sagittal else views[::-1]

    assert res.mechanism is not None and res.sweep is not None
    mech = next((d for d in given if d.feet is None), None)
    if mech is None:
        mech = mechanism_drawing(res.mechanism, res.sweep, units)
    return [_view(mech, idx, "mechanism")]


def _cranks(d: Drawing) -> set[int]:
    """Return the indices in ``d.links`` of the driven cranks (one per walker leg).

    The links named ``crank``, else each leg's first binary link on a ground pivot (a crank is the
    first construction on the ground in a program).
    """
    named = {
        k for k, link in enumerate(d.links) if link.name == "crank" or link.name.endswith(".crank")
    }
    if named:
        return named
    out: dict[int | None, int] = {}
    for k, link in enumerate(d.links):
        if link.kind != "ground" and len(link.joints) == 2 and set(link.joints) & set(d.pivots):
            out.setdefault(link.leg, k)
    return set(out.values())


def _view(
    d: Drawing,
    idx: NDArray[np.intp],
    title: str,
    to_scale: bool = True,
    shift: Array | None = None,
) -> dict[str, Any]:
    """Build one view of a drawing for the page.

    The view holds its shapes and the page positions of their points at the embedded frames
    (joints, then feet, then the centre of gravity).
    """
    bounds = d.bounds(0.06)
    stretch = 1.0
    if not to_scale:
        # Legs in the horizontal plane seen from the side: a strip a few pad heights tall.
        # Heights are stretched to a quarter of the width and the title says so.
        x0, x1, y0, y1 = bounds
        if y1 > y0:
            stretch = max(1.0, 0.25 * (x1 - x0) / (y1 - y0))
        title += f" (heights ×{stretch:.3g}, not to scale)" if stretch > 1 else ""
    fr = _Frame(bounds, stretch)
    nj = len(d.joint_names)
    parts = [np.asarray(d.positions, dtype=float)[idx]]
    shapes: list[list[Any]] = []
    if d.ground is not None:
        shapes.append(["groundline", int(fr(np.array([0.0, d.ground]))[1])])
    if d.body is not None:
        shapes.append(["outline", _path(fr(d.body)) + "Z", "body"])
    if d.support is not None:
        shapes.append(["support"])
    walker = d.feet is not None
    for label, p in d.paths.items():
        shapes.append(["path", _path(fr(p)), "footpath" if walker else "trace", label])
    cranks = _cranks(d)
    moving: set[int] = set()
    # Plates under bars: a bar's end on a plate stays visible.
    order = sorted(range(len(d.links)), key=lambda k: d.links[k].kind != "plate")
    for k in order:
        link = d.links[k]
        if link.kind == "ground":
            continue
        moving.update(link.joints)
        kind = "plate" if link.kind == "plate" else "bar"
        shapes.append([kind, list(link.joints), "crank" if k in cranks else "link", link.name])
    for s in d.sliders:
        u = np.asarray(s.direction, dtype=float)[idx]
        ang = np.degrees(np.arctan2(-u[:, 1] * stretch, u[:, 0]))
        shapes.append(
            [
                "slider",
                s.joint,
                s.origin,
                [round(float(a), 1) if math.isfinite(a) else None for a in ang],
            ]
        )
    shapes.extend(["pivot", j] for j in d.pivots)
    # A leg's joint that is its foot is drawn as the foot (below), not as a pin.
    foot_joint = _foot_joints(d, idx) if walker else {}
    feet_at = set(foot_joint.values())
    pins = sorted(moving - set(d.pivots) - feet_at - ({d.trace} if d.trace is not None else set()))
    shapes.extend(["joint", j] for j in pins)
    if d.trace is not None:
        shapes.append(["tracer", d.trace])
    extra: dict[str, Any] = {}
    if walker:
        assert d.feet is not None
        feet = np.asarray(d.feet, dtype=float)[idx]
        legs = feet.shape[1]
        labels = d.leg_labels or d.legs
        extra_feet = [i for i in range(legs) if i not in foot_joint]
        parts.append(feet[:, extra_feet])
        at = dict(foot_joint)
        at.update({i: nj + k for k, i in enumerate(extra_feet)})
        for i in range(legs):
            shapes.append(["foot", at[i], i, labels[i] if i < len(labels) else str(i)])
        if d.cg is not None:
            parts.append(np.broadcast_to(np.asarray(d.cg, dtype=float), (len(idx), 1, 2)))
            shapes.append(["cg", nj + len(extra_feet)])
        if d.support is not None:
            sup = fr(np.asarray(d.support, dtype=float)[idx])
            extra["support"] = [_ints(row[np.isfinite(row).all(axis=1)]) for row in sup]
        if shift is not None:
            extra["shift"] = [round(float(v) * fr.scale) for v in shift]
        if d.feet is not None and title.startswith("top"):
            # Leg names at the far end of each foot's path from the body's centre line.
            mid = np.nanmean(d.feet, axis=0)
            centre = float(np.nanmean(mid[:, 1]))
            for i in range(legs):
                p = d.feet[:, i]
                out = 1.0 if mid[i, 1] >= centre else -1.0
                y = float(np.nanmax(p[:, 1]) if out > 0 else np.nanmin(p[:, 1]))
                q = fr(np.array([float(mid[i, 0]), y]))
                shapes.append(["text", int(q[0]), int(q[1] - 14 * out), labels[i], out])
    fixed, moving_pts, rows = _points(fr(np.concatenate(parts, axis=1)))
    return {
        "title": title,
        "axes": list(d.axes),
        "size": list(fr.size),
        "unit": fr.scale,
        "stretch": stretch,
        "shapes": shapes,
        "count": int(sum(p.shape[1] for p in parts)),
        "fixed": fixed,
        "moving": moving_pts,
        "points": rows,
        **extra,
    }


def _foot_joints(d: Drawing, idx: NDArray[np.intp]) -> dict[int, int]:
    """Map a leg index to the joint that is that leg's foot at every embedded frame.

    The foot is its linkage's trace point, or the end of its foot bar; legs without one are left
    out.
    """
    feet = np.asarray(d.feet, dtype=float)[idx]
    pos = np.asarray(d.positions, dtype=float)[idx]
    tol = 1e-9 * max(1.0, float(np.nanmax(np.abs(pos))) if np.isfinite(pos).any() else 1.0)
    out: dict[int, int] = {}
    for i in range(feet.shape[1]):
        with np.errstate(invalid="ignore"):
            same = np.all(np.abs(pos - feet[:, i : i + 1]) <= tol, axis=(0, 2))
        hits = np.flatnonzero(same)
        if len(hits):
            out[i] = int(hits[-1])
    return out


def _stance(res: Result) -> list[str] | None:
    """Which feet are down at each embedded frame: a string of 0/1 per leg."""
    if res.simulation is None:
        return None
    st = np.asarray(res.simulation.stance, dtype=bool)[frames(len(res.time))]
    return ["".join("1" if v else "0" for v in row) for row in st]


def _decimals(v: Array, significant: int = 4) -> int:
    """Decimals that show ``significant`` digits of the column's largest magnitude."""
    finite = np.abs(v[np.isfinite(v)])
    if not len(finite) or float(finite.max()) == 0.0:
        return 0
    return int(max(0, min(12, significant - 1 - math.floor(math.log10(float(finite.max()))))))


def _column(label: str, unit: str, v: Array, decimals: int | None = None) -> dict[str, Any]:
    d = _decimals(v) if decimals is None else decimals
    return {
        "label": label,
        "unit": unit,
        "decimals": d,
        "values": [round(float(x), d) if math.isfinite(x) else None for x in v],
    }


def _readout(res: Result, idx: NDArray[np.intp]) -> list[dict[str, Any]]:
    u = length_unit(res.scene)
    theta = np.degrees(np.mod(res.theta[idx], 2 * math.pi))
    cols = [_column("time", "s", res.time[idx])]
    phase = crank_phase_deg(res.scene)
    if phase % 360:
        # The crank is at θ + its phase (an exported synthesis candidate's): both, named.
        cols.append(_column("drive angle θ", "°", theta, 1))
        cols.append(_column("crank angle", "°", np.mod(theta + phase, 360.0), 1))
    else:
        cols.append(_column("crank angle", "°", theta, 1))
    s = res.sweep
    if s is not None:
        p = np.array(s.point[idx], dtype=float)
        p[~s.valid[idx]] = np.nan
        name = f"trace {s.trace}" if s.trace else "trace"
        cols.append(_column(f"{name} x", u, p[:, 0], _decimals(s.point[s.valid])))
        cols.append(_column(f"{name} y", u, p[:, 1], _decimals(s.point[s.valid])))
    if res.rates is not None:
        speed = np.linalg.norm(res.rates.velocity[idx], axis=1)
        cols.append(_column("trace speed", f"{u}/s", speed))
    sim = res.simulation
    if sim is not None:
        labels = res.walker.leg_labels() if res.walker is not None else sim.legs
        down = [
            f"{int(row.sum())}: {' '.join(n for n, on in zip(labels, row) if on)}"
            if row.any()
            else "0"
            for row in np.asarray(sim.stance[idx], dtype=bool)
        ]
        cols.append({"label": "feet down", "unit": "", "decimals": 0, "values": down})
        cols.append(_column("body speed", f"{u}/s", np.asarray(sim.body_velocity)[idx]))
        margin = np.where(np.isfinite(sim.margin[idx]), sim.margin[idx], np.nan)
        cols.append(_column("stability margin", u, margin))
        cols.append(_column("body travel", u, np.asarray(sim.body_position)[idx]))
    return cols


# -- the page ---------------------------------------------------------------------------------


def _json_script(data: Any) -> str:
    """JSON that is safe inside a ``<script>`` element."""
    text = json.dumps(data, separators=(",", ":"), allow_nan=False, ensure_ascii=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _cells(row: Any) -> list[str]:
    """Return a figures row as its four cells (figure, value, unit, error estimate)."""
    if isinstance(row, (tuple, list)):
        cells = [str(c) for c in row]
    else:
        cells = [
            str(getattr(row, k, ""))
            for k in ("figure", "value", "unit", "error")
            if hasattr(row, k)
        ]
    return ([*cells, "", "", "", ""])[:4]


def _figures_table(res: Result) -> str:
    rows = []
    for row in res.figures:
        name, value, unit, err = (html.escape(c) for c in _cells(row))
        rows.append(
            f"<tr><th scope=row>{name}</th><td class=num>{value}</td>"
            f"<td>{unit}</td><td class=err>{err}</td></tr>"
        )
    return (
        "<table class=figures><thead><tr><th>figure</th><th>value</th><th>unit</th>"
        "<th>error estimate</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>"
    )


def _plots(images: Sequence[Path]) -> str:
    out = []
    for p in images:
        path = Path(p)
        mime = _MIME.get(path.suffix.lower())
        name = html.escape(path.name)
        if mime is None:
            out.append(f"<figure><figcaption>{name} (not shown)</figcaption></figure>")
            continue
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        out.append(
            f'<figure><img alt="{name}" src="data:{mime};base64,{data}">'
            f"<figcaption>{name}</figcaption></figure>"
        )
    return "".join(out) or "<p>No plots in this report.</p>"


_CSS = """
:root{--ink:#1d2433;--muted:#5b6477;--line:#d6dae3;--bg:#fafbfc;--accent:#1f5fbf;
--trace:#c8372d;--link:#3b4a66;--crank:#1f5fbf;--plate:#9fb3d9}
*{box-sizing:border-box}
body{margin:0;font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;
color:var(--ink);background:var(--bg)}
header,main{max-width:1200px;margin:0 auto;padding:0 20px}
header{padding-top:18px}
h1{font-size:1.5em;margin:.2em 0}
h2{font-size:1.15em;margin:1.4em 0 .5em;border-bottom:1px solid var(--line);padding-bottom:.2em}
.desc,.meta{color:var(--muted);margin:.2em 0}
.stage{display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start}
.left{flex:1 1 560px}
.views{display:flex;flex-wrap:wrap;gap:12px}
.legend{display:flex;flex-wrap:wrap;gap:4px 16px;color:var(--muted);font-size:.85em;
margin-top:6px}
.legend span{display:inline-flex;align-items:center;gap:5px}
.legend svg{overflow:visible}
.view{flex:1 1 420px;background:#fff;border:1px solid var(--line);border-radius:6px;
padding:6px}
.view h3{font-size:.9em;color:var(--muted);margin:0 0 4px;font-weight:600}
.view svg{width:100%;height:auto;max-height:62vh;display:block}
.panel{flex:0 1 300px;background:#fff;border:1px solid var(--line);border-radius:6px;
padding:10px 12px}
.controls{display:flex;flex-wrap:wrap;gap:8px;align-items:center;margin-bottom:8px}
button{font:inherit;padding:4px 14px;border:1px solid var(--accent);background:var(--accent);
color:#fff;border-radius:4px;cursor:pointer;min-width:5.5em}
select{font:inherit}
input[type=range]{width:100%}
.readout{width:100%;border-collapse:collapse;font-variant-numeric:tabular-nums}
.readout th{text-align:left;font-weight:normal;color:var(--muted);padding:2px 6px 2px 0}
.readout td{text-align:right;padding:2px 0}
.readout td.u{text-align:left;padding-left:6px;color:var(--muted);white-space:nowrap}
table.figures{border-collapse:collapse;width:100%;background:#fff;
font-variant-numeric:tabular-nums}
.figures th,.figures td{border-bottom:1px solid var(--line);padding:5px 10px;text-align:left;
vertical-align:top}
.figures thead th{background:#eef1f6}
.figures tbody th{font-weight:normal}
.figures td.num{text-align:right;white-space:nowrap}
.figures td.err{color:var(--muted)}
.plots{display:flex;flex-wrap:wrap;gap:14px}
.plots figure{margin:0;background:#fff;border:1px solid var(--line);border-radius:6px;
padding:6px;flex:1 1 440px;max-width:100%}
.plots img{max-width:100%;height:auto;display:block;margin:0 auto}
figcaption{color:var(--muted);font-size:.85em;text-align:center}
footer{color:var(--muted);font-size:.8em;margin:2em 0 1em}
svg .bar{stroke:var(--link);stroke-width:7;stroke-linecap:round;stroke-linejoin:round;
fill:none}
svg .guide{stroke:var(--muted);stroke-width:1.5;stroke-dasharray:10 5}
svg .bar.crank{stroke:var(--crank)}
svg .plate{fill:var(--plate);fill-opacity:.55;stroke:var(--link);stroke-width:4;
stroke-linejoin:round}
svg .joint{fill:#fff;stroke:var(--ink);stroke-width:2.5}
svg .pivot{fill:#fff;stroke:var(--ink);stroke-width:2.5}
svg .hatch{stroke:var(--ink);stroke-width:1.6}
svg .trace{fill:none;stroke:var(--trace);stroke-width:2;stroke-opacity:.75}
svg .footpath{fill:none;stroke:var(--muted);stroke-width:1.2;stroke-dasharray:4 4}
svg .tracer{fill:var(--trace);stroke:#fff;stroke-width:2}
svg .block{fill:#e8c66a;stroke:var(--ink);stroke-width:2.5}
svg .body{fill:#dfe5ef;stroke:var(--link);stroke-width:3}
svg .ground{stroke:var(--ink);stroke-width:2.5}
svg .foot{stroke:var(--ink);stroke-width:2}
svg .foot.down{fill:var(--trace)}
svg .foot.up{fill:#fff}
svg .support{fill:#3aa76d;fill-opacity:.18;stroke:#2d8a57;stroke-width:2.5}
svg .cg{fill:var(--ink)}
svg .label{font-size:calc(var(--k, 1.4) * 14px);fill:var(--muted)}
svg .scalebar{stroke:var(--muted);stroke-width:2}
"""


_TEMPLATE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width,initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src data:; \
style-src 'unsafe-inline'; script-src 'unsafe-inline'">
<link rel="icon" href="data:,">
<title>{title} — linkage report</title>
<style>{css}</style></head>
<body>
<header><h1>{title}</h1>{description}
<p class=meta>{units}; times in s; angles in degrees.</p></header>
<main>
<h2>Motion</h2>
<div class=stage>
<div class=left><div class=views id=views></div><div class=legend id=legend></div></div>
<div class=panel>
<div class=controls>
<button id=play type=button>Pause</button>
<label>speed <select id=speed></select></label>
</div>
<input id=scrub type=range min=0 value=0 step=1 aria-label="sample">
<table class=readout id=readout></table>
</div>
</div>
<h2>Figures</h2>
{figures}
<h2>Plots</h2>
<div class=plots>{plots}</div>
<footer>Written by linkage. This page is self-contained: it loads nothing from the network.\
</footer>
</main>
<script type="application/json" id=linkage-data>{data}</script>
<script>{js}</script>
</body></html>
"""


_SYNTHESIS_TEMPLATE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width,initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src data:; \
style-src 'unsafe-inline'">
<link rel="icon" href="data:,">
<title>{title} — linkage report</title>
<style>{css}
.wide{{overflow-x:auto}}
#candidates{{font-size:.88em}}
#candidates td{{white-space:nowrap}}
#candidates td.wrap{{white-space:normal;text-align:left;min-width:11em}}
.nb{{white-space:nowrap}}</style></head>
<body>
<header><h1>{title}</h1>{description}
<p class=meta>{units}; angles in degrees. Path synthesis: {sought} whose coupler point passes \
through the target points, best first.</p></header>
<main>
<h2>Figures</h2>
{figures}
<h2>Candidates</h2>
<p class=meta>Each candidate is in the target's frame; candidate <i>k</i>'s scene file in this \
folder runs it (<code>linkage run candidate-<i>k</i>.toml</code>, e.g. \
<code>candidate-1.toml</code>). Pivots and lengths to 6 digits here; \
<code>candidates.csv</code> has them in full.</p>
<div class=wide>{candidates}</div>
<h2>Plots</h2>
<div class=plots>{plots}</div>
<footer>Written by linkage. This page is self-contained: it loads nothing from the network.\
</footer>
</main>
</body></html>
"""


_JS = r"""
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("linkage-data").textContent);
  const NS = "http://www.w3.org/2000/svg";
  const nframes = D.readout[0].values.length;
  const times = D.readout[0].values;
  const el = (name, attrs, parent) => {
    const e = document.createElementNS(NS, name);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  };
  // Frames after the first (and after a missing one) are stored as changes: undo that.
  for (const V of D.views) {
    let prev = null;
    V.points = V.points.map((r) => {
      if (r === null) { prev = null; return null; }
      prev = prev === null ? r : prev.map((x, k) => x + r[k]);
      return prev;
    });
  }
  const views = [];
  const kinds = new Set();
  const host = document.getElementById("views");
  for (const V of D.views) {
    const box = document.createElement("div");
    box.className = "view";
    const h = document.createElement("h3");
    h.textContent = V.title;
    box.appendChild(h);
    const w = V.size[0], ht = V.size[1];
    const band = 60;  // below the drawing: the scale bar
    const svg = el("svg", {viewBox: `0 0 ${w} ${ht + band}`, role: "img",
      "aria-label": V.title}, box);
    for (const S of V.shapes) kinds.add(S[0] === "bar" || S[0] === "plate" ? S[2] : S[0]);
    for (const S of V.shapes) if (S[0] === "plate") kinds.add("plate");
    svg.dataset.view = V.title;
    host.appendChild(box);
    const ups = [];
    const groundG = el("g", {}, svg);
    const pr = 12;
    for (const S of V.shapes) {
      const kind = S[0];
      if (kind === "bar" || kind === "plate") {
        const e = el(kind === "bar" ? "polyline" : "polygon", {class: kind + " " + S[2]}, svg);
        el("title", {}, e).textContent = S[3];
        const ids = S[1];
        ups.push((P) => e.setAttribute("points",
          ids.map((j) => P[2 * j] + "," + P[2 * j + 1]).join(" ")));
      } else if (kind === "path" || kind === "outline") {
        const e = el("path", {class: S[2], d: S[1]}, svg);
        if (S[3]) el("title", {}, e).textContent = S[3];
      } else if (kind === "text") {
        const e = el("text", {class: "label", x: S[1], y: S[2], "text-anchor": "middle",
          "dominant-baseline": S[4] > 0 ? "auto" : "hanging"}, svg);
        e.textContent = S[3];
      } else if (kind === "slider") {
        const j = S[1], o = S[2], ang = S[3];
        const guide = el("line", {class: "guide"}, svg);
        const g = el("g", {}, svg);
        el("rect", {class: "block", x: -2 * pr, y: -1.2 * pr, width: 4 * pr, height: 2.4 * pr,
          rx: 2}, g);
        el("circle", {class: "joint", r: pr * 0.55}, g);
        ups.push((P, f) => {
          const a = ang[f] === null ? 0 : ang[f], r = a * Math.PI / 180;
          const c = Math.cos(r), s = Math.sin(r), L = 2 * Math.max(w, ht);
          const ox = P[2 * o], oy = P[2 * o + 1];
          guide.setAttribute("x1", ox - L * c); guide.setAttribute("y1", oy - L * s);
          guide.setAttribute("x2", ox + L * c); guide.setAttribute("y2", oy + L * s);
          g.setAttribute("transform", `translate(${P[2 * j]} ${P[2 * j + 1]}) rotate(${a})`);
        });
      } else if (kind === "pivot") {
        const j = S[1];
        const g = el("g", {}, svg);
        el("path", {class: "pivot", d: `M0 0L${-1.6 * pr} ${2.6 * pr}H${1.6 * pr}Z`}, g);
        el("line", {class: "ground", x1: -2.4 * pr, x2: 2.4 * pr, y1: 2.6 * pr, y2: 2.6 * pr}, g);
        for (let k = -2; k <= 2; k++) {
          const x = k * pr;
          el("line", {class: "hatch", x1: x, y1: 2.6 * pr, x2: x - pr, y2: 3.6 * pr}, g);
        }
        el("circle", {class: "joint", r: pr * 0.55}, g);
        ups.push((P) => g.setAttribute("transform", `translate(${P[2 * j]} ${P[2 * j + 1]})`));
      } else if (kind === "joint" || kind === "tracer") {
        const j = S[1];
        const e = el("circle", {class: kind, r: kind === "tracer" ? pr * 0.8 : pr * 0.55}, svg);
        ups.push((P) => { e.setAttribute("cx", P[2 * j]); e.setAttribute("cy", P[2 * j + 1]); });
      } else if (kind === "block") {
        const j = S[1];
        const e = el("rect", {class: "block", width: 3 * pr, height: 2 * pr}, svg);
        ups.push((P) => {
          e.setAttribute("x", P[2 * j] - 1.5 * pr); e.setAttribute("y", P[2 * j + 1] - pr);
        });
      } else if (kind === "groundline") {
        const y = S[1];
        el("line", {class: "ground", x1: 0, x2: w, y1: y, y2: y}, groundG);
        const hatch = el("g", {}, groundG);
        const step = 40;
        for (let x = -step; x <= w + 2 * step; x += step)
          el("line", {class: "hatch", x1: x, y1: y, x2: x - 16, y2: y + 16}, hatch);
        ups.push((P, f) => {
          const s = V.shift ? V.shift[f] : 0;
          hatch.setAttribute("transform", `translate(${-(((s % step) + step) % step)} 0)`);
        });
      } else if (kind === "foot") {
        const j = S[1], leg = S[2];
        const e = el("circle", {class: "foot", r: pr * 0.7}, svg);
        const tip = el("title", {}, e);
        ups.push((P, f) => {
          e.setAttribute("cx", P[2 * j]); e.setAttribute("cy", P[2 * j + 1]);
          const down = D.stance && D.stance[f][leg] === "1";
          e.setAttribute("class", "foot " + (down ? "down" : "up"));
          tip.textContent = `${S[3]}: ${down ? "stance" : "swing"}`;
        });
      } else if (kind === "support") {
        const e = el("polygon", {class: "support"}, svg);
        ups.push((P, f) => {
          const q = V.support[f], pts = [];
          for (let k = 0; k + 1 < q.length; k += 2) pts.push(q[k] + "," + q[k + 1]);
          e.setAttribute("points", pts.join(" "));
        });
      } else if (kind === "cg") {
        const j = S[1];
        const g = el("g", {}, svg);
        el("circle", {r: pr, fill: "#fff", stroke: "#1d2433", "stroke-width": 2.5}, g);
        const q = `${pr} ${pr} 0 0 1`;
        el("path", {class: "cg", d: `M0 0V${-pr}A${q} ${pr} 0ZM0 0V${pr}A${q} ${-pr} 0Z`}, g);
        ups.push((P) => g.setAttribute("transform", `translate(${P[2 * j]} ${P[2 * j + 1]})`));
      }
    }
    // Scale bar: a round length in the scene's units.
    const target = w / 5 / V.unit;
    const mag = Math.pow(10, Math.floor(Math.log10(target)));
    const len = [5, 2, 1].map((k) => k * mag).find((v) => v <= target) || mag;
    const sb = el("g", {transform: `translate(${w - 20 - len * V.unit} ${ht + band - 14})`},
      svg);
    el("path", {class: "scalebar", d: `M0 -8V0H${len * V.unit}V-8`, fill: "none"}, sb);
    const t = el("text", {class: "label", x: len * V.unit / 2, y: -14, "text-anchor": "middle"},
      sb);
    t.textContent = `${+len.toPrecision(3)} ${D.units}`.trim();
    const P = new Array(2 * V.count).fill(0);
    for (const j in V.fixed) { P[2 * j] = V.fixed[j][0]; P[2 * j + 1] = V.fixed[j][1]; }
    views.push({V, svg, ups, band, P});
  }
  // Labels keep a readable size on the screen whatever the view's scale.
  function fit() {
    for (const v of views) {
      const r = v.svg.getBoundingClientRect();
      if (r.width > 0 && r.height > 0) {
        const k = Math.max(v.V.size[0] / r.width, (v.V.size[1] + v.band) / r.height);
        v.svg.style.setProperty("--k", String(k));
      }
    }
  }
  fit();
  window.addEventListener("resize", fit);
  // The legend: one entry per kind of symbol drawn.
  const LEGEND = [
    ["link", "link", '<line class="bar link" x1="4" y1="8" x2="30" y2="8"/>'],
    ["crank", "crank (driven)", '<line class="bar crank" x1="4" y1="8" x2="30" y2="8"/>'],
    ["plate", "rigid plate", '<path class="plate" d="M4 14L17 2L30 14Z"/>'],
    ["pivot", "ground pivot", '<path class="pivot" d="M17 3L11 12H23Z"/>' +
      '<line class="ground" x1="8" x2="26" y1="12" y2="12"/>'],
    ["slider", "slider on its guide", '<line class="guide" x1="0" y1="8" x2="34" y2="8"/>' +
      '<rect class="block" x="10" y="3" width="14" height="10"/>'],
    ["tracer", "trace point and its path", '<path class="trace" d="M2 12Q17 0 32 12"/>' +
      '<circle class="tracer" cx="17" cy="6" r="4"/>'],
    ["foot", "foot: in stance / in swing", '<circle class="foot down" cx="10" cy="8" r="5"/>' +
      '<circle class="foot up" cx="24" cy="8" r="5"/>'],
    ["footpath", "foot path", '<path class="footpath" d="M2 12Q17 0 32 12"/>'],
    ["support", "support polygon", '<path class="support" d="M4 14L17 2L30 14Z"/>'],
    ["cg", "centre of gravity", '<circle cx="17" cy="8" r="6" fill="#fff" stroke="#1d2433"' +
      ' stroke-width="1.5"/>' +
      '<path class="cg" d="M17 8V2A6 6 0 0 1 23 8ZM17 8V14A6 6 0 0 1 11 8Z"/>'],
    ["body", "body", '<rect class="body" x="3" y="3" width="28" height="10"/>'],
    ["groundline", "ground", '<line class="ground" x1="2" x2="32" y1="5" y2="5"/>' +
      '<path class="hatch" d="M8 5l-4 6M16 5l-4 6M24 5l-4 6M32 5l-4 6"/>'],
  ];
  const legend = document.getElementById("legend");
  for (const [kind, label, icon] of LEGEND) {
    if (!kinds.has(kind)) continue;
    const item = document.createElement("span");
    item.innerHTML = `<svg viewBox="0 0 34 16" width="34" height="16">${icon}</svg>`;
    item.append(label);
    legend.appendChild(item);
  }

  const scrub = document.getElementById("scrub");
  scrub.max = String(nframes - 1);
  const table = document.getElementById("readout");
  const cells = D.readout.map((c) => {
    const tr = document.createElement("tr");
    const th = document.createElement("th");
    th.textContent = c.label;
    const td = document.createElement("td");
    const tu = document.createElement("td");
    tu.className = "u";
    tu.textContent = c.unit;
    tr.append(th, td, tu);
    table.appendChild(tr);
    return td;
  });
  let frame = 0;
  function show(f) {
    frame = Math.max(0, Math.min(nframes - 1, f | 0));
    for (const v of views) {
      const row = v.V.points[frame];
      v.svg.style.opacity = row === null ? "0.25" : "1";
      if (row !== null) {
        const P = v.P, m = v.V.moving;
        for (let k = 0; k < m.length; k++) {
          P[2 * m[k]] = row[2 * k]; P[2 * m[k] + 1] = row[2 * k + 1];
        }
        for (const u of v.ups) u(P, frame);
      }
      v.svg.dataset.frame = String(frame);
    }
    D.readout.forEach((c, k) => {
      const x = c.values[frame];
      cells[k].textContent =
        x === null ? "—" : typeof x === "string" ? x : x.toFixed(c.decimals);
    });
    scrub.value = String(frame);
  }

  const speeds = [0.05, 0.1, 0.25, 0.5, 1, 2, 5, 10, 20, 50, 100];
  const sel = document.getElementById("speed");
  // Default: the nearest speed that plays the run in about eight seconds (at most real time).
  const want = Math.min(1, 8 / Math.max(D.duration, 1e-9));
  let best = speeds[0];
  const off = (s) => Math.abs(Math.log(s / want));
  for (const s of speeds) if (off(s) < off(best)) best = s;
  for (const s of speeds) {
    const o = document.createElement("option");
    o.value = String(s); o.textContent = s + "×";
    if (s === best) o.selected = true;
    sel.appendChild(o);
  }
  const playBtn = document.getElementById("play");
  let playing = !window.matchMedia("(prefers-reduced-motion: reduce)").matches;
  let clock = times[0] || 0, last = null;
  const t0 = times[0] || 0, span = Math.max(D.duration, 1e-12);
  function frameAt(t) {
    let lo = 0, hi = nframes - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  function tick(now) {
    if (!playing) { last = null; return; }
    if (last !== null) {
      clock += (now - last) / 1000 * parseFloat(sel.value);
      if (clock > t0 + span) clock = t0 + ((clock - t0) % span);
      const f = frameAt(clock);
      if (f !== frame) show(f);
    }
    last = now;
    requestAnimationFrame(tick);
  }
  function setPlaying(p) {
    playing = p;
    playBtn.textContent = p ? "Pause" : "Play";
    playBtn.setAttribute("aria-pressed", String(p));
    if (p) { clock = times[frame]; requestAnimationFrame(tick); }
  }
  playBtn.addEventListener("click", () => setPlaying(!playing));
  scrub.addEventListener("input", () => { setPlaying(false); show(parseInt(scrub.value, 10)); });
  document.addEventListener("keydown", (e) => {
    // Controls keep their own keys (a focused button already toggles on the space bar).
    if (e.target && ["SELECT", "BUTTON", "INPUT"].includes(e.target.tagName)) return;
    if (e.key === " ") { e.preventDefault(); setPlaying(!playing); }
    else if (e.key === "ArrowRight") { setPlaying(false); show(frame + 1); }
    else if (e.key === "ArrowLeft") { setPlaying(false); show(frame - 1); }
  });
  show(0);
  setPlaying(playing);
  window.linkageReport = {show, setPlaying, frames: nframes, frame: () => frame, data: D};
})();
"""
