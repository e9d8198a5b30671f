"""Kinetostatics from Python: the thesis 2 leg, power method, energy balance, a static case."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage
from linkage.forces import LinkMass, PointLoad, joint_forces

MASSES = {
    "crank": LinkMass(0.0036, (0.005, 0), 0.122432e-6),
    "coupler": LinkMass(0.0210, (0.0312566, 0), 2.17781e-6),
    "rocker": LinkMass(0.0060, (0.0125, 0), 0.774427e-6),
}


def trapezoid(y, x):
    """Trapezoid rule (numpy's own was renamed between versions)."""
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def leg():
    return linkage.FourBar(ground=0.020, crank=0.010, coupler=0.025, rocker=0.025, point=(0.050, 0))


def test_thesis_two_leg_torque():
    """docs/domain.md: 20 rpm clockwise, 0.5·9.81 N at the foot (along x, as the source's listing
    applies it), no gravity in the source's model."""
    theta = np.radians(np.arange(0, 360, 1.0))
    f = joint_forces(
        leg(),
        theta,
        omega=-20 * 2 * math.pi / 60,
        masses=MASSES,
        gravity=(0, 0),
        loads=[PointLoad("coupler", "P", (0.5 * 9.81, 0))],
    )
    assert f.valid.all()
    np.testing.assert_allclose(f.torque, f.power_torque, rtol=1e-10, atol=1e-14)
    # Measured figures (README): mean |T| 0.0734 N·m, peak 0.240 N·m.
    assert f.mean_abs_torque == pytest.approx(0.0734, abs=5e-4)
    assert f.peak_torque == pytest.approx(0.2403, abs=5e-4)
    # Newton for the whole leg: ground reactions + foot force = Σ m·a_G (no gravity here).
    s = leg().sweep(theta, omega=-20 * 2 * math.pi / 60, outputs=("acceleration",))
    acc, j = s.joint_accelerations, s.joints
    inertial = np.zeros((len(theta), 2))
    for (a, b), m in (
        ((0, 2), MASSES["crank"]),
        ((2, 3), MASSES["coupler"]),
        ((1, 3), MASSES["rocker"]),
    ):
        frac = m.centre[0] / np.linalg.norm(j[:, b] - j[:, a], axis=1)[:, None]
        inertial += m.mass * (acc[:, a] + frac * (acc[:, b] - acc[:, a]))
    total = f.reaction("O") + f.reaction("C") + np.array([0.5 * 9.81, 0.0])
    np.testing.assert_allclose(total, inertial, atol=1e-12)


def test_static_case_by_hand():
    par = linkage.FourBar(ground=3, crank=1, coupler=3, rocker=1, point=(1.5, 0))
    theta = np.array([0.3, 1.0, 2.2])
    massless = {k: LinkMass(0.0) for k in ("crank", "coupler", "rocker")}
    f = joint_forces(
        par,
        theta,
        omega=0.0,
        masses=massless,
        gravity=(0, 0),
        loads=[PointLoad("coupler", "P", (0.0, -7.0))],
    )
    np.testing.assert_allclose(f.torque, 7.0 * np.cos(theta), atol=1e-12)
    # Hanging weight instead of a load: a 2 kg coupler under gravity needs T = m g r cos θ.
    heavy = dict(massless, coupler=LinkMass(2.0, (1.5, 0.0), 0.1))
    f = joint_forces(par, theta, omega=0.0, masses=heavy, gravity=(0, -9.81))
    np.testing.assert_allclose(f.torque, 2.0 * 9.81 * np.cos(theta), atol=1e-12)


def test_work_equals_energy_change_minus_external_work():
    """Over 0.75 s of a 3-4-5 crank motion: ∫T·ω dt = ΔKE + ΔPE − ∫F·v dt (trapezoid rule on
    30 001 samples; agreement to 1e-5 of the driver's work)."""
    from linkage.drive import Program, Segment

    fb = leg()
    drive = Program(0.3, [Segment(1.0, math.pi, "3-4-5")])
    t = np.linspace(0.0, 0.75, 30001)
    load = (0.5 * 9.81, -2.0)
    f = joint_forces(
        fb,
        time=t,
        drive=drive,
        masses=MASSES,
        gravity=(0, -9.81),
        loads=[PointLoad("coupler", "P", load)],
    )
    th, w, al = drive.angles(t)
    s = fb.sweep(th, omega=w, alpha=al, outputs=("velocity",))
    work_driver = trapezoid(f.torque * w, t)
    p_ext = s.velocity @ np.array(load)
    work_ext = trapezoid(p_ext, t)

    def energy(k):
        j, v = s.joints[k], s.joint_velocities[k]
        e = 0.0
        for (a, b), m in (
            ((0, 2), MASSES["crank"]),
            ((2, 3), MASSES["coupler"]),
            ((1, 3), MASSES["rocker"]),
        ):
            u = (j[b] - j[a]) / np.linalg.norm(j[b] - j[a])
            g = j[a] + m.centre[0] * u
            dv = v[b] - v[a]
            d = j[b] - j[a]
            om = (d[0] * dv[1] - d[1] * dv[0]) / (d @ d)
            vg = v[a] + om * np.array([-(g - j[a])[1], (g - j[a])[0]])
            e += 0.5 * m.mass * vg @ vg + 0.5 * m.inertia * om**2 + m.mass * 9.81 * g[1]
        return e

    balance = energy(-1) - energy(0) - work_ext
    assert abs(work_driver - balance) < 1e-5 * abs(work_driver)


def test_missing_masses_are_an_error_not_zeros():
    with pytest.raises(linkage.LinkageError, match=r"masses missing for links \['rocker'\]"):
        joint_forces(leg(), [0.1], omega=1.0, masses={k: MASSES[k] for k in ("crank", "coupler")})
    with pytest.raises(linkage.LinkageError, match="unknown links"):
        joint_forces(leg(), [0.1], omega=1.0, masses=dict(MASSES, wheel=LinkMass(1.0)))
    with pytest.raises(linkage.LinkageError, match="mass must be non-negative"):
        LinkMass(-1.0)
    with pytest.raises(linkage.LinkageError, match="need crank angles and speeds"):
        joint_forces(leg(), [0.1], masses=MASSES)
    with pytest.raises(linkage.LinkageError, match="unknown joint"):
        joint_forces(
            leg(), [0.1], omega=1.0, masses=MASSES, loads=[PointLoad("coupler", "Q", (1, 0))]
        )


def test_multi_loop_forces_power_method_agrees():
    m = linkage.catalog.peaucellier()
    masses = {name: LinkMass(0.01, (5.0, 0.0), 1.0) for name in m.links[1:]}
    theta = np.linspace(-1.2, 1.2, 50)
    f = joint_forces(
        m,
        theta,
        omega=2.0,
        alpha=0.5,
        masses=masses,
        gravity=(0, -9.81),
        loads=[PointLoad("B-P", "P", (0.0, -1.0))],
    )
    assert f.valid.all()
    np.testing.assert_allclose(f.torque, f.power_torque, rtol=1e-9, atol=1e-9)


def test_forces_forces_the_deprecated_name_of_joint_forces_is_removed():
    # linkage.forces.forces was a deprecated alias (it shadowed its module's name): removed.
    assert not hasattr(linkage.forces, "forces")
    assert "forces" not in linkage.forces.__all__
