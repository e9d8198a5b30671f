"""Sliders in scenes, and slider-cranks found by ``[synthesis]`` scenes.

A scene's joint table has ``kind = "slider"`` joints (an RRP dyad on a fixed line or on a line
carried by a link); a run of one agrees with independent constructions (``SliderCrank`` and a
closed form of a block on a turning link). A ``[synthesis]`` scene with ``kind =
"slider-crank"`` (or ``"any"``) finds slider-cranks, and its report — ``candidates.csv``,
``summary.json``, the page and each candidate as a scene to run — describes them: every
exported scene passes ``check`` and, run, draws the target.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

import linkage
from linkage import export, runner, scene, synthesis
from linkage.cli import main
from linkage.synthesis import largest_distance

SLIDER_SCENE = """
name = "slider"
units = "mm"
outputs = ["trajectory", "velocity", "acceleration", "cad", "instant_centres"]

[mechanism]
trace = "P"
joints = [
  {{ name = "O", kind = "fixed", at = [3.0, -2.0] }},
  {{ name = "G", kind = "fixed", at = {g} }},
  {{ name = "A", kind = "crank", centre = "O", radius = 20.0 }},
  {{ name = "B", kind = "slider", pivot = "A", r = 55.0, origin = "G", direction = {d}{reach} }},
  {{ name = "P", kind = "point", on = ["A", "B"], along = 30.0, left = 10.0 }},
]

[drive]
kind = "constant"
rpm = 60.0
cycles = 1
samples = 361
"""


@pytest.mark.parametrize("reach", ["ahead", "behind"])
def test_a_slider_joint_runs_as_the_slider_crank_it_builds(reach: str) -> None:
    # The line through G along (cos γ, sin γ), 6 mm left of O: the same linkage as
    # SliderCrank(offset=6, angle=γ), whose pose is the core's closed form.
    gamma = 0.3
    o = np.array([3.0, -2.0])
    g = o + 6.0 * np.array([-math.sin(gamma), math.cos(gamma)])
    text = SLIDER_SCENE.format(
        g=f"[{float(g[0])!r}, {float(g[1])!r}]",
        d=f"[{math.cos(gamma)!r}, {math.sin(gamma)!r}]",
        reach=f', reach = "{reach}"' if reach == "behind" else "",
    )
    res = runner.run(scene.parse(text))
    assert res.sweep is not None and res.rates is not None
    sc = linkage.SliderCrank(20.0, 55.0, 6.0, (30.0, 10.0), tuple(o), gamma, reach)  # type: ignore[arg-type]
    ref = sc.sweep(res.theta, outputs=("joints", "velocity"), omega=2 * math.pi)
    assert res.sweep.valid.all() and ref.valid.all()
    assert np.abs(res.sweep.joints - ref.joints).max() < 1e-12 * 55
    assert np.abs(res.rates.velocity - ref.velocity).max() < 1e-11 * 55 * 2 * math.pi
    # The slider stays on its line, r from the crank end.
    b, a = res.sweep.joint("B"), res.sweep.joint("A")
    normal = np.array([-math.sin(gamma), math.cos(gamma)])
    assert np.abs((b - g) @ normal).max() < 1e-12 * 55
    assert np.abs(np.hypot(*(b - a).T) - 55.0).max() < 1e-12 * 55


def test_a_slider_on_a_turning_link_agrees_with_its_closed_form(tmp_path: Path) -> None:
    # A block on the crank's own line (through O, along O → A) at 12 from the fixed pivot C:
    # B = O + t u with |B − C| = 12, t = u·(C − O) + √(12² − (u × (C − O))²) (reach ahead).
    text = """
