"""Gait searches: the crank phases or the duty factor that keep a walker stable or slipping least.

Both search one setting of a :class:`~linkage.walker.Walker` by simulating it over a grid of
candidates: :func:`search_phases` the legs' crank phases under one crank drive,
:func:`search_duty_factor` the duty factor of a crank-speed schedule with every leg on its own
motor. The objective is the minimum static stability margin (``"margin"``, maximised) or the
total foot slip per cycle among statically stable candidates (``"slip"``, minimised).

Both are also reachable as before: ``Walker.search_phases`` and ``linkage.walker.search_*``.
For those, :mod:`linkage.walker` imports this module, and this one does not import it: a
walker is checked against the class ``_Walkers``, as which :class:`~linkage.walker.Walker`
registers itself.
"""

from __future__ import annotations

import itertools
import math
from abc import ABC
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, get_args

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.arrays import as_choice, as_count, as_finite
from linkage._shared.choices import Objective
from linkage.drives.drive import crank_schedule, stance_profile

if TYPE_CHECKING:
    # Not imported when running: linkage.walker imports this module.
    from linkage.walking.walker import Walker

__all__ = ["search_duty_factor", "search_phases"]

Array = NDArray[np.float64]


class _Walkers(ABC):  # noqa: B024 (no abstract methods: a type to register with)
    """The type of the walkers the searches take: :class:`linkage.walker.Walker` (registered).

    An ``isinstance`` check against this class is one against ``Walker`` without importing
    :mod:`linkage.walker`, which imports this module.
    """


