"""The ``linkage`` command and its scenes: the default run and every example write the files
they promise; only the asked-for stages run; bad scenes fail with located messages and write
nothing."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import linkage
import linkage.report_folder
from linkage.cli import main
from linkage.report import MARKER

EXAMPLES = sorted((Path(__file__).parent.parent / "examples").glob("*.toml"))
PLOTS = {
    "trajectory": ["trajectory.png"],
    "velocity": ["rates.png"],
    "acceleration": ["rates.png"],
    "torque": ["torque.png"],
    "cam": ["cam.png"],
    "gait": ["gait.png"],
    "stability": ["stability.png"],
    "slip": ["slip.png"],
    "animation": ["animation.gif"],
}


def expected_files(outputs, summary=None):
    # Every report: the page and the data; the CAD drawing when asked for.
    files = {"index.html", "data.csv", "data.npz", "summary.json"}
    if "synthesis" in outputs:
        # A synthesis report: the plot, the candidates' table and each one as a scene.
        assert summary is not None
        scenes = {c["scene"] for c in summary["synthesis"]["candidates"]}
        files = {"index.html", "synthesis.png", "candidates.csv", "data.npz", "summary.json"}
        files |= scenes
    if "cad" in outputs:
        files |= {"mechanism.dxf", "mechanism.svg"}
    for o in outputs:
        files.update(PLOTS.get(o, []))
    return files


def report_files(folder: Path) -> set[str]:
    """The report's files: everything in the folder but the tool's marker (which must be there
    and list exactly those files)."""
    names = {p.name for p in folder.iterdir()}
    assert MARKER in names, f"{folder} has no {MARKER}"
    marker = json.loads((folder / MARKER).read_text())
    assert marker["tool"] == "linkage" and set(marker["files"]) == names - {MARKER}
    # A folder a killed run left is swept only if it holds nothing but such names.
    unknown = [n for n in names if not linkage.report_folder.TOOL_FILE.fullmatch(n)]
    assert unknown == [], f"add {unknown} to linkage.report_folder.TOOL_FILE"
    return names - {MARKER}


def check_images(folder: Path):
    for png in folder.glob("*.png"):
        with Image.open(png) as im:
            assert im.width >= 300 and im.height >= 150, png
            pixels = np.asarray(im.convert("L"), dtype=float)
            assert pixels.std() > 5, f"{png} is blank"
    for gif in folder.glob("*.gif"):
        with Image.open(gif) as im:
            assert im.n_frames >= 2, gif


def run(tmp_path, *args):
    out = tmp_path / "report"
    code = main(["run", *args, "--out", str(out), "--samples", "61", "--frames", "4"])
    return code, out


def test_default_run_writes_its_report(tmp_path, capsys):
    code, out = run(tmp_path)
    assert code == 0
    text = capsys.readouterr().out
    assert "quadruped-hoecken" in text and "minimum stability margin" in text
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["files"]) == expected_files(summary["outputs"])
    assert report_files(out) == expected_files(summary["outputs"])
    check_images(out)
    # The default is the source's quadruped: two or four feet down, statically stable.
    figures = {f["figure"]: f["value"] for f in summary["figures"]}
    assert figures["feet down (min / max)"] == [2, 4]
    assert figures["minimum stability margin"] > 0


@pytest.mark.parametrize("columns", [100, 80])
def test_the_table_fits_the_terminal(tmp_path, capsys, monkeypatch, columns):
    """The default run's table (a long drive description, long error estimates: 160 columns
    unwrapped) fits the terminal's width, its long cells wrapped at spaces onto lines of their
    own; every figure's name is still printed whole on the first line of its row."""
    monkeypatch.setenv("COLUMNS", str(columns))
    code, _ = run(tmp_path)
    assert code == 0
    lines = capsys.readouterr().out.splitlines()
    rule = [k for k, line in enumerate(lines) if line.startswith("----")]
    table = lines[rule[0] : rule[-1] + 1]
    assert max(len(line) for line in table) <= columns, table
    assert any(line.startswith("drive ") for line in table)
    joined = " ".join(" ".join(line.split()) for line in table)
    assert "constant 50 rpm through 18→15→14 gears" in joined, table


@pytest.mark.parametrize("scene", EXAMPLES, ids=lambda p: p.stem)
def test_every_example_scene(scene, tmp_path):
    code, out = run(tmp_path, str(scene))
    assert code == 0
    summary = json.loads((out / "summary.json").read_text())
    assert report_files(out) == expected_files(summary["outputs"], summary)
    check_images(out)
    data = np.load(out / "data.npz")
    if "synthesis" in summary["outputs"]:
        # --samples sets the samples of each candidate's coupler curve.
        assert data["curves"].shape[1:] == (61, 2)
    else:
        assert len(data["time"]) == 61


