"""The report folder never costs the user a file: ``linkage run`` removes only what it wrote.

Each test builds a small world of user files in ``tmp_path``, runs the command in-process (and
once as a real child process interrupted with SIGINT), and compares the whole tree before and
after: scene names that climb out of ``linkage-report/``, ``--out`` at a user folder, a link, a
file, the working directory, home, with and without ``--force``; an interrupted or failing write
leaves no partial folder and an earlier report byte for byte as it was.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from linkage import report
from linkage._core import LinkageError
from linkage._shared import report_folder
from linkage.cli import main
from linkage.report import MARKER, export
from linkage.report import stages as runner

SCENE = (
    'name = "{name}"\noutputs = {outputs}\n[mechanism]\ncatalog = "hoecken"\n'
    '[drive]\nkind = "constant"\nomega = 1.0\n'
)
FAST = ["--samples", "31", "--frames", "2", "--quiet"]
DATA_FILES = {"data.csv", "data.npz", "summary.json"}
"""What every report writes besides its plots and its page."""


def scene_file(folder: Path, name: str = "fast", outputs: str = '["trajectory"]') -> Path:
    path = folder / f"scene-{abs(hash((name, outputs)))}.toml"
    path.write_text(SCENE.format(name=name.replace("\\", "\\\\"), outputs=outputs))
    return path


def snapshot(root: Path) -> dict[str, object]:
    """Every entry under ``root``: files by content, links by target, folders by name."""
    seen: dict[str, object] = {}
    for here, dirs, files in os.walk(root, followlinks=False):
        for d in dirs:
            p = Path(here, d)
            rel = str(p.relative_to(root))
            seen[rel] = ("link", os.readlink(p)) if p.is_symlink() else "dir"
        for f in files:
            p = Path(here, f)
            rel = str(p.relative_to(root))
            seen[rel] = ("link", os.readlink(p)) if p.is_symlink() else p.read_bytes()
    return seen


def leftovers(folder: Path) -> list[str]:
    """The tool's temporary or set-aside folders left in ``folder``."""
    return sorted(p.name for p in folder.iterdir() if ".partial-" in p.name or ".old-" in p.name)


def one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("linkage: "), err
    assert "Traceback" not in err
    return lines[0]


@pytest.fixture
def world(tmp_path, monkeypatch):
    """A home folder with a thesis, a working directory with the user's files and an earlier
    report of another scene; cwd is the working directory, HOME the home folder."""
    home = tmp_path / "home"
    (home / "thesis").mkdir(parents=True)
    (home / "thesis" / "chapter1.tex").write_text("years of work")
    (home / "notes.txt").write_text("notes")
    work = home / "work"
    work.mkdir()
    (work / "data.csv").write_text("1,2,3\n")
    (work / "keep.txt").write_text("keep me")
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.chdir(work)
    assert main(["run", str(scene_file(tmp_path, "other")), *FAST]) == 0
    assert (work / "linkage-report" / "other" / MARKER).is_file()
    return tmp_path


# -- scene names -----------------------------------------------------------------------------


CLIMBERS = [".", "..", "../..", "../escape", "a/../..", "/tmp", ".hidden", "a/b", "..\\x", "~"]


@pytest.mark.parametrize("name", CLIMBERS)
@pytest.mark.parametrize("force", [False, True])
def test_scene_names_cannot_leave_the_report_folder(world, capsys, name, force):
    scene = scene_file(world, name)
    before = snapshot(world)
    code = main(["run", str(scene), *FAST, *(["--force"] if force else [])])
    line = one_error_line(capsys.readouterr().err)
    assert code == 2
    # Rejected by the scene's name rule (file:line: name) or by the default-folder guard.
    assert (f"{scene}:" in line and "name" in line) or "linkage-report" in line, line
    assert snapshot(world) == before


