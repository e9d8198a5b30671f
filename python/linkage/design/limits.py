"""What a study may ask: each family's parameter domain, and the memory a search needs.

:class:`~linkage.design.search.Study` checks its values here when it is made, so that a study
file's mistake is found at load (located by :func:`~linkage.design.study_file.load_study`),
not when the search reaches it: :func:`param_domain` bounds each parameter by its kind (a
length, an offset, an angle, a ratio), and :func:`search_memory` estimates what NSGA-II and the
kept candidates need, refused beyond :func:`linkage._arrays.memory_limit`.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from typing import NoReturn

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.arrays import _bytes, memory_limit
from linkage.design.cluster import scheduler_address
from linkage.walking.legs import FIGURES, OBJECTIVES, Settings, family

__all__ = [
    "INDIVIDUAL_BYTES",
    "INITIAL_POPULATION",
    "MATRIX_BYTES",
    "NEIGHBOUR_SPREAD",
    "SIZE_LIMIT",
    "Constraints",
    "Study",
    "StudyError",
    "StudyMemoryError",
    "check_memory",
    "check_study",
    "param_domain",
    "search_memory",
]

Array = NDArray[np.float64]


class StudyError(LinkageError):
    """A study value out of place.

    ``section`` (``["design"]``, ``["design", "bounds"]``…) and ``key`` say which, ``problem``
    says what (a study file locates it by line).
    """

    def __init__(self, message: str, section: list[str], key: str, problem: str) -> None:
        super().__init__(message)
        self.section = section
        self.key = key
        self.problem = problem


class StudyMemoryError(StudyError, MemoryError):
    """A study whose search cannot fit in this process's memory (also a ``MemoryError``)."""


_LENGTH, _OFFSET, _RADIANS, _DEGREES, _RATIO = "length", "offset", "radians", "degrees", "ratio"
_KINDS: dict[str, dict[str, str]] = {
    "fourbar": {"ground": _LENGTH, "ground_angle": _RADIANS, "coupler": _LENGTH, "rocker": _LENGTH},
    "jansen": {p: _LENGTH for p in "bcdefghijk"},
    "klann": {
        **{p: _LENGTH for p in ("crank", "ground", "pivot_b", "rocker", "coupler", "leg")},
        **{p: _DEGREES for p in ("pivot_b_angle", "alpha", "foot_angle", "tilt")},
        "leg_rocker": _LENGTH,
        "rho": _RATIO,
    },
    "guided": {
        **{p: _LENGTH for p in ("ground", "coupler", "rocker", "guide", "link")},
        "ground_angle": _RADIANS,
    },
}
"""Each family's parameters by kind; any other (a position or offset) is an ``offset``."""

SIZE_LIMIT = 1e6
"""Lengths and offsets are bounded by this many times the family's scale (far beyond any leg,
well within floating point)."""


def param_domain(family_name: str) -> dict[str, tuple[float, float, str]]:
    """Return each parameter's domain: ``{name: (lowest, highest, what)}``.

    Lengths are positive (the lowest is excluded), offsets of either sign; both within
    :data:`SIZE_LIMIT` times the family's scale. Angles within a turn either way (radians or
    degrees as the family takes them), ratios positive up to 1000.

    Examples
    --------
    >>> from linkage.design.search import param_domain
    >>> d = param_domain("fourbar")
    >>> d["coupler"], d["ground_angle"][2], d["along"][:2]
    ((0.0, 50000000.0, 'a length: more than 0'), 'an angle in radians', (-50000000.0, 50000000.0))
    """
    fam = family(family_name)
    size = SIZE_LIMIT * fam.scale
    kinds = _KINDS.get(fam.name, {})
    out: dict[str, tuple[float, float, str]] = {}
    for p in fam.params:
        kind = kinds.get(p, _OFFSET)
        out[p] = {
            _LENGTH: (0.0, size, "a length: more than 0"),
            _OFFSET: (-size, size, "a position or offset"),
            _RADIANS: (-2 * math.pi, 2 * math.pi, "an angle in radians"),
            _DEGREES: (-360.0, 360.0, "an angle in degrees"),
            _RATIO: (0.0, 1000.0, "a ratio: more than 0"),
        }[kind]
    return out


MATRIX_BYTES = 17
"""Bytes per population² pymoo's NSGA-II holds at its peak in a generation (its duplicate check
and sorting build population × population matrices: measured with ``tracemalloc`` 17.35 at
4 000, 17.7 at 2 000, 19.8 at 500, with the linear part)."""
INDIVIDUAL_BYTES = 2048
"""Bytes per individual of pymoo's population objects (measured about 1 400)."""


