"""Walking-leg design search: leg families, their figures from the core, a Pareto front by
NSGA-II (pymoo), evaluated in chunks on Dask, with checkpoints and a report.

A *family* is a parametrised leg generator with documented bounds and a reference point (the
design a source chose). A candidate's figures come from the core's leg figures
(``linkage_core::gait``; :func:`linkage._core.four_bar_gaits` for four-bars, batched,
:func:`linkage._core.leg_gait` on a swept foot path for multi-loop legs). The search is
deterministic for a seed: candidates are independent, chunks are gathered in order, and the
four-bar batch gives the same bits for any split, so the front is the same serially, on a
``LocalCluster`` or on a real cluster.

This module needs the optional packages ``pymoo`` and ``dask[distributed]``
(``pip install "linkage-kinematics[design]"``).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import pickle
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError

try:
    import distributed
    from pymoo.algorithms.moo.nsga2 import NSGA2  # type: ignore[import-untyped]
    from pymoo.core.problem import Problem  # type: ignore[import-untyped]
except ImportError as _exc:  # pragma: no cover - exercised by hand without the extra
    raise ImportError(
        f"linkage.design needs the optional packages pymoo and dask[distributed] "
        f"(missing: {_exc.name}); install them with: pip install 'linkage-kinematics[design]'"
    ) from None

Array = NDArray[np.float64]

from linkage.legs import (  # noqa: E402  (after the optional imports' check)
    CRANK,
    FAMILIES,
    FIGURES,
    JANSEN_HOLY,
    KLANN_REF,
    OBJECTIVES,
    UNITS,
    Family,
    Settings,
    family,
)

__all__ = [
    "CRANK",
    "FAMILIES",
    "FIGURES",
    "JANSEN_HOLY",
    "KLANN_REF",
    "OBJECTIVES",
    "UNITS",
    "Constraints",
    "Evaluator",
    "Family",
    "Front",
    "Settings",
    "Study",
    "StudyFile",
    "family",
    "load_study",
    "pareto_front",
    "placement",
    "reference_figures",
    "scene_text",
    "search",
    "write_report",
]

# -- the study ----------------------------------------------------------------------------


@dataclass(frozen=True)
class Constraints:
    """Feasibility: the whole turn on one circuit and one stance run (always), and bounds."""

    min_transmission: float = 20.0
    """Smallest transmission angle (degrees)."""
    foot_below_hip: float = 0.0
    """Least depth of the ground below the hip (crank pivot), foot bar included."""
    min_lift: float = 0.0
    """Least lift (the obstacle the swing clears)."""
    min_duty: float = 0.4
    """Least duty factor (0.5: two legs in antiphase always have a foot down)."""


@dataclass(frozen=True)
class Study:
    """A design study: family, bounds, objectives, constraints, budget, seed, execution."""

    family: str = "fourbar"
    objectives: tuple[str, ...] = ("stride", "straightness", "speed_variation")
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)
    constraints: Constraints = field(default_factory=Constraints)
    settings: Settings = field(default_factory=Settings)
    population: int = 64
    budget: int = 640
    seed: int = 1
    workers: int = 0
    """0: evaluate in this process; n: a LocalCluster of n single-threaded worker processes."""
    scheduler: str | None = None
    """Address of a running Dask scheduler (``tcp://host:8786``): use that cluster."""
    chunk: int = 256
    """Candidates per task."""
    name: str = "design"

    def __post_init__(self) -> None:
        fam = family(self.family)
        for o in self.objectives:
            if o not in OBJECTIVES:
                raise LinkageError(f"unknown objective {o!r}; choose from {', '.join(OBJECTIVES)}")
        if not self.objectives:
            raise LinkageError("a study needs at least one objective")
        for k, (lo, hi) in self.bounds.items():
            if k not in fam.params:
                raise LinkageError(
                    f"family {fam.name!r} has no parameter {k!r}; it has {', '.join(fam.params)}"
                )
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise LinkageError(f"bounds of {k!r} must be finite with lower < upper")
        if self.population < 4:
            raise LinkageError(f"population must be at least 4, got {self.population}")
        if self.budget < self.population:
            raise LinkageError(
                f"budget ({self.budget}) must be at least one population ({self.population})"
            )
        if self.workers < 0 or self.chunk < 1:
            raise LinkageError("workers must be ≥ 0 and chunk ≥ 1")

    @property
    def generations(self) -> int:
        """Generations the budget pays for (the first population included)."""
        return self.budget // self.population

    def box(self) -> tuple[Array, Array]:
        """Lower and upper bounds of every parameter (the family's, overridden)."""
        fam = family(self.family)
        b = fam.bounds()
        b.update(self.bounds)
        return (
            np.array([b[p][0] for p in fam.params], dtype=float),
            np.array([b[p][1] for p in fam.params], dtype=float),
        )

    def fingerprint(self) -> str:
        """What a checkpoint must match to be resumed (everything but where it runs)."""
        d = {
            "family": self.family,
            "objectives": self.objectives,
            "box": [v.tolist() for v in self.box()],
            "constraints": self.constraints.__dict__,
            "settings": self.settings.__dict__,
            "population": self.population,
            "seed": self.seed,
        }
        return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]