@pytest.mark.parametrize("name", [".", "..", "../..", "../escape", ".hidden"])
def test_the_default_folder_is_guarded_even_if_a_name_passes_the_scene_rules(
    world, capsys, monkeypatch, name
):
    # Defence in depth: should a climbing name ever get past scene validation, the report path
    # still refuses it (with and without --force) and nothing is touched.
    from linkage import scene as scene_module

    real = scene_module.load

    def load(path):
        sc = real(path)
        sc.name = name
        return sc

    monkeypatch.setattr(scene_module, "load", load)
    scene = scene_file(world)
    before = snapshot(world)
    for force in ([], ["--force"]):
        assert main(["run", str(scene), *FAST, *force]) == 2
        line = one_error_line(capsys.readouterr().err)
        assert "cannot name a folder inside linkage-report" in line, line
        assert snapshot(world) == before


@pytest.mark.parametrize("name", ["", ".", "..", "../x", "a/b", ".hidden", "x" * 200, "a\0b"])
def test_default_folder_refuses_names_that_are_not_one_plain_folder(tmp_path, name):
    with pytest.raises(LinkageError, match="cannot name a folder"):
        report.default_folder(name, tmp_path / "linkage-report")


def test_default_folder_accepts_a_slug(tmp_path):
    base = tmp_path / "linkage-report"
    assert report.default_folder("hoecken-leg_2", base) == base / "hoecken-leg_2"


# -- --out at things that are not a report folder --------------------------------------------


@pytest.mark.parametrize("force", [False, True])
def test_out_at_a_user_folder_is_refused_and_its_files_survive(world, capsys, force):
    thesis = Path(os.environ["HOME"]) / "thesis"
    before = snapshot(world)
    for out in (str(thesis), "~/thesis"):
        code = main(["run", "--out", out, *FAST, *(["--force"] if force else [])])
        line = one_error_line(capsys.readouterr().err)
        assert code == 2
        assert "thesis" in line and "not a report written by linkage" in line, line
        assert snapshot(world) == before


def test_out_at_an_empty_user_folder_is_refused_too(world, capsys):
    empty = world / "empty"
    empty.mkdir()
    assert main(["run", "--out", str(empty), *FAST, "--force"]) == 2
    assert "not a report written by linkage" in one_error_line(capsys.readouterr().err)
    assert empty.is_dir() and not any(empty.iterdir())


@pytest.mark.parametrize("force", [False, True])
def test_out_at_a_symlink_to_a_folder_or_a_report_is_refused(world, capsys, force):
    work = Path.cwd()
    for to in (Path(os.environ["HOME"]) / "thesis", work / "linkage-report" / "other"):
        link = world / "link"
        link.symlink_to(to, target_is_directory=True)
        before = snapshot(world)
        code = main(["run", "--out", str(link), *FAST, *(["--force"] if force else [])])
        line = one_error_line(capsys.readouterr().err)
        assert code == 2 and "symbolic link" in line and str(link) in line, line
        assert snapshot(world) == before
        link.unlink()


@pytest.mark.parametrize("force", [False, True])
def test_out_at_a_dangling_symlink_is_refused_and_nothing_is_created(world, capsys, force):
    link = world / "dangling"
    target = world / "nowhere" / "report"
    link.symlink_to(target)
    before = snapshot(world)
    code = main(["run", "--out", str(link), *FAST, *(["--force"] if force else [])])
    line = one_error_line(capsys.readouterr().err)
    assert code == 2 and "dangling symbolic link" in line, line
    assert snapshot(world) == before
    assert not (world / "nowhere").exists()


@pytest.mark.parametrize("force", [False, True])
def test_out_at_a_file_is_refused(world, capsys, force):
    f = Path.cwd() / "keep.txt"
    code = main(["run", "--out", str(f), *FAST, *(["--force"] if force else [])])
    line = one_error_line(capsys.readouterr().err)
    assert code == 2 and "is not a folder" in line, line
    assert f.read_text() == "keep me"


@pytest.mark.parametrize("out", ["", ".", "..", "../..", "{cwd}", "{home}", "~", "/"])
def test_out_at_cwd_home_root_or_an_ancestor_is_refused_even_with_force(world, capsys, out):
    out = out.format(cwd=Path.cwd(), home=os.environ["HOME"])
    before = snapshot(world)
    code = main(["run", "--out", out, *FAST, "--force"])
    line = one_error_line(capsys.readouterr().err)
    assert code == 2, line
    assert any(w in line for w in ("working directory", "home folder", "root of the file")), line
    assert snapshot(world) == before


