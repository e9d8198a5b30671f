"""The stages of a path search, each a source of starts or of refined fits.

The curve's equation, atlas matches, cognates of exact fits, long fits, restarts, parts of a
closed target searched as arcs, and the global search by differential evolution.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage.kinematics.slider_crank import SliderCrank
from linkage.synthesis.atlas import Atlas
from linkage.synthesis.candidates import Candidate, _crossed, _params_of
from linkage.synthesis.fitting import (
    _Budget,
    _errors,
    _finish,
    _measure,
    _placed,
    _slid_along_curves,
)
from linkage.synthesis.kinds import _ARC_KIND, EXACT, FOURBAR, SLIDER, Float2D, _Kind
from linkage.synthesis.targets import target_size

__all__ = [
    "COGNATES_OF",
    "CURVE_EQUATION_POINTS",
    "EQUATION_STARTS",
    "HOPS",
    "PART_FITS",
    "PART_GAP",
    "PART_MATCHES",
    "PART_POINTS",
    "POLISH",
    "POLISH_NFEV",
    "SLID",
    "SLIDER_EQUATION_POINTS",
    "SLIDES",
    "VALLEY",
    "WIDER",
]

CURVE_EQUATION_POINTS: int = _core.synthesis.CURVE_EQUATION_POINTS
"""Fewest target points from which a four-bar is sought through the equation of the curve they
lie on (``linkage_core::CURVE_EQUATION_POINTS``: the equation has 16 coefficients)."""

SLIDER_EQUATION_POINTS: int = _core.synthesis.SLIDER_EQUATION_POINTS
"""Fewest target points from which a slider-crank is sought through the equation of the curve
they lie on (``linkage_core::SLIDER_EQUATION_POINTS``: a circular quartic, 13 coefficients)."""


def _evolution_starts(
    target: Float2D,
    closed: bool,
    size: float,
    centre: NDArray[np.float64],
    seed: int,
    maxiter: int,
    threads: int,
    bar: Any,
    keep: int = 4,
    kind: _Kind = FOURBAR,
    full_turn: bool = False,
    min_transmission: float = 0.0,
) -> list[tuple[NDArray[np.float64], bool]]:
    """Search by differential evolution over placed linkages (a four-bar's both assemblies).

    The population is evaluated in one batch call per generation. A four-bar's shape
    constraints add their shortfall to the cost (:func:`_shortfall`), so the search heads for
    linkages they admit.
    """
    from scipy.optimize import differential_evolution  # type: ignore[import-untyped]  # noqa: PLC0415

    span = 3.0 * size
    pivot = [(centre[0] - span, centre[0] + span), (centre[1] - span, centre[1] + span)]
    if kind is SLIDER:
        # Crank pivot, line direction and offset, crank, rod, coupler point.
        box = [*pivot, (-math.pi, math.pi), (-span, span), (0.05 * size, 4 * size)]
        box += [(0.05 * size, 6 * size), (-span, span), (-span, span)]
    else:
        box = [*pivot, *pivot, (0.05 * size, 4 * size), (0.05 * size, 6 * size)]
        box += [(0.05 * size, 6 * size), (-span, span), (-span, span)]
    found = []
    for crossed in (False, True) if kind is FOURBAR else (False,):

        def cost(pop: NDArray[np.float64], crossed: bool = crossed) -> NDArray[np.float64]:
            params = np.ascontiguousarray(pop.T)
            e, _ = _errors(
                params,
                np.full(len(params), crossed),
                target,
                closed,
                samples=128,
                threads=threads,
                kind=kind,
            )
            f = np.maximum(e[:, 0], e[:, 2]) if closed else e[:, 0]
            if kind is FOURBAR and (full_turn or min_transmission > 0):
                f = f + size * _shortfall(params, size, full_turn, min_transmission, closed)
            return np.where(np.isfinite(f), f, 100.0 * size)

        def step(*_: Any, **__: Any) -> bool:
            if bar is not None:
                bar.update(1)
            return False

        r = differential_evolution(
            cost,
            box,
            popsize=15,
            maxiter=maxiter,
            tol=1e-12,
            seed=seed + int(crossed),
            vectorized=True,
            updating="deferred",
            polish=False,
            callback=step,
        )
        # The best few distinct members of the last generation, for least squares to finish.
        order = np.argsort(r.population_energies, kind="stable")
        for i in order[:keep]:
            found.append((np.asarray(r.population[i], dtype=np.float64), crossed))
    return found


def _shortfall(
    params: NDArray[np.float64],
    size: float,
    full_turn: bool,
    min_transmission: float,
    closed: bool,
) -> NDArray[np.float64]:
    """Return how far each placed four-bar (rows of ``params``) is from its shape constraints.

    A crank that does not turn fully (if ``full_turn``): the lengths by which the base
    ``|C − A|``, over ``[|g − r|, g + r]``, leaves the dyad's ``[|b − c|, b + c]``, over
    ``size``. The transmission angle (a closed target, whose matched part is the whole
    circuit): ``min_transmission`` less its least distance from a toggle, in radians — reached
    at the base's extremes when the crank turns fully, zero (a toggle) when it rocks — by the
    core's one formula (``_core.linkages.min_transmission_angle``).
    """
    g = np.hypot(params[:, 2] - params[:, 0], params[:, 3] - params[:, 1])
    r, b, c = params[:, 4], params[:, 5], params[:, 6]
    lo, hi = np.abs(g - r), g + r
    out = np.zeros(len(params))
    turns = (lo >= np.abs(b - c)) & (hi <= b + c)
    if full_turn:
        out += (np.maximum(0.0, np.abs(b - c) - lo) + np.maximum(0.0, hi - (b + c))) / size
    if closed and min_transmission > 0:
        # The transmission angle's cosine at the base's extremes; over the circuit its sine is
        # least at one of them, and the core folds that sine to the angle's distance from a
        # toggle (0 for a crank that rocks, and for NaN).
        with np.errstate(invalid="ignore", divide="ignore"):
            k_lo = np.clip((b * b + c * c - lo * lo) / (2 * b * c), -1.0, 1.0)
            k_hi = np.clip((b * b + c * c - hi * hi) / (2 * b * c), -1.0, 1.0)
        sine = np.minimum(
            np.sqrt((1.0 - k_lo) * (1.0 + k_lo)), np.sqrt((1.0 - k_hi) * (1.0 + k_hi))
        )
        least = _core.linkages.min_transmission_angle(np.where(turns, sine, 0.0))
        out += np.maximum(0.0, min_transmission - least)
    return out


EQUATION_STARTS = 4
"""Linkages from the curve's equation that are refined (four-bars: of up to 6, each on the
better of its assemblies; slider-cranks: of up to 6, each on the better of its reaches; best
first by their unrefined error): for a four-bar's curve its three cognates, for a
slider-crank's the linkage and its cognate, then the next best solves."""


