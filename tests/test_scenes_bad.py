"""Hostile scenes: every file in ``tests/scenes/bad/`` holds one mistake, and its sibling
``.expected`` holds the exact message (``{scene}`` standing for the file's path) that both
``linkage check`` and ``linkage run`` must print — exit status 2, one line, no traceback, and
nothing written. Every example scene must still pass ``check``."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from linkage import OUTPUTS as SWEEP_OUTPUTS
from linkage import _schema, scene
from linkage.cli import main
from linkage.report import stages as runner
from linkage.scene import builders as build

ROOT = Path(__file__).parent.parent
BAD = Path(__file__).parent / "scenes" / "bad"
CASES = sorted(BAD.glob("*.toml"))
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))


def expected(path: Path) -> str:
    text = path.with_suffix(".expected").read_text(encoding="utf-8").strip()
    return text.replace("{scene}", str(path))


def refused(capsys: pytest.CaptureFixture[str], message: str) -> None:
    """Exactly one line on stderr, the message; nothing on stdout."""
    captured = capsys.readouterr()
    assert captured.out == ""
    assert "Traceback" not in captured.err and "internal error" not in captured.err
    assert captured.err.splitlines() == [f"linkage: error: {message}"], captured.err


def test_the_corpus_is_large_and_every_file_has_its_message():
    assert len(CASES) >= 60
    for case in CASES:
        assert case.with_suffix(".expected").is_file(), case
    stray = {p.stem for p in BAD.glob("*.expected")} - {p.stem for p in CASES}
    assert not stray


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.stem)
def test_bad_scene_is_refused_by_check_and_run_with_its_message(
    path, tmp_path, capsys, monkeypatch
):
    message = expected(path)
    assert message.startswith(f"{path}:")
    line = message[len(str(path)) + 1 :].split(":", 1)[0]
    assert line.isdigit() and int(line) >= 1, message
    assert main(["check", str(path)]) == 2
    refused(capsys, message)

    box = tmp_path / "box"
    box.mkdir()
    monkeypatch.chdir(box)
    assert main(["run", str(path), "--out", str(box / "report"), "--frames", "2"]) == 2
    refused(capsys, message)
    assert main(["run", str(path), "--frames", "2"]) == 2  # default folder under the cwd
    refused(capsys, message)
    assert list(box.iterdir()) == []


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.stem)
def test_the_api_raises_scene_error_only(path):
    with pytest.raises(scene.SceneError) as info:
        scene.load(path)
    assert str(info.value) == expected(path)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_example_passes_check(path, capsys):
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    sc = scene.load(path)
    assert out.startswith(f"ok: {sc.name}:")
    assert scene.NAME.fullmatch(sc.name)


def test_default_scene_name_is_a_slug():
    assert scene.NAME.fullmatch(scene.parse(scene.DEFAULT_SCENE).name)


def test_a_scene_file_over_the_size_limit_is_refused_unread(tmp_path, capsys):
    big = tmp_path / "big.toml"
    body = (ROOT / "examples" / "hoecken.toml").read_text()
    big.write_text(body + "#" * (scene.FILE_MAX + 1))
    assert main(["check", str(big)]) == 2
    refused(capsys, f"{big}: not a scene: larger than {scene.FILE_MAX // 1024} KiB")


def test_a_device_or_a_folder_as_the_scene_is_refused(tmp_path, capsys):
    assert main(["check", "/dev/zero"]) == 2
    refused(capsys, "/dev/zero: the scene is a device, not a regular file")
    assert main(["check", str(tmp_path)]) == 2
    refused(capsys, f"{tmp_path}: the scene is a folder, not a regular file")


def test_a_named_pipe_nobody_writes_does_not_hang_and_a_written_one_is_read(tmp_path):
    """A FIFO as the scene had blocked ``linkage check`` in open() for ever; a pipe with a writer
    (the shell's ``<(cat scene.toml)``) is still a way to pass a scene."""
    import os
    import subprocess
    import sys
    import threading

    fifo = tmp_path / "scene.toml"
    os.mkfifo(fifo)
    lone = subprocess.run(
        [sys.executable, "-m", "linkage", "check", str(fifo)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert lone.returncode == 2 and "Traceback" not in lone.stderr, lone.stderr
    body = (ROOT / "examples" / "hoecken.toml").read_bytes()
    child = subprocess.Popen(
        [sys.executable, "-m", "linkage", "check", str(fifo)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    writer = threading.Thread(target=lambda: fifo.write_bytes(body), daemon=True)
    writer.start()
    out, err = child.communicate(timeout=60)
    assert child.returncode == 0 and out.startswith("ok: hoecken"), err


def test_brackets_inside_strings_and_comments_do_not_count_as_nesting(tmp_path, capsys):
    ok = tmp_path / "ok.toml"
    body = (ROOT / "examples" / "hoecken.toml").read_text()
    deep = "[" * 100 + "{" * 100
    ok.write_text(f'description = "{deep}"\n# {deep}\n' + body.replace("description", "# was"))
    assert main(["check", str(ok)]) == 0, capsys.readouterr().err


def test_a_scene_without_a_name_takes_its_file_stem_as_a_slug(tmp_path):
    path = tmp_path / "My Study (v2).toml"
    body = (ROOT / "examples" / "hoecken.toml").read_text()
    path.write_text("\n".join(ln for ln in body.splitlines() if not ln.startswith("name")))
    assert scene.load(path).name == "my-study-v2"


def test_samples_override_beyond_the_memory_cap_is_refused_before_writing(tmp_path, capsys):
    out = tmp_path / "report"
    hoecken = ROOT / "examples" / "hoecken.toml"
    assert main(["run", str(hoecken), "--out", str(out), "--samples", "200000000"]) == 2
    err = capsys.readouterr().err
    assert "samples: 200000000 samples would need about" in err and "GiB limit" in err
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_memory_estimate_grows_with_samples_and_outputs():
    sc = scene.load(ROOT / "examples" / "hoecken.toml")
    mech = build.build_mechanism(sc)
    small, big = build.estimate_memory(sc, mech, 1000), build.estimate_memory(sc, mech, 10**6)
    assert small < big <= scene.MEMORY_CAP
    plain = scene.parse(
        'outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
        '[drive]\nkind = "constant"\nrpm = 50.0\n'
    )
    assert build.estimate_memory(plain, mech, 10**6) < big


# Watt's linkage assembles only for |θ| < 46.6°; a dwell at 180° never reaches it: a scene the
# schema accepts and only building the study refuses.
NEVER_ASSEMBLES = (
    'outputs = ["trajectory"]\n[mechanism]\ncatalog = "watt"\n'
    '[drive]\nkind = "program"\nstart_deg = 180.0\nsegments = [{ duration = 1.0 }]\n'
)


def test_no_assembled_sample_under_a_samples_override_is_an_error():
    # The scene is refused by validation; run() refuses it too when called on a hand-made Scene.
    with pytest.raises(scene.SceneError, match="no sample assembles"):
        scene.parse(NEVER_ASSEMBLES)
    sc = scene.Scene(
        name="s",
        path=None,
        outputs=("trajectory",),
        mechanism={"catalog": "watt"},
        drive={"kind": "program", "start_deg": 180.0, "segments": [{"duration": 1.0}]},
    )
    with pytest.raises(scene.SceneError, match=r"^\[drive\] start_deg: no sample assembles"):
        runner.run(sc, samples=64)


def test_parse_and_load_build_the_scene_once_the_schema_parser_never(tmp_path, monkeypatch):
    assert _schema.parse_only(NEVER_ASSEMBLES).mechanism == {"catalog": "watt"}
    path = tmp_path / "never.toml"
    path.write_text(NEVER_ASSEMBLES, encoding="utf-8")
    where = re.escape(f"{path}:6: [drive] start_deg: no sample assembles")
    with pytest.raises(scene.SceneError, match=f"^{where}"):
        scene.load(path)
    built: list[scene.Scene] = []
    monkeypatch.setattr(build, "validate", built.append)
    hoecken = ROOT / "examples" / "hoecken.toml"
    sc = scene.load(hoecken)
    assert built == [sc]
    assert _schema.parse_only(hoecken.read_text(), hoecken) == sc and built == [sc]
    assert scene.parse(hoecken.read_text(), hoecken) == sc and built == [sc, sc]


def test_a_walker_with_feet_off_the_ground_reports_no_support_not_minus_infinity():
    # An absolute ground tolerance of 0.1 on legs scaled ten times: at some samples no foot is
    # within it, so there is no support polygon there.
    text = (ROOT / "examples" / "biped_custom_legs.toml").read_text()
    big = text.replace('catalog = "hoecken",', 'catalog = "hoecken", scale = 10.0,')
    res = runner.run(scene.parse(big))
    rows = {r[0]: r for r in res.figures}
    value = rows["minimum stability margin"][1]
    assert value.startswith("none: no foot down at ")
    assert all("inf" not in cell for row in res.figures for cell in row)


def test_scene_outputs_the_deprecated_name_of_report_outputs_is_removed():
    assert not hasattr(scene, "OUTPUTS") and "OUTPUTS" not in scene.__all__
    # Not the outputs of a sweep (linkage.OUTPUTS), whose name it shared.
    assert "cad" in scene.REPORT_OUTPUTS and "cad" not in SWEEP_OUTPUTS