def test_trajectory_only_runs_no_other_stage_and_the_printed_times_add_up(tmp_path, capsys):
    scene = tmp_path / "t.toml"
    scene.write_text(
        'name = "t"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
        '[drive]\nkind = "constant"\nomega = 1.0\n'
    )
    code, out = run(tmp_path, str(scene))
    assert code == 0
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["stages_s"]) == {"build", "trajectory", "second resolution", "report"}
    assert report_files(out) == expected_files(["trajectory"])
    data = np.load(out / "data.npz")
    assert "velocity" not in data and "torque" not in data
    # The printed stage times, the data files' and the time outside the stages add up to the
    # total (each row rounded to 0.1 ms).
    ms = {}
    for line in capsys.readouterr().out.splitlines():
        parts = line.split()
        if "ms" in parts and line.startswith(("stage: ", "outside the stages", "total")):
            value = parts[parts.index("ms") - 1]
            ms[line[: line.index(value)].strip()] = float(value)
    assert "stage: data files" in ms and "outside the stages" in ms, ms
    parts_sum = sum(v for k, v in ms.items() if k != "total")
    assert abs(parts_sum - ms["total"]) <= 0.05 * len(ms) + 1e-9, ms


BAD = [
    ('outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n', 1, "drive", "missing"),
    (
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoeken"\n[drive]\nkind = "constant"\nomega = 1\n',
        3,
        "catalog",
        "did you mean 'hoecken'",
    ),
    (
        'outputs = ["trajectory"]\n[mechanism]\nground = 20\ncrank = -10\ncoupler = 25\nrocker = 25\n[drive]\nkind = "constant"\nomega = 1\n',
        4,
        "crank",
        "must be positive",
    ),
    (
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "constant"\nrpm = "fast"\n',
        6,
        "rpm",
        "must be a finite number",
    ),
    (
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "constant"\nrpm = 50\nduty_factor = 0.5\n',
        7,
        "duty_factor",
        "contradictory drive",
    ),
    (
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "constant"\nrpm = 50\nomega = 5\n',
        6,
        "rpm",
        "exactly one of rpm",
    ),
    (
        'outputs = ["trajectory", "torque"]\n[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "constant"\nomega = 1\n',
        1,
        "outputs",
        "needs link masses",
    ),
    (
        'outputs = ["trajectry"]\n[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "constant"\nomega = 1\n',
        1,
        "outputs",
        "did you mean 'trajectory'",
    ),
    (
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\nscael = 2\n[drive]\nkind = "constant"\nomega = 1\n',
        4,
        "scael",
        "did you mean 'scale'",
    ),
    (
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "program"\n',
        4,
        "segments",
        "missing",
    ),
    ('outputs = ["trajectory"\n', 1, "", "not valid TOML"),
    (
        'outputs = ["gait"]\n[walker]\nlegs = [\n  { name = "L", catalog = "hokken", mount = [0, 0, 0] },\n]\n[drive]\nkind = "constant"\nomega = 1\n',
        4,
        "catalog",
        "did you mean 'hoecken'",
    ),
    (
        'outputs = ["gait"]\n[walker]\nlegs = [\n  { name = "L", catalog = "hoecken" },\n]\n[drive]\nkind = "constant"\nomega = 1\n',
        4,
        "mount",
        "missing",
    ),
    (
        'outputs = ["gait"]\n[walker]\nmodel = "hexapod_tripod"\ngait = "tripod"\nphases_deg = [0, 180]\n[drive]\nkind = "constant"\nomega = 1\n',
        5,
        "phases_deg",
        "not both",
    ),
]