def search_memory(study: Study) -> tuple[int, int]:
    """Return the bytes a search of ``study`` needs: (the optimiser's, the candidates').

    The optimiser's peak per generation (:data:`MATRIX_BYTES` × population² plus
    :data:`INDIVIDUAL_BYTES` for the population and its offspring), and every candidate's
    parameters and figures kept three times over (the lists, the joined arrays, the checkpoint).

    Examples
    --------
    >>> from linkage.design.search import Study, search_memory
    >>> opt, candidates = search_memory(Study(population=1000, budget=10_000))
    >>> round(opt / 2**20, 1), round(candidates / 2**20, 1)    # MiB
    (20.1, 3.7)
    """
    n = study.population
    rows = study.generations * n
    width = len(family(study.family).params) + len(FIGURES)
    return MATRIX_BYTES * n * n + INDIVIDUAL_BYTES * 2 * n, 3 * 8 * rows * width


def check_memory(study: Study) -> None:
    """Refuse a study whose search cannot fit in memory, with the estimate."""
    limit = memory_limit()
    opt, cands = search_memory(study)
    if opt > limit:
        problem = (
            f"a population of {study.population} needs {_bytes(opt)} for NSGA-II's "
            f"population × population matrices; this process can hold {_bytes(limit)}: "
            f"use a population of at most {math.isqrt(limit // (MATRIX_BYTES + 1))}"
        )
        raise StudyMemoryError(problem, ["design"], "population", problem)
    if opt + cands > limit:
        problem = (
            f"{study.generations * study.population} candidates need {_bytes(cands)} kept "
            f"with their figures, and the optimiser {_bytes(opt)}; this process can hold "
            f"{_bytes(limit)}"
        )
        raise StudyMemoryError(problem, ["design"], "budget", problem)


def check_study(study: Study) -> None:
    """Check every value of ``study``: a :class:`StudyError` (a ``LinkageError``) naming the key.

    Objectives known and distinct; bounds within the family's domain (:func:`param_domain`);
    the constraints' angle and fraction in range; the stance tolerance a fraction of at most
    one half; the scheduler an address this tool can use
    (:func:`linkage.design.cluster.scheduler_address`); the search's memory within this
    process's (:func:`check_memory`).

    Examples
    --------
    >>> from linkage.design.search import Study
    >>> Study(bounds={"coupler": (-5.0, 30.0)})
    Traceback (most recent call last):
    ...
    linkage.design.limits.StudyError: bounds of 'coupler' must be within the family's domain (a length: more than 0), got (-5.0, 30.0)
    >>> Study(population=10**6, budget=10**6)
    Traceback (most recent call last):
    ...
    linkage.design.limits.StudyMemoryError: a population of 1000000 needs 15.5 TiB ...
    """  # noqa: E501
    fam = family(study.family)

    def bad(section: list[str], key: str, problem: str, message: str | None = None) -> NoReturn:
        raise StudyError(message or f"{key} {problem}", section, key, problem)

    design = ["design"]
    if not study.objectives:
        bad(
            design,
            "objectives",
            "needs at least one objective",
            "a study needs at least one objective",
        )
    for o in study.objectives:
        if not isinstance(o, str) or o not in OBJECTIVES:
            bad(
                design,
                "objectives",
                f"unknown objective {o!r}; choose from {', '.join(OBJECTIVES)}",
                f"unknown objective {o!r}; choose from {', '.join(OBJECTIVES)}",
            )
    if len(set(study.objectives)) != len(study.objectives):
        bad(design, "objectives", f"lists an objective twice: {list(study.objectives)}")
    domain = param_domain(fam.name)
    for k, (lo, hi) in study.bounds.items():
        if k not in fam.params:
            bad(
                ["design", "bounds"],
                k,
                f"family {fam.name!r} has no parameter {k!r}; it has {', '.join(fam.params)}",
                f"family {fam.name!r} has no parameter {k!r}; it has {', '.join(fam.params)}",
            )
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            bad(
                ["design", "bounds"],
                k,
                f"must be [lower, upper] with finite lower < upper, got {[lo, hi]!r}",
                f"bounds of {k!r} must be finite with lower < upper",
            )
        d_lo, d_hi, what = domain[k]
        length = what.endswith("more than 0")
        if (lo <= d_lo if length else lo < d_lo) or hi > d_hi:
            bad(
                ["design", "bounds"],
                k,
                f"must be within the family's domain ({what}, up to {d_hi:g}), got {[lo, hi]!r}",
                f"bounds of {k!r} must be within the family's domain ({what}), got {(lo, hi)!r}",
            )
    if study.population < 4:
        bad(
            design,
            "population",
            f"must be at least 4, got {study.population}",
            f"population must be at least 4, got {study.population}",
        )
    if study.budget < study.population:
        bad(
            design,
            "budget",
            f"must be at least one population ({study.population})",
            f"budget ({study.budget}) must be at least one population ({study.population})",
        )
    if study.workers < 0 or study.chunk < 1:
        bad(
            design,
            "workers" if study.workers < 0 else "chunk",
            "workers must be ≥ 0 and chunk ≥ 1",
            "workers must be ≥ 0 and chunk ≥ 1",
        )
    st = study.settings
    if not (isinstance(st.stance_tol, (int, float)) and 0.0 <= st.stance_tol <= 0.5):
        bad(
            design,
            "stance_tol",
            f"must be a fraction of the path's extent from 0 to 0.5, got {st.stance_tol!r}",
        )
    size = SIZE_LIMIT * fam.scale
    if not (isinstance(st.foot_bar, (int, float)) and 0.0 <= st.foot_bar <= size):
        bad(design, "foot_bar", f"must be a length from 0 to {size:g}, got {st.foot_bar!r}")
    c = study.constraints
    ranges = {
        "min_transmission": (0.0, 90.0, "an angle in degrees"),
        "min_duty": (0.0, 1.0, "a fraction"),
        "foot_below_hip": (-size, size, "a length"),
        "min_lift": (-size, size, "a length"),
    }
    for key, (lo, hi, what) in ranges.items():
        v = getattr(c, key)
        if not (isinstance(v, (int, float)) and lo <= v <= hi):
            bad(
                ["design", "constraints"],
                key,
                f"must be {what} from {lo:g} to {hi:g}, got {v!r}",
            )
    if study.scheduler is not None:
        try:
            scheduler_address(study.scheduler)
        except LinkageError as exc:
            bad(design, "scheduler", str(exc), f"scheduler {exc}")
    check_memory(study)


