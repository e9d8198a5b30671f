"""The report folder of a run: plots (PNG), an animation (GIF), the data (CSV, NPZ) and a JSON
summary — only the files the scene's outputs call for."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from linkage._core import LinkageError
from linkage.runner import Result


def prepare(folder: Path, force: bool) -> None:
    """Make sure the report can be written without losing anything: an existing folder is an
    error unless ``force`` (then it is replaced)."""
    if folder.exists():
        if not force:
            raise LinkageError(f"{folder} exists; pass --force to replace it (nothing was written)")
        if not folder.is_dir():
            raise LinkageError(f"{folder} exists and is not a folder")
        shutil.rmtree(folder)


def write(res: Result, folder: Path, frames: int = 48) -> list[Path]:
    """Write the report for ``res`` into ``folder`` (created); returns the files written."""
    import matplotlib

    matplotlib.use("Agg")
    import time

    import matplotlib.pyplot as plt

    started = time.perf_counter()
    folder.mkdir(parents=True)
    files: list[Path] = []
    scene = res.scene

    def save(fig: Any, name: str) -> None:
        path = folder / name
        fig.tight_layout()
        fig.savefig(path, dpi=110)
        plt.close(fig)
        files.append(path)

    t = res.time
    if scene.wants("trajectory"):
        fig, ax = plt.subplots(figsize=(6, 4.5))
        if res.simulation is not None:
            for i, leg in enumerate(res.simulation.legs):
                sim_feet = res.simulation.feet
                ax.plot(sim_feet[:, i, 0], sim_feet[:, i, 2], lw=1, label=leg)
            ax.set_xlabel("x (body frame)")
            ax.set_ylabel("z")
            ax.set_title("foot paths, side view")
            ax.legend(fontsize=7)
        else:
            s = res.sweep
            assert s is not None
            ax.plot(s.point[:, 0], s.point[:, 1], "k-", lw=1.5, label=f"trace {s.trace}")
            if res.geometry is not None and "curvature" in res.geometry.outputs:
                c = res.geometry.curvature_centre
                ax.plot(
                    c[:, 0], c[:, 1], ".", ms=2, color="tab:orange", label="centres of curvature"
                )
            if res.straight is not None and res.straight.count:
                idx = res.straight.indices
                ax.plot(
                    s.point[idx, 0],
                    s.point[idx, 1],
                    "-",
                    lw=3,
                    color="tab:green",
                    alpha=0.6,
                    label="straight part",
                )
            ax.set_title(f"{scene.name}: trace path")
            ax.legend(fontsize=7)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        save(fig, "trajectory.png")

    rates = res.rates
    if rates is not None and scene.wants("velocity", "acceleration"):
        fig, axes = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
        axes[0].plot(t, np.linalg.norm(rates.velocity, axis=1), "tab:blue")
        axes[0].set_ylabel("speed")
        axes[1].plot(t, np.linalg.norm(rates.acceleration, axis=1), "tab:red")
        axes[1].set_ylabel("acceleration")
        axes[1].set_xlabel("time (s)")
        axes[0].set_title(f"{scene.name}: trace point against time")
        for a in axes:
            a.grid(alpha=0.3)
        save(fig, "rates.png")

    if res.forces is not None:
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(
            np.degrees(np.mod(res.theta, 2 * math.pi)),
            res.forces.torque,
            ".",
            ms=2,
            label="Newton–Euler",
        )
        ax.set_xlabel("crank angle (deg)")
        ax.set_ylabel("driver torque")
        ax.set_title(f"{scene.name}: torque against crank angle")
        ax.grid(alpha=0.3)
        save(fig, "torque.png")

    if res.cam is not None:
        p = res.cam
        fig, ax = plt.subplots(figsize=(5, 5))
        ax.plot(p.profile[:, 0], p.profile[:, 1], "k-", label="profile")
        ax.plot(p.pitch[:, 0], p.pitch[:, 1], "--", color="tab:gray", label="pitch curve")
        ax.set_aspect("equal")
        ax.legend(fontsize=7)
        ax.set_title("cam")
        save(fig, "cam.png")

    sim = res.simulation
    if sim is not None and scene.wants("gait"):
        fig, ax = plt.subplots(figsize=(6, max(2.0, 0.5 + 0.4 * len(sim.legs))))
        for i, (_leg, bars) in enumerate(sim.gait_diagram()):
            ax.broken_barh(
                [(a, max(b - a, t[1] - t[0])) for a, b in bars], (i - 0.35, 0.7), color="k"
            )
        ax.set_yticks(range(len(sim.legs)), sim.legs)
        ax.set_xlabel("time (s)")
        ax.set_title("gait diagram (bars: stance)")
        ax.set_xlim(t[0], t[-1])
        save(fig, "gait.png")
    if sim is not None and scene.wants("stability"):
        fig, ax = plt.subplots(figsize=(6, 3.5))
        m = np.where(np.isfinite(sim.margin), sim.margin, np.nan)
        ax.plot(t, m, "tab:green")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("stability margin")
        ax.set_title("static stability margin (CG projection)")
        ax.grid(alpha=0.3)
        save(fig, "stability.png")
    if sim is not None and scene.wants("slip"):
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot(t, sim.spread, "tab:purple")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("stance speed spread")
        ax.set_title("foot slip: spread of stance-foot speeds")
        ax.grid(alpha=0.3)
        save(fig, "slip.png")

    if scene.wants("animation"):
        files.append(_animation(res, folder / "animation.gif", frames))

    res.stages["report"] = time.perf_counter() - started
    files.extend(_data(res, folder))
    return files


def _animation(res: Result, path: Path, frames: int) -> Path:
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    fig, ax = plt.subplots(figsize=(4, 3.5))
    n = len(res.time)
    pick = np.linspace(0, n - 1, max(2, min(frames, n))).astype(int)
    ax.set_aspect("equal", adjustable="box")
    if res.simulation is not None:
        sim = res.simulation
        xs, zs = sim.feet[:, :, 0], sim.feet[:, :, 2]
        ax.set_xlim(np.nanmin(xs) - 0.05 * np.ptp(xs), np.nanmax(xs) + 0.05 * np.ptp(xs))
        ax.set_ylim(
            min(np.nanmin(zs), 0) - 0.1 * np.ptp(zs), max(np.nanmax(zs), 0) + 0.1 * np.ptp(zs)
        )
        (feet,) = ax.plot([], [], "o")
        (body,) = ax.plot([], [], "k-", lw=3)

        def draw(k: int) -> Any:
            i = pick[k]
            down = sim.stance[i]
            feet.set_data(xs[i], zs[i])
            feet.set_color("k")
            x0, x1 = np.nanmin(xs), np.nanmax(xs)
            body.set_data([x0, x1], [0, 0])
            ax.set_title(f"t = {res.time[i]:.2f} s, {int(down.sum())} feet down")
            return feet, body
    else:
        s = res.sweep
        assert s is not None
        j = s.joints
        ax.plot(s.point[:, 0], s.point[:, 1], "-", color="tab:gray", lw=1)
        fin = j[np.isfinite(j[:, :, 0])]
        ax.set_xlim(fin[:, 0].min() - 1, fin[:, 0].max() + 1)
        ax.set_ylim(fin[:, 1].min() - 1, fin[:, 1].max() + 1)
        (links,) = ax.plot([], [], "o-", color="k", lw=2, ms=4)

        def draw(k: int) -> Any:
            i = pick[k]
            links.set_data(j[i, :, 0], j[i, :, 1])
            ax.set_title(f"θ = {math.degrees(res.theta[i]) % 360:.0f}°")
            return (links,)

    anim = FuncAnimation(fig, draw, frames=len(pick), blit=False)
    anim.save(path, writer=PillowWriter(fps=12))
    plt.close(fig)
    return path


def _data(res: Result, folder: Path) -> list[Path]:
    arrays = {k: np.asarray(v) for k, v in res.arrays.items()}
    npz = folder / "data.npz"
    np.savez_compressed(npz, **arrays)  # type: ignore[arg-type]
    # CSV: one row per sample, the per-sample scalar and 2-vector series.
    n = len(res.time)
    cols: dict[str, np.ndarray] = {}
    for k, v in arrays.items():
        if v.shape[:1] != (n,):
            continue
        if v.ndim == 1:
            cols[k] = v
        elif v.ndim == 2 and v.shape[1] == 2:
            cols[f"{k}_x"], cols[f"{k}_y"] = v[:, 0], v[:, 1]
        elif v.ndim == 2:
            for i in range(v.shape[1]):
                cols[f"{k}_{i}"] = v[:, i]
    csv = folder / "data.csv"
    header = ",".join(cols)
    np.savetxt(csv, np.column_stack(list(cols.values())), delimiter=",", header=header, comments="")
    summary = folder / "summary.json"
    summary.write_text(
        json.dumps(
            {
                "scene": res.scene.name,
                "outputs": list(res.scene.outputs),
                "figures": [
                    dict(zip(("figure", "value", "unit", "error_estimate"), r)) for r in res.figures
                ],
                "stages_s": res.stages,
                "files": sorted(p.name for p in folder.iterdir()) + ["summary.json"],
            },
            indent=2,
        )
    )
    return [npz, csv, summary]
