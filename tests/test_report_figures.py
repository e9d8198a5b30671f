"""The figures table (the rows linkage.stage_figures makes for linkage.runner): units on every
row, digits the error supports, ∞ for a straight path, and error estimates that bound the
sampling error measured at 8× the samples."""

import math
from pathlib import Path
from typing import Union

import numpy as np
import pytest

import linkage
from linkage import LinkageError, figures, runner, scene, stage_figures
from linkage.figures import Row, format_number, significant_digits

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))

LENGTH_ROWS = {
    "trace x range",
    "trace y range",
    "loop-closure residual",
    "leg loop-closure residual",
    "smallest radius of curvature",
    "straight part within 0.1 % of size",
    "straight part max deviation",
    "stride",
    "lift height (obstacle a foot clears)",
    "body clearance",
    "body travel",
    "minimum stability margin",
    "foot slip per cycle (all feet)",
    "cam profile's smallest radius of curvature",
}
SPEED_ROWS = {"peak trace speed", "mean body speed", "largest stance-speed spread"}


def load(path):
    # With its path: a synthesis example's points file is relative to the scene's folder.
    return scene.parse(path.read_text(), path)


@pytest.fixture(scope="module")
def results():
    return {p.stem: runner.run(load(p)) for p in EXAMPLES}


def test_rows_are_four_strings_with_typed_values(results):
    for name, res in results.items():
        for row in res.figures:
            assert isinstance(row, Row) and len(row) == 4, (name, row)
            _figure, _text, _unit, note = row
            assert all(isinstance(c, str) for c in row)
            assert "sampled" not in note, (name, row)
            if isinstance(row.value, float):
                assert row.error is None or row.error >= 0


@pytest.mark.parametrize("name", [p.stem for p in EXAMPLES])
def test_every_quantity_has_its_unit(results, name):
    res = results[name]
    u = res.scene.units or "length units"
    rows = {r[0]: r for r in res.figures}
    for figure, row in rows.items():
        if (figure in LENGTH_ROWS and row.value is not None) or figure.startswith(
            "smallest radius"
        ):
            assert row[2] == u, (figure, row)
        if figure in SPEED_ROWS:
            assert row[2] == f"{u}/s", (figure, row)
    if "duration" in rows:
        assert rows["duration"][2] == "s"
    if "peak trace acceleration" in rows:
        assert rows["peak trace acceleration"][2] == f"{u}/s²"
    for figure in ("driver torque mean |T|", "driver torque peak |T|"):
        if figure in rows:
            assert rows[figure][2] == ("N·m" if res.scene.units == "m" else rows[figure][2])
            assert rows[figure][2]
    if "speed variation along it" in rows:
        assert rows["speed variation along it"][2] == "%"


@pytest.mark.parametrize("name", [p.stem for p in EXAMPLES])
def test_printed_numbers_agree_with_the_value_within_the_error(results, name):
    for row in results[name].figures:
        if not isinstance(row.value, float) or row.error is None or row.exact:
            continue
        printed = float(row[1].replace("−", "-"))
        sig = significant_digits(row.value, row.error)
        # Rounded to the digits the error supports: off by at most the error, or half a unit of
        # the last digit when the error is below that (at most 6 significant digits).
        last = 10.0 ** (math.floor(math.log10(abs(row.value))) - sig + 1) if row.value else 0.0
        assert abs(printed - row.value) <= max(row.error, 0.5 * last * (1 + 1e-9)), row
        digits = len(row[1].split("e")[0].replace("-", "").replace(".", "").lstrip("0"))
        assert digits <= sig, row


def test_no_runaway_digits_and_metres_keep_their_millimetres(results):
    for res in results.values():
        for row in res.figures:
            if not isinstance(row.value, float):
                continue
            mantissa = row[1].split("e")[0]
            assert len(mantissa.replace("-", "").replace(".", "").lstrip("0")) <= 6, row
    hexapod = {r[0]: r for r in results["hexapod_tripod"].figures}
    lift = hexapod["lift height (obstacle a foot clears)"]
    assert lift[2] == "m" and float(lift[1]) == pytest.approx(0.0014, rel=1e-3)
    assert lift[1] != "0.001"


