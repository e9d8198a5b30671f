"""The report folder of a run: plots (PNG), an animation (GIF), the data and a JSON summary.

Only the files the scene's outputs call for are written; the data are CSV and NPZ. A
``[synthesis]`` scene's report holds ``synthesis.png`` (the target and every candidate's coupler
curve, the best drawn at one pose), ``candidates.csv``, each candidate as a scene to run and the
summary.

The folder is written safely by :mod:`linkage.report_folder` (a temporary sibling, a marker,
an atomic rename; only what linkage wrote is ever removed), whose names are re-exported here:
:func:`write_folder`, :func:`prepare`, :func:`default_folder`, :func:`read_marker`,
:data:`MARKER` and :data:`DEFAULT_BASE`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib import font_manager
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.patches import Polygon
from matplotlib.ticker import MaxNLocator
from PIL import Image, ImageDraw, ImageFont

# The folder writer, re-exported: ``linkage.report.write_folder`` etc. keep working.
from linkage._shared.report_folder import DEFAULT_BASE as DEFAULT_BASE
from linkage._shared.report_folder import MARKER as MARKER
from linkage._shared.report_folder import default_folder as default_folder
from linkage._shared.report_folder import prepare as prepare
from linkage._shared.report_folder import read_marker as read_marker
from linkage._shared.report_folder import write_folder as write_folder
from linkage.drawing import (
    Array,
    Drawing,
    LinkShape,
    clip_to,
    leg_angles,
    mechanism_drawing,
    walker_drawing,
)
from linkage.drives.drive import CrankSchedule
from linkage.report import export
from linkage.report import html as html_report
from linkage.report.figures import Result, crank_phase_deg, format_number, torque_unit, unit_label
from linkage.scene.builders import build_drive
from linkage.synthesis import source_text

__all__ = [
    "DEFAULT_BASE",
    "GIF_DPI",
    "MARKER",
    "PALETTE",
    "SYNTHESIS_SHOWN",
    "TARGET_MARKERS",
    "default_folder",
    "leg_legend",
    "line_style",
    "prepare",
    "read_marker",
    "write",
    "write_folder",
]


def write(res: Result, folder: Path, frames: int = 48, force: bool = False) -> list[Path]:
    r"""Write the report for ``res`` to ``folder``; return the files written (in ``folder``).

    The report is written as :func:`~linkage.report_folder.write_folder` writes any folder: into
    a temporary sibling, its marker last, renamed into place; an existing ``folder`` is replaced
    only with ``force`` and only if linkage wrote it (see :mod:`linkage.report_folder`).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.report import write
    >>> from linkage.runner import run
    >>> from linkage.scene import parse
    >>> scene = parse('units = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...               '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n', name="hoecken")
    >>> res = run(scene)
    >>> tmp = tempfile.TemporaryDirectory()
    >>> sorted(f.name for f in write(res, Path(tmp.name) / "report"))
    ['data.csv', 'data.npz', 'index.html', 'summary.json', 'trajectory.png']
    >>> write(res, Path(tmp.name) / "report")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...report holds an earlier report; pass --force to replace it (nothing...
    >>> len(write(res, Path(tmp.name) / "report", force=True))
    5
    >>> tmp.cleanup()
    """
    return write_folder(
        folder,
        res.scene.name,
        lambda tmp: [p.name for p in _write_files(res, tmp, frames)],
        force,
    )


# -- figures ------------------------------------------------------------------------------------
#
# Every drawing of the linkage (the pose in trajectory.png, each frame of animation.gif) comes
# from one model, ``linkage.drawing.Drawing``, drawn by ``_Pose``: bars as thick lines with pin
# circles, plates as filled polygons, ground pivots with the hatched symbol, slider blocks on
# their guides, walkers' legs on the body with the ground line, stance feet and support polygon.

DPI = 110
GIF_DPI = 80
"""Resolution of the PNG figures and of the animation's frames."""
PALETTE = (
    "#1f77b4",
    "#ff7f0e",
    "#2ca02c",
    "#d62728",
    "#9467bd",
    "#8c564b",
    "#e377c2",
    "#7f7f7f",
    "#bcbd22",
    "#17becf",
    "#393b79",
    "#637939",
    "#7b4173",
    "#000000",
)
"""Line colours, distinct for 14 lines (tab10 and four dark shades); past that, dashed."""

BAR = "#2c3e50"
CRANK = "#c0392b"
PLATE = "#aec7e8"


def line_style(k: int) -> tuple[str, str]:
    """Colour and line style of the ``k``-th line of a plot: distinct for 28 lines.

    Examples
    --------
    >>> from linkage.report import line_style
    >>> line_style(0), line_style(14), line_style(28)
    (('#1f77b4', '-'), ('#1f77b4', '--'), ('#1f77b4', '-'))
    >>> len({line_style(k) for k in range(28)})
    28
    """
    return PALETTE[k % len(PALETTE)], "-" if (k // len(PALETTE)) % 2 == 0 else "--"


def leg_legend(names: Sequence[str], labels: Sequence[str]) -> list[str]:
    """Legend text per leg: its position label, with its own name when that differs.

    Examples
    --------
    >>> from linkage.report import leg_legend
    >>> leg_legend(["A", "R2"], ["L1", "R2"])
    ['L1 (A)', 'R2']
    """
    return [lab if lab == name else f"{lab} ({name})" for name, lab in zip(names, labels)]


def _new_figure(width: float, height: float) -> Any:

    fig = Figure(figsize=(width, height), dpi=DPI)
    FigureCanvasAgg(fig)
    return fig


def _margins(
    fig: Any,
    left: float = 0.85,
    right: float = 0.2,
    bottom: float = 0.6,
    top: float = 0.4,
    gap: float = 0.0,
    rows: int = 1,
) -> None:
    """Set fixed margins in inches (no tight layout: it lays out every tick label twice)."""
    w, h = fig.get_size_inches()
    inner = h - bottom - top - gap * (rows - 1)
    fig.subplots_adjust(
        left=left / w,
        right=1 - right / w,
        bottom=bottom / h,
        top=1 - top / h,
        hspace=gap / (inner / rows) if rows > 1 else 0.2,
    )


def _y_labels_width(fig: Any, ax: Any) -> float:
    """Return the width (inches) of the widest y tick label of ``ax`` at its current limits.

    Laid out as text only (no draw of the figure).
    """
    renderer = fig.canvas.get_renderer()
    widths = [t.get_window_extent(renderer).width for t in ax.get_yticklabels() if t.get_text()]
    return float(max(widths, default=0.0) / fig.dpi)


def _tidy(ax: Any, xlabel: str, ylabel: str) -> None:

    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.xaxis.set_major_locator(MaxNLocator(nbins=6))
    ax.yaxis.set_major_locator(MaxNLocator(nbins=6))
    ax.grid(alpha=0.3)


def _view(ax: Any, d: Drawing, equal: bool = True, margin: float = 0.06) -> None:
    """Axis labels with units and limits from the drawing (joints and paths only)."""
    x0, x1, y0, y1 = d.bounds(margin)
    if not equal and d.feet is not None:
        # Height not to scale: fit the feet's heights and the ground, so a lift shows.
        z = d.feet[..., 1][np.isfinite(d.feet[..., 1])]
        lo = min(float(z.min()), d.ground if d.ground is not None else float(z.min()))
        hi = float(z.max())
        pad = 0.15 * (hi - lo) if hi > lo else 1.0
        y0, y1 = lo - pad, hi + 2 * pad
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal" if equal else "auto", adjustable="box")
    u = unit_label(d.units)
    scale = "" if equal else ", not to scale"
    _tidy(ax, f"{d.axes[0]} ({u})", f"{d.axes[1]} ({u}{scale})")


def _panel_height(d: Drawing, width: float, equal: bool) -> float:
    x0, x1, y0, y1 = d.bounds()
    if not equal:
        return 1.6
    return float(min(max(width * (y1 - y0) / (x1 - x0), 1.4), 5.0))


def _ground_symbol(ax: Any, d: Drawing, size: float) -> None:
    """Draw the hatched ground symbol under every pivot (static)."""
    if not d.pivots:
        return
    row = _reference_row(d)
    tri, lines = [], []
    for j in d.pivots:
        x, y = row[j]
        if not (np.isfinite(x) and np.isfinite(y)):
            continue
        s = size
        tri.append([(x, y), (x - 0.6 * s, y - s), (x + 0.6 * s, y - s)])
        lines.append([(x - s, y - s), (x + s, y - s)])
        for k in range(5):
            a = x - s + k * 0.5 * s
            lines.append([(a, y - s), (a - 0.35 * s, y - 1.45 * s)])
    ax.add_collection(PolyCollection(tri, facecolors="white", edgecolors="k", lw=1, zorder=2))
    ax.add_collection(LineCollection(lines, colors="k", lw=1, zorder=2))


def _reference_row(d: Drawing) -> Array:
    ok = np.isfinite(d.positions).all(axis=(1, 2))
    row: Array = d.positions[int(np.argmax(ok))]
    return row


def _size(d: Drawing) -> float:
    x0, x1, y0, y1 = d.bounds(0.0)
    return 0.035 * max(x1 - x0, y1 - y0)


class _Pose:
    """The moving artists of a drawing, updated to a sample by :meth:`update`.

    The static ones — paths, ground, body, pivots — are drawn once by :func:`_static`.
    """

    def __init__(self, ax: Any, d: Drawing, animated: bool, faint: bool = False) -> None:

        self.d = d
        self.size = _size(d)
        alpha = 0.45 if faint else 1.0
        walker = bool(d.legs)
        lw = 2.0 if walker else 3.0
        self.bars = [k for k in d.links if k.kind == "bar"]
        self.plates = [k for k in d.links if k.kind == "plate"]
        driver = _driver_link(d)

        def colour(k: LinkShape) -> str:
            if k.leg is not None:
                return line_style(k.leg)[0]
            return CRANK if k is driver else BAR

        self.bar_art = LineCollection(
            [], colors=[colour(k) for k in self.bars], linewidths=lw, alpha=alpha, zorder=4
        )
        self.bar_art.set_capstyle("round")
        self.plate_art = PolyCollection(
            [],
            facecolors=[PLATE if k.leg is None else colour(k) for k in self.plates],
            edgecolors=[BAR if k.leg is None else colour(k) for k in self.plates],
            linewidths=1.5,
            alpha=0.75 * alpha,
            zorder=3,
        )
        moving = sorted({j for k in self.bars + self.plates for j in k.joints})
        self.pin_idx = np.array(moving, dtype=int)
        (self.pins,) = ax.plot(
            [], [], "o", ms=3.5 if walker else 5, mfc="white", mec="k", mew=1, alpha=alpha, zorder=5
        )
        # Only the artists there is something to draw with (each costs time in every frame).
        self.artists: list[Any] = [self.plate_art] if self.plates else []
        self.artists += [self.bar_art, self.pins]
        for art in self.artists[:-1]:
            ax.add_collection(art)
        self.trace: Any = None
        if d.trace is not None:
            (self.trace,) = ax.plot([], [], "o", ms=6, color="tab:red", alpha=alpha, zorder=6)
            self.artists.append(self.trace)
        self.blocks: Any = None
        if d.sliders:
            self.guides = LineCollection([], colors="0.35", linewidths=1.2, zorder=2)
            self.blocks = PolyCollection([], facecolors="#f5cba7", edgecolors="k", zorder=4.5)
            # Each guide spans the block's whole travel (and its origin), the same every frame.
            self.travel = []
            for sl in d.sliders:
                rel = d.positions[:, sl.joint] - d.positions[:, sl.origin]
                along = np.einsum("ij,ij->i", rel, sl.direction)
                along = along[np.isfinite(along)]
                lo = min(0.0, float(along.min())) if len(along) else 0.0
                hi = max(0.0, float(along.max())) if len(along) else 0.0
                self.travel.append((lo - 2.5 * self.size, hi + 2.5 * self.size))
            ax.add_collection(self.guides)
            ax.add_collection(self.blocks)
            self.artists += [self.guides, self.blocks]
        self.down: Any = None
        if d.feet is not None:
            (self.down,) = ax.plot([], [], "s", ms=6, color="k", zorder=7, label="stance foot")
            (self.up,) = ax.plot(
                [], [], "o", ms=5, mfc="white", mec="0.3", zorder=7, label="foot in swing"
            )
            self.artists += [self.down, self.up]
        self.support: Any = None
        if d.support is not None:
            self.support = Polygon(
                np.zeros((1, 2)),
                closed=True,
                fc="tab:green",
                alpha=0.18,
                ec="tab:green",
                zorder=1,
                label="support polygon",
            )
            ax.add_patch(self.support)
            self.artists.append(self.support)
        for a in self.artists:
            a.set_animated(animated)

    def update(self, i: int) -> list[Any]:
        d = self.d
        p = d.positions[i]
        self.bar_art.set_segments([p[list(k.joints)] for k in self.bars])
        if self.plates:
            self.plate_art.set_verts([p[list(k.joints)] for k in self.plates])
        self.pins.set_data(p[self.pin_idx, 0], p[self.pin_idx, 1])
        if self.trace is not None and d.trace is not None:
            self.trace.set_data([p[d.trace, 0]], [p[d.trace, 1]])
        if self.blocks is not None:
            s = self.size
            guides, blocks = [], []
            for sl, (lo, hi) in zip(d.sliders, self.travel):
                u = sl.direction[i]
                n = np.array([-u[1], u[0]])
                o, c = p[sl.origin], p[sl.joint]
                guides.append([o + lo * u, o + hi * u])
                blocks.append(
                    [
                        c - 1.2 * s * u - 0.7 * s * n,
                        c + 1.2 * s * u - 0.7 * s * n,
                        c + 1.2 * s * u + 0.7 * s * n,
                        c - 1.2 * s * u + 0.7 * s * n,
                    ]
                )
            self.guides.set_segments(guides)
            self.blocks.set_verts(blocks)
        if self.down is not None and d.feet is not None and d.stance is not None:
            f, st = d.feet[i], d.stance[i]
            self.down.set_data(f[st, 0], f[st, 1])
            self.up.set_data(f[~st, 0], f[~st, 1])
        if self.support is not None and d.support is not None:
            hull = d.support[i]
            hull = hull[np.isfinite(hull).all(axis=1)]
            self.support.set_xy(hull if len(hull) else np.full((1, 2), np.nan))
        return self.artists


def _driver_link(d: Drawing) -> LinkShape | None:
    """Return the crank: the first moving link of a mechanism's program."""
    for k in d.links:
        if k.kind != "ground" and k.leg is None:
            return k
    return None


def _static(ax: Any, d: Drawing, paths: bool = True, labels: bool = True) -> list[Any]:
    """Draw the parts of a drawing that do not move; return the paths' lines (for a legend).

    Those are the traced paths, ground line, body, pivots and CG.
    """
    handles: list[Any] = []
    size = _size(d)
    if d.ground is not None:
        _x0, _x1, y0, _ = d.bounds()
        ax.axhspan(y0 - 10 * size, d.ground, fc="none", ec="0.65", hatch="////", lw=0, zorder=0)
        ax.axhline(d.ground, color="#7f5f3f", lw=2, zorder=1, label="ground")
    if d.body is not None:
        ax.fill(d.body[:, 0], d.body[:, 1], fc="0.88", ec="0.45", lw=1, zorder=1, label="body")
    if paths:
        for k, (name, path) in enumerate(d.paths.items()):
            colour, ls = line_style(k) if d.legs else ("k", "-")
            lw = 1.1 if d.legs else 1.5
            handles += ax.plot(
                path[:, 0], path[:, 1], ls=ls, color=colour, lw=lw, zorder=2, label=name
            )
    _ground_symbol(ax, d, size)
    if d.cg is not None:
        ax.plot(*d.cg, "P", ms=9, color="tab:red", mec="k", zorder=8, label="CG projection")
    if labels and d.legs and d.axes == ("x", "y"):
        row = _reference_row(d)
        for li, lab in enumerate(d.leg_labels):
            mine = [j for k in d.links if k.leg == li and k.kind == "ground" for j in k.joints]
            if not mine:
                continue
            x, y = row[mine].mean(axis=0)
            # Inside the body, halfway from the leg's mount to the centre line (clear of the
            # ground symbols hanging from the mount).
            mid = d.cg[1] if d.cg is not None else 0.0
            ax.text(
                x,
                y + 0.55 * (mid - y),
                lab,
                ha="center",
                va="center",
                fontsize=8,
                fontweight="bold",
                color=line_style(li)[0],
                zorder=9,
            )
    return handles


def _pose_sample(d: Drawing) -> int:
    """Return the sample a static figure shows.

    A sixth of the run in (a crank along the ground line at θ = 0 hides it), or the first assembled
    one.
    """
    ok = np.asarray(np.isfinite(d.positions).all(axis=(1, 2)), dtype=bool)
    k = ok.shape[0] // 6
    return k if bool(ok[k]) else int(np.argmax(ok))


def _walker_views(res: Result, units: str) -> list[tuple[Drawing, bool]]:
    """Build the side and top views of a run's walker, each with whether it is drawn to scale.

    The side view of legs that all lie in the horizontal plane is only a few pad heights tall.
    """
    walker, sim = res.walker, res.simulation
    assert walker is not None and sim is not None
    drive, _ = build_drive(res.scene, walker.legs[0].linkage)
    theta = leg_angles(walker, sim, drive, isinstance(drive, CrankSchedule))
    side = walker_drawing(walker, sim, "side", theta, units)
    top = walker_drawing(walker, sim, "top", theta, units)
    sagittal = any(leg.plane == "sagittal" for leg in walker.legs)
    return [(side, sagittal), (top, True)] if sagittal else [(top, True), (side, False)]


def _drawing_figure(
    views: list[tuple[Drawing, bool]], width: float, top: float = 0.4, bottom: float = 0.6
) -> tuple[Any, list[Any]]:
    """Make a figure with one panel per view, each as tall as its drawing at the figure's width."""
    heights = [_panel_height(d, width - 1.05, eq) for d, eq in views]
    gap = 0.85
    fig = _new_figure(width, sum(heights) + top + bottom + gap * (len(views) - 1))
    axes = fig.subplots(len(views), 1, gridspec_kw={"height_ratios": heights}, squeeze=False)
    _margins(fig, top=top, bottom=bottom, gap=gap, rows=len(views))
    return fig, [a for row in axes for a in row]


def _mechanism_drawing(res: Result, units: str) -> Drawing:

    assert res.mechanism is not None and res.sweep is not None
    return mechanism_drawing(res.mechanism, res.sweep, units)


def _write_files(res: Result, folder: Path, frames: int) -> list[Path]:
    """Write the report's files into the (new, empty) ``folder``; returns them."""
    started = time.perf_counter()
    files: list[Path] = []
    scene = res.scene
    units = scene.units
    u = unit_label(units)

    def save(fig: Any, name: str) -> None:
        path = folder / name
        fig.savefig(path, dpi=DPI, pil_kwargs={"compress_level": 2})
        files.append(path)

    if res.synthesis is not None:
        save(_synthesis(res), "synthesis.png")
        files.append(html_report.write_index(res, folder, files))
        res.stages["report"] = time.perf_counter() - started
        return _with_data(res, folder, files)

    t = res.time
    sim = res.simulation
    walker_views = _walker_views(res, units) if sim is not None else []
    drawing = _mechanism_drawing(res, units) if res.sweep is not None else None
    if scene.wants("trajectory"):
        if sim is not None:
            save(_walker_trajectory(res, walker_views), "trajectory.png")
        else:
            assert drawing is not None
            save(_trajectory(res, drawing), "trajectory.png")

    rates = res.rates
    if rates is not None and scene.wants("velocity", "acceleration"):
        fig = _new_figure(6, 5)
        axes = fig.subplots(2, 1, sharex=True)
        axes[0].plot(t, np.linalg.norm(rates.velocity, axis=1), "tab:blue")
        axes[1].plot(t, np.linalg.norm(rates.acceleration, axis=1), "tab:red")
        _tidy(axes[0], "", f"speed ({u}/s)")
        _tidy(axes[1], "time (s)", f"acceleration ({u}/s²)")
        axes[0].set_title(f"{scene.name}: trace point {rates.trace} against time")
        _margins(fig, gap=0.15, rows=2)
        save(fig, "rates.png")

    if res.forces is not None:
        fig = _new_figure(6, 4)
        ax = fig.subplots()
        ax.plot(np.degrees(np.mod(res.theta, 2 * math.pi)), res.forces.torque, ".", ms=2)
        _tidy(ax, "crank angle (deg)", f"driver torque ({torque_unit(scene)})")
        ax.set_xlim(0, 360)
        ax.set_title(f"{scene.name}: torque against crank angle (Newton–Euler)")
        _margins(fig)
        save(fig, "torque.png")

    if res.cam is not None:
        p = res.cam
        fig = _new_figure(5, 5.25)
        ax = fig.subplots()
        ax.plot(p.profile[:, 0], p.profile[:, 1], "k-", label="profile")
        ax.plot(p.pitch[:, 0], p.pitch[:, 1], "--", color="tab:gray", label="pitch curve")
        ax.plot([0], [0], "+", color="k", ms=10, label="cam axis")
        ax.set_aspect("equal")
        _tidy(ax, f"x ({u})", f"y ({u})")
        # Below the axes, in one row: inside, it covered the cam axis at the centre.
        fig.legend(fontsize=7, loc="lower center", ncol=3, frameon=False)
        ax.set_title(f"{scene.name}: cam")
        _margins(fig, bottom=0.85)
        save(fig, "cam.png")

    if sim is not None:
        names = leg_legend(sim.legs, walker_views[0][0].leg_labels)
        if scene.wants("gait"):
            save(_gait(res, names), "gait.png")
        if scene.wants("stability"):
            fig = _new_figure(6, 3.5)
            ax = fig.subplots()
            m = np.where(np.isfinite(sim.margin), sim.margin, np.nan)
            ax.plot(t, m, "tab:green", label="margin")
            ax.fill_between(t, m, 0, where=m < 0, color="tab:red", alpha=0.3, label="unstable")
            ax.axhline(0, color="k", lw=0.8)
            _tidy(ax, "time (s)", f"stability margin ({u})")
            ax.set_xlim(t[0], t[-1])
            ax.set_title(f"{scene.name}: static stability margin (CG projection)")
            _margins(fig)
            save(fig, "stability.png")
        if scene.wants("slip"):
            fig = _new_figure(6, 3.5)
            ax = fig.subplots()
            ax.plot(t, sim.spread, "tab:purple")
            _tidy(ax, "time (s)", f"stance speed spread ({u}/s)")
            ax.set_xlim(t[0], t[-1])
            ax.set_title(f"{scene.name}: foot slip (spread of stance-foot speeds)")
            _margins(fig)
            save(fig, "slip.png")

    if scene.wants("animation"):
        if sim is not None:
            views = walker_views
        else:
            assert drawing is not None
            views = [(drawing, True)]
        files.append(_animation(res, views, folder / "animation.gif", frames))

    # The page embeds the plots and redraws the animation from the drawings already built.
    shown = [d for d, _ in walker_views] or ([drawing] if drawing is not None else None)
    pngs = [p for p in files if p.suffix == ".png"]
    files.append(html_report.write_index(res, folder, pngs, shown))
    res.stages["report"] = time.perf_counter() - started
    return _with_data(res, folder, files)


def _with_data(res: Result, folder: Path, files: list[Path]) -> list[Path]:
    """Write the data files last, their own time the stage ``data files``, measured after the fact.

    Last, because summary.json lists every file in the folder and the stage times up to the
    report's.
    """
    started = time.perf_counter()
    files.extend(export.write_data(res, folder, cad=res.scene.wants("cad")))
    res.stages["data files"] = time.perf_counter() - started
    return files


TARGET_MARKERS: dict[str, Any] = dict(
    ls="none", marker="o", ms=5, mfc="white", mec="k", mew=1.2, zorder=7
)
"""How a synthesis target and a scene's reference points are drawn: white dots ringed black."""


def _trajectory(res: Result, d: Drawing) -> Any:
    """Plot the trace path with the mechanism drawn at its first assembled pose.

    The plot also shows the straight part and the centres of curvature that fall in the view.
    """
    s = res.sweep
    assert s is not None
    fig, (ax,) = _drawing_figure([(d, True)], 6.4, bottom=0.95)
    _static(ax, d)
    i0 = _pose_sample(d)
    _Pose(ax, d, animated=False, faint=True).update(i0)
    if res.straight is not None and res.straight.count:
        idx = res.straight.indices
        ax.plot(
            s.point[idx, 0],
            s.point[idx, 1],
            "-",
            lw=6,
            color="tab:green",
            alpha=0.45,
            label="straight part",
            zorder=1.5,
        )
    reference = res.arrays.get("reference")
    _view(ax, d)
    if reference is not None:
        gap = next((r for r in res.figures if r[0] == "reference points to the trace"), None)
        value = getattr(gap, "value", None)
        within = ""
        if gap is not None and isinstance(value, float):
            within = f", within {format_number(value, digits=3)} {gap[2]}".rstrip()
        # Points the trace misses stay in view, up to three times the linkage's extent; those
        # farther (a reference in other units or another frame) are counted, not drawn.
        x0, x1 = ax.get_xlim()
        y0, y1 = ax.get_ylim()
        w = max(x1 - x0, y1 - y0)
        box = (x0 - w, x1 + w, y0 - w, y1 + w)
        shown = clip_to(reference, box)
        ok = np.isfinite(shown).all(axis=1)
        off = len(reference) - int(ok.sum())
        if ok.any():
            lo, hi = shown[ok].min(axis=0), shown[ok].max(axis=0)
            g = 0.03 * w
            ax.set_xlim(min(x0, lo[0] - g), max(x1, hi[0] + g))
            ax.set_ylim(min(y0, lo[1] - g), max(y1, hi[1] + g))
        # As synthesis.png draws a target.
        ax.plot(
            shown[:, 0],
            shown[:, 1],
            **TARGET_MARKERS,
            label=f"reference points ({len(reference)}){within}"
            + (f" ({off} off the plot)" if off else ""),
        )
    if res.geometry is not None and "curvature" in res.geometry.outputs:
        c = res.geometry.curvature_centre
        x0, x1 = ax.get_xlim()
        y0, y1 = ax.get_ylim()
        shown = clip_to(c, (x0, x1, y0, y1))
        inside = int(np.isfinite(shown).all(axis=1).sum())
        off = int(np.isfinite(c).all(axis=1).sum()) - inside
        note = f" ({off} off the plot)" if off else ""
        ax.plot(
            shown[:, 0],
            shown[:, 1],
            ".",
            ms=2,
            color="tab:orange",
            label=f"centres of curvature{note}",
            zorder=2,
        )
    theta = math.degrees(float(res.theta[i0])) % 360
    # A crank with a phase (an exported synthesis candidate's) is at θ + phase: say where, as
    # synthesis.png names the crank's own angle.
    phase = crank_phase_deg(res.scene)
    crank = f" (crank at {(theta + phase) % 360:.0f}°)" if phase % 360 else ""
    ax.set_title(
        f"{res.scene.name}: path of {s.trace}, pose at θ = {theta:.0f}°{crank}", fontsize=10
    )
    # Below the plot, where it cannot hide the path or the linkage.
    fig.legend(loc="lower center", ncol=3, fontsize=7, frameon=False)
    return fig


SYNTHESIS_SHOWN = 8
"""Most candidates ``synthesis.png`` draws (the best first); the rest are in the CSV."""


def _synthesis(res: Result) -> Any:
    """Plot ``synthesis.png``: the target points and every candidate's coupler curve.

    Each curve is named in the legend with its largest error, the best candidate drawn at one pose
    with its ground pivots; to scale, limits from the target and the best candidate's links and
    curve (the other curves may leave the view, and their legend entries say so: they are
    compared where the target is).
    """
    run = res.synthesis
    assert run is not None
    units = res.scene.units
    u = unit_label(units)
    d = export.synthesis_drawing(res)
    # The best candidate's links and curve, and the target, set the view (not the target
    # path the drawing carries: it is drawn as markers below).
    view = replace(d, paths={k: v for k, v in d.paths.items() if k != "target"})
    x0, x1, y0, y1 = view.bounds(0.0)
    lo = np.minimum([x0, y0], run.target.min(axis=0))
    hi = np.maximum([x1, y1], run.target.max(axis=0))
    g = 0.06 * float(max(hi - lo))
    box = (float(lo[0] - g), float(hi[0] + g), float(lo[1] - g), float(hi[1] + g))
    width = 6.4
    shown = run.candidates[:SYNTHESIS_SHOWN]
    fig = _new_figure(width, 4.0)  # sized below, once the y tick labels are known
    ax = fig.subplots()
    size = _size(view)
    _ground_symbol(ax, view, size)
    pose = export.synthesis_pose(d)
    _Pose(ax, view, animated=False, faint=True).update(pose)
    for k in reversed(range(len(shown))):
        colour, ls = line_style(k)
        c = shown[k]
        err = format_number(c.error, digits=3)
        xy = run.curves[k]
        # A curve that strays far from the target leaves the view: the legend says so.
        out = bool(
            np.any((xy[:, 0] < box[0]) | (xy[:, 0] > box[1]))
            or np.any((xy[:, 1] < box[2]) | (xy[:, 1] > box[3]))
        )
        ax.plot(
            run.curves[k][:, 0],
            run.curves[k][:, 1],
            ls=ls,
            color=colour,
            lw=2.2 if k == 0 else 1.3,
            zorder=3.5 if k == 0 else 3 - 0.01 * k,
            label=f"#{k + 1}: max error {err} {u}, {c.grashof}, {source_text(c.source)}"
            f"{' (leaves the view)' * out}",
        )
    t = run.target
    ax.plot(
        t[:, 0],
        t[:, 1],
        **TARGET_MARKERS,
        label=f"target ({len(t)} points, {'closed' if run.closed else 'open'})",
    )
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    ax.set_aspect("equal", adjustable="box")  # the limits stay; the figure fits them
    _tidy(ax, f"x ({u})", f"y ({u})")
    # Room on the left for the y tick labels ("−640000" for a target 1e5 mm across) and the
    # axis label; the plot's height follows the width that leaves, to scale.
    left = max(0.85, _y_labels_width(fig, ax) + 0.45)
    ratio = (box[3] - box[2]) / (box[1] - box[0])
    height = float(min(max((width - left - 0.2) * ratio, 2.2), 6.0))
    drawn = (
        f"{len(run.candidates)} candidate coupler curves"
        if len(shown) == len(run.candidates)
        else f"{len(shown)} of {len(run.candidates)} candidate coupler curves (all in "
        "candidates.csv)"
    )
    theta = math.degrees(float(run.best.theta[pose])) % 360
    title = ax.set_title(
        f"{res.scene.name}: target and {drawn}; #1 drawn at θ = {theta:.0f}°", fontsize=10
    )
    handles, labels = ax.get_legend_handles_labels()
    # Target first, then the candidates best first, down the first column and on down the
    # second (as matplotlib fills them): read either column downwards, the ranks ascend.
    order = [len(labels) - 1, *reversed(range(len(labels) - 1))]
    renderer = fig.canvas.get_renderer()
    room = width * fig.dpi - 8  # px: the legend and the title stay inside the figure
    legend, ncol = None, 1
    for ncol in (1,) if len(order) <= 3 else (2, 1):
        if legend is not None:
            legend.remove()
        legend = fig.legend(
            [handles[i] for i in order],
            [labels[i] for i in order],
            loc="lower center",
            ncol=ncol,
            fontsize=7,
            frameon=False,
        )
        if legend.get_window_extent(renderer).width <= room:
            break  # two columns of long labels (an open target's) overran both edges
    rows = math.ceil(len(order) / ncol)
    bottom = 0.55 + 0.2 * rows
    fig.set_size_inches(width, height + 0.4 + bottom)
    _margins(fig, left=left, top=0.4, bottom=bottom)
    # The title is centred over the plot as laid out (the equal aspect may narrow it): one too
    # wide for the figure (a long scene name at top = 50 overran both edges) is set smaller.
    for _ in range(3):
        fig.draw_without_rendering()  # the layout as drawn: the title where it will be
        box_px = title.get_window_extent()
        centre = 0.5 * (box_px.x0 + box_px.x1)
        fits = 2 * min(centre, fig.bbox.width - centre) - 8
        if box_px.width <= fits:
            break
        title.set_fontsize(title.get_fontsize() * fits / box_px.width)
    return fig


def _walker_trajectory(res: Result, views: list[tuple[Drawing, bool]]) -> Any:
    """Foot paths in the side and top views, with the legs drawn at the first sample."""
    fig, axes = _drawing_figure(views, 6.4, bottom=1.25)
    handles: list[Any] = []
    t0 = float(res.time[0]) if len(res.time) else 0.0
    for ax, (d, equal) in zip(axes, views):
        lines = _static(ax, d)
        handles = handles or lines
        _Pose(ax, d, animated=False, faint=True).update(0)
        _view(ax, d, equal)
        what = "side view" if d.axes[1] == "z" else "top view"
        ax.set_title(
            f"{res.scene.name}: foot paths, {what} (body frame; legs at t = {t0:g} s)",
            fontsize=10,
        )
    d0 = views[0][0]
    labels = leg_legend(d0.legs, d0.leg_labels)
    # The symbols of the drawing (body, ground, feet in stance and in swing, support polygon,
    # centre of gravity), each once, after the legs' colours.
    legs = {*labels, *d0.legs, *(d0.leg_labels or ())}
    symbols: dict[str, Any] = {}
    for ax in axes:
        for h, name in zip(*ax.get_legend_handles_labels()):
            if not name.startswith("_") and name not in legs:
                symbols.setdefault(name, h)
    fig.legend(
        [*handles, *symbols.values()],
        [*labels, *symbols],
        loc="lower center",
        ncol=min(6, max(len(labels), len(symbols))),
        fontsize=7,
        frameon=False,
    )
    return fig


def _gait(res: Result, names: list[str]) -> Any:
    sim = res.simulation
    assert sim is not None
    t = res.time
    fig = _new_figure(6, max(2.2, 0.8 + 0.4 * len(sim.legs)))
    ax = fig.subplots()
    step = t[1] - t[0] if len(t) > 1 else 1.0
    for i, (_leg, bars) in enumerate(sim.gait_diagram()):
        ax.broken_barh(
            [(a, max(b - a, step)) for a, b in bars], (i - 0.35, 0.7), color=line_style(i)[0]
        )
    ax.set_yticks(range(len(sim.legs)), names)
    ax.invert_yaxis()
    ax.set_xlabel("time (s)")
    ax.set_title(f"{res.scene.name}: gait diagram (bars: stance)")
    ax.set_xlim(t[0], t[-1])
    ax.grid(alpha=0.3, axis="x")
    _margins(fig, left=0.9)
    return fig


def _animation(res: Result, views: list[tuple[Drawing, bool]], path: Path, frames: int) -> Path:
    """Write the GIF: static parts drawn once, each frame drawing only the moving artists.

    Each frame restores the static parts and draws the moving artists (blitting on the Agg canvas),
    its caption written with Pillow, and every frame quantised to one shared palette.
    """
    d0 = views[0][0]
    walker = bool(d0.legs)
    fig, axes = _drawing_figure(
        views, 5.6 if walker else 5.0, top=0.55, bottom=0.95 if walker else 0.6
    )
    poses = []
    handles: list[Any] = []
    for ax, (d, equal) in zip(axes, views):
        lines = _static(ax, d, labels=True)
        handles = handles or lines
        _view(ax, d, equal)
        poses.append(_Pose(ax, d, animated=True))
    if walker:
        for ax, (d, _) in zip(axes, views):
            what = "side" if d.axes[1] == "z" else "top"
            ax.set_title(f"{what} view (body frame)", fontsize=9)
        fig.legend(
            handles,
            leg_legend(d0.legs, d0.leg_labels),
            loc="lower center",
            ncol=min(6, len(d0.legs)),
            fontsize=7,
            frameon=False,
        )
    fig.set_dpi(GIF_DPI)
    canvas = fig.canvas
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    # Frames spread over the samples that assembled (a linkage that cannot turn fully skips
    # the angles where it does not exist).
    ok = np.flatnonzero(np.isfinite(d0.positions).all(axis=(1, 2)))
    if len(ok) < 2:
        ok = np.arange(len(res.time))
    pick = ok[np.linspace(0, len(ok) - 1, max(2, min(frames, len(ok)))).astype(int)]
    sim = res.simulation
    font = _caption_font(round(11 * GIF_DPI / 72))
    images = []
    for i in pick:
        canvas.restore_region(background)
        for pose in poses:
            for a in pose.update(int(i)):
                fig.draw_artist(a)
        w, h = canvas.get_width_height()
        im = Image.frombuffer("RGBA", (w, h), canvas.buffer_rgba(), "raw", "RGBA", 0, 1)
        im = im.convert("RGB")
        if sim is not None:
            down = int(sim.stance[i].sum())
            caption = f"{res.scene.name}: t = {res.time[i]:.2f} s, {down} feet down"
        else:
            theta = math.degrees(float(res.theta[i])) % 360
            caption = f"{res.scene.name}: θ = {theta:.0f}°, t = {res.time[i]:.3f} s"
        ImageDraw.Draw(im).text((im.width // 2, 8), caption, fill=(0, 0, 0), font=font, anchor="mt")
        images.append(im)
    # One palette for every frame, from a strip of a few frames (so all colours are in it).
    sample = images[:: max(1, len(images) // 4)][:4]
    strip = Image.new("RGB", (sum(im.width for im in sample), sample[0].height))
    x = 0
    for im in sample:
        strip.paste(im, (x, 0))
        x += im.width
    palette = strip.quantize(colors=96, method=Image.Quantize.FASTOCTREE)
    gif = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
    gif[0].save(path, save_all=True, append_images=gif[1:], duration=83, loop=0)
    return path


def _caption_font(size: int) -> Any:
    """Matplotlib's own sans-serif font for Pillow (Pillow's default if it cannot be read)."""
    try:
        return ImageFont.truetype(font_manager.findfont("DejaVu Sans"), size)
    except OSError:
        return ImageFont.load_default(size)
