"""Precision-point synthesis: Burmester motion generation, Freudenstein function generation.

Golden values are by construction: a known four-bar's coupler poses, or its own input-output
function, are synthesised and the same four-bar must come back (no textbook figures are quoted:
the worked examples of Norton, Shigley/Uicker, Sandor & Erdman and McCarthy were not at hand to
check their numbers). Consistency tests compute one quantity two ways.
"""

from __future__ import annotations

import inspect
import math
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkage
from linkage.synthesis.precision_points import (
    centre_point_curve,
    chebyshev_points,
    circle_point_curve,
    function,
    motion,
)

TAU = 2 * math.pi


def coupler_poses(fb: linkage.FourBar, theta):
    """Poses (x, y, angle of A→B) of ``fb``'s coupler at crank angles ``theta`` (no tracking:
    each on the declared assembly), and the pins A, B."""
    s = fb.sweep(np.asarray(theta, dtype=float))
    a, b = s.joints[:, 2], s.joints[:, 3]
    d = b - a
    return np.column_stack([s.point, np.arctan2(d[:, 1], d[:, 0])]), a, b


def crank_rocker(assembly: str = "open") -> linkage.FourBar:
    return linkage.FourBar(
        crank=0.7,
        coupler=1.9,
        rocker=1.6,
        point=(0.8, 0.6),
        o=(0.3, -0.2),
        c=(2.3, 0.4),
        assembly=assembly,
    )


def same(a: linkage.FourBar, b: linkage.FourBar, tol: float = 1e-12) -> bool:
    pa = np.array([*a.o, *a.c, a.crank, a.coupler, a.rocker, *a.point])
    pb = np.array([*b.o, *b.c, b.crank, b.coupler, b.rocker, *b.point])
    return bool(np.max(np.abs(pa - pb)) <= tol and a.assembly == b.assembly)


def reproduces(c, poses, tol=1e-12) -> float:
    """Largest mismatch of the candidate's own tracked sweep at its crank angles."""
    s = c.linkage.sweep(c.crank_angles)
    a, b = s.joints[:, 2], s.joints[:, 3]
    ang = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])
    offset = poses[0, 2] - ang[0]
    dang = (ang + offset - poses[:, 2] + np.pi) % TAU - np.pi
    return float(max(np.max(np.abs(s.point - poses[:, :2])), np.max(np.abs(dang))))


def test_three_poses_recover_a_four_bar_from_circle_points():
    fb = crank_rocker()
    poses, a, b = coupler_poses(fb, [0.4, 1.3, 2.5])
    cands = motion(poses, circle_points=[a[0], b[0]])
    assert len(cands) == 2  # each dyad driving once
    first = next(c for c in cands if np.allclose(c.crank.centre, fb.o, atol=1e-12))
    assert first.reaches and first.defect is None and first.direction == 1
    assert same(first.linkage, fb)
    assert first.grashof == "crank-rocker"
    np.testing.assert_allclose(first.crank_angles, [0.4, 1.3, 2.5], atol=1e-12)
    assert first.position_error <= 1e-12 and first.angle_error <= 1e-12
    # The sweep of the returned linkage through the poses reproduces them (two ways).
    assert reproduces(first, poses) <= 1e-12
    # Candidates come valid first.
    assert cands[0].reaches or not any(c.reaches for c in cands)


def test_three_poses_from_centre_points_invert_exactly():
    fb = crank_rocker()
    poses, a, b = coupler_poses(fb, [0.4, 1.3, 2.5])
    cands = motion(poses, centre_points=[fb.o, fb.c])
    first = next(c for c in cands if np.allclose(c.crank.centre, fb.o))
    np.testing.assert_allclose(first.crank.circle, a[0], atol=1e-12)
    np.testing.assert_allclose(first.rocker.circle, b[0], atol=1e-12)
    assert same(first.linkage, fb) and first.reaches


def test_four_poses_recover_the_dyads_on_the_burmester_curves():
    fb = crank_rocker()
    theta = np.array([0.2, 0.9, 1.7, 2.6])
    poses, _a, b = coupler_poses(fb, theta)
    rocker_angle = np.arctan2(b[:, 1] - fb.c[1], b[:, 0] - fb.c[0])
    # The free rotation is to one of poses 1-3; try the crank's and rocker's rotations to each.
    beta = [theta[k] - theta[0] for k in (1, 2, 3)] + [
        rocker_angle[k] - rocker_angle[0] for k in (1, 2, 3)
    ]
    cands = motion(poses, beta=beta)
    hits = [c for c in cands if same(c.linkage, fb, 1e-9)]
    assert hits and all(c.reaches for c in hits)
    assert reproduces(hits[0], poses) <= 1e-9