def objectives_and_constraints(study: Study, figs: Array) -> tuple[Array, Array]:
    """pymoo's ``F`` (minimised) and ``G`` (≤ 0 feasible) from figures. Constraints are
    scaled to comparable sizes (angles by 90°, lengths by the family's scale, the duty factor
    as it is) so that the optimiser's summed violation weighs them alike. A candidate without
    figures (no full turn) gets the worst objectives the optimiser can rank (1e12, never
    reported) and violates every constraint by 10."""
    col = {n: figs[:, k] for k, n in enumerate(FIGURES)}
    f = np.stack([-OBJECTIVES[o] * col[o] for o in study.objectives], axis=1)
    c = study.constraints
    size = family(study.family).scale
    with np.errstate(invalid="ignore"):
        g = np.stack(
            [
                1.0 - col["full_turn"],
                np.abs(col["stance_runs"] - 1.0),
                (c.min_transmission - col["min_transmission"]) / 90.0,
                (c.foot_below_hip - col["hip_depth"]) / size,
                (c.min_lift - col["lift"]) / size,
                c.min_duty - col["duty_factor"],
            ],
            axis=1,
        )
    bad = ~np.isfinite(f).all(axis=1)
    f[bad] = 1e12
    g[~np.isfinite(g)] = 10.0
    return f, g


# -- evaluation (serial or on Dask) -------------------------------------------------------


def evaluate_chunk(family_name: str, x: Array, settings: Settings) -> Array:
    """Figures of one chunk of candidates (what a Dask task runs)."""
    return family(family_name).evaluate(x, settings)


class Evaluator:
    """Evaluates candidates in this process, on a LocalCluster or on a scheduler's cluster,
    in chunks of ``chunk`` candidates gathered in order (the same figures either way)."""

    def __init__(self, study: Study) -> None:
        self.study = study
        self.client: Any = None
        self.cluster: Any = None
        if study.scheduler:
            self.client = distributed.Client(study.scheduler, timeout="20s")  # type: ignore[no-untyped-call]
        elif study.workers > 0:
            self.cluster = distributed.LocalCluster(  # type: ignore[no-untyped-call]
                n_workers=study.workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
            )
            self.client = distributed.Client(self.cluster)  # type: ignore[no-untyped-call]

    def __call__(self, x: Array) -> Array:
        s = self.study
        if self.client is None:
            return evaluate_chunk(s.family, x, s.settings)
        parts = [x[i : i + s.chunk] for i in range(0, len(x), s.chunk)]
        futures = self.client.map(
            evaluate_chunk, [s.family] * len(parts), parts, [s.settings] * len(parts), pure=False
        )
        return np.concatenate(self.client.gather(futures), axis=0)

    def close(self) -> None:
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def __enter__(self) -> Evaluator:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


# -- the search ---------------------------------------------------------------------------


class _Box(Problem):  # type: ignore[misc]
    """The search space for pymoo: evaluation is done outside (ask/tell), so it pickles."""

    def __init__(self, n_var: int, n_obj: int, n_constr: int, xl: Array, xu: Array) -> None:
        super().__init__(n_var=n_var, n_obj=n_obj, n_ieq_constr=n_constr, xl=xl, xu=xu)


@dataclass
class Front:
    """The search's result: every candidate evaluated (parameters and figures, in order), the
    indices of the final Pareto front, and the study."""

    study: Study
    x: Array
    figures: Array
    front: NDArray[np.int64]
    generations: int
    evaluations: int
    seconds: float = 0.0

    def front_x(self) -> Array:
        return self.x[self.front]

    def front_figures(self) -> Array:
        return self.figures[self.front]


