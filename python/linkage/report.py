"""The report folder of a run: plots (PNG), an animation (GIF), the data (CSV, NPZ) and a JSON
summary — only the files the scene's outputs call for.

The folder is the user's disk, so this module removes only what it wrote:

- every report folder carries a marker file, ``.linkage-report`` (JSON: tool, version, scene and
  the files written), written last;
- a report is written into a temporary sibling (``.<name>.partial-<pid>``) and renamed into place
  when complete; any failure, ``KeyboardInterrupt`` included, removes the temporary folder and
  leaves an earlier report untouched;
- ``force`` replaces a folder only if it carries the marker and holds nothing but the files the
  marker lists; the old report is renamed aside, the new one renamed in, and then the old one is
  removed file by file (only the listed files; never ``rmtree`` on a folder the tool did not
  create);
- a target that is a symbolic link (dangling or not), not a folder, the file-system root, the home
  folder, the working directory or one of their ancestors is refused, force or not.
"""

from __future__ import annotations

import contextlib
import datetime
import errno
import json
import math
import os
import re
import shutil
import signal
import sys
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from linkage._core import LinkageError
from linkage.runner import Result

MARKER = ".linkage-report"
"""Name of the marker file that makes a folder a report linkage wrote (and may replace)."""

DEFAULT_BASE = Path("linkage-report")
"""Where reports go without ``--out``: ``linkage-report/<scene name>``."""

_SAFE_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,127}")
_NOTHING = "nothing was written"


def default_folder(name: str, base: Path = DEFAULT_BASE) -> Path:
    """The default report folder of a scene called ``name``: ``base/name``, refused unless ``name``
    is a single plain folder name that stays inside ``base`` (no ``.``, ``..``, separators, or a
    leading dot, which is kept for the tool's temporary folders)."""
    if not _SAFE_NAME.fullmatch(name) or name in (".", ".."):
        raise LinkageError(
            f"scene name {name!r} cannot name a folder inside {base}/ (it must start with a "
            f"letter or digit and hold only letters, digits, '_', '-' or '.'); give --out "
            f"({_NOTHING})"
        )
    folder = base / name
    try:
        inside = folder.resolve().parent == base.resolve()
    except (OSError, RuntimeError):
        inside = False
    if not inside:
        raise LinkageError(f"{folder} would not be inside {base}/; give --out ({_NOTHING})")
    return folder


def read_marker(folder: Path) -> dict[str, Any] | None:
    """The marker of a report folder written by linkage, or ``None`` if it has none (or one that
    does not parse as a linkage marker: such a folder is treated as the user's)."""
    path = folder / MARKER
    try:
        if not path.is_file() or path.is_symlink():
            return None
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("tool") != "linkage":
        return None
    files = data.get("files")
    if not isinstance(files, list) or not all(_plain_name(f) for f in files):
        return None
    return data


def _plain_name(f: object) -> bool:
    return (
        isinstance(f, str) and f not in ("", ".", "..", MARKER) and "/" not in f and "\\" not in f
    )


def _describe(folder: Path, target: Path) -> str:
    return str(folder) if Path(os.path.abspath(folder)) == target else f"{folder} (= {target})"


