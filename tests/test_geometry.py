"""Geometry of motion: instant centres, curvature, Ball point, straightness, mobility,
catalogue figures and the Chebyshev–Hoecken cognates."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage
from linkage import geometry as g


def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def line_intersection(p, d, q, e):
    t = cross(q - p, e) / cross(d, e)
    return p + d * t[..., None]


def test_instant_centres_of_a_four_bar_match_kennedy_construction(hoecken):
    theta = np.linspace(0, 2 * np.pi, 361)
    s = hoecken.sweep(theta, outputs=("instant_centres",))
    assert s.links == ("ground", "crank", "coupler", "rocker")
    assert s.instant_centres.shape == (361, 6, 2)
    o, c, a, b, _p = (s.joints[:, i] for i in range(5))
    np.testing.assert_allclose(s.instant_centre("ground", "crank"), o, atol=1e-12)
    np.testing.assert_allclose(s.instant_centre("crank", "coupler"), a, atol=1e-12)
    np.testing.assert_allclose(s.instant_centre("coupler", "rocker"), b, atol=1e-12)
    np.testing.assert_allclose(s.instant_centre("rocker", "ground"), c, atol=1e-12)
    with np.errstate(divide="ignore", invalid="ignore"):
        i13 = line_intersection(o, a - o, c, b - c)
        i24 = line_intersection(a, b - a, o, c - o)
    ic13 = s.instant_centre("ground", "coupler")
    fin = np.isfinite(ic13[:, 0])
    np.testing.assert_allclose(ic13[fin], i13[fin], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(s.instant_centre("crank", "rocker"), i24, rtol=1e-9, atol=1e-9)
    # At θ = 90° OA and CB are both vertical: the coupler translates, its centre is at
    # infinity along them, flagged, not a huge number.
    q = s.link_pairs.index(("ground", "coupler"))
    np.testing.assert_array_equal(np.flatnonzero(~fin), [90])
    assert s.instant_centre_at_infinity[90, q]
    np.testing.assert_allclose(np.abs(s.instant_centre_directions[90, q]), [0, 1], atol=1e-12)
    # Kennedy: I12, I23, I13 collinear, for every sample.
    i12, i23 = s.instant_centre("ground", "crank"), s.instant_centre("crank", "coupler")
    u, w = i23 - i12, ic13[fin] - i12[fin]
    u = u[fin]
    ratio = np.abs(cross(u, w)) / np.linalg.norm(u, axis=1)
    assert (ratio < 1e-9 * (1 + np.linalg.norm(w, axis=1))).all()


def test_velocity_is_perpendicular_to_offset_from_instant_centre(hoecken):
    theta = np.linspace(0, 2 * np.pi, 97)
    s = hoecken.sweep(theta, omega=3.0, outputs=("velocity", "instant_centres"))
    ic = s.instant_centre("ground", "coupler")
    fin = np.isfinite(ic[:, 0])
    r = np.where(fin[:, None], s.point - ic, 0.0)
    # At infinity the coupler translates: velocity perpendicular to the centre's direction.
    q = s.link_pairs.index(("ground", "coupler"))
    r[~fin] = s.instant_centre_directions[~fin, q]
    cosang = np.sum(r * s.velocity, axis=1) / (
        np.linalg.norm(r, axis=1) * np.linalg.norm(s.velocity, axis=1)
    )
    assert np.abs(cosang).max() < 1e-10


def test_translating_coupler_has_centre_at_infinity():
    fb = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1, 0))
    s = fb.sweep([0.7, 1.9], outputs=("instant_centres",))
    q = s.link_pairs.index(("ground", "coupler"))
    assert s.instant_centre_at_infinity[:, q].all()
    assert np.isnan(s.instant_centres[:, q]).all()
    d = s.instant_centre_directions[:, q]
    crank = s.joints[:, 2] / np.linalg.norm(s.joints[:, 2], axis=1)[:, None]
    np.testing.assert_allclose(np.abs(cross(d, crank)), 0, atol=1e-12)


def test_multi_loop_links_and_kennedy():
    m = linkage.catalog.hart()
    assert len(m.links) == 6 and m.mobility().degrees_of_freedom == 1
    s = m.sweep([0.7], outputs=("instant_centres",))
    n = len(s.links)
    assert s.instant_centres.shape == (1, n * (n - 1) // 2, 2)


@pytest.mark.parametrize("name", ["hoecken", "hart", "jansen", "parallelogram"])
def test_chosen_pairs_are_those_of_every_pair(name):
    """``pairs=`` computes only the pairs named, in their order, with the bits of an
    every-pair sweep (either order within a pair), directions of centres at infinity
    included (computed on first use); on arbitrary angles (the held pass) and few samples
    (the tracker)."""
    item = (
        linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1, 0))
        if name == "parallelogram"
        else linkage.catalog.get(name)
    )
    m = item.mechanism() if isinstance(item, linkage.FourBar) else item
    links = m.links
    rng = np.random.default_rng(5)
    chosen = [
        (links[-1], links[0]),
        (links[1], links[2]),
        (links[0], links[2]),
        (links[1], links[-1]),
    ]
    for theta in (rng.uniform(-7, 7, 3000), np.array([0.7, 1.9, math.pi / 2])):
        every = m.sweep(theta, outputs=("instant_centres",))
        some = m.sweep(theta, outputs=("point", "instant_centres"), pairs=chosen)
        assert some.link_pairs == tuple(chosen)
        assert some.instant_centres.shape == (len(theta), len(chosen), 2)
        for q, (a, b) in enumerate(chosen):
            np.testing.assert_array_equal(some.instant_centres[:, q], every.instant_centre(a, b))
            np.testing.assert_array_equal(some.instant_centre(b, a), every.instant_centre(a, b))
            k = every.link_pairs.index((a, b) if (a, b) in every.link_pairs else (b, a))
            np.testing.assert_array_equal(
                some.instant_centre_directions[:, q], every.instant_centre_directions[:, k]
            )
        np.testing.assert_array_equal(some.point, every.point)
    if name == "parallelogram":  # the coupler translates: its centre with the ground is far
        assert some.instant_centre_at_infinity[:, 2].all()


def test_bad_pairs_are_named():
    fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25)
    ic = ("instant_centres",)
    with pytest.raises(
        linkage.LinkageError, match=r"pairs\[1\]: no link 'frame'; links are ground"
    ):
        fb.sweep([0.0], outputs=ic, pairs=[("ground", "crank"), ("frame", "crank")])
    with pytest.raises(KeyError):  # an UnknownNameError is also a KeyError
        fb.sweep([0.0], outputs=ic, pairs=[("ground", "frame")])
    with pytest.raises(linkage.LinkageError, match=r"pairs\[0\]: 'crank' and 'crank' are one link"):
        fb.sweep([0.0], outputs=ic, pairs=[("crank", "crank")])
    with pytest.raises(linkage.LinkageError, match=r"pairs\[0\] must hold two link names, got 3"):
        fb.sweep([0.0], outputs=ic, pairs=[("ground", "crank", "rocker")])
    with pytest.raises(TypeError, match=r"pairs\[0\] must be a \(link, link\) pair"):
        fb.sweep([0.0], outputs=ic, pairs=["ground"])
    with pytest.raises(TypeError, match=r"pairs\[0\]: links must be named by str, got int"):
        fb.sweep([0.0], outputs=ic, pairs=[(0, 2)])
    with pytest.raises(TypeError, match="pairs must be a sequence"):
        fb.sweep([0.0], outputs=ic, pairs="ground")
    # Ordered pairs only: a set's order is not the caller's, a dict is no sequence of pairs.
    with pytest.raises(TypeError, match=r"pairs must be a sequence of .* got dict"):
        fb.sweep([0.0], outputs=ic, pairs={"ground": "crank"})
    with pytest.raises(TypeError, match=r"pairs\[0\] must be a \(link, link\) pair"):
        fb.sweep([0.0], outputs=ic, pairs=[{"ground", "crank"}])
    # numpy's strings are names too.
    s = fb.sweep([0.0], outputs=ic, pairs=np.array([["ground", "crank"]]))
    assert s.link_pairs == (("ground", "crank"),) and type(s.link_pairs[0][0]) is str
    with pytest.raises(linkage.LinkageError, match="add 'instant_centres' to outputs"):
        fb.sweep([0.0], outputs=("point",), pairs=[("ground", "coupler")])
    s = fb.sweep([0.0], outputs=ic, pairs=[("ground", "coupler")])
    with pytest.raises(linkage.LinkageError, match="'crank' and 'rocker' was not computed"):
        s.instant_centre("crank", "rocker")
    # No pairs at all is an empty set of centres, not an error.
    assert fb.sweep([0.0, 1.0], outputs=ic, pairs=[]).instant_centres.shape == (2, 0, 2)


@pytest.mark.parametrize("name", linkage.catalog.names())
def test_every_catalogue_linkage_has_one_degree_of_freedom(name):
    """Kutzbach–Gruebler cross-checked with the constructive solver, which drives one crank."""
    item = linkage.catalog.get(name)
    m = item.mechanism() if isinstance(item, linkage.FourBar) else item
    assert m.mobility().degrees_of_freedom == 1


def test_mobility_formula_golden():
    # Thesis 2: four-bar n = 4, j1 = 4 gives F = +1; a roll-slide contact is j2.
    assert g.mobility(4, 4).degrees_of_freedom == 1
    assert g.mobility(3, 2, 1).degrees_of_freedom == 1
    assert g.mobility(6, 7).degrees_of_freedom == 1  # Hart: six links, seven revolutes
    with pytest.raises(linkage.LinkageError, match="non-negative"):
        g.mobility(4, -1)
    with pytest.raises(TypeError, match="links must be an int"):
        g.mobility(4.0, 4)


def test_crank_pin_path_radius_is_the_crank(hoecken):
    s = hoecken.sweep(np.linspace(0, 2 * np.pi, 100), outputs=("curvature",))
    k = s.joint_curvatures[:, 2]
    np.testing.assert_allclose(1 / k, 10.0, rtol=1e-12)
    np.testing.assert_allclose(s.joint_curvature_centres[:, 2], 0.0, atol=1e-12)


def test_curvature_centre_does_not_depend_on_timing(hoecken):
    """Same path under constant speed and a 3-4-5 motion law (thesis 1: 91° → 271° in 1 s)."""
    t = np.linspace(0.02, 0.98, 200)
    s_law, v_law, a_law, _ = linkage.drive.motion_law("3-4-5", t)  # rise 180° over 1 s
    theta = np.radians(91 + 180 * s_law)
    omega = np.radians(180) * v_law
    alpha = np.radians(180) * a_law
    # Closed form of the 3-4-5 law: s = 10u³ − 15u⁴ + 6u⁵, so the library's law is checked too.
    np.testing.assert_allclose(s_law, 10 * t**3 - 15 * t**4 + 6 * t**5, rtol=1e-13, atol=1e-15)
    law = hoecken.sweep(
        theta, omega=omega, alpha=alpha, outputs=("velocity", "acceleration", "curvature")
    )
    steady = hoecken.sweep(theta, omega=2.0, outputs=("velocity", "acceleration"))
    c_law, k_law = g.curvature_centre(law.point, law.velocity, law.acceleration)
    c_steady, k_steady = g.curvature_centre(steady.point, steady.velocity, steady.acceleration)
    finite = np.isfinite(c_law).all(axis=1)
    assert finite.mean() > 0.9
    scale = 1 + np.linalg.norm(c_law[finite], axis=1)
    for other in (c_steady, law.curvature_centre):
        err = np.linalg.norm(c_law[finite] - other[finite], axis=1)
        assert (err <= 1e-9 * scale**2).all(), err.max()
    np.testing.assert_allclose(k_law, k_steady, rtol=1e-9, atol=1e-12)
    # The motion law's peak crank speed: 180°·30/16 = 337.5°/s at t = 0.5 (thesis 1).
    peak = linkage.drive.motion_law("3-4-5", [0.5])[1][0]
    assert math.degrees(np.radians(180) * peak) == pytest.approx(337.5, rel=1e-14)


def test_three_point_estimate_converges_to_analytic_centre(hoecken):
    theta0 = 0.4  # on the swing
    exact = hoecken.sweep(theta0, outputs=("curvature",)).curvature_centre
    errors = []
    for h in (0.08, 0.04, 0.02, 0.01, 0.005):
        p = hoecken.sweep([theta0 - h, theta0, theta0 + h]).point
        errors.append(float(np.linalg.norm(g.circumcentre(p[0], p[1], p[2]) - exact)))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # Symmetric triples converge at second order in the spacing.
    assert (orders > 1.8).all(), (errors, orders)
    assert errors[-1] < 1e-3


def test_curvature_sign_and_inflection_nan():
    c, k = g.curvature_centre([[0, 0], [1, 1]], [[1, 0], [1, 0]], [[0, 2], [3, 0]])
    assert k[0] == pytest.approx(2.0) and k[1] == 0.0
    np.testing.assert_allclose(c[0], [0, 0.5])
    assert np.isnan(c[1]).all()
    c, k = g.curvature_centre([0, 0], [0, 0], [1, 0])
    assert np.isnan(k) and np.isnan(c).all()


def test_inflection_circle_ball_point_has_stationary_zero_curvature(hoecken):
    for theta0 in (0.5, 2.0, 4.5):
        inf = g.inflection_circle(hoecken, theta0)
        assert math.dist(inf.ball_point, inf.centre) == pytest.approx(inf.radius, rel=1e-9)
        assert math.dist(inf.pole, inf.centre) == pytest.approx(inf.radius, rel=1e-9)
        fb = linkage.FourBar(
            ground=20, crank=10, coupler=25, rocker=25, point=inf.ball_point_coupler
        )
        h = 1e-5
        s = fb.sweep(theta0 + h * np.arange(-3, 4), outputs=("curvature",))
        np.testing.assert_allclose(s.point[3], inf.ball_point, atol=1e-9)
        k = s.curvature
        assert abs(k[3]) < 1e-9 / inf.radius
        # Another point of the circle, the inflection pole, has zero curvature too but a
        # non-stationary one: its dκ/dθ sets the scale the Ball point's must vanish against.
        a, b = s.joints[3, 2], s.joints[3, 3]
        u = (b - a) / np.linalg.norm(b - a)
        r = np.asarray(inf.inflection_pole) - a
        fj = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(r @ u, cross(u, r)))
        kj = fj.sweep(theta0 + h * np.arange(-3, 4), outputs=("curvature",)).curvature
        assert abs(kj[3]) < 1e-9 / inf.radius
        generic = abs(kj[4] - kj[2]) / (2 * h)
        ball = abs(k[4] - k[2]) / (2 * h)
        assert generic > 1e-3 / inf.radius
        assert ball < 1e-4 * generic, (ball, generic)


def test_straightness_of_exact_and_approximate_linkages():
    rows = {f.name: f for f in linkage.catalog.figures(samples=8001)}
    for name in ("peaucellier", "hart"):
        assert rows[name].max_deviation < 1e-12 * rows[name].size, name
    for name in ("watt", "roberts", "chebyshev", "hoecken", "evans_a", "evans_b", "evans_c"):
        f = rows[name]
        assert 0 < f.max_deviation <= f.tolerance * (1 + 1e-12), name
        assert f.straight_length > 3 * f.tolerance / 1e-3 * 1e-2, name
    # Peaucellier's line spans |y| ≤ √(60² − 40²) (|DP| = 1200/|DA|, |DA| ≥ 20): 89.443 mm.
    assert rows["peaucellier"].straight_length == pytest.approx(2 * math.sqrt(2000), rel=1e-3)


def test_catalogue_rows_with_stated_tolerances():
    rows = {f.name: f for f in linkage.catalog.figures(samples=8001)}
    assert rows["hoecken"].grashof == "crank-rocker" and rows["hoecken"].input_range is None
    assert rows["chebyshev"].grashof == "double-rocker"
    for name, lo, hi in (("evans_a", 27, 333), ("evans_b", -81, 81), ("evans_c", -75, 75)):
        r = rows[name].input_range
        assert abs(math.degrees(r[0]) - lo) < 1 and abs(math.degrees(r[1]) - hi) < 1, name
    # Hoecken within 0.1% of its size: about 16 mm of straight line, speed within 5%
    # (figures measured at 20001 samples: 16.12 mm, 4.7%; stated tolerance 2%).
    assert rows["hoecken"].straight_length == pytest.approx(16.12, rel=0.02)
    assert rows["hoecken"].speed_variation < 0.05
    assert math.isinf(rows["evans_c"].speed_variation)  # its straight part reaches a toggle


def test_hoecken_exact_straight_span_at_its_bulge():
    """At a tolerance just above the bulge between the exact points x = 0, 20, 40 (0.0975 mm),
    the stride covers the whole span."""
    s = linkage.catalog.hoecken().circuit(20001)
    fp = g.foot_path(s.point[:-1], tol=0.1, velocity=s.velocity[:-1])
    assert fp.stride > 40.0
    assert fp.lift_height == pytest.approx(2 * math.sqrt(600) - 40, abs=0.1)
    assert 0.5 < fp.stance_fraction < 0.7


def test_chebyshev_and_hoecken_are_cognates():
    """Hoecken's foot path is exactly twice Chebyshev's midpoint curve as placed here (both
    symmetric: Chebyshev's axis x = 10 meets its curve at (10, 20) and (10, 10√6), Hoecken's at
    (20, 40) and (20, 20√6))."""
    h = linkage.catalog.hoecken().circuit(20001)
    c = linkage.catalog.chebyshev().circuit(20001)
    hp, cp = h.point[:-1], c.point[:-1]
    a, b = hp, np.roll(hp, -1, axis=0)
    ab = b - a
    worst = 0.0
    for p in 2 * cp[::40]:
        t = np.clip(np.sum((p - a) * ab, axis=1) / np.sum(ab * ab, axis=1), 0, 1)
        worst = max(worst, float(np.min(np.linalg.norm(a + t[:, None] * ab - p, axis=1))))
    # Bounded by the chord sag of the 20000-segment polyline, not by the curves.
    assert worst < 1e-5
    # Their straight parts at matching tolerances (0.1% of 25 mm, doubled for Hoecken) agree
    # in length to 1%: the least-squares criterion weights samples by each linkage's crank
    # timing, which differs between the cognates (same curve, different speed along it).
    sc = g.straightness(cp, 0.025, closed=True, velocity=c.velocity[:-1])
    sh = g.straightness(hp, 0.05, closed=True, velocity=h.velocity[:-1])
    assert sh.length == pytest.approx(2 * sc.length, rel=0.01)
    # Same straight line: Chebyshev's doubled lies on Hoecken's.
    assert abs(2 * sc.point[1] - sh.point[1]) < 0.05
    assert sc.speed_variation > 5 * sh.speed_variation


def test_straightness_errors_and_none():
    with pytest.raises(linkage.LinkageError, match="shape"):
        g.straightness(np.zeros((5, 3)), 0.1)
    with pytest.raises(linkage.LinkageError, match="tol must be non-negative"):
        g.straightness(np.zeros((5, 2)), -1)
    with pytest.raises(TypeError, match="path must hold real numbers"):
        g.straightness([["a", "b"]], 0.1)
    circle = np.c_[np.cos(np.linspace(0, 6, 50)), np.sin(np.linspace(0, 6, 50))]
    assert g.straightness(circle, 1e-9) is None
    with pytest.raises(linkage.LinkageError, match="no straight part"):
        g.foot_path(circle, 1e-9)
    with pytest.raises(linkage.LinkageError, match="broadcast"):
        g.circumcentre(np.zeros((3, 2)), np.zeros((4, 2)), np.zeros((3, 2)))


def test_ball_point_the_deprecated_name_of_inflection_circle_is_removed(hoecken):
    # linkage.ball_point / linkage.geometry.ball_point were deprecated aliases: removed.
    assert not hasattr(linkage, "ball_point") and not hasattr(g, "ball_point")
    assert linkage.inflection_circle(hoecken, 1.0) == g.inflection_circle(hoecken, 1.0)


def test_inflection_circle_errors():
    fb = linkage.catalog.evans_b()
    with pytest.raises(linkage.AssemblyError):
        g.inflection_circle(fb, math.pi)
    par = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1, 0))
    with pytest.raises(linkage.LinkageError, match="translating"):
        g.inflection_circle(par, 1.0)


def test_outputs_not_asked_are_not_there(hoecken):
    s = hoecken.sweep([0.1, 0.2])
    with pytest.raises(AttributeError, match="instant_centres was not computed"):
        _ = s.instant_centres
    with pytest.raises(AttributeError, match="curvature was not computed"):
        _ = s.curvature_centre


def test_straight_part_speed_and_lift_from_the_core_match_numpy() -> None:
    """The core's speed figures and swing lift of a straight run against numpy written out here,
    on the Hoecken foot path (a wrapping run) and on a path reaching a toggle."""
    fb = linkage.catalog.hoecken()
    theta = np.linspace(0.0, 2 * np.pi, 720, endpoint=False) + 4.0  # the run wraps past the end
    s = fb.sweep(theta, omega=1.0, outputs=("point", "velocity"))
    fp = g.foot_path(s.point, 0.025, velocity=s.velocity)
    idx = fp.stance.indices
    assert idx[0] > idx[-1]  # wraps
    speed = np.hypot(*s.velocity[idx].T)
    assert fp.stance.mean_speed == pytest.approx(speed.mean(), rel=1e-13)
    want = (speed.max() - speed.min()) / speed.mean()
    assert fp.stance.speed_variation == pytest.approx(want, rel=1e-12)
    d = np.asarray(fp.stance.direction)
    offsets = (s.point - np.asarray(fp.stance.point)) @ np.array([-d[1], d[0]])
    side = np.sign(np.mean(np.delete(offsets, idx)))
    assert fp.lift_height == pytest.approx(np.max(side * offsets), rel=1e-13)
    assert fp.lift_height == pytest.approx(2 * math.sqrt(600) - 40, abs=0.01)
    # A speed that is not finite on the run: both figures infinite.
    v = s.velocity.copy()
    v[idx[3]] = np.nan
    part = g.straightness(s.point, 0.025, closed=True, velocity=v)
    assert part is not None and part.mean_speed == part.speed_variation == math.inf


def test_messages_name_what_is_wrong() -> None:
    """An unknown link is named alone; an all-NaN foot path says it has no finite sample."""
    s = linkage.catalog.hoecken().mechanism().sweep([0.5], outputs=("instant_centres",))
    with pytest.raises(linkage.LinkageError, match=r"^no link 'foo'; links are ground,"):
        s.instant_centre("ground", "foo")
    with pytest.raises(linkage.LinkageError, match="are one link"):
        s.instant_centre("crank", "crank")
    with pytest.raises(linkage.LinkageError, match="no finite sample"):
        g.foot_path(np.full((10, 2), np.nan), 0.1)
