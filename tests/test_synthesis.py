"""Path synthesis (``linkage.synthesis``): exact recovery of four-bar curves under any
placement, open arcs, validity of every candidate, bad input."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import linkage
from linkage import synthesis
from linkage.cli.synthesize import CLI_CONSTRAINTS
from linkage.synthesis import Atlas


@pytest.fixture(scope="module")
def atlas() -> Atlas:
    # Small: the default (200,000 entries) is for users; 40,000 covers the test linkages.
    return Atlas.build(40_000, threads=2)


def placed(
    points: np.ndarray, rng: np.random.Generator, roll: bool = True
) -> tuple[np.ndarray, float]:
    """``points`` under a random rotation, scale, translation and (``roll``) starting point."""
    ang = rng.uniform(-math.pi, math.pi)
    k = 10 ** rng.uniform(-2, 2)
    rot = np.array([[math.cos(ang), -math.sin(ang)], [math.sin(ang), math.cos(ang)]])
    out = k * points @ rot.T + rng.uniform(-100, 100, 2)
    return (np.roll(out, int(rng.integers(len(out))), axis=0) if roll else out), k


def size_of(points: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.sum((points - points.mean(0)) ** 2, 1))))


def tracked_distance(fb: linkage.FourBar, target: np.ndarray, n: int = 20001) -> float:
    """Largest target-to-curve distance against the tracker's own circuit sweep (a densely
    sampled polyline): an independent measure of a candidate's error."""
    curve = fb.circuit(n).point
    assert np.all(np.isfinite(curve)), "the tracker's circuit has unassembled samples"
    a, b = curve[:-1], curve[1:]
    ab = b - a
    worst = 0.0
    for p in target:
        u = np.clip(np.sum((p - a) * ab, 1) / np.maximum(np.sum(ab * ab, 1), 1e-300), 0, 1)
        worst = max(worst, float(np.min(np.hypot(*(a + ab * u[:, None] - p).T))))
    return worst


CATALOGUE = ["hoecken", "chebyshev", "watt", "roberts", "evans_a"]


@pytest.mark.parametrize("name", CATALOGUE)
def test_catalogue_curve_is_recovered_exactly(atlas: Atlas, name: str) -> None:
    fb = linkage.catalog.get(name)
    assert isinstance(fb, linkage.FourBar)
    curve = fb.circuit(241).point[:-1][::3]  # 80 points, closed (the last repeats the first)
    rng = np.random.default_rng(CATALOGUE.index(name))
    target, _ = placed(curve, rng)
    found = synthesis.path(target, atlas=atlas, top=3, global_search=False)
    assert found, "no candidate"
    best = found[0]
    size = size_of(target)
    assert best.error <= 1e-6 * size, (name, best.error / size)
    # The error is what the tracker's own sweep of the returned linkage gives (to its chord).
    assert tracked_distance(best.linkage, target) <= 1e-6 * size + 1e-4 * size
    assert best.rms <= best.error


def random_fourbar(rng: np.random.Generator) -> linkage.FourBar:
    while True:
        g, r, b, c = 1.0, *np.exp(rng.uniform(math.log(0.3), math.log(3), 3))
        fb = linkage.FourBar(
            ground=g,
            crank=r,
            coupler=b,
            rocker=c,
            point=(b * rng.uniform(-0.5, 1.5), b * rng.uniform(-1, 1)),
            assembly=str(rng.choice(["open", "crossed"])),
        )
        if fb.input_ranges() and fb.grashof() != "change-point":
            return fb


