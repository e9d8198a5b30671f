"""Mechanism: building by names, sweeping multi-loop chains, and its errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage
from linkage import _schema, build, scene
from linkage._mechanism import JOINT_KINDS


def slider_crank(r=2.0, rod=5.0):
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.crank("A", "O", radius=r)
    m.slider("S", "A", rod, "O", direction=(1, 0))
    return m


def test_slider_crank_closed_form():
    r, rod = 2.0, 5.0
    theta = np.linspace(0, 2 * np.pi, 361)
    w = 3.0
    s = slider_crank(r, rod).sweep(theta, omega=w, outputs=("velocity", "acceleration"))
    root = np.sqrt(rod**2 - (r * np.sin(theta)) ** 2)
    x = r * np.cos(theta) + root
    np.testing.assert_allclose(s.point[:, 0], x, atol=1e-13)
    np.testing.assert_allclose(s.point[:, 1], 0, atol=1e-13)
    xdot = -r * np.sin(theta) * w - r**2 * np.sin(theta) * np.cos(theta) * w / root
    np.testing.assert_allclose(s.velocity[:, 0], xdot, atol=1e-12)


def test_slider_on_a_link_direction():
    # A line carried by the crank itself: the joint slides along O→A at distance rod from C.
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("C", (3, 0))
    m.crank("A", "O", radius=1.0)
    m.slider("S", "C", 4.0, "O", link=("O", "A"), reach="ahead")
    s = m.sweep(np.linspace(0, 2 * np.pi, 100))
    d = np.linalg.norm(s.joint("S") - s.joint("C"), axis=1)
    np.testing.assert_allclose(d, 4.0, atol=1e-13)
    u = s.joint("A") / np.linalg.norm(s.joint("A"), axis=1)[:, None]
    cross = u[:, 0] * s.joint("S")[:, 1] - u[:, 1] * s.joint("S")[:, 0]
    np.testing.assert_allclose(cross, 0, atol=1e-13)


def test_peaucellier_exact_line():
    m = linkage.catalog.peaucellier()
    theta = np.linspace(-2, 2, 4001)
    s = m.sweep(theta)
    lim = 2 * math.acos(2 / 3)  # 20 ≤ |DA| = 30|cos(θ/2)|
    np.testing.assert_array_equal(s.valid, np.abs(theta) <= lim)
    dev = np.abs(s.point[s.valid, 0] - 40.0).max()
    assert dev < 1e-12, dev
    assert np.ptp(s.point[s.valid, 1]) > 80


def test_hart_exact_line():
    s = linkage.catalog.hart().sweep(np.linspace(-np.pi, np.pi, 4001))
    assert s.valid.sum() > 500
    assert np.abs(s.point[s.valid, 0] - 7.5).max() < 1e-12
    assert s.trace == "P"


def test_pantograph_doubles_the_foot_path():
    m = linkage.catalog.hoecken_pantograph(2.0)
    s = m.sweep(np.linspace(0, 2 * np.pi, 721))
    q = s.joint("Q")
    np.testing.assert_allclose(s.point, q + 2 * (s.joint("T") - q), atol=1e-11)
    foot = linkage.catalog.hoecken().sweep(np.linspace(0, 2 * np.pi, 721)).point
    np.testing.assert_allclose(s.joint("T"), foot, atol=1e-12)
    with pytest.raises(linkage.LinkageError, match="scale"):
        linkage.catalog.hoecken_pantograph(0.5)


def test_fourbar_mechanism_equals_fourbar_sweep(hoecken):
    theta = np.linspace(0, 2 * np.pi, 37)
    np.testing.assert_array_equal(
        hoecken.mechanism().sweep(theta).joints, hoecken.sweep(theta).joints
    )


def test_named_builder_errors():
    m = linkage.Mechanism()
    with pytest.raises(linkage.LinkageError, match="no joints"):
        m.sweep(0.0)
    m.fixed("O", (0, 0))
    with pytest.raises(linkage.LinkageError, match="already defined"):
        m.fixed("O", (1, 0))
    with pytest.raises(
        linkage.LinkageError, match=r"centre: unknown joint 'X' \(defined so far: O\)"
    ):
        m.crank("A", "X", radius=1)
    with pytest.raises(linkage.LinkageError, match="radius must be a positive finite length"):
        m.crank("A", "O", radius=-1)
    with pytest.raises(TypeError, match="joint name"):
        m.fixed(3, (0, 0))
    m.crank("A", "O", radius=1)
    with pytest.raises(linkage.LinkageError, match=r"joint 'A2': .*second crank"):
        m.crank("A2", "O", radius=1)
    with pytest.raises(linkage.LinkageError, match="side must be one of"):
        m.dyad("B", "A", "O", 1, 1, side="up")
    with pytest.raises(linkage.LinkageError, match="exactly one of direction"):
        m.slider("S", "A", 1.0, "O")
    with pytest.raises(linkage.LinkageError, match=r"joint 'B': .*coincide"):
        m.dyad("B", "A", "A", 1, 1)
    with pytest.raises(linkage.LinkageError, match="on must be a pair"):
        m.point("P", on="A", at=(1, 0))
    # A failed add leaves the mechanism unchanged.
    assert m.joint_names == ("O", "A")


def test_mechanism_without_crank_cannot_sweep():
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    with pytest.raises(linkage.LinkageError, match="no crank"):
        m.sweep(0.0)


def test_capacity_limit_is_an_error():
    m = linkage.Mechanism()
    for i in range(linkage._core.CAPACITY):
        m.fixed(f"J{i}", (i, 0))
    with pytest.raises(linkage.LinkageError, match="at most 64 joints"):
        m.fixed("extra", (0, 0))


def test_trace_selection():
    m = linkage.catalog.peaucellier()
    m.trace = "B"
    s = m.sweep([0.0])
    np.testing.assert_array_equal(s.point, s.joint("B"))
    with pytest.raises(linkage.LinkageError, match="unknown joint"):
        m.trace = "Z"
    with pytest.raises(KeyError, match="no joint 'Z'"):
        s.joint("Z")


def slider_on_link():
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("C", (3, 0))
    m.crank("A", "O", radius=1.0)
    m.slider("S", "C", 4.0, "O", link=("O", "A"), angle=0.3, reach="ahead")
    m.point("P", on=("C", "S"), at=(2.0, 0.5))
    return m


def d_dtheta(f, h):
    """Five-point central difference along axis 0 (error ~ h⁴/30 · f⁽⁵⁾); drops 2 rows each end."""
    return (-f[4:] + 8 * f[3:-1] - 8 * f[1:-3] + f[:-4]) / (12 * h)


@pytest.mark.parametrize(
    "build, lo, hi",
    [
        (linkage.catalog.peaucellier, -1.5, 1.5),
        (linkage.catalog.hart, 0.4, 1.0),
        (linkage.catalog.hoecken_pantograph, 0.0, 6.2),
        (slider_on_link, 0.0, 6.2),
    ],
)
def test_multi_loop_rates_match_central_differences(build, lo, hi):
    m = build()
    theta = np.linspace(lo, hi, 8001)
    # A varying crank speed exercises the alpha terms too.
    omega, alpha = 1.7 + 0.3 * np.sin(theta), 0.3 * np.cos(theta)
    s = m.sweep(theta, omega=omega, alpha=alpha, outputs=("velocity", "acceleration"))
    assert s.valid.all()
    h = theta[1] - theta[0]
    unit = m.sweep(theta, omega=1.0, outputs=("velocity",)).joint_velocities
    dp, d2p = d_dtheta(s.joints, h), d_dtheta(unit, h)
    w, a = omega[2:-2, None, None], alpha[2:-2, None, None]
    scale = np.abs(unit).max() + np.abs(d2p).max()
    np.testing.assert_allclose(s.joint_velocities[2:-2], dp * w, rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(
        s.joint_accelerations[2:-2], d2p * w**2 + dp * a, rtol=0, atol=1e-7 * scale
    )


def test_jansen_leg():
    """Theo Jansen's holy numbers: a full-turn crank, one degree of freedom, and the foot's
    flat-bottomed path (measured 67.9 × 22.5 in his units)."""
    m = linkage.catalog.jansen()
    assert m.mobility().degrees_of_freedom == 1
    s = m.sweep(np.linspace(0, 2 * np.pi, 721))
    assert s.valid.all()
    width, height = np.ptp(s.point, axis=0)
    assert 60 < width < 75 and 18 < height < 26
    part = linkage.straightness(s.point[:-1], 0.5, closed=True)
    assert part is not None and part.length > 30


def test_one_registry_of_joint_kinds() -> None:
    """The schema, the builder and the build's error blame read one table of joint kinds."""
    assert scene.JOINT_KINDS is JOINT_KINDS and _schema.JOINT_KINDS is JOINT_KINDS
    assert build.JOINT_KINDS is JOINT_KINDS
    for kind, k in JOINT_KINDS.items():
        assert k.blame in k.required, kind
        assert not set(k.required) & set(k.optional), kind
    with pytest.raises(linkage.LinkageError, match=r"\(fixed, crank, dyad, slider, point\)"):
        linkage.Mechanism().add_joint({"kind": "gear", "name": "G"})


