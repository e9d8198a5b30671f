"""Bounds of path synthesis (issue 29, items 9 and 10): the work on a target no linkage draws is
bounded by its size, and a points file is read as its user meant (UTF-16 without a byte-order
mark, a mistyped first point, a point far out of scale)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from linkage import LinkageError, synthesis

POINTS = [(0.0, 0.0), (1.0, 0.5), (2.0, 1.5), (3.0, 1.0), (4.0, 2.5), (5.0, 2.0)]


def csv(points: list[tuple[float, float]], header: str | None = "x,y") -> str:
    lines = ([header] if header is not None else []) + [f"{x},{y}" for x, y in points]
    return "\n".join(lines) + "\n"


# -- reading a points file ------------------------------------------------------------------


@pytest.mark.parametrize("encoding", ["utf-16-le", "utf-16-be"])
def test_utf16_without_a_byte_order_mark_is_read(tmp_path: Path, encoding: str) -> None:
    f = tmp_path / "points.csv"
    f.write_bytes(csv(POINTS).encode(encoding))  # no BOM: Python's utf-16-le/be write none
    assert not f.read_bytes().startswith((b"\xff\xfe", b"\xfe\xff"))
    np.testing.assert_array_equal(synthesis.read_points(f), np.array(POINTS))


def test_utf16_without_a_byte_order_mark_that_does_not_decode_says_so(tmp_path: Path) -> None:
    f = tmp_path / "points.csv"
    # A lone low surrogate, which no UTF-16 text holds, among ASCII lines.
    f.write_bytes(csv(POINTS).encode("utf-16-le") + b"\x01\xdc" + "3,4\n".encode("utf-16-le"))
    with pytest.raises(LinkageError, match="looks like UTF-16 without a byte-order mark"):
        synthesis.read_points(f)


@pytest.mark.parametrize("first", ["1.0,2.o", "l.0,2.0", "1,2,", "1.0;x", "1 2 3"])
def test_a_mistyped_first_point_is_an_error_naming_line_1(tmp_path: Path, first: str) -> None:
    f = tmp_path / "points.csv"
    f.write_text(first + "\n" + csv(POINTS, header=None))
    if first == "1,2,":
        # A trailing separator is no field: a point.
        assert len(synthesis.read_points(f)) == len(POINTS) + 1
        return
    with pytest.raises(LinkageError, match=rf"{f.name}:1: "):
        synthesis.read_points(f)


@pytest.mark.parametrize("header", ["x,y", "X;Y", "x (mm)\ty (mm)", "point x, point y"])
def test_a_header_line_is_still_skipped(tmp_path: Path, header: str) -> None:
    f = tmp_path / "points.csv"
    f.write_text(csv(POINTS, header=header))
    np.testing.assert_array_equal(synthesis.read_points(f), np.array(POINTS))


@pytest.mark.parametrize("closed", [True, False])
def test_a_point_far_out_of_scale_is_refused_for_that_reason(closed: bool) -> None:
    rng = np.random.default_rng(1)
    pts = np.vstack([rng.uniform(0, 1, (10, 2)), [[1e300, 0.0]], rng.uniform(0, 1, (2, 2))])
    with pytest.raises(LinkageError, match=r"points\[10\] = \[1e\+300, 0.0\] is far out of") as e:
        synthesis.clean_target(pts, closed)
    assert "collinear" not in str(e.value)


@pytest.mark.parametrize("scale", [1e-300, 1.0, 1e300])
def test_a_curve_at_any_scale_is_not_out_of_scale(scale: float) -> None:
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    pts = np.c_[np.cos(t), 0.3 * np.sin(t)] * scale + (2.0 * scale, 0.0)
    assert len(synthesis.clean_target(pts, True)) == 40


# -- the work on a target no linkage draws --------------------------------------------------


def test_the_later_stages_budget_falls_with_the_points() -> None:
    full = synthesis.LATER_EVALUATIONS
    assert synthesis._Budget.of(5).left == full
    assert synthesis._Budget.of(synthesis.LATER_POINTS).left == full
    assert synthesis._Budget.of(100).left == pytest.approx(full * 0.4**3)
    assert synthesis._Budget.of(synthesis.FIT_POINTS).left < full / 20


def test_an_unfittable_open_target_stops_its_later_stages_at_the_budget(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    arcs = synthesis.Atlas.build(2000, kind="fourbar-arcs", threads=1)
    pts = np.random.default_rng(0).uniform(-1.0, 1.0, (30, 2))
    rows = [0]
    residuals = synthesis._residuals

    def counted(kind, params, *rest):  # type: ignore[no-untyped-def]
        rows[0] += len(params)
        return residuals(kind, params, *rest)

    budgets: list[synthesis._Budget] = []
    of = synthesis._Budget.of

    def recorded(points: int) -> synthesis._Budget:
        budgets.append(of(points))
        return budgets[-1]

    monkeypatch.setattr(synthesis.fitting, "_residuals", counted)
    monkeypatch.setattr(synthesis._Budget, "of", staticmethod(recorded))
    monkeypatch.setattr(synthesis.fitting, "LATER_EVALUATIONS", 20_000)
    kw = dict(closed=False, top=1, atlas=arcs, refine=2, global_search=False)
    found = synthesis.path(pts, **kw)  # type: ignore[arg-type]
    assert found and found[0].error > 0.05 * synthesis.target_size(pts)  # none draws it
    (b,) = budgets
    assert b.left == 20_000 and b.out
    # A stage stops between fits: the budget is overrun by at most one long fit's evaluations
    # (three rounds; each evaluation of a Jacobian 4 × 10 rows, of the residuals 1).
    one_fit = 3 * (synthesis.POLISH_NFEV + synthesis.POLISH_NFEV // 5) * 41
    assert b.spent <= b.left + one_fit
    bounded = rows[0]
    # Without the budget the same search evaluates far more.
    rows[0] = 0
    budgets.clear()
    monkeypatch.setattr(synthesis.fitting, "LATER_EVALUATIONS", 10**12)
    synthesis.path(pts, **kw)  # type: ignore[arg-type]
    assert rows[0] > bounded + b.left


def test_a_target_too_small_for_normal_floats_is_refused_for_that_reason():
    """Points scaled by 1e-310 had been refused as "ground = 4.15e-310 is subnormal ... scale the
    linkage up", a link the user never gave (found by a hostile re-trial)."""
    square = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [0.7, 0.7]])
    with pytest.raises(LinkageError, match=r"the points span 2e-310, below the 9\.33e-302"):
        synthesis.clean_target(square * 1e-310, True)
    assert synthesis.clean_target(square * 1e-300, True).shape == (5, 2)