@pytest.mark.parametrize("seed", range(4))
def test_random_fourbar_curve_is_recovered_exactly(atlas: Atlas, seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    fb = random_fourbar(rng)
    target, _ = placed(fb.circuit(181).point[:-1][::2], rng)
    found = synthesis.path(target, atlas=atlas, top=1, maxiter=100, seed=seed)
    assert found
    assert found[0].error <= 1e-6 * size_of(target), (fb, found[0].error / size_of(target))


# Two triple-rockers of a new user's trial (2026-11-27), 40 points taken evenly in the index of
# circuit(2001), whose crank angles crowd at the limits: a thin crescent, and a curve whose
# points leave out a wide loop between two of them. The atlas stage ended at 1.9e-4 and 0.21 of
# their size (the global search too); the parts searched as open arcs recover them.
MISSED_CLOSED = {
    "crescent": linkage.FourBar(
        ground=1,
        crank=0.565497,
        coupler=0.412182,
        rocker=1.84145,
        point=(0.41674999, 0.01020754),
        assembly="crossed",
    ),
    "loop left out": linkage.FourBar(
        ground=1,
        crank=1.04384,
        coupler=0.582212,
        rocker=0.540187,
        point=(0.93208113, 0.31001864),
        assembly="open",
    ),
}


def missed_closed_target(name: str) -> np.ndarray:
    return MISSED_CLOSED[name].circuit(2001).point[np.linspace(0, 2000, 41)[:-1].astype(int)]


@pytest.mark.parametrize("name", sorted(MISSED_CLOSED))
def test_a_closed_curve_the_atlas_misses_is_recovered_from_its_parts(
    atlas: Atlas, arc_atlas: Atlas, name: str, no_equation: None
) -> None:
    """With these fixtures the closed stage alone ends at 1.5e-4 and 0.26 of the size (as
    placed by the trial; 1.9e-4 and 0.21 with the default atlases); with the parts at 3e-14 …
    4e-8 under each of 8 random placements (this test's is the first), with both atlases, on
    Python 3.11 with SciPy 1.17.1, 3.9 with 1.10.1 and 3.13 with 1.18.1 alike."""
    rng = np.random.default_rng(sorted(MISSED_CLOSED).index(name))
    target, _ = placed(missed_closed_target(name), rng)
    found = synthesis.path(target, atlas=[atlas, arc_atlas], top=1, global_search=False)
    assert found
    best, size = found[0], size_of(target)
    assert best.error <= 1e-6 * size, (name, best.error / size)
    assert tracked_distance(best.linkage, target) <= 1e-6 * size + 1e-4 * size


@pytest.mark.parametrize("name", sorted(MISSED_CLOSED))
def test_the_curve_equation_recovers_the_closed_curves_the_atlas_misses(
    atlas: Atlas,
    monkeypatch,
    name: str,  # type: ignore[no-untyped-def]
) -> None:
    """The same targets with the parts stage and the global search off: the four-bars from the
    curve's equation, refined, draw them exactly."""
    monkeypatch.setattr(synthesis.stages, "PART_POINTS", 10**9)
    rng = np.random.default_rng(sorted(MISSED_CLOSED).index(name))
    target, _ = placed(missed_closed_target(name), rng)
    found = synthesis.path(target, atlas=atlas, top=1, global_search=False)
    assert found
    best, size = found[0], size_of(target)
    assert best.error <= 1e-10 * size, (name, best.error / size)
    assert best.source in ("equation", "cognate"), best.source
    assert tracked_distance(best.linkage, target) <= 1e-10 * size + 1e-4 * size


def test_parts_of_a_closed_target_are_cut_at_its_gaps() -> None:
    """The loop left out: two runs of 20 points between its two gaps (13 times the median);
    the crescent, whose spacing varies by a factor 1.3 at most: thirds from its largest gap,
    sharing their ends; too few points for a part of PART_POINTS: none."""
    loop = synthesis._parts(missed_closed_target("loop left out"))
    assert sorted(p.tolist() for p in loop) == [
        list(range(11, 31)),
        [*range(31, 40), *range(11)],
    ]
    crescent = synthesis._parts(missed_closed_target("crescent"))
    assert [len(p) for p in crescent] == [14, 14, 14]
    assert all(a[-1] == b[0] for a, b in zip(crescent, crescent[1:]))
    assert len(np.unique(np.concatenate(crescent))) == 40
    ring = np.c_[np.cos(np.arange(11.0)), np.sin(np.arange(11.0))]
    assert synthesis._parts(ring) == []


@pytest.fixture(scope="module")
def arc_atlas() -> Atlas:
    # 200,000 arcs (about 3,600 circuits): the default (560,000) is for users.
    return Atlas.build(200_000, kind="fourbar-arcs", threads=2)


@pytest.fixture
def no_equation(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """Turn off the search's first stage, the linkages from the curve's equation, for a test
    of a later stage (it recovers these targets before the later stages run)."""
    monkeypatch.setattr(synthesis.stages, "CURVE_EQUATION_POINTS", 10**9)
    monkeypatch.setattr(synthesis.stages, "SLIDER_EQUATION_POINTS", 10**9)


def arc_of(fb: linkage.FourBar, rng: np.random.Generator, frac: float) -> np.ndarray:
    """40 points on ``frac`` of ``fb``'s circuit from a random start, randomly placed."""
    circuit = fb.circuit(4001).point[:-1]
    n = len(circuit)
    idx = (int(rng.integers(n)) + np.round(np.linspace(0, frac * n, 40)).astype(int)) % n
    return placed(circuit[idx], rng, roll=False)[0]


def test_open_arc_is_matched(atlas: Atlas, arc_atlas: Atlas) -> None:
    """Most of Hoecken's curve as an open arc (crank 1 … 4 rad, its near-straight part
    included), placed anywhere: a linkage through it, traced on one circuit. Not exact: the arc
    atlas and least squares reach 2.9e-5 of the size (with this fixture and with the default
    atlas; arcs 0 … 3 and 2 … 5 rad: 6.3e-14 and 5.1e-5 since the long fits, 7.1e-5 and 1.2e-4
    before), a basin of near-fits of the straight part; the global search alone reached
    1.2e-4 … 5e-3."""
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    arc = fb.sweep(np.linspace(1.0, 4.0, 40)).point
    target, _ = placed(arc, np.random.default_rng(7), roll=False)
    found = synthesis.path(target, closed=False, top=1, atlas=[atlas, arc_atlas], seed=1)
    assert found
    best = found[0]
    size = size_of(target)
    assert best.error <= 1e-4 * size, best.error / size
    assert_one_circuit(best)
    assert tracked_distance(best.linkage, target) <= best.error + 1e-4 * size
    lo, hi = best.crank_range
    assert hi > lo


# Arcs of 1/4 … 3/5 of a circuit that the fixture's atlas recovers, chosen among 42 tried
# (before the long fits, arcs of 0.15 and 0.25 mostly ended at 1e-6 … 3e-4; over random arcs of
# 1/8 … 3/4 the default atlas recovers 54 of 58, bench/open_arcs.py): they pin the method, not
# its rate.
OPEN_ARCS = [
    ("random", 2, 0.3),
    ("random", 6, 0.3),
    ("random", 3, 0.6),
    ("chebyshev", 4, 0.5),
    ("watt", 5, 0.5),
    ("roberts", 4, 0.25),
]


@pytest.mark.parametrize(("name", "seed", "frac"), OPEN_ARCS)
def test_open_arc_is_recovered_exactly(arc_atlas: Atlas, name: str, seed: int, frac: float) -> None:
    rng = np.random.default_rng(200 + seed)
    fb = random_fourbar(rng) if name == "random" else linkage.catalog.get(name)
    assert isinstance(fb, linkage.FourBar)
    target = arc_of(fb, rng, frac)
    found = synthesis.path(target, closed=False, top=1, atlas=arc_atlas, global_search=False)
    assert found
    size = size_of(target)
    assert found[0].error <= 1e-6 * size, (name, seed, found[0].error / size)
    assert_one_circuit(found[0])
    assert tracked_distance(found[0].linkage, target) <= 1e-6 * size + 1e-4 * size


def test_an_arc_the_first_fits_miss_is_recovered_by_the_long_fits(
    arc_atlas: Atlas, no_equation: None
) -> None:
    """A third of Watt's curve (bench/open_arcs.py's watt#1, rounded): with this fixture its
    first fits stall in near-fits and, before the long fits and wider matches, the answer was
    6.5e-5 of the size; now ~5e-14."""
    fb = linkage.catalog.get("watt")
    assert isinstance(fb, linkage.FourBar)
    circuit = fb.circuit(4001).point[:-1]
    idx = (2101 + np.round(np.linspace(0, 0.35 * 4000, 40)).astype(int)) % 4000
    ang, k = 0.45, 0.19
    rot = np.array([[math.cos(ang), -math.sin(ang)], [math.sin(ang), math.cos(ang)]])
    target = k * circuit[idx] @ rot.T + np.array([18.9, -32.4])
    found = synthesis.path(target, closed=False, top=1, atlas=arc_atlas, global_search=False)
    assert found
    size = size_of(target)
    assert found[0].error <= 1e-6 * size, found[0].error / size
    assert_one_circuit(found[0])
    assert tracked_distance(found[0].linkage, target) <= 1e-6 * size + 1e-4 * size


CATALOGUE_ARCS = ("hoecken", "chebyshev", "watt", "roberts", "evans_a", "evans_b")


def bench_arc(seed: int, name: str) -> np.ndarray:
    """The target ``name`` (``"watt#1"``, ``"random#6"``) of ``bench/open_arcs.py --seed
    seed``: the same generators drawn in the same order (three arcs of each catalogue linkage,
    then random four-bars)."""
    rng = np.random.default_rng(seed)
    for cat in CATALOGUE_ARCS:
        fb = linkage.catalog.get(cat)
        assert isinstance(fb, linkage.FourBar)
        for k in range(3):
            target = arc_of(fb, rng, rng.uniform(1 / 8, 3 / 4))
            if f"{cat}#{k}" == name:
                return target
    for k in range(40):
        target = arc_of(random_fourbar(rng), rng, rng.uniform(1 / 8, 3 / 4))
        if f"random#{k}" == name:
            return target
    raise KeyError(name)


@pytest.mark.parametrize(("seed", "name"), [(0, "random#6")])
def test_a_short_arc_in_a_curved_valley_is_recovered_by_geodesic_steps(
    arc_atlas: Atlas, seed: int, name: str, no_equation: None
) -> None:
    """Arcs of bench/open_arcs.py whose long fits crawl along a curved valley of near-fits.
    random#6 (seed 0, 0.18 of a crossed triple-rocker's circuit): MINPACK's steps ended at 1.4e-5
    of the size (1.5e-5 with this fixture); Levenberg-Marquardt with geodesic acceleration reaches
    3.4e-7 (both atlases). random#17 (seed 1) is not held here: with the long fits' Jacobian
    by central differences it ended at 2.9e-6 with this fixture, by fourth-order differences at
    2.1e-7 under Python 3.11's SciPy, but still at 2.9e-6 in the wheel's Python 3.12 and 3.13
    environments (their SciPy's least squares; measured by .ci/run on 2026-11-27)."""
    target = bench_arc(seed, name)
    found = synthesis.path(target, closed=False, top=1, atlas=arc_atlas, global_search=False)
    assert found
    size = size_of(target)
    assert found[0].error <= 1e-6 * size, found[0].error / size
    assert_one_circuit(found[0])
    assert tracked_distance(found[0].linkage, target) <= 1e-6 * size + 1e-4 * size


def test_matches_slid_along_their_curves_reach_a_basin_the_frames_miss() -> None:
    """bench/open_arcs.py --seed 0 random#27 (0.45 of a crossed four-bar's circuit) with the
    default arc atlas: its matches placed by the arcs' frames, ranked by their distance, end in
    other basins (the search's first fits, wider matches and long fits at 3.0e-4 of the size at
    best); the same nearest shapes moved along their curves by ``_slid`` and ranked again put
    one in the drawing linkage's basin among the ``SLID`` fitted (to ~1e-13; the search then
    ends at 1.3e-12). Only the default atlas shows it: the tests' 200,000-arc one recovers
    neither way."""
    at = synthesis.default_atlas(kind="fourbar-arcs")
    target = bench_arc(0, "random#27")
    size = size_of(target)
    fb = synthesis.FOURBAR
    bounds = synthesis._bounds(None, None, size, fb)
    nearest = 4 * 16 * 8  # the wider matches' nearest shapes under path's defaults
    best: dict[int, synthesis.Candidate] = {}
    for slide in (0, synthesis.SLIDES):
        pool = synthesis._atlas_pool(fb, at, target, synthesis.SLID, nearest, 1, slide=slide)
        fits = synthesis._finish(
            pool, target, False, size, bounds, len(pool), 1, None, 1, fb, exact_at=1e-6
        )
        best[slide] = min(fits, key=lambda c: c.error)
    assert best[0].error > 1e-5 * size, best[0].error / size
    found = best[synthesis.SLIDES]
    assert found.error <= 1e-6 * size, found.error / size
    assert_one_circuit(found)
    assert tracked_distance(found.linkage, target) <= 1e-6 * size + 1e-4 * size


@pytest.mark.parametrize("seed", range(6))
def test_the_curve_equation_recovers_a_random_arc_without_the_atlas(
    arc_atlas: Atlas, seed: int
) -> None:
    """An arc of a third to three quarters of a random four-bar's circuit, anywhere at any
    scale, with no atlas match fitted (``refine=0``) and no global search: a four-bar from the
    equation of the curve through its points, refined (or a cognate of it), draws it to within
    EXACT (1e-6) of its size; seed 2's arc, which passes a limit 0.1° from a toggle, ends at
    1.7e-9."""
    rng = np.random.default_rng(100 + seed)
    target = arc_of(random_fourbar(rng), rng, rng.uniform(1 / 3, 3 / 4))
    found = synthesis.path(
        target, closed=False, top=1, atlas=arc_atlas, refine=0, global_search=False
    )
    assert found
    size = size_of(target)
    assert found[0].error <= synthesis.EXACT * size, found[0].error / size
    assert found[0].source in ("equation", "cognate"), found[0].source
    assert_one_circuit(found[0])
    assert tracked_distance(found[0].linkage, target) <= 1e-6 * size + 1e-4 * size


def test_the_curve_equation_takes_sixteen_points_or_more() -> None:
    """The core's function names its least count; the search leaves the stage out below it."""
    pts = linkage.catalog.hoecken().circuit(16).point[:-1]
    with pytest.raises(linkage.LinkageError, match="needs at least 16 points on the curve, got 15"):
        linkage._core.synthesis.fourbars_from_curve(np.ascontiguousarray(pts))
    assert synthesis._equation_pool(np.ascontiguousarray(pts), True, 1) == []
    bad = np.ascontiguousarray(linkage.catalog.hoecken().circuit(21).point[:-1])
    bad[4, 1] = np.nan
    with pytest.raises(linkage.LinkageError, match="curve point"):
        linkage._core.synthesis.fourbars_from_curve(bad)


def test_full_turn_guides_the_search_not_only_the_ranking(
    arc_atlas: Atlas, no_equation: None
) -> None:
    """An arc of a crank-rocker with full_turn=True: the constraint picks which matches are
    refined, so the drawing crank-rocker is found; before, an exact fit of another class ended
    the search and the filter then left an empty list (found by a new-user trial)."""
    fb = linkage.FourBar(ground=10, crank=4, coupler=12, rocker=11, point=(6, -5))
    target = fb.sweep(np.linspace(0.3, 0.3 + 0.85 * 2 * np.pi, 40)).point
    found = synthesis.path(
        target, closed=False, top=1, full_turn=True, atlas=arc_atlas, global_search=False
    )
    assert found, "full_turn=True left no candidate"
    size = size_of(target)
    assert found[0].full_turn, found[0]
    assert found[0].error <= 1e-6 * size, found[0].error / size
    assert_one_circuit(found[0])


def test_arc_atlas_round_trips_and_finds_its_own_arcs(tmp_path) -> None:  # type: ignore[no-untyped-def]
    a = Atlas.build(3000, kind="fourbar-arcs", threads=1)
    assert np.array_equal(
        a.descriptors, Atlas.build(3000, kind="fourbar-arcs", threads=2).descriptors
    )
    assert a.params.shape == (3000, 8) and a.kind == "fourbar-arcs" and a.phases == 8
    a.save(tmp_path / "arcs")
    c = Atlas.load(tmp_path / "arcs")
    assert (c.kind, c.phases, c.samples) == ("fourbar-arcs", 8, 128)
    assert np.array_equal(a.params, c.params)
    idx, dist, _ = c.nearest(np.asarray(a.descriptors[17:18]), 1)
    assert idx[0] == 17 and dist[0] == 0
    # A closed search does not take an arc atlas, and an arc atlas's entries are checked.
    with pytest.raises(linkage.LinkageError, match="fourbar-arcs atlas was given"):
        synthesis.path(
            np.c_[np.cos(np.arange(8.0)), np.sin(np.arange(8.0))], kind="slider-crank", atlas=a
        )
    with pytest.raises(linkage.LinkageError, match="arc phase"):
        synthesis._core.synthesis.arc_entry_frame(
            np.array([1.0, 2.0, 1.5, 0.5, 0.5, 0.0, 9.0, 0.0]), 8, 128, 8
        )


@settings(
    max_examples=6, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(
    coeffs=st.lists(st.floats(-0.4, 0.4), min_size=6, max_size=6),
    aspect=st.floats(0.2, 1.0),
)
def test_no_candidate_switches_branch(atlas: Atlas, coeffs: list[float], aspect: float) -> None:
    """Random smooth closed targets: every candidate's curve, swept by the tracker over its
    circuit, assembles everywhere, moves continuously, and is the curve its error was measured
    on."""
    t = np.linspace(0, 2 * math.pi, 60, endpoint=False)
    a1, b1, a2, b2, a3, b3 = coeffs
    x = np.cos(t) + a1 * np.cos(2 * t) + b1 * np.sin(2 * t) + a3 * np.cos(3 * t)
    y = aspect * np.sin(t) + a2 * np.cos(2 * t) + b2 * np.sin(2 * t) + b3 * np.sin(3 * t)
    target = np.c_[x, y]
    found = synthesis.path(target, atlas=atlas, top=5, global_search=False, refine=3)
    for cand in found:
        assert_one_circuit(cand)
        span = float(np.ptp(cand.linkage.circuit(101).point, axis=0).max())
        d = tracked_distance(cand.linkage, target, 20001)
        # The polyline is within its longest chord of the curve (a branch switch would differ
        # by the size of the linkage): near a crank limit of a near-change-point linkage the
        # curve runs fast and its chords are long (measured: 7e-3 at 4001 samples).
        curve = cand.linkage.circuit(20001).point
        chord = float(np.max(np.hypot(*np.diff(curve, axis=0).T)))
        assert abs(d - cand.error) <= 1e-3 * span + chord, (d, cand.error, chord)


def assert_one_circuit(cand: synthesis.Candidate, n: int = 1001) -> None:
    """The tracker's circuit sweep of the candidate (``FourBar.circuit``: driven, branch
    tracked) is, sample for sample, the declared assembly's closed form from limit to limit and
    the other assembly's back (full turn: the declared assembly throughout): it never switched
    branch and every sample assembled."""
    fb = cand.linkage
    sweep = fb.circuit(n)
    assert np.all(np.isfinite(sweep.point)), "an unassembled sample"
    if cand.full_turn:
        s = 2 * math.pi * np.arange(n) / (n - 1)
    else:
        half = (n + 1) // 2
        k = np.arange(n)
        s = np.where(
            k < half, math.pi * k / (half - 1), math.pi + math.pi * (k - half) / (n - half - 1)
        )
    closed_form = linkage._core.synthesis.residuals(
        cand.params[None, :], np.array([fb.assembly == "crossed"]), np.zeros((n, 2)), s[None, :]
    )[0]
    size = float(np.ptp(sweep.point, axis=0).max())
    # A switch is a jump of the order of the size. At a crank limit (a toggle) the position
    # keeps only √ε of its digits, amplified where the coupler point is far from the coupler
    # (measured up to 2.3e-6 of the size), so the bound is 1e-4 of the size.
    gap = np.hypot(*(sweep.point - closed_form).T)
    assert np.max(gap) <= 1e-4 * size
    assert np.median(gap) <= 1e-9 * size


def test_constraints_are_met(atlas: Atlas) -> None:
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    target = fb.circuit(121).point[:-1][::2]
    found = synthesis.path(
        target,
        atlas=atlas,
        top=5,
        global_search=False,
        full_turn=True,
        min_transmission=math.radians(10),
    )
    assert found
    for c in found:
        assert c.full_turn and c.min_transmission >= math.radians(10)
        assert c.crank_range[1] - c.crank_range[0] == pytest.approx(2 * math.pi)
        assert not c.through_limit
        assert_one_circuit(c)


@pytest.mark.parametrize("scale", [1.0, 1e6])
def test_an_empty_result_says_which_constraint_removed_the_fits(atlas: Atlas, scale: float) -> None:
    # Hoecken's curve, whose pivots are asked to lie in a box far from it. At 1e6 the search
    # runs on the target moved to unit size and the removed fit is moved back too.
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    target = scale * fb.circuit(121).point[:-1][::2]
    box = ((1000 * scale, 1000 * scale), (1001 * scale, 1001 * scale))
    asked = dict(atlas=atlas, top=3, global_search=False)
    free = synthesis.path(target, **asked)
    found = synthesis.path(target, pivots=box, **asked)
    assert isinstance(found, synthesis.Candidates) and found == []
    assert list(found.removed) == ["pivots"] and found.removed["pivots"] >= len(free)
    gone = found.closest_removed
    assert gone is not None and found.closest_fails == ("pivots",)
    # It is a fit in the target's frame (the constraints steered it, so it need not be exact):
    # its error is its curve's distance from the target, and its pivots lie outside the box.
    # (Up to the polyline's chords, 3e-7 of the size: the curve's equation brings a removed
    # fit at 5e-10 of the size.)
    curve = gone.linkage.circuit(20001).point
    chords = 1e-6 * size_of(target)
    assert synthesis.largest_distance(target, curve) == pytest.approx(
        gone.error, rel=1e-3, abs=chords
    )
    assert gone.error < size_of(target)
    assert not (box[0][0] <= gone.linkage.o[0] <= box[1][0])
    why, blamed = synthesis.why_none(found, CLI_CONSTRAINTS)
    assert blamed == "pivots" and f"fits failing --pivots: {found.removed['pivots']})" in why
    pins = ", ".join(f"({x:.3g}, {y:.3g})" for x, y in (gone.linkage.o, gone.linkage.c))
    assert f"the closest, error {gone.error:.3g}, fails --pivots (pivots {pins}): loosen it" in why
    # With no constraint, nothing is removed.
    assert free and free.removed == {} and free.closest_removed is None


def test_a_bounded_search_of_an_arc_is_exact(arc_atlas: Atlas) -> None:
    # Bounds that hold Hoecken's linkage (links 10 … 25, its point 50 from A): its arc is found
    # to 8e-12 of the size in 1.4 s. The bounded trust region (lsmr) had stopped at 4.0e-6 in
    # 64 s (default atlas); bounded parameters are now sines fitted by MINPACK.
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    arc = fb.circuit(241).point[:-1][20:90:2]
    found = synthesis.path(arc, closed=False, top=3, atlas=arc_atlas, lengths=(5.0, 60.0))
    assert found and found[0].error <= 1e-6 * size_of(arc)
    for c in found:
        g = c.linkage
        assert all(5.0 <= v <= 60.0 for v in (g.ground, g.crank, g.coupler, g.rocker))
        assert_one_circuit(c)


def test_a_looser_constraint_finds_what_a_tighter_one_does(atlas: Atlas) -> None:
    # On the foot path, min_transmission=30° alone found nothing while adding full_turn=True
    # found a candidate (0.245 mm, μ 67°) that meets the looser constraint too (default atlas):
    # the matches refined first were ordered by full turns only when full_turn was asked for,
    # least squares left the transmission bound, and the global search ignored it. With this
    # atlas both found nothing.
    pts = synthesis.read_points("examples/foot_path.csv")
    mu = math.radians(30)
    for top in (1, 4):
        tight = synthesis.path(pts, atlas=atlas, top=top, min_transmission=mu, full_turn=True)
        loose = synthesis.path(pts, atlas=atlas, top=top, min_transmission=mu)
        assert len(loose) >= len(tight) >= 1
        assert all(c.min_transmission >= mu for c in loose)
        assert all(c.full_turn and c.min_transmission >= mu for c in tight)


def test_csv_input(tmp_path, atlas: Atlas) -> None:  # type: ignore[no-untyped-def]
    fb = linkage.catalog.get("chebyshev")
    assert isinstance(fb, linkage.FourBar)
    pts = fb.circuit(121).point[:-1][::2]
    f = tmp_path / "curve.csv"
    f.write_text("x,y\n" + "\n".join(f"{float(x)!r},{float(y)!r}" for x, y in pts))
    found = synthesis.path(f, atlas=atlas, top=1, global_search=False)
    assert found[0].error <= 1e-6 * size_of(pts)


def test_atlas_round_trips_through_files(tmp_path) -> None:  # type: ignore[no-untyped-def]
    a = Atlas.build(3000, harmonics=6, threads=1)
    b = Atlas.build(3000, harmonics=6, threads=2)
    assert np.array_equal(a.descriptors, b.descriptors) and np.array_equal(a.params, b.params)
    a.save(tmp_path / "atlas")
    c = Atlas.load(tmp_path / "atlas")
    assert isinstance(c.descriptors, np.memmap)
    assert np.array_equal(a.descriptors, c.descriptors) and c.harmonics == 6
    idx, dist, _ = c.nearest(np.asarray(a.descriptors[5:6]), 2)
    assert idx[0] == 5 and dist[0] == 0
    with pytest.raises(linkage.LinkageError, match="not a readable atlas"):
        Atlas.load(tmp_path / "nothing")


@pytest.mark.parametrize(
    ("points", "error", "match"),
    [
        (np.zeros((3, 2)), linkage.LinkageError, "at least 5 distinct points"),
        (
            np.tile([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], (6, 1)),
            linkage.LinkageError,
            r"at least 5 distinct points, got 3 \(18 points repeating them\)",
        ),
        (
            np.array([[0, 0], [1, 0], [np.nan, 1], [2, 2], [3, 1], [0, 3]]),
            linkage.LinkageError,
            "finite",
        ),
        (np.c_[np.arange(8.0), 2 * np.arange(8.0)], linkage.LinkageError, "collinear"),
        (np.zeros((8, 3)), linkage.LinkageError, r"shape \(n, 2\)"),
        (np.array([["a", "b"]] * 6), TypeError, "real numbers"),
    ],
)
def test_bad_input(points: np.ndarray, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        synthesis.path(points, atlas=Atlas.build(100, threads=1))


def test_bad_csv(tmp_path) -> None:  # type: ignore[no-untyped-def]
    f = tmp_path / "bad.csv"
    f.write_text("1,2\n3,x\n")
    with pytest.raises(linkage.LinkageError, match=r"bad\.csv:2"):
        synthesis.read_points(f)
    f.write_text("1,2\n3,4,5\n")
    with pytest.raises(linkage.LinkageError, match=r"bad\.csv:2: 3 numbers"):
        synthesis.read_points(f)
    with pytest.raises(linkage.LinkageError, match="cannot read"):
        synthesis.read_points(tmp_path / "missing.csv")


def test_cli_synth(tmp_path, capsys, monkeypatch, atlas: Atlas) -> None:  # type: ignore[no-untyped-def]
    from linkage import cli

    reads: list[object] = []
    read = synthesis.read_points
    monkeypatch.setattr(synthesis.targets, "read_points", lambda p: reads.append(p) or read(p))

    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    pts = fb.circuit(121).point[:-1][::2]
    f = tmp_path / "foot.csv"
    np.savetxt(f, pts, delimiter=",", header="x,y", comments="")
    folder = atlas.save(tmp_path / "atlas")
    code = cli.main(
        ["synth", str(f), "--top", "2", "--units", "mm", "--quiet", "--atlas", str(folder)]
    )
    out = capsys.readouterr().out
    assert code == 0
    assert [p for p in reads if isinstance(p, str)] == [str(f)]  # the file is read once
    assert "error mm" in out
    assert any(k in out for k in ("crank-rocker", "double-rocker", "rocker-crank")), out
    # The last column says which stage found each candidate (61 points of a four-bar's curve:
    # the curve-equation stage draws it exactly, as the atlas may too).
    table = [line.split() for line in out.splitlines()[1:]]
    assert table[0][-1] == "from", out
    assert "equation" in {r[-1] for r in table[1:]}, out
    assert {r[-1] for r in table[1:]} <= {"equation", "atlas", "global", "cognate"}, out
    code = cli.main(["synth", str(tmp_path / "missing.csv"), "--quiet", "--atlas", str(folder)])
    assert code != 0
    assert "cannot read" in capsys.readouterr().err
    # --atlas is the atlas used: a folder that is not one is refused, not replaced.
    code = cli.main(["synth", str(f), "--quiet", "--atlas", str(tmp_path)])
    assert code == 2
    assert "not a readable atlas" in capsys.readouterr().err
    # The constraints a scene sets are options too; every printed candidate meets them.
    box = ["--pivots", "-200", "-300", "200", "100", "--lengths", "2", "200"]
    args = ["synth", str(f), "--quiet", "--atlas", str(folder), "--full-turn", *box]
    code = cli.main([*args, "--min-transmission-deg", "20", "--seed", "3", "--tol", "1e-4"])
    out = capsys.readouterr().out
    assert code == 0, out
    rows = [line.split() for line in out.splitlines()[2:]]
    assert rows and all(float(r[r.index("…") + 2]) >= 20.0 for r in rows), out  # min μ
    # Nothing found is one line on stderr and status 2, naming the constraints given.
    far = ["--pivots", "1000", "1000", "1001", "1001"]
    assert cli.main(["synth", str(f), "--quiet", "--atlas", str(folder), *far]) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.splitlines()) == 1, err
    assert err.startswith("linkage: error: no valid four-bar found for"), err
    assert "(fits failing --pivots: " in err and ", fails --pivots (pivots (" in err, err
    assert ")): loosen it, or refine" in err, err
    # Too many points: named after the file, with what to do.
    many = tmp_path / "many.csv"
    np.savetxt(many, np.random.default_rng(0).normal(size=(10_001, 2)), delimiter=",")
    assert cli.main(["synth", str(many), "--quiet", "--atlas", str(folder)]) == 2
    err = capsys.readouterr().err
    assert f"{many}: path synthesis takes at most 10000 points, got 10001: thin them" in err, err
    for bad, match in (
        (["--min-transmission-deg", "120"], "between 0 and 90, got 120"),
        (["--lengths", "5", "2"], "0 < least < greatest"),
        (["--top", "51"], "between 1 and 50"),
        (["--refine", "201"], "--refine must be between 0 and 200, got 201"),
    ):
        assert cli.main(["synth", str(f), "--quiet", "--atlas", str(folder), *bad]) == 2
        assert match in capsys.readouterr().err


def test_a_fit_with_a_vanishing_link_is_no_candidate() -> None:
    # A crank of 3.9e-6 mm on a foot path had been listed as a full-turn crank-rocker drawing
    # a dot: a link under SHORTEST_LINK of the target's size is no linkage.
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    target = np.ascontiguousarray(fb.circuit(121).point[:-1][::3])
    x = np.array([0.0, 0.0, 20.0, 0.0, 10.0, 25.0, 25.0, 50.0, 0.0])
    assert synthesis._measure(x, False, target, True, "atlas", 1) is not None
    x[4] = 0.5 * synthesis.SHORTEST_LINK * synthesis.target_size(target)
    assert synthesis._measure(x, False, target, True, "atlas", 1) is None


def test_the_cli_notes_a_candidate_near_a_change_point(tmp_path, capsys, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # A double-crank whose Grashof sums differ by 6e-6 (a fit pushed against full_turn): the
    # table says so, as the report's class note does.
    from linkage import cli

    fb = linkage.FourBar(ground=10, crank=35.56, coupler=35.36, rocker=10.200006, point=(29, 27))
    pts = fb.circuit(61).point[:-1]
    c = synthesis.Candidate(
        fb,
        6.86,
        3.77,
        58.6,
        (0.0, 2 * math.pi),
        True,
        fb.grashof(),
        0.0,
        False,
        "atlas",
        np.zeros(9),
    )
    monkeypatch.setattr(synthesis, "path", lambda *a, **k: synthesis.Candidates([c]))
    f = tmp_path / "curve.csv"
    np.savetxt(f, pts, delimiter=",")
    assert cli.main(["synth", str(f), "--quiet", "--units", "mm"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1].endswith("note") and out[2].endswith(
        "6.0e-06 mm from a change point: can flip branch"
    )


def test_progress_is_reported_on_stderr(atlas: Atlas, capsys) -> None:  # type: ignore[no-untyped-def]
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    pts = fb.circuit(121).point[:-1][::3]
    synthesis.path(pts, top=1, atlas=atlas, refine=2, global_search=False, progress=True)
    err = capsys.readouterr().err
    assert "synthesis: [" in err and "/2" in err, err


def test_progress_stages_never_run_backwards(monkeypatch, capsys) -> None:  # type: ignore[no-untyped-def]
    """A stage added as a run goes (long fits, more matches, the global search) is a line of
    its own on a terminal, counted from zero: no line's count goes down (a bar that showed
    24/24 and then 25/30 read as going backwards)."""
    from linkage._progress import Bar

    monkeypatch.setattr(Bar, "__init__", _tty_bar_init(Bar.__init__))
    # A clock that never moves: only the first update draws (at most ten draws a second).
    monkeypatch.setattr("time.monotonic", lambda: 1.0)
    b = Bar("synthesis", total=3)
    for _ in range(2):  # the second is not drawn (no time has passed): the stage draws it
        b.update()
    b.stage("long fits", 2)
    for _ in range(2):
        b.update()
    b.close()
    lines = [seg.split("\r")[-1].strip() for seg in capsys.readouterr().err.split("\n")]
    assert lines[:2] == [
        "synthesis: [####################..........] 2/3",
        "synthesis, long fits: [##############################] 2/2",
    ], lines


def _tty_bar_init(init):  # type: ignore[no-untyped-def]
    def tty_init(self, *args, **kwargs):  # type: ignore[no-untyped-def]
        init(self, *args, **kwargs)
        self.tty = True

    return tty_init


def test_progress_names_a_default_atlas_build(tmp_path, monkeypatch, capsys) -> None:  # type: ignore[no-untyped-def]
    """The first open-target search builds the default arc atlas (~5 s at the default size)
    before its first fit: the progress bar says so first, and not once the atlas is cached."""
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(synthesis.kinds, "DEFAULT_ARC_ENTRIES", 5600)
    # The message is under test, not the search: no further stages after the first fit.
    for name in ("POLISH", "WIDER", "HOPS"):
        monkeypatch.setattr(synthesis.stages, name, 0)
    fb = linkage.catalog.get("hoecken")
    assert isinstance(fb, linkage.FourBar)
    arc = fb.sweep(np.linspace(0.0, 3.0, 20)).point
    kw = dict(closed=False, top=1, refine=1, global_search=False, progress=True)
    synthesis.path(arc, **kw)  # type: ignore[arg-type]
    err = capsys.readouterr().err
    first = err.splitlines()[0] if err else ""
    assert "building the default fourbar-arcs atlas" in first, err
    assert str(tmp_path) in first, err
    synthesis.path(arc, **kw)  # type: ignore[arg-type]
    err = capsys.readouterr().err
    assert "synthesis: [" in err and "building" not in err, err


def _placed_reference(entry, frame_t, frame_c, flip):  # type: ignore[no-untyped-def]
    """The similarity placement written out in numpy (the former Python implementation)."""
    k = frame_t[2] / frame_c[2]
    phi = frame_t[3] - frame_c[3] + (math.pi if flip else 0.0)
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    o, c = (frame_t[:2] + k * rot @ (np.asarray(p) - frame_c[:2]) for p in ((0, 0), (1, 0)))
    return np.array([o[0], o[1], c[0], c[1], *(k * np.asarray(entry[:5]))])


def _arc_reference(feet):  # type: ignore[no-untyped-def]
    s = np.sort(np.mod(feet, 2 * math.pi))
    gaps = np.diff(np.concatenate([s, [s[0] + 2 * math.pi]]))
    g = int(np.argmax(gaps))
    start, end = s[(g + 1) % len(s)], s[g]
    return start, end + 2 * math.pi if end < start else end


def _distance_reference(points, path):  # type: ignore[no-untyped-def]
    a, ab = path[:-1], np.diff(path, axis=0)
    rel = points[:, None, :] - a[None]
    u = np.clip(np.sum(rel * ab, 2) / np.sum(ab * ab, 1), 0.0, 1.0)
    gap = rel - u[..., None] * ab[None]
    return float(np.max(np.min(np.hypot(gap[..., 0], gap[..., 1]), axis=1)))


def test_placement_arc_and_polyline_distance_from_the_core_match_numpy() -> None:
    """The core's placement of atlas entries, covering arc and polyline distance against numpy
    versions written out here, and a NaN sample breaking the polyline."""
    rng = np.random.default_rng(11)
    for _ in range(200):
        entry = rng.uniform(0.2, 3.0, 6)
        ft = np.array([*rng.normal(size=2) * 10, rng.uniform(0.1, 5), rng.uniform(-4, 4)])
        fc = np.array([*rng.normal(size=2), rng.uniform(0.1, 5), rng.uniform(-4, 4)])
        for flip in (False, True):
            got, want = (
                synthesis._placed(entry, ft, fc, flip),
                _placed_reference(entry, ft, fc, flip),
            )
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.abs(want).max())
        feet = rng.uniform(-10.0, 20.0, int(rng.integers(1, 30)))
        np.testing.assert_allclose(synthesis._arc(feet, False), _arc_reference(feet), atol=1e-12)
        path, pts = rng.normal(size=(40, 2)), rng.normal(size=(15, 2)) * 2
        assert synthesis.largest_distance(pts, path) == pytest.approx(
            _distance_reference(pts, path), 1e-12
        )
        # Each point against its own polyline (reference_gap's measure).
        own = rng.normal(size=(15, 7, 2))
        each = linkage._core.synthesis.polyline_distance_each(pts, own.reshape(-1, 2), 7)
        want = [_distance_reference(pts[i : i + 1], own[i]) for i in range(15)]
        np.testing.assert_allclose(each, want, rtol=1e-12)
    assert synthesis._arc(np.array([0.3, 1.0]), True) == (0.0, 2 * math.pi)
    with pytest.raises(linkage.LinkageError, match="polylines"):
        linkage._core.synthesis.polyline_distance_each(np.zeros((3, 2)), np.zeros((8, 2)), 3)
    # A NaN sample breaks the polyline: no segment across the gap (the old code drew one).
    path = np.array([[0.0, 0.0], [2.0, 0.0], [np.nan, np.nan], [2.0, 2.0]])
    assert synthesis.largest_distance(np.array([[2.0, 1.5]]), path) == pytest.approx(0.5)
    assert synthesis.largest_distance(np.array([[0.0, 1.0]]), np.full((3, 2), np.nan)) == math.inf


def evans_b_target() -> np.ndarray:
    fb = linkage.catalog.evans_b()
    assert isinstance(fb, linkage.FourBar)
    return np.ascontiguousarray(fb.circuit(41).point[:-1])


def test_candidates_draw_different_curves(atlas: Atlas) -> None:
    # On the foot path the same crossed linkage came twice, once driven from each pivot
    # (#2 and #3 of `linkage synth examples/foot_path.csv`), and on Evans B's curve three
    # fits differing only in a coupler of 29,000 … 64,000 (errors 0.2567 ×3).
    for pts in (synthesis.read_points("examples/foot_path.csv"), evans_b_target()):
        target = synthesis.clean_target(pts, True)
        size = synthesis.target_size(target)
        found = synthesis.path(pts, top=5, atlas=atlas)
        assert len(found) >= 3
        curves = [synthesis._matched_curve(c, target, True) for c in found]
        for i in range(len(found)):
            for j in range(i):
                a, b = found[i], found[j]
                pivots_a = {a.linkage.o, a.linkage.c}
                pivots_b = {b.linkage.o, b.linkage.c}
                assert pivots_a != pivots_b
                if synthesis._cognates(a, b, 1e-3 * size) or synthesis._cognates(b, a, 1e-3 * size):
                    continue  # Roberts cognates draw the same curve and are kept on purpose
                gap = max(
                    synthesis.largest_distance(curves[i], curves[j]),
                    synthesis.largest_distance(curves[j], curves[i]),
                )
                assert gap > max(1e-6 * size, min(a.error, b.error) / 20), (i, j)


def test_ranking_puts_long_links_last_and_prefers_full_turns_among_exact_fits(atlas: Atlas) -> None:
    # Before atlas format 3 Evans B's best fit was a coupler of 64,200 on an 8.9 curve, passing a
    # toggle. Ranking: a link beyond max_link sizes goes after buildable fits whatever its error
    # (max_link=None ranks by error alone); among exact fits (error ≤ EXACT × size) a full-turn
    # crank comes first, then the transmission angle farthest from a toggle.
    pts = evans_b_target()
    size = synthesis.target_size(pts)
    exact = synthesis.path(pts, top=1, atlas=atlas)[0]
    assert exact.error <= synthesis.EXACT * size
    fb = exact.linkage
    huge = replace(
        exact,
        linkage=linkage.FourBar(
            o=fb.o, c=fb.c, crank=fb.crank, coupler=1e4 * size, rocker=1e4 * size, point=fb.point
        ),
        error=0.5 * exact.error,
    )
    rough = replace(exact, error=0.1 * size, full_turn=True, min_transmission=1.0)
    turning = replace(exact, error=0.9 * exact.error, full_turn=True, min_transmission=0.2)
    rocking = replace(exact, error=0.5 * exact.error, full_turn=False, min_transmission=0.9)
    limit = synthesis.LONG_LINK * size
    ranked = synthesis._ranked([huge, rough, rocking, turning], size, limit)
    assert ranked == [turning, rocking, rough, huge]
    assert synthesis._ranked([rough, huge], size, math.inf) == [huge, rough]
    with pytest.raises(linkage.LinkageError, match="max_link"):
        synthesis.path(pts, max_link=0.0, atlas=atlas)


def test_exact_fits_tie_and_the_better_transmission_angle_ranks_first(atlas: Atlas) -> None:
    """Two exact fits that do not turn fully (the rule path's docstring states): a rocker
    passing within 0.1° of a toggle at 1e-13 of the size goes after a buildable one at 8e-7
    (an exact linkage as the long fits of a short arc leave it); a fit just above EXACT does
    not tie."""
    pts = evans_b_target()
    size = synthesis.target_size(pts)
    exact = synthesis.path(pts, top=1, atlas=atlas)[0]
    toggling = replace(
        exact, error=1e-13 * size, full_turn=False, min_transmission=math.radians(0.1)
    )
    buildable = replace(
        exact, error=8e-7 * size, full_turn=False, min_transmission=math.radians(40)
    )
    near = replace(exact, error=1.2e-6 * size, full_turn=False, min_transmission=math.radians(60))
    ranked = synthesis._ranked([toggling, near, buildable], size, math.inf)
    assert ranked == [buildable, toggling, near], [
        (c.error / size, c.min_transmission_deg) for c in ranked
    ]


def test_evans_b_is_recovered_exactly(atlas: Atlas) -> None:
    pts = evans_b_target()
    found = synthesis.path(pts, top=1, atlas=atlas)
    assert found[0].error <= 1e-6 * synthesis.target_size(pts)


def test_cognates_of_an_exact_fit_offer_its_full_turn_drives() -> None:
    """An exact fit by a linkage whose crank rocks (Hoecken's first cognate, a double-rocker,
    draws Hoecken's curve) brings its cognates and other drives along: Hoecken itself and
    Chebyshev's lambda driven at D, both crank-rockers fitting to rounding, which the ranking
    then prefers. The search may stop at its first exact fit (``top=1``)."""
    fb = linkage.catalog.hoecken()
    first, _ = fb.cognates()
    target = synthesis.clean_target(np.ascontiguousarray(fb.circuit(61).point[:-1]), True)
    size = synthesis.target_size(target)
    x = np.array(first._p()[:9], dtype=np.float64)
    rocking = synthesis._measure(x, first.assembly == "crossed", target, True, "atlas", 1)
    assert rocking is not None and rocking.grashof == "double-rocker"
    assert rocking.error <= synthesis.EXACT * size
    more = synthesis._cognate_candidates([rocking], target, True, size, 1)
    turning = [c for c in more if c.full_turn and c.error <= 1e-12 * size]
    pivots = {frozenset((c.linkage.o, c.linkage.c)) for c in turning}
    assert pivots == {frozenset({(0.0, 0.0), (20.0, 0.0)}), frozenset({(40.0, 0.0), (20.0, 0.0)})}
    assert all(c.grashof == "crank-rocker" and c.source == "cognate" for c in turning)
    best = synthesis._ranked([rocking, *more], size, math.inf)[0]
    assert best.full_turn, best


def test_a_cognate_is_not_hidden_by_its_numbers_on_the_other_assembly() -> None:
    """Half a double-rocker's circuit (a new user's trial, 2026-11-27): its open crank-rocker
    cognate (crank 7.21 about the double-rocker's pivot O, turns fully, μ 29°) has the same nine
    numbers as the other crank-rocker's reversed drive on the crossed assembly, which misses by
    5.6 sizes. That variant, tried first, had marked the numbers as seen, and the exact
    full-turn cognate was never listed."""
    fb = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20, point=(4, 6))
    c = fb.circuit(20001).point[:-1]
    idx = ((0.61 + 0.5 * np.linspace(0, 1, 20)) * len(c)).astype(int) % len(c)
    rot = np.array([[math.cos(0.3), math.sin(0.3)], [-math.sin(0.3), math.cos(0.3)]])
    target = np.ascontiguousarray(c[idx] @ rot)
    size = size_of(target)
    found = synthesis.path(target, closed=False, top=3)
    turning = [x for x in found if x.full_turn and x.error <= synthesis.EXACT * size]
    cranks = sorted(round(x.linkage.crank, 4) for x in turning)
    assert cranks == [7.2111, 8.4853], [(x.source, x.linkage) for x in found]


def test_cognate_candidates_are_exact_and_each_linkage_is_listed_once(atlas: Atlas) -> None:
    """A new user's case: a crossed crank-rocker's curve gave the same cognate driven at either
    pivot twice (their assemblies differ: a rocking crank's flips at its limits), and a reversed
    double-rocker tracing its other circuit at an error of the curve's size. Every candidate is
    now a different linkage, and every cognate fits exactly."""
    fb = linkage.FourBar(
        ground=30, crank=22, coupler=9, rocker=26, point=(-4, 12), assembly="crossed"
    )
    pts = np.ascontiguousarray(fb.circuit(60).point[:-1])
    size = synthesis.target_size(pts)
    found = synthesis.path(pts, top=5, atlas=atlas)
    assert found and found[0].full_turn and found[0].error <= 1e-12 * size
    for c in found:
        if c.source == "cognate":
            assert c.error <= synthesis.EXACT * size, c
    for i, a in enumerate(found):
        for b in found[:i]:
            assert not synthesis._same_pivots(a, b, 1e-9 * size), (a, b)


def test_atlas_save_keeps_the_users_files(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # Saving into a folder holding the user's own meta.json replaced it without a word, and
    # saving onto a file raised a bare FileExistsError (a new user's trial).
    a = Atlas.build(200, threads=1)
    mine = tmp_path / "notes"
    mine.mkdir()
    (mine / "meta.json").write_text("my own notes\n")
    with pytest.raises(linkage.LinkageError, match="not an atlas's"):
        a.save(mine)
    assert (mine / "meta.json").read_text() == "my own notes\n"
    assert sorted(q.name for q in mine.iterdir()) == ["meta.json"]
    (tmp_path / "file.txt").write_text("x")
    with pytest.raises(linkage.LinkageError, match="is a file"):
        a.save(tmp_path / "file.txt")
    assert (tmp_path / "file.txt").read_text() == "x"
    # A folder holding an atlas is replaced, and nothing is left beside it.
    a.save(tmp_path / "atlas")
    b = Atlas.build(300, threads=1)
    b.save(tmp_path / "atlas")
    assert len(Atlas.load(tmp_path / "atlas")) == 300
    assert sorted(q.name for q in tmp_path.iterdir()) == ["atlas", "file.txt", "notes"]


def test_points_files_in_a_spreadsheets_encodings_and_separators(tmp_path) -> None:  # type: ignore[no-untyped-def]
    pts = linkage.catalog.hoecken().circuit(13).point[:-1]
    lines = [f"{float(x)!r}{{sep}}{float(y)!r}" for x, y in pts]
    for name, sep, encoding in (
        ("utf16.txt", "\t", "utf-16"),  # "Unicode text": UTF-16 with a byte-order mark, tabs
        ("bom.csv", ",", "utf-8-sig"),
        ("spaces.txt", "   ", "utf-8"),
        ("semicolons.csv", ";", "utf-8"),
    ):
        f = tmp_path / name
        f.write_text(
            "\n".join(["x_mm,y_mm"] + [s.format(sep=sep) for s in lines]), encoding=encoding
        )
        np.testing.assert_array_equal(synthesis.read_points(f), pts)
    # Decimal commas, as a spreadsheet in such a locale exports them, with semicolons or tabs.
    for name, sep in (("euro.csv", ";"), ("euro.txt", "\t")):
        f = tmp_path / name
        f.write_text(
            "\n".join(["x;y"] + [s.format(sep=sep).replace(".", ",") for s in lines]),
            encoding="utf-8",
        )
        np.testing.assert_array_equal(synthesis.read_points(f), pts)
    bad = [
        (b"\xff\xfe\x00\xd8", "utf16-lone.csv", "not UTF-8 text, nor UTF-16"),
        (
            b"1,2\n\xe9,3\n",
            "latin1.csv",
            r"nor UTF-16 with a byte-order mark \(byte 0xe9 at offset 4\)",
        ),
        (b"\x00\x01\x02binary", "binary.csv", "no points in it"),
        (b"1,2\n3,4\n5\n", "short-row.csv", r"short-row.csv:3: 1 number, not two"),
        (b"1,2\n3,abc\n", "text.csv", "separated by a comma, semicolon, tab or spaces"),
    ]
    for data, name, match in bad:
        (tmp_path / name).write_bytes(data)
        with pytest.raises(linkage.LinkageError, match=match):
            synthesis.read_points(tmp_path / name)
    (tmp_path / "folder.csv").mkdir()
    with pytest.raises(linkage.LinkageError, match="is a folder"):
        synthesis.read_points(tmp_path / "folder.csv")
    (tmp_path / "three.csv").write_text("0,0\n1,0\n1,1\n")
    with pytest.raises(linkage.LinkageError, match=r"three.csv: path synthesis needs at least 5"):
        synthesis.path(tmp_path / "three.csv")


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"top": 51}, "top must be between 1 and 50"),
        ({"refine": 201}, "refine must be between 0 and 200"),
        ({"tol": 0.0}, "tol must be positive"),
        ({"min_transmission": 30}, r"did you mean math.radians\(30\)"),
        ({"min_transmission": -0.1}, "between 0 and π/2"),
    ],
)
def test_path_checks_what_scenes_check(kw: dict[str, object], match: str) -> None:
    pts = linkage.catalog.hoecken().circuit(13).point[:-1]
    with pytest.raises(linkage.LinkageError, match=match):
        synthesis.path(pts, atlas=Atlas.build(100, threads=1), **kw)  # type: ignore[arg-type]
    with pytest.raises(linkage.LinkageError, match="at most 10000 points"):
        synthesis.path(np.random.default_rng(0).normal(size=(10_001, 2)))


