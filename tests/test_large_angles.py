"""Sweeps at large crank angles against an exact reduction (issue 29, item 7).

Every catalogue linkage swept at θ from 1e6 to 1e300 rad gives the pose of ``θ mod 2π`` (computed
with mpmath at 3000 bits, rounded to a float) to within 1e-13 of the linkage's size, and
assembles exactly where that angle does. Jansen used to err by 1e-8 at 1e6 and report
``valid=False`` from about 1e16; Peaucellier assembled at 1e16 where its reduction does not.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

import mpmath  # type: ignore[import-untyped]
import numpy as np
import pytest

from linkage import catalog

ANGLES = (1e6, -1e6, 1e11, 1.6e15, -1.6e15, 1e16, 1e17, 1e22, 1e100, 1e300, -1e300)

#: Every catalogue linkage: the named ones and the leg references built from families.
LINKAGES: dict[str, Callable[[], object]] = {
    **{name: partial(catalog.get, name) for name in catalog.names()},
    "klann": catalog.klann,
    "hoecken_guided": catalog.hoecken_guided,
}


def exact_reduction(theta: float) -> float:
    """``theta mod 2π`` in ``[0, 2π)``, exact to 3000 bits, rounded once to a float."""
    with mpmath.workprec(3000):
        x = mpmath.mpf(theta)
        tau = 2 * mpmath.pi
        return float(x - mpmath.floor(x / tau) * tau)


def test_the_reference_reduction_is_exact() -> None:
    """The reference itself: 2π·k + r rounds back to θ, and a known remainder (1e22 mod 2π)."""
    assert exact_reduction(1e22) == pytest.approx(5.263007914620499, abs=1e-15)
    assert 0.0 <= exact_reduction(-1e300) < 2 * np.pi


def _positions(sweep: object) -> np.ndarray:
    joints = getattr(sweep, "joints", None)
    return np.asarray(sweep.point if joints is None else joints)  # type: ignore[attr-defined]


@pytest.mark.parametrize("name", sorted(LINKAGES))
def test_large_angles_match_the_exact_reduction(name: str) -> None:
    linkage = LINKAGES[name]()
    for theta in ANGLES:
        for angles in ([theta], [0.5, theta, 1.0], theta + np.linspace(0.0, 7.0, 9)):
            at = np.asarray(angles, dtype=np.float64)
            reduced = np.array([exact_reduction(t) for t in at])
            got = linkage.sweep(at)  # type: ignore[attr-defined]
            want = linkage.sweep(reduced)  # type: ignore[attr-defined]
            np.testing.assert_array_equal(
                got.valid, want.valid, err_msg=f"{name} at {theta:g}: validity differs"
            )
            ok = np.asarray(want.valid)
            if not ok.any():
                continue
            p, q = _positions(got)[ok], _positions(want)[ok]
            size = float(np.max(np.abs(q)))
            err = float(np.max(np.abs(p - q))) / size
            assert err <= 1e-13, f"{name} at {theta:g}: {err:.3g} of the size"


def test_jansen_assembles_at_every_large_angle() -> None:
    """The reported symptom: Jansen assembles at every angle, so every sample is valid."""
    m = catalog.jansen()
    theta = np.array([1e16, 3e16, 1e17, 1e100, 1e300, -1e300])
    assert bool(np.all(m.sweep(theta).valid))


def test_reduce_angle_is_exact_and_keeps_a_phase() -> None:
    """``_core.numeric.reduce_angle``: θ mod 4π exact to an ulp, small angles as they are; adding a
    phase to it keeps the phase, where ``θ + φ`` rounds it away at large θ (a walker's legs)."""
    from linkage import _core

    theta = np.array([1e6, -1.6e15, 1e16, 1e22, 1e300, -1e300])
    got = _core.numeric.reduce_angle(theta)
    with mpmath.workprec(3000):
        four_pi = 4 * mpmath.pi
        for t, r in zip(theta, got):
            x = mpmath.mpf(float(t))
            assert r == pytest.approx(float(x - mpmath.floor(x / four_pi) * four_pi), abs=2e-15)
    small = np.array([0.0, -1.0, 63.5, -63.5])
    np.testing.assert_array_equal(_core.numeric.reduce_angle(small), small)
    leg = catalog.jansen()
    phase = 0.7
    for t in (1e16, 1e300):
        want = leg.sweep([exact_reduction(t) + phase]).point
        np.testing.assert_allclose(
            leg.sweep(_core.numeric.reduce_angle(np.array([t])) + phase).point, want, atol=1e-12
        )
