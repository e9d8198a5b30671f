"""The command under hostile conditions: a file-size limit, a reader that goes away, a run killed
with -9, concurrent runs on one folder and stop signals.

Each message must be one true line: it names the file that could not be written, it says
"nothing was written" only when nothing was, and a run that lost a race to another is told so
(not that the user changed files). Folders a killed run left behind are cleaned by the next
run in the same place, but only when they are certainly the tool's own.
"""

from __future__ import annotations

import json
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from linkage._shared import report_folder
from linkage.cli import main
from linkage.report import MARKER, export

SCENE = (
    'name = "fast"\noutputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    '[drive]\nkind = "constant"\nomega = 1.0\n'
)
FAST = ["--samples", "31", "--frames", "2", "--quiet"]


@pytest.fixture
def scene(tmp_path: Path) -> Path:
    path = tmp_path / "fast.toml"
    path.write_text(SCENE)
    return path


def env(tmp_path: Path) -> dict[str, str]:
    """The child's environment: this tree first, linkage's caches in the test's own folder.

    Matplotlib's font cache stays where it is, built by this process (under a file-size limit
    matplotlib could not write it, and says so on stderr). The standard output is buffered, as
    a user's is (``PYTHONUNBUFFERED``, set on some machines, had hidden the interpreter's own
    failing flush at exit)."""
    import matplotlib.font_manager  # noqa: F401

    python = str(Path(report_folder.__file__).parent.parent)
    return {
        **{k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"},
        "PYTHONPATH": python + os.pathsep + os.environ.get("PYTHONPATH", ""),
        "LINKAGE_CACHE_DIR": str(tmp_path / "cache"),
    }


def linkage(*args: str) -> list[str]:
    return [sys.executable, "-m", "linkage", *args]


def one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("linkage: "), err
    return lines[0]


def temporaries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if ".partial-" in p.name or ".old-" in p.name)


