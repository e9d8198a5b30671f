"""Two smaller findings of issue 29 (item 10).

* An unaligned, C-contiguous float64 array (a view of a byte buffer at an odd offset) was
  refused as "not a contiguous float64 array": the binding now copies it once into an aligned
  buffer, and gives the same result as an ordinary array. An unaligned ``out`` (written in place,
  so no copy can stand in) is refused with a message that says "unaligned" and how to fix it.
* Subnormal lengths (~1e-309) constructed but never assembled: every constructor now raises
  ``LinkageError`` saying the length is subnormal.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkage
from linkage import LinkageError, catalog


def unaligned(values: np.ndarray) -> np.ndarray:
    """A C-contiguous float64 copy of ``values`` that numpy holds unaligned (offset 1 byte)."""
    flat = np.ascontiguousarray(values, dtype=np.float64)
    a = np.frombuffer(b"\0" + flat.tobytes(), dtype=np.float64, offset=1).reshape(flat.shape)
    assert not a.flags.aligned and a.flags.c_contiguous
    return a


THETA = np.linspace(-1.0, 7.0, 23)


def test_an_unaligned_angle_array_sweeps_like_an_aligned_one() -> None:
    for m in (catalog.jansen(), catalog.hoecken(), linkage.SliderCrank(crank=2, coupler=5)):
        got = m.sweep(unaligned(THETA))
        want = m.sweep(THETA)
        np.testing.assert_array_equal(got.valid, want.valid)
        np.testing.assert_array_equal(got.point, want.point)


def test_unaligned_rates_are_accepted() -> None:
    m = catalog.jansen()
    omega = np.full(THETA.shape, 2.0)
    got = m.sweep(unaligned(THETA), omega=unaligned(omega), outputs=("point", "velocity"))
    want = m.sweep(THETA, omega=omega, outputs=("point", "velocity"))
    np.testing.assert_array_equal(got.velocity, want.velocity)


def test_an_unaligned_empty_array_is_fine() -> None:
    a = np.frombuffer(b"\0", dtype=np.float64, offset=1)
    assert a.size == 0
    assert catalog.jansen().sweep(a).valid.shape == (0,)


def test_an_unaligned_out_array_is_refused_saying_so() -> None:
    fb = linkage._core.FourBar((0.0, 0.0), (20.0, 0.0), 10.0, 25.0, 25.0, (50.0, 0.0), "open")
    out = unaligned(np.zeros((8, 2)))
    with pytest.raises(LinkageError, match="unaligned"):
        fb.uniform_sweep(0.0, 0.1, 8, out=out)


@pytest.mark.parametrize("tiny", [1e-309, 5e-324, 2.2e-308])
def test_subnormal_four_bar_lengths_are_refused(tiny: float) -> None:
    assert 0 < tiny < np.finfo(np.float64).tiny
    for ground, crank, coupler, rocker in (
        (20, tiny, 25, 25),
        (tiny, 10, 25, 25),
        (20, 10, tiny, 25),
        (20, 10, 25, tiny),
    ):
        with pytest.raises(LinkageError, match="subnormal"):
            linkage.FourBar(ground, crank, coupler, rocker, point=(50, 0))


def test_the_smallest_normal_length_is_a_length() -> None:
    m = np.finfo(np.float64).tiny
    fb = linkage.FourBar(2 * m, m, 2 * m, 2 * m, point=(0, 0))
    assert bool(fb.sweep([0.5]).valid.all())


def test_subnormal_slider_crank_and_mechanism_lengths_are_refused() -> None:
    with pytest.raises(LinkageError, match="subnormal"):
        linkage.SliderCrank(crank=1e-309, coupler=5)
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    with pytest.raises(LinkageError, match="subnormal"):
        m.crank("A", "O", 1e-309)