def test_burmester_curves_pair_concyclic_points():
    poses = np.array([[0.0, 0.0, 0.0], [1.0, 0.3, 0.4], [1.8, 1.1, 0.9], [2.1, 2.0, 1.6]])
    g = centre_point_curve(poses, n=360)
    k = circle_point_curve(poses, n=360)
    assert g.shape == k.shape == (720, 2)
    ok = np.all(np.isfinite(g), axis=1)
    assert ok.sum() > 400
    assert np.array_equal(ok, np.all(np.isfinite(k), axis=1))
    # Each circle point's four positions lie on a circle about its centre point.
    c, s = np.cos(poses[:, 2]), np.sin(poses[:, 2])
    w = k[ok] - poses[0, :2]
    w = np.column_stack([c[0] * w[:, 0] + s[0] * w[:, 1], -s[0] * w[:, 0] + c[0] * w[:, 1]])
    radii = []
    for j in range(4):
        pos = poses[j, :2] + np.column_stack(
            [c[j] * w[:, 0] - s[j] * w[:, 1], s[j] * w[:, 0] + c[j] * w[:, 1]]
        )
        radii.append(np.hypot(*(pos - g[ok]).T))
    r = np.array(radii)
    assert np.max(np.abs(r - r[0]) / np.maximum(r[0], 1.0)) < 1e-9


def test_branch_defect_is_flagged_never_passed():
    fb = crank_rocker()
    p_open, a, b = coupler_poses(fb, [0.4, 1.3])
    p_crossed, _, _ = coupler_poses(crank_rocker("crossed"), [2.5])
    poses = np.vstack([p_open, p_crossed])
    cands = motion(poses, circle_points=[a[0], b[0]])
    first = next(c for c in cands if np.allclose(c.crank.centre, fb.o))
    assert not first.reaches
    assert first.defect == "branch" and first.defect_pose == 2


def test_order_defect_is_flagged():
    fb = crank_rocker()
    theta = np.array([0.0, 3.0, 1.5, 4.5])
    poses, _a, b = coupler_poses(fb, theta)
    rocker_angle = np.arctan2(b[:, 1] - fb.c[1], b[:, 0] - fb.c[0])
    beta = [theta[k] - theta[0] for k in (1, 2, 3)] + [
        rocker_angle[k] - rocker_angle[0] for k in (1, 2, 3)
    ]
    hits = [c for c in motion(poses, beta=beta) if same(c.linkage, fb, 1e-9)]
    assert hits and all(c.defect == "order" for c in hits)


def test_chebyshev_spacing():
    h = math.sqrt(3) / 4
    np.testing.assert_allclose(chebyshev_points(0.0, 1.0, 3), [0.5 - h, 0.5, 0.5 + h], atol=1e-15)
    x = chebyshev_points(1.0, 4.0, 6)
    np.testing.assert_allclose(x + x[::-1], 5.0, atol=1e-14)
    j = np.arange(6)
    np.testing.assert_allclose(x, 2.5 - 1.5 * np.cos((2 * j + 1) * np.pi / 12), atol=1e-15)


def rocker_angle_of(fb: linkage.FourBar, theta: float) -> float:
    b = fb.sweep([theta]).joints[0, 3]
    return math.atan2(b[1] - fb.c[1], b[0] - fb.c[0])


def test_function_generation_recovers_a_known_linkage():
    fb = linkage.FourBar(ground=1.0, crank=0.45, coupler=1.1, rocker=0.8)

    def f(x: float) -> float:
        return rocker_angle_of(fb, x)

    lo, hi = 0.5, 2.2
    r = function(f, (lo, hi), (lo, hi), (f(lo), f(hi)))
    assert same(r.linkage, fb)
    assert r.reaches and r.defect is None
    assert r.structural_error < 1e-11
    assert r.precision_points.shape == (3, 2)
    np.testing.assert_allclose(r.precision_points[:, 0], chebyshev_points(lo, hi, 3))
    d, a, b, c = 1.0, 0.45, 1.1, 0.8
    np.testing.assert_allclose(r.k, [d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)])
    # Least squares over 7 points of the same function is exact too.
    r7 = function(f, (lo, hi), (lo, hi), (f(lo), f(hi)), points=7)
    assert same(r7.linkage, fb)