def test_cwd_is_protected_even_when_it_is_a_report_linkage_wrote(world, capsys, monkeypatch):
    # The marker alone would allow --force; the working directory is refused all the same.
    monkeypatch.chdir(Path.cwd() / "linkage-report" / "other")
    before = snapshot(world)
    assert main(["run", "--out", ".", *FAST, "--force"]) == 2
    assert "working directory" in one_error_line(capsys.readouterr().err)
    assert snapshot(world) == before


# -- replacing an earlier report -------------------------------------------------------------


def test_force_replaces_a_report_linkage_wrote_and_only_that(world, capsys):
    out = world / "r"
    scene = scene_file(world, "fast", '["trajectory", "animation"]')
    assert main(["run", str(scene), "--out", str(out), *FAST]) == 0
    assert "animation.gif" in json.loads((out / MARKER).read_text())["files"]
    # Without --force the report is kept as it is.
    before = snapshot(out)
    assert main(["run", str(scene_file(world)), "--out", str(out), *FAST]) == 2
    assert "pass --force" in one_error_line(capsys.readouterr().err)
    assert snapshot(out) == before
    # With --force it is replaced: the file the new run does not write is gone too.
    assert main(["run", str(scene_file(world)), "--out", str(out), *FAST, "--force"]) == 0
    names = {p.name for p in out.iterdir()}
    assert names == {MARKER, "trajectory.png", "index.html", *DATA_FILES}
    assert set(json.loads((out / MARKER).read_text())["files"]) == names - {MARKER}
    assert leftovers(world) == []


def test_default_folder_report_is_replaced_with_force(world, capsys):
    scene = scene_file(world, "other")
    out = Path.cwd() / "linkage-report" / "other"
    first = (out / "summary.json").read_bytes()
    assert main(["run", str(scene), *FAST]) == 2
    assert (out / "summary.json").read_bytes() == first
    assert main(["run", str(scene), "--samples", "41", "--frames", "2", "--quiet", "--force"]) == 0
    assert json.loads((out / "summary.json").read_text()) != json.loads(first)
    assert leftovers(out.parent) == []


def test_a_report_the_user_added_a_file_to_is_refused(world, capsys):
    out = Path.cwd() / "linkage-report" / "other"
    (out / "my-notes.txt").write_text("mine")
    before = snapshot(world)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    line = one_error_line(capsys.readouterr().err)
    assert "did not write" in line and "my-notes.txt" in line and str(out.name) in line, line
    assert snapshot(world) == before


def test_a_report_whose_listed_file_became_a_folder_is_refused(world, capsys):
    out = Path.cwd() / "linkage-report" / "other"
    (out / "data.csv").unlink()
    (out / "data.csv").mkdir()
    (out / "data.csv" / "inner.txt").write_text("mine")
    before = snapshot(world)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    assert "data.csv" in one_error_line(capsys.readouterr().err)
    assert snapshot(world) == before


def test_a_report_whose_file_the_user_edited_is_refused_by_name(world, capsys):
    # A candidate scene tuned in place, say: --force must not silently put linkage's back.
    out = Path.cwd() / "linkage-report" / "other"
    with (out / "data.csv").open("a") as f:
        f.write("# my note\n")
    before = snapshot(world)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    line = one_error_line(capsys.readouterr().err)
    assert "changed since linkage wrote them (data.csv)" in line and out.name in line, line
    assert snapshot(world) == before
    # Moved out of the folder, the edit is kept and the report is replaced.
    (out / "data.csv").rename(world / "mine.csv")
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 0
    assert (world / "mine.csv").read_text().endswith("# my note\n")
    assert "# my note" not in (out / "data.csv").read_text()


