"""Stiff and extreme cases against 50-digit mpmath, with stated bounds (the fast CI subset of
``bench/stability.py``): errors within a few ε of the coordinates times the conditioning, and no
branch flip."""

from __future__ import annotations

import numpy as np
import pytest
import stability_cases as sc

import linkage


@pytest.mark.parametrize("stretched", [True, False])
def test_dyads_near_toggle_keep_full_accuracy(stretched):
    rows = sc.toggle_dyad([1e-4, 1e-8, 1e-12], stretched=stretched)
    for case, err, ratio, flips, note in rows:
        assert ratio <= 1.0, (case, err, note)


def test_link_length_ratios_from_1e_minus_6_to_1e6():
    for case, err, ratio, flips, _ in sc.link_ratios([1e-6, 1e-3, 1.0, 1e3, 1e6], samples=24):
        assert ratio <= 1.0, (case, err)


def test_pivots_far_from_the_origin():
    for case, err, ratio, flips, _ in sc.far_pivots([1e4, 1e8], samples=24):
        assert ratio <= 1.0, (case, err)


def test_change_points_pass_their_flat_positions_without_flipping():
    for case, err, ratio, flips, _ in sc.singular_passes((0.5, 45.0)):
        assert flips == 0, case
        assert ratio <= 8.0, (case, err)


def test_rates_near_a_toggle_within_the_conditioning():
    for case, err, ratio, flips, note in sc.rates_near_toggle([1e-2, 1e-6, 1e-10]):
        assert ratio <= 10.0, (case, err, note)


def test_near_toggle_samples_are_flagged():
    fb = linkage.catalog.evans_c()
    _lo, hi = fb.input_limits()
    s = fb.sweep([0.0, hi - 1e-3, hi - 1e-14, hi], omega=1.0, outputs=("velocity",))
    np.testing.assert_array_equal(s.near_toggle(1e-6), [False, False, True, True])
    assert s.valid.all()


@pytest.mark.parametrize("scale", [1e-300, 1e-150, 1e-6, 1e6, 1e150, 1e300])
def test_scale_invariance_across_the_double_range(scale):
    """The same linkage at any scale gives the same shape: products are formed in units of a
    power of two near the longest side, so nothing overflows or underflows."""
    theta = np.linspace(0, 2 * np.pi, 13)
    unit = linkage.catalog.hoecken().sweep(theta).point
    fb = linkage.FourBar(
        ground=20 * scale,
        crank=10 * scale,
        coupler=25 * scale,
        rocker=25 * scale,
        point=(50 * scale, 0),
    )
    s = fb.sweep(theta)
    assert s.valid.all()
    np.testing.assert_allclose(s.point / scale, unit, rtol=1e-13, atol=1e-13 * 50)


def test_overflowing_numbers_give_invalid_samples_not_garbage():
    m = linkage.Mechanism()
    m.fixed("O", (0.0, 0.0))
    m.crank("A", "O", radius=1e308)
    m.fixed("C", (-1e308, 0.0))
    m.point("P", on=("C", "A"), at=(1e308, 0.0))
    s = m.sweep([0.0, 1.0])
    # At θ = 0, A − C = (2e308, 0) overflows: no position, flagged. At θ = 1 it does not, and
    # P sits exactly 1e308 from C toward A.
    np.testing.assert_array_equal(s.valid, [False, True])
    assert np.isnan(s.point[0]).all()
    d = s.point[1] - s.joint("C")[1]
    assert np.hypot(*(d / 1e300)) == pytest.approx(1e8, rel=1e-14)
