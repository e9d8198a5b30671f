"""Disc cams: profile from pitch curve, pressure angle closed form, undercut detection."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage
from linkage.cam import DiscCam, leg_lift, leg_lift_cam
from linkage.drive import Program, Segment


def rise_dwell(rise=20.0, beta=math.pi / 3, law="cycloidal"):
    return Program(
        0.0,
        [
            Segment(beta, rise, law),
            Segment(math.pi - beta),
            Segment(beta, -rise, law),
            Segment(math.pi - beta),
        ],
    )


def test_profile_is_the_pitch_curve_offset_by_the_roller():
    cam = DiscCam(rise_dwell(), base_radius=60.0, roller_radius=8.0, offset=3.0)
    p = cam.profile(1441)
    np.testing.assert_allclose(np.linalg.norm(p.pitch - p.profile, axis=1), 8.0, rtol=1e-12)
    # The offset is along the pitch curve's normal: perpendicular to its tangent.
    tangent = np.gradient(p.pitch, axis=0)
    cosang = np.sum(tangent * (p.pitch - p.profile), axis=1) / (
        np.linalg.norm(tangent, axis=1) * 8.0
    )
    assert np.abs(cosang[1:-1]).max() < 2e-3
    # On the low dwell (s = 0, the last segment) the profile is the base circle.
    dwell = (p.phi > 4 * math.pi / 3 + 0.05) & (p.phi < 2 * math.pi - 0.05)
    np.testing.assert_allclose(np.linalg.norm(p.profile[dwell], axis=1), 60.0, rtol=1e-12)
    assert p.problems == []


def test_pressure_angle_against_closed_form():
    """Norton: tan φ = (s' − e)/(s + √(Rp² − e²)); here a constant-velocity rise with offset."""
    rb, rr, e, rise, beta = 30.0, 6.0, 4.0, 12.0, math.pi
    cam = DiscCam(
        Program(
            0.0,
            [Segment(beta, rise, "constant-velocity"), Segment(beta, -rise, "constant-velocity")],
        ),
        rb,
        roller_radius=rr,
        offset=e,
        pressure_limit=math.radians(80),
    )
    p = cam.profile(361)
    first = p.phi < beta - 1e-9
    s = rise * p.phi[first] / beta
    expected = np.arctan2(rise / beta - e, s + math.sqrt((rb + rr) ** 2 - e**2))
    np.testing.assert_allclose(p.pressure_angle[first], expected, atol=1e-14)


def test_undercut_detected_on_a_small_base_circle():
    # Cycloidal 20 mm rise in 60° on a 5 mm base circle: the pitch curve's tightest convex
    # radius (8.92 mm at the top of the rise) is smaller than a 9 mm roller.
    p = DiscCam(rise_dwell(), base_radius=5.0, roller_radius=9.0).profile(1441)
    assert p.undercut
    assert any("undercut" in m and "roller radius 9" in m for m in p.problems)
    with pytest.raises(linkage.LinkageError, match="undercut"):
        p.check()
    flat = DiscCam(rise_dwell(), base_radius=5.0).profile(1441)
    assert flat.undercut and "cusp" in flat.problems[0]
    big = DiscCam(rise_dwell(), base_radius=150.0, roller_radius=6.0).profile(1441)
    assert not big.undercut and big.check() is big


def test_pressure_angle_limit_message():
    p = DiscCam(rise_dwell(), base_radius=12.0, roller_radius=3.0).profile(721)
    assert any("pressure angle" in m and "exceeds the limit 30.0°" in m for m in p.problems)


def test_flat_follower_profile_and_curvature():
    cam = DiscCam(rise_dwell(rise=5.0), base_radius=60.0)
    p = cam.profile(2881)
    assert (p.pressure_angle == 0).all()
    s, v, a, _ = cam.program.eval(p.phi)
    np.testing.assert_allclose(p.profile_radius, 60.0 + s + a, rtol=1e-12)
    # Contact point on the face is s' from the axis: profile = R(−φ)(s', Rb + s).
    r = np.linalg.norm(p.profile, axis=1)
    np.testing.assert_allclose(r, np.hypot(v, 60.0 + s), rtol=1e-12)


def test_leg_lift_cam_of_thesis_two():
    p = leg_lift_cam().profile(721)
    assert p.displacement.max() == pytest.approx(1.4)
    assert not p.undercut and p.max_pressure_angle < math.radians(30)


def test_bad_cams():
    with pytest.raises(linkage.LinkageError, match="one turn"):
        DiscCam(Program(0.0, [Segment(1.0, 1.0, "cycloidal")]), 10.0)
    with pytest.raises(linkage.LinkageError, match="return to its start"):
        DiscCam(Program(0.0, [Segment(2 * math.pi, 1.0, "cycloidal")]), 10.0)
    with pytest.raises(linkage.LinkageError, match="base_radius"):
        DiscCam(rise_dwell(), -1.0)
    with pytest.raises(TypeError, match="Program"):
        DiscCam("rise", 10.0)


def test_one_leg_lift_for_the_cam_the_hexapod_and_the_example_scene():
    """Thesis 2's lift is one model: the cam's follower, the hexapod's feet (in m) and the
    example scene's cam (turned by a quarter turn, its mounting angle) all follow leg_lift."""
    from pathlib import Path

    from linkage import build, scene

    t = np.linspace(0.0, 2 * np.pi, 721)
    s = leg_lift(1.4).eval(t)[0]
    assert s.max() == pytest.approx(1.4) and s.min() == 0.0
    assert (s[(t > np.pi / 2 + 1e-9) & (t < 3 * np.pi / 2 - 1e-9)] == 0).all()  # stance half
    np.testing.assert_array_equal(leg_lift_cam().program.eval(t)[0], s)
    feet = {leg.lift.eval(t)[0].tobytes() for leg in linkage.catalog.hexapod_tripod().legs}
    assert len(feet) == 1
    np.testing.assert_allclose(leg_lift(0.0014).eval(t)[0] * 1e3, s, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(
        linkage.catalog.hexapod_tripod().legs[0].lift.eval(t)[0] * 1e3, s, atol=1e-15
    )
    example = Path(__file__).resolve().parent.parent / "examples" / "thesis2_leg_torque.toml"
    cam = build.build_cam(scene.load(example))
    turned = leg_lift(0.0014).eval((t - np.pi / 2) % (2 * np.pi))[0]
    np.testing.assert_allclose(cam.program.eval(t)[0], turned, atol=1e-15)
