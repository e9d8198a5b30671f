"""``[synthesis]`` scenes: ``linkage run`` searches four-bars for target points and writes
``synthesis.png``, ``candidates.csv``, every candidate as a scene that ``linkage check`` accepts
and that traces the candidate's curve, ``summary.json`` and ``index.html``; a search that finds
nothing is one located line and writes nothing; ``check`` reads the points but never searches.

The example uses the default atlas (built once into the cache folder, about 3 s); the other
scenes here use a small atlas of their own.
"""

from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import linkage
from linkage import runner, scene, synthesis
from linkage.cli import main
from linkage.report import MARKER
from linkage.synthesis import largest_distance

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "synthesis_foot.toml"
SCHEMA = ROOT / "docs" / "summary-schema.md"


@pytest.fixture(scope="module")
def atlas_folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    # Small: the linkages here are the Hoecken foot path's (see test_synthesis.py).
    return synthesis.Atlas.build(40_000, threads=2).save(tmp_path_factory.mktemp("atlas") / "a")


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("example") / "report"
    assert main(["run", str(EXAMPLE), "--out", str(out), "--quiet"]) == 0
    return out


def summary_of(folder: Path) -> dict:
    return json.loads((folder / "summary.json").read_text(encoding="utf-8"))


def test_the_example_writes_the_synthesis_report(report: Path) -> None:
    s = summary_of(report)
    cands = s["synthesis"]["candidates"]
    scenes = {f"candidate-{k}.toml" for k in range(1, len(cands) + 1)}
    files = {"synthesis.png", "candidates.csv", "index.html", "summary.json", "data.npz"}
    files |= {"mechanism.dxf", "mechanism.svg"} | scenes  # the example asks for cad
    assert set(s["files"]) == files
    marker = json.loads((report / MARKER).read_text())
    assert set(marker["files"]) == files == {p.name for p in report.iterdir()} - {MARKER}
    assert s["outputs"] == ["synthesis", "cad"] and s["length_unit"] == "mm"
    # The target is the Hoecken foot path 100 mm down: the best candidate draws it exactly (to
    # the file's rounding, 1e-6 mm) with a full-turn crank — Hoecken's linkage or its Roberts
    # cognate of the same class, on two of the pivots (0, −100), (20, −100), (40, −100) — and
    # Hoecken's own linkage is among the candidates.
    best = cands[0]
    assert best["error"] < 1e-5 and best["rms"] <= best["error"]
    assert best["grashof"] == "crank-rocker" and best["full_turn"] is True
    pivots = np.array([[0.0, -100.0], [20.0, -100.0], [40.0, -100.0]])
    for p in (best["o"], best["c"]):
        assert np.min(np.abs(pivots - p).max(axis=1)) < 1e-5, p

    def is_hoecken(c: dict) -> bool:  # type: ignore[type-arg]
        got = [*c["o"], *c["c"], *(c[k] for k in ("ground", "crank", "coupler", "rocker"))]
        want = [0.0, -100.0, 20.0, -100.0, 20.0, 10.0, 25.0, 25.0]
        return bool(np.allclose([*got, *c["point"]], [*want, 50.0, 0.0], atol=1e-5))

    assert any(is_hoecken(c) for c in cands), [(c["o"], c["c"]) for c in cands]
    # Every candidate meets the example's constraints, best first.
    assert len(cands) >= 2
    for c in cands:
        assert c["full_turn"] is True and c["min_transmission_deg"] >= 15.0
        assert c["crank_range_deg"][1] - c["crank_range_deg"][0] == pytest.approx(360.0)
    assert [c["error"] for c in cands] == sorted(c["error"] for c in cands)
    target = s["synthesis"]["target"]
    assert target == {
        "points": 36,
        "closed": True,
        "size": pytest.approx(16.4, abs=0.05),
        "file": "foot_path.csv",
    }
    assert s["synthesis"]["constraints"]["min_transmission_deg"] == 15.0