def search_phases(
    walker: Walker,
    objective: Objective = "margin",
    step: float = math.radians(15.0),
    samples: int = 360,
    rounds: int = 3,
    max_evals: int = 5000,
) -> tuple[Array, float]:
    """Search the crank phases that maximise the stability margin or minimise the foot slip.

    The first leg's phase is kept; the others take values on a grid of ``step``. With
    ``"margin"`` the phases maximise the minimum static stability margin over a turn; with
    ``"slip"`` they minimise the total foot slip per cycle among statically stable phasings (a
    phasing whose margin ever drops below zero is rejected — all legs in phase slip least but
    fall over). The search is exhaustive over the grid when it has at most ``max_evals``
    phasings, otherwise a coordinate search from the current phases, which may take at most
    ``max_evals`` evaluations too (``rounds × (legs − 1) × 2π/step``), so the search time stays
    bounded. Legs' tracks are computed once and shifted, so a phasing costs one support-polygon
    pass.

    Parameters
    ----------
    walker : Walker
        The walker; its phases are the coordinate search's start.
    objective : {"margin", "slip"}, default "margin"
        What to optimise.
    step : float, default 15°
        Grid of the phases (radians); ``2π/step`` must be a whole number of at least 2.
    samples : int, default 360
        Samples per turn (rounded up to a multiple of the grid).
    rounds : int, default 3
        Passes of the coordinate search over the legs.
    max_evals : int, default 5000
        The most phasings evaluated.

    Returns
    -------
    phases : ndarray, shape (legs,)
        The best crank phases found (radians, on the grid).
    value : float
        Their minimum stability margin (``"margin"``) or foot slip per cycle (``"slip"``; ``inf``
        when no phasing on the grid is stable).

    Raises
    ------
    LinkageError
        For a ``step`` that does not divide a full turn, a search that would need more than
        ``max_evals`` evaluations, an unknown objective or a count out of range.
    TypeError
        If ``walker`` is not a :class:`~linkage.walker.Walker`.

    Examples
    --------
    Thesis 1's quadruped on a quarter-turn grid keeps its diagonal gait:

    >>> import math, numpy as np, linkage
    >>> from linkage.gait_search import search_phases
    >>> phases, margin = search_phases(linkage.catalog.quadruped_hoecken(), step=math.pi / 2,
    ...                                samples=64)
    >>> np.degrees(phases).round(6), round(margin, 3)
    (array([  0., 180., 180.,   0.]), 4.224)

    A step must divide the turn:

    >>> search_phases(linkage.catalog.quadruped_hoecken(), step=0.7)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: step must divide a full turn (2π/step a whole number ≥ 2)
    """
    if not isinstance(walker, _Walkers):
        raise TypeError(f"walker must be a Walker, got {type(walker).__name__}")
    objective = as_choice(objective, "objective", get_args(Objective))
    step = as_finite(step, "step")
    samples = as_count(samples, "samples")
    rounds = as_count(rounds, "rounds", 0)
    max_evals = as_count(max_evals, "max_evals", 0)
    turns = 2 * math.pi / step if step > 0 else math.inf
    if not (math.isfinite(turns) and turns < 2**53):
        raise LinkageError(f"step must divide a full turn into at most 2**53 parts, got {step!r}")
    g = round(turns)
    if g < 2 or abs(g * step - 2 * math.pi) > 1e-9:
        raise LinkageError("step must divide a full turn (2π/step a whole number ≥ 2)")
    per = max(1, -(-samples // g))
    n = g * per
    walker._check_size(n)
    theta = np.linspace(0, 2 * math.pi, n, endpoint=False)
    # Every leg's track at phase 0 over one turn; a phase on the grid is a cyclic shift.
    base = [replace(leg, phase=0.0).feet(theta, np.ones(n)) for leg in walker.legs]
    t = theta.copy()

    def score(k: Sequence[int]) -> float:
        feet = np.stack([np.roll(base[i][0], -k[i] * per, axis=0) for i in range(len(k))], 1)
        vel = np.stack([np.roll(base[i][1], -k[i] * per, axis=0) for i in range(len(k))], 1)
        sim = walker._evaluate(theta, t, feet, vel)
        if objective == "margin":
            return sim.min_margin
        if sim.min_margin < 0:
            return -math.inf
        return -float(sim.slip_distance.sum())

    start = [round(p / step) % g for p in walker.phases]
    free = len(walker.legs) - 1
    exhaustive = g**free <= max_evals
    if not exhaustive and rounds * free * g > max(max_evals, 1):
        # Bounded time: the coordinate search tries every grid phase of every leg per round.
        raise LinkageError(
            f"step {step:g} gives {g} phases per leg: the search would need "
            f"{rounds * free * g} evaluations, more than max_evals = {max_evals}"
        )
    if exhaustive:
        # Exhaustive over the grid (the first leg fixed).
        best_k, best_val = start, score(start)
        for combo in itertools.product(range(g), repeat=free):
            k = [start[0], *combo]
            v = score(k)
            if v > best_val + 1e-12:
                best_k, best_val = k, v
    else:
        best_k, best_val = start, score(start)
        for _ in range(rounds):
            improved = False
            for i in range(1, len(walker.legs)):
                for c in range(g):
                    k = list(best_k)
                    k[i] = c
                    v = score(k)
                    if v > best_val + 1e-12:
                        best_k, best_val, improved = k, v, True
            if not improved:
                break
    phases = np.array([k * step for k in best_k])
    return phases, best_val if objective == "margin" else -best_val


def search_duty_factor(
    walker: Walker,
    foot_speed: float,
    objective: Objective = "margin",
    duty_factors: Sequence[float] = tuple(np.linspace(0.5, 0.75, 11)),
    samples: int = 721,
) -> tuple[float, float]:
    """Search the duty factor of a crank-speed schedule for the best margin or the least slip.

    Every leg runs the schedule (:func:`linkage.drive.crank_schedule` of the first leg at
    ``foot_speed``) on its own motor, shifted in time by its phase's share of the period. With
    ``"margin"`` the duty factor maximises the minimum static stability margin; with ``"slip"``
    it minimises the foot slip per cycle among stable runs. Duty factors whose schedule is
    infeasible are skipped.

    Parameters
    ----------
    walker : Walker
        The walker; its first leg's linkage sets the schedule.
    foot_speed : float
        The foot's speed along its stance line (length units per second).
    objective : {"margin", "slip"}, default "margin"
        What to optimise.
    duty_factors : sequence of float, default 0.5 to 0.75 in steps of 0.025
        The candidates, each a share of the cycle in stance.
    samples : int, default 721
        Samples per schedule period.

    Returns
    -------
    duty_factor : float
        The best candidate.
    value : float
        Its minimum stability margin (``"margin"``) or foot slip per cycle (``"slip"``; ``inf``
        when no candidate runs stably).

    Raises
    ------
    LinkageError
        When no candidate gives a feasible schedule, or for an unknown objective or a count out
        of range.
    TypeError
        If ``walker`` is not a :class:`~linkage.walker.Walker` or ``duty_factors`` is not a
        sequence of numbers.

    Examples
    --------
    >>> import linkage
    >>> from linkage.gait_search import search_duty_factor
    >>> q = linkage.catalog.quadruped_hoecken()
    >>> beta, margin = search_duty_factor(q, 80.0, duty_factors=(0.5, 0.6, 0.7), samples=121)
    >>> beta, round(margin, 3)
    (0.7, 8.307)

    A duty factor the schedule cannot reach is skipped; with none left the search fails:

    >>> search_duty_factor(q, 80.0, duty_factors=(0.3,), samples=121)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: no duty factor gives a feasible schedule
    """
    if not isinstance(walker, _Walkers):
        raise TypeError(f"walker must be a Walker, got {type(walker).__name__}")
    objective = as_choice(objective, "objective", get_args(Objective))
    samples = as_count(samples, "samples")
    walker._check_size(samples)
    if isinstance(duty_factors, (str, bytes)) or not hasattr(duty_factors, "__iter__"):
        raise TypeError(
            f"duty_factors must be a sequence of numbers, got {type(duty_factors).__name__}"
        )
    betas = [as_finite(b, "duty_factors[]") for b in duty_factors]
    best: tuple[float, float] | None = None
    # The stance is the same for every duty factor: find it once.
    leg = walker.legs[0].linkage
    stance = stance_profile(leg)
    for beta in betas:
        try:
            sched = crank_schedule(leg, foot_speed, beta, stance=stance)
        except LinkageError:
            continue
        t = np.linspace(0.0, sched.period, samples)
        sim = walker.simulate(time=t, drive=sched, per_leg_time=True)
        if objective == "margin":
            value = sim.min_margin
        else:
            value = -float(sim.slip_distance.sum()) if sim.min_margin >= 0 else -math.inf
        if best is None or value > best[1]:
            best = (float(beta), value)
    if best is None:
        raise LinkageError("no duty factor gives a feasible schedule")
    return best[0], best[1] if objective == "margin" else -best[1]