def test_the_marker_records_each_files_hash(world):
    out = Path.cwd() / "linkage-report" / "other"
    marker = json.loads((out / MARKER).read_text())
    assert set(marker["sha256"]) == set(marker["files"])
    for name, digest in marker["sha256"].items():
        assert hashlib.sha256((out / name).read_bytes()).hexdigest() == digest


def old_marker(out: Path) -> None:
    """Make the report's marker one without hashes, as builds before them wrote it."""
    marker = json.loads((out / MARKER).read_text())
    marker.pop("sha256", None)
    (out / MARKER).write_text(json.dumps(marker, indent=2) + "\n")


def test_a_marker_without_hashes_still_lets_force_replace_the_report(world, capsys):
    out = Path.cwd() / "linkage-report" / "other"
    old_marker(out)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 0
    assert "sha256" in json.loads((out / MARKER).read_text())


def test_a_marker_without_hashes_counts_a_file_modified_after_it_as_edited(world, capsys):
    out = Path.cwd() / "linkage-report" / "other"
    old_marker(out)
    written = (out / MARKER).stat().st_mtime_ns
    (out / "summary.json").write_text("{}")
    os.utime(out / "summary.json", ns=(written + 1, written + 1))
    before = snapshot(world)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    line = one_error_line(capsys.readouterr().err)
    assert "changed since linkage wrote them (summary.json)" in line, line
    assert snapshot(world) == before


@pytest.mark.parametrize(
    "marker",
    [
        "not json",
        json.dumps({"tool": "other", "files": []}),
        json.dumps({"tool": "linkage", "files": ["../../notes.txt"]}),
        json.dumps({"tool": "linkage", "files": "summary.json"}),
        json.dumps({"tool": "linkage", "files": [], "sha256": ["summary.json"]}),
        json.dumps(["tool", "linkage"]),
    ],
)
def test_a_forged_or_broken_marker_makes_the_folder_the_users(world, capsys, marker):
    out = world / "forged"
    out.mkdir()
    (out / MARKER).write_text(marker)
    before = snapshot(world)
    assert main(["run", "--out", str(out), *FAST, "--force"]) == 2
    assert "not a report written by linkage" in one_error_line(capsys.readouterr().err)
    assert snapshot(world) == before


def test_a_file_added_while_the_run_computes_is_not_lost(world, capsys, monkeypatch):
    out = Path.cwd() / "linkage-report" / "other"
    real = runner.run

    def run_then_user_writes(*args, **kwargs):
        res = real(*args, **kwargs)
        (out / "late.txt").write_text("written during the run")
        return res

    monkeypatch.setattr(runner, "run", run_then_user_writes)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    assert "late.txt" in one_error_line(capsys.readouterr().err)
    assert (out / "late.txt").read_text() == "written during the run"
    assert (out / MARKER).is_file() and (out / "summary.json").is_file()
    assert leftovers(out.parent) == []


def test_replacing_removes_only_the_listed_files_of_the_old_report(world, capsys, monkeypatch):
    # A file that lands in the old report in the instant it is being replaced is kept (the old
    # report is removed file by file, never with rmtree), and the user is told where it is.
    out = Path.cwd() / "linkage-report" / "other"
    real = os.rename

    def rename(src, dst):
        real(src, dst)
        if ".old-" in str(dst):
            (Path(dst) / "late.txt").write_text("mine")

    monkeypatch.setattr(report_folder.os, "rename", rename)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 0
    line = one_error_line(capsys.readouterr().err)
    assert "warning" in line and ".old-" in line, line
    (aside,) = [p for p in out.parent.iterdir() if ".old-" in p.name]
    assert {p.name for p in aside.iterdir()} == {"late.txt"}
    assert (aside / "late.txt").read_text() == "mine"
    assert (out / MARKER).is_file() and (out / "summary.json").is_file()


# -- interrupted and failing writes ----------------------------------------------------------


def interrupt_mid_write(monkeypatch, exc: BaseException) -> list[Path]:
    """Make the data writer write one file, then raise ``exc``; returns the folders it saw."""
    seen: list[Path] = []

    def data(res, folder, **_):
        seen.append(folder)
        (folder / "data.npz").write_bytes(b"half a file")
        raise exc

    monkeypatch.setattr(export, "write_data", data)
    return seen