def _resolve(folder: Path) -> Path:
    """The real path the report would occupy, refusing every target that is not a folder of its
    own: a link, the root, home, the working directory or an ancestor of those."""
    if folder.is_symlink():
        try:
            to = os.readlink(folder)
        except OSError:
            to = "?"
        dangling = "dangling " if not folder.exists() else ""
        raise LinkageError(
            f"{folder} is a {dangling}symbolic link (to {to}); give a real folder ({_NOTHING})"
        )
    try:
        target = folder.resolve()
    except (OSError, RuntimeError) as exc:
        raise LinkageError(f"{folder}: cannot resolve the path: {exc} ({_NOTHING})") from None
    where = _describe(folder, target)
    if target.parent == target:
        raise LinkageError(f"{where} is the root of the file system; refused ({_NOTHING})")
    protected: list[tuple[Path, str]] = []
    with contextlib.suppress(OSError, RuntimeError):
        protected.append((Path.cwd().resolve(), "the working directory"))
    with contextlib.suppress(OSError, RuntimeError, KeyError):
        protected.append((Path.home().resolve(), "the home folder"))
    for base, what in protected:
        if target == base:
            raise LinkageError(
                f"{where} is {what}; a report needs a folder of its own ({_NOTHING})"
            )
        if target in base.parents:
            raise LinkageError(
                f"{where} holds {what}; a report needs a folder of its own ({_NOTHING})"
            )
    if os.path.lexists(target) and not target.is_dir():
        raise LinkageError(f"{where} exists and is not a folder ({_NOTHING})")
    return target


def _check_existing(folder: Path, target: Path, force: bool) -> dict[str, Any] | None:
    """For an existing ``target``: its marker if ``force`` may replace it; otherwise refuse."""
    where = _describe(folder, target)
    marker = read_marker(target)
    if marker is None:
        raise LinkageError(
            f"{where} exists and is not a report written by linkage (no readable {MARKER} "
            f"marker); --force replaces only folders linkage wrote: choose another --out or "
            f"remove it yourself ({_NOTHING})"
        )
    if not force:
        raise LinkageError(
            f"{where} holds an earlier report; pass --force to replace it ({_NOTHING})"
        )
    listed = set(marker["files"])
    try:
        entries = sorted(os.listdir(target))
    except OSError as exc:
        raise LinkageError(
            f"{where}: cannot list the folder: {exc.strerror} ({_NOTHING})"
        ) from None
    foreign = [
        e
        for e in entries
        if e != MARKER
        and (e not in listed or not (target / e).is_file() or (target / e).is_symlink())
    ]
    if foreign:
        shown = ", ".join(foreign[:5]) + (
            f" and {len(foreign) - 5} more" if len(foreign) > 5 else ""
        )
        raise LinkageError(
            f"{where} holds files linkage did not write ({shown}); --force replaces only a "
            f"folder holding nothing but a linkage report: move them or choose another --out "
            f"({_NOTHING})"
        )
    return marker


def prepare(folder: Path, force: bool) -> None:
    """Check, before anything is computed, that the report can be written to ``folder`` without
    losing anything; raise ``LinkageError`` naming the folder and the reason otherwise. Nothing is
    created or removed here (``write`` repeats the check just before it moves anything)."""
    target = _resolve(folder)
    if os.path.lexists(target):
        _check_existing(folder, target, force)