name = "turning"
outputs = ["trajectory"]
[mechanism]
trace = "B"
joints = [
  { name = "O", kind = "fixed", at = [0.0, 0.0] },
  { name = "C", kind = "fixed", at = [5.0, 1.0] },
  { name = "A", kind = "crank", centre = "O", radius = 2.0 },
  { name = "B", kind = "slider", pivot = "C", r = 12.0, origin = "O", link = ["O", "A"] },
]
[drive]
kind = "constant"
rpm = 60.0
cycles = 1
samples = 73
"""
    path = tmp_path / "turning.toml"
    path.write_text(text)
    assert main(["check", str(path)]) == 0
    res = runner.run(scene.load(path))
    assert res.sweep is not None and res.sweep.valid.all()
    th = res.theta
    u = np.stack([np.cos(th), np.sin(th)], axis=1)
    c = np.array([5.0, 1.0])
    along = u @ c
    across = u[:, 0] * c[1] - u[:, 1] * c[0]
    t = along + np.sqrt(12.0**2 - across**2)
    assert np.abs(res.sweep.point - t[:, None] * u).max() < 1e-12 * 12
    # Turned by angle_deg = 90 the line is square to the crank: another linkage, checked alike.
    turned = text.replace('link = ["O", "A"] }', 'link = ["O", "A"], angle_deg = 90.0 }')
    res = runner.run(scene.parse(turned))
    assert res.sweep is not None
    v = np.stack([-np.sin(th), np.cos(th)], axis=1)
    t = v @ c + np.sqrt(12.0**2 - (v[:, 0] * c[1] - v[:, 1] * c[0]) ** 2)
    assert np.abs(res.sweep.point - t[:, None] * v).max() < 1e-12 * 12


def test_a_slider_scene_writes_its_report(tmp_path: Path) -> None:
    text = SLIDER_SCENE.format(g="[0.0, 5.0]", d="[1.0, 0.2]", reach="")
    path = tmp_path / "slider.toml"
    path.write_text(text)
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out), "--quiet"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert {"mechanism.dxf", "mechanism.svg", "trajectory.png", "data.csv"} <= set(s["files"])
    svg = (out / "mechanism.svg").read_text()
    assert svg.count("<polygon") >= 1  # the slider's block


# -- synthesis ----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def slider_atlas(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("atlas") / "sliders"
    return synthesis.Atlas.build(100_000, threads=2, kind="slider-crank").save(folder)


TARGET = linkage.SliderCrank(20.0, 50.0, 5.0, (25.0, 15.0), (10.0, 40.0), 0.3)


def write_target(folder: Path) -> Path:
    s = TARGET.circuit(41)
    points = s.point[s.valid][:-1]
    path = folder / "path.csv"
    np.savetxt(path, points, delimiter=",", fmt="%.12f", header="x,y", comments="")
    return path


def synth_scene(folder: Path, kind: str, atlas: Path | None, top: int = 3) -> Path:
    write_target(folder)
    line = f"atlas = {json.dumps(str(atlas))}\n" if atlas is not None else ""
    path = folder / "fit.toml"
    path.write_text(
        f'name = "fit"\nunits = "mm"\noutputs = ["synthesis", "cad"]\n[synthesis]\n'
        f'points = "path.csv"\nkind = "{kind}"\ntop = {top}\n{line}'
    )
    return path


def test_a_slider_crank_synthesis_scene_finds_it_and_exports_runnable_scenes(
    tmp_path: Path, slider_atlas: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = synth_scene(tmp_path, "slider-crank", slider_atlas)
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out), "--quiet"]) == 0
    s = json.loads((out / "summary.json").read_text())
    run = s["synthesis"]
    assert run["kind"] == "slider-crank"
    cands = run["candidates"]
    size = run["target"]["size"]
    assert cands and all(c["linkage"] == "slider-crank" for c in cands)
    best = cands[0]
    # The target's own linkage, recovered to the file's rounding.
    assert best["error"] < 1e-6 * size and best["full_turn"] is True
    assert best["grashof"] == "crank-slider"
    assert best["crank"] == pytest.approx(20.0, rel=1e-7)
    assert best["coupler"] == pytest.approx(50.0, rel=1e-7)
    assert best["o"] == pytest.approx([10.0, 40.0], abs=1e-6)
    for c in cands:
        assert -180.0 <= c["line_angle_deg"] <= 180.0
        assert c["reach"] in ("ahead", "behind") and "c" not in c and "assembly" not in c
    # candidates.csv: the slider-crank's columns, every value the summary's.
    with open(out / "candidates.csv", encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    names = [n for n, _ in export.candidate_columns("slider-crank")]
    assert [h.split(" [")[0] for h in rows[0]] == names
    assert "pivot_C_x" not in names and "rocker" not in names
    for row, c in zip(rows[1:], cands):
        got = dict(zip(names, row))
        assert float(got["offset"]) == c["offset"] and got["reach"] == c["reach"]
        assert float(got["line_angle"]) == c["line_angle_deg"]
    # Every exported scene passes check, and run draws the target (a rocking crank's scene from
    # limit to limit on one reach: the part it traces lies on the candidate's curve).
    target = np.load(out / "data.npz")["target"]
    for k, c in enumerate(cands, 1):
        # The candidate rebuilt from the summary's numbers, its curve sampled finely (the
        # report's 721-sample curves are polylines 2e-4 mm off the curve near its sharp ends).
        fine = linkage.SliderCrank(
            c["crank"],
            c["coupler"],
            c["offset"],
            tuple(c["point"]),
            tuple(c["o"]),
            math.radians(c["line_angle_deg"]),
            c["reach"],
        ).circuit(200_001)
        curve = fine.point[fine.valid]
        scene_path = out / f"candidate-{k}.toml"
        assert main(["check", str(scene_path)]) == 0
        text = scene_path.read_text()
        assert 'kind = "slider"' in text and 'name = "G"' in text
        res = runner.run(scene.load(scene_path))
        assert res.sweep is not None
        ok = res.sweep.valid
        assert ok.sum() >= len(ok) - 1
        assert largest_distance(res.sweep.point[ok], curve) < 1e-6 * size
        if c["full_turn"]:
            # The run's polyline is within its chords' sag of the curve: a candidate far from the
            # target (the curve-equation stage lists one 3.4 sizes off, its curve large) measures
            # the target against the chords, 1.3e-4 mm from the curve there.
            sag = largest_distance(curve, res.sweep.point[ok])
            assert largest_distance(target, res.sweep.point) == pytest.approx(
                c["error"], abs=1e-6 * size + sag
            )
    # The page names the kind searched and a slider's line.
    page = (out / "index.html").read_text()
    assert "Path synthesis: slider-cranks whose" in page and "slider line" in page
    assert (out / "mechanism.dxf").is_file() and (out / "synthesis.png").is_file()
    capsys.readouterr()


def test_any_kind_lists_both_with_every_column(
    tmp_path: Path, slider_atlas: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # The given atlas serves the slider-cranks; four-bars come from the default atlas.
    path = synth_scene(tmp_path, "any", slider_atlas, top=6)
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out), "--quiet"]) == 0
    cands = json.loads((out / "summary.json").read_text())["synthesis"]["candidates"]
    kinds = {c["linkage"] for c in cands}
    assert cands[0]["linkage"] == "slider-crank" and kinds == {"slider-crank", "fourbar"}
    with open(out / "candidates.csv", encoding="utf-8", newline="") as fh:
        rows = list(csv.DictReader(fh))
    for row, c in zip(rows, cands):
        assert row["linkage"] == c["linkage"]
        if c["linkage"] == "fourbar":
            assert row["reach"] == "" and row["assembly"] == c["assembly"]
            assert float(row["pivot_C_x [mm]"]) == c["c"][0]
        else:
            assert row["assembly"] == "" and row["pivot_C_x [mm]"] == ""
            assert float(row["offset [mm]"]) == c["offset"]
    for k in range(1, len(cands) + 1):
        assert main(["check", str(out / f"candidate-{k}.toml")]) == 0
    capsys.readouterr()


def test_an_atlas_of_the_other_kind_is_a_located_error(
    tmp_path: Path, slider_atlas: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = synth_scene(tmp_path, "fourbar", slider_atlas)
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"linkage: error: {path}:") and "[synthesis] atlas:" in err, err
    assert "slider-crank" in err and not out.exists()


def test_a_candidate_through_a_crank_limit_is_exported_with_its_limits_and_branches(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # 40% of an offset crank-slider's curve as an open target: the best fit is a rocker-slider
    # (a cognate, crank 15) whose matched part passes a crank limit, going on along the other
    # reach. Its scene must say the true limits, draw the branch with most of the target, and
    # say how many points the other reach draws.
    sc = linkage.SliderCrank(crank=10, coupler=32, offset=6, point=(12, 9))
    arc = sc.circuit(401).point[50:210] @ [[0.6, 0.8], [-0.8, 0.6]] + (250, 40)
    np.savetxt(tmp_path / "open.csv", arc[::4], delimiter=",", fmt="%.12g")
    path = tmp_path / "open.toml"
    path.write_text(
        'name = "open"\nunits = "mm"\n[synthesis]\npoints = "open.csv"\n'
        'kind = "slider-crank"\nclosed = false\ntop = 2\n'
    )
    out = tmp_path / "report"
    assert main(["run", str(path), "--out", str(out), "--quiet"]) == 0
    res = runner.run(scene.load(path))
    assert res.synthesis is not None
    target = res.synthesis.target
    size = res.synthesis.size
    through = [(k, c) for k, c in enumerate(res.synthesis.candidates, 1) if c.through_limit]
    assert through, "the search should find a rocker-slider through a limit here"
    for k, c in through:
        text = (out / f"candidate-{k}.toml").read_text()
        # The comment lines, unwrapped.
        header = " ".join(line[2:] for line in text.splitlines() if line.startswith("# "))
        a, b = (math.degrees(v) for v in export.crank_limits(c))
        assert f"between its limits {a:.3f}° and {b:.3f}°" in header
        counts = export.branch_points(c, target)
        side = export.candidate_side(c, target)
        assert counts[side] == max(counts.values()) and sum(counts.values()) == len(target)
        other = next(r for r in counts if r != side)
        n = len(target)
        assert f"this scene draws {counts[side]} of the target's {n} points" in header
        assert f'reach = "{other}" draws the other {counts[other]}' in header
        assert f'reach = "{side}" }}' in text
        # Run as written, the scene draws its share of the target (and the other reach the
        # rest), on the candidate's curve.
        drawn = runner.run(scene.load(out / f"candidate-{k}.toml")).sweep
        assert drawn is not None
        near = _core_distances(target, drawn.point[drawn.valid])
        assert int(np.sum(near <= 1e-6 * size + 2e-3 * size)) >= counts[side] - 1
        flipped = text.replace(f'reach = "{side}" }}', f'reach = "{other}" }}')
        rest = runner.run(scene.parse(flipped)).sweep
        assert rest is not None
        near = _core_distances(target, rest.point[rest.valid])
        assert int(np.sum(near <= 1e-6 * size + 2e-3 * size)) >= counts[other] - 1
    capsys.readouterr()


def _core_distances(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    from linkage import _core

    return _core.synthesis.polyline_distance(
        np.ascontiguousarray(points, dtype=np.float64), np.ascontiguousarray(path)
    )