@pytest.mark.parametrize("force", [False, True])
def test_interrupt_mid_write_leaves_the_old_report_and_no_partial_folder(
    world, capsys, monkeypatch, force
):
    out = Path.cwd() / "linkage-report" / "other"
    before = snapshot(world)
    seen = interrupt_mid_write(monkeypatch, KeyboardInterrupt())
    code = main(["run", str(scene_file(world, "other")), *FAST, *(["--force"] if force else [])])
    line = one_error_line(capsys.readouterr().err)
    if force:
        assert code == 130 and line == "linkage: interrupted; nothing was written"
        assert len(seen) == 1 and ".partial-" in seen[0].name and not seen[0].exists()
    else:  # refused before anything was computed or written
        assert code == 2 and "pass --force" in line and seen == []
    assert snapshot(world) == before
    assert leftovers(out.parent) == []


def test_interrupt_of_a_first_report_removes_the_folders_it_created(world, capsys, monkeypatch):
    out = world / "new" / "deeper" / "report"
    scene = scene_file(world)
    before = snapshot(world)
    interrupt_mid_write(monkeypatch, KeyboardInterrupt())
    assert main(["run", str(scene), "--out", str(out), *FAST]) == 130
    assert one_error_line(capsys.readouterr().err) == "linkage: interrupted; nothing was written"
    assert not (world / "new").exists()
    assert snapshot(world) == before