def test_constructions_are_the_program_as_values() -> None:
    """The extension describes each joint's construction by kind and fields (not Debug text)."""
    m = slider_on_link()
    m.fixed("G", (0, -5))
    m.slider("B", "A", 30, "G", direction=(2, 0), reach="behind")
    m.dyad("D", "A", "C", 2.0, 3.0, side="right")
    assert m._core.constructions() == [
        {"kind": "fixed", "at": (0.0, 0.0)},
        {"kind": "fixed", "at": (3.0, 0.0)},
        {"kind": "crank", "centre": 0, "radius": 1.0, "phase": 0.0},
        {
            "kind": "slider",
            "pivot": 1,
            "r": 4.0,
            "origin": 0,
            "direction": ("link", 0, 2, 0.3),
            "reach": "ahead",
        },
        {"kind": "point", "from": 1, "to": 3, "along": 2.0, "left": 0.5},
        {"kind": "fixed", "at": (0.0, -5.0)},
        # A fixed direction is stored as a unit vector.
        {
            "kind": "slider",
            "pivot": 2,
            "r": 30.0,
            "origin": 5,
            "direction": ("fixed", 1.0, 0.0),
            "reach": "behind",
        },
        {"kind": "dyad", "p1": 2, "p2": 1, "r1": 2.0, "r2": 3.0, "side": "right"},
    ]


