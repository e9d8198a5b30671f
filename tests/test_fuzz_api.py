"""Every public function and method of ``linkage`` fuzzed with hostile arguments: wrong types,
wrong shapes and dtypes, NaN, ±inf, subnormals, ±1e308, huge and negative integers, counts that
cannot be represented. Contract (issue 10): only ``LinkageError`` (a ``ValueError``),
``TypeError`` and ``MemoryError`` may escape — never a Rust panic (``PanicException``, a
``BaseException``), ``OverflowError``, ``IndexError``, ``ZeroDivisionError``, a plain
``ValueError`` from numpy, ``AttributeError`` or ``KeyError`` alone — and results at float
extremes are right (scale-invariant quantities do not change with the scale) or a clear error.

Sizes that could really allocate are kept small here; absurd sizes run in a child process under
an address-space limit (``test_memory_limits.py``). Examples per test: ``LINKAGE_FUZZ_EXAMPLES``
(CI default 100; ``make fuzz`` 4000), expensive calls a tenth of that.
"""

from __future__ import annotations

import math
import os
import sys
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import linkage
from linkage import catalog, geometry
from linkage.cam import DiscCam, leg_lift_cam
from linkage.drive import (
    ConstantSpeed,
    Geared,
    GearTrain,
    Program,
    Segment,
    crank_schedule,
    motion_law,
)
from linkage.forces import LinkMass, PointLoad, joint_forces
from linkage.gait_search import search_duty_factor
from linkage.walker import Leg, Walker, gait_phases

