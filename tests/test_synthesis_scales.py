"""Path synthesis at extreme scales: a target of size 1e±300 is searched at unit size and the
candidates moved back, so the result is the same figure scaled; the measures of a curve (``target_size``, ``largest_distance``) hold there too,
with no overflow warning; a ``[synthesis]`` scene of such points runs."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import linkage
from linkage import runner, scene, synthesis
from linkage.synthesis import largest_distance, target_size

SLIDER = linkage.SliderCrank(crank=10, coupler=32, offset=6, point=(12, 9))
FOURBAR = linkage.catalog.hoecken()


def curve(kind: str) -> np.ndarray:
    lk = SLIDER if kind == "slider-crank" else FOURBAR
    return lk.circuit(61).point[:-1] @ [[0.6, 0.8], [-0.8, 0.6]] + (250.0, 40.0)


@pytest.mark.parametrize("kind", ["fourbar", "slider-crank"])
@pytest.mark.parametrize("scale", [1e-300, 1e-150, 1e150, 1e300])
def test_a_target_at_an_extreme_scale_is_found_as_at_unit_scale(kind: str, scale: float) -> None:
    unit = curve(kind)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow or underflow warning anywhere
        refs = synthesis.path(unit, kind=kind, top=3)
        got = synthesis.path(unit * scale, kind=kind, top=1)[0]
        size = target_size(unit * scale)
        assert size == pytest.approx(target_size(unit) * scale, rel=1e-14)
        assert got.error <= 1e-12 * size and refs[0].error <= 1e-12 * target_size(unit)
        # The candidate is a unit one scaled: its own circuit passes through the target. (Which
        # one: Hoecken's two crank-rocker cognates are mirror images, alike to the last digits
        # of every measure, so rounding picks the first.)
        s = got.linkage.circuit(4001)
        assert largest_distance(unit * scale, s.point[s.valid]) <= 1e-5 * size
        same = [
            r
            for r in refs
            if r.crank_range == pytest.approx(got.crank_range, abs=1e-9)
            and (r.grashof, r.full_turn) == (got.grashof, got.full_turn)
        ]
        assert same, (got, refs)
        assert same[0].min_transmission == pytest.approx(refs[0].min_transmission, abs=1e-12)


def test_measures_of_a_curve_hold_at_extreme_scales() -> None:
    square = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
    for scale in (1e-308, 1e-300, 1e300, 1e307):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert target_size(square * scale) == pytest.approx(scale, rel=1e-15)
            d = largest_distance(square * scale, [[2 * scale, 0.0], [2 * scale, 2 * scale]])
            assert d == pytest.approx(3 * scale, rel=1e-15)  # from (-1, 0) to (2, 0)
    # The target's check (collinear points?) had summed coordinates of 1e306 and overflowed.
    hoecken = FOURBAR.circuit(37).point[:-1]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert synthesis.clean_target(hoecken * 1e306, True).shape == hoecken.shape
        with pytest.raises(linkage.LinkageError, match="collinear"):
            synthesis.clean_target(np.c_[np.arange(6.0), np.arange(6.0)] * 1.7e307, True)


def test_a_synthesis_scene_of_huge_points_runs(tmp_path: Path) -> None:
    np.savetxt(tmp_path / "big.csv", curve("slider-crank") * 1e200, delimiter=",")
    path = tmp_path / "big.toml"
    path.write_text(
        'name = "big"\nunits = "mm"\n[synthesis]\npoints = "big.csv"\nkind = "slider-crank"\n'
        "top = 2\n"
    )
    res = runner.run(scene.load(path))
    assert res.synthesis is not None
    best = res.synthesis.candidates[0]
    assert best.error <= 1e-9 * res.synthesis.size


def test_accept_ends_the_search_once_a_candidate_is_good_enough(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # Hoecken's curve over crank 1 … 4 rad as an open arc: the first fits end near 1e-4 of the
    # size, so without accept= the long fits run (to 3e-5); with accept=1e-2 of the size they
    # must not, and the answer is within it. (The curve's equation, the search's first stage,
    # recovers this arc exactly: it is turned off here to test the stages accept= governs.)
    monkeypatch.setattr(synthesis.stages, "CURVE_EQUATION_POINTS", 10**9)
    arc = FOURBAR.sweep(np.linspace(1.0, 4.0, 40)).point
    size = target_size(arc)
    calls = []
    real = synthesis._polish

    def counted(*args, **kw):  # type: ignore[no-untyped-def]
        calls.append(1)
        return real(*args, **kw)

    monkeypatch.setattr(synthesis.stages, "_polish", counted)
    quick = synthesis.path(arc, closed=False, top=1, accept=1e-2 * size)
    assert quick and quick[0].error <= 1e-2 * size and not calls
    full = synthesis.path(arc, closed=False, top=1)
    assert calls and full[0].error <= quick[0].error
    for bad in (-1.0, float("nan")):
        with pytest.raises(linkage.LinkageError, match="accept"):
            synthesis.path(arc, closed=False, accept=bad)