def dead_pid() -> int:
    """The pid of a process that has ended (its number not yet reused)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def intact(folder: Path) -> bool:
    """Whether ``folder`` is a whole report: its marker lists exactly its files, as written."""
    marker = report_folder.read_marker(folder)
    if marker is None:
        return False
    names = {p.name for p in folder.iterdir()} - {MARKER}
    return names == set(marker["files"]) and all(
        report_folder._sha256(folder / n) == marker["sha256"][n] for n in names
    )


# -- a file-size limit (ulimit -f) -------------------------------------------------------------


def limit_file_size(size: int):  # type: ignore[no-untyped-def]
    def set_limit() -> None:
        resource.setrlimit(
            resource.RLIMIT_FSIZE, (size, resource.getrlimit(resource.RLIMIT_FSIZE)[1])
        )

    return set_limit


def test_a_file_size_limit_names_the_file_that_did_not_fit(tmp_path, scene):
    out = tmp_path / "report"
    child = subprocess.run(
        linkage("run", str(scene), "--out", str(out), *FAST),
        capture_output=True,
        text=True,
        env=env(tmp_path),
        preexec_fn=limit_file_size(20_000),
        timeout=300,
    )
    line = one_line(child.stderr)
    assert child.returncode == 2
    # The file that hit the limit is named inside the report folder the user asked for (the
    # data files and the page are under the limit; the plot is not).
    assert f"{out}/trajectory.png: File too large" in line, line
    assert line.endswith("(nothing was written)"), line
    assert not out.exists() and temporaries(tmp_path) == []


def test_a_failed_write_without_a_path_is_named_from_the_file_being_written(
    tmp_path, scene, capsys, monkeypatch
):
    # A full disk or a quota is reported by write() with no file name: the report names the
    # file the run was writing when it failed.
    import errno

    def data(res, folder, **_):
        with open(folder / "data.npz", "wb") as fh:
            fh.write(b"half")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(export, "write_data", data)
    out = tmp_path / "report"
    assert main(["run", str(scene), "--out", str(out), *FAST]) == 2
    line = one_line(capsys.readouterr().err)
    assert f"{out}/data.npz: No space left on device" in line, line
    assert line.endswith("(nothing was written)") and not out.exists()
    assert temporaries(tmp_path) == []


def test_standard_output_over_the_limit_is_named(tmp_path):
    target = tmp_path / "table.txt"
    with target.open("wb") as fh:
        child = subprocess.run(
            linkage("catalog", "--samples", "73"),
            stdout=fh,
            stderr=subprocess.PIPE,
            text=True,
            env=env(tmp_path),
            preexec_fn=limit_file_size(200),
            timeout=300,
        )
    line = one_line(child.stderr)
    assert child.returncode == 2
    assert "cannot write to the standard output: File too large" in line, line


# -- a reader that goes away (| head) ----------------------------------------------------------


@pytest.mark.parametrize(
    "args",
    [
        ["--help"],
        ["catalog", "--samples", "73"],
        ["check", "{scene}"],
        ["synth", "{points}", "--quiet", "--top", "2"],
        ["run", "{scene}", "--out", "{out}", *FAST[:-1]],
    ],
    ids=["help", "catalog", "check", "synth", "run"],
)
def test_a_closed_pipe_ends_the_command_quietly(tmp_path, scene, args):
    points = tmp_path / "points.csv"
    points.write_text("0,0\n1,0\n1,1\n0,1\n0.5,1.2\n")
    out = tmp_path / "report"
    argv = [a.format(scene=scene, points=points, out=out) for a in args]
    # A real pipe whose reader closes it before the command writes (as `| head -1` does once
    # it has its line): every write after that is EPIPE.
    child = subprocess.Popen(
        linkage(*argv),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env(tmp_path),
    )
    assert child.stdout is not None and child.stderr is not None
    child.stdout.close()
    err = child.stderr.read().decode()
    child.wait(timeout=300)
    assert err == "", err
    # 141 = 128 + SIGPIPE, what a shell reports for a Unix tool cut off by its reader. --help
    # is written by argparse, which from Python 3.10 ignores a failed write itself (exit 0 when
    # the write fails at once, unbuffered; 141 when our flush finds it); on 3.9 its write raised
    # BrokenPipeError, a traceback.
    assert child.returncode in ((0, 141) if args == ["--help"] else (141,))
    if args[0] == "run":  # the report was written before the table was printed
        assert intact(out)


def test_a_reader_that_leaves_after_the_first_line(tmp_path):
    # As `linkage catalog | head -1`, unbuffered so that the command is still writing.
    child = subprocess.Popen(
        linkage("catalog", "--samples", "73"),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**env(tmp_path), "PYTHONUNBUFFERED": "1"},
    )
    assert child.stdout is not None and child.stderr is not None
    assert child.stdout.readline()
    child.stdout.close()
    err = child.stderr.read().decode()
    child.wait(timeout=300)
    assert err == "", err
    assert child.returncode in (0, 141)


# -- folders a killed run left behind ----------------------------------------------------------


def plant_report(folder: Path, files: dict[str, bytes], scene: str = "fast") -> None:
    folder.mkdir()
    for name, data in files.items():
        (folder / name).write_bytes(data)
    marker = {
        "tool": "linkage",
        "version": "0",
        "scene": scene,
        "files": sorted(files),
        "sha256": {n: report_folder.hashlib.sha256(d).hexdigest() for n, d in files.items()},
    }
    (folder / MARKER).write_text(json.dumps(marker))


def test_a_later_run_sweeps_what_a_killed_run_left_and_nothing_else(tmp_path, scene, capsys):
    reports = tmp_path / "reports"
    reports.mkdir()
    dead, live = dead_pid(), os.getppid()
    # A killed run's temporary folder (a plot and half the data): removed.
    stale = reports / f".fast.partial-{dead}"
    stale.mkdir()
    (stale / "trajectory.png").write_bytes(b"png")
    (stale / "data.npz").write_bytes(b"half")
    # Another scene's, from a second try of the same pid (suffix -1), empty: removed.
    (reports / f".other.partial-{dead}-1").mkdir()
    # A live process's: being written now, kept.
    running = reports / f".fast.partial-{live}"
    running.mkdir()
    (running / "data.csv").write_text("1,2\n")
    # A dead pid's folder holding a file the tool never writes: the user's, kept.
    users = reports / f".mine.partial-{dead}"
    users.mkdir()
    (users / "thesis.tex").write_text("years of work")
    # A folder inside one: kept.
    nested = reports / f".nested.partial-{dead}"
    (nested / "sub").mkdir(parents=True)
    # A link of the pattern to a folder of the tool's names: kept, and its target too.
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "summary.json").write_text("{}")
    (reports / f".link.partial-{dead}").symlink_to(elsewhere)
    # A report set aside by a killed --force whose new report is in place: removed.
    plant_report(reports / "done", {"summary.json": b"{}"})
    plant_report(reports / f".done.old-{dead}", {"summary.json": b"{} old", "data.csv": b"1\n"})
    # ... and one whose new report never arrived: put back where it was.
    plant_report(reports / f".gone.old-{dead}", {"summary.json": b"{} gone"}, scene="gone")
    # A set-aside report holding a user's file too: kept whole.
    plant_report(reports / f".kept.old-{dead}", {"summary.json": b"{}"})
    (reports / f".kept.old-{dead}" / "notes.txt").write_text("mine")
    # A set-aside report whose listed file was edited: kept whole.
    plant_report(reports / f".edited.old-{dead}", {"data.csv": b"1\n"})
    (reports / f".edited.old-{dead}" / "data.csv").write_text("2\n")

    assert main(["run", str(scene), "--out", str(reports / "fast"), *FAST]) == 0
    assert capsys.readouterr().err == ""
    assert intact(reports / "fast")
    assert sorted(p.name for p in reports.iterdir()) == sorted(
        [
            "done",
            "fast",
            "gone",
            f".fast.partial-{live}",
            f".mine.partial-{dead}",
            f".nested.partial-{dead}",
            f".link.partial-{dead}",
            f".kept.old-{dead}",
            f".edited.old-{dead}",
        ]
    )
    assert (running / "data.csv").read_text() == "1,2\n"
    assert (users / "thesis.tex").read_text() == "years of work"
    assert (elsewhere / "summary.json").read_text() == "{}"
    assert (
        intact(reports / "gone") and (reports / "gone" / "summary.json").read_bytes() == b"{} gone"
    )
    assert sorted(p.name for p in (reports / f".kept.old-{dead}").iterdir()) == [
        MARKER,
        "notes.txt",
        "summary.json",
    ]
    assert (reports / f".edited.old-{dead}" / "data.csv").read_text() == "2\n"


def test_every_file_a_report_writes_is_one_the_sweep_knows():
    # The sweep removes a dead run's folder only if it holds nothing but the tool's files: a
    # new kind of output must be added to the list, or its folders are kept forever.
    for name in [
        "trajectory.png",
        "rates.png",
        "torque.png",
        "cam.png",
        "gait.png",
        "stability.png",
        "slip.png",
        "synthesis.png",
        "animation.gif",
        "index.html",
        "data.csv",
        "data.npz",
        "summary.json",
        "mechanism.dxf",
        "mechanism.svg",
        "candidates.csv",
        "candidate-12.toml",
        "candidates.parquet",
        "front.csv",
        "pareto.png",
        "designs.png",
        "design-3.toml",
        MARKER,
    ]:
        assert report_folder.TOOL_FILE.fullmatch(name), name
    for name in ["thesis.tex", "notes.txt", "photo.png", "design-x.toml", "data.csv~", ".git"]:
        assert not report_folder.TOOL_FILE.fullmatch(name), name


# -- concurrent --force runs -------------------------------------------------------------------


def test_concurrent_forced_runs_lose_nothing_and_say_nothing_false(tmp_path, scene):
    out = tmp_path / "report"
    assert main(["run", str(scene), "--out", str(out), *FAST]) == 0
    for _ in range(3):
        children = [
            subprocess.Popen(
                linkage("run", str(scene), "--out", str(out), "--force", *FAST),
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
                env=env(tmp_path),
            )
            for _ in range(2)
        ]
        for child in children:
            _, err = child.communicate(timeout=300)
            assert "changed since" not in err, err
            assert child.returncode == 0 or "another linkage run" in err, err
        assert intact(out)
        assert temporaries(tmp_path) == []


def test_a_run_that_commits_while_this_one_checks_is_not_called_an_edit(
    tmp_path, scene, capsys, monkeypatch
):
    # Deterministically, the race the concurrent runs above may hit: another run reaches its
    # commit while this one is checking the old report file by file.
    out = tmp_path / "report"
    assert main(["run", str(scene), "--out", str(out), *FAST]) == 0
    capsys.readouterr()
    real = report_folder._sha256
    others: list[subprocess.Popen[str]] = []

    def sha256(path: Path) -> str:
        if not others and path.parent == out and any(temporaries(tmp_path)):
            other = subprocess.Popen(
                linkage("run", str(out.parent / "fast.toml"), "--out", str(out), "--force", *FAST),
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
                env=env(tmp_path),
            )
            others.append(other)
            # Wait until the other run has finished its files (its marker is written last),
            # then give it time to commit if nothing holds it off.
            deadline = time.monotonic() + 120
            while time.monotonic() < deadline and other.poll() is None:
                partial = [p for p in tmp_path.iterdir() if f".partial-{other.pid}" in p.name]
                if partial and (partial[0] / MARKER).exists():
                    break
                time.sleep(0.01)
            time.sleep(1.0)
        return real(path)

    monkeypatch.setattr(report_folder, "_sha256", sha256)
    code = main(["run", str(scene), "--out", str(out), "--force", *FAST])
    err = capsys.readouterr().err
    assert others, "the check never ran while a partial folder existed"
    _, other_err = others[0].communicate(timeout=300)
    assert "changed since" not in err and "changed since" not in other_err, (err, other_err)
    assert code == 0 or "another linkage run" in err, err
    assert others[0].returncode == 0 or "another linkage run" in other_err, other_err
    assert intact(out)
    assert temporaries(tmp_path) == []


# -- stop signals: "nothing was written" only when true ----------------------------------------


def test_a_stop_after_the_report_is_in_place_does_not_say_nothing_was_written(
    tmp_path, scene, capsys, monkeypatch
):
    # The signal lands between the report's commit and the command's bookkeeping.
    real = report_folder.write_folder

    def write_folder(*args, **kwargs):
        real(*args, **kwargs)
        raise KeyboardInterrupt

    monkeypatch.setattr(report_folder, "write_folder", write_folder)
    from linkage import report

    monkeypatch.setattr(report, "write_folder", write_folder)
    out = tmp_path / "report"
    assert main(["run", str(scene), "--out", str(out), *FAST]) == 130
    line = one_line(capsys.readouterr().err)
    assert "nothing was written" not in line and str(out) in line, line
    assert intact(out)


@pytest.mark.parametrize("delay", [0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
def test_sigterm_at_any_moment_tells_the_truth(tmp_path, scene, delay):
    out = tmp_path / "report"
    child = subprocess.Popen(
        linkage("run", str(scene), "--out", str(out), *FAST),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env(tmp_path),
    )
    time.sleep(delay)
    child.send_signal(signal.SIGTERM)
    _, err = child.communicate(timeout=300)
    assert temporaries(tmp_path) == []
    if child.returncode == 0:
        assert err == "" and intact(out)
        return
    if child.returncode == -signal.SIGTERM:  # before the command began (or after it ended)
        assert err == "" and (not out.exists() or intact(out)), err
        return
    line = one_line(err)
    assert child.returncode == 143 and "stopped by SIGTERM" in line, err
    if "nothing was written" in line:
        assert not out.exists(), line
    else:
        assert intact(out), line


def test_a_run_that_finds_another_runs_report_where_there_was_none_is_told_so(tmp_path):
    out = tmp_path / "report"

    def fill(folder: Path) -> list[str]:
        # Meanwhile another run puts its report where there was none.
        report_folder.write_folder(
            out, "other", lambda f: [(f / "data.csv").write_text("1\n") and "data.csv"]
        )
        (folder / "data.csv").write_text("2\n")
        return ["data.csv"]

    with pytest.raises(report_folder.LinkageError) as caught:
        report_folder.write_folder(out, "fast", fill)
    message = str(caught.value)
    assert message.startswith(f"another linkage run wrote {out} while this one ran"), message
    assert "nothing was written" in message and "--force" in message
    assert (out / "data.csv").read_text() == "1\n" and intact(out)
    assert temporaries(tmp_path) == []


def test_a_warning_is_one_line_naming_no_source_file(monkeypatch, capsys):
    """A warning raised during a command (a corrupt default atlas rebuilt, a force with no
    effect) reads ``linkage: warning: ...``: Python's format had printed the library's file,
    line and source line."""
    import warnings

    from linkage import catalog, cli

    def table(**_):
        warnings.warn("rebuilding the default fourbar atlas: /cache/atlas-x: bad", stacklevel=2)
        return []

    monkeypatch.setattr(catalog, "table", table)
    monkeypatch.setattr(catalog, "format_table", lambda rows, tol: ["(no rows)"])
    assert cli.main(["catalog"]) == 0
    err = capsys.readouterr().err
    assert err == "linkage: warning: rebuilding the default fourbar atlas: /cache/atlas-x: bad\n"
    assert warnings.showwarning.__module__ == "warnings"  # restored after the command


def test_another_librarys_deprecation_notice_is_not_said_as_linkages(monkeypatch, capsys):
    """Under pytest (or -W), a DXF export's first import of ezdxf raised pyparsing's deprecation
    notices, which the command printed as ``linkage: warning: 'parseString' deprecated``; the
    tool's own warnings are still said."""
    import warnings

    from linkage import catalog, cli

    def table(**_):
        warnings.simplefilter("always")
        warnings.warn_explicit(
            "'parseString' deprecated", DeprecationWarning, "/venv/ezdxf/queryparser.py", 57
        )
        warnings.warn("the tool's own", stacklevel=2)
        return []

    monkeypatch.setattr(catalog, "table", table)
    monkeypatch.setattr(catalog, "format_table", lambda rows, tol: ["(no rows)"])
    assert cli.main(["catalog"]) == 0
    assert capsys.readouterr().err == "linkage: warning: the tool's own\n"


def test_a_straightness_tolerance_of_a_whole_size_or_more_is_refused(capsys):
    """``linkage catalog --tol 1e300`` printed a table of parts "within 1e+300 × size"."""
    from linkage import cli

    assert cli.main(["catalog", "--tol", "1e300", "--no-cache"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("linkage: error: rel_tol must be above 0 and below 1"), err