EXAMPLES = int(os.environ.get("LINKAGE_FUZZ_EXAMPLES", "100"))
FAST = settings(
    max_examples=EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
# Calls that sweep thousands of samples per example (schedules, searches, catalogue figures).
SLOW = settings(FAST, max_examples=max(5, EXAMPLES // 10))

DOCUMENTED = (linkage.LinkageError, TypeError, MemoryError)


def call(fn):
    """Run ``fn``; a documented exception gives None, anything else fails the test — including
    BaseExceptions such as a Rust ``PanicException``, which hypothesis would not shrink."""
    try:
        return fn()
    except DOCUMENTED:
        return None
    except (KeyboardInterrupt, SystemExit):  # pragma: no cover
        raise
    except BaseException as exc:
        raise AssertionError(
            f"undocumented {type(exc).__module__}.{type(exc).__name__}: {exc}"
        ) from exc


# -- hostile values ---------------------------------------------------------------------------
EXTREMES = [0.0, -0.0, 5e-324, -5e-324, 2.2e-308, 1e308, -1e308, 1.7976931348623157e308, 1e-300]
ANY_FLOAT = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True),
    st.sampled_from([*EXTREMES, math.nan, math.inf, -math.inf]),
)
HUGE = st.sampled_from([400, 330]).flatmap(
    lambda e: st.sampled_from([10**e, -(10**e), Fraction(10**e, 3)])
)  # drawn, not listed: a strategy holding 400-digit ints has a 30 kB repr
ODD = st.sampled_from(
    [
        None,
        True,
        False,
        "x",
        "",
        b"x",
        1j,
        object(),
        [],
        (),
        {},
        {"a": 1},
        Decimal("1.5"),
        Fraction(1, 3),
        2**63,
        -(2**63),
        2**64,
        np.float32("nan"),
        np.float16(65504),
        np.int64(-1),
        np.uint64(2**64 - 1),
        np.bool_(True),
        np.array([]),
        np.array(["a"]),
        [[1.0], [2.0, 3.0]],
        np.zeros((2, 2, 2)),
    ]
)
DTYPES = st.sampled_from(
    [np.float64, np.float32, np.float16, np.int8, np.int64, np.uint64, np.bool_, np.complex128]
)


def arrays(min_dims=0, max_dims=3, max_side=5):
    return DTYPES.flatmap(
        lambda dt: hnp.arrays(
            dtype=dt,
            shape=hnp.array_shapes(
                min_dims=min_dims, max_dims=max_dims, min_side=0, max_side=max_side
            ),
            elements=ANY_FLOAT if dt is np.float64 else None,
        )
    )


SCALAR = st.one_of(ANY_FLOAT, st.integers(-(2**70), 2**70), ODD, HUGE)
HOSTILE = st.one_of(SCALAR, arrays(0, 3), st.lists(ANY_FLOAT, max_size=4))
PAIR = st.one_of(st.tuples(SCALAR, SCALAR), st.tuples(ANY_FLOAT, ANY_FLOAT), HOSTILE)
POINTS = st.one_of(
    hnp.arrays(
        np.float64,
        hnp.array_shapes(min_dims=1, max_dims=3, max_side=6).map(lambda s: (*s[:-1], 2)),
        elements=ANY_FLOAT,
    ),
    HOSTILE,
)
# Counts: small ones that run, and ones that must be refused before anything is allocated.
COUNT = st.one_of(
    st.integers(-3, 2000),
    st.sampled_from([2**62, 2**63 - 1, 2**63, 2**64, 10**30, -(2**63)]),
    ANY_FLOAT,
    ODD,
)
NAME = st.one_of(st.text(max_size=6), ODD, st.sampled_from(["O", "A", "B", "C", "P", "ground"]))


def maybe(base, hostile):
    """Each argument either its sound value or a hostile one."""
    return st.one_of(st.just(base), hostile)


def args(**fields):
    return st.fixed_dictionaries(fields)


HOECKEN = catalog.hoecken()
QUAD = catalog.quadruped_hoecken()
MASSES = {"crank": LinkMass(1.0), "coupler": LinkMass(1.0), "rocker": LinkMass(1.0)}
OUTS = ("point", "joints", "velocity", "acceleration", "instant_centres", "curvature")


def sound_fourbar():
    """Four-bars that are sometimes sound, sometimes at the float extremes."""
    length = st.one_of(
        st.floats(1e-3, 1e3), st.sampled_from([5e-324, 1e-300, 1e300, 1e308, 1.7e308])
    )
    return st.builds(
        lambda g, r, c, k, px, py, asm: call(
            lambda: linkage.FourBar(
                ground=g, crank=r, coupler=c, rocker=k, point=(px, py), assembly=asm
            )
        ),
        length,
        length,
        length,
        length,
        ANY_FLOAT,
        ANY_FLOAT,
        st.sampled_from(["open", "crossed"]),
    ).filter(lambda fb: fb is not None)


def check_sweep(s, n):
    """A sweep result: one row per angle, NaN exactly where not valid, finite where valid."""
    valid, joints = np.atleast_1d(s.valid), s.joints.reshape(-1, *s.joints.shape[-2:])
    assert valid.dtype == np.bool_ and joints.shape[0] == n == np.size(s.theta)
    assert np.isnan(joints[~valid][..., -1, :]).all() or np.isnan(joints[~valid]).any()
    assert np.isfinite(joints[valid]).all()


# -- FourBar ----------------------------------------------------------------------------------
@FAST
@given(
    kw=args(
        ground=maybe(20, HOSTILE),
        crank=maybe(10, HOSTILE),
        coupler=maybe(25, HOSTILE),
        rocker=maybe(25, HOSTILE),
        point=maybe((50, 0), PAIR),
        assembly=maybe("open", NAME),
        o=maybe((0, 0), PAIR),
    ),
    use_c=st.booleans(),
    c=PAIR,
)
def test_fourbar_constructor(kw, use_c, c):
    if use_c:
        kw = {**kw, "c": c, "ground": None}
    fb = call(lambda: linkage.FourBar(**kw))
    if fb is None:
        return
    for p in (fb.ground, fb.crank, fb.coupler, fb.rocker):
        assert (math.isfinite(p) and p > 0) or not math.isfinite(fb.ground)
    assert fb.grashof() in (
        "crank-rocker",
        "double-crank",
        "rocker-crank",
        "double-rocker",
        "change-point",
        "triple-rocker",
    )
    repr(fb)
    ranges = call(fb.input_ranges)
    if ranges is not None:
        for lo, hi in ranges:
            assert math.isfinite(lo) and math.isfinite(hi) and lo <= hi
    call(fb.input_limits)
    call(fb.mechanism)


@FAST
@given(
    kw=args(
        crank=maybe(1.0, HOSTILE),
        coupler=maybe(3.0, HOSTILE),
        offset=maybe(0.5, HOSTILE),
        point=maybe((1.0, 0.5), PAIR),
        o=maybe((0, 0), PAIR),
        angle=maybe(0.3, HOSTILE),
        reach=maybe("ahead", NAME),
    ),
    theta=HOSTILE,
    n=maybe(17, COUNT),
)
def test_slider_crank(kw, theta, n):
    sc = call(lambda: linkage.SliderCrank(**kw))
    if sc is None:
        return
    assert sc.crank > 0 and sc.coupler > 0 and sc.reach in ("ahead", "behind")
    ranges = sc.input_ranges()
    assert len(ranges) <= 2 and all(lo <= hi for lo, hi in ranges)
    s = call(lambda: sc.sweep(theta))
    if s is not None:
        check_sweep(s, np.size(s.theta))
    mu = call(lambda: sc.transmission_angle(theta))
    if mu is not None:
        mu = np.asarray(mu)
        assert ((mu[np.isfinite(mu)] >= 0) & (mu[np.isfinite(mu)] <= math.pi / 2)).all()
    c = call(lambda: sc.circuit(n))
    if c is not None:
        assert c.point.shape == (n, 2)


@FAST
@given(fb=sound_fourbar(), theta=HOSTILE, omega=HOSTILE, alpha=HOSTILE, outputs=maybe(OUTS, NAME))
def test_fourbar_sweeps(fb, theta, omega, alpha, outputs):
    s = call(lambda: fb.sweep(theta, omega=omega, alpha=alpha, outputs=outputs))
    if s is not None:
        check_sweep(s, np.size(s.theta))
    mu = call(lambda: fb.transmission_angle(theta))
    if mu is not None:
        mu = np.asarray(mu)
        assert ((mu[np.isfinite(mu)] >= 0) & (mu[np.isfinite(mu)] <= math.pi)).all()
    call(lambda: fb.sweep([0.0, 1.0], omega=1.0, outputs=OUTS))
    call(lambda: fb.circuit(17))


@FAST
@given(
    kw=args(
        theta0=maybe(0.0, HOSTILE),
        dtheta=maybe(0.1, HOSTILE),
        n=maybe(10, COUNT),
        mode=maybe("table", NAME),
        block=maybe(64, COUNT),
        threads=maybe(
            1,
            st.one_of(
                st.integers(-2, 4),
                COUNT.filter(lambda v: not (isinstance(v, int) and 4 < v < 2**63)),
            ),
        ),
        out=maybe(None, HOSTILE),
    )
)
@example(kw=dict(theta0=0.0, dtheta=0.1, n=2**62, mode="table", block=64, threads=1, out=None))
def test_fourbar_uniform_sweep(kw):
    pts = call(lambda: HOECKEN.uniform_sweep(**kw))
    if pts is not None:
        assert pts.shape == (kw["n"], 2) and pts.dtype == np.float64


@FAST
@given(n=COUNT, fb=st.sampled_from([HOECKEN, catalog.evans_b(), catalog.watt()]))
@example(n=2**62, fb=HOECKEN)  # awaits A (D2): capacity-overflow panic today
def test_fourbar_circuit(n, fb):
    s = call(lambda: fb.circuit(n))
    if s is not None:
        assert len(s) == n
        check_sweep(s, n)
        assert ((s.margin[s.valid] >= 0) & (s.margin[s.valid] <= 1 + 1e-12)).all()


# -- Mechanism and Sweep ----------------------------------------------------------------------
@FAST
@given(
    kw=args(
        at=maybe((0, 0), PAIR),
        radius=maybe(10, HOSTILE),
        phase=maybe(0.0, HOSTILE),
        r1=maybe(25, HOSTILE),
        r2=maybe(25, HOSTILE),
        side=maybe("left", NAME),
        on=maybe(("A", "B"), st.one_of(NAME, st.tuples(NAME, NAME))),
        along=maybe((50, 0), PAIR),
        r=maybe(100.0, HOSTILE),
        direction=maybe((0, 1), PAIR),
        reach=maybe("ahead", NAME),
        link=maybe(("A", "B"), st.one_of(NAME, st.tuples(NAME, NAME))),
        angle=maybe(0.3, HOSTILE),
        name=maybe("S", NAME),
        trace=maybe("P", NAME),
    ),
    theta=maybe([0.0, 1.0], HOSTILE),
)
def test_mechanism_builder(kw, theta):
    m = linkage.Mechanism()
    call(lambda: m.fixed("O", kw["at"]))
    call(lambda: m.fixed("C", (20, 0)))
    call(lambda: m.crank("A", "O", radius=kw["radius"], phase=kw["phase"]))
    call(lambda: m.dyad("B", "A", "C", kw["r1"], kw["r2"], side=kw["side"]))
    call(lambda: m.point("P", on=kw["on"], at=kw["along"]))
    call(
        lambda: m.slider(
            kw["name"], "P", kw["r"], "O", direction=kw["direction"], reach=kw["reach"]
        )
    )
    call(lambda: m.slider("T", "B", kw["r"], "O", link=kw["link"], angle=kw["angle"]))
    call(lambda: setattr(m, "trace", kw["trace"]))
    repr(m)
    assert len(m) == len(m.joint_names)
    call(lambda: m.links)
    call(m.link_members)
    call(m.mobility)
    s = call(lambda: m.sweep(theta, omega=1.0, outputs=OUTS))
    if s is not None:
        check_sweep(s, np.size(s.theta))


@FAST
@given(
    threshold=HOSTILE,
    joint=NAME,
    a=NAME,
    b=NAME,
    theta=st.lists(st.floats(-10, 10), min_size=1, max_size=5),
)
def test_sweep_object(threshold, joint, a, b, theta):
    s = HOECKEN.sweep(theta, omega=1.0, outputs=OUTS)
    flags = call(lambda: s.near_toggle(threshold))
    if flags is not None:
        assert flags.shape == s.valid.shape and flags.dtype == np.bool_
    call(lambda: s.joint(joint))
    call(lambda: s.instant_centre(a, b))
    repr(s)
    assert np.isnan(s.curvature_radius[~s.valid]).all()


# -- geometry ---------------------------------------------------------------------------------
@FAST
@given(links=COUNT, lower=COUNT, higher=COUNT)
def test_mobility(links, lower, higher):
    m = call(lambda: geometry.mobility(links, lower, higher))
    if m is not None:
        dof = 3 * (int(links) - 1) - 2 * int(lower) - int(higher)
        assert m.degrees_of_freedom == dof


@FAST
@given(p=POINTS, v=POINTS, a=POINTS, step=COUNT, tol=HOSTILE, closed=HOSTILE)
def test_geometry_functions(p, v, a, step, tol, closed):
    res = call(lambda: geometry.curvature_centre(p, v, a))
    if res is not None:
        centre, kappa = res
        assert centre.shape == (*kappa.shape, 2)
    call(lambda: geometry.circumcentre(p, v, a))
    call(lambda: geometry.three_point_centres(p, step))
    part = call(lambda: geometry.straightness(p, tol, closed=closed, velocity=v))
    if part is not None:
        assert part.count >= 3 and part.max_deviation <= float(tol) + 1e-12 * abs(float(tol))
    call(lambda: geometry.foot_path(p, tol, velocity=v))


@FAST
@given(fb=st.one_of(sound_fourbar(), HOSTILE), theta=HOSTILE)
@example(
    fb=linkage.FourBar(ground=1.0, crank=2.2250738585072014e-308, coupler=1.0, rocker=1.0),
    theta=0.0,
)
def test_inflection_circle(fb, theta):
    inf = call(lambda: geometry.inflection_circle(fb, theta))
    if inf is not None:
        assert math.isfinite(inf.radius) and inf.radius >= 0


@FAST
@given(
    ground=maybe(20.0, HOSTILE),
    crank=maybe([10.0, 5.0], HOSTILE),
    coupler=maybe(25.0, HOSTILE),
    rocker=maybe(25.0, HOSTILE),
    point=maybe((50.0, 0.0), HOSTILE),
    theta=maybe(np.linspace(0, 6.3, 7), HOSTILE),
    assembly=maybe("open", st.one_of(NAME, HOSTILE)),
    threads=maybe(1, COUNT),
)
def test_batch_sweep_fourbars(ground, crank, coupler, rocker, point, theta, assembly, threads):
    out = call(
        lambda: linkage.batch.sweep_fourbars(
            ground, crank, coupler, rocker, point, theta, assembly=assembly, threads=threads
        )
    )
    if out is not None:
        pts, valid = out
        assert pts.shape[:-1] == valid.shape and pts.shape[-1] == 2
        assert np.isfinite(pts[valid]).all() and np.isnan(pts[~valid]).all()


# -- drives -----------------------------------------------------------------------------------
LAW = st.one_of(st.sampled_from(list(linkage.drive.LAWS)), NAME)


@FAST
@given(name=LAW, u=HOSTILE)
def test_motion_law(name, u):
    out = call(lambda: motion_law(name, u))
    if out is not None:
        assert all(np.isfinite(col).all() for col in out)


@FAST
@given(
    start=maybe(0.0, HOSTILE),
    segs=st.lists(
        st.tuples(maybe(1.0, HOSTILE), maybe(1.0, HOSTILE), st.one_of(st.none(), LAW)),
        min_size=0,
        max_size=3,
    ),
    t=HOSTILE,
    tol=maybe(1e-9, HOSTILE),
)
@example(start=0.0, segs=[(8.98846567431158e307, 1.0, None)] * 2, t=0.0, tol=1e-9)  # fsum overflow
def test_programs(start, segs, t, tol):
    segments = [
        s for s in (call(lambda d=d, r=r, law=law: Segment(d, r, law)) for d, r, law in segs) if s
    ]
    prog = call(lambda: Program(start, segments))
    if prog is None:
        return
    assert math.isfinite(prog.period) and prog.period > 0
    out = call(lambda: prog.eval(t))
    if out is not None:
        assert all(np.isfinite(col).all() for col in out)
    call(lambda: prog.angles(t))
    call(lambda: prog.discontinuities(tol))


@FAST
@given(omega=HOSTILE, theta0=HOSTILE, t=HOSTILE, ratio=HOSTILE, sign=HOSTILE, v=HOSTILE)
def test_constant_speed_and_gears(omega, theta0, t, ratio, sign, v):
    out = call(lambda: ConstantSpeed(omega, theta0).angles(t))
    if out is not None:
        assert all(np.isfinite(col).all() for col in out)
    train = call(lambda: GearTrain(ratio, sign))
    if train is not None:
        assert math.isfinite(train.ratio) and train.ratio > 0 and train.sign in (1, -1)
        w = call(lambda: train.output_speed(v))
        assert w is None or math.isfinite(w)
        repr(train)
        geared = call(lambda: Geared(ConstantSpeed(1.0), train).angles(t))
        if geared is not None:
            assert all(np.isfinite(col).all() for col in geared)


TEETH = st.one_of(
    st.integers(1, 200),
    st.integers(-(2**70), 2**70),
    st.sampled_from([2**31, 2**32, 2**53 + 1, 2**63 - 1, 2**63, 2**64, 10**30]),
    ODD,
)


@FAST
@given(
    teeth=st.lists(TEETH, max_size=5),
    stages=st.lists(st.one_of(st.tuples(TEETH, TEETH), HOSTILE), max_size=5),
)
@example(teeth=[1, 2**40], stages=[(1, 2**40)])  # awaits A (D4): OverflowError today
def test_gear_trains_hostile_teeth(teeth, stages):
    """Awaits A (rust-findings D4): huge tooth counts are OverflowError in the binding today, and
    a compound ratio underflows to 0."""
    train = call(lambda: GearTrain.simple(teeth))
    if train is not None:
        exact = Fraction(int(teeth[0]), int(teeth[-1]))
        assert train.ratio == pytest.approx(float(exact), rel=1e-12)
        assert train.sign == (-1) ** (len(teeth) - 1)
    train = call(lambda: GearTrain.compound(stages))
    if train is not None:
        exact = Fraction(1)
        for a, b in stages:
            exact *= Fraction(int(a), int(b))
        assert train.ratio == pytest.approx(float(exact), rel=1e-12)


def test_gear_train_ratio_out_of_float_range_is_an_error():
    """A compound train whose ratio is 1e-360 is not 0, and 1e360 is not inf: an error (today
    from ``GearTrain``'s own check of the ratio the core returns; see rust-findings D4)."""
    for stages in ([(1, 10**9)] * 40, [(10**9, 1)] * 40):
        with pytest.raises(linkage.LinkageError):
            GearTrain.compound(stages)


SCHED = crank_schedule(HOECKEN, 100.0, 0.6, samples=16, resolution=721)


@SLOW
@given(
    kw=args(
        leg=maybe(HOECKEN, st.one_of(HOSTILE, st.just(QUAD))),
        foot_speed=maybe(100.0, HOSTILE),
        duty_factor=maybe(0.6, HOSTILE),
        samples=maybe(16, COUNT.filter(lambda v: not (isinstance(v, int) and 300 < v < 2**62))),
        tol=maybe(None, HOSTILE),
        resolution=maybe(721, COUNT),
    )
)
def test_crank_schedule(kw):
    s = call(lambda: crank_schedule(**kw))
    if s is not None:
        assert np.isfinite(s.theta).all() and np.isfinite(s.omega).all() and (s.omega > 0).all()
        assert math.isfinite(s.period) and s.period > 0


@FAST
@given(t=HOSTILE, single=HOSTILE, k=st.integers(-1000, 1000))
def test_crank_schedule_hostile_times(t, single, k):
    out = call(lambda: SCHED.angles(t, single=single))
    if out is not None:
        assert all(np.isfinite(col).all() for col in out)
    # Periodic: k periods later, the angle is k turns on (while the float can tell).
    th0, w0, _ = SCHED.angles([0.3])
    th1, w1, _ = SCHED.angles([0.3 + k * SCHED.period])
    assert th1[0] - th0[0] == pytest.approx(2 * math.pi * k, abs=1e-6 * (1 + abs(k)))
    assert w1[0] == pytest.approx(w0[0], rel=1e-6)


# -- cams -------------------------------------------------------------------------------------
PROGRAMS = st.sampled_from(
    [
        leg_lift_cam().program,
        Program(0.0, [Segment(math.pi, 1.0, "cycloidal"), Segment(math.pi, -1.0, "3-4-5")]),
        Program(0.0, [Segment(1.0, 1.0, "cycloidal")]),
    ]
)


@FAST
@given(
    kw=args(
        program=maybe(leg_lift_cam().program, st.one_of(PROGRAMS, HOSTILE)),
        base_radius=maybe(6.5, HOSTILE),
        roller_radius=maybe(2.0, HOSTILE),
        offset=maybe(0.0, HOSTILE),
        pressure_limit=maybe(0.5, HOSTILE),
    ),
    n=maybe(30, COUNT.filter(lambda v: not (isinstance(v, int) and 5000 < v < 2**62))),
)
def test_disc_cams(kw, n):
    cam = call(lambda: DiscCam(**kw))
    if cam is None:
        return
    p = call(lambda: cam.profile(n))
    if p is not None:
        assert len(p.phi) == n and p.pitch.shape == (n, 2)
        call(p.check)
        assert isinstance(p.undercut, bool)
        call(lambda: p.max_pressure_angle)
    call(lambda: leg_lift_cam(kw["roller_radius"], kw["base_radius"]).profile(16))


# -- forces -----------------------------------------------------------------------------------
@FAST
@given(
    mass=maybe(1.0, HOSTILE),
    centre=maybe((0.0, 0.0), PAIR),
    inertia=maybe(0.0, HOSTILE),
    theta=maybe([0.0, 1.0], HOSTILE),
    omega=maybe(1.0, HOSTILE),
    alpha=maybe(0.0, HOSTILE),
    gravity=maybe((0.0, -9.81), PAIR),
    link=maybe("coupler", NAME),
    joint=maybe("P", NAME),
    force=maybe((1.0, 0.0), HOSTILE),
    torque=maybe(0.0, HOSTILE),
    masses=maybe(
        None,
        st.one_of(
            HOSTILE,
            st.dictionaries(
                st.one_of(st.text(max_size=6), st.sampled_from(["crank", "coupler", "rocker"])),
                st.one_of(HOSTILE, st.tuples(SCALAR, PAIR, SCALAR)),
                max_size=3,
            ),
        ),
    ),
)
def test_forces(
    mass, centre, inertia, theta, omega, alpha, gravity, link, joint, force, torque, masses
):
    lm = call(lambda: LinkMass(mass, centre, inertia))
    ms = dict(MASSES, crank=lm if lm is not None else (mass, centre, inertia))
    if masses is not None:
        ms = masses
    loads = [PointLoad(link, joint, force, torque)]
    f = call(
        lambda: joint_forces(HOECKEN, theta, omega, alpha, masses=ms, gravity=gravity, loads=loads)
    )
    if f is None:
        return
    assert f.torque.shape == f.valid.shape
    assert np.isnan(f.torque[~f.valid]).all() and np.isfinite(f.torque[f.valid]).all()
    m = f.mean_abs_torque
    assert math.isnan(m) if not f.valid.any() else math.isfinite(m)
    assert math.isnan(f.peak_torque) if not f.valid.any() else f.peak_torque >= m
    call(lambda: f.reaction(joint))


def test_forces_reaction_columns_are_structural():
    """Awaits A (D9): the reaction columns depend on the mechanism, not on which samples are
    valid."""
    ok = joint_forces(HOECKEN, [0.0, 1.0], 1.0, masses=MASSES)
    bad = joint_forces(HOECKEN, [0.0, 1.0], 1e308, masses=MASSES)
    empty = joint_forces(HOECKEN, [], 1.0, masses=MASSES)
    assert bad.reaction_links == ok.reaction_links == empty.reaction_links
    assert np.isnan(bad.reaction("B")).all() and bad.reaction("B").shape == (2, 2)


# -- walkers ----------------------------------------------------------------------------------
@FAST
@given(
    kw=args(
        name=maybe("A", NAME),
        linkage=maybe(HOECKEN, st.one_of(HOSTILE, st.just(catalog.peaucellier()))),
        mount=maybe((0.0, 0.0, 0.0), st.one_of(st.tuples(SCALAR, SCALAR, SCALAR), HOSTILE)),
        phase=maybe(0.0, HOSTILE),
        plane=maybe("sagittal", NAME),
        mirror=maybe(False, HOSTILE),
        foot_offset=maybe((0.0, -100.0), PAIR),
        lift=maybe(None, st.one_of(HOSTILE, PROGRAMS)),
        pad=maybe(10.0, HOSTILE),
    ),
    cg=maybe((0.0, 0.0), PAIR),
    ground_tol=maybe(None, HOSTILE),
    body_underside=maybe(None, HOSTILE),
    theta=maybe(np.linspace(0, 2 * np.pi, 9), HOSTILE),
    omega=maybe(1.0, HOSTILE),
)
def test_legs_and_walkers(kw, cg, ground_tol, body_underside, theta, omega):
    leg = call(lambda: Leg(**kw))
    legs = [leg, *QUAD.legs[1:]] if leg is not None and leg.name not in "BCD" else list(QUAD.legs)
    w = call(lambda: Walker(legs, cg, ground_tol, body_underside))
    if w is None:
        return
    sim = call(lambda: w.simulate(theta, omega))
    if sim is None:
        return
    assert sim.feet.shape == (len(sim.theta), len(legs), 3) and np.isfinite(sim.feet).all()
    down = sim.support_count > 0
    assert np.isfinite(sim.margin[down]).all() and (sim.margin[~down] == -np.inf).all()
    for prop in ("min_margin", "duty_factor", "pr_ratio", "stride", "lift_height", "slip_distance"):
        call(lambda prop=prop: getattr(sim, prop))
    call(sim.gait_diagram)
    call(lambda: sim.min_margin_at)


@FAST
@given(
    walker=maybe(QUAD, HOSTILE),
    phases=maybe([0.0, 1.0, 2.0, 3.0], st.one_of(HOSTILE, st.lists(SCALAR, max_size=5))),
    samples=COUNT.filter(lambda v: not (isinstance(v, int) and 200 < v < 2**62)),
    gait=st.one_of(st.sampled_from(["tripod", "wave", "ripple", "diagonal", "crawl"]), NAME),
    names=st.one_of(st.lists(NAME, max_size=6), HOSTILE),
)
def test_walker_methods(walker, phases, samples, gait, names):
    w = call(lambda: QUAD.with_phases(phases))
    if w is not None:
        assert np.isfinite(w.phases).all()
    h = call(lambda: QUAD.body_clearance(samples))
    assert h is None or math.isfinite(h)
    p = call(lambda: gait_phases(gait, names))
    if p is not None:
        assert np.isfinite(p).all()


@SLOW
@given(
    walker=maybe(QUAD, HOSTILE),
    objective=maybe("margin", NAME),
    step=maybe(math.pi / 2, HOSTILE),
    samples=maybe(16, COUNT.filter(lambda v: not (isinstance(v, int) and 64 < v < 2**62))),
    rounds=maybe(1, COUNT.filter(lambda v: not (isinstance(v, int) and 3 < v < 2**62))),
    max_evals=maybe(10, COUNT.filter(lambda v: not (isinstance(v, int) and 100 < v < 2**62))),
)
def test_search_phases(walker, objective, step, samples, rounds, max_evals):
    res = call(lambda: QUAD.search_phases(objective, step, samples, rounds, max_evals))
    if res is not None:
        phases, value = res
        assert np.isfinite(phases).all() and not math.isnan(value)
    # The function in linkage.gait_search, which the method calls, with any walker.
    res = call(
        lambda: linkage.gait_search.search_phases(
            walker, objective, step, samples, rounds, max_evals
        )
    )
    if res is not None:
        phases, value = res
        assert np.isfinite(phases).all() and not math.isnan(value)


@SLOW
@given(
    walker=maybe(QUAD, HOSTILE),
    foot_speed=maybe(100.0, HOSTILE),
    objective=maybe("margin", NAME),
    duty=maybe((0.6,), st.one_of(HOSTILE, st.lists(SCALAR, max_size=2))),
    samples=maybe(31, COUNT.filter(lambda v: not (isinstance(v, int) and 200 < v < 2**62))),
)
def test_search_duty_factor(walker, foot_speed, objective, duty, samples):
    res = call(lambda: search_duty_factor(walker, foot_speed, objective, duty, samples))
    if res is not None:
        assert 0 < res[0] < 1


# -- catalogue --------------------------------------------------------------------------------
@FAST
@given(name=st.one_of(st.sampled_from(catalog.names()), NAME), scale=HOSTILE)
@example(name="watt", scale=1e308)  # awaits A (D1): unreachable!() panic today
def test_catalogue_constructors_at_any_scale(name, scale):
    """Awaits A (D1) for huge scales: the pantograph panics at scale 1e308 today."""
    item = call(lambda: catalog.get(name))
    if item is not None:
        check_sweep(item.sweep([0.0, 1.0]), 2)
    m = call(lambda: catalog.hoecken_pantograph(scale))
    if m is not None:
        s = m.sweep([0.0, 1.0, 2.0])
        check_sweep(s, 3)


@SLOW
@given(
    rel_tol=maybe(1e-3, HOSTILE),
    samples=COUNT.filter(lambda v: not (isinstance(v, int) and 400 < v < 2**62)),
)
def test_catalogue_figures(rel_tol, samples):
    rows = call(lambda: catalog.figures(rel_tol, samples))
    if rows is not None:
        assert len(rows) == len(catalog.names())


@FAST
@given(
    theta=HOSTILE,
    threads=st.one_of(st.integers(-2, 4), ODD),
    which=st.lists(st.sampled_from(["hoecken", "jansen", "x"]), max_size=3),
)
def test_batch_sweep_mechanisms(theta, threads, which):
    made = {"hoecken": HOECKEN.mechanism(), "jansen": catalog.jansen(), "x": "x"}
    ms = [made[w] for w in which]
    r = call(lambda: linkage.batch.sweep_mechanisms(ms, theta, threads))
    if r is not None:
        joints, valid = r
        assert joints.shape[:2] == valid.shape and joints.shape[-1] == 2
        assert np.isfinite(joints[valid]).all()


# -- synthesis --------------------------------------------------------------------------------
SMALL_ATLAS = linkage.synthesis.Atlas.build(600, threads=1)
# Open targets search an arc atlas (without one, path builds the default into the cache).
SMALL_ARCS = linkage.synthesis.Atlas.build(600, kind="fourbar-arcs", threads=1)
TARGET = np.c_[np.cos(np.linspace(0, 6, 12)), 0.5 * np.sin(np.linspace(0, 6, 12))]


@SLOW
@given(
    points=st.one_of(st.just(TARGET), POINTS),
    closed=maybe(True, HOSTILE),
    top=maybe(2, COUNT),
    refine=maybe(1, st.integers(-2, 3)),
    lengths=st.one_of(st.none(), PAIR),
    pivots=st.one_of(st.none(), st.tuples(PAIR, PAIR), HOSTILE),
    tol=maybe(1e-3, HOSTILE),
    threads=st.one_of(st.none(), st.integers(-2, 3), ODD),
)
def test_synthesis_path(points, closed, top, refine, lengths, pivots, tol, threads):
    found = call(
        lambda: linkage.synthesis.path(
            points,
            closed=closed,
            top=top,
            atlas=[SMALL_ATLAS, SMALL_ARCS],
            refine=refine,
            global_search=False,
            lengths=lengths,
            pivots=pivots,
            tol=tol,
            threads=threads,
        )
    )
    for c in found or []:
        assert math.isfinite(c.error) and c.error >= 0 and c.rms <= c.error
        assert np.all(np.isfinite(c.linkage.circuit(64).point))


@FAST
@given(entries=COUNT, harmonics=COUNT, samples=COUNT, threads=st.one_of(st.none(), COUNT))
def test_synthesis_atlas_build(entries, harmonics, samples, threads):
    small = (
        isinstance(entries, int)
        and isinstance(harmonics, int)
        and isinstance(samples, int)
        and entries * max(harmonics, 1) * max(samples, 1) <= 10**6
    )
    assume(small or not all(isinstance(v, int) and v > 0 for v in (entries, harmonics, samples)))
    at = call(lambda: linkage.synthesis.Atlas.build(entries, harmonics, samples, threads))
    if at is not None:
        assert len(at) == entries and np.all(np.isfinite(at.descriptors))
        hits = call(lambda: at.nearest(at.descriptors[:1], 1))
        assert hits is None or int(hits[0][0]) == 0


# Random pose angles beyond 2π draw motion()'s degrees hint, which is for users, not a failure.
@pytest.mark.filterwarnings("ignore:poses.*pose angles exceed 2π:UserWarning")
@FAST
@given(poses=st.one_of(POINTS, HOSTILE), n=COUNT, beta=st.one_of(st.none(), HOSTILE))
def test_synthesis_motion(poses, n, beta):
    for c in call(lambda: linkage.synthesis.motion(poses, n=n, beta=beta)) or []:
        assert isinstance(c.reaches, bool)
    call(lambda: linkage.synthesis.centre_point_curve(poses, n))


@FAST
@given(x_range=PAIR, phi_range=PAIR, psi_range=PAIR, points=st.one_of(COUNT, HOSTILE), spacing=NAME)
def test_synthesis_function(x_range, phi_range, psi_range, points, spacing):
    r = call(lambda: linkage.synthesis.function(math.sqrt, x_range, phi_range, psi_range, points))
    if r is not None:
        assert isinstance(r.linkage, linkage.FourBar)
    call(lambda: linkage.synthesis.chebyshev_points(x_range, phi_range, points))


def test_every_public_name_is_exercised():
    """The lists above cover the public API: a new public name must be added to this suite."""
    covered = {
        "OUTPUTS", "AssemblyError", "FourBar", "batch", "Leg", "LinkageError", "Mechanism", "Sweep",
        "SliderCrank",
        "Walker", "cam", "catalog", "circumcentre", "curvature_centre", "drive",
        "foot_path", "gait_phases", "gait_search", "forces", "geometry", "inflection_circle",
        "mobility", "search_duty_factor",
        "straightness", "synthesis", "three_point_centres", "walker", "__version__",
        # Literal types, not callables: held equal to the core's choices by test_choices.py.
        "Assembly", "Output", "Reach", "Side",
    }  # fmt: skip
    assert set(linkage.__all__) <= covered, set(linkage.__all__) - covered


# -- results at float extremes ----------------------------------------------------------------
FOURBARS = [
    dict(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0)),  # Hoecken, crank-rocker
    dict(ground=23.05, crank=10, coupler=12, rocker=11.67, point=(15, 0)),  # Evans B, limited
    dict(ground=1.5, crank=1.0, coupler=0.9, rocker=1.2, point=(0.5, 0.3)),  # triple rocker
    dict(ground=10, crank=4, coupler=10, rocker=4, point=(2, 1)),  # parallelogram
]
SCALES = st.one_of(
    st.sampled_from([1e-300, 1e-200, 1e-100, 1e100, 1e200, 1e300, 1e306]),
    st.floats(-300, 305).map(lambda e: 10.0**e),
)