def test_far_from_the_origin_and_many_points(atlas: Atlas) -> None:
    # The Hoecken curve moved 1e10 away ended at 2e-3 of its size (the fit lost its digits to
    # the coordinates); now it is searched at the origin and ends at the input's own rounding.
    # 1000 points had not finished in 285 s (a fit's cost grows with the cube of its points):
    # now 120 of them are fitted and every point measured.
    fb = linkage.catalog.hoecken()
    pts = fb.circuit(37).point[:-1]
    far = synthesis.path(pts + 1e10, atlas=atlas, top=1, global_search=False)[0]
    rounding = float(np.max(np.abs((pts + 1e10) - 1e10 - pts)))
    assert far.error <= 2 * rounding + 1e-12 * size_of(pts)
    many = fb.circuit(1001).point[:-1] * 7 + (3, -2)
    best = synthesis.path(many, atlas=atlas, top=1, global_search=False)[0]
    assert best.error <= 1e-9 * size_of(many)
    # The error is the largest over all 1000 points, as _errors measures it.
    e, _ = synthesis._errors(
        best.params[None, :],
        np.array([best.linkage.assembly == "crossed"]),
        np.ascontiguousarray(many),
        True,
        samples=2048,
        exact=True,
    )
    assert e[0, 0] == pytest.approx(best.error, rel=1e-9, abs=1e-15 * size_of(many))