def test_the_figures_are_typed_with_units_and_three_digits(report: Path) -> None:
    s = summary_of(report)
    rows = {f["figure"]: f for f in s["figures"]}
    n = len(s["synthesis"]["candidates"])
    assert rows["candidates found"]["value"] == n and rows["candidates found"]["exact"]
    assert rows["target"]["value"] == 36
    for k in range(1, n + 1):
        err = rows[f"candidate {k}: max error"]
        assert err["unit"] == "mm" and isinstance(err["value"], float)
        assert err["value"] == s["synthesis"]["candidates"][k - 1]["error"]
        digits = err["text"].split("e")[0].replace(".", "").lstrip("0")
        assert len(digits) <= 3, err["text"]
        assert rows[f"candidate {k}: RMS error"]["unit"] == "mm"
        assert rows[f"candidate {k}: Grashof class"]["value"] == "crank-rocker"
        lo, hi = rows[f"candidate {k}: crank range"]["value"]
        assert rows[f"candidate {k}: crank range"]["unit"] == "deg" and hi - lo == pytest.approx(
            360.0, abs=0.2
        )
        mu = rows[f"candidate {k}: min transmission angle"]
        assert mu["unit"] == "deg" and mu["value"] >= 15.0
        # The values in full, as the candidate's own record (and candidates.csv) has them; only
        # the text is rounded.
        cand = s["synthesis"]["candidates"][k - 1]
        assert [lo, hi] == cand["crank_range_deg"] and mu["value"] == cand["min_transmission_deg"]
        assert mu["text"] == f"{mu['value']:.1f}"
    time = rows["search time"]
    assert time["unit"] == "s" and time["value"] > 0
    # An "atlas" stage too when the default atlas was not in the cache yet (a fresh machine).
    assert set(s["stages_s"]) - {"atlas"} == {"build", "synthesis", "report"}
    # The figures come in the order of the terminal's table: count, candidates, time.
    names = [f["figure"] for f in s["figures"]]
    assert names.index("candidates found") < names.index("candidate 1: max error")
    assert names[-1] == "search time"


def test_the_plot_shows_the_target_and_the_curves(report: Path) -> None:
    with Image.open(report / "synthesis.png") as im:
        assert im.width >= 600 and im.height >= 400
        rgb = np.asarray(im.convert("RGB"), dtype=int)
    assert rgb.std() > 5
    # The best candidate's curve in the first line colour (tab:blue) and the second's (orange):
    # the second is a Roberts cognate drawing the same curve, under the best but for its edges
    # and its legend line.
    for colour, least in (((0x1F, 0x77, 0xB4), 60), ((0xFF, 0x7F, 0x0E), 20)):
        near = np.abs(rgb - np.array(colour)).sum(axis=2) < 40
        assert near.sum() > least, colour