def test_line_directions_are_the_carrying_link_turned() -> None:
    """The core's slider line directions over a sweep, against the crank angle + 0.3 by arctan2;
    NaN where the sweep did not assemble; bad joints and shapes are LinkageErrors."""
    m = slider_on_link()
    m.slider("T", "C", 2.5, "O", link=("O", "A"), angle=1.1, reach="ahead")  # fails in places
    s = m.sweep(np.linspace(0, 2 * np.pi, 181))
    assert 0 < s.valid.sum() < len(s.valid)
    a = s.joint("A") - s.joint("O")
    for joint, turn in ((3, 0.3), (5, 1.1)):
        u = m._core.line_directions(joint, s.joints)
        assert u.shape == (181, 2) and u.dtype == np.float64
        phi = np.arctan2(a[:, 1], a[:, 0]) + turn
        np.testing.assert_allclose(u, np.c_[np.cos(phi), np.sin(phi)], rtol=0, atol=1e-15)
        assert np.array_equal(np.isnan(u).any(axis=1), np.isnan(a).any(axis=1))
    assert m._core.line_directions(3, s.joints[:0]).shape == (0, 2)
    with pytest.raises(linkage.LinkageError, match="joint 2 is not a slider"):
        m._core.line_directions(2, s.joints)
    with pytest.raises(linkage.LinkageError, match="joint 99 is not a slider"):
        m._core.line_directions(99, s.joints)
    with pytest.raises(linkage.LinkageError, match="joint must be ≥ 0"):
        m._core.line_directions(-1, s.joints)
    with pytest.raises(linkage.LinkageError, match=r"shape \(n, 6, 2\)"):
        m._core.line_directions(3, s.joints[:, :5].copy())


def test_rate_margin_is_the_cores() -> None:
    """One rate margin, the core's ``32·√ε`` (2⁻²¹ for float64), read by ``Sweep.regular``."""
    from linkage import _sweep

    assert linkage._core.RATE_MARGIN == 32 * math.sqrt(np.finfo(np.float64).eps) == 2.0**-21
    assert _sweep.RATE_MARGIN is linkage._core.RATE_MARGIN


def test_the_rest_of_a_sweep_is_computed_from_unchanged_inputs_or_refused() -> None:
    """Every joint, the flags and the directions of centres at infinity of a sweep that did not
    ask for them are computed on first use by sweeping the caller's arrays again: with them
    unchanged, the same bits as asking at once; changed since, a LinkageError naming what came
    out different, never a silent overwrite of what was already returned."""
    fb = linkage.catalog.hoecken()
    pairs = [("ground", "coupler"), ("crank", "rocker")]
    theta = np.linspace(0.1, 6.0, 50)
    at_once = fb.sweep(theta, omega=1.0, outputs=("joints", "velocity", "instant_centres"))
    s = fb.sweep(theta.copy(), omega=1.0, outputs=("point", "velocity"))
    np.testing.assert_array_equal(s.joints, at_once.joints)
    np.testing.assert_array_equal(s.margin, at_once.margin)
    s = fb.sweep(theta.copy(), outputs=("instant_centres",), pairs=pairs)
    np.testing.assert_array_equal(
        s.instant_centre_directions[:, 0],
        at_once.instant_centre_directions[:, at_once.link_pairs.index(pairs[0])],
    )
    # The caller reuses its buffers before the first use.
    mine = theta.copy()
    s = fb.sweep(mine, outputs=("instant_centres",), pairs=pairs)
    centres = s.instant_centres.copy()
    mine += 1.0
    with pytest.raises(linkage.LinkageError, match="joints came out different"):
        s.instant_centre_at_infinity  # noqa: B018
    np.testing.assert_array_equal(s.instant_centres, centres)
    w = np.ones(50)
    s = fb.sweep(theta, omega=w, outputs=("point", "velocity"))
    velocity = s.velocity.copy()
    w *= 3.0
    with pytest.raises(linkage.LinkageError, match="velocity came out different"):
        s.joints  # noqa: B018
    np.testing.assert_array_equal(s.velocity, velocity)


def test_a_scalar_time_gives_one_sample_without_a_sample_axis() -> None:
    from linkage.drive import ConstantSpeed

    fb = linkage.catalog.hoecken()
    drive = ConstantSpeed(omega=1.0)
    one = fb.sweep(time=0.3, drive=drive, outputs=("point", "instant_centres"))
    many = fb.sweep(time=[0.3], drive=drive, outputs=("point", "instant_centres"))
    assert one.point.shape == (2,) and one.instant_centres.shape == (6, 2)
    assert one.time is not None and one.time.shape == () and float(one.time) == 0.3
    np.testing.assert_array_equal(one.point, many.point[0])
