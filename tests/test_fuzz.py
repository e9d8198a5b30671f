"""The Python boundary fuzzed: arbitrary floats (NaN, ±inf, subnormals, huge, negative), shapes
and dtypes never crash or leak a panic — they give a result (NaN + mask where a sample cannot
be assembled) or one of the documented exceptions (LinkageError, a ValueError; TypeError;
MemoryError). The rest of the public API is fuzzed in test_fuzz_api.py, absurd sizes in
test_memory_limits.py."""

from __future__ import annotations

import os

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import linkage
from linkage import geometry

ANY_FLOAT = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True),
    st.sampled_from([0.0, -0.0, 5e-324, -5e-324, 1e308, -1e308, 1e-300, 1e300]),
)
DOCUMENTED = (linkage.LinkageError, TypeError, MemoryError)
DTYPES = st.sampled_from(
    [
        np.float64,
        np.float32,
        np.float16,
        np.int8,
        np.int64,
        np.uint64,
        np.bool_,
        np.complex128,
        object,
    ]
)


def arrays(min_dims=0, max_dims=3):
    return DTYPES.flatmap(
        lambda dt: hnp.arrays(
            dtype=dt if dt is not object else np.float64,
            shape=hnp.array_shapes(min_dims=min_dims, max_dims=max_dims, min_side=0, max_side=5),
            # float64 gets the hand-picked extremes; narrower types their own full range.
            elements=ANY_FLOAT if dt in (np.float64, object) else None,
        ).map(lambda a, dt=dt: a.astype(object) if dt is object else a)
    )


def call(fn):
    try:
        return fn()
    except DOCUMENTED:
        return None


# 300 examples per test in CI; `make fuzz` runs 20 000 (LINKAGE_FUZZ_EXAMPLES).
FAST = settings(
    max_examples=int(os.environ.get("LINKAGE_FUZZ_EXAMPLES", "300")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)


@FAST
@given(g=ANY_FLOAT, r=ANY_FLOAT, c=ANY_FLOAT, k=ANY_FLOAT, px=ANY_FLOAT, py=ANY_FLOAT)
def test_fourbar_construction_and_sweep(g, r, c, k, px, py):
    fb = call(lambda: linkage.FourBar(ground=g, crank=r, coupler=c, rocker=k, point=(px, py)))
    if fb is None:
        return
    s = fb.sweep(np.linspace(0, 2 * np.pi, 7))
    # Either assembled (finite) or NaN with the mask down — never garbage.
    assert np.isfinite(s.point[s.valid]).all() or not np.isfinite([g, r, c, k, px, py]).all()
    assert np.isnan(s.point[~s.valid]).all()
    call(lambda: fb.input_limits())
    call(lambda: fb.transmission_angle([0.0, 1.0]))


@FAST
@given(theta=arrays(), omega=st.one_of(st.none(), ANY_FLOAT), alpha=ANY_FLOAT)
def test_sweep_arguments(theta, omega, alpha):
    fb = linkage.catalog.hoecken()
    out = call(
        lambda: fb.sweep(
            theta,
            omega=omega,
            alpha=alpha,
            outputs=("point", "velocity") if omega is not None else ("point",),
        )
    )
    if out is not None:
        assert out.point.shape[-1] == 2 and out.valid.dtype == np.bool_
        assert np.isnan(out.point[~out.valid]).all()


@FAST
@given(path=arrays(1, 3), tol=ANY_FLOAT, vel=arrays(1, 3))
def test_geometry_functions(path, tol, vel):
    call(lambda: geometry.straightness(path, tol, velocity=vel))
    call(lambda: geometry.curvature_centre(path, vel, path))
    call(lambda: geometry.circumcentre(path, vel, path))
    call(lambda: geometry.foot_path(path, tol))


@FAST
@given(
    x=ANY_FLOAT,
    y=ANY_FLOAT,
    r=ANY_FLOAT,
    r2=ANY_FLOAT,
    side=st.sampled_from(["left", "right", "up", 3]),
)
def test_mechanism_builder(x, y, r, r2, side):
    m = linkage.Mechanism()
    call(lambda: m.fixed("O", (x, y)))
    call(lambda: m.fixed("C", (1.0, 0.0)))
    call(lambda: m.crank("A", "O", radius=r))
    call(lambda: m.dyad("B", "A", "C", r, r2, side=side))
    call(lambda: m.sweep([0.0, 1.0, 2.0]))


@FAST
@given(speed=ANY_FLOAT, duty=ANY_FLOAT, t=arrays(0, 1))
def test_drives(speed, duty, t):
    from linkage.drive import Program, Segment, crank_schedule, motion_law

    call(lambda: motion_law("cycloidal", t))
    call(lambda: Program(speed, [Segment(duty, speed, "3-4-5")]).angles(t))
    if np.isfinite([speed, duty]).all() and 0 < duty < 1 and 1e-3 < abs(speed) < 1e3:
        call(
            lambda: crank_schedule(
                linkage.catalog.hoecken(), abs(speed), duty, samples=16, resolution=721
            )
        )
