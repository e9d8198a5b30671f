"""FourBar: the Python contract (shapes, dtypes, masks, errors) and references."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from reference import fourbar_reference

import linkage


def test_contract_shapes_and_dtypes():
    fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 0))
    theta = np.linspace(0, 2 * np.pi, 3601)
    s = fb.sweep(theta)
    assert s.point.shape == (3601, 2) and s.point.dtype == np.float64
    assert s.joints.shape == (3601, 5, 2) and s.joints.dtype == np.float64
    assert s.valid.shape == (3601,) and s.valid.dtype == np.bool_ and s.valid.all()
    assert s.joint_names == ("O", "C", "A", "B", "P")
    np.testing.assert_array_equal(s.point, s.joints[:, 4])
    s = fb.sweep(theta, omega=2.0, alpha=0.0, outputs=("point", "velocity", "acceleration"))
    assert s.velocity.shape == (3601, 2) and s.acceleration.shape == (3601, 2)
    assert s.joint_velocities.shape == (3601, 5, 2)
    assert fb.grashof() == "crank-rocker"
    assert fb.input_limits() is None


def test_scalar_angle_gives_unbatched_shapes(hoecken):
    s = hoecken.sweep(math.pi)
    assert s.point.shape == (2,) and s.joints.shape == (5, 2) and s.valid.shape == ()
    np.testing.assert_allclose(s.point, [20.0, 40.0], atol=1e-13)


def test_any_float_array_like_and_zero_copy_input(hoecken):
    ref = hoecken.sweep(np.array([0.0, 1.0, 2.0])).point
    for theta in (
        [0, 1, 2],
        (0.0, 1.0, 2.0),
        np.array([0, 1, 2], dtype=np.int32),
        np.array([0, 1, 2], dtype=np.float32),
    ):
        np.testing.assert_array_equal(hoecken.sweep(theta).point, ref)
    strided = np.array([0.0, 9.0, 1.0, 9.0, 2.0, 9.0])[::2]
    np.testing.assert_array_equal(hoecken.sweep(strided).point, ref)


def test_rates_not_requested_are_not_computed(hoecken):
    s = hoecken.sweep([0.0, 1.0])
    with pytest.raises(AttributeError, match="velocity was not computed"):
        _ = s.velocity
    s = hoecken.sweep([0.0, 1.0], omega=1.0, outputs=("velocity",))
    assert s.velocity.shape == (2, 2)
    with pytest.raises(AttributeError, match="acceleration was not computed"):
        _ = s.acceleration


def test_positions_against_mpmath_reference():
    rng = np.random.default_rng(7)
    cases = [
        (20, 10, 25, 25, 50, 0, True),
        (40, 40, 20, 40, 10, -math.sqrt(1500), True),
        (20, 25, 10, 25, 5, 0, False),
        (3.0, 1.0, 2.5, 2.2, 1.7, 0.4, True),
    ]
    for g, r, c, k, al, le, op in cases:
        fb = linkage.FourBar(
            ground=g,
            crank=r,
            coupler=c,
            rocker=k,
            point=(al, le),
            assembly="open" if op else "crossed",
        )
        theta = rng.uniform(-np.pi, np.pi, 400)
        s = fb.sweep(theta)
        size = max(g, r, c, k, abs(al), abs(le))
        worst = 0.0
        for i in np.flatnonzero(s.valid):
            (_, _), (bx, by), (px, py) = fourbar_reference(g, r, c, k, al, le, theta[i], op)
            worst = max(
                worst,
                abs(float(bx) - s.joints[i, 3, 0]),
                abs(float(by) - s.joints[i, 3, 1]),
                abs(float(px) - s.point[i, 0]),
                abs(float(py) - s.point[i, 1]),
            )
        assert worst <= 1e-14 * size * 8, worst


def test_rates_against_mpmath_derivatives():
    g, r, c, k, al, le = 20, 10, 25, 25, 50, 0
    fb = linkage.FourBar(ground=g, crank=r, coupler=c, rocker=k, point=(al, le))
    omega, alpha = 6.732, -1.5
    for theta in (0.3, 1.9, 3.5, 5.2):
        s = fb.sweep([theta], omega=omega, alpha=alpha, outputs=("velocity", "acceleration"))
        for axis in (0, 1):
            f = lambda t, a=axis: fourbar_reference(g, r, c, k, al, le, t)[2][a]
            d1 = mp.diff(f, theta, 1)
            d2 = mp.diff(f, theta, 2)
            v = float(d1 * omega)
            a = float(d2 * omega**2 + d1 * alpha)
            assert abs(s.velocity[0, axis] - v) <= 1e-12 * 500
            assert abs(s.acceleration[0, axis] - a) <= 1e-12 * 5000


def test_unassemblable_samples_are_nan_with_mask_and_gap():
    fb = linkage.catalog.evans_b()
    theta = np.radians([0.0, 80.0, 90.0, 180.0, -80.0])
    s = fb.sweep(theta, omega=1.0, outputs=("velocity",))
    np.testing.assert_array_equal(s.valid, [True, True, False, False, True])
    assert np.isnan(s.point[~s.valid]).all() and np.isnan(s.velocity[~s.valid]).all()
    assert np.isfinite(s.point[s.valid]).all()
    assert (s.gap[~s.valid] > 0).all() and (s.gap[s.valid] == 0).all()
    # 180°: |AC| = 33.05 exceeds coupler + rocker = 23.67 by 9.38.
    assert s.gap[3] == pytest.approx(33.05 - 23.67, abs=1e-12)


def test_evans_input_limits_golden():
    """docs/domain.md / thesis 1 §1.4.3.6: about 27°…333°, −81°…+81°, −75°…+75°."""
    lo, hi = map(math.degrees, linkage.catalog.evans_a().input_limits())
    assert abs(lo - 27) < 1 and abs(hi - 333) < 1
    lo, hi = map(math.degrees, linkage.catalog.evans_b().input_limits())
    assert abs(hi - 81) < 0.5 and lo == -hi
    lo, hi = linkage.catalog.evans_c().input_limits()
    assert hi == pytest.approx(math.acos(0.25), abs=1e-15) and lo == -hi


def test_input_limit_is_toggle():
    fb = linkage.catalog.evans_c()
    _lo, hi = fb.input_limits()
    s = fb.sweep([hi - 1e-9, hi, hi + 1e-7])
    np.testing.assert_array_equal(s.valid, [True, True, False])
    assert s.margin[1] < 1e-7
    assert fb.transmission_angle(hi) == pytest.approx(math.pi, abs=1e-6)


def test_transmission_angle_matches_law_of_cosines(hoecken):
    theta = np.linspace(0, 2 * np.pi, 50)
    mu = hoecken.transmission_angle(theta)
    d2 = 10**2 + 20**2 - 2 * 10 * 20 * np.cos(theta)
    np.testing.assert_allclose(np.cos(mu), (25**2 + 25**2 - d2) / (2 * 25 * 25), atol=1e-13)


@pytest.mark.parametrize("name", ["evans_a", "evans_b", "evans_c", "watt", "chebyshev"])
def test_circuit_traces_whole_curve_continuously(name):
    fb = linkage.catalog.get(name)
    s = fb.circuit(2001)
    assert s.valid.all()
    p = s.point
    steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
    # No branch jump: no step exceeds a few times the median step.
    assert steps.max() < 12 * np.median(steps), (steps.max(), np.median(steps))
    np.testing.assert_allclose(p[0], p[-1], atol=1e-6)
    half = (len(p) + 1) // 2
    np.testing.assert_allclose(p[half - 1], p[half], atol=1e-6)
    assert np.all(np.abs(np.diff(s.theta[:half])) > 0)


def test_coarse_sweep_of_crank_rocker_stays_on_branch(hoecken):
    fine = hoecken.sweep(np.radians(np.arange(0, 1001, 1.0)))
    coarse = hoecken.sweep(np.radians(np.arange(0, 1001, 100.0)))
    np.testing.assert_allclose(coarse.point, fine.point[::100], atol=1e-12)


def test_change_point_parallelogram_keeps_parallelogram_coarse_and_fine():
    fb = linkage.FourBar(ground=30, crank=10, coupler=30, rocker=10, point=(15, 0), assembly="open")
    assert fb.grashof() == "change-point"
    for step in (0.5, 10.0, 50.0):
        theta = np.radians(90 + np.arange(0, 720, step))
        s = fb.sweep(theta)
        # Parallelogram: B = A + (30, 0) throughout, through both flat positions.
        np.testing.assert_allclose(s.joints[:, 3], s.joints[:, 2] + [30, 0], atol=1e-9)


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        (
            dict(ground=20, crank=0, coupler=25, rocker=25),
            linkage.LinkageError,
            "crank must be a positive",
        ),
        (
            dict(ground=-20, crank=10, coupler=25, rocker=25),
            linkage.LinkageError,
            "ground must be a positive",
        ),
        (
            dict(ground=20, crank=10, coupler=float("nan"), rocker=25),
            linkage.LinkageError,
            "coupler",
        ),
        (
            dict(ground=20, crank=10, coupler=25, rocker=float("inf")),
            linkage.LinkageError,
            "rocker",
        ),
        (
            dict(ground=20, crank="10", coupler=25, rocker=25),
            TypeError,
            "crank must be a real number",
        ),
        (dict(ground=20, crank=True, coupler=25, rocker=25), TypeError, "crank"),
        (dict(ground=20, crank=10, coupler=25), TypeError, "rocker"),
        (
            dict(ground=20, crank=10, coupler=25, rocker=25, point=(1,)),
            linkage.LinkageError,
            "point",
        ),
        (
            dict(ground=20, crank=10, coupler=25, rocker=25, point=(1, float("nan"))),
            linkage.LinkageError,
            "point",
        ),
        (
            dict(ground=20, crank=10, coupler=25, rocker=25, assembly="upside"),
            linkage.LinkageError,
            "assembly",
        ),
        (
            dict(ground=21, crank=10, coupler=25, rocker=25, c=(20, 0)),
            linkage.LinkageError,
            "contradicts",
        ),
        (dict(crank=10, coupler=25, rocker=25, o=(1, 1), c=(1, 1)), linkage.LinkageError, "ground"),
    ],
)
def test_bad_parameters_raise_specific_errors(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        linkage.FourBar(**kwargs)


@pytest.mark.parametrize(
    "args, kwargs, exc, match",
    [
        ((["a", "b"],), {}, TypeError, "theta must hold real numbers"),
        (([1 + 2j],), {}, TypeError, "theta"),
        ((None,), {}, TypeError, "theta"),
        ((np.zeros((2, 3)),), {}, linkage.LinkageError, r"theta must be a scalar or 1-D"),
        (([0.0, np.nan],), {}, linkage.LinkageError, r"theta\[1\] is nan"),
        (([0.0, np.inf],), {}, linkage.LinkageError, "theta must be finite"),
        (
            ([0.0, 1.0],),
            dict(outputs=("point", "speed")),
            linkage.LinkageError,
            "unknown output 'speed'",
        ),
        (([0.0, 1.0],), dict(outputs=("velocity",)), linkage.LinkageError, "need omega"),
        (
            ([0.0, 1.0],),
            dict(omega=[1.0, 2.0, 3.0], outputs=("velocity",)),
            linkage.LinkageError,
            "omega must be a scalar or have one value per angle",
        ),
        (
            ([0.0, 1.0],),
            dict(omega=np.nan, outputs=("velocity",)),
            linkage.LinkageError,
            "omega must be finite",
        ),
        (([0.0, 1.0],), dict(omega=1.0, alpha="x", outputs=("acceleration",)), TypeError, "alpha"),
        (([0.0, 1.0],), dict(outputs=3), TypeError, "outputs"),
    ],
)
def test_bad_sweep_arguments(hoecken, args, kwargs, exc, match):
    with pytest.raises(exc, match=match):
        hoecken.sweep(*args, **kwargs)


def test_errors_are_valueerror_subclasses():
    assert issubclass(linkage.LinkageError, ValueError)
    assert issubclass(linkage.AssemblyError, linkage.LinkageError)


def test_per_sample_omega_and_alpha(hoecken):
    theta = np.linspace(0, 1, 5)
    w = np.linspace(1, 2, 5)
    s = hoecken.sweep(theta, omega=w, alpha=0.5, outputs=("velocity", "acceleration"))
    for i in range(5):
        si = hoecken.sweep(
            theta[i : i + 1], omega=w[i], alpha=0.5, outputs=("velocity", "acceleration")
        )
        np.testing.assert_allclose(s.velocity[i], si.velocity[0], rtol=0, atol=1e-12)
        np.testing.assert_allclose(s.acceleration[i], si.acceleration[0], rtol=0, atol=1e-12)


def test_fast_sweep_simd_paths_give_the_portable_bits(hoecken, monkeypatch):
    """The fast sweep dispatches to AVX-512 or AVX2 builds of the same kernel when the CPU has
    them; the arithmetic is identical, so the bits must be too (LINKAGE_PORTABLE=1 forces the
    portable code)."""

    def sweeps():
        return [hoecken.uniform_sweep(0.1, 1e-3, 5000, m) for m in ("trig", "table", "recurrence")]

    monkeypatch.delenv("LINKAGE_PORTABLE", raising=False)
    isa = linkage.FourBar.uniform_sweep_isa()
    assert isa in ("avx512", "avx2", "portable")
    fast = sweeps()
    monkeypatch.setenv("LINKAGE_PORTABLE", "1")
    assert linkage.FourBar.uniform_sweep_isa() == "portable"
    for a, b in zip(fast, sweeps()):
        np.testing.assert_array_equal(a, b)
    monkeypatch.setenv("LINKAGE_PORTABLE", "0")
    assert linkage.FourBar.uniform_sweep_isa() == isa


def test_fast_sweep_matches_tracked_sweep_and_checks_arguments(hoecken):
    theta0, dt, n = 0.2, 0.01, 700
    fast = hoecken.uniform_sweep(theta0, dt, n, "table", threads=2)
    slow = hoecken.sweep(theta0 + dt * np.arange(n)).point
    np.testing.assert_allclose(fast, slow, atol=1e-12)
    with pytest.raises(linkage.LinkageError, match="mode"):
        hoecken.uniform_sweep(0.0, 0.1, 10, "simd")
    with pytest.raises(linkage.LinkageError, match="threads"):
        hoecken.uniform_sweep(0.0, 0.1, 10, threads=0)
    with pytest.raises(linkage.LinkageError, match="at most 256"):
        hoecken.uniform_sweep(0.0, 0.1, 10, "table", block=1000)


def test_fast_sweep_into_out_array(hoecken):
    n = 1000
    fresh = hoecken.uniform_sweep(0.3, 0.006, n, "table", threads=2)
    out = np.full((n, 2), 7.0)
    got = hoecken.uniform_sweep(0.3, 0.006, n, "table", threads=2, out=out)
    assert got is out
    np.testing.assert_array_equal(out, fresh)
    # Bad `out` arrays are refused before anything is written.
    keep = np.full((n, 2), 7.0)
    with pytest.raises(linkage.LinkageError, match=r"shape \(1000, 2\)"):
        hoecken.uniform_sweep(0.3, 0.006, n, out=np.zeros((n, 3)))
    with pytest.raises(linkage.LinkageError, match=r"shape \(1000, 2\), got \(2000\)"):
        hoecken.uniform_sweep(0.3, 0.006, n, out=np.zeros(2 * n))
    with pytest.raises(TypeError, match="float64"):
        hoecken.uniform_sweep(0.3, 0.006, n, out=np.zeros((n, 2), np.float32))
    with pytest.raises(TypeError, match="float64"):
        hoecken.uniform_sweep(0.3, 0.006, n, out=[[0.0, 0.0]] * n)
    with pytest.raises(linkage.LinkageError, match="C-contiguous"):
        hoecken.uniform_sweep(0.3, 0.006, n, out=np.zeros((2, n)).T)
    frozen = keep.copy()
    frozen.flags.writeable = False
    with pytest.raises(linkage.LinkageError, match="writeable"):
        hoecken.uniform_sweep(0.3, 0.006, n, out=frozen)
    with pytest.raises(linkage.LinkageError, match="mode"):
        hoecken.uniform_sweep(0.3, 0.006, n, "simd", out=keep)
    with pytest.raises(linkage.LinkageError, match="dtheta"):
        hoecken.uniform_sweep(0.3, np.nan, n, out=keep)
    assert (keep == 7.0).all()


def test_none_among_angles_is_named_not_reported_as_nan() -> None:
    """A None in the angles is a TypeError naming its index (it used to read as NaN), and a
    circuit needs two samples whichever count is refused."""
    fb = linkage.catalog.hoecken()
    for bad in ([0.5, None], np.array([1.0, None], dtype=object)):
        with pytest.raises(TypeError, match=r"got None at theta\[1\]"):
            fb.sweep(bad)
    for n in (0, 1):
        with pytest.raises(linkage.LinkageError, match="n must be an int ≥ 2"):
            fb.circuit(n)