@contextlib.contextmanager
def _sigint_held() -> Iterator[None]:
    """Hold Ctrl-C off a few renames or a clean-up so they cannot be cut in half (main thread
    only; elsewhere signals are not delivered to Python anyway)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    try:
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except (ValueError, OSError):
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def _make_sibling(parent: Path, name: str, kind: str) -> Path:
    """Create a new, empty hidden sibling folder ``.<name>.<kind>-<pid>[-k]`` in ``parent``."""
    stem = f".{name}.{kind}-{os.getpid()}"
    for k in range(1000):
        path = parent / (stem if k == 0 else f"{stem}-{k}")
        try:
            path.mkdir()
        except FileExistsError:
            continue
        return path
    raise FileExistsError(errno.EEXIST, "no free temporary folder name", str(parent / stem))


def _discard_partial(tmp: Path) -> None:
    """Remove a temporary folder this run created (everything in it is this run's)."""
    if tmp.is_dir() and not tmp.is_symlink() and ".partial-" in tmp.name:
        shutil.rmtree(tmp, ignore_errors=True)


def _remove_report(folder: Path, marker: dict[str, Any]) -> bool:
    """Remove a report folder linkage wrote: only the files its marker lists, then the marker,
    then the folder if it is empty. Returns whether the folder is gone."""
    for name in marker["files"]:
        path = folder / name
        if path.is_file() and not path.is_symlink():
            with contextlib.suppress(OSError):
                path.unlink()
    with contextlib.suppress(OSError):
        (folder / MARKER).unlink()
    try:
        folder.rmdir()
    except OSError:
        return False
    return True


def _os_message(exc: OSError, tmp: Path, folder: Path) -> str:
    reason = exc.strerror or str(exc)
    name = exc.filename
    if name is None:
        return reason
    shown = str(name)
    if shown.startswith(str(tmp)):
        shown = str(folder) + shown[len(str(tmp)) :]
    return f"{shown}: {reason}"


def write(res: Result, folder: Path, frames: int = 48, force: bool = False) -> list[Path]:
    """Write the report for ``res`` to ``folder``; returns the files written (in ``folder``).

    The report is written into a temporary sibling folder, its marker last, and renamed into
    place. An existing ``folder`` is replaced only with ``force`` and only if linkage wrote it
    (see the module docstring). On any failure — an exception, ``KeyboardInterrupt``, a full disk
    — the temporary folder is removed and an earlier report is left as it was; an ``OSError``
    becomes a ``LinkageError`` naming the path.
    """
    import matplotlib

    matplotlib.use("Agg")

    target = _resolve(folder)
    earlier = os.path.lexists(target)
    if earlier:
        _check_existing(folder, target, force)
    parent = target.parent
    created: list[Path] = []
    tmp: Path | None = None
    try:
        missing = [p for p in (parent, *parent.parents) if not p.exists()]
        # Held off Ctrl-C so that every folder made here is known to the clean-up below.
        with _sigint_held():
            for p in reversed(missing):
                p.mkdir()
                created.append(p)
            tmp = _make_sibling(parent, target.name, "partial")
        names = [p.name for p in _write_files(res, tmp, frames)]
        marker = {
            "tool": "linkage",
            "version": _version(),
            "scene": res.scene.name,
            "written": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "files": sorted(names),
        }
        (tmp / MARKER).write_text(json.dumps(marker, indent=2) + "\n", encoding="utf-8")
        with _sigint_held():
            _commit(folder, target, tmp, force)
    except BaseException as exc:
        with _sigint_held():
            if tmp is not None:
                _discard_partial(tmp)
            for p in reversed(created):
                with contextlib.suppress(OSError):
                    p.rmdir()
        if isinstance(exc, OSError):
            kept = "; the earlier report is unchanged" if earlier else ""
            raise LinkageError(
                f"{folder}: cannot write the report: {_os_message(exc, tmp or target, folder)} "
                f"({_NOTHING}{kept})"
            ) from None
        raise
    return [target / n for n in names]


def _commit(folder: Path, target: Path, tmp: Path, force: bool) -> None:
    """Move the finished ``tmp`` into place at ``target``, replacing a report linkage wrote."""
    if not os.path.lexists(target):
        os.rename(tmp, target)
        return
    # Check again: the folder may have changed while the report was computed.
    old = _check_existing(folder, target, force)
    assert old is not None
    aside = _make_sibling(target.parent, target.name, "old")
    aside.rmdir()
    os.rename(target, aside)
    try:
        os.rename(tmp, target)
    except BaseException:
        os.rename(aside, target)
        raise
    if not _remove_report(aside, old):
        sys.stderr.write(
            f"linkage: warning: the replaced report was kept in {aside}: it held files linkage "
            f"did not write\n"
        )


def _version() -> str:
    from linkage import __version__

    return str(__version__)


def _write_files(res: Result, folder: Path, frames: int) -> list[Path]:
    """Write the report's files into the (new, empty) ``folder``; returns them."""
    import time

    import matplotlib.pyplot as plt

    started = time.perf_counter()
    files: list[Path] = []
    scene = res.scene

    def save(fig: Any, name: str) -> None:
        path = folder / name
        fig.tight_layout()
        try:
            fig.savefig(path, dpi=110)
        finally:
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
