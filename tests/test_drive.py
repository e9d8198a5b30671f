"""Motion laws, programs, gear trains, time-domain sweeps and the crank-speed schedule."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage
from linkage.drive import (
    LAWS,
    ConstantSpeed,
    Geared,
    GearTrain,
    Program,
    Segment,
    crank_schedule,
    motion_law,
)

u = np.linspace(0, 1, 200001)


@pytest.mark.parametrize("law", LAWS)
def test_boundary_values(law):
    s, _v, _a, _j = motion_law(law, [0.0, 1.0])
    assert s[0] == pytest.approx(0, abs=1e-15) and s[1] == pytest.approx(1, abs=1e-12)


# Textbook peaks (Norton, Design of Machinery ch. 8): |v|, |a| in units of L/β, L/β².
PEAKS = {
    "constant-velocity": (1.0, 0.0),
    "constant-acceleration": (2.0, 4.0),
    "simple-harmonic": (math.pi / 2, math.pi**2 / 2),
    "cycloidal": (2.0, 2 * math.pi),
    "3-4-5": (15 / 8, 10 / math.sqrt(3)),
    "4-5-6-7": (35 / 16, 7.5132),
    "modified-trapezoid": (2.0, 4.8881),
}


@pytest.mark.parametrize("law", LAWS)
def test_peaks_against_textbook(law):
    _s, v, a, _j = motion_law(law, u)
    pv, pa = PEAKS[law]
    assert np.abs(v).max() == pytest.approx(pv, rel=1e-4)
    assert np.abs(a).max() == pytest.approx(pa, rel=1e-4, abs=1e-12)


# Continuity class of a rise between dwells: the highest derivative that is continuous
# everywhere (0 = only displacement).
CLASS = {
    "constant-velocity": 0,
    "constant-acceleration": 1,
    "simple-harmonic": 1,
    "cycloidal": 2,
    "3-4-5": 2,
    "4-5-6-7": 3,
    "modified-trapezoid": 2,
}


@pytest.mark.parametrize("law", LAWS)
def test_continuity_class_in_a_rise_dwell_return_dwell(law):
    prog = Program(
        0.0, [Segment(1.0, 1.0, law), Segment(0.5), Segment(1.0, -1.0, law), Segment(0.5)]
    )
    jumps = prog.discontinuities(1e-9)
    lowest_jump = min((order for _, order, _ in jumps), default=4)
    # Inside the rise: a jump of the next derivative between neighbouring samples.
    vals = np.stack(motion_law(law, u))
    inner = [k for k in range(1, 4) if np.abs(np.diff(vals[k])).max() > 1e-2]
    lowest_inner = min(inner, default=4)
    assert min(lowest_jump, lowest_inner) - 1 == CLASS[law], (jumps[:3], inner)


def test_thesis_one_drive_peaks_at_337_5_deg_per_s():
    p = Program(math.radians(91), [Segment(1.0, math.pi, "3-4-5"), Segment(1.0, math.pi, "3-4-5")])
    t = np.linspace(0, 2, 40001)
    th, w, _a = p.angles(t)
    assert math.degrees(w.max()) == pytest.approx(337.5, rel=1e-9)
    assert math.degrees(th[-1]) == pytest.approx(451.0)
    assert p.discontinuities() == []


def test_gear_train_of_thesis_one():
    train = GearTrain.simple([18, 15, 14])
    assert train.ratio == pytest.approx(9 / 7) and train.sign == 1
    assert train.output_speed(50.0) == pytest.approx(64.2857142857, rel=1e-10)
    assert GearTrain.compound([(12, 36), (10, 40)]).ratio == pytest.approx(1 / 12)
    with pytest.raises(linkage.LinkageError, match="positive"):
        GearTrain.simple([18, 0])
    with pytest.raises(TypeError):
        GearTrain.simple([18.5, 14])


def test_time_sweep_through_gear_train_matches_angle_sweep(hoecken):
    motor = ConstantSpeed(50 * 2 * math.pi / 60)
    drive = Geared(motor, GearTrain.simple([18, 15, 14]))
    t = np.linspace(0, 0.9, 301)
    s = hoecken.sweep(time=t, drive=drive, outputs=("velocity", "acceleration"))
    w = 64.2857142857142857 * 2 * math.pi / 60
    ref = hoecken.sweep(w * t, omega=w, outputs=("velocity", "acceleration"))
    np.testing.assert_allclose(s.velocity, ref.velocity, rtol=1e-12, atol=1e-9)
    np.testing.assert_array_equal(s.time, t)
    with pytest.raises(linkage.LinkageError, match="both time= and drive="):
        hoecken.sweep(time=t)
    with pytest.raises(linkage.LinkageError, match="either theta"):
        hoecken.sweep(t, time=t, drive=drive)


def test_time_sweep_with_motion_law_velocity_matches_finite_difference(hoecken):
    p = Program(math.radians(91), [Segment(1.0, math.pi, "3-4-5"), Segment(1.0, math.pi, "3-4-5")])
    t = np.linspace(0.0, 2.0, 20001)
    s = hoecken.sweep(time=t, drive=p, outputs=("velocity", "acceleration"))
    dt = t[1] - t[0]
    fd = (s.point[2:] - s.point[:-2]) / (2 * dt)
    np.testing.assert_allclose(s.velocity[1:-1], fd, atol=1e-3 * np.abs(s.velocity).max())
    # The source reports a peak foot speed of 262 mm/s (CAD) and 297.46 mm/s (its listing) for
    # this drive; ours (288.55 mm/s measured) lies between the two.
    assert 262 < np.linalg.norm(s.velocity, axis=1).max() < 297.46


def test_bad_programs():
    with pytest.raises(linkage.LinkageError, match="unknown motion law"):
        Segment(1.0, 1.0, "sinusoid")
    with pytest.raises(linkage.LinkageError, match="duration"):
        Segment(0.0, 1.0, "cycloidal")
    with pytest.raises(linkage.LinkageError, match="at least one segment"):
        Program(0.0, [])


def test_crank_schedule_holds_the_stance_speed(hoecken):
    sched = crank_schedule(hoecken, foot_speed=80.0, duty_factor=0.5, samples=720)
    # Stated: stance foot speed within 0.1 % of the target with a 720-entry table.
    assert sched.speed_ripple < 1e-3
    assert sched.theta.shape == sched.omega.shape == (720,)  # the table asked for
    assert sched.theta.dtype == np.float32 and sched.omega.dtype == np.float32
    # Independently: sweep the leg under the schedule and measure the stance foot speed.
    t = np.linspace(0, sched.period, 5001)
    th, w, _a = sched.angles(t)
    s = hoecken.sweep(th, omega=w, outputs=("velocity",))
    lo, hi = sched.stance_angles
    stance = (th >= lo) & (th <= hi)
    speed = np.abs(s.velocity[stance, 0])
    assert np.abs(speed / 80.0 - 1).max() < 2e-3
    # The crank turns once per period and never reverses.
    assert th[-1] - th[0] == pytest.approx(2 * math.pi, rel=1e-3)
    assert (w > 0).all()


def test_schedule_table_in_f32_agrees_with_f64(hoecken):
    sched = crank_schedule(hoecken, foot_speed=80.0, duty_factor=0.6)
    t = np.linspace(0, 3 * sched.period, 3001)
    a64, w64, _ = sched.angles(t)
    a32, w32, _ = sched.angles(t, single=True)
    # f32 rounding of θ up to ~4π·3: a few ulp of 40 rad ≈ 1e-5 rad.
    assert np.abs(a32 - a64).max() < 2e-5
    assert np.abs(w32 - w64).max() < 1e-4 * np.abs(w64).max()


def test_infeasible_schedule_is_a_clear_error(hoecken):
    with pytest.raises(linkage.LinkageError, match="crank to stop"):
        crank_schedule(hoecken, foot_speed=80.0, duty_factor=0.3)
    with pytest.raises(linkage.LinkageError, match="duty_factor"):
        crank_schedule(hoecken, foot_speed=80.0, duty_factor=1.2)