def test_candidates_csv_has_units_and_every_candidate(report: Path) -> None:
    with open(report / "candidates.csv", encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    head, body = rows[0], rows[1:]
    for column in (
        "rank",
        "error [mm]",
        "rms [mm]",
        "grashof",
        "crank_from [deg]",
        "crank_to [deg]",
        "min_transmission [deg]",
        "pivot_O_x [mm]",
        "pivot_C_y [mm]",
        "ground [mm]",
        "crank [mm]",
        "coupler [mm]",
        "rocker [mm]",
        "point_along [mm]",
        "point_left [mm]",
        "assembly",
        "scene",
    ):
        assert column in head, column
    cands = summary_of(report)["synthesis"]["candidates"]
    assert len(body) == len(cands)
    for row, c in zip(body, cands):
        got = dict(zip(head, row))
        assert int(got["rank"]) == c["rank"]
        assert float(got["error [mm]"]) == c["error"]  # full precision
        assert float(got["crank [mm]"]) == c["crank"]
        assert got["scene"] == c["scene"] and got["assembly"] == c["assembly"]


def test_every_exported_candidate_passes_check_and_draws_its_curve(report: Path, capsys) -> None:
    data = np.load(report / "data.npz")
    target, curves = data["target"], data["curves"]
    cands = summary_of(report)["synthesis"]["candidates"]
    for k, c in enumerate(cands, 1):
        path = report / f"candidate-{k}.toml"
        assert main(["check", str(path)]) == 0
        assert capsys.readouterr().out.startswith(f"ok: synthesis-foot-candidate-{k}:")
        sc = scene.load(path)
        assert sc.mechanism is not None and sc.drive["kind"] == "constant"
        res = runner.run(sc)
        assert res.sweep is not None and res.sweep.valid.all()
        trace = res.sweep.point
        # One crank turn draws the candidate's coupler curve, in the target's frame.
        assert largest_distance(trace, curves[k - 1]) < 1e-6
        assert largest_distance(target, trace) == pytest.approx(c["error"], abs=1e-3)
        # The scene carries the target as its reference points; the run measures their
        # distance from the trace on its own, to the candidate's error.
        np.testing.assert_allclose(res.arrays["reference"], target, rtol=0, atol=1e-9)
        row = next(r for r in res.figures if r[0] == "reference points to the trace")
        assert row.value == pytest.approx(c["error"], rel=1e-3, abs=1e-9)
        assert row.error is not None and row.error < 1e-6
    # The best one is the linkage the foot path came from.
    assert largest_distance(
        target, runner.run(scene.load(report / "candidate-1.toml")).sweep.point
    ) < (1e-5)


def test_the_page_shows_the_figures_the_candidates_and_the_plot(report: Path) -> None:
    text = (report / "index.html").read_text(encoding="utf-8")
    s = summary_of(report)
    tables = re.findall(r"<table class=figures(.*?)</table>", text, re.S)
    assert len(tables) == 2
    assert tables[0].count("<tr>") == len(s["figures"]) + 1  # and the header
    assert tables[1].startswith(" id=candidates")
    assert tables[1].count("<tr>") == len(s["synthesis"]["candidates"]) + 1
    assert "<code>candidate-1.toml</code>" in text  # the note names each candidate's scene
    assert 'alt="synthesis.png" src="data:image/png;base64,' in text
    assert "<script" not in text
    refs = re.findall(r"""(?:src|href|url)\s*[=(]\s*["']?([^"')\s>]*)""", text)
    assert refs and all(r.startswith("data:") for r in refs), refs


def free_scene(tmp_path: Path, atlas: Path, extra: str = "", outputs: str = "") -> Path:
    """The example's target, with ``extra`` settings, the given atlas and no outputs line."""
    (tmp_path / "foot.csv").write_text((ROOT / "examples" / "foot_path.csv").read_text())
    path = tmp_path / "free.toml"
    path.write_text(
        f'name = "free"\nunits = "mm"\n{outputs}\n[synthesis]\npoints = "foot.csv"\n'
        f"atlas = {json.dumps(str(atlas))}\n{extra}"
    )
    return path


def test_cranks_that_rock_are_exported_driven_between_their_limits(
    tmp_path: Path, atlas_folder: Path, capsys
) -> None:
    path = free_scene(tmp_path, atlas_folder)
    sc = scene.load(path)
    assert sc.outputs == ("synthesis",)  # the default
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out), "--quiet"]) == 0
    s = summary_of(out)
    assert "mechanism.dxf" not in s["files"]  # cad not asked for
    cands = s["synthesis"]["candidates"]
    rocking = [k for k, c in enumerate(cands, 1) if not c["full_turn"]]
    assert rocking, "the unconstrained search should find linkages whose crank rocks"
    curves = np.load(out / "data.npz")["curves"]
    for k in rocking:
        path = out / f"candidate-{k}.toml"
        assert main(["check", str(path)]) == 0
        text = path.read_text()
        assert "rocks between" in text and "duration = " in text
        # Driven steadily to its limits, its rates are unbounded there: none is asked for (a
        # trial's run had printed a peak speed of 1.2e8 mm/s ±0 for a 27 mm linkage).
        assert scene.load(path).outputs == ("trajectory", "animation", "cad")
        res = runner.run(scene.load(path))
        assert not any(r[0].startswith("peak") for r in res.figures)
        assert res.sweep is not None and res.sweep.valid.any()
        lo, hi = cands[k - 1]["crank_range_deg"]
        theta = np.degrees(res.theta[-1] - res.theta[0])
        assert theta == pytest.approx(hi - lo, rel=1e-9)
        # From limit to limit on one assembly: half the circuit, on the candidate's curve.
        ok = res.sweep.valid
        assert (
            largest_distance(res.sweep.point[ok], curves[k - 1])
            < 1e-3 * s["synthesis"]["target"]["size"]
        )
    capsys.readouterr()