CHECKPOINT_MAGIC = "linkage-design-checkpoint-1"


def _save_checkpoint(path: Path, state: dict[str, Any]) -> None:
    """Write atomically (temp file, then rename) a checkpoint the tool owns."""
    tmp = path.with_name(f".{path.name}.partial-{os.getpid()}")
    with open(tmp, "wb") as fh:
        pickle.dump({"magic": CHECKPOINT_MAGIC, **state}, fh)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)


def _load_checkpoint(path: Path, study: Study) -> dict[str, Any] | None:
    if not path.exists():
        return None
    try:
        with open(path, "rb") as fh:
            state = pickle.load(fh)
    except Exception as exc:
        raise LinkageError(
            f"{path}: not a readable design checkpoint ({exc}); remove it or choose another "
            f"--checkpoint (nothing was overwritten)"
        ) from None
    if not isinstance(state, dict) or state.get("magic") != CHECKPOINT_MAGIC:
        raise LinkageError(
            f"{path} is not a linkage design checkpoint; refusing to overwrite it "
            f"(choose another --checkpoint)"
        )
    if state.get("fingerprint") != study.fingerprint():
        raise LinkageError(
            f"{path} is the checkpoint of a different study (family, bounds, objectives, "
            f"constraints, population or seed changed); remove it or choose another --checkpoint"
        )
    return state


def search(
    study: Study,
    checkpoint: str | Path | None = None,
    progress: bool = False,
    stop_after: int | None = None,
) -> Front:
    """Run NSGA-II over the study's family; returns the :class:`Front`.

    With ``checkpoint`` the state is saved atomically after every generation and a search
    started again with the same study resumes from it (to the same front: the optimiser's
    random state is part of the checkpoint). ``stop_after`` ends after that many generations
    in this call (a stopped search, for tests). ``progress`` draws a bar on stderr.
    """
    if not isinstance(study, Study):
        raise TypeError(f"study must be a Study, got {type(study).__name__}")
    fam = family(study.family)
    xl, xu = study.box()
    n_con = 6
    path = Path(checkpoint) if checkpoint is not None else None
    state = _load_checkpoint(path, study) if path is not None else None
    t0 = time.perf_counter()
    if state is None:
        problem = _Box(len(fam.params), len(study.objectives), n_con, xl, xu)
        algorithm = NSGA2(pop_size=study.population)
        algorithm.setup(problem, termination=("n_gen", study.generations), seed=study.seed)
        xs: list[Array] = []
        figs: list[Array] = []
        gen = 0
    else:
        algorithm = state["algorithm"]
        xs, figs, gen = state["x"], state["figures"], state["generation"]
    done_here = 0
    with Evaluator(study) as ev:
        while gen < study.generations:
            if stop_after is not None and done_here >= stop_after:
                break
            pop = algorithm.ask()
            x = np.asarray(pop.get("X"), dtype=float)
            fig = ev(x)
            f, g = objectives_and_constraints(study, fig)
            pop.set("F", f, "G", g)
            algorithm.tell(infills=pop)
            xs.append(x)
            figs.append(fig)
            gen += 1
            done_here += 1
            if path is not None:
                _save_checkpoint(
                    path,
                    {
                        "fingerprint": study.fingerprint(),
                        "algorithm": algorithm,
                        "x": xs,
                        "figures": figs,
                        "generation": gen,
                    },
                )
            if progress:
                _bar(gen, study.generations, sum(len(v) for v in xs))
    if progress and sys.stderr.isatty():
        sys.stderr.write("\n")
    x_all = np.concatenate(xs) if xs else np.empty((0, len(fam.params)))
    f_all = np.concatenate(figs) if figs else np.empty((0, len(FIGURES)))
    return Front(
        study=study,
        x=x_all,
        figures=f_all,
        front=pareto_front(study, f_all),
        generations=gen,
        evaluations=len(x_all),
        seconds=time.perf_counter() - t0,
    )


