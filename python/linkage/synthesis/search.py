""":func:`path`, path synthesis: the target read, then the stages run in turn and ranked."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from linkage._core import LinkageError
from linkage._shared.arrays import as_count, as_finite, as_flag, as_point
from linkage._shared.choices import AtlasKind, PathKind
from linkage._shared.progress import Bar
from linkage._shared.size import mean as _mean
from linkage._shared.size import pow2 as _pow2
from linkage.synthesis import stages
from linkage.synthesis.atlas import (
    Atlas,
    AtlasArg,
    _atlases,
    _note_builds,
    default_atlas,
    missing_atlases,
)
from linkage.synthesis.candidates import (
    LONG_LINK,
    Candidate,
    Candidates,
    _crossed,
    _failed,
    _kept,
    _linkage_of,
    _longest,
    _ranked,
)
from linkage.synthesis.fitting import _bounds, _Budget, _distinct, _finish, _measure
from linkage.synthesis.kinds import _KIND, EXACT, FOURBAR, TIGHT, Float2D, _Kind, _kind, _threads
from linkage.synthesis.limits import SYNTHESIS_REFINE_MAX, SYNTHESIS_TOP_MAX
from linkage.synthesis.stages import (
    SLID,
    SLIDES,
    _atlas_pool,
    _cognate_candidates,
    _equation_pool,
    _evolution_starts,
    _from_parts,
    _restarts,
    _shape_order,
)
from linkage.synthesis.targets import _target, target_size

__all__ = [
    "FAR",
    "FIT_POINTS",
    "UNIT_RANGE",
    "path",
]


def path(
    points: str | os.PathLike[str] | ArrayLike,
    closed: bool = True,
    top: int = 5,
    *,
    kind: PathKind = "fourbar",
    atlas: AtlasArg | Sequence[AtlasArg] = None,
    refine: int = 8,
    global_search: bool | None = None,
    full_turn: bool = False,
    min_transmission: float = 0.0,
    lengths: tuple[float, float] | None = None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None = None,
    max_link: float | None = LONG_LINK,
    tol: float = 1e-3,
    maxiter: int = 150,
    seed: int = 0,
    threads: int | None = None,
    progress: bool = False,
    accept: float | None = None,
) -> Candidates:
    """Four-bars (or slider-cranks) whose coupler curve passes through ``points``, best first.

    A four-bar search of 16 points or more (:data:`CURVE_EQUATION_POINTS`) starts from the
    equation of the curve through them: its foci are the pivots of the cognates that draw it,
    and its lengths follow from one linear solve (``linkage_core::fourbars_from_curve``). On a
    curve a four-bar draws, closed or an arc that singles the curve out (given to about 8–9
    significant digits), those four-bars, refined, are exact (``source == "equation"``,
    unless the atlas or the cognates found the same linkage: exact fits tie, and each is
    listed once); the atlas matches, refined, and the later stages search on as described
    below and in ``docs/synthesis.md``. A slider-crank search of 13 points or more
    (:data:`SLIDER_EQUATION_POINTS`) starts likewise from the circular quartic through them,
    whose one focus is the crank pivot (``linkage_core::slider_cranks_from_curve``).

    Parameters
    ----------
    points : (n, 2) array_like or path of a CSV file
        Target points in order along the curve, any position, orientation and scale.
    closed : bool
        Whether the points go round a closed curve (else: a part of one, matched anywhere on a
        candidate's circuit).
    top : int
        Most candidates returned.
    kind : {"fourbar", "slider-crank", "any"}
        The linkage sought: a four-bar, an offset slider-crank (crank, rod, slider on a line at
        any angle and offset, coupler point rigid with the rod), or either (both searched, one
        ranking).
    atlas : Atlas, folder, None, or a sequence of them
        The atlas of each kind searched (default: :func:`default_atlas` of that kind); for
        ``kind="any"`` a sequence may give one of each. Open targets search an atlas of open
        arcs, ``kind="fourbar-arcs"`` or ``"slider-crank-arcs"`` (default: the
        :func:`default_atlas` of that kind), which the sequence may give too.
    refine : int
        Atlas matches refined by least squares (of each kind; at most 200): a closed target's
        ``max(refine, top)``, an open target's ``3 × refine`` first fits. The search's time, and
        how good its best candidate can be, grow with it (and so with ``top``).
    global_search : bool or None
        Run differential evolution; ``None``: when no atlas candidate of any kind searched is
        within ``tol`` of the target's size.
    full_turn, min_transmission, lengths, pivots
        Constraints: a crank that turns fully, a transmission angle at least this far from a
        toggle (radians) over the matched part (over the whole turn for a crank that turns
        fully: the motor drives it all), every link length within ``lengths`` (a
        slider-crank's crank and rod) and both sides of the coupler triangle to the point at most
        its greatest, both ground pivots (a slider-crank's crank pivot) inside
        the box ``pivots = ((xmin, ymin), (xmax, ymax))``.
    accept : float or None
        A largest error (target units) that is good enough: the later stages — an open
        target's long fits and further matches, and the global search when ``global_search``
        is None — run only while no admissible candidate is within it (default: they run
        until one is exact, :data:`EXACT` of the size, and the global search while none is
        within ``tol``; an open target's best exact fit above :data:`TIGHT` of the size then
        gets one long fit more). The stages skipped would have found more candidates too: the
        list may hold fewer than ``top``.
    max_link : float or None
        Candidates with a link (or coupler-triangle side) longer than ``max_link`` times the
        target's size (:func:`target_size`) are ranked after every other, whatever their error:
        a fit that runs a link off towards infinity (a coupler of 64,000 for a curve of size 9)
        can beat every buildable one by a hair. They are not removed: they fill the list when
        fewer than ``top`` others are found, and ``max_link=None`` ranks by error alone. Ignored
        when ``lengths`` is given (that bound filters instead).

    Returns
    -------
    Candidates
        A list of :class:`Candidate`; when the constraints removed fits, its ``removed``
        counts them by constraint and ``closest_removed`` is the best of them
        (:func:`why_none` words why a list is empty). At most ``top``, ranked by ``error``
        then ``rms`` (after ``max_link``), except that errors within the refinement's own
        accuracy tie: every fit to within :data:`EXACT` (1e-6) of the target's size counts
        as exact (the long fits of short arcs end some fits of the exact curve at 2e-7 …
        8e-7 of the size, where well-conditioned fits reach 1e-13), and among exact fits a
        crank that turns fully comes first, then the transmission angle farthest from a
        toggle over the matched part (so a buildable linkage is not put after a rocker that
        passes within 0.1° of a toggle by a difference of error nobody can see), then the
        error. The candidates draw different curves: two candidates whose matched parts lie
        within ``max(1e-6·size, error/20)`` of each other both ways are one design and only
        the better is kept, so mirror images of a symmetric curve, the same linkage driven
        from its other pivot, and fits that differ only by a link drifting to a toggle
        appear once. Roberts cognates are the exception: they draw the same curve with
        different links and pivots (another choice of where to put the frame), so each
        cognate found is kept.

    Raises
    ------
    TypeError
        For non-numeric points.
    LinkageError
        For a wrong shape, fewer than :data:`MIN_POINTS` distinct points, non-finite values, a
        closed target whose points are all collinear, an unknown ``kind``, or an atlas of a
        kind not searched.

    Examples
    --------
    Twelve points round the Hoecken curve, matched in a small atlas (the default atlas is built
    once, into the cache folder; ``refine=0`` skips the least squares):

    >>> import linkage
    >>> target = linkage.catalog.hoecken().circuit(13).point[:-1]
    >>> small = linkage.synthesis.Atlas.build(200, threads=1)
    >>> best = linkage.synthesis.path(target, top=1, atlas=small, refine=0, global_search=False)
    >>> len(best), best[0].kind, best[0].source, type(best[0].linkage).__name__
    (1, 'fourbar', 'atlas', 'FourBar')
    >>> linkage.synthesis.path([(0, 0), (1, 1), (2, 2), (3, 3), (4, 4)], atlas=small)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: the points are all collinear: a closed curve through them encloses ...
    """
    search, target = _read_arguments(**locals())  # every argument (nothing else is bound yet)
    size = target_size(target)
    frame = _unit_frame(target, size)
    if frame is not None:
        # An extreme scale or a far centre: searched moved to the origin at unit size.
        return _at_unit_size(search, target, *frame)
    threads = _threads(search.threads)
    if len(target) > FIT_POINTS:
        # Many points: searched through FIT_POINTS of them, then measured on every point.
        return _through_fewer_points(search, target, size, threads)
    run = _Run.start(search, target, size, threads)
    found: list[Candidate[Any]] = []
    for k in search.kinds:
        found += _search_kind(run, k)
    if _runs_global_search(run, found):
        found += _global_search(run)
    if run.bar is not None:
        run.bar.close()
    found += _cognate_candidates(found, target, search.closed, size, threads, search.top)
    return _ranked_distinct(search, found, target, size)


@dataclass(frozen=True)
class _Search:
    """The arguments of :func:`path` but the points, checked."""

    kind: PathKind
    kinds: list[_Kind]
    closed: bool
    top: int
    atlas: AtlasArg | Sequence[AtlasArg]
    refine: int
    global_search: bool | None
    full_turn: bool
    min_transmission: float
    lengths: tuple[float, float] | None
    pivots: tuple[tuple[float, float], tuple[float, float]] | None
    max_link: float | None
    tol: float
    maxiter: int
    seed: int
    threads: int | None
    progress: bool
    accept: float | None

    def kept(self) -> dict[str, Any]:
        """Return the settings a search of the target moved or thinned keeps (by name)."""
        return {
            "kind": self.kind,
            "atlas": self.atlas,
            "refine": self.refine,
            "global_search": self.global_search,
            "full_turn": self.full_turn,
            "min_transmission": self.min_transmission,
            "max_link": self.max_link,
            "tol": self.tol,
            "maxiter": self.maxiter,
            "seed": self.seed,
            "threads": self.threads,
            "progress": self.progress,
        }

    def limit(self, size: float) -> float:
        """Return the longest link that does not rank a candidate last (``max_link`` sizes)."""
        return (
            math.inf if self.lengths is not None or self.max_link is None else self.max_link * size
        )


def _read_arguments(
    points: str | os.PathLike[str] | ArrayLike,
    closed: bool,
    top: int,
    kind: PathKind,
    atlas: AtlasArg | Sequence[AtlasArg],
    refine: int,
    global_search: bool | None,
    full_turn: bool,
    min_transmission: float,
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
    max_link: float | None,
    tol: float,
    maxiter: int,
    seed: int,
    threads: int | None,
    progress: bool,
    accept: float | None,
) -> tuple[_Search, Float2D]:
    """Check :func:`path`'s arguments in turn (the first wrong one named), then read the target."""
    kinds = list(_KIND.values()) if kind == "any" else [_kind(kind, "any")]
    closed = as_flag(closed, "closed")
    top = as_count(top, "top")
    if top > SYNTHESIS_TOP_MAX:
        raise LinkageError(f"top must be between 1 and {SYNTHESIS_TOP_MAX}, got {top}")
    refine = as_count(refine, "refine", 0)
    if refine > SYNTHESIS_REFINE_MAX:
        raise LinkageError(f"refine must be between 0 and {SYNTHESIS_REFINE_MAX}, got {refine}")
    maxiter = as_count(maxiter, "maxiter")
    seed = as_count(seed, "seed", 0)
    tol = as_finite(tol, "tol")
    if tol <= 0:
        raise LinkageError(f"tol must be positive (a fraction of the target's size), got {tol}")
    min_transmission = as_finite(min_transmission, "min_transmission")
    if not 0 <= min_transmission <= math.pi / 2:
        hint = (
            f" (radians: did you mean math.radians({min_transmission:g})?)"
            if math.pi < min_transmission <= 90
            else ""
        )
        raise LinkageError(
            "min_transmission must be an angle in radians between 0 and π/2 (90°), "
            f"got {min_transmission:g}{hint}"
        )
    full_turn = as_flag(full_turn, "full_turn")
    progress = as_flag(progress, "progress")
    if global_search is not None:
        global_search = as_flag(global_search, "global_search")
    if accept is not None:
        accept = as_finite(accept, "accept")
        if accept < 0:
            raise LinkageError(f"accept must be a distance, at least 0, got {accept}")
    if max_link is not None:
        max_link = as_finite(max_link, "max_link")
        if max_link <= 0:
            raise LinkageError(f"max_link must be positive, got {max_link}")
    if lengths is not None:
        lengths = _pair(lengths, "lengths")
    if pivots is not None:
        if isinstance(pivots, (str, bytes)) or np.ndim(pivots) == 0 or len(pivots) != 2:
            raise TypeError("pivots must be ((xmin, ymin), (xmax, ymax))")
        pivots = (as_point(pivots[0], "pivots[0]"), as_point(pivots[1], "pivots[1]"))
    search = _Search(
        kind,
        kinds,
        closed,
        top,
        atlas,
        refine,
        global_search,
        full_turn,
        min_transmission,
        lengths,
        pivots,
        max_link,
        tol,
        maxiter,
        seed,
        threads,
        progress,
        accept,
    )
    return search, _target(points, closed)


def _at_unit_size(
    search: _Search, target: Float2D, origin: NDArray[np.float64], unit: float
) -> Candidates:
    """Search ``target`` moved to the origin and scaled by ``unit`` (a power of two), moved back."""
    lengths, pivots, accept = search.lengths, search.pivots, search.accept
    at_unit = path(
        (target - origin) / unit,
        search.closed,
        search.top,
        **search.kept(),
        lengths=None if lengths is None else (lengths[0] / unit, lengths[1] / unit),
        pivots=(
            None
            if pivots is None
            else (
                ((pivots[0][0] - origin[0]) / unit, (pivots[0][1] - origin[1]) / unit),
                ((pivots[1][0] - origin[0]) / unit, (pivots[1][1] - origin[1]) / unit),
            )
        ),
        accept=None if accept is None else accept / unit,
    )
    gone = at_unit.closest_removed
    return Candidates(
        [_moved(cand, origin, unit) for cand in at_unit],
        at_unit.removed,
        None if gone is None else _moved(gone, origin, unit),
        at_unit.closest_fails,
    )


def _through_fewer_points(
    search: _Search, target: Float2D, size: float, threads: int
) -> Candidates:
    """Search through :data:`FIT_POINTS` of the target's points spread along it.

    A fit's cost grows with the cube of the points it fits: the candidates are then measured,
    checked and ranked on every point.
    """
    closed = search.closed
    some = path(
        target[_spread(target, closed, FIT_POINTS)],
        closed,
        min(SYNTHESIS_TOP_MAX, 2 * search.top),
        **search.kept(),
        lengths=search.lengths,
        pivots=search.pivots,
        accept=search.accept,
    )

    def on_every_point(c: Candidate[Any]) -> Candidate[Any] | None:
        kind = _KIND[c.kind]
        return _measure(c.params, _crossed(c), target, closed, c.source, threads, kind)

    measured = [m for m in map(on_every_point, some) if m is not None]
    gone = some.closest_removed
    thin = Candidates((), some.removed, None if gone is None else on_every_point(gone))
    return _ranked_distinct(search, measured, target, size, thin)


def _ranked_distinct(
    search: _Search,
    found: list[Candidate[Any]],
    target: Float2D,
    size: float,
    removed: Candidates | None = None,
) -> Candidates:
    """Return the best ``top`` distinct candidates the constraints keep, and what they removed."""
    s = search
    ok, result = _kept(found, s.full_turn, s.min_transmission, s.lengths, s.pivots, removed)
    result.extend(_distinct(_ranked(ok, size, s.limit(size)), target, s.closed, size, s.top))
    return result


@dataclass
class _Run:
    """One search of a target: its settings, size, threads, progress bar and the atlases given."""

    search: _Search
    target: Float2D
    size: float
    threads: int
    centre: NDArray[np.float64]
    fits: int  # atlas matches refined first, of each kind
    bar: Bar | None
    atlases: dict[str, Atlas]
    limit: float  # the longest link that ranks a candidate with the others
    goal: float  # the error that ends the later stages

    @classmethod
    def start(cls, search: _Search, target: Float2D, size: float, threads: int) -> _Run:
        """Start the search: the progress bar, the atlases given, and the builds to come."""
        closed, accept = search.closed, search.accept
        centre = target.mean(axis=0)
        fits = search.refine if closed else 3 * search.refine
        bar = _progress_bar(search.progress, fits * len(search.kinds))
        atlases = _atlases(search.atlas, search.kinds)
        _note_builds(missing_atlases(search.kind, closed, atlases), bar)
        goal = EXACT * size if accept is None else max(EXACT * size, accept)
        limit = search.limit(size)
        return cls(search, target, size, threads, centre, fits, bar, atlases, limit, goal)

    def admissible(self, c: Candidate[Any]) -> bool:
        """Whether ``c`` meets the constraints."""
        s = self.search
        return not _failed(c, s.full_turn, s.min_transmission, s.lengths, s.pivots)

    def best(self, cs: list[Candidate[Any]]) -> float:
        """Return the least error of the admissible candidates (∞ if none is)."""
        return min((c.error for c in cs if self.admissible(c)), default=math.inf)

    def usable(self, c: Candidate[Any]) -> bool:
        """Whether ``c`` is admissible and ranks before the long-linked (``max_link``)."""
        return self.admissible(c) and _longest(c) <= self.limit

    def best_usable(self, cs: list[Candidate[Any]]) -> float:
        """Return the least error of the usable candidates.

        An open target's further stages go on while its only exact fits have a link ranked last.
        """
        return min((c.error for c in cs if self.usable(c)), default=math.inf)

    def exact_at(self) -> float:
        """Return the error, in sizes, at which the first fits stop (``accept`` or round-off)."""
        accept = self.search.accept
        return 1e-10 if accept is None else max(1e-10, accept / self.size)


@dataclass
class _Matches:
    """A kind's atlas matches for the first fits, and how many were sought (for later stages)."""

    atlas: Atlas
    pool: list[tuple[NDArray[np.float64], bool, str]]
    placed: int  # matches refined first
    many: int  # nearest shapes they are chosen from


def _search_kind(run: _Run, k: _Kind) -> list[Candidate[Any]]:
    """Search for linkages of kind ``k``: the first fits, then the later stages while none is exact.

    The first fits are the refined linkages of the curve's equation and of the atlas matches
    (docs/synthesis.md, steps 0-3); the later stages (step 4) are judged by the candidates the
    constraints admit: an exact fit they reject must not end the search for one they admit.
    """
    s, target, size = run.search, run.target, run.size
    bounds = _bounds(s.lengths, s.pivots, size, k)
    # A four-bar from the equation of the curve through the points, refined: exact for a
    # curve a four-bar draws, closed or an arc that singles it out (docs/synthesis.md,
    # step 0).
    equation = _equation_pool(target, s.closed, run.threads, k)
    ahead = _finish(
        equation,
        target,
        s.closed,
        size,
        bounds,
        len(equation),
        run.threads,
        None,
        s.top,
        k,
        run.admissible,
        exact_at=run.exact_at(),
    )
    matches = _atlas_matches(run, k)
    mine = _finish(
        matches.pool,
        target,
        s.closed,
        size,
        bounds,
        run.fits,
        run.threads,
        run.bar,
        s.top,
        k,
        run.admissible,
        exact_at=run.exact_at(),
    )
    mine = ahead + mine
    # The later stages of an open search share one budget of evaluations, smaller the more
    # points a fit has (a target no linkage draws runs them all; #29).
    later = _Budget.of(len(target))
    if not s.closed and mine and run.best_usable(mine) > run.goal:
        _open_later_stages(run, k, bounds, matches, mine, later)
    if not s.closed and mine and run.best_usable(mine) > run.goal:
        starts = [c for c in mine if run.admissible(c)] or mine
        mine += _restarts(starts, target, size, bounds, s.seed, run.threads, k, later)
    if s.closed and s.refine > 0 and run.best_usable(mine) > run.goal:
        # A closed target no match fitted exactly: parts of it searched as open arcs, their
        # best fits refined on the whole target (docs/synthesis.md, step 4).
        given = run.atlases.get(k.arcs)
        if given is None:
            _note_builds(missing_atlases(k.name, False), run.bar)
        arcs = given or default_atlas(kind=k.arcs)
        mine += _from_parts(
            target, size, bounds, s.refine, arcs, run.threads, run.bar, k, run.usable
        )
    return _tightened(run, k, bounds, mine)


def _atlas_matches(run: _Run, k: _Kind) -> _Matches:
    """Return the matches of the target in the atlas of ``k`` to refine first.

    Open targets are matched against open arcs of the kind's circuits.
    """
    s, target = run.search, run.target
    name: AtlasKind = k.name if s.closed else k.arcs
    at = run.atlases.get(name) or default_atlas(kind=name)
    many = 4 * max(s.top, s.refine) if s.closed else 16 * max(s.top, s.refine)
    placed = max(s.refine, s.top) if s.closed else 3 * s.refine
    if s.full_turn or s.min_transmission > 0:
        # Refine the best matches whose circuit meets the constraints asked for (a
        # full-turn crank, the transmission angle), from four times as many, first.
        pool = _atlas_pool(k, at, target, 4 * placed, 4 * many, run.threads)
        pool.sort(key=lambda e: _shape_order(e, k, s.full_turn, s.min_transmission))
        pool = pool[:placed]
    else:
        pool = _atlas_pool(k, at, target, placed, many, run.threads)
    return _Matches(at, pool, placed, many)


def _open_later_stages(
    run: _Run,
    k: _Kind,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    matches: _Matches,
    mine: list[Candidate[Any]],
    later: _Budget,
) -> None:
    """Add to ``mine`` the later stages' fits of an open target no match fitted exactly.

    Long fits of the best, then more matches and long fits of theirs, then the nearest shapes
    re-placed along their curves (docs/synthesis.md, step 4), while none is exact and ``later``
    is not spent.
    """
    s, target, size, bar = run.search, run.target, run.size, run.bar
    at, placed, many = matches.atlas, matches.placed, matches.many
    polished: list[NDArray[np.float64]] = []
    starts = [c for c in mine if run.usable(c)] or mine
    mine += stages._polish(
        starts, polished, target, size, bounds, run.threads, bar, k, run.usable, budget=later
    )
    if run.best_usable(mine) > run.goal and not later.out:
        seen = {x.tobytes() for x, _, _ in matches.pool}
        wider = _atlas_pool(k, at, target, placed + stages.WIDER, 4 * many, run.threads)
        if s.full_turn or s.min_transmission > 0:
            wider.sort(key=lambda e: _shape_order(e, k, s.full_turn, s.min_transmission))
        wider = [w for w in wider if w[0].tobytes() not in seen][: stages.WIDER]
        if bar is not None:
            bar.stage("more matches", len(wider))
        more = _finish(
            wider,
            target,
            False,
            size,
            bounds,
            len(wider),
            run.threads,
            bar,
            1,
            k,
            run.usable,
            exact_at=EXACT,
            budget=later,
        )
        mine += more
        if more and run.best_usable(mine) > run.goal:
            starts = [c for c in more if run.usable(c)] or more
            mine += stages._polish(
                starts,
                polished,
                target,
                size,
                bounds,
                run.threads,
                bar,
                k,
                run.usable,
                budget=later,
            )
    if run.best_usable(mine) > run.goal and not later.out:
        # The same nearest shapes re-placed along their curves (_slid_along_curves), ranked again
        # and fitted as the first (docs/synthesis.md, step 4).
        slid = _atlas_pool(k, at, target, 4 * SLID, 4 * many, run.threads, slide=SLIDES)
        if s.full_turn or s.min_transmission > 0:
            slid.sort(key=lambda e: _shape_order(e, k, s.full_turn, s.min_transmission))
        slid = slid[:SLID]
        if bar is not None:
            bar.stage("matches re-placed", len(slid))
        mine += _finish(
            slid,
            target,
            False,
            size,
            bounds,
            len(slid),
            run.threads,
            bar,
            1,
            k,
            run.usable,
            exact_at=EXACT,
            budget=later,
        )


def _tightened(
    run: _Run,
    k: _Kind,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    mine: list[Candidate[Any]],
) -> list[Candidate[Any]]:
    """Return ``mine``, its best usable fit of an open target taken down to round-off.

    An exact fit (within EXACT) that the first fits left in a valley above round-off (8.9e-7
    of the size, links 1e-3 off, where the drawing linkage is at 4e-14): one long fit takes it
    down (docs/synthesis.md, step 4), and replaces it when better (else the same design would
    be listed twice, with its cognate measured from it).
    """
    s, size = run.search, run.size
    loose = min((c for c in mine if run.usable(c)), key=lambda c: c.error, default=None)
    if (
        not s.closed
        and s.accept is None
        and loose is not None
        and TIGHT * size < loose.error <= run.goal
    ):
        tight = stages._polish(
            [loose], [], run.target, size, bounds, run.threads, run.bar, k, run.usable, TIGHT
        )
        if min((c.error for c in tight), default=math.inf) < loose.error:
            mine = [c for c in mine if c is not loose] + tight
    return mine


def _runs_global_search(run: _Run, found: list[Candidate[Any]]) -> bool:
    """Whether the global search runs: as asked, else when no admissible fit is within ``tol``."""
    s = run.search
    enough = s.tol * run.size if s.accept is None else s.accept
    return s.global_search if s.global_search is not None else run.best(found) > enough


def _global_search(run: _Run) -> list[Candidate[Any]]:
    """Return the refined fits of the global search of each kind (differential evolution)."""
    s, bar = run.search, run.bar
    found: list[Candidate[Any]] = []
    for k in s.kinds:
        if bar is not None:
            # Generations (of both assemblies for four-bars), then refinements.
            bar.stage(f"global search ({k.name})", (2 if k is FOURBAR else 1) * s.maxiter + 8)
        starts = _evolution_starts(
            run.target,
            s.closed,
            run.size,
            run.centre,
            s.seed,
            s.maxiter,
            run.threads,
            bar,
            kind=k,
            full_turn=s.full_turn,
            min_transmission=s.min_transmission,
        )
        found += _finish(
            [(x, c, "global") for x, c in starts],
            run.target,
            s.closed,
            run.size,
            _bounds(s.lengths, s.pivots, run.size, k),
            min(s.refine, len(starts)),
            run.threads,
            bar,
            kind=k,
            admissible=run.admissible,
        )
    return found


def _pair(value: Any, name: str) -> tuple[float, float]:
    a, b = as_point(value, name)
    return a, b


def _progress_bar(progress: bool, total: int) -> Bar | None:
    return Bar("synthesis", total=total) if progress else None


UNIT_RANGE = (2.0**-64, 2.0**64)
"""Target sizes searched where they are; a target of a size outside is searched moved to the
origin and scaled to unit size (:func:`path`)."""


FAR = 2.0**10
"""A target whose centre is farther from the origin than this many sizes is searched moved to
the origin (:func:`_unit_frame`): coordinates that large would cost the fit their digits."""

FIT_POINTS = 120
"""Most target points a search fits; a target of more is searched through this many spread
along it by arc length, and its candidates measured on every point (:func:`path`)."""


def _spread(target: Float2D, closed: bool, n: int) -> NDArray[np.intp]:
    """Return the indices of ``n`` of ``target``'s points spread evenly by arc length.

    An open target keeps both its ends; a closed one is spread round its loop.
    """
    ring = np.concatenate([target, target[:1]]) if closed else target
    steps = np.hypot(*np.diff(ring, axis=0).T)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    if closed:
        want = np.linspace(0.0, along[-1], n, endpoint=False)
        idx = np.searchsorted(along[:-1], want).clip(0, len(target) - 1)
    else:
        want = np.linspace(0.0, along[-1], n)
        idx = np.searchsorted(along, want).clip(0, len(target) - 1)
        idx[0], idx[-1] = 0, len(target) - 1
    return np.unique(idx)


def _unit_frame(target: Float2D, size: float) -> tuple[NDArray[np.float64], float] | None:
    """Return ``(centre, k)`` that take ``target`` (of size ``size``) to unit size at the origin.

    ``k`` is a power of two (an exact scaling); None when the size is within
    :data:`UNIT_RANGE` and the centre within :data:`FAR` sizes of the origin.
    """
    lo, hi = UNIT_RANGE
    centre = _mean(target)
    if lo <= size <= hi and float(np.max(np.abs(centre))) <= FAR * size:
        return None
    return centre, _pow2(size)


def _moved(c: Candidate[Any], centre: NDArray[np.float64], k: float) -> Candidate[Any]:
    """``c`` (found for a target moved by ``-centre`` and scaled by ``1/k``) moved back."""
    x = np.array(c.params, dtype=np.float64)
    kind = _KIND[c.kind]
    for i, j in kind.pivots:
        x[i], x[j] = centre[0] + k * x[i], centre[1] + k * x[j]
    x[list(kind.scaled)] *= k
    crossed = _crossed(c)
    lk = _linkage_of(x, crossed, kind)
    return replace(c, linkage=lk, error=c.error * k, rms=c.rms * k, back=c.back * k, params=x)