def test_function_generation_structural_error_two_ways():
    # y = log10 x on [1, 2]; φ from 45° over 60°, ψ from 135° over 90° (figures measured here).
    phi = (math.radians(45), math.radians(105))
    psi = (math.radians(135), math.radians(225))
    r = function(math.log10, (1.0, 2.0), phi, psi)
    assert r.reaches
    assert 1e-6 < r.structural_error < math.radians(1.0)
    # The error at the precision points is zero: the returned linkage, swept there.
    for (x, _), (p, q) in zip(r.precision_points, r.precision_angles):
        theta = p + (r.crank_range[0] - phi[0])
        out = rocker_angle_of(r.linkage, theta) - r.output_offset
        assert abs((out - q + np.pi) % TAU - np.pi) < 1e-12
    # The error curve equals the sweep of the returned linkage against the desired output.
    theta = r.crank_range[0] + (r.x - 1.0) * (r.crank_range[1] - r.crank_range[0])
    s = r.linkage.sweep(theta)
    b = s.joints[:, 3]
    out = np.arctan2(b[:, 1] - r.linkage.c[1], b[:, 0] - r.linkage.c[0]) - r.output_offset
    want = psi[0] + np.log10(r.x) / math.log10(2.0) * (psi[1] - psi[0])
    err = (out - want + np.pi) % TAU - np.pi
    np.testing.assert_allclose(err, r.error, atol=1e-12)
    assert r.structural_error == pytest.approx(np.max(np.abs(err)), abs=1e-12)
    assert r.structural_error_y == pytest.approx(
        r.structural_error * math.log10(2.0) / (psi[1] - psi[0])
    )


@pytest.mark.parametrize(
    ("poses", "kwargs", "exc", "match"),
    [
        ([[0, 0, 0], [1, 0, 0.1]], {"circle_points": [[0, 1]]}, linkage.LinkageError, "at least 3"),
        ([[0, 0, 0]] * 5, {}, linkage.LinkageError, "3 or 4 poses"),
        (
            [[0, 0, 0], [1, 0, np.nan], [0, 1, 0]],
            {"circle_points": [[0, 1]]},
            linkage.LinkageError,
            "finite",
        ),
        (
            [[0, 0, 0.1], [1, 0.5, 0.4], [0, 0, 0.1]],
            {"circle_points": [[0.3, 0.3], [1, 1]]},
            linkage.LinkageError,
            "0 and 2 coincide",
        ),
        ([[0, 0, 0], [1, 0, 0.1], [2, 0.5, 0.2]], {}, linkage.LinkageError, "circle_points="),
        (
            [[0, 0, 0.5], [1, 1, 0.5], [3, 3, 0.5]],
            {"circle_points": [[0.2, -0.7], [1, 0]]},
            linkage.LinkageError,
            r"circle_points\[0\].*infinity",
        ),
        (
            [[0, 0, 0.2], [1, 0, 0.2], [1, 1, 0.2], [0, 2, 0.2]],
            {},
            linkage.LinkageError,
            "pure translations",
        ),
        ([[0, 0, 0], [1, 0, 0.1], [2, 0.5, 0.2]], {"beta": [0.1]}, TypeError, "beta"),
        (
            [[0, 0, 0], [1, 0, 0.1], [2, 0.5, 0.2], [2, 1, 0.4]],
            {"circle_points": [[0, 1]]},
            TypeError,
            "beta",
        ),
        (
            [[0, 0, 0], [1, 0, 0.1], [2, 0.5, 0.2]],
            {"circle_points": [[5, 5]]},
            linkage.LinkageError,
            "at least 2 dyads",
        ),
    ],
)
def test_motion_bad_input(poses, kwargs, exc, match):
    with pytest.raises(exc, match=match):
        motion(np.asarray(poses, dtype=float), **kwargs)