def test_a_short_arc_of_fewer_points_than_unknowns_is_fitted(arc_atlas: Atlas) -> None:
    # 5 … 7 points (fewer than a four-bar's nine parameters) of the Hoecken curve's straight
    # stance ended at 8e-3 … 1.2e-2 of their size: MINPACK refuses a fit with fewer residuals
    # than unknowns (2n < 9 + n), and the refusal left every match unrefined.
    hoecken = linkage.catalog.hoecken().circuit(37).point[:-1]
    for n in (5, 6, 7):
        pts = hoecken[:n]
        best = synthesis.path(pts, closed=False, top=1, atlas=arc_atlas, global_search=False)[0]
        assert best.error <= 1e-9 * size_of(pts), (n, best.error / size_of(pts))


def test_near_copies_of_a_long_linked_fit_are_listed_once() -> None:
    """A new user's open arc (a flat stance and the start of a swing) listed the same crank-rocker
    three times: its 330 mm crank and far pivot moved along a valley of near-fits by 4.6 … 6.7 mm,
    a quarter of the target's size but 2 % of the linkage. Near-copies are judged on the
    linkage's own scale when it is larger; a different design is still listed."""
    k = np.arange(1, 8)
    target = np.r_[
        np.c_[np.arange(30, -30.1, -2.5), np.full(25, -100.0)],
        np.c_[-30 + 3.75 * k, -100 + 20 * np.sin(np.radians(11.25 * k))],
    ]
    size = synthesis.target_size(target)
    found = []
    # Places 1, 2 and 3 of path(target, closed=False, top=3) with the default atlases.
    for crossed, x in (
        (
            False,
            [
                -233.41653,
                130.12765,
                5.9090245,
                -106.15229,
                333.194,
                18.480665,
                15.363937,
                15.910363,
                21.340885,
            ],
        ),
        (
            False,
            [
                -228.82568,
                125.15304,
                5.9878175,
                -106.21728,
                326.5078,
                18.521772,
                15.379368,
                15.942438,
                21.4187,
            ],
        ),
        (
            True,
            [
                8.494579,
                -110.16956,
                -127.74456,
                91.440971,
                23.033959,
                26.107881,
                240.11767,
                16.815098,
                -28.585516,
            ],
        ),
    ):
        c = synthesis._measure(np.array(x), crossed, target, False, "atlas", 1)
        assert c is not None and c.error < 0.01 * size, c
        found.append(c)
    # The first two differ by a quarter of the size and more: five times NEAR of it.
    assert np.abs(found[0].params - found[1].params).max() > 5 * synthesis.NEAR * size
    kept = synthesis._distinct(found, target, False, size, 5)
    assert kept == [found[0], found[2]]