def _equation_pool(
    target: Float2D, closed: bool, threads: int, kind: _Kind = FOURBAR
) -> list[tuple[NDArray[np.float64], bool, str]]:
    """Return starts from the equation of the curve through ``target``.

    Four-bars: ``linkage_core::fourbars_from_curve``, each on the better of its assemblies.
    Slider-cranks: ``linkage_core::slider_cranks_from_curve``, each on the better of its
    reaches (the line reversed: ``angle + π``, ``−offset``). Best first by their error, at most
    :data:`EQUATION_STARTS`; none for fewer than :data:`CURVE_EQUATION_POINTS` (four-bars) or
    :data:`SLIDER_EQUATION_POINTS` points, or points that give no equation.
    """
    slider = kind is SLIDER
    if len(target) < (SLIDER_EQUATION_POINTS if slider else CURVE_EQUATION_POINTS):
        return []
    solve = (
        _core.synthesis.slider_cranks_from_curve if slider else _core.synthesis.fourbars_from_curve
    )
    try:
        params, _, _, _, _ = solve(np.ascontiguousarray(target))
    except LinkageError:
        return []
    if not len(params):
        return []
    rows = np.repeat(params, 2, axis=0)
    if slider:
        # The other reach of each: the same linkage with its line reversed (no assembly flag).
        rows[1::2, 2] += math.pi
        rows[1::2, 3] *= -1.0
        crossed = np.zeros(len(rows), dtype=bool)
    else:
        crossed = np.tile([False, True], len(params))
    e, _ = _errors(rows, crossed, target, closed, threads=threads, kind=kind)
    chosen: list[int] = []
    for i in np.argsort(e[:, 0], kind="stable"):
        if len(chosen) == EQUATION_STARTS or not np.isfinite(e[i, 0]):
            break
        # One assembly of each four-bar: a double-rocker's two trace one circuit (its two
        # rows fit alike, and would be refined twice). A slider-crank's two rows differ.
        tol = 1e-9 * float(np.max(np.abs(rows[i])))
        if all(np.max(np.abs(rows[i] - rows[j])) > tol for j in chosen):
            chosen.append(int(i))
    return [(rows[i], bool(crossed[i]), "equation") for i in chosen]


