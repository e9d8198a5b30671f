"""Walking machines: gaits, ground contact, stability margin, foot slip, phase search."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import linkage
from linkage import _core
from linkage.drive import crank_schedule
from linkage.gait_search import search_duty_factor
from linkage.walker import Leg, Walker, gait_phases

THETA = np.linspace(0, 2 * np.pi, 1441)


def test_tripod_has_three_feet_down_alternating():
    w = linkage.catalog.hexapod_tripod()
    sim = w.simulate(THETA)
    legs = sim.legs
    down = sim.stance.sum(axis=1)
    # Away from the transitions exactly three feet carry the body; at transitions all six.
    assert set(np.unique(down)) == {3, 6}
    assert (down == 3).mean() > 0.9
    sets = {frozenset(np.array(legs)[row]) for row in sim.stance[down == 3]}
    assert sets == {frozenset({"L1", "R2", "L3"}), frozenset({"R1", "L2", "R3"})}
    # The sets alternate: each appears as one contiguous block per cycle.
    a = sim.stance[:, legs.index("L1")] & (down == 3)
    assert np.count_nonzero(np.diff(a.astype(int)) == 1) == 1
    assert np.allclose(sim.lift_height, 0.0014)
    assert sim.min_margin > 0


def test_quadruped_moves_diagonal_pairs():
    sim = linkage.catalog.quadruped_hoecken().simulate(THETA)
    legs = np.array(sim.legs)
    down = sim.stance.sum(axis=1)
    assert set(np.unique(down)) == {2, 4}
    pairs = {frozenset(legs[row]) for row in sim.stance[down == 2]}
    assert pairs == {frozenset({"A", "D"}), frozenset({"B", "C"})}
    # p/r (from the core's duty-factor figure) against a count of the samples of the stance
    # mask (swing over stance), and the Hoecken stance's ~210° of the turn.
    swing, stance = (~sim.stance).sum(axis=0), sim.stance.sum(axis=0)
    np.testing.assert_allclose(sim.pr_ratio, swing / stance, rtol=1e-12)
    assert np.all((sim.pr_ratio > 0.6) & (sim.pr_ratio < 0.8)), sim.pr_ratio
    assert sim.stride == pytest.approx(np.full(4, 44.376), abs=0.01)
    # The Hoecken swing rises 2√600 − 40 = 8.99 mm above the stance line (exact points).
    np.testing.assert_allclose(sim.lift_height, 2 * math.sqrt(600) - 40, atol=1e-9)
    # Legs hang on 100 mm bars from the coupler point 40 mm above the pivots: the body's
    # underside (pivot level) clears 60 mm.
    assert linkage.catalog.quadruped_hoecken().body_clearance() == pytest.approx(60.0)
    bars = dict(sim.gait_diagram())
    assert len(bars["A"]) >= 1 and all(b > a for a, b in bars["A"])


def test_stability_margin_against_a_hand_computed_polygon():
    # Pads (points) at the corners of a 4 × 2 rectangle: margin at (1, 0.5) is 0.5 (bottom edge).
    pts = np.array([[[0, 0], [4, 0], [4, 2], [0, 2], [np.nan, np.nan]]], dtype=float)
    margin, _hull, count = _core.walking.support_margins(pts, np.array([[1.0, 0.5]]))
    assert margin[0] == pytest.approx(0.5) and count[0] == 4
    margin, _, _ = _core.walking.support_margins(pts, np.array([[5.0, 1.0]]))
    assert margin[0] == pytest.approx(-1.0)
    # A triangle (3, 4, 5): the inradius point (1, 1) is 1 from every side.
    tri = np.array([[[0, 0], [4, 0], [0, 3]]], dtype=float)
    assert _core.walking.support_margins(tri, np.array([[1.0, 1.0]]))[0][0] == pytest.approx(1.0)


def test_margin_sign_flips_when_the_cg_leaves_the_polygon():
    q = linkage.catalog.quadruped_hoecken()
    assert q.simulate(THETA).min_margin > 0
    legs = q.legs
    outside = Walker(legs, cg=(150.0, 0.0), ground_tol=0.1)
    sim = outside.simulate(THETA)
    assert sim.min_margin < 0 and np.nanmax(sim.margin) < 0


def test_slip_zero_when_stance_feet_move_identically():
    q = linkage.catalog.quadruped_hoecken()
    same = q.with_phases([0.0, 0.0, 0.0, 0.0]).simulate(THETA)
    assert same.slip_distance.max() == pytest.approx(0.0, abs=1e-12)
    assert np.nanmax(same.spread) == pytest.approx(0.0, abs=1e-12)
    # In phase the machine is unsupported during the common swing: -inf margin, flagged.
    assert same.min_margin == -math.inf
    trot = q.simulate(THETA)
    assert trot.slip_distance.sum() > 1.0  # mm per cycle, with all cranks at one speed


def test_schedule_lowers_slip_on_both_source_machines():
    """Measured (README): per cycle, quadruped 4.77 mm of slip at constant crank speed against
    2e-4 mm with the schedule (duty factor 0.55); hexapod 0.78 mm against 5e-5 mm."""
    for walker, speed, unit in (
        (linkage.catalog.quadruped_hoecken(), 80.0, 1.0),
        (linkage.catalog.hexapod_tripod(), 0.08, 1e-3),
    ):
        base = walker.simulate(THETA)
        sched = crank_schedule(walker.legs[0].linkage, speed, 0.55)
        t = np.linspace(0, sched.period, 1441)
        run = walker.simulate(time=t, drive=sched, per_leg_time=True)
        assert run.slip_distance.sum() < 1e-3 * base.slip_distance.sum()
        assert run.min_margin > 0
        assert base.slip_distance.sum() > 0.5 * unit


def test_phase_search_recovers_the_trot_from_an_unstable_crawl():
    q = linkage.catalog.quadruped_hoecken()
    crawl = q.with_phases(gait_phases("crawl", ["A", "B", "C", "D"]))
    before = crawl.simulate(THETA)
    assert before.min_margin < 0
    phases, value = crawl.search_phases("margin", step=math.radians(30))
    after = crawl.with_phases(phases).simulate(THETA)
    # (the search samples 360 angles, this check 1441: the sampled minima differ slightly)
    assert value > 0 and after.min_margin == pytest.approx(value, rel=2e-2)
    rel = np.mod(phases - phases[0], 2 * math.pi)
    # A & D together, B & C half a turn away: the source's diagonal pairs.
    assert (
        rel[3] == pytest.approx(0)
        and rel[1] == pytest.approx(math.pi)
        and rel[2] == pytest.approx(math.pi)
    )
    phases, slip = crawl.search_phases("slip", step=math.radians(30))
    assert slip < before.slip_distance.sum()


def test_wilson_gaits():
    legs = ["L1", "L2", "L3", "R1", "R2", "R3"]
    for gait in ("wave", "ripple", "tripod"):
        ph = dict(zip(legs, np.mod(-gait_phases(gait, legs) / (2 * math.pi), 1.0)))
        for seg in "123":  # contralateral legs in antiphase
            assert abs(((ph["L" + seg] - ph["R" + seg]) % 1.0) - 0.5) < 1e-12
        if gait != "tripod":  # the wave runs hind to front
            assert ph["L3"] < ph["L2"] < ph["L1"]
    with pytest.raises(linkage.LinkageError, match="unknown gait"):
        gait_phases("gallop", legs)
    with pytest.raises(linkage.LinkageError, match="no phase for legs"):
        gait_phases("tripod", ["A"])


def test_bad_walkers():
    leg = linkage.catalog.hoecken()
    with pytest.raises(linkage.LinkageError, match="at least one leg"):
        Walker([])
    with pytest.raises(linkage.LinkageError, match="unique"):
        Walker([Leg("A", leg, (0, 0, 0)), Leg("A", leg, (1, 0, 0))])
    with pytest.raises(linkage.LinkageError, match="plane"):
        Leg("A", leg, (0, 0, 0), plane="frontal")
    with pytest.raises(linkage.LinkageError, match="lift program"):
        Leg("A", leg, (0, 0, 0), plane="horizontal")
    with pytest.raises(linkage.LinkageError, match="cannot be assembled"):
        Walker([Leg("E", linkage.catalog.evans_b(), (0, 0, 0))]).simulate(THETA)
    with pytest.raises(linkage.LinkageError, match="step must divide"):
        linkage.catalog.quadruped_hoecken().search_phases(step=0.7)


@pytest.mark.filterwarnings("error::RuntimeWarning")
def test_a_body_travel_beyond_the_float_range_is_an_error_not_an_overflow_warning():
    quad = linkage.catalog.quadruped_hoecken()
    # every time is finite, but travel = speed x time passes 1.8e308 mm
    with pytest.raises(linkage.LinkageError, match="body's travel is not representable"):
        quad.simulate(np.array([0.0, 1e308, 1.7e308]))
    with pytest.raises(linkage.LinkageError, match="body's travel is not representable"):
        quad.simulate(np.array([-1e308, 0.0, 1e308]), 1e300)
    # a long run well inside the range is travelled in full
    sim = quad.simulate(np.linspace(0.0, 2e6 * np.pi, 4001))
    assert np.isfinite(sim.body_position).all() and abs(sim.body_position[-1]) > 1e6


def test_duty_factor_search_with_schedule():
    q = linkage.catalog.quadruped_hoecken()
    beta, margin = search_duty_factor(q, 80.0, "margin", duty_factors=(0.5, 0.55, 0.6, 0.65))
    # A longer stance overlaps the diagonal pairs more: the margin grows with the duty factor
    # (measured 1.06 mm at 0.5, 3.24 at 0.55, 5.21 at 0.6).
    assert beta == 0.65 and margin > 5.0
    beta, slip = search_duty_factor(q, 80.0, "slip", duty_factors=(0.5, 0.55, 0.6))
    assert slip < 1e-2


def test_stance_and_figures_come_from_the_core_leg_figures():
    """One implementation: the walker's stance mask, duty factor, stride and lift are the
    core's leg figures (``_core.walking.leg_gait``) of each foot's sagittal path with the walker's
    ground and tolerance."""
    q = linkage.catalog.quadruped_hoecken()
    sim = q.simulate(THETA)
    for i in range(len(sim.legs)):
        path = np.ascontiguousarray(sim.feet[:, i, [0, 2]])
        rate = np.ascontiguousarray(sim.foot_velocity[:, i, [0, 2]])
        g, stance = _core.walking.leg_gait(path, rate, 0.1, sim.ground)
        np.testing.assert_array_equal(stance, sim.stance[:, i])
        assert g == sim.gaits[i]
        # The rule itself: within the tolerance of the lowest foot level.
        np.testing.assert_array_equal(stance, sim.feet[:, i, 2] <= sim.ground + 0.1)
    assert sim.duty_factor == pytest.approx(np.full(4, 0.58), abs=0.005)
    # A negative tolerance is an error, not an empty stance.
    with pytest.raises(linkage.LinkageError, match="stance tolerance"):
        Walker(q.legs, ground_tol=-1.0).simulate(THETA)


def test_the_searches_live_in_gait_search_and_their_old_names_are_gone():
    from linkage import gait_search

    assert search_duty_factor is gait_search.search_duty_factor is linkage.search_duty_factor
    # linkage.walker.search_phases / search_duty_factor were deprecated aliases: removed.
    assert not hasattr(linkage.walker, "search_phases")
    assert not hasattr(linkage.walker, "search_duty_factor")
    q = linkage.catalog.quadruped_hoecken()
    by_method = q.search_phases("slip", step=math.pi / 2, samples=64)
    by_function = gait_search.search_phases(q, "slip", step=math.pi / 2, samples=64)
    np.testing.assert_array_equal(by_method[0], by_function[0])
    assert by_method[1] == by_function[1]
    with pytest.raises(TypeError, match="walker must be a Walker"):
        gait_search.search_phases(q.legs[0])
    with pytest.raises(AttributeError, match="no attribute 'search_gait'"):
        _ = linkage.walker.search_gait


LEGS = Path(__file__).parent / "scenes" / "legs"


def test_a_leg_from_a_mechanism_scene_walks_as_the_catalogue_leg(tmp_path: Path) -> None:
    # tests/scenes/legs/walker.toml is examples/biped_custom_legs.toml with each leg given by a
    # scene of Hoecken's linkage built joint by joint (as a synthesis candidate is exported):
    # the walker's figures and feet are the catalogue legs'.
    from linkage import runner, scene

    ours = runner.run(scene.load(LEGS / "walker.toml"))
    text = (LEGS / "walker.toml").read_text()
    text = text.replace('scene = "hoecken_joints.toml"', 'catalog = "hoecken"')
    (tmp_path / "walker.toml").write_text(text)
    theirs = runner.run(scene.load(tmp_path / "walker.toml"))
    np.testing.assert_allclose(ours.arrays["feet"], theirs.arrays["feet"], rtol=0, atol=1e-9)
    rows = {r[0]: r.value for r in theirs.figures if not r[0].startswith(("stage", "outside"))}
    mine = {r[0]: r.value for r in ours.figures if not r[0].startswith(("stage", "outside"))}
    assert mine.keys() == rows.keys() and "stride" in rows
    for k, v in rows.items():
        if isinstance(v, float) and k not in ("total",):
            assert mine[k] == pytest.approx(v, rel=1e-9, abs=1e-9), k


def test_a_slider_crank_is_a_leg_as_its_mechanism() -> None:
    sc = linkage.SliderCrank(crank=10, coupler=32, offset=6, point=(12, 9))
    leg = Leg("L", sc, mount=(0.0, 0.0, 0.0))
    assert isinstance(leg.linkage, linkage.Mechanism)
    theta = np.linspace(0, 2 * np.pi, 37)
    np.testing.assert_allclose(leg.linkage.sweep(theta).point, sc.sweep(theta).point, atol=1e-12)
    with pytest.raises(TypeError, match="FourBar, SliderCrank or Mechanism, got int"):
        Leg("L", 3, mount=(0.0, 0.0, 0.0))  # type: ignore[arg-type]


def test_a_leg_whose_pivots_are_below_the_ground_is_reported(tmp_path: Path) -> None:
    # Hoecken's foot path lies above its pivots: mounted with no foot bar, the pivots are
    # under the ground by the path's lowest height; with the example's 100 mm bar, above it.
    from linkage import runner, scene

    low = float(linkage.catalog.hoecken().circuit(20001).point[:, 1].min())
    text = (LEGS / "walker.toml").read_text().replace("foot_offset = [0.0, -100.0], ", "")
    (tmp_path / "walker.toml").write_text(text)
    (tmp_path / "hoecken_joints.toml").write_text((LEGS / "hoecken_joints.toml").read_text())
    for path, want in ((LEGS / "walker.toml", 100.0 - low), (tmp_path / "walker.toml", -low)):
        res = runner.run(scene.load(path))
        row = next(r for r in res.figures if r[0] == "lowest leg pivot above the ground")
        assert row.value == pytest.approx(want, abs=1e-3)
        assert ("below the ground" in row[3]) == (want < 0)