def test_a_full_turn_crank_reports_its_transmission_over_the_whole_turn(arc_atlas: Atlas) -> None:
    """A new user's open target (a 60 mm stance and the start of a 20 mm swing) with
    ``full_turn``: the motor drives the crank through the whole turn, so the least transmission
    angle counts there, not only on the matched part (one candidate read 53.5° and came within
    0.1° of a toggle elsewhere in its turn). Checked by an independent sweep of the joints."""
    stance = np.c_[np.linspace(0, 60, 20), np.zeros(20)]
    t = np.linspace(0, 0.3, 9)[1:]
    target = np.r_[stance, np.c_[60 - 60 * t, 20 * np.sin(np.pi * t)]]
    found = synthesis.path(target, closed=False, top=5, atlas=arc_atlas, full_turn=True)
    assert found and all(c.full_turn for c in found)
    theta = np.linspace(0, 2 * np.pi, 20001)
    for c in found:
        joints = c.linkage.sweep(theta).joints  # O, C, A, B, …
        a, b, r = joints[:, 2], joints[:, 3], joints[:, 1]
        u, v = b - a, b - r
        cos = (u * v).sum(axis=1) / np.hypot(*u.T) / np.hypot(*v.T)
        mu = np.arccos(np.clip(cos, -1, 1))
        least = float(np.min(np.minimum(mu, np.pi - mu)))
        # The sweep's 20,001 samples and the circuit's 512 see the same least angle.
        assert c.min_transmission == pytest.approx(least, abs=math.radians(0.05)), c