def test_a_search_that_finds_nothing_is_one_located_line_and_writes_nothing(
    tmp_path: Path, atlas_folder: Path, capsys
) -> None:
    # No full-turn crank keeps its transmission angle within 1° of 90° all the way round.
    path = free_scene(tmp_path, atlas_folder, "full_turn = true\nmin_transmission_deg = 89.0\n")
    assert main(["check", str(path)]) == 0
    capsys.readouterr()
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out)]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    # One line, at the key of the first constraint the closest fit fails, naming the count each
    # constraint removed and that fit's error.
    (line,) = captured.err.splitlines()
    found = re.fullmatch(
        rf"linkage: error: {re.escape(str(path))}:(\d+): \[synthesis\] (\w+): no valid four-bar "
        r"found: every valid fit fails a constraint \(fits failing (.+)\); the closest, error "
        r"(\S+) mm, fails (.+): loosen (it|them), or refine more atlas matches \(refine\)",
        line,
    )
    assert found is not None, line
    at, key, counts, error, fails = found.group(1, 2, 3, 4, 5)
    assert {"full_turn": "7", "min_transmission_deg": "8"}[key] == at
    assert fails.split(" (")[0] == key  # each failed constraint with the fit's value
    assert re.fullmatch(r"(full_turn: \d+, )?min_transmission_deg: \d+", counts), counts
    assert 0 <= float(error) < 1.0  # mm, on a 60 mm foot path
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["foot.csv", "free.toml"]


def test_check_reads_the_points_but_never_searches(monkeypatch, capsys) -> None:
    def refuse(*_a: object, **_k: object) -> None:
        raise AssertionError("check must not search")

    monkeypatch.setattr(synthesis, "path", refuse)
    assert main(["check", str(EXAMPLE)]) == 0
    assert capsys.readouterr().out == "ok: synthesis-foot: outputs synthesis, cad\n"


def test_points_are_relative_to_the_scene_or_the_working_directory(
    tmp_path: Path, monkeypatch, atlas_folder: Path
) -> None:
    text = EXAMPLE.read_text()
    monkeypatch.chdir(tmp_path)
    with pytest.raises(scene.SceneError) as info:
        scene.parse(text)  # no path: relative to the working directory, which has no such file
    assert str(info.value) == (
        "<scene>:12: [synthesis] points: cannot read 'foot_path.csv' (relative to the scene's "
        "folder): No such file or directory"
    )
    assert scene.parse(text, EXAMPLE).synthesis is not None
    monkeypatch.chdir(EXAMPLE.parent)
    assert scene.parse(text).synthesis is not None
    # Inline points, any order of keys.
    fb = linkage.catalog.hoecken()
    pts = fb.circuit(121).point[:-1][::4]
    inline = ", ".join(f"[{float(x)!r}, {float(y)!r}]" for x, y in pts)
    sc = scene.parse(
        f'name = "inline"\n[synthesis]\ntop = 1\natlas = {json.dumps(str(atlas_folder))}\n'
        f"points = [{inline}]\n"
    )
    res = runner.run(sc, samples=101)
    assert res.synthesis is not None and len(res.synthesis.candidates) == 1
    assert res.synthesis.candidates[0].error < 1e-9 * 20
    assert res.synthesis.curves[0].shape == (101, 2)
    assert math.isclose(res.synthesis.candidates[0].linkage.ground, 20.0, rel_tol=1e-9)


def test_the_summary_schema_documents_the_synthesis_fields(report: Path) -> None:
    doc = SCHEMA.read_text(encoding="utf-8")
    s = summary_of(report)["synthesis"]
    for key in [*s, *s["target"], *s["constraints"], *s["candidates"][0]]:
        assert f"`{key}`" in doc, key
    for name in ("synthesis.png", "candidates.csv", "candidate-<k>.toml"):
        assert name in doc, name