@pytest.mark.parametrize("text, line, key, message", BAD)
def test_bad_scenes_fail_with_file_line_and_key(tmp_path, capsys, text, line, key, message):
    scene = tmp_path / "bad.toml"
    scene.write_text(text)
    out = tmp_path / "report"
    assert main(["run", str(scene), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{scene}:{line}:" in err, err
    assert key in err and message in err, err
    assert not out.exists()
    assert main(["check", str(scene)]) == 2


def test_existing_report_is_not_overwritten_without_force(tmp_path, capsys):
    out = tmp_path / "report"
    out.mkdir()
    keep = out / "mine.txt"
    keep.write_text("user data")
    # A folder linkage did not write is refused with and without --force.
    for extra in ([], ["--force"]):
        assert main(["run", "--out", str(out), "--samples", "31", "--frames", "2", *extra]) == 2
        err = capsys.readouterr().err
        assert str(out) in err and "not a report written by linkage" in err, err
        assert keep.read_text() == "user data"
        assert {p.name for p in out.iterdir()} == {"mine.txt"}
    # A report linkage wrote is refused without --force and replaced with it.
    keep.unlink()
    out.rmdir()
    assert main(["run", "--out", str(out), "--samples", "31", "--frames", "2", "--quiet"]) == 0
    first = (out / MARKER).read_text()
    assert main(["run", "--out", str(out), "--samples", "31", "--frames", "2"]) == 2
    assert "--force" in capsys.readouterr().err
    assert (out / MARKER).read_text() == first
    assert main(["run", "--out", str(out), "--samples", "31", "--frames", "2", "--force"]) == 0
    assert "summary.json" in report_files(out)


def test_check_and_module_entry(tmp_path):
    ok = subprocess.run(
        [sys.executable, "-m", "linkage", "check", str(EXAMPLES[0])], capture_output=True, text=True
    )
    assert ok.returncode == 0 and ok.stdout.startswith("ok: ")
    cat = subprocess.run(
        [sys.executable, "-m", "linkage", "catalog", "--samples", "2001"],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "LINKAGE_CACHE_DIR": str(tmp_path / "cache")},
    )
    for name in (
        "hoecken",
        "evans_a",
        "peaucellier",
        "hart",
        "hoecken_pantograph",
        "quadruped_hoecken",
    ):
        assert name in cat.stdout
    missing = subprocess.run(
        [sys.executable, "-m", "linkage", "run", str(tmp_path / "nope.toml")],
        capture_output=True,
        text=True,
    )
    assert missing.returncode == 2 and "cannot read the scene" in missing.stderr


def test_quiet_prints_nothing(tmp_path, capsys):
    assert (
        main(["run", "--out", str(tmp_path / "r"), "--samples", "31", "--frames", "2", "--quiet"])
        == 0
    )
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err == ""


def test_default_scene_equals_the_example_file():
    from linkage import scene

    default = scene.parse(scene.DEFAULT_SCENE, None)
    example = scene.load(Path(__file__).parent.parent / "examples" / "quadruped_hoecken.toml")
    default.path = example.path = None
    assert default == example


def test_scene_scale_multiplies_every_length_of_a_catalogue_four_bar():
    from linkage import build, catalog, scene

    base = catalog.hoecken()
    mech = build.build_mechanism(
        scene.parse(
            'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\nscale = 2.5\n'
            '[drive]\nkind = "constant"\nrpm = 50.0\n'
        )
    )
    assert isinstance(mech, linkage.FourBar)
    for name in ("ground", "crank", "coupler", "rocker"):
        assert getattr(mech, name) == 2.5 * getattr(base, name)
    assert mech.point == (2.5 * base.point[0], 2.5 * base.point[1])
    assert mech.assembly == base.assembly
    theta = np.linspace(0.0, 6.0, 7)
    np.testing.assert_allclose(mech.sweep(theta).point, 2.5 * base.sweep(theta).point, atol=1e-12)

    text = (Path(__file__).parent.parent / "examples" / "biped_custom_legs.toml").read_text()
    big = text.replace('catalog = "hoecken",', 'catalog = "hoecken", scale = 2.0,')
    assert big != text
    legs = build.build_walker(scene.parse(big)).legs
    for leg in legs:
        for name in ("ground", "crank", "coupler", "rocker"):
            assert getattr(leg.linkage, name) == 2.0 * getattr(base, name)


@pytest.mark.parametrize("frames", ["1", "2001", "1000000000"])
def test_frames_out_of_range_is_refused_before_anything_runs(tmp_path, capsys, frames):
    out = tmp_path / "r"
    with pytest.raises(SystemExit) as exc:
        main(["run", "--out", str(out), "--frames", frames])
    assert exc.value.code == 2
    assert "--frames must be between 2 and 2000" in capsys.readouterr().err
    assert not out.exists()


def synthesis_rows(n: int) -> list[tuple[str, str, str, str]]:
    """A synthesis run's table as the trial at 1e5 mm printed it (item 24), ``n`` candidates."""
    rows = [
        ("target", "40 points, closed curve", "", ""),
        ("target size", "100150", "mm", "RMS distance of the points from their centroid"),
        ("candidates found", str(n), "", f"best first (at most top = {n})"),
    ]
    for k in range(1, n + 1):
        c = f"candidate {k}"
        rows += [
            (
                f"{c}: max error",
                "3.68e-9",
                "mm",
                "largest distance of a target point from the coupler curve",
            ),
            (f"{c}: RMS error", "1.20e-9", "mm", "root mean square of those distances"),
            (f"{c}: Grashof class", "crank-rocker", "", "crossed assembly, from the atlas search"),
            (f"{c}: crank range", "-180.0 … 180.0", "deg", "full turn"),
            (
                f"{c}: min transmission angle",
                "23.1",
                "deg",
                "least distance from a toggle over the matched part",
            ),
        ]
    return [*rows, ("search time", "0.38", "s", "wall clock")]


def test_the_table_wraps_notes_before_values_and_names(capsys):
    """At 100 columns (output captured to a file) the trial's table wraps its notes; the short
    values ("-180.0 … 180.0") and the figure names stay whole on the first line of their row:
    the notes of the long-named rows wrap anyway, so a narrower name column saves no line."""
    from linkage.cli import print_table

    rows = synthesis_rows(4)
    print_table("macro", rows, width=100)
    lines = capsys.readouterr().out.splitlines()
    assert max(len(line) for line in lines) <= 100
    for figure, value, _, _ in rows[1:]:
        start = [line for line in lines if line.startswith(f"{figure}  ")]
        assert len(start) == 1 and f"  {value} " in start[0] + " ", (figure, value, lines)