COGNATES_OF = 8
"""Most exact four-bar fits whose cognates and reversed drives are measured too (the best
``top`` of them, at most this many: each costs five measurements, about 12 ms)."""


def _cognate_candidates(
    found: list[Candidate[Any]],
    target: Float2D,
    closed: bool,
    size: float,
    threads: int,
    top: int = COGNATES_OF,
) -> list[Candidate[Any]]:
    """Measure the cognates of the best exact fits.

    A four-bar's are its Roberts cognates, each driven at either pivot; a slider-crank's is its
    one cognate (:meth:`SliderCrank.cognate`). They draw the same curve, so they fit as well;
    the search may have stopped at the first exact fit (``top=1``), and a cognate or the other
    drive may turn fully or transmit better, which the ranking prefers. Only those that fit
    exactly are kept.
    """
    exact = sorted((c for c in found if c.error <= EXACT * size), key=lambda c: c.error)
    out: list[Candidate[Any]] = []
    # A tried variant is its parameters and its assembly: the same nine numbers on the other
    # assembly draw another circuit (a cognate's reversed drive on the wrong assembly, 5.6 sizes
    # off, had hidden the exact full-turn cognate with those numbers; found by a new-user trial).
    seen = [(c.params, _crossed(c)) for c in found]
    for c in exact[: min(top, COGNATES_OF)]:
        fb = c.linkage
        if isinstance(fb, SliderCrank):
            out += _slider_cognate(fb, seen, target, closed, size, threads)
            continue
        try:
            first, second = fb.cognates()
            variants = [fb.reversed(), first, second, first.reversed(), second.reversed()]
        except LinkageError:
            continue
        for v in variants:
            x, crossed = _params_of(v), v.assembly == "crossed"
            if _tried(x, crossed, seen, size):
                continue  # found already (a search finds cognates too)
            seen.append((x, crossed))
            cand = _measure(x, crossed, target, closed, "cognate", threads)
            # Exact or nothing: a variant that is not exact traces the curve on another circuit (a
            # crank that rocks over two intervals traces the first; see FourBar.cognates).
            if cand is not None and cand.error <= EXACT * size:
                out.append(cand)
    return out


def _tried(
    x: NDArray[np.float64], crossed: bool, seen: list[tuple[NDArray[np.float64], bool]], size: float
) -> bool:
    """Whether the placed linkage ``x`` on that assembly is in ``seen`` (to 1e-9 of ``size``)."""
    return any(
        f == crossed and q.shape == x.shape and np.max(np.abs(x - q)) <= 1e-9 * size
        for q, f in seen
    )


def _slider_cognate(
    sc: SliderCrank,
    seen: list[tuple[NDArray[np.float64], bool]],
    target: Float2D,
    closed: bool,
    size: float,
    threads: int,
) -> list[Candidate[Any]]:
    """Measure the cognate of an exact slider-crank fit (:meth:`SliderCrank.cognate`).

    Placed on either reach (the line, or the line reversed with the offset negated: a crank
    that turns fully draws the curve on one of them); only an exact fit is kept.
    """
    try:
        cog = sc.cognate()
    except LinkageError:
        return []
    (ox, oy), (along, left) = cog.o, cog.point
    out = []
    for angle, offset in ((cog.angle, cog.offset), (cog.angle + math.pi, -cog.offset)):
        x = np.array([ox, oy, angle, offset, cog.crank, cog.coupler, along, left])
        if _tried(x, False, seen, size):
            continue  # found already
        seen.append((x, False))
        cand = _measure(x, False, target, closed, "cognate", threads, SLIDER)
        if cand is not None and cand.error <= EXACT * size:
            out.append(cand)
    return out