def _bar(done: int, total: int, evaluations: int) -> None:
    """A progress bar on a terminal (redrawn in place); elsewhere a line every tenth."""
    width = 30
    full = int(width * done / max(total, 1))
    text = (
        f"[{'#' * full}{'.' * (width - full)}] generation {done}/{total}, "
        f"{evaluations} legs evaluated"
    )
    if sys.stderr.isatty():
        sys.stderr.write("\r" + text)
    elif done == total or done % max(1, total // 10) == 0:
        sys.stderr.write(text + "\n")
    sys.stderr.flush()


def pareto_front(study: Study, figs: Array) -> NDArray[np.int64]:
    """Indices of the feasible candidates no other feasible candidate dominates (over every
    candidate evaluated, in order; duplicates keep their first)."""
    f, g = objectives_and_constraints(study, figs)
    ok = np.flatnonzero((g <= 0).all(axis=1))
    if len(ok) == 0:
        return np.empty(0, dtype=np.int64)
    ff = f[ok]
    keep = []
    for i in range(len(ff)):
        dominated = np.any(np.all(ff <= ff[i], axis=1) & np.any(ff < ff[i], axis=1))
        duplicate = np.any(np.all(ff[:i] == ff[i], axis=1))
        if not dominated and not duplicate:
            keep.append(ok[i])
    return np.asarray(keep, dtype=np.int64)


def reference_figures(study: Study) -> Array:
    """Figures of the family's reference design (the sources' choice) under the study."""
    fam = family(study.family)
    row: Array = fam.evaluate(np.asarray([fam.reference], dtype=float), study.settings)[0]
    return row


def placement(study: Study, result: Front) -> dict[str, Any]:
    """Where the reference design sits relative to the front: whether it is feasible, which
    front designs dominate it (indices into ``result.x``) and, per objective, its rank among
    the front's values (0 = better than every front design)."""
    ref = reference_figures(study)
    f_ref, g_ref = objectives_and_constraints(study, ref[None, :])
    f_front, _ = objectives_and_constraints(study, result.front_figures())
    dom = [
        int(result.front[i])
        for i in range(len(f_front))
        if np.all(f_front[i] <= f_ref[0]) and np.any(f_front[i] < f_ref[0])
    ]
    ranks = {o: int(np.sum(f_front[:, k] < f_ref[0, k])) for k, o in enumerate(study.objectives)}
    return {
        "feasible": bool((g_ref <= 0).all()),
        "dominated_by": dom,
        "rank": ranks,
        "figures": {n: float(v) for n, v in zip(FIGURES, ref)},
    }


# -- study files --------------------------------------------------------------------------

_TOP_KEYS = {
    "family": str,
    "objectives": list,
    "population": int,
    "budget": int,
    "seed": int,
    "workers": int,
    "scheduler": str,
    "chunk": int,
    "samples": int,
    "stance_tol": float,
    "foot_bar": float,
    "choose": int,
    "bounds": dict,
    "constraints": dict,
}
_CONSTRAINT_KEYS = ("min_transmission", "foot_below_hip", "min_lift", "min_duty")


@dataclass(frozen=True)
class StudyFile:
    """A study read from a TOML file: the study, how many front designs to draw and export
    (``choose``), and the file it came from."""

    study: Study
    choose: int
    path: Path


def load_study(path: str | Path) -> StudyFile:
    """Read a study file: a ``[design]`` section (family, objectives, population, budget,
    seed, workers or scheduler, chunk, samples, stance_tol, foot_bar, choose) with
    ``[design.bounds]`` (``parameter = [lower, upper]``) and ``[design.constraints]``.
    Errors name ``file:line: [section] key``."""
    from linkage._toml_lines import Locator, NotText, decode

    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise LinkageError(f"{p}: cannot read the study: {exc.strerror or exc}") from None
    try:
        text = decode(data)
    except NotText as exc:
        raise LinkageError(f"{p}:{exc.line}: {exc.problem}") from None
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        line = getattr(exc, "lineno", None) or _line_of(str(exc))
        raise LinkageError(f"{p}:{line}: not valid TOML: {exc}") from None
    loc = Locator(text, str(p))

    def err(section: Sequence[str], key: str, problem: str) -> LinkageError:
        return LinkageError(loc.message(list(section), key, problem))

    name = str(doc.get("name", p.stem)) if isinstance(doc.get("name", ""), str) else p.stem
    for key in doc:
        if key not in ("design", "name"):
            raise err([], key, "unknown key (a study file has name and a [design] section)")
    d = doc.get("design")
    if not isinstance(d, dict):
        raise err([], "design", "missing: a study file needs a [design] section")
    for key, value in d.items():
        want = _TOP_KEYS.get(key)
        if want is None:
            raise err(["design"], key, f"unknown key; expected one of {', '.join(_TOP_KEYS)}")
        ok = (
            isinstance(value, (int, float)) and not isinstance(value, bool)
            if want is float
            else isinstance(value, want) and not isinstance(value, bool)
        )
        if not ok:
            raise err(["design"], key, f"must be {want.__name__}, got {value!r}")
    fam_name = d.get("family", "fourbar")
    if fam_name not in FAMILIES:
        raise err(
            ["design"], "family", f"unknown family {fam_name!r}; choose from {', '.join(FAMILIES)}"
        )
    fam = FAMILIES[fam_name]
    objectives = d.get("objectives", ["stride", "straightness", "speed_variation"])
    for o in objectives:
        if o not in OBJECTIVES:
            raise err(
                ["design"],
                "objectives",
                f"unknown objective {o!r}; choose from {', '.join(OBJECTIVES)}",
            )
    if not objectives:
        raise err(["design"], "objectives", "needs at least one objective")
    bounds: dict[str, tuple[float, float]] = {}
    for key, value in d.get("bounds", {}).items():
        if key not in fam.params:
            raise err(
                ["design", "bounds"],
                key,
                f"family {fam_name!r} has no parameter {key!r}; it has {', '.join(fam.params)}",
            )
        if (
            not isinstance(value, list)
            or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
            or not all(math.isfinite(v) for v in value)
            or not value[0] < value[1]
        ):
            raise err(
                ["design", "bounds"],
                key,
                f"must be [lower, upper] with finite lower < upper, got {value!r}",
            )
        bounds[key] = (float(value[0]), float(value[1]))
    cons: dict[str, float] = {}
    for key, value in d.get("constraints", {}).items():
        if key not in _CONSTRAINT_KEYS:
            raise err(
                ["design", "constraints"],
                key,
                f"unknown constraint; expected one of {', '.join(_CONSTRAINT_KEYS)}",
            )
        if (
            not isinstance(value, (int, float))
            or isinstance(value, bool)
            or not math.isfinite(value)
        ):
            raise err(["design", "constraints"], key, f"must be a finite number, got {value!r}")
        cons[key] = float(value)
    ints = {
        "population": (4, 10**7),
        "budget": (4, 10**12),
        "seed": (0, 2**32 - 1),
        "workers": (0, 4096),
        "chunk": (1, 10**7),
        "samples": (16, 10**6),
        "choose": (0, 50),
    }
    for key, (lo, hi) in ints.items():
        if key in d and not lo <= d[key] <= hi:
            raise err(["design"], key, f"must be between {lo} and {hi}, got {d[key]}")
    for key in ("stance_tol", "foot_bar"):
        if key in d and not (math.isfinite(d[key]) and d[key] >= 0):
            raise err(["design"], key, f"must be a finite number ≥ 0, got {d[key]}")
    if "workers" in d and "scheduler" in d:
        raise err(["design"], "scheduler", "give workers or scheduler, not both")
    population = int(d.get("population", 64))
    budget = int(d.get("budget", 10 * population))
    if budget < population:
        raise err(["design"], "budget", f"must be at least one population ({population})")
    settings = Settings(
        samples=int(d.get("samples", 360)),
        stance_tol=float(d.get("stance_tol", 2.5e-3)),
        foot_bar=float(d.get("foot_bar", 0.0)),
    )
    study = Study(
        family=fam_name,
        objectives=tuple(objectives),
        bounds=bounds,
        constraints=Constraints(**cons),
        settings=settings,
        population=population,
        budget=budget,
        seed=int(d.get("seed", 1)),
        workers=int(d.get("workers", 0)),
        scheduler=d.get("scheduler"),
        chunk=int(d.get("chunk", 256)),
        name=name,
    )
    return StudyFile(study=study, choose=int(d.get("choose", 3)), path=p)


def _line_of(message: str) -> int:
    import re

    m = re.search(r"line (\d+)", message)
    return int(m.group(1)) if m else 1


# -- report -------------------------------------------------------------------------------


def chosen(result: Front, count: int) -> list[int]:
    """Up to ``count`` front designs to draw and export: the best in each objective in turn,
    then the design nearest the ideal point (objectives scaled to the front's range)."""
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
    """A ready-to-run scene (TOML) of the design ``x``: its joints, a constant crank speed."""
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
    """Write the search's report to ``folder`` (safely: see :mod:`linkage.report`): every
    candidate (``candidates.parquet`` with pyarrow, else ``candidates.csv``), ``front.csv``,
    ``pareto.png`` (objectives pairwise, with units, the reference design marked),
    ``designs.png`` (the chosen designs' foot paths and linkages), one scene per chosen design
    (``design-<k>.toml``) and ``summary.json`` (the reference's placement)."""
    from linkage import report

    out = Path(os.path.expanduser(str(folder)))
    target = report._resolve(out)
    earlier = os.path.lexists(target)
    if earlier:
        report._check_existing(out, target, force)
    parent = target.parent
    parent.mkdir(parents=True, exist_ok=True)
    tmp: Path | None = None
    try:
        with report._sigint_held():
            tmp = report._make_sibling(parent, target.name, "partial")
        names = _write_files(result, tmp, choose)
        marker = {
            "tool": "linkage",
            "version": report._version(),
            "scene": result.study.name,
            "files": sorted(names),
        }
        (tmp / report.MARKER).write_text(json.dumps(marker, indent=2) + "\n", encoding="utf-8")
        with report._sigint_held():
            report._commit(out, target, tmp, force)
    except BaseException as exc:
        with report._sigint_held():
            if tmp is not None:
                report._discard_partial(tmp)
        if isinstance(exc, OSError):
            raise LinkageError(
                f"{out}: cannot write the report: {exc} (nothing was written)"
            ) from None
        raise
    return [target / n for n in names]


def _write_files(result: Front, folder: Path, choose: int) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    study = result.study
    fam = family(study.family)
    names: list[str] = []
    header = list(fam.params) + list(FIGURES) + ["front"]
    on_front = np.zeros(len(result.x), dtype=bool)
    on_front[result.front] = True
    table = np.column_stack([result.x, result.figures, on_front.astype(float)])
    try:
        import pyarrow as pa  # type: ignore[import-not-found,import-untyped,unused-ignore]
        import pyarrow.parquet as pq  # type: ignore[import-not-found,import-untyped,unused-ignore]

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
    fig, axes = plt.subplots(1, len(pairs), figsize=(4.2 * len(pairs), 4.0), squeeze=False)
    f_all, g_all = objectives_and_constraints(study, result.figures)
    feas = (g_all <= 0).all(axis=1)
    for ax, (a, b) in zip(axes[0], pairs):
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
        ax.set_xlabel(f"{a} ({UNITS[a]})")
        ax.set_ylabel(f"{b} ({UNITS[b]})")
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle(f"{study.name}: {fam.doc} {result.evaluations} legs, seed {study.seed}")
    fig.tight_layout()
    fig.savefig(folder / "pareto.png", dpi=110)
    plt.close(fig)
    names.append("pareto.png")
    picks = chosen(result, choose)
    if picks:
        fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 4.0), squeeze=False)
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
                f"design {picks.index(i) + 1}: " + ", ".join(f"{o} {figs[o]:.3g}" for o in objs),
                fontsize=8,
            )
            ax.set_aspect("equal")
            ax.set_xlabel("x (length)")
            ax.set_ylabel("y (length)")
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
        "objectives": {o: UNITS[o] for o in objs},
        "seed": study.seed,
        "evaluations": result.evaluations,
        "generations": result.generations,
        "front_size": int(len(result.front)),
        "seconds": result.seconds,
        "reference": {"name": fam.reference_name, **place},
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


def main_design(
    path: str, out: str | None, force: bool, checkpoint: str | None, quiet: bool
) -> int:
    """``linkage design study.toml``: search, write the report, print where the reference
    design sits."""
    from linkage import report

    sf = load_study(path)
    folder = Path(out) if out else report.default_folder(sf.study.name)
    report.prepare(folder, force)
    ck = Path(checkpoint) if checkpoint else folder.with_name(f".{folder.name}.checkpoint")
    result = search(sf.study, checkpoint=ck, progress=not quiet)
    files = write_report(result, folder, sf.choose, force)
    if not quiet:
        place = placement(sf.study, result)
        print(
            f"{sf.study.name}: {result.evaluations} legs in {result.seconds:.1f} s, "
            f"front of {len(result.front)}; reference "
            f"{'feasible' if place['feasible'] else 'infeasible'}, dominated by "
            f"{len(place['dominated_by'])} front designs; ranks {place['rank']}"
        )
        print(f"report: {folder}/ ({', '.join(sorted(p.name for p in files))})")
    return 0
