"""The search's report, written safely like a run's (:mod:`linkage.report_folder`).

Candidates and front as CSV (or Parquet), the Pareto plot, the chosen designs drawn and exported as
scenes, a JSON summary — written as a temporary sibling renamed into place, with a marker, nothing
of the user's overwritten.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared import report_folder
from linkage.design.cluster import SchedulerError
from linkage.design.search import (
    Front,
    Study,
    objectives_and_constraints,
    placement,
    reference_figures,
    search,
)
from linkage.design.study_file import load_study
from linkage.walking.legs import FIGURES, OBJECTIVES, UNITS, family

__all__ = ["chosen", "main_design", "scene_text", "write_report"]

Array = NDArray[np.float64]


# -- report -------------------------------------------------------------------------------


def chosen(result: Front, count: int) -> list[int]:
    """Choose up to ``count`` front designs to draw and export.

    The best in each objective in turn, then the design nearest the ideal point (objectives scaled
    to the front's range).

    Examples
    --------
    >>> from linkage.design import Settings
    >>> from linkage.design.report import chosen
    >>> from linkage.design.search import Study, search
    >>> study = Study(population=4, budget=8, settings=Settings(samples=64, foot_bar=100.0),
    ...               bounds={"ground": (15.0, 25.0), "coupler": (20.0, 30.0)})
    >>> result = search(study)
    >>> result.front.tolist(), chosen(result, 3), chosen(result, 0)
    ([0], [0], [])

    An empty front (no candidate feasible: without the foot bar every foot is above the hip)
    gives nothing to choose:

    >>> chosen(search(Study(population=4, budget=8, settings=Settings(samples=64))), 3)
    []
    """
    study = result.study
    if len(result.front) == 0 or count <= 0:
        return []
    f, _ = objectives_and_constraints(study, result.front_figures())
    picks: list[int] = []
    for k in range(f.shape[1]):
        i = int(result.front[int(np.argmin(f[:, k]))])
        if i not in picks:
            picks.append(i)
    span = np.ptp(f, axis=0)
    span[span == 0] = 1.0
    knee = int(result.front[int(np.argmin(np.linalg.norm((f - f.min(axis=0)) / span, axis=1)))])
    if knee not in picks:
        picks.append(knee)
    return picks[:count]


def scene_text(study: Study, x: Sequence[float], name: str) -> str:
    """Return a ready-to-run scene (TOML) of design ``x``: its joints, a constant crank speed.

    Examples
    --------
    >>> from linkage.design import family
    >>> from linkage.design.report import scene_text
    >>> from linkage.design.search import Study
    >>> from linkage.scene import parse
    >>> text = scene_text(Study(), family("fourbar").reference, "hoecken-leg")
    >>> print(text.splitlines()[10])
        { name = "B", kind = "dyad", p1 = "A", p2 = "C", r1 = 25.0, r2 = 25.0, side = "left" },
    >>> scene = parse(text)      # a valid scene: its joints build
    >>> scene.name, scene.mechanism["trace"], scene.drive["samples"]
    ('hoecken-leg', 'F', 361)
    """
    fam = family(study.family)
    lines = [
        f"# Designed by `linkage design` (family {fam.name}, study {study.name!r}).",
        f'name = "{name}"',
        'outputs = ["trajectory", "velocity", "straightness"]',
        "",
        "[mechanism]",
        'trace = "F"',
        "joints = [",
    ]
    for j in fam.joints(x):
        parts = []
        for k, v in j.items():
            if isinstance(v, str):
                parts.append(f'{k} = "{v}"')
            elif isinstance(v, (list, tuple)):
                items = ", ".join(f'"{e}"' if isinstance(e, str) else repr(float(e)) for e in v)
                parts.append(f"{k} = [{items}]")
            else:
                parts.append(f"{k} = {float(v)!r}")
        lines.append("    { " + ", ".join(parts) + " },")
    lines += [
        "]",
        "",
        "[drive]",
        'kind = "constant"',
        "omega = 1.0",
        f"samples = {study.settings.samples + 1}",
        "",
    ]
    return "\n".join(lines)


def write_report(
    result: Front, folder: str | Path, choose: int = 3, force: bool = False
) -> list[Path]:
    """Write the search's report to ``folder`` (safely: see :mod:`linkage.report_folder`).

    The report holds every candidate (``candidates.parquet`` with pyarrow, else ``candidates.csv``),
    ``front.csv``, ``pareto.png`` (objectives pairwise, with units and which way is better, the
    reference design marked),
    ``designs.png`` (the chosen designs' foot paths and linkages), one scene per chosen design
    (``design-<k>.toml``) and ``summary.json`` (the reference's placement: how many front designs
    dominate it and how many it dominates).

    Examples
    --------
    >>> import os, tempfile
    >>> from linkage.design import Settings
    >>> from linkage.design.report import write_report
    >>> from linkage.design.search import Study, search
    >>> study = Study(population=4, budget=8, settings=Settings(samples=64, foot_bar=100.0),
    ...               bounds={"ground": (15.0, 25.0), "coupler": (20.0, 30.0)})
    >>> result = search(study)
    >>> tmp = tempfile.TemporaryDirectory()
    >>> folder = os.path.join(tmp.name, "report")
    >>> files = write_report(result, folder, choose=1)
    >>> sorted(os.listdir(folder)) == sorted([".linkage-report"] + [p.name for p in files])
    True
    >>> sorted(p.name for p in files if p.suffix != ".parquet")
    ['candidates.csv', 'design-1.toml', 'designs.png', 'front.csv', 'pareto.png', 'summary.json']

    An earlier report is replaced only with ``force=True``:

    >>> write_report(result, folder)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...an earlier report; pass --force to replace it (nothing was written)
    >>> tmp.cleanup()
    """
    out = Path(os.path.expanduser(str(folder)))
    return report_folder.write_folder(
        out, result.study.name, lambda tmp: _write_files(result, tmp, choose), force
    )


def _write_files(result: Front, folder: Path, choose: int) -> list[str]:
    import matplotlib  # noqa: PLC0415 (the Agg backend is chosen before pyplot is imported)

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415 (after the backend is chosen)

    study = result.study
    fam = family(study.family)
    names: list[str] = []
    header = list(fam.params) + list(FIGURES) + ["front"]
    on_front = np.zeros(len(result.x), dtype=bool)
    on_front[result.front] = True
    table = np.column_stack([result.x, result.figures, on_front.astype(float)])
    try:
        import pyarrow as pa  # type: ignore[import-not-found,import-untyped,unused-ignore]  # noqa: PLC0415 (optional)
        import pyarrow.parquet as pq  # type: ignore[import-not-found,import-untyped,unused-ignore]  # noqa: PLC0415 (optional)

        pq.write_table(
            pa.table({h: table[:, k] for k, h in enumerate(header)}),
            folder / "candidates.parquet",
        )
        names.append("candidates.parquet")
    except ImportError:
        np.savetxt(
            folder / "candidates.csv",
            table,
            delimiter=",",
            header=",".join(header),
            comments="",
            fmt="%.10g",
        )
        names.append("candidates.csv")
    np.savetxt(
        folder / "front.csv",
        table[result.front],
        delimiter=",",
        header=",".join(header),
        comments="",
        fmt="%.10g",
    )
    names.append("front.csv")
    ref = reference_figures(study)
    place = placement(study, result)
    objs = list(study.objectives)
    col = {n: k for k, n in enumerate(FIGURES)}
    pairs = [(a, b) for i, a in enumerate(objs) for b in objs[i + 1 :]] or [(objs[0], objs[0])]
    ncols = min(3, len(pairs))
    nrows = -(-len(pairs) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.4 * ncols, 4.0 * nrows), squeeze=False)
    for ax in axes.flat[len(pairs) :]:
        ax.set_visible(False)
    _f_all, g_all = objectives_and_constraints(study, result.figures)
    feas = (g_all <= 0).all(axis=1)

    def unit(name: str) -> str:
        return UNITS[name].replace("length", fam.units)

    def better(name: str) -> str:
        return "(higher is better)" if OBJECTIVES[name] > 0 else "(lower is better)"

    for ax, (a, b) in zip(axes.flat, pairs):
        fa, fb = result.figures[:, col[a]], result.figures[:, col[b]]
        ax.scatter(fa[feas], fb[feas], s=4, c="0.75", label="feasible candidates")
        ax.scatter(fa[result.front], fb[result.front], s=10, c="C0", label="Pareto front")
        ax.scatter(
            [ref[col[a]]],
            [ref[col[b]]],
            marker="*",
            s=120,
            c="C3",
            label=fam.reference_name.split(" (")[0],
        )
        ax.set_xlabel(f"{a} ({unit(a)})\n{better(a)}")
        ax.set_ylabel(f"{b} ({unit(b)})\n{better(b)}")
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle(f"{study.name}: {fam.doc} {result.evaluations} legs, seed {study.seed}")
    fig.tight_layout()
    fig.savefig(folder / "pareto.png", dpi=110)
    plt.close(fig)
    names.append("pareto.png")
    picks = chosen(result, choose)
    if picks:
        fig, axes = plt.subplots(
            1, len(picks), figsize=(4.2 * len(picks), 3.6 + 0.3 * len(objs)), squeeze=False
        )
        theta = np.linspace(0, 2 * math.pi, 361)
        for ax, i in zip(axes[0], picks):
            m = fam.mechanism(result.x[i])
            sw = m.sweep(theta)
            ax.plot(sw.point[:, 0], sw.point[:, 1], c="C0", lw=1)
            j0 = sw.joints[0]
            ax.plot(j0[:, 0], j0[:, 1], "o", ms=3, c="k")
            for spec in fam.joints(result.x[i]):
                if spec["kind"] == "fixed":
                    continue
                if spec["kind"] == "crank":
                    a, b = spec["centre"], spec["name"]
                elif spec["kind"] == "dyad":
                    a, b = spec["p1"], spec["name"]
                    ka, kb = m.joint_names.index(spec["p2"]), m.joint_names.index(b)
                    ax.plot(j0[[ka, kb], 0], j0[[ka, kb], 1], c="0.3", lw=1.5)
                else:
                    a, b = spec["on"][0], spec["name"]
                ka, kb = m.joint_names.index(a), m.joint_names.index(b)
                ax.plot(j0[[ka, kb], 0], j0[[ka, kb], 1], c="0.3", lw=1.5)
            figs = dict(zip(FIGURES, result.figures[i]))
            ax.set_title(
                f"design {picks.index(i) + 1}\n"
                + "\n".join(f"{o} {figs[o]:#.3g} {unit(o)}" for o in objs),
                fontsize=8,
            )
            ax.set_aspect("equal")
            ax.set_xlabel(f"x ({fam.units})")
            ax.set_ylabel(f"y ({fam.units}); foot bar not drawn")
        fig.tight_layout()
        fig.savefig(folder / "designs.png", dpi=110)
        plt.close(fig)
        names.append("designs.png")
    for k, i in enumerate(picks, start=1):
        (folder / f"design-{k}.toml").write_text(
            scene_text(study, result.x[i], f"{study.name}-design-{k}"), encoding="utf-8"
        )
        names.append(f"design-{k}.toml")
    summary = {
        "study": study.name,
        "family": fam.name,
        "objectives": {o: unit(o) for o in objs},
        "seed": study.seed,
        "evaluations": result.evaluations,
        "generations": result.generations,
        "front_size": len(result.front),
        "seconds": result.seconds,
        "reference": {
            "name": fam.reference_name,
            **place,
            "dominated_by_count": len(place["dominated_by"]),
            "dominates_count": len(place["dominates"]),
        },
        "chosen": [
            {
                "parameters": dict(zip(fam.params, map(float, result.x[i]))),
                "figures": dict(zip(FIGURES, map(float, result.figures[i]))),
            }
            for i in picks
        ],
    }
    (folder / "summary.json").write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    names.append("summary.json")
    return names


def _note(line: str) -> None:
    """One line on stderr, as the command's messages are (never raising itself)."""
    with contextlib.suppress(OSError, ValueError):
        print(f"linkage: {line}", file=sys.stderr)
        sys.stderr.flush()


def main_design(
    path: str, out: str | None, force: bool, checkpoint: str | None, quiet: bool
) -> int:
    r"""Run ``linkage design study.toml``: search, write the report, place the reference.

    ``out`` is the report folder (default: :func:`linkage.report_folder.default_folder` of the
    study's name), ``force`` replaces an earlier report, ``checkpoint`` is the search's checkpoint
    file (default: ``.<folder name>.checkpoint`` beside the folder) and ``quiet`` prints nothing.
    Returns the exit status, 0.

    A scheduler that cannot be reached is named with where the study gives it
    (``file:line: [design] scheduler``). Stopped by Ctrl-C or SIGTERM after a checkpoint was
    written, it says on stderr that the checkpoint is kept for resuming (no partial
    temporary is left: see :mod:`linkage.design.checkpoint`).

    Examples
    --------
    >>> import os, tempfile
    >>> from linkage.design.report import main_design
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     study = os.path.join(tmp, "tiny.toml")
    ...     with open(study, "w") as fh:
    ...         _ = fh.write("[design]\nobjectives = ['stride']\npopulation = 4\nbudget = 8\n")
    ...         _ = fh.write("samples = 64\nchoose = 0\n")
    ...     main_design(study, os.path.join(tmp, "out"), False, None, quiet=True)
    ...     sorted(os.listdir(tmp))
    0
    ['.out.checkpoint', 'out', 'tiny.toml']
    >>> main_design("no-such-study.toml", None, False, None, quiet=True)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: no-such-study.toml: cannot read the study: No such file or directory
    """
    sf = load_study(path)
    folder = Path(out) if out else report_folder.default_folder(sf.study.name)
    report_folder.prepare(folder, force)
    ck = Path(checkpoint) if checkpoint else folder.with_name(f".{folder.name}.checkpoint")
    try:
        result = search(sf.study, checkpoint=ck, progress=not quiet)
        # Stopped while the report is written, the finished search is in the checkpoint too.
        files = write_report(result, folder, sf.choose, force)
    except SchedulerError as exc:
        where = f"{sf.scheduler_at}: " if sf.scheduler_at else f"{sf.path}: "
        raise LinkageError(f"{where}{exc} (nothing was written)") from None
    except BaseException:
        # Ctrl-C, or the error a library made of it (Dask may), or a failure after the search
        # began: the checkpoint it wrote stays, and the user is told where.
        if ck.is_file() and not ck.is_symlink():
            _note(f"the search so far is kept in {ck}: the same command resumes it")
        raise
    if not quiet:
        place = placement(sf.study, result)
        print(
            f"{sf.study.name}: {result.evaluations} legs in {result.seconds:.1f} s, "
            f"front of {len(result.front)}; reference "
            f"{'feasible' if place['feasible'] else 'infeasible'}"
            f"{', on the front' if place['on_front'] else ''}, dominated by "
            f"{len(place['dominated_by'])} front designs, dominating "
            f"{len(place['dominates'])}; ranks {place['rank']}"
        )
        print(f"report: {folder}/ ({', '.join(sorted(p.name for p in files))})")
    return 0