def _shape_order(
    entry: tuple[NDArray[np.float64], bool, str],
    kind: _Kind,
    full_turn: bool,
    min_transmission: float,
) -> tuple[int, float]:
    """Order atlas matches by the shape constraints asked for (a sort key, least first).

    A match whose whole circuit meets them — its crank turns fully (if ``full_turn``) and its
    transmission angle stays ``min_transmission`` from a toggle, properties of the shape known
    before a fit — comes first (in match order, the sort being stable); then the full-turn
    cranks (if asked for) nearest to meeting the transmission bound, as a fit moves the angle;
    then the rest. A match whose circuit passes a toggle may still fit an open target's part
    that avoids it: this only orders the matches to refine.
    """
    x, crossed, _ = entry
    try:
        if kind is SLIDER:
            problem, full, _, _, mu, _ = _core.synthesis.slider_circuit_info(
                x, 0.0, 2 * math.pi, 64
            )
        else:
            problem, full, _, _, mu, _ = _core.synthesis.circuit_info(
                x, crossed, 0.0, 2 * math.pi, 64
            )
    except LinkageError:
        return (3, 0.0)
    if problem is not None or (full_turn and not full):
        return (2, 0.0)
    return (0, 0.0) if mu >= min_transmission else (1, -float(mu))


WIDER = 48
"""Further arc-atlas matches refined (from four times as many nearest shapes) for an open target
that none of the first fitted exactly."""

POLISH = 6
"""Distinct best fits of an open target refined again at length (:data:`POLISH_NFEV`) when none
is exact."""

POLISH_NFEV = 1500
"""Evaluations in each round of a long fit (:func:`_polish`; a first fit's rounds take 60)."""


def _polish(
    found: list[Candidate[Any]],
    polished: list[NDArray[np.float64]],
    target: Float2D,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    threads: int,
    bar: Any,
    kind: _Kind,
    admissible: Callable[[Candidate[Any]], bool],
    exact: float | None = None,
    closed: bool = False,
    budget: _Budget | None = None,
) -> list[Candidate[Any]]:
    """Refine the best :data:`POLISH` distinct fits at length, stopping at the first exact one.

    Exact is within ``exact`` of the size (default :data:`EXACT`). A short or near-straight arc is
    matched to ~1e-5 … 1e-4 of its size along a long, curved valley of near-fits (the scaled
    Jacobian's singular values span 10⁹ on an eighth of Hoecken's curve): least squares crawls along
    it to the exact linkage, in hundreds to thousands of evaluations where a first fit's rounds stop
    at 60 (measured in docs/synthesis.md). These fits take geodesic acceleration
    (:func:`_geodesic_lm`), whose steps follow the valley's bend. Fits whose parameters all lie
    within 1e-3 of the size of a better one's, or of one in ``polished`` (the starts of earlier
    calls, to which this call's are added), are one start. No start is fitted once ``budget``
    is spent.
    """
    picked: list[Candidate[Any]] = []
    for c in sorted(found, key=lambda c: c.error):
        if len(picked) >= POLISH:
            break
        if all(np.max(np.abs(c.params - p)) > 1e-3 * size for p in polished):
            picked.append(c)
            polished.append(c.params)
    if bar is not None:
        bar.stage("long fits", len(picked))
    out: list[Candidate[Any]] = []
    for c in picked:
        if budget is not None and budget.out:
            break
        crossed = _crossed(c)
        out += _finish(
            [(c.params, crossed, c.source)],
            target,
            closed,
            size,
            bounds,
            1,
            threads,
            bar,
            kind=kind,
            nfev=POLISH_NFEV,
            geodesic=True,
            budget=budget,
        )
        if any(o.error <= (exact or EXACT) * size and admissible(o) for o in out):
            break
    return out


HOPS = 12
"""Perturbed restarts of the least-squares fit for an open target that no arc match fits exactly."""


def _restarts(
    found: list[Candidate[Any]],
    target: Float2D,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    seed: int,
    threads: int,
    kind: _Kind,
    budget: _Budget | None = None,
) -> list[Candidate[Any]]:
    """Refine perturbed copies of the best three fits, stopping at the first exact one.

    No copy is fitted once ``budget`` is spent.
    Every parameter moves by a normal step of 5 %, then 1 %, of the target's size, in turn.
    An arc is matched to ~1e-5 of its size by many linkages; the fit stalls in such a basin,
    and a restart from near it often reaches the exact one (measured in docs/synthesis.md).
    """
    rng = np.random.default_rng(seed)
    starts = sorted(found, key=lambda c: c.error)[:3]
    out: list[Candidate[Any]] = []
    for t in range(HOPS):
        if budget is not None and budget.out:
            break
        c = starts[t % len(starts)]
        step = (0.05 if t % 2 == 0 else 0.01) * size
        x = c.params + step * rng.standard_normal(len(c.params))
        crossed = _crossed(c)
        out += _finish(
            [(x, crossed, "atlas")],
            target,
            False,
            size,
            bounds,
            1,
            threads,
            None,
            kind=kind,
            budget=budget,
        )
        if out and min(o.error for o in out) <= 1e-10 * size:
            break
    return out


