"""The search: a study, its evaluation in chunks, NSGA-II and the Pareto front.

A study gives the family, bounds, objectives, constraints, budget, seed and where it runs; its
candidates are evaluated in chunks (in this process, on a LocalCluster or on a scheduler's cluster),
NSGA-II runs by ask and tell with a checkpoint after every generation, and the result is the Pareto
front and where the family's reference design sits relative to it.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import distributed
import numpy as np
from numpy.typing import NDArray
from pymoo.algorithms.moo.nsga2 import NSGA2  # type: ignore[import-untyped]
from pymoo.core.problem import Problem  # type: ignore[import-untyped]

from linkage._shared.progress import Bar
from linkage.design import checkpoint as _checkpoint
from linkage.design.cluster import SchedulerError, connect, gather, scheduler_address
from linkage.design.limits import (
    INITIAL_POPULATION,
    NEIGHBOUR_SPREAD,
    Constraints,
    Study,
    StudyError,
    StudyMemoryError,
    param_domain,
    search_memory,
)
from linkage.walking.legs import FIGURES, OBJECTIVES, Settings, family

__all__ = [
    "INITIAL_POPULATION",
    "NEIGHBOUR_SPREAD",
    "Constraints",
    "Evaluator",
    "Front",
    "SchedulerError",
    "Study",
    "StudyError",
    "StudyMemoryError",
    "evaluate_chunk",
    "initial_population",
    "objectives_and_constraints",
    "param_domain",
    "pareto_front",
    "placement",
    "reference_figures",
    "search",
    "search_memory",
]

Array = NDArray[np.float64]


# -- the study ----------------------------------------------------------------------------


def objectives_and_constraints(study: Study, figs: Array) -> tuple[Array, Array]:
    """Compute pymoo's ``F`` (minimised) and ``G`` (≤ 0 feasible) from figures.

    Constraints are scaled to comparable sizes (angles by 90°, lengths by the family's scale, the
    duty factor as it is) so that the optimiser's summed violation weighs them alike. A candidate
    without figures (no full turn) gets the worst objectives the optimiser can rank (1e12, never
    reported); it violates the full-turn and one-stance-run constraints by 1 (its ``full_turn`` is
    0 and its ``stance_runs`` 0) and every other, whose figure is NaN, by 10.

    Examples
    --------
    Hoecken's leg (the family's reference) on a 100 mm foot bar, and a four-bar that does not
    assemble (coupler and rocker too short to reach across the ground):

    >>> import numpy as np
    >>> from linkage.design import Settings, family
    >>> from linkage.design.search import Study, objectives_and_constraints
    >>> study = Study(settings=Settings(samples=64, foot_bar=100.0))
    >>> x = np.array([family("fourbar").reference, [20.0, 0.0, 5.0, 5.0, 50.0, 0.0]])
    >>> f, g = objectives_and_constraints(study, family("fourbar").evaluate(x, study.settings))
    >>> f.round(3)             # -stride, straightness, speed variation: all minimised
    array([[-4.353e+01,  5.100e-02,  4.520e-01],
           [ 1.000e+12,  1.000e+12,  1.000e+12]])
    >>> (g <= 0).all(axis=1)   # feasible, infeasible
    array([ True, False])
    >>> g[1]                   # full turn, one stance run, then the bounds
    array([ 1.,  1., 10., 10., 10., 10.])
    """
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
    """Figures of one chunk of candidates (what a Dask task runs).

    Examples
    --------
    >>> import numpy as np
    >>> from linkage.design import FIGURES, Settings, family
    >>> from linkage.design.search import evaluate_chunk
    >>> x = np.array([family("fourbar").reference, [20.0, 0.0, 5.0, 5.0, 50.0, 0.0]])
    >>> figs = evaluate_chunk("fourbar", x, Settings(samples=64))
    >>> figs.shape == (2, len(FIGURES)), figs[:, FIGURES.index("full_turn")]
    (True, array([1., 0.]))
    >>> [round(float(v), 4) for v in figs[:, FIGURES.index("duty_factor")]]
    [0.5781, nan]
    """
    return family(family_name).evaluate(x, settings)


class Evaluator:
    """Evaluator of candidates in this process, on a LocalCluster or on a scheduler's cluster.

    Candidates are evaluated in chunks of ``chunk`` gathered in order (the same figures either way).
    A scheduler is reached and waited on within bounds (:mod:`linkage.design.cluster`): one that
    does not answer, or answers as no Dask scheduler does, is a :class:`SchedulerError`.
    """

    def __init__(self, study: Study) -> None:
        self.study = study
        self.client: Any = None
        self.cluster: Any = None
        self.address: str | None = None
        if study.scheduler is not None:
            self.address = scheduler_address(study.scheduler)
            self.client = connect(self.address)
        elif study.workers > 0:
            self.cluster = distributed.LocalCluster(  # type: ignore[no-untyped-call]
                n_workers=study.workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
            )
            self.client = distributed.Client(self.cluster)  # type: ignore[no-untyped-call]

    def __call__(self, x: Array) -> Array:
        """Evaluate the candidates ``x`` (M, params): their figures (M, figures), in order."""
        s = self.study
        if self.client is None:
            return evaluate_chunk(s.family, x, s.settings)
        parts = [x[i : i + s.chunk] for i in range(0, len(x), s.chunk)]
        futures = self.client.map(
            evaluate_chunk, [s.family] * len(parts), parts, [s.settings] * len(parts), pure=False
        )
        return np.concatenate(gather(self.client, futures, self.address), axis=0)

    def close(self) -> None:
        """Close the client and the local cluster, if any.

        Examples
        --------
        Evaluated in this process (``workers=0``, no scheduler) there is nothing to close:

        >>> import numpy as np
        >>> from linkage.design import Settings, family
        >>> from linkage.design.search import Evaluator, Study
        >>> ev = Evaluator(Study(settings=Settings(samples=64)))
        >>> ev(np.array([family("fourbar").reference])).shape
        (1, 10)
        >>> ev.close()
        >>> ev.client is None and ev.cluster is None
        True
        """
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def __enter__(self) -> Evaluator:
        """Return the evaluator itself."""
        return self

    def __exit__(self, *exc: Any) -> None:
        """Close the evaluator (see :meth:`close`)."""
        self.close()


# -- the search ---------------------------------------------------------------------------


def initial_population(study: Study) -> Array:
    """Return the first population ``(population, params)``, deterministic for the seed.

    Row 0 is the family's reference design, then ``population // 8`` designs drawn uniformly
    within ±2 % of each parameter's bounds around it (clipped to the box), then designs drawn
    uniformly over the box. The reference is a candidate so that the front, the non-dominated
    set of every candidate, holds it or designs dominating it: the four-bar family's feasible
    set is a sliver of the box (no design of 200 000 drawn uniformly meets the example study's
    duty factor ≥ 0.4), and a search started from the box alone converges on the first feasible
    pocket it reaches. A reference outside the study's bounds is left out (and so are its
    neighbours): the search then covers only the box.

    Examples
    --------
    >>> import numpy as np
    >>> from linkage.design import family
    >>> from linkage.design.search import Study, initial_population
    >>> ref = np.array(family("fourbar").reference)
    >>> x = initial_population(Study(population=16))
    >>> x.shape, bool((x[0] == ref).all())
    ((16, 6), True)
    >>> near = np.abs(x[1:3] - ref) <= 0.02 * np.subtract(*Study().box()[::-1])
    >>> bool(near.all())                # population // 8 = 2 neighbours
    True

    With bounds that exclude the reference (its ground is 20) it is left out:

    >>> x = initial_population(Study(population=16, bounds={"ground": (30.0, 40.0)}))
    >>> bool((x == ref).all(axis=1).any()), float(x[:, 0].min()) >= 30.0
    (False, True)
    """
    fam = family(study.family)
    xl, xu = study.box()
    rng = np.random.default_rng(study.seed)
    ref = np.asarray(fam.reference, dtype=float)
    rows: list[Array] = []
    if np.all((xl <= ref) & (ref <= xu)):
        rows.append(ref[None, :])
        n = study.population // 8
        half = NEIGHBOUR_SPREAD * (xu - xl)
        rows.append(np.clip(ref + rng.uniform(-1.0, 1.0, (n, len(ref))) * half, xl, xu))
    n = study.population - sum(len(r) for r in rows)
    rows.append(xl + rng.random((n, len(xl))) * (xu - xl))
    return np.concatenate(rows)


class _Box(Problem):  # type: ignore[misc]
    """The search space for pymoo: evaluation is done outside (ask/tell), so it pickles."""

    def __init__(self, n_var: int, n_obj: int, n_constr: int, xl: Array, xu: Array) -> None:
        super().__init__(n_var=n_var, n_obj=n_obj, n_ieq_constr=n_constr, xl=xl, xu=xu)


@dataclass
class Front:
    """The search's result: every candidate evaluated, the final Pareto front, and the study.

    Candidates are kept in order (parameters and figures); the front is their indices.
    """

    study: Study
    x: Array
    figures: Array
    front: NDArray[np.int64]
    generations: int
    evaluations: int
    seconds: float = 0.0

    def front_x(self) -> Array:
        """Return the parameters of the front's candidates, (F, params).

        Examples
        --------
        >>> from linkage.design import Settings
        >>> from linkage.design.search import Study, search
        >>> result = search(Study(population=4, budget=8, settings=Settings(samples=64)))
        >>> result.front_x().shape == (len(result.front), 6), result.x.shape
        (True, (8, 6))
        """
        return self.x[self.front]

    def front_figures(self) -> Array:
        """Return the figures of the front's candidates, (F, figures).

        Examples
        --------
        With the default constraints Hoecken's leg is infeasible (its foot is above the hip:
        ``foot_below_hip`` is 0 and there is no foot bar), and so is every candidate of this tiny
        search: the front is empty.

        >>> from linkage.design import Settings
        >>> from linkage.design.search import Study, search
        >>> result = search(Study(population=4, budget=8, settings=Settings(samples=64)))
        >>> result.front_figures().shape, result.front.tolist()
        ((0, 10), [])
        """
        return self.figures[self.front]


def _uses_global_rng(algorithm: Any) -> bool:
    """Return whether the algorithm draws from the process-wide random generators.

    pymoo 0.6.2 on draws from a generator of its own (``algorithm.random_state``), whose state
    the checkpoint holds. Earlier releases (0.6.1, the last for Python 3.9) seed and draw from the
    global ``random`` and ``numpy.random`` generators instead, so a checkpoint must carry their
    states too for a resumed search to reach the same front.
    """
    return not isinstance(getattr(algorithm, "random_state", None), np.random.Generator)


def search(
    study: Study,
    checkpoint: str | Path | None = None,
    progress: bool = False,
    stop_after: int | None = None,
) -> Front:
    """Run NSGA-II over the study's family; returns the :class:`Front`.

    The first population holds the family's reference design and designs around it
    (:func:`initial_population`), so the front, the non-dominated set of every candidate, holds
    the reference or designs that dominate it, and none that it dominates.

    With ``checkpoint`` the state is saved atomically after every generation
    (:mod:`linkage.design.checkpoint`: plain arrays, never a pickle) and a search started again
    with the same study resumes from it (to the same front: the optimiser's random state is part
    of the checkpoint, see :func:`_uses_global_rng`); the temporaries of killed runs beside it
    are swept first. ``stop_after`` ends after that many generations in this call (a stopped
    search, for tests). ``progress`` draws a bar on stderr.

    Examples
    --------
    The smallest search (two generations of four), Hoecken's leg on a 100 mm foot bar:

    >>> from linkage.design import Settings
    >>> from linkage.design.search import Study, search
    >>> study = Study(population=4, budget=8, settings=Settings(samples=64, foot_bar=100.0),
    ...               bounds={"ground": (15.0, 25.0), "coupler": (20.0, 30.0)})
    >>> result = search(study)
    >>> result.generations, result.evaluations, result.front.tolist()
    (2, 8, [0])
    >>> search(study).front_x().tolist() == result.front_x().tolist()   # the same for a seed
    True
    >>> search("study.toml")
    Traceback (most recent call last):
    ...
    TypeError: study must be a Study, got str
    >>> Study(population=2)
    Traceback (most recent call last):
    ...
    linkage.design.limits.StudyError: population must be at least 4, got 2
    """
    if not isinstance(study, Study):
        raise TypeError(f"study must be a Study, got {type(study).__name__}")
    fam = family(study.family)
    xl, xu = study.box()
    n_con = 6
    path = Path(checkpoint) if checkpoint is not None else None
    saved = None
    if path is not None:
        _checkpoint.sweep(path)
        saved = _checkpoint.load(path, study)
    t0 = time.perf_counter()
    problem = _Box(len(fam.params), len(study.objectives), n_con, xl, xu)
    algorithm = NSGA2(pop_size=study.population, sampling=initial_population(study))
    algorithm.setup(problem, termination=("n_gen", study.generations), seed=study.seed)
    xs: list[Array] = []
    figs: list[Array] = []
    gen = 0
    if saved is not None and path is not None:
        f, g = objectives_and_constraints(study, saved.figures[saved.pop_index])
        _checkpoint.restore(path, saved, algorithm, f, g)
        xs, figs, gen = [np.array(saved.x)], [np.array(saved.figures)], saved.generation
    global_rng = _uses_global_rng(algorithm)
    done_here = 0
    evaluated = sum(len(v) for v in xs)
    bar = Bar("design search", total=study.generations, enabled=progress)
    bar.done = gen
    with Evaluator(study) as ev:
        while gen < study.generations:
            if stop_after is not None and done_here >= stop_after:
                break
            pop = algorithm.ask()
            x = np.asarray(pop.get("X"), dtype=float)
            fig = ev(x)
            f, g = objectives_and_constraints(study, fig)
            # "candidate": each one's row among every candidate (the checkpoint's survivors)
            pop.set("F", f, "G", g, "candidate", np.arange(evaluated, evaluated + len(x)))
            algorithm.tell(infills=pop)
            xs.append(x)
            figs.append(fig)
            evaluated += len(x)
            gen += 1
            done_here += 1
            if path is not None:
                _checkpoint.save(
                    path,
                    study,
                    algorithm,
                    np.concatenate(xs),
                    np.concatenate(figs),
                    gen,
                    global_rng,
                )
            bar.update(1, f"{evaluated} legs evaluated")
    bar.close()
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


def pareto_front(study: Study, figs: Array) -> NDArray[np.int64]:
    """Return the indices of the feasible candidates no other feasible candidate dominates.

    Over every candidate evaluated, in order; duplicates keep their first.

    Examples
    --------
    Hoecken's figures, then the same again (a duplicate), with a shorter stride (dominated),
    with a longer but less straight stride (a trade-off) and without a full turn (infeasible):

    >>> import numpy as np
    >>> from linkage.design import FIGURES, Settings
    >>> from linkage.design.search import Study, pareto_front, reference_figures
    >>> study = Study(settings=Settings(samples=64, foot_bar=100.0))
    >>> figs = np.tile(reference_figures(study), (5, 1))
    >>> figs[2, FIGURES.index("stride")] -= 1.0
    >>> figs[3, FIGURES.index("stride")] += 1.0
    >>> figs[3, FIGURES.index("straightness")] += 0.01
    >>> figs[4, FIGURES.index("full_turn")] = 0.0
    >>> pareto_front(study, figs).tolist()
    [0, 3]

    With no feasible candidate the front is empty:

    >>> pareto_front(study, figs[4:])
    array([], dtype=int64)
    """
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
    """Figures of the family's reference design (the sources' choice) under the study.

    Examples
    --------
    >>> from linkage.design import FIGURES, Settings
    >>> from linkage.design.search import Study, reference_figures
    >>> figs = reference_figures(Study(settings=Settings(samples=64)))
    >>> {n: round(float(figs[FIGURES.index(n)]), 3) for n in ("stride", "lift", "duty_factor")}
    {'stride': 43.53, 'lift': 8.99, 'duty_factor': 0.578}
    """
    fam = family(study.family)
    row: Array = fam.evaluate(np.asarray([fam.reference], dtype=float), study.settings)[0]
    return row


def placement(study: Study, result: Front) -> dict[str, Any]:
    """Place the reference design relative to the front.

    Returns whether it is feasible, whether it is on the front (a candidate with its exact
    parameters is), which front designs dominate it and which it dominates (indices into
    ``result.x``; the latter is empty when the reference was a feasible candidate of the search)
    and, per objective, its rank among the front's values (0 = better than every front design).

    Examples
    --------
    >>> from linkage.design import Settings
    >>> from linkage.design.search import Study, placement, search
    >>> study = Study(population=4, budget=8, settings=Settings(samples=64, foot_bar=100.0),
    ...               bounds={"ground": (15.0, 25.0), "coupler": (20.0, 30.0)})
    >>> place = placement(study, search(study))
    >>> place["feasible"], place["on_front"], place["dominated_by"], place["rank"]["stride"]
    (True, True, [], 0)

    Without the foot bar the reference is infeasible (its foot is above the hip), so it dominates
    nothing:

    >>> study = Study(population=4, budget=8, settings=Settings(samples=64))
    >>> place = placement(study, search(study))
    >>> place["feasible"], place["dominates"], round(place["figures"]["hip_depth"], 6)
    (False, [], -40.0)
    """
    ref = reference_figures(study)
    f_ref, g_ref = objectives_and_constraints(study, ref[None, :])
    f_front, _ = objectives_and_constraints(study, result.front_figures())
    a = f_ref[0]
    dominated_by = np.all(f_front <= a, axis=1) & np.any(f_front < a, axis=1)
    dominates = np.all(a <= f_front, axis=1) & np.any(a < f_front, axis=1)
    feasible = bool((g_ref <= 0).all())
    ref_x = np.asarray(family(study.family).reference, dtype=float)
    ranks = {o: int(np.sum(f_front[:, k] < a[k])) for k, o in enumerate(study.objectives)}
    return {
        "feasible": feasible,
        "on_front": bool(np.any(np.all(result.front_x() == ref_x, axis=1))),
        "dominated_by": [int(i) for i in result.front[dominated_by]],
        "dominates": [int(i) for i in result.front[dominates]] if feasible else [],
        "rank": ranks,
        "figures": {n: float(v) for n, v in zip(FIGURES, ref)},
    }