@FAST
@given(which=st.sampled_from(range(len(FOURBARS))), s=SCALES)
@example(which=2, s=1e-300)  # awaits A (D5): input ranges (0, 0)
@example(which=0, s=1e-100)  # awaits A (D6): uniform_sweep rows (20, 0)
def test_fourbar_scale_invariance(which, s):
    """Awaits A (D5, D6, D7): every result of a four-bar scales with its lengths — angles and
    classes do not change at all; positions and velocities scale by ``s``. Today the input
    ranges, rates, transmission angles and ``uniform_sweep`` go NaN or 0 at scales 1e±300."""
    base_kw = FOURBARS[which]
    kw = {
        k: (tuple(s * x for x in v) if isinstance(v, tuple) else s * v) for k, v in base_kw.items()
    }
    base = linkage.FourBar(**base_kw)
    fb = linkage.FourBar(**kw)  # every length here is finite at every scale drawn
    assert fb.grashof() == base.grashof()
    r0, r1 = base.input_ranges(), fb.input_ranges()
    assert len(r0) == len(r1)
    for (a0, b0), (a1, b1) in zip(r0, r1):
        assert a1 == pytest.approx(a0, abs=1e-9) and b1 == pytest.approx(b0, abs=1e-9)
    theta = np.linspace(-3, 3, 13)
    s0 = base.sweep(theta, omega=1.0, outputs=("point", "velocity", "acceleration"))
    s1 = fb.sweep(theta, omega=1.0, outputs=("point", "velocity", "acceleration"))
    sure = s0.valid & (s0.margin > 1e-6)
    assert (s1.valid[sure]).all()
    np.testing.assert_allclose(s1.point[sure] / s, s0.point[sure], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(s1.velocity[sure] / s, s0.velocity[sure], rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(
        s1.acceleration[sure] / s, s0.acceleration[sure], rtol=1e-6, atol=1e-6
    )
    np.testing.assert_allclose(
        fb.transmission_angle(theta[sure]), base.transmission_angle(theta[sure]), atol=1e-9
    )
    if base.input_limits() is None:
        try:
            u0 = base.uniform_sweep(0.0, 0.1, 32)
        except linkage.LinkageError:
            # A change-point linkage (the parallelogram) flattens on this path: the fixed-
            # assembly sweep refuses it, and must refuse it at every scale.
            assert base.grashof() == "change-point"
            with pytest.raises(linkage.LinkageError, match="flattens"):
                fb.uniform_sweep(0.0, 0.1, 32)
        else:
            u1 = fb.uniform_sweep(0.0, 0.1, 32)
            np.testing.assert_allclose(u1 / s, u0, rtol=1e-9, atol=1e-9)


@FAST
@given(
    pts=hnp.arrays(np.float64, (3, 2), elements=st.floats(-1, 1)),
    s=st.one_of(st.sampled_from([5e-324 * 2**60, 1e-300, 1e300, 1e307]), SCALES),
)
@example(pts=np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]), s=1e308)  # awaits A (D8)
def test_circumcentre_scale_invariance(pts, s):
    """Awaits A (D8): a circumcentre and a centre of curvature scale with the points; NaN only
    where the unscaled one is NaN (collinear), never from overflow or underflow.

    Only for scaled points that are floats at all: every nonzero coordinate times ``s`` must be
    a normal float. Below the smallest normal the product loses digits (below the smallest
    subnormal it is 0, and three points at 0 rightly have a NaN centre); above the largest it
    is infinite. Those inputs are not the points scaled, so there is nothing to compare."""
    with np.errstate(over="ignore", under="ignore"):
        scaled = s * pts
    nonzero = np.abs(scaled[pts != 0])
    assume(bool(np.all(nonzero >= np.finfo(np.float64).tiny) and np.all(np.isfinite(nonzero))))
    largest = np.finfo(np.float64).max
    c0 = geometry.circumcentre(pts[0], pts[1], pts[2])
    if not np.isfinite(c0).all() or np.abs(c0).max() > 1e3:  # (nearly) collinear
        return
    c1 = geometry.circumcentre(*scaled)
    if float(np.abs(c0).max()) * s <= largest:  # else the scaled centre is not a float: no claim
        np.testing.assert_allclose(c1 / s, c0, rtol=1e-8, atol=1e-8)
    centre, _kappa = geometry.curvature_centre(scaled[0], scaled[1], scaled[2])
    c_base, k_base = geometry.curvature_centre(pts[0], pts[1], pts[2])
    if (
        np.isfinite(c_base).all()
        and np.abs(c_base).max() < 1e3
        and 1e-3 < abs(k_base) < 1e3
        and float(np.abs(c_base).max()) * s <= largest
    ):
        np.testing.assert_allclose(centre / s, c_base, rtol=1e-8, atol=1e-8)