PART_GAP = 3.0
"""A closed target is cut into parts (:func:`_parts`) where two consecutive points are more than
this many times the median spacing apart."""

PART_POINTS = 12
"""Fewest points of a part of a closed target searched as an open arc (:func:`_parts`): well
over the nine through which finitely many four-bars pass exactly (Wampler, Morgan and Sommese
1992: 1442 of them), so that a fit exact on a part says something about the whole."""

PART_FITS = 2
"""Best fits of each part refined on the whole closed target (:func:`_from_parts`)."""

PART_MATCHES = 3
"""Fits of each part, in units of ``refine`` (as an open target's first fits): with ``refine``
alone the crescent of the tests ended at 1e-4 … 3e-4 of its size under 8 of 8 placements with
the tests' 200,000-arc atlas, with three times as many at ≤ 5e-12 under 8 of 8."""

VALLEY = 1e-3
"""A closed target's best :data:`PART_FITS` fits from its parts, when none is exact, get long
fits if within this fraction of its size (:func:`_from_parts`): one placement of the tests'
crescent, whose best such fit (1.5e-4) stayed there, was recovered by one at 2.8e-4 (to
3.6e-14; measured with an earlier guard of MINPACK's Jacobian copy, docs/synthesis.md)."""


def _parts(target: Float2D) -> list[NDArray[np.intp]]:
    """Return the indices of the parts of a closed ``target`` searched as open arcs.

    The points are cut where a gap exceeds :data:`PART_GAP` times the median gap (and at the
    largest gap), into runs the curve passes through without a stretch the points leave out;
    a run of ``m`` of the ``n`` points is cut again into ``min(⌊3m/n⌋, ⌊m/PART_POINTS⌋)``
    parts (thirds of a target of 36 or more points with no such gap), consecutive parts sharing
    their end point. Parts of fewer than :data:`PART_POINTS` points are left out; the longest
    come first.
    """
    n = len(target)
    gaps = np.hypot(*(np.roll(target, -1, axis=0) - target).T)
    # Start after the largest gap, so that no run crosses it.
    order = np.roll(np.arange(n), -(int(np.argmax(gaps)) + 1))
    cuts = sorted(set(np.flatnonzero(gaps[order] > PART_GAP * np.median(gaps)).tolist()) | {n - 1})
    out: list[NDArray[np.intp]] = []
    start = 0
    for end in cuts:
        run = order[start : end + 1]
        start = end + 1
        m = max(1, min(3 * len(run) // n, len(run) // PART_POINTS))
        for j in range(m):
            a = j * len(run) // m
            b = (j + 1) * len(run) // m + (1 if j < m - 1 else 0)
            if b - a >= PART_POINTS:
                out.append(run[a:b])
    out.sort(key=len, reverse=True)
    return out


def _from_parts(
    target: Float2D,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    refine: int,
    arcs: Atlas,
    threads: int,
    bar: Any,
    kind: _Kind,
    admissible: Callable[[Candidate[Any]], bool],
) -> list[Candidate[Any]]:
    """Fit a closed target from fits of its parts, stopping at the first exact one.

    Each part (:func:`_parts`, longest first) is matched against the open-arc atlas ``arcs``,
    its :data:`PART_MATCHES` × ``refine`` best placed matches are fitted to it as an open
    target's first fits are (stopping at one exact on the part), and its best :data:`PART_FITS`
    fits are refined on the whole target. When none of those is exact, the best
    :data:`PART_FITS` within :data:`VALLEY` of the size get long fits (:func:`_polish`). A part
    leaves out the stretches between sparse points, which mislead the closed polygon's
    descriptors, and the rest of the curve; a fit close on a part lies in the basin of the
    linkage that draws the whole more often than the closed matches do (docs/synthesis.md).
    """
    parts = _parts(target)
    if bar is not None:
        bar.stage("parts as arcs", len(parts))
    out: list[Candidate[Any]] = []
    for idx in parts:
        part = target[idx]
        part_size = target_size(part)
        # As an open target's first fits (path): 3 × refine of the 16 × refine nearest.
        pool = _atlas_pool(kind, arcs, part, PART_MATCHES * refine, 16 * refine, threads)
        fits = _finish(
            pool, part, False, part_size, bounds, len(pool), threads, None, 1, kind, exact_at=EXACT
        )
        fits.sort(key=lambda c: c.error)
        for c in fits[:PART_FITS]:
            out += _finish(
                [(c.params, _crossed(c), "atlas")],
                target,
                True,
                size,
                bounds,
                1,
                threads,
                None,
                kind=kind,
                admissible=admissible,
            )
        if bar is not None:
            bar.update(1)
        if any(o.error <= EXACT * size and admissible(o) for o in out):
            return out
    # A near-fit (within VALLEY of the size) may lie in a valley that leads to the exact linkage
    # (step 4): the best PART_FITS get long fits. More cost too much on a target no four-bar
    # draws (a long fit of 60 points took up to 7.6 s), whose fits can come that near too.
    near = sorted((c for c in out if c.error <= VALLEY * size), key=lambda c: c.error)
    polished: list[NDArray[np.float64]] = []
    for c in near[:PART_FITS]:
        out += _polish(
            [c], polished, target, size, bounds, threads, bar, kind, admissible, closed=True
        )
        if any(o.error <= EXACT * size and admissible(o) for o in out):
            break
    return out


def _atlas_pool(
    kind: _Kind,
    at: Atlas,
    target: Float2D,
    keep: int,
    k: int,
    threads: int,
    slide: int = 0,
) -> list[tuple[NDArray[np.float64], bool, str]]:
    """Return the ``keep`` best placed atlas matches of ``target``, of the ``k`` nearest shapes.

    Each nearest entry is placed by the similarity between its curve's frame and the target's
    (both ends of the major axis), moved along its curve by ``slide`` rounds of
    :func:`_slid_along_curves` (an open target's), and scored by the polyline distance both ways
    (an arc atlas's entries, :data:`ARCS` or :data:`SLIDER_ARCS`, against an open target: one
    way).
    """
    closed = at.kind not in _ARC_KIND
    variants, frame_t = _core.synthesis.query_descriptors(target, at.harmonics, closed)
    idx, _, _ = at.nearest(variants, min(max(k, 16), len(at)), threads)
    placed, crossed = [], []
    # An entry near several query variants is listed once for each: place it once.
    for i in dict.fromkeys(idx.tolist()):
        entry = np.asarray(at.params[int(i)], dtype=np.float64)
        try:
            if not closed:
                slider = kind is SLIDER
                cr = not slider and bool(entry[5])
                frame_c = _core.synthesis.arc_entry_frame(
                    entry, at.harmonics, at.samples, at.phases, slider
                )
            elif kind is FOURBAR:
                base = np.array([0.0, 0.0, 1.0, 0.0, *entry[:5]])
                cr = bool(entry[5])
                frame_c = _core.synthesis.circuit_frame(base, cr, at.harmonics, at.samples)
            else:
                coupler, offset, along, left = entry[:4]
                base = np.array([0.0, 0.0, 0.0, offset, 1.0, coupler, along, left])
                cr = False
                frame_c = _core.synthesis.slider_circuit_frame(base, at.harmonics, at.samples)
        except LinkageError:
            continue
        for flip in (False, True):
            placed.append(_placed(entry, frame_t, frame_c, flip, kind))
            crossed.append(cr)
    if not placed:
        return []
    p, cr_a = np.array(placed), np.array(crossed)
    if slide:
        p = _slid_along_curves(kind, p, cr_a, target, slide, threads)
    e, _ = _errors(p, cr_a, target, closed, threads=threads, kind=kind)
    worst = np.maximum(e[:, 0], e[:, 2]) if closed else e[:, 0]
    score = np.where(np.isfinite(worst), worst, np.inf)
    order = np.argsort(score, kind="stable")
    return [(p[j], bool(cr_a[j]), "atlas") for j in order[:keep] if np.isfinite(score[j])]


SLID = 24
"""Matches re-placed by :func:`_slid_along_curves` and fitted for an open target that no earlier
stage fitted exactly (the best of ``4 × SLID``, from the wider matches' nearest shapes)."""

SLIDES = 3
"""Rounds of :func:`_slid_along_curves`."""