# -- the study (linkage.design.search re-exports it) ----------------------------------------

INITIAL_POPULATION = "reference, neighbours within 2 % of the box, uniform"
"""How the first population is drawn (part of a checkpoint's fingerprint)."""

NEIGHBOUR_SPREAD = 0.02
"""Half-width of the reference's neighbourhood, as a fraction of each parameter's bounds."""


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
        """Check every value (:func:`linkage.design.limits.check_study`)."""
        check_study(self)

    @property
    def generations(self) -> int:
        """Generations the budget pays for (the first population included)."""
        return self.budget // self.population

    def box(self) -> tuple[Array, Array]:
        """Lower and upper bounds of every parameter (the family's, overridden).

        Examples
        --------
        >>> from linkage.design import family
        >>> from linkage.design.search import Study
        >>> lo, hi = Study(bounds={"ground": (12.0, 40.0)}).box()
        >>> dict(zip(family("fourbar").params, zip(lo.tolist(), hi.tolist())))["ground"]
        (12.0, 40.0)
        >>> lo.shape, bool((lo < hi).all())
        ((6,), True)
        """
        fam = family(self.family)
        b = fam.bounds()
        b.update(self.bounds)
        return (
            np.array([b[p][0] for p in fam.params], dtype=float),
            np.array([b[p][1] for p in fam.params], dtype=float),
        )

    def fingerprint(self) -> str:
        """Return what a checkpoint must match to be resumed (everything but where it runs).

        Examples
        --------
        >>> from linkage.design.search import Study
        >>> fp = Study().fingerprint()
        >>> len(fp), fp == Study(workers=2).fingerprint(), fp == Study(seed=2).fingerprint()
        (16, True, False)
        """
        d = {
            "family": self.family,
            "objectives": self.objectives,
            "box": [v.tolist() for v in self.box()],
            "constraints": self.constraints.__dict__,
            "settings": self.settings.__dict__,
            "population": self.population,
            "seed": self.seed,
            "start": INITIAL_POPULATION,
        }
        return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Constraints": Constraints, "Study": Study}
for _cls in __test__.values():
    _cls.__module__ = "linkage.design.search"
