"""Toggle and bifurcation classes against 50-digit mpmath references: the parallelogram, a
general change-point linkage, the kite (crank = ground, coupler = rocker) and the deltoid
(crank = coupler, ground = rocker), swept through their flat positions.

What is asserted, sample by sample: positions within a few ε of the linkage size, also
1e-12 rad from a flat position and on it;
rates either within the conditioning bound ``ε/margin²`` of the mpmath derivative, or NaN with
``regular`` False — never a huge number; the branch is the one that continues the motion
smoothly through the flat position, whatever the sampling.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import linkage

mp.mp.dps = 50
EPS = float(np.finfo(np.float64).eps)


def _analytic(kind, g, r, c, k):
    """The tracked branch as an mpmath function of the crank angle, B(θ) on branch ``s``."""

    def crank(th):
        return mp.mpf(r) * mp.cos(th), mp.mpf(r) * mp.sin(th)

    if kind == "parallelogram":
        # The parallelogram branch continues as a parallelogram: B = A + (g, 0).
        def b(th, s):
            ax, ay = crank(th)
            return ax + g, ay

    elif kind == "kite":
        # OA = OC, so B lies on the bisector of angle AOC: B = t·(cos θ/2, sin θ/2),
        # t = r cos θ/2 + s√(k² − r² sin² θ/2): analytic in θ, period 4π.
        def b(th, s):
            h = th / 2
            t = r * mp.cos(h) + s * mp.sqrt(k * k - r * r * mp.sin(h) ** 2)
            return t * mp.cos(h), t * mp.sin(h)

    elif kind == "deltoid":
        # |AO| = r = c and |CO| = g = k: B = O is one branch; the other is O mirrored in AC.
        def b(th, s):
            if s < 0:
                return mp.mpf(0), mp.mpf(0)
            ax, ay = crank(th)
            ux, uy = g - ax, -ay
            n2 = ux * ux + uy * uy
            # foot of O on line AC, then the mirror image of O
            t = -(ax * ux + ay * uy) / n2
            fx, fy = ax + t * ux, ay + t * uy
            return 2 * fx, 2 * fy

    else:
        # A general change point: the side of A → C flips at each flat position (ψ ≡ 0 here),
        # the smooth continuation; s is the side before the first one.
        def b(th, s):
            ax, ay = crank(th)
            dx, dy = g - ax, -ay
            d = mp.sqrt(dx * dx + dy * dy)
            x = (d * d + c * c - k * k) / (2 * d)
            h = mp.sqrt(c * c - x * x)
            flips = int(mp.floor(th / (2 * mp.pi)))
            side = s * (-1) ** flips
            return ax + (x * dx + side * h * dy) / d, ay + (x * dy - side * h * dx) / d

    return b


CASES = {
    # kind: (ground, crank, coupler, rocker, flat crank angles in one turn)
    "parallelogram": (3.0, 1.0, 3.0, 1.0, (0.0, np.pi)),
    "change_point": (4.0, 2.0, 5.0, 3.0, (0.0,)),
    "kite": (2.0, 2.0, 3.0, 3.0, (0.0,)),
    "deltoid": (3.0, 1.0, 1.0, 3.0, (0.0, np.pi)),
}


def _samples(flats, turns=2, offsets=(1e-3, 1e-6, 1e-9, 1e-12, 0.0)):
    """An increasing sweep from 0.5 rad over ``turns`` turns, with samples on and next to every
    flat position (as ``np.linspace`` sweeps hit them)."""
    grid = list(np.linspace(0.5, 0.5 + 2 * np.pi * turns, 37 * turns))
    for t in range(turns + 1):
        for f in flats:
            base = f + 2 * np.pi * t
            grid += [base - o for o in offsets] + [base + o for o in offsets]
    th = np.array(sorted(set(x for x in grid if 0.5 <= x <= 0.5 + 2 * np.pi * turns)))
    return th


def _reference(kind, fb_args, th, b, branch):
    _g, _r, _c, _k = fb_args
    pos = np.array([[float(v) for v in b(mp.mpf(t), branch)] for t in th])
    vel = np.array(
        [[float(mp.diff(lambda x, a=a: b(x, branch)[a], mp.mpf(t))) for a in (0, 1)] for t in th]
    )
    return pos, vel


@pytest.mark.parametrize("kind", sorted(CASES))
def test_toggle_class_against_mpmath(kind):
    g, r, c, k, flats = CASES[kind]
    fb = linkage.FourBar(ground=g, crank=r, coupler=c, rocker=k, point=(0.5 * c, 0.3))
    assert fb.grashof() == "change-point"
    th = _samples(flats)
    s = fb.sweep(th, omega=1.0, outputs=("point", "velocity", "acceleration", "curvature"))
    B = s.joint("B")
    vB = s.joint_velocities[:, 3]
    b = _analytic(kind, g, r, c, k)
    # The declared assembly picks the branch at the first sample; the rest is continuation.
    first = [
        np.hypot(*(np.array([float(v) for v in b(mp.mpf(th[0]), sgn)]) - B[0])) for sgn in (1, -1)
    ]
    branch = 1 if first[0] < first[1] else -1
    ref, vref = _reference(kind, (g, r, c, k), th, b, branch)
    size = g + r + c + k
    # Undetermined instants (the kite's crank pin exactly on the rocker pivot) are invalid;
    # everything else assembles.
    A = s.joint("A")
    d = np.hypot(A[:, 0] - g, A[:, 1])
    assert np.all(s.valid | (d < 1e-12)), th[~s.valid]
    ok = s.valid
    # Positions: a few ε of the size, right up to the flat positions (the base vector and its
    # distance to the toggle are formed in closed form in the crank angle, so even the kite's
    # vanishing base keeps its direction).
    bound = 8 * EPS * size
    err = np.hypot(*(B - ref).T)
    assert np.all(err[ok] <= bound), (th[ok][err[ok] > bound], err[ok].max() / size)
    # Rates: NaN exactly where flagged, right within ε/margin² elsewhere, never huge.
    reg = s.regular
    assert np.all(reg <= ok)
    assert np.all(np.isnan(vB[ok & ~reg])) and np.all(np.isnan(s.acceleration[ok & ~reg]))
    assert np.all(np.isnan(s.curvature[ok & ~reg]))
    assert np.all(np.isfinite(vB[reg]))
    verr = np.hypot(*(vB - vref).T)
    vscale = np.maximum(np.hypot(*vref.T), r)
    vbound = 16 * EPS * vscale / np.minimum(s.margin, 1.0) ** 2
    assert np.all(verr[reg] <= vbound[reg]), (th[reg][verr[reg] > vbound[reg]], verr[reg].max())
    assert np.nanmax(np.abs(s.acceleration)) < 1e3 * size
    # Every sample off the flat positions (margin clear of the rate margin) has its rates.
    assert np.all(reg[ok & (s.margin > 1e-6)])


@pytest.mark.parametrize("kind", sorted(CASES))
def test_branch_does_not_depend_on_where_the_sweep_starts(kind):
    """The declared assembly names the branch with the crank up; a sweep reaches its first
    sample from there. So every start, order and single sample lands on one circuit: θ = 0 and
    2π alike, a reversed sweep the same poses, a lone sample below the ground line what a
    sweep from the crank-up position through the flat position gives (a new user found a
    parallelogram started at 2π, or at one sample in (π, 2π), on the antiparallelogram)."""
    g, r, c, k, _ = CASES[kind]
    fb = linkage.FourBar(ground=g, crank=r, coupler=c, rocker=k, point=(0.5 * c, 0.3))
    th = np.linspace(0.0, 2 * np.pi, 73)
    forward = fb.sweep(th).joint("B")
    backward = fb.sweep(th[::-1]).joint("B")[::-1]
    ok = np.isfinite(forward).all(axis=1)
    np.testing.assert_allclose(backward[ok], forward[ok], atol=1e-9, rtol=0)
    if ok[0] and ok[-1]:  # (the kite's crank pin on the rocker pivot at θ = 0 is undetermined)
        np.testing.assert_allclose(forward[0], forward[-1], atol=1e-9)
    # From the crank-up position to each angle, against each angle alone.
    for t in (0.1, 2.0, 3.5, 4.2, 5.9, 2 * np.pi, -0.7):
        path = np.linspace(np.pi / 2, t, 200)
        walked = fb.sweep(path).joint("B")[-1]
        alone = fb.sweep([t]).joint("B")[0]
        if np.isfinite(walked).all():
            np.testing.assert_allclose(alone, walked, atol=1e-9, err_msg=f"θ = {t}")
    if kind == "parallelogram":
        # The open parallelogram stays one: the coupler parallel to the ground throughout.
        rng = np.random.default_rng(3)
        for start in (th, th[::-1], rng.uniform(-10.0, 10.0, 500)):
            j = fb.sweep(start, outputs=("joints",)).joints
            ab = j[:, 3] - j[:, 2]
            assert np.nanmax(np.abs(ab[:, 1])) < 1e-9, np.nanmax(np.abs(ab[:, 1]))


@pytest.mark.parametrize("kind", sorted(CASES))
def test_branch_does_not_depend_on_the_sampling(kind):
    g, r, c, k, _ = CASES[kind]
    fb = linkage.FourBar(ground=g, crank=r, coupler=c, rocker=k, point=(0.5 * c, 0.3))
    coarse = np.deg2rad(np.arange(5.0, 5.0 + 1440.0 + 1, 30.0))
    on_coarse = fb.sweep(coarse).joint("B")
    for step in (0.1, 1.0, 10.0):
        fine = np.deg2rad(np.arange(5.0, 5.0 + 1440.0 + step / 2, step))
        s = fb.sweep(fine)
        pick = np.isclose(np.mod(np.rad2deg(fine) - 5.0, 30.0), 0.0, atol=1e-6) | np.isclose(
            np.mod(np.rad2deg(fine) - 5.0, 30.0), 30.0, atol=1e-6
        )
        assert pick.sum() == len(coarse)
        np.testing.assert_allclose(s.joint("B")[pick], on_coarse, atol=1e-9, rtol=0)
        # and the motion is continuous: no jump of the size of a link between samples
        jump = np.nanmax(np.hypot(*np.diff(s.joint("B"), axis=0).T))
        assert jump < 2.0 * np.deg2rad(step) * (g + r + c + k), jump


def test_parallelogram_linspace_has_exact_positions_and_flagged_rates():
    fb = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0.5))
    th = np.linspace(0, 2 * np.pi, 9)
    s = fb.sweep(th, omega=1.0, outputs=("point", "velocity", "instant_centres"))
    np.testing.assert_allclose(s.joint("B") - s.joint("A"), np.tile([3.0, 0.0], (9, 1)), atol=4e-16)
    flat = np.array([True, False, False, False, True, False, False, False, True])
    np.testing.assert_array_equal(s.regular, ~flat)
    assert np.isnan(s.velocity[flat]).all()
    # Off the flats the coupler translates: velocity of A, instant centre at infinity.
    np.testing.assert_allclose(s.velocity[~flat], s.joint_velocities[~flat, 2], atol=1e-15)
    gc = s.link_pairs.index(("ground", "coupler"))
    assert s.instant_centre_at_infinity[~flat, gc].all()
    assert not np.isfinite(s.instant_centres[:, gc]).any()


@pytest.mark.parametrize("offset", [0.0, 1e-12, 1e-9])
def test_inflection_circle_refuses_a_flat_position(offset):
    fb = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0.5))
    with pytest.raises(linkage.LinkageError):
        linkage.inflection_circle(fb, offset)


def test_uniform_sweep_refuses_a_flat_position_on_its_path():
    fb = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0.5))
    out = np.full((100, 2), 7.0)
    with pytest.raises(linkage.LinkageError, match=r"flattens at crank angle 3\.14159"):
        fb.uniform_sweep(0.1, 0.05, 100, out=out)
    assert (out == 7.0).all()
    pts = fb.uniform_sweep(0.1, 0.03, 100)  # 0.1 … 3.07: between the flats
    assert np.isfinite(pts).all()


def test_change_point_next_to_its_flat_position_keeps_every_digit():
    """The issue's case: the base distance from hypot cancelled against |coupler − rocker|
    (5e-9 on a size-5 linkage); the closed form in the crank angle keeps full accuracy."""
    g, r, c, k = 2.0, 1.0, 1.5, 0.5  # s + l = 0.5 + 2 = 1 + 1.5: flat at θ = 0
    fb = linkage.FourBar(ground=g, crank=r, coupler=c, rocker=k, point=(0.0, 0.0))
    assert fb.grashof() == "change-point"
    worst = 0.0
    for t in (1e-4, 1e-6, 1e-7, 1e-8, 1e-10):
        s = fb.sweep([0.5, t])
        B = s.joint("B")[1]
        ref = _analytic("change_point", g, r, c, k)(mp.mpf(t), 1)
        first = _analytic("change_point", g, r, c, k)(mp.mpf(0.5), 1)
        if np.hypot(*(np.array([float(v) for v in first]) - s.joint("B")[0])) > 1e-9:
            ref = _analytic("change_point", g, r, c, k)(mp.mpf(t), -1)
        worst = max(worst, float(mp.sqrt((ref[0] - B[0]) ** 2 + (ref[1] - B[1]) ** 2)))
    assert worst <= 4 * EPS * (g + r + c + k), worst


def test_huge_jumps_cost_a_few_turns():
    """Samples 1e9 rad apart: a parallelogram's orientation is a function of the angle (one
    placement a sample), and a walked mechanism skips whole periods of the turn, so each costs a
    few turns of work (the core's work counter is proptested; here, that it finishes at all)."""
    fb = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0.5))
    th = 0.5 + np.arange(200) * 1e9
    s = fb.sweep(th)
    np.testing.assert_allclose(
        s.joint("B") - s.joint("A"), np.tile([3.0, 0.0], (200, 1)), atol=1e-12
    )


def test_a_long_sweep_honours_ctrl_c():
    import _thread
    import threading
    import time

    # A parallelogram driving a second dyad from its coupler point: flat positions (so no held
    # pass) and a dyad not on the crank (so no closed form): every sample is walked to.
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("C", (3, 0))
    m.crank("A", "O", radius=1)
    m.dyad("B", "A", "C", 3, 1, side="left")
    m.point("P", on=("A", "B"), at=(1.5, 0.5))
    m.fixed("D", (1.5, 4.0))
    m.dyad("E", "P", "D", 3.0, 2.0, side="left")
    th = 0.5 + np.arange(400_000) * 1e6  # each step walks a few turns: minutes in all
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    t0 = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            m.sweep(th)
    finally:
        timer.cancel()
    # The whole sweep takes minutes (each jump walks a few turns, 0.4 ms); the signal is seen
    # after at most 2^15 placements of work (~10 ms here), so a second is ample on a loaded
    # machine and still proves the sweep stopped long before its end.
    assert time.monotonic() - t0 < 0.3 + 1.0