def test_a_straight_path_has_an_infinite_radius_spelled_out():
    sc = scene.parse(
        'name = "p"\nunits = "mm"\noutputs = ["trajectory", "curvature"]\n'
        '[mechanism]\ncatalog = "peaucellier"\n[drive]\nkind = "constant"\nomega = 1.0\n'
    )
    row = {r[0]: r for r in runner.run(sc).figures}["smallest radius of curvature"]
    assert row[1] == "∞ (straight path)" and row[2] == "mm" and row.value is None


def figure(res, name):
    return {r[0]: r for r in res.figures}[name]


# Sampled figures whose error estimate must cover the difference from a run at 8× the samples
# (the error estimate is the larger difference from runs at about half and twice the samples).
SAMPLED = [
    ("quadruped_hoecken", "stride"),
    ("quadruped_hoecken", "minimum stability margin"),
    ("quadruped_hoecken", "foot slip per cycle (all feet)"),
    ("quadruped_hoecken", "duty factor (per leg, mean)"),
    ("hexapod_tripod", "foot slip per cycle (all feet)"),
    ("hexapod_tripod", "stride"),
    ("hoecken", "straight part within 0.1 % of size"),
    ("roberts", "straight part within 0.1 % of size"),
    ("watt", "smallest radius of curvature"),
    ("hoecken", "peak trace acceleration"),
]


@pytest.mark.parametrize(("name", "fig"), SAMPLED, ids=lambda v: str(v))
def test_error_estimates_cover_the_difference_from_eight_times_the_samples(results, name, fig):
    res = results[name]
    n = len(res.time)
    fine = runner.run(res.scene, samples=8 * (n - 1) + 1)
    row, ref = figure(res, fig), figure(fine, fig)
    assert row.error is not None and row.error > 0, row
    assert abs(row.value - ref.value) <= 2 * row.error, (row, ref.value)


def test_the_old_stride_and_slip_discrepancies_are_within_their_errors(results):
    # Issue 12: stride 44.252 at 721 samples and 44.407 at 5761; hexapod slip 6.6e-4 vs 7.8e-4 m.
    stride = figure(results["quadruped_hoecken"], "stride")
    assert stride.value == pytest.approx(44.252, abs=1e-3)
    assert stride.error >= 0.5 * abs(44.407 - 44.252)
    slip = figure(results["hexapod_tripod"], "foot slip per cycle (all feet)")
    assert slip.error >= 0.5 * abs(7.8e-4 - 6.6e-4)


def test_check_counts_share_only_the_ends_with_the_run():
    for n in (8, 9, 361, 721, 800, 5761):
        half, double = figures.check_counts(n)
        assert math.gcd(half - 1, n - 1) == 1 and double == 2 * n - 1
        t = np.linspace(0, 1, n)
        shared = np.intersect1d(np.round(t, 12), np.round(np.linspace(0, 1, half), 12))
        assert len(shared) == 2


def test_format_number():
    assert format_number(44.2523, 0.155) == "44.25"
    assert format_number(0.0014, 1e-7) == "0.00140000"
    assert format_number(6.6e-4, 1.2e-4) == "6.6e-4"
    assert format_number(12741226936709.7) == "1.274e13"
    assert format_number(math.inf) == "∞" and format_number(math.nan) == "NaN"
    assert format_number(-25.0899, 0.01) == "-25.090"
    assert format_number(0.0) == "0"
    # Exact values: up to six digits, no trailing zeros.
    assert format_number(3.0, 0) == "3" and format_number(2 / 3, 0) == "0.666667"
    assert format_number(60.0, 0) == "60" and format_number(1e-9, 0) == "1e-9"


def test_a_geared_drive_names_the_crank_speed_in_the_scene_unit():
    # 50 rpm through 18 → 15 → 14: the crank turns at 50·18/14 rpm (idler 15), not rad/s.
    rows = {
        r[0]: r[1] for r in runner.run(scene.parse(scene.DEFAULT_SCENE, None), samples=31).figures
    }
    crank = 50 * 18 / 14
    assert f"(crank {format_number(crank, 0)} rpm)" in rows["drive"], rows["drive"]