def test_counts_beyond_an_index_are_refused_before_rust():
    """Counts that cannot be represented are a LinkageError naming the argument."""
    for n in (2**63, 2**64, 10**30):
        with pytest.raises(linkage.LinkageError, match="n = "):
            HOECKEN.circuit(n)
        with pytest.raises(linkage.LinkageError, match="n = "):
            HOECKEN.uniform_sweep(0.0, 0.1, n)
    assert sys.maxsize == 2**63 - 1 or sys.maxsize == 2**31 - 1


def test_core_counts_never_panic():
    """Awaits A (D2, D3): a count whose output cannot be addressed is a MemoryError (the size
    is checked before allocating), never a capacity-overflow panic or a silent wrap."""
    for fn in (
        lambda: HOECKEN.circuit(2**62),
        lambda: HOECKEN.uniform_sweep(0.0, 0.1, 2**62),
    ):
        with pytest.raises((MemoryError, linkage.LinkageError)):
            try:
                fn()
            except BaseException as exc:  # a PanicException is not an Exception
                if isinstance(exc, (MemoryError, linkage.LinkageError)):
                    raise
                raise AssertionError(f"{type(exc).__name__}: {exc}") from exc
    # The binding itself must not wrap 2**63 to an empty array.
    with pytest.raises((MemoryError, linkage.LinkageError)):
        out = HOECKEN._core.uniform_sweep(0.0, 0.1, 2**63, "table", 64, 1, None)
        raise AssertionError(f"n = 2**63 gave an array of shape {out.shape}")


