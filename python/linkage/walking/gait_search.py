"""Gait searches: the crank phases or the duty factor that keep a walker stable or slipping least.

Both search one setting of a :class:`~linkage.walker.Walker` by simulating it over a grid of
candidates: :func:`search_phases` the legs' crank phases under one crank drive,
:func:`search_duty_factor` the duty factor of a crank-speed schedule with every leg on its own
motor. The objective is the minimum static stability margin (``"margin"``, maximised) or the
total foot slip per cycle among statically stable candidates (``"slip"``, minimised).

The phase search is also :meth:`Walker.search_phases <linkage.walker.Walker.search_phases>`,
which does the work: this module imports :mod:`linkage.walker`, not the other way.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import get_args

import numpy as np
from numpy.typing import NDArray

from linkage._core import LinkageError
from linkage._shared.arrays import as_choice, as_count, as_finite
from linkage._shared.choices import Objective
from linkage.drives.drive import crank_schedule, stance_profile
from linkage.walking.walker import Walker

__all__ = ["search_duty_factor", "search_phases"]

Array = NDArray[np.float64]


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
    if not isinstance(walker, Walker):
        raise TypeError(f"walker must be a Walker, got {type(walker).__name__}")
    return walker.search_phases(objective, step, samples, rounds, max_evals)


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
    if not isinstance(walker, Walker):
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