def test_a_straight_path_is_recognised_by_the_core_line_fit():
    """``stage_figures._on_a_line``: every point within 1e-9 of the extent from one line."""
    t = np.linspace(-1.0, 1.0, 101)
    line = np.c_[3.0 + 40.0 * t, -2.0 + 30.0 * t]  # extent 80
    wobble = np.c_[-0.6, 0.8] * (1e-12 * np.sin(7 * t))[:, None]  # off the line by ≤ 1e-12
    assert stage_figures._on_a_line(line + wobble, 80.0)
    bent = line.copy()
    bent[50] += np.array([-0.6, 0.8]) * 1e-6  # one point 1e-6 off the line
    assert not stage_figures._on_a_line(bent, 80.0)
    arc = np.c_[np.cos(t), np.sin(t)]
    assert not stage_figures._on_a_line(arc, 2.0)
    assert not stage_figures._on_a_line(line[:2], 80.0)


def test_synthesis_rows_refuse_a_run_that_is_not_a_synthesis():
    # synthesis_figures asserted (an AssertionError, or an AttributeError under python -O).
    res = figures.Result(scene=scene.Scene("leg", None, ()), time=np.zeros(0), theta=np.zeros(0))
    with pytest.raises(LinkageError, match="not a synthesis run"):
        stage_figures.synthesis_figures(res)
    assert res.figures == []


def test_a_run_that_reaches_a_toggle_has_unbounded_peak_rates():
    # At a double-rocker's limits the rates of a steadily driven crank are unbounded; the
    # sampled ones are NaN there, or round-off a hair away (a rocking slider-crank's exported
    # scene had printed a peak speed of 1.2e8 mm/s "±0").
    from linkage.figures import Result
    from linkage.scene import Scene

    dr = linkage.FourBar(ground=20, crank=15, coupler=10, rocker=20)
    lo, hi = dr.input_limits()
    outs = ("point", "velocity", "acceleration")
    res = Result(
        Scene("dr", None, ("velocity", "acceleration"), units="mm"), np.zeros(0), np.zeros(0)
    )
    res.check_samples = (37,)
    runs = [dr.sweep(np.linspace(lo, hi, n), omega=1.0, outputs=outs) for n in (73, 37)]
    stage_figures.rate_figures(res, runs[0], runs[1:])
    rows = {r[0]: r for r in res.figures}
    assert rows["peak trace speed"][1:3] == ("unbounded (the run reaches a toggle)", "mm/s")
    assert rows["peak trace acceleration"][1:3] == ("unbounded (the run reaches a toggle)", "mm/s²")
    # Away from the limits the peaks are numbers with their error estimates.
    res.figures.clear()
    runs = [dr.sweep(np.linspace(lo + 0.1, hi - 0.1, n), omega=1.0, outputs=outs) for n in (73, 37)]
    stage_figures.rate_figures(res, runs[0], runs[1:])
    speed = {r[0]: r for r in res.figures}["peak trace speed"]
    assert math.isfinite(float(speed[1])) and speed[3].startswith("±")


def test_a_candidate_on_the_edge_of_a_change_point_is_named_so() -> None:
    """A new user's full-turn fits ended on the full-turn condition: "crank-rocker" with s + l
    equal to p + q within 1.7e-5 mm (it can flip branch where its links lie flat), and only a
    transmission angle of 0.0° hinted at it. The class's note says so."""
    from linkage.synthesis import Candidate

    def note(lk: Union[linkage.FourBar, linkage.SliderCrank], cls: str) -> str:
        c = Candidate(lk, 1.0, 1.0, 1.0, (0.0, 6.3), True, cls, 0.0, False, "atlas", np.zeros(9))
        return stage_figures._near_change_point(c, 40.0, "mm")

    edge = linkage.FourBar(ground=70.55, crank=21.0, coupler=69.93, rocker=21.62 + 1.68e-5)
    assert edge.grashof() == "crank-rocker"
    assert note(edge, "crank-rocker") == (
        "; 1.7e-5 mm from a change point (s + l = p + q): it can flip branch where its links "
        "lie flat"
    )
    assert note(linkage.catalog.hoecken(), "crank-rocker") == ""
    slider = linkage.SliderCrank(crank=1.0, coupler=2.0, offset=1.0 - 3e-6)
    assert "from a change point (|offset| + crank = rod)" in note(slider, "crank-slider")
    assert note(linkage.SliderCrank(crank=1.0, coupler=3.0), "crank-slider") == ""