@FAST
@given(
    s=st.one_of(
        st.sampled_from([1e-200, 1e-100, 1e100, 1e200]), st.floats(-200, 200).map(lambda e: 10.0**e)
    )
)
@example(s=1e200)  # awaits A (D6): leg velocities NaN on valid samples at this scale
def test_walker_scale_invariance(s):
    """Awaits A (D6): a walker scaled by ``s`` has the same duty factors and its margins,
    strides and body speed scale by ``s`` — not a LinkageError from NaN rates."""
    from dataclasses import replace

    def scaled(w, k):
        legs = []
        for leg in w.legs:
            fb = leg.linkage
            f = linkage.FourBar(
                ground=fb.ground * k,
                crank=fb.crank * k,
                coupler=fb.coupler * k,
                rocker=fb.rocker * k,
                point=(fb.point[0] * k, fb.point[1] * k),
            )
            legs.append(
                replace(
                    leg,
                    linkage=f,
                    mount=tuple(x * k for x in leg.mount),
                    foot_offset=tuple(x * k for x in leg.foot_offset),
                    pad=leg.pad * k,
                )
            )
        return Walker(legs, cg=(0.0, 0.0), ground_tol=0.1 * k)

    theta = np.linspace(0, 2 * np.pi, 73)
    base, sim = scaled(QUAD, 1.0).simulate(theta), scaled(QUAD, s).simulate(theta)
    np.testing.assert_array_equal(sim.stance, base.stance)
    assert sim.min_margin / s == pytest.approx(base.min_margin, rel=1e-9)
    np.testing.assert_allclose(sim.stride / s, base.stride, rtol=1e-9)
    np.testing.assert_allclose(sim.body_velocity / s, base.body_velocity, rtol=1e-9, atol=1e-9)