def test_interrupt_while_computing_exits_130_with_one_line(world, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(runner, "run", interrupted)
    scene = scene_file(world)
    before = snapshot(world)
    assert main(["run", str(scene), "--out", str(world / "r"), *FAST]) == 130
    assert one_error_line(capsys.readouterr().err) == "linkage: interrupted; nothing was written"
    assert snapshot(world) == before


@pytest.mark.parametrize(
    "err, words",
    [
        (errno.ENOSPC, "No space left on device"),
        (errno.EACCES, "Permission denied"),
    ],
)
def test_a_failing_write_names_the_path_and_keeps_the_old_report(
    world, capsys, monkeypatch, err, words
):
    out = Path.cwd() / "linkage-report" / "other"
    before = snapshot(world)

    def data(res, folder, **_):
        (folder / "data.npz").write_bytes(b"half")
        raise OSError(err, os.strerror(err), str(folder / "data.npz"))

    monkeypatch.setattr(export, "write_data", data)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    line = one_error_line(capsys.readouterr().err)
    assert words in line and str(Path("linkage-report") / "other" / "data.npz") in line, line
    assert "nothing was written; the earlier report is unchanged" in line, line
    assert ".partial-" not in line
    assert snapshot(world) == before
    assert leftovers(out.parent) == []


def test_a_failing_final_rename_puts_the_old_report_back(world, capsys, monkeypatch):
    out = Path.cwd() / "linkage-report" / "other"
    before = snapshot(world)
    real = os.rename

    def rename(src, dst):
        if ".partial-" in str(src):
            raise OSError(errno.EXDEV, os.strerror(errno.EXDEV), str(src), str(dst))
        real(src, dst)

    monkeypatch.setattr(report_folder.os, "rename", rename)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 2
    assert "cannot write the report" in one_error_line(capsys.readouterr().err)
    assert snapshot(world) == before
    assert leftovers(out.parent) == []


def test_memory_error_is_one_line(world, capsys, monkeypatch):
    def huge(*args, **kwargs):
        raise MemoryError("a sweep of 10^12 samples needs 48 TB")

    monkeypatch.setattr(runner, "run", huge)
    scene = scene_file(world)
    before = snapshot(world)
    assert main(["run", str(scene), "--out", str(world / "r"), *FAST]) == 2
    line = one_error_line(capsys.readouterr().err)
    assert "out of memory" in line and "48 TB" in line, line
    assert snapshot(world) == before


@pytest.mark.parametrize("debug", [False, True])
def test_a_bug_is_called_an_internal_error(world, capsys, monkeypatch, debug):
    def bug(*args, **kwargs):
        return 1 // 0

    monkeypatch.setattr(runner, "run", bug)
    if debug:
        monkeypatch.setenv("LINKAGE_DEBUG", "1")
    else:
        monkeypatch.delenv("LINKAGE_DEBUG", raising=False)
    scene = scene_file(world)
    before = snapshot(world)
    assert main(["run", str(scene), "--out", str(world / "r"), *FAST]) == 3
    err = capsys.readouterr().err
    if debug:
        assert "Traceback" in err and "ZeroDivisionError" in err
    else:
        line = one_error_line(err)
        assert "internal error" in line and "ZeroDivisionError" in line, line
    assert snapshot(world) == before


class PanicException(BaseException):
    """Stands in for pyo3's PanicException, which derives from BaseException."""


def test_a_rust_panic_is_an_internal_error_not_a_traceback(world, capsys, monkeypatch):
    def panic(*args, **kwargs):
        raise PanicException("index out of bounds: the len is 3 but the index is 7")

    monkeypatch.setattr(runner, "run", panic)
    monkeypatch.delenv("LINKAGE_DEBUG", raising=False)
    scene = scene_file(world)
    before = snapshot(world)
    assert main(["run", str(scene), "--out", str(world / "r"), *FAST]) == 3
    line = one_error_line(capsys.readouterr().err)
    assert "internal error" in line and "PanicException" in line and "the index is 7" in line, line
    assert snapshot(world) == before


def test_ctrl_c_that_a_library_turns_into_its_own_error_is_still_an_interrupt(
    world, capsys, monkeypatch
):
    # matplotlib's C++ renderer, hit by Ctrl-C while it converts its arguments, reports
    # "ValueError: Invalid bounding box" and drops the KeyboardInterrupt (a CI run saw it)
    out = Path.cwd() / "linkage-report" / "other"
    real = report._write_files

    def swallowing(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5)  # the handler runs at the next bytecode; this is never reached
        except KeyboardInterrupt:
            raise ValueError("Invalid bounding box") from None
        return real(*args, **kwargs)

    monkeypatch.setattr(report, "_write_files", swallowing)
    monkeypatch.delenv("LINKAGE_DEBUG", raising=False)
    before = snapshot(world)
    assert main(["run", str(scene_file(world, "other")), *FAST, "--force"]) == 130
    line = one_error_line(capsys.readouterr().err)
    assert "interrupted" in line and "nothing was written" in line, line
    assert snapshot(world) == before
    assert leftovers(out.parent) == []
    # the handlers are Python's own again once the run is over
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL


# -- a real Ctrl-C ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("signum", "status", "said"),
    [
        (signal.SIGINT, 130, "interrupted"),
        # kill, timeout, a cancelled CI job: the partial folder had been left behind
        (signal.SIGTERM, 143, "stopped by SIGTERM"),
    ],
)
def test_a_signal_to_a_real_run_exits_and_leaves_the_old_report(
    world, tmp_path_factory, signum, status, said
):
    out = Path.cwd() / "linkage-report" / "other"
    scene = scene_file(world, "other", '["trajectory", "animation"]')
    before = snapshot(world)
    child = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "linkage",
            "run",
            str(scene),
            "--force",
            "--quiet",
            "--samples",
            "2001",
            "--frames",
            "300",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        # matplotlib's font cache goes to its own folder, not into the watched (fake) home
        env={**os.environ, "MPLCONFIGDIR": str(tmp_path_factory.mktemp("mplconfig"))},
    )
    try:
        deadline = time.monotonic() + 120
        while not leftovers(out.parent) and child.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        assert child.poll() is None, "the run ended before its report was half written"
        partial = leftovers(out.parent)
        assert len(partial) == 1 and ".partial-" in partial[0]
        time.sleep(0.2)  # well inside the write (the animation takes seconds)
        child.send_signal(signum)
        stdout, stderr = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert child.returncode == status, stderr
    assert stderr.strip() == f"linkage: {said}; nothing was written", stderr
    assert stdout == ""
    assert leftovers(out.parent) == []
    assert snapshot(world) == before