def test_function_bad_input():
    rng = (0.0, 1.0)
    with pytest.raises(TypeError, match="callable"):
        function(3.0, rng, rng, rng)  # type: ignore[arg-type]
    with pytest.raises(linkage.LinkageError, match="points must be an int ≥ 3, got 2"):
        function(math.exp, rng, rng, (0.5, 1.5), points=2)
    with pytest.raises(linkage.LinkageError, match="distinct"):
        function(math.exp, (1.0, 1.0), rng, rng)
    with pytest.raises(linkage.LinkageError, match="not finite"):
        function(lambda x: math.nan, rng, rng, rng)
    with pytest.raises(linkage.LinkageError, match="y_range"):
        function(math.cos, (-1.0, 1.0), rng, rng)
    with pytest.raises(linkage.LinkageError, match=r"points\[0\] and points\[2\] are the same"):
        function(math.exp, rng, (0.5, 1.5), (1.0, 2.0), points=[0.2, 0.5, 0.2])
    with pytest.raises(linkage.LinkageError, match="spacing"):
        function(math.exp, rng, (0.5, 1.5), (1.0, 2.0), spacing="random")


@settings(max_examples=40, deadline=None)
@given(
    lens=st.tuples(*[st.floats(0.3, 3.0)] * 4),
    start=st.floats(0.0, TAU),
    steps=st.lists(st.floats(0.2, 1.5), min_size=2, max_size=2),
    crossed=st.lists(st.booleans(), min_size=3, max_size=3),
)
def test_every_candidate_reaches_or_is_flagged(lens, start, steps, crossed):
    g, r, b, c = lens
    theta = np.cumsum([start, *steps])
    rows, pins = [], []
    for t, x in zip(theta, crossed):
        fb = linkage.FourBar(
            ground=g,
            crank=r,
            coupler=b,
            rocker=c,
            point=(0.4, 0.3),
            assembly="crossed" if x else "open",
        )
        p, a, bb = coupler_poses(fb, [t])
        if not np.all(np.isfinite(p)):
            return
        rows.append(p[0])
        pins.append((a[0], bb[0]))
    poses = np.array(rows)
    try:
        cands = motion(poses, circle_points=[pins[0][0], pins[0][1]])
    except linkage.LinkageError:
        return
    for cand in cands:
        if cand.reaches:
            size = max(cand.linkage.ground, cand.linkage.crank, cand.linkage.coupler, 1.0)
            assert reproduces(cand, poses) <= 1e-9 * size
        else:
            assert cand.defect in ("branch", "toggle", "order", "flat-position")


# The trial's log10 generator (tests/…/FINDINGS item 4 and 17).
LOG_ARGS = (math.log10, (1.0, 2.0), np.radians((45, 105)), np.radians((135, 225)))