def test_samples_beyond_the_memory_cap_are_refused_before_searching(tmp_path: Path, capsys) -> None:
    out = tmp_path / "report"
    assert main(["run", str(EXAMPLE), "--out", str(out), "--samples", "100000000"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("linkage: error: samples: 100000000 samples of 5 coupler curves")
    assert "GiB limit; at most" in err and len(err.splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("scale", [1.0, 8e3])
def test_the_plot_keeps_its_labels_in_the_figure_and_its_legend_in_rank_order(
    tmp_path: Path, atlas_folder: Path, scale: float
) -> None:
    # At 8e3 the foot path spans −840000 … 360000 mm: the y tick labels are wide, and the
    # axis label must still lie inside the figure (it was cut off the left edge).
    from linkage import report as report_module

    foot = np.loadtxt(ROOT / "examples" / "foot_path.csv", delimiter=",", skiprows=1)
    np.savetxt(tmp_path / "foot.csv", foot * scale, delimiter=",")
    path = tmp_path / "big.toml"
    # A long scene name: the title had run off both edges of the figure.
    name = "a-foot-path-for-the-hind-legs-of-the-big-walker-drawn-at-scale"
    path.write_text(
        f'name = "{name}"\nunits = "mm"\n[synthesis]\npoints = "foot.csv"\n'
        f"atlas = {json.dumps(str(atlas_folder))}\ntop = 4\n"
    )
    res = runner.run(scene.load(path))
    fig = report_module._synthesis(res)
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)
    (ax,) = fig.axes
    (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
    texts = [
        ax.yaxis.label,
        ax.xaxis.label,
        *(t for t in ax.get_yticklabels() if y0 <= t.get_position()[1] <= y1),
        *(t for t in ax.get_xticklabels() if x0 <= t.get_position()[0] <= x1),
    ]
    width = fig.bbox.width
    for t in [*texts, ax.title]:
        box = t.get_window_extent(renderer)
        assert box.x0 >= 0 and box.x1 <= width and box.y0 >= 0, (t.get_text(), box, width)
    (whole,) = fig.legends
    box = whole.get_window_extent(renderer)
    assert box.x0 >= 0 and box.x1 <= width, (box, width)
    # A curve that leaves the view says so in its legend entry, and only such a curve.
    for line in ax.lines:
        if line.get_label().startswith("#"):
            x, y = (np.asarray(v, dtype=float) for v in line.get_data())
            out = bool(np.any((x < x0) | (x > x1) | (y < y0) | (y > y1)))
            assert out == line.get_label().endswith("(leaves the view)"), line.get_label()
    # Each entry names the stage that found its candidate.
    assert res.synthesis is not None
    named = {
        line.get_label().split(":")[0]: line.get_label()
        for line in ax.lines
        if line.get_label().startswith("#")
    }
    for k, c in enumerate(res.synthesis.candidates[:4], 1):
        assert f", {synthesis.source_text(c.source)}" in named[f"#{k}"], named
    # The legend reads down its columns: the target, then #1, #2, … in rank order.
    (legend,) = fig.legends
    entries = [(t.get_window_extent(renderer), t.get_text()) for t in legend.get_texts()]
    down_columns = sorted(entries, key=lambda e: (round(e[0].x0), -e[0].y0))
    ranks = [text.split(":")[0] for _, text in down_columns]
    assert ranks[0].startswith("target") and len(ranks) == 5, ranks
    assert ranks[1:] == [f"#{k}" for k in range(1, 5)], ranks


def test_a_curve_outside_the_plot_is_named_in_the_legend(
    tmp_path: Path, atlas_folder: Path
) -> None:
    """The view is set by the target and the best candidate; a worse candidate's curve far from
    the target (a poor fit at a large scale) would leave it without a word."""
    from linkage import report as report_module

    path = tmp_path / "foot.toml"
    foot = ROOT / "examples" / "foot_path.csv"
    path.write_text(
        f'name = "foot"\nunits = "mm"\n[synthesis]\npoints = {json.dumps(str(foot))}\n'
        f"atlas = {json.dumps(str(atlas_folder))}\ntop = 3\n"
    )
    res = runner.run(scene.load(path))
    run = res.synthesis
    assert run is not None and len(run.curves) == 3
    run.curves[2] = run.curves[2] + np.array([0.0, 40.0 * synthesis.target_size(run.target)])
    fig = report_module._synthesis(res)
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    flagged = [t.split(":")[0] for t in labels if t.endswith("(leaves the view)")]
    assert flagged == ["#3"], labels


def test_a_scene_sets_how_many_matches_are_refined(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """``refine`` is the search's depth (``top`` had been the only knob a scene had)."""
    seen: dict[str, object] = {}

    def spy(points, **kw):  # type: ignore[no-untyped-def]
        seen.update(kw)
        return synthesis.Candidates()

    monkeypatch.setattr(synthesis, "path", spy)
    path = tmp_path / "deep.toml"
    path.write_text(
        'name = "deep"\nunits = "mm"\n[synthesis]\n'
        "points = [[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 1.5]]\nrefine = 32\n"
    )
    with pytest.raises(linkage.LinkageError, match="no valid four-bar found"):
        runner.run(scene.load(path))
    assert seen["refine"] == 32


def test_a_mechanism_scene_measures_its_reference_points(tmp_path: Path) -> None:
    # Points on Hoecken's coupler curve between the run's samples, one moved 0.25 mm along the
    # curve's normal: the figure is that 0.25 mm, with its error estimate, from a CSV file
    # relative to the scene's folder.
    fb = linkage.catalog.hoecken()
    on = fb.sweep(np.array([0.011, 0.9, 2.5, 4.2, 5.77]), omega=1.0, outputs=("point", "velocity"))
    t = on.velocity[2] / np.linalg.norm(on.velocity[2])
    points = on.point.copy()
    points[2] += 0.25 * np.array([-t[1], t[0]])
    (tmp_path / "ref").mkdir()
    np.savetxt(tmp_path / "ref" / "foot.csv", points, delimiter=",", header="x,y", comments="")
    path = tmp_path / "leg.toml"
    path.write_text(
        'name = "leg"\nunits = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
        'reference = "ref/foot.csv"\n[drive]\nkind = "constant"\nrpm = 60\nsamples = 181\n'
    )
    res = runner.run(scene.load(path))
    row = next(r for r in res.figures if r[0] == "reference points to the trace")
    assert row.value == pytest.approx(0.25, abs=1e-9)
    assert row.error is not None and row.error < 1e-9
    assert row[2] == "mm" and "largest distance of the 5 points" in row[3]
    # Without the moved point, the points lie on the path: the chords of the run's 181 samples
    # (2° apart) had put them up to ~1e-3 mm off it.
    np.savetxt(tmp_path / "ref" / "foot.csv", on.point, delimiter=",", header="x,y", comments="")
    res = runner.run(scene.load(path))
    row = next(r for r in res.figures if r[0] == "reference points to the trace")
    assert 0 <= row.value < 1e-8 and largest_distance(on.point, res.sweep.point) > 1e-5


def test_a_reference_point_far_off_is_counted_not_drawn(tmp_path: Path) -> None:
    # One point a thousand kilometres off (other units, another frame) would have shrunk the
    # plot to a dot: the view keeps to the linkage and the legend counts it.
    from linkage import export, report

    path = tmp_path / "leg.toml"
    path.write_text(
        'name = "leg"\nunits = "mm"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
        "reference = [[20, 48.99], [1e9, 1e9]]\n"
        '[drive]\nkind = "constant"\nrpm = 60\nsamples = 181\n'
    )
    res = runner.run(scene.load(path))
    fig = report._trajectory(res, export.drawing_of(res))
    (ax,) = fig.axes
    assert ax.get_xlim()[1] < 1e3 and ax.get_ylim()[1] < 1e3
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(
        t.startswith("reference points (2), within") and "(1 off the plot)" in t for t in labels
    )