def test_the_same_search_returns_the_same_candidates(arc_atlas: Atlas) -> None:
    """A new user's open target returned one of two candidate lists from run to run, with the
    same seed, in one process too: SciPy's C MINPACK (1.15 on) read one element past its copy of
    the Jacobian (valgrind), so a few fits depended on whatever lay there. Without the fix 2 of
    5 identical calls differed here; a search must be repeatable."""
    stance = np.c_[np.linspace(0, 60, 20), np.zeros(20)]
    t = np.linspace(0, 0.3, 9)[1:]
    target = np.r_[stance, np.c_[60 - 60 * t, 20 * np.sin(np.pi * t)]]
    kw = dict(closed=False, top=5, full_turn=True, min_transmission=math.radians(30))
    runs = [
        [c.params for c in synthesis.path(target, atlas=arc_atlas, global_search=False, **kw)]
        for _ in range(4)
    ]
    assert runs[0]
    for other in runs[1:]:
        assert len(other) == len(runs[0])
        for a, b in zip(runs[0], other):
            np.testing.assert_array_equal(a, b)


def test_a_long_linked_candidate_says_why_it_is_ranked_after(tmp_path, capsys, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """A new user read a fit 500 times better listed third as a sorting mistake: it had a
    448 mm coupler side on a 15 mm target, past ``max_link``. The CLI table and the page say
    why it comes after."""
    from linkage import cli
    from linkage.html_report import _ranked_after

    pts = linkage.catalog.hoecken().circuit(13).point[:-1]
    f = tmp_path / "foot.csv"
    np.savetxt(f, pts, delimiter=",")
    size = synthesis.target_size(pts)
    short = linkage.catalog.hoecken()
    long = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(40 * size, 0))
    found = [
        synthesis.Candidate(
            lk, e, e, e, (0.0, 6.3), True, "crank-rocker", 0.5, False, "atlas", np.zeros(9)
        )
        for lk, e in ((short, 1e-3), (long, 1e-9))
    ]
    monkeypatch.setattr(synthesis, "path", lambda *a, **k: found)
    assert cli.main(["synth", str(f), "--quiet"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split()[-1] == "note"
    assert not lines[2].endswith("ranked after")
    assert lines[3].endswith("× size: ranked after")
    assert _ranked_after(found[0], size) == ""
    assert "the size: ranked after" in _ranked_after(found[1], size)


def test_lengths_bound_the_coupler_triangle_too(atlas: Atlas) -> None:
    """``lengths`` bounds the links; a new user's foot bar (the coupler triangle's side to the
    point, a link of the leg too) came out at 136–144 mm under a bound of 80 or 120. Hoecken's
    own point lies 50 from its crank pin: under a bound of 40 it is no answer."""
    pts = linkage.catalog.hoecken().circuit(37).point[:-1]
    found = synthesis.path(pts, top=3, atlas=atlas, lengths=(5, 40), global_search=False)
    assert found
    for c in found:
        along, left = c.linkage.point
        arms = (math.hypot(along, left), math.hypot(c.linkage.coupler - along, left))
        assert max(arms) <= 40, c