@pytest.mark.parametrize(
    ("kwargs", "exc", "match"),
    [
        ({"points": 0}, linkage.LinkageError, "points must be an int ≥ 3, got 0"),
        ({"points": 3.0}, TypeError, "points must be an int .* got float"),
        ({"points": np.float64(5)}, TypeError, "points must be an int .* got float64"),
        ({"points": True}, TypeError, "points must be an int .* got bool"),
        ({"n_check": 1}, linkage.LinkageError, "n_check must be an int ≥ 2, got 1"),
        ({"n_check": 0}, linkage.LinkageError, "n_check must be an int ≥ 2, got 0"),
        ({"n_check": 11.0}, TypeError, "n_check must be an int"),
    ],
)
def test_function_counts_state_their_real_limits(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        function(*LOG_ARGS, **kwargs)


def test_function_refuses_counts_beyond_memory_before_any_work(monkeypatch):
    def f(x: float) -> float:
        raise AssertionError(f"f({x}) called before the memory check")

    # A 10 MB budget: 10**6 precision points need ~80 MB (f is never called).
    monkeypatch.setattr("linkage._shared.arrays.memory_limit", lambda: 10**7)
    with pytest.raises(MemoryError, match=r"1000000 precision points .*needs"):
        function(f, (1.0, 2.0), (0.5, 1.5), (1.0, 2.0), y_range=(0.0, 1.0), points=10**6)
    with pytest.raises(MemoryError, match="1000000 samples needs"):
        function(f, (1.0, 2.0), (0.5, 1.5), (1.0, 2.0), y_range=(0.0, 1.0), n_check=10**6)
    # Within the budget it runs.
    assert function(math.log10, (1.0, 2.0), (0.5, 1.5), (1.0, 2.0), points=100).k


def test_function_time_grows_linearly_with_points():
    # 2·10⁵ points took ~45 s when the core compared every pair of points (3·10⁴: 1.1 s);
    # linear, it takes ~0.2 s (f is called once a point).
    start = time.perf_counter()
    r = function(*LOG_ARGS, points=200_000)
    took = time.perf_counter() - start
    assert r.precision_points.shape == (200_000, 2) and r.reaches
    assert took < 10.0, f"200 000 points took {took:.1f} s"


def test_three_poses_of_one_rotation_are_refused_with_the_geometry():
    # The trial's case: a body pinned at the origin; every dyad's centre is the origin.
    poses = np.array([[0, 0, 0], [0, 0, 0.5], [0, 0, 1.0]])
    with pytest.raises(linkage.LinkageError, match=r"rotations about one point, \(0, 0\)"):
        motion(poses, circle_points=[[1, 0], [0, 1]])
    with pytest.raises(linkage.LinkageError, match="ground link of length zero"):
        motion(poses, centre_points=[[1, 0], [0, 1]])
    # About another point, built with rounding.
    c = np.array([1.5, -2.0])
    a = np.array([0.1, 0.7, 1.9])
    rot = np.stack([np.cos(a), -np.sin(a), np.sin(a), np.cos(a)], axis=1).reshape(3, 2, 2)
    turned = np.column_stack([c + rot @ -c, a])
    with pytest.raises(linkage.LinkageError, match=r"\(1\.5, -2\)"):
        motion(turned, circle_points=[[1, 0], [0, 1]])
    # A near miss (the body also moves that point) still gives real four-bars.
    turned[2, 0] += 0.3
    found = motion(turned, circle_points=[[1, 0], [0, 1]])
    assert found and all(c.linkage.ground > 0.01 for c in found)


def test_motion_names_the_argument_at_fault():
    fb = crank_rocker()
    poses, a, b = coupler_poses(fb, [0.4, 1.3, 2.5])
    with pytest.raises(
        linkage.LinkageError, match=r"circle_points\[0\] driving circle_points\[1\]"
    ):
        motion(poses, circle_points=[a[0], a[0]])
    poses[1] = poses[0]
    with pytest.raises(linkage.LinkageError, match=r"^poses: precision positions 0 and 1 coincide"):
        motion(poses, circle_points=[a[0], b[0]])


@pytest.mark.parametrize("k", [1, 2, 3])
def test_four_pose_beta_is_measured_to_the_pose_asked_and_reported(k):
    fb = crank_rocker()
    theta = np.array([0.2, 0.9, 1.7, 2.6])
    poses, _a, b = coupler_poses(fb, theta)
    rocker_angle = np.unwrap(np.arctan2(b[:, 1] - fb.c[1], b[:, 0] - fb.c[0]))
    beta = [theta[k] - theta[0], rocker_angle[k] - rocker_angle[0]]
    found = motion(poses, beta=beta, beta_pose=k)
    assert found and {c.beta_pose for c in found} == {k}
    hits = [c for c in found if same(c.linkage, fb, 1e-9)]
    assert hits and all(c.reaches for c in hits)
    # The crank turns by beta from pose 0 to pose k (mod 2π), as reported.
    turn = hits[0].crank_angles[k] - hits[0].crank_angles[0]
    assert abs((turn - beta[0] + np.pi) % TAU - np.pi) < 1e-9


def test_four_pose_default_beta_pose_is_reported_and_consistent():
    fb = crank_rocker()
    theta = np.array([0.2, 0.9, 1.7, 2.6])
    poses, _a, _b = coupler_poses(fb, theta)
    found = motion(poses, n=12)
    (k,) = {c.beta_pose for c in found}
    # The default is the same as asking for that pose, and the curves agree.
    again = motion(poses, n=12, beta_pose=k)
    assert [c.crank.centre for c in found] == [c.crank.centre for c in again]
    np.testing.assert_array_equal(
        centre_point_curve(poses, n=12), centre_point_curve(poses, n=12, beta_pose=k)
    )
    other = 1 + k % 3
    assert not np.array_equal(
        circle_point_curve(poses, n=12, beta_pose=k),
        circle_point_curve(poses, n=12, beta_pose=other),
        equal_nan=True,
    )
    assert all(c.beta_pose is None for c in motion(poses[:3], circle_points=[[0, 1], [1, 0]]))


@pytest.mark.parametrize(
    ("kwargs", "exc", "match"),
    [
        ({"beta_pose": 0}, linkage.LinkageError, "beta_pose must be 1, 2 or 3 .* got 0"),
        ({"beta_pose": 4}, linkage.LinkageError, "beta_pose must be 1, 2 or 3 .* got 4"),
        ({"beta_pose": 1.0}, TypeError, "beta_pose must be an int"),
    ],
)
def test_beta_pose_bad_input(kwargs, exc, match):
    poses = [(1.0, 1.1, 0.4), (0.3, 1.7, 0.3), (-0.6, 1.5, 0.5), (-1.0, 1.0, 0.9)]
    with pytest.raises(exc, match=match):
        motion(poses, **kwargs)
    with pytest.raises(exc, match=match):
        centre_point_curve(poses, **kwargs)
    with pytest.raises(TypeError, match="beta_pose applies to four poses"):
        motion(poses[:3], circle_points=[[0, 1], [1, 0]], beta_pose=1)


def test_function_generator_short_of_its_range_reports_the_part_it_follows():
    """A new user's y = x² on 1…3 (input 30…120°, output 60…150°, 3 Chebyshev points): the
    linkage stops at its input limit near x = 2.954, so the structural error over the range is
    NaN; the part it follows and the largest error there are reported (the user found 2.954 and
    7.64° from ``error`` by hand)."""
    g = function(lambda x: x**2, (1, 3), np.radians((30, 120)), np.radians((60, 150)), points=3)
    assert not g.reaches and g.defect == "input-limit" and math.isnan(g.structural_error)
    ok = np.isfinite(g.error)
    upto = int(np.argmin(ok))  # the first sample it does not follow
    assert g.x_reached == (1.0, g.x[upto - 1]) and 2.9 < g.x_reached[1] < 3.0
    assert g.structural_error_reached == np.max(np.abs(g.error[:upto]))
    assert math.degrees(g.structural_error_reached) == pytest.approx(7.64, abs=0.01)
    # One that follows the whole range reports the whole range.
    h = function(np.log10, (1, 2), np.radians((45, 105)), np.radians((135, 225)), points=3)
    assert h.reaches and h.x_reached == (1.0, 2.0)
    assert h.structural_error_reached == h.structural_error


# The trial's level-platform task (FINDINGS 9): pure translation, moving pivots 40 apart.
LEVEL = np.array([[0.0, 0.0, 0.0], [30.0, 10.0, 0.0], [60.0, 0.0, 0.0]])


def nearest_on_sweep(fb: linkage.FourBar, theta_from: float, theta_to: float, point) -> float:
    """Distance from ``point`` to ``fb``'s coupler point swept densely (tracked, from its
    declared start) between two crank angles."""
    s = fb.sweep(np.linspace(theta_from, theta_to, 2001))
    return float(np.min(np.hypot(*(s.point - np.asarray(point)).T)))


def test_parallelogram_reaches_driven_from_either_pivot():
    # Both candidates are the parallelogram (ground 40, cranks 50); the one driven from the
    # right-hand pivot was built on its antiparallelogram branch (a change point's assembly
    # names its branch at its start angle, a flat position away from pose 0) and missed pose 0.
    cands = motion(LEVEL, circle_points=[[0.0, 0.0], [40.0, 0.0]])
    assert len(cands) == 2
    assert {tuple(np.round(c.linkage.o, 9)) for c in cands} == {(30.0, -40.0), (70.0, -40.0)}
    for c in cands:
        assert c.grashof == "change-point"
        assert c.reaches and c.defect is None, (c.linkage, c.defect, c.defect_pose)
        assert reproduces(c, LEVEL) <= 1e-9
        # Independently: the linkage swept densely from pose 0's crank angle to pose 2's passes
        # through every pose's point.
        t0, t2 = c.crank_angles[0], c.crank_angles[-1]
        for point in LEVEL[:, :2]:
            assert nearest_on_sweep(c.linkage, t0, t2, point) < 0.05
        # The tracked sweep at the poses' crank angles keeps the coupler level (translation).
        s = c.linkage.sweep(c.crank_angles)
        d = s.joints[:, 3] - s.joints[:, 2]
        turn = np.arctan2(d[:, 1], d[:, 0]) - np.arctan2(d[0, 1], d[0, 0])
        np.testing.assert_allclose((turn + np.pi) % TAU - np.pi, 0, atol=1e-12)


def parallelogram_poses(degrees) -> tuple[np.ndarray, np.ndarray]:
    """Level poses of the parallelogram O (30, −40), C (70, −40), cranks 50, body point 7 left
    and 11 above the crank pin, at crank angles ``degrees``; and the pins at the first."""
    o, r = np.array([30.0, -40.0]), 50.0
    t = np.radians(degrees)
    a = o + r * np.column_stack([np.cos(t), np.sin(t)])
    poses = np.column_stack([a + np.array([-7.0, 11.0]), np.zeros(len(t))])
    return poses, np.array([a[0], a[0] + np.array([40.0, 0.0])])


@pytest.mark.parametrize("degrees", [(120, 170, 220), (-30, 10, 40)])
def test_parallelogram_passing_its_flat_position_is_flagged(degrees):
    # At the flat position (crank along the ground line) the parallelogram may go on as an
    # antiparallelogram: a motion through it is a defect, driven from either pivot.
    poses, pins = parallelogram_poses(degrees)
    cands = motion(poses, circle_points=pins)
    assert len(cands) == 2
    assert all(c.grashof == "change-point" for c in cands)
    assert [c.defect for c in cands] == ["flat-position"] * 2
    # Short of it, the same linkages pass.
    start, flat = degrees[0], (180 if degrees[0] > 0 else 0)
    poses, pins = parallelogram_poses((start, (start + flat) / 2, flat - 3))
    assert all(c.reaches for c in motion(poses, circle_points=pins))


# The trial's four-pose task (FINDINGS 9 and 19): mm and radians.
POSES4 = np.array(
    [
        [0.0, 0.0, 0.0],
        [40.0, 15.0, np.radians(30)],
        [70.0, 50.0, np.radians(75)],
        [80.0, 90.0, np.radians(110)],
    ]
)


def test_beta_where_the_burmester_curves_are_not_real_says_so():
    # Independently: the sampled curve has no real point at 40° (row 4 of 10° steps, both
    # halves), but has at 40° measured to pose 2.
    curve = centre_point_curve(POSES4, n=36, beta_pose=1)
    assert np.isnan(curve[[4, 40]]).all()
    assert np.isfinite(centre_point_curve(POSES4, n=36, beta_pose=2)[[4, 40]]).all()
    with pytest.raises(linkage.LinkageError, match=r"no real point at beta = 40° .*pose 1"):
        motion(POSES4, beta=np.radians(40), beta_pose=1)
    assert len(motion(POSES4, beta=np.radians(40), beta_pose=2)) == 2


def test_candidates_that_do_not_reach_have_nan_figures_and_rank_last():
    # FINDINGS 19: fixed pivots chosen; neither candidate reaches, and the one that toggles
    # reported a perfect 90° and 0 mm over "the poses reached" (pose 0 alone).
    poses = POSES4[:3]
    cands = motion(poses, centre_points=[[-20.0, 80.0], [90.0, 100.0]])
    assert cands and not any(c.reaches for c in cands)
    for c in cands:
        assert math.isnan(c.position_error) and math.isnan(c.angle_error)
        assert math.isnan(c.min_transmission_angle)
    # Four poses: every candidate that reaches comes first, by transmission angle, and the
    # figures are finite exactly for them.
    cands = motion(POSES4, n=24, max_link=None)
    reach = [c.reaches for c in cands]
    assert any(reach) and not all(reach)
    assert reach == sorted(reach, reverse=True)
    mu = [c.min_transmission_angle for c in cands if c.reaches]
    assert mu == sorted(mu, reverse=True) and np.isfinite(mu).all()
    assert all(np.isnan(c.position_error) for c in cands if not c.reaches)
    # Those that do not reach: the ones reaching more poses first.
    got = [np.count_nonzero(np.isfinite(c.crank_angles)) for c in cands if not c.reaches]
    assert got == sorted(got, reverse=True)


def links_measured(c, point) -> tuple[float, ...]:
    """Ground, crank, coupler, rocker and the body's sides to its point ``point`` (at pose 0),
    from the candidate's two dyads (not its linkage)."""
    o, cc = np.array(c.crank.centre), np.array(c.rocker.centre)
    a, b, p = np.array(c.crank.circle), np.array(c.rocker.circle), np.asarray(point)
    d = np.linalg.norm
    return (d(cc - o), d(a - o), d(b - a), d(b - cc), d(p - a), d(p - b))


def test_max_link_ranks_compact_designs_first():
    size = linkage.synthesis.target_size(POSES4[:, :2])
    plain = [c for c in motion(POSES4, n=24, max_link=None) if c.reaches]
    for c in plain[:10]:
        assert c.longest_link == pytest.approx(max(links_measured(c, POSES4[0, :2])), rel=1e-9)
    long = [c.longest_link > 3 * size for c in plain]
    assert any(long) and not all(long)
    assert long != sorted(long), "by transmission alone, a long one comes before a compact one"
    ranked = [c for c in motion(POSES4, n=24, max_link=3) if c.reaches]
    long = [c.longest_link > 3 * size for c in ranked]
    assert long == sorted(long)
    assert len(ranked) == len(plain)
    # The default is path's (LONG_LINK sizes), which none of these reach: the same order.
    assert inspect.signature(motion).parameters["max_link"].default == linkage.synthesis.LONG_LINK
    assert linkage.synthesis.LONG_LINK * size > max(c.longest_link for c in plain)
    default = [c for c in motion(POSES4, n=24) if c.reaches]
    assert [c.crank for c in default] == [c.crank for c in plain]


def test_lengths_and_pivots_filter():
    every = motion(POSES4, n=24, max_link=None)
    lo, hi = 5.0, 80.0
    kept = motion(POSES4, n=24, lengths=(lo, hi))
    assert 0 < len(kept) < len(every)
    for c in kept:
        links = links_measured(c, POSES4[0, :2])
        assert all(lo - 1e-9 <= v <= hi + 1e-9 for v in links[:4]) and max(links) <= hi + 1e-9
    inside = [
        c for c in every if lo <= min(links_measured(c, POSES4[0, :2])[:4]) and c.longest_link <= hi
    ]
    assert len(kept) == len(inside)
    box = ((-30.0, 60.0), (30.0, 120.0))
    kept = motion(POSES4, n=24, pivots=box)
    assert 0 < len(kept) < len(every)
    for c in kept:
        for x, y in (c.linkage.o, c.linkage.c):
            assert -30 <= x <= 30 and 60 <= y <= 120
    # An emptied list says so, counting what each filter removed: every four-bar of `every`
    # (max_link only ranks) has a link over 2.
    with pytest.warns(
        UserWarning,
        match=rf"removed all {len(every)} four-bars \(removed by lengths {len(every)}\)",
    ):
        assert motion(POSES4, n=24, lengths=(1.0, 2.0)) == []
    far = ((1e4, 1e4), (1e4 + 1, 1e4 + 1))
    with pytest.warns(UserWarning, match=r"removed by lengths \d+, pivots \d+\): loosen them"):
        assert motion(POSES4, n=24, lengths=(1.0, 2.0), pivots=far) == []


@pytest.mark.parametrize(
    ("kwargs", "exc", "match"),
    [
        ({"lengths": (5.0, 1.0)}, linkage.LinkageError, "0 < least < greatest"),
        ({"lengths": 5.0}, TypeError, r"lengths must be a pair \(least, greatest\), got float"),
        ({"lengths": (1, 2, 3)}, linkage.LinkageError, "lengths must be a pair .* got 3 values"),
        ({"lengths": (1, np.inf)}, linkage.LinkageError, r"lengths\[1\]"),
        ({"pivots": ((0, 0), (0, 1))}, linkage.LinkageError, "xmin, ymin"),
        ({"pivots": (0, 0)}, TypeError, r"pivots\[0\] must be a pair"),
        ({"max_link": 0.0}, linkage.LinkageError, "max_link must be positive"),
    ],
)
def test_motion_filter_bad_input(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        motion(POSES4, n=4, **kwargs)


def test_pose_angles_in_degrees_warn():
    # FINDINGS 19: degrees by mistake passed silently. Legal (angles count modulo 2π), so a
    # warning that names the likely mistake, not an error.
    degrees = np.array([[0, 0, 0], [40, 15, 30], [70, 50, 75]], dtype=float)
    with pytest.warns(UserWarning, match=r"2 of 3 pose angles exceed 2π.*np\.radians") as rec:
        motion(degrees, circle_points=[[-10, -20], [25, -15]])
    assert rec[0].filename == __file__  # attributed to the caller
    with pytest.warns(UserWarning, match="radians") as rec:
        centre_point_curve(np.vstack([degrees, [80, 90, 110]]), n=4)
    assert rec[0].filename == __file__
    radians = degrees.copy()
    radians[:, 2] = np.radians(radians[:, 2])
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        motion(radians, circle_points=[[-10, -20], [25, -15]])
        motion(POSES4, n=4)
