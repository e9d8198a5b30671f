"""The ``linkage`` command: ``run`` a scene (the main job), ``check`` one, list the ``catalog``.

``linkage run`` with no scene runs the built-in default, thesis 1's quadruped on Hoecken legs
under its drive (the same as ``examples/quadruped_hoecken.toml``).

Exit status: 0 done; 2 a mistake in the scene or arguments, a refused or failed report folder, or
out of memory (one line on stderr, nothing written); 3 an internal error (a bug; set
LINKAGE_DEBUG=1 for the traceback); 130 interrupted by Ctrl-C, 143 stopped by SIGTERM, 129 by
SIGHUP (nothing written: a report being written is removed as after Ctrl-C); 141 (128 + SIGPIPE)
when the reader of the output went away (``linkage catalog | head -1``), silently, as a Unix
tool cut off by its reader (a report already in place stays).
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import os
import shutil
import signal
import sys
import textwrap
import threading
import time
import traceback
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

from linkage import catalog, scene
from linkage._core import LinkageError
from linkage._shared.report_folder import STOP_SIGNALS, recording

__all__ = [
    "EXIT_ERROR",
    "EXIT_INTERNAL",
    "EXIT_INTERRUPTED",
    "EXIT_PIPE",
    "MAX_FRAMES",
    "Stopped",
    "main",
    "print_table",
]

EXIT_ERROR = 2
"""Exit status for a mistake in the scene or the arguments, or a failed write."""
EXIT_INTERNAL = 3
"""Exit status for an internal error (a bug in linkage)."""
EXIT_INTERRUPTED = 130
"""Exit status after Ctrl-C (128 + SIGINT, as shells report it); after SIGTERM or SIGHUP, 128
plus its number."""
EXIT_PIPE = 141
"""Exit status when the reader of the output went away (128 + SIGPIPE, as a shell reports a Unix
tool that its reader cut off)."""


class Stopped(KeyboardInterrupt):
    """SIGTERM or SIGHUP while a command runs.

    ``kill``, ``timeout``, a cancelled CI job or a closed terminal: raised as Ctrl-C's
    ``KeyboardInterrupt`` is, so a report being written is removed the same way.
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


DEBUG_ENV = "LINKAGE_DEBUG"


MAX_FRAMES = 2000
"""The most animation frames a run draws: each is a full figure render, so more is only slower."""


def print_table(
    title: str, rows: Sequence[tuple[str, str, str, str]], width: int | None = None
) -> None:
    """Print rows as an aligned four-column table, at most ``width`` columns wide.

    ``width`` defaults to the terminal's (100 when the output is not a terminal). A table
    wider than that wraps cells at spaces onto lines of their own in the same column: the
    error estimates first, the figure names next, the values last (a drive's description, where
    that saves lines); a word longer than its column stays whole.

    Examples
    --------
    >>> from linkage.cli import print_table
    >>> print_table("hoecken", [("stride", "43.53", "mm", "±0.02"), ("legs", "A, B", "", "")])
    hoecken
    ------  -----  ----  --------------
    figure  value  unit  error estimate
    ------  -----  ----  --------------
    stride  43.53  mm    ±0.02
    legs    A, B
    ------  -----  ----  --------------
    >>> drive = ("drive", "constant 50 rpm through 18→15→14 gears", "", "exact")
    >>> stride = ("stride", "44.25", "mm", "±0.12 (vs 360 and 1441 samples)")
    >>> print_table("quadruped", [drive, stride], width=50)
    quadruped
    ------  -----------------  ----  -----------------
    figure  value              unit  error estimate
    ------  -----------------  ----  -----------------
    drive   constant 50 rpm          exact
            through 18→15→14
            gears
    stride  44.25              mm    ±0.12 (vs 360 and
                                     1441 samples)
    ------  -----------------  ----  -----------------
    """
    head = ("figure", "value", "unit", "error estimate")
    limit = width if width is not None else shutil.get_terminal_size((100, 24)).columns
    widths = _column_widths([head, *rows], limit)
    line = "  ".join("-" * w for w in widths)

    def emit(cells: Sequence[str]) -> None:
        parts = [textwrap.wrap(c, w, break_long_words=False) or [""] for c, w in zip(cells, widths)]
        for k in range(max(len(p) for p in parts)):
            row = [p[k] if k < len(p) else "" for p in parts]
            print("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip())

    print(title)
    print(line)
    emit(head)
    print(line)
    for r in rows:
        emit(r)
    print(line)


def _column_widths(rows: Sequence[Sequence[str]], limit: int) -> list[int]:
    """Return the widths of the four columns of ``rows`` (the heading first) within ``limit``.

    Each column is as wide as its longest cell if they fit. Otherwise the figure, value and
    error columns (not the unit) are narrowed, never below their heading or longest word, to
    the widths of least cost, tried all: each line of the table costs 1, and each extra line of
    a wrapped value 2 more, of a wrapped figure name 1 more. So the notes wrap first, a name
    next and a value last; a name is not split just because its row's note takes two lines
    anyway.
    """
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    room = limit - 6 - widths[2]
    if sum(widths) - widths[2] <= room:
        return widths
    # The narrowest each column may get: its heading, its longest word (never split inside a
    # word).
    words = [max(len(w) for r in rows for w in (r[i].split() or [""])) for i in range(4)]
    floor = [max(len(rows[0][i]), words[i]) for i in range(4)]
    wrapped: dict[tuple[str, int], int] = {}

    def lines(cell: str, w: int) -> int:
        if len(cell) <= w:
            return 1
        if (cell, w) not in wrapped:
            wrapped[cell, w] = len(textwrap.wrap(cell, w, break_long_words=False))
        return wrapped[cell, w]

    def counts(i: int, w: int) -> list[int]:
        return [lines(r[i], w) for r in rows]

    fig = {w: counts(0, w) for w in range(floor[0], widths[0] + 1)}
    val = {w: counts(1, w) for w in range(floor[1], widths[1] + 1)}
    err: dict[int, list[int]] = {}
    best: tuple[tuple[int, int, int, int, int], list[int]] | None = None
    for w1, n1 in val.items():
        for w0, n0 in fig.items():
            w3 = min(room - w0 - w1, widths[3])
            if w3 < floor[3]:
                continue
            n3 = err.setdefault(w3, counts(3, w3))
            height = sum(max(a, b, c) for a, b, c in zip(n0, n1, n3))
            cost = (height + 2 * sum(n1) + sum(n0), sum(n1), sum(n0), -w1, -w0)
            if best is None or cost < best[0]:
                best = cost, [w0, w1, widths[2], w3]
    # Nothing fits: every column at its narrowest (the table is wider than the limit).
    return best[1] if best is not None else [floor[0], floor[1], widths[2], floor[3]]


class _Progress:
    """A one-line progress display on a terminal; silent otherwise."""

    def __init__(self, enabled: bool, total: int) -> None:
        self.enabled = enabled and sys.stderr.isatty()
        self.total, self.done = total, 0

    def __call__(self, stage: str) -> None:
        if self.enabled:
            self.done += 1
            bar = "#" * self.done + "." * max(0, self.total - self.done)
            sys.stderr.write(f"\r[{bar}] {stage:<14}")
            sys.stderr.flush()

    def close(self) -> None:
        if self.enabled:
            sys.stderr.write("\r" + " " * (self.total + 20) + "\r")


def _load(path: str | None):  # type: ignore[no-untyped-def]
    if path is None:
        return scene.parse(scene.DEFAULT_SCENE, None, name="quadruped-hoecken")
    return scene.load(path)


def _run(args: argparse.Namespace, state: dict[str, Path]) -> int:
    # The total counts from here: the report's imports, the scene, the stages and the folder
    # (not the interpreter's start and `import linkage`, which come before any command).
    t0 = time.perf_counter()
    # matplotlib (0.3 s) only for `run`, not for check/catalog/--help.
    from linkage import report  # noqa: PLC0415
    from linkage.report import stages as runner  # noqa: PLC0415

    sc = _load(args.scene)
    if args.out is not None:
        out = Path(os.path.expanduser(args.out))
    else:
        out = report.default_folder(sc.name)
    # Refuse before computing anything: nothing the user has is touched, and --force replaces
    # only a folder linkage wrote (see linkage.report_folder).
    report.prepare(out, args.force)
    progress = _Progress(not args.quiet, 8)
    try:
        res = runner.run(sc, samples=args.samples, progress=progress)
        progress("report")
        files = report.write(res, out, frames=args.frames, force=args.force)
    finally:
        progress.close()
    state["written"] = out
    if args.quiet:
        return 0
    rows = list(res.figures)
    for name, sec in res.stages.items():
        rows.append((f"stage: {name}", f"{1e3 * sec:.1f}", "ms", "wall clock"))
    total = time.perf_counter() - t0
    other = total - sum(res.stages.values())
    rows.append(
        ("outside the stages", f"{1e3 * max(other, 0.0):.1f}", "ms", "imports, scene, folder")
    )
    rows.append(("total", f"{1e3 * total:.1f}", "ms", "wall clock"))
    title = f"{sc.name}" + (f" — {sc.description}" if sc.description else "")
    print_table(title, rows)
    print(f"report: {out}/ ({', '.join(sorted(p.name for p in files))})")
    return 0


def _check(args: argparse.Namespace, state: dict[str, Path]) -> int:
    sc = _load(args.scene)
    print(f"ok: {sc.name}: outputs {', '.join(sc.outputs)}")
    return 0


def _catalog(args: argparse.Namespace, state: dict[str, Path]) -> int:
    rows = catalog.table(rel_tol=args.tol, samples=args.samples, cache=not args.no_cache)
    for line in catalog.format_table(rows, args.tol):
        print(line)
    return 0


def _synth(args: argparse.Namespace, state: dict[str, Path]) -> int:
    from linkage import synthesis  # noqa: PLC0415 (scipy and the atlases on demand)
    from linkage.cli import synthesize  # noqa: PLC0415

    # The package's path() as it is when called (a test or a user may have replaced it).
    return synthesize.command(args, synthesis.path)


def _design(args: argparse.Namespace, state: dict[str, Path]) -> int:
    try:
        from linkage import design  # noqa: PLC0415 (needs the optional extra [design])
    except ImportError as exc:
        raise LinkageError(str(exc)) from None
    # A search stopped after its first generation keeps its checkpoint (main_design says where):
    # the closing line then says no report was written, not that nothing was.
    state["checkpoint"] = Path(args.checkpoint or ".")
    return design.main_design(args.study, args.out, args.force, args.checkpoint, args.quiet)


def _parser() -> argparse.ArgumentParser:
    """Return the parser of the ``linkage`` command and its sub-commands."""
    parser = argparse.ArgumentParser(
        prog="linkage", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser(
        "run", help="run a scene (default: thesis 1's quadruped) and write its report"
    )
    run.add_argument("scene", nargs="?", default=None, help="scene file (TOML); see examples/")
    run.add_argument("--out", help="report folder (default ./linkage-report/<scene name>)")
    run.add_argument(
        "--force",
        action="store_true",
        help="replace an earlier report linkage wrote (never a folder it did not write)",
    )
    run.add_argument("--quiet", action="store_true", help="no progress, no table")
    run.add_argument("--samples", type=int, default=None, help="override the scene's samples")
    run.add_argument(
        "--frames",
        type=int,
        default=48,
        help=f"animation frames (default 48, at most {MAX_FRAMES})",
    )
    run.set_defaults(func=_run)
    check = sub.add_parser("check", help="validate a scene without running it")
    check.add_argument("scene", help="scene file (TOML)")
    check.set_defaults(func=_check)
    cat = sub.add_parser(
        "catalog", help="list the built-in linkages with their straight-line figures"
    )
    cat.add_argument("--tol", type=float, default=1e-3, help="straightness tolerance / size")
    cat.add_argument(
        "--samples",
        type=int,
        default=catalog.TABLE_SAMPLES,
        help=f"samples per circuit (default {catalog.TABLE_SAMPLES})",
    )
    cat.add_argument(
        "--no-cache", action="store_true", help="recompute instead of using the user cache"
    )
    cat.set_defaults(func=_catalog)
    des = sub.add_parser(
        "design", help="search walking-leg designs (a [design] study): Pareto front and report"
    )
    des.add_argument("study", help="study file (TOML with a [design] section); see examples/")
    des.add_argument("--out", help="report folder (default ./linkage-report/<study name>)")
    des.add_argument("--force", action="store_true", help="replace an earlier report it wrote")
    des.add_argument(
        "--checkpoint", help="checkpoint file (default .<out>.checkpoint beside the report)"
    )
    des.add_argument("--quiet", action="store_true", help="no progress bar, no summary")
    des.set_defaults(func=_design)
    syn = sub.add_parser(
        "synth", help="four-bars (or slider-cranks) whose coupler curve passes through points"
    )
    syn.add_argument("curve", help="CSV file of target points x,y (one a line, in order)")
    syn.add_argument("--top", type=int, default=5, help="candidates shown (default 5)")
    syn.add_argument("--open", action="store_true", help="the points are part of a curve")
    syn.add_argument("--units", default="", help="length unit shown in the table, e.g. mm")
    syn.add_argument("--full-turn", action="store_true", help="only cranks that turn fully")
    syn.add_argument(
        "--min-transmission-deg",
        type=float,
        default=0.0,
        help="least distance of the transmission angle from a toggle, in degrees",
    )
    syn.add_argument(
        "--lengths",
        type=float,
        nargs=2,
        metavar=("LEAST", "GREATEST"),
        help="every link's length within these (target units)",
    )
    syn.add_argument(
        "--pivots",
        type=float,
        nargs=4,
        metavar=("XMIN", "YMIN", "XMAX", "YMAX"),
        help="ground pivots within this box (target units)",
    )
    syn.add_argument(
        "--refine",
        type=int,
        default=8,
        help="atlas matches refined by least squares, at least --top (default 8): a deeper, "
        "slower search",
    )
    syn.add_argument("--seed", type=int, default=0, help="the global search's seed (default 0)")
    syn.add_argument(
        "--tol",
        type=float,
        default=1e-3,
        help="run the global search while the best error exceeds this fraction of the size",
    )
    syn.add_argument(
        "--kind",
        choices=("fourbar", "slider-crank", "any"),
        default="fourbar",
        help="linkage sought (default fourbar; any: both, one ranking)",
    )
    syn.add_argument("--atlas", help="atlas folder (default: built once into the user cache)")
    syn.add_argument(
        "--accept",
        type=float,
        default=None,
        help="an error (target units) good enough to stop the search's later stages",
    )
    syn.add_argument("--quiet", action="store_true", help="no progress bar")
    syn.set_defaults(func=_synth)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    r"""Entry point of the ``linkage`` console script.

    ``argv`` are the arguments (default: the command line's); returns the exit status (see the
    module's docstring). Errors are one line on stderr, never a traceback.

    Examples
    --------
    >>> import os, tempfile
    >>> from linkage.cli import main
    >>> tmp = tempfile.TemporaryDirectory()
    >>> scene = os.path.join(tmp.name, "leg.toml")
    >>> with open(scene, "w") as fh:
    ...     _ = fh.write('outputs = ["trajectory"]\n[mechanism]\ncatalog = "hoecken"\n'
    ...                  '[drive]\nkind = "constant"\nrpm = 50.0\nsamples = 73\n')
    >>> main(["check", scene])
    ok: leg: outputs trajectory
    0
    >>> main(["run", scene, "--out", os.path.join(tmp.name, "report"), "--quiet"])
    0
    >>> sorted(os.listdir(os.path.join(tmp.name, "report")))
    ['.linkage-report', 'data.csv', 'data.npz', 'index.html', 'summary.json', 'trajectory.png']

    A mistake is one line on stderr and exit status 2, with nothing written:

    >>> main(["run", os.path.join(tmp.name, "missing.toml"), "--out", os.path.join(tmp.name, "x")])
    2
    >>> sorted(os.listdir(tmp.name))
    ['leg.toml', 'report']
    >>> tmp.cleanup()
    """
    parser = _parser()
    stdout = sys.stdout
    try:
        try:
            args = parser.parse_args(argv)
        finally:
            # --help and --version exit inside: a reader gone away shows on this flush (on
            # Python 3.9 already on the write), not at the interpreter's exit.
            sys.stdout.flush()
    except BrokenPipeError:
        return _pipe_closed(stdout)
    if getattr(args, "samples", None) is not None and args.samples < 8:
        parser.error("--samples must be at least 8")
    if not 2 <= getattr(args, "frames", 2) <= MAX_FRAMES:
        parser.error(f"--frames must be between 2 and {MAX_FRAMES}")
    state: dict[str, Path] = {}
    signals: list[int] = []
    written: list[Path] = []
    try:
        with _signals_noted(signals), recording() as written, _stdout_named(), _warnings_said():
            code = int(args.func(args, state))
            # Inside: a reader gone away or a full disk shows on this flush, not at exit.
            sys.stdout.flush()
            return code
    except BrokenPipeError:
        return _pipe_closed(stdout)
    except (SystemExit, GeneratorExit):
        raise
    except BaseException as exc:
        if written:
            # Recorded in the same step as the rename: true even if a signal came before the
            # command itself noted the report.
            state["written"] = written[-1]
        if isinstance(exc, KeyboardInterrupt):
            return _stopped(exc.signum if isinstance(exc, Stopped) else signal.SIGINT, state)
        if signals:
            # The signal's KeyboardInterrupt was raised inside a library that turned it into an
            # error of its own (matplotlib's C++ renderer reports "Invalid bounding box"):
            # still a stop
            return _stopped(signals[-1], state)
        return _failed(exc, state)


_PACKAGE = Path(__file__).resolve().parent.parent
"""The installed ``linkage`` package's folder: warnings from inside it are the tool's own."""

STDOUT = "<stdout>"
"""The file name given to an error writing the standard output."""


class _NamedOutput:
    """The standard output, whose write errors name it (``write()`` gives no file name)."""

    def __init__(self, stream: Any) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            return int(self._stream.write(text))
        except OSError as exc:
            raise _named(exc) from None

    def flush(self) -> None:
        try:
            self._stream.flush()
        except OSError as exc:
            raise _named(exc) from None

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _named(exc: OSError) -> OSError:
    if exc.filename is None:
        exc.filename = STDOUT
    return exc


@contextlib.contextmanager
def _stdout_named() -> Iterator[None]:
    was = sys.stdout
    sys.stdout = _NamedOutput(was)
    try:
        yield
    finally:
        sys.stdout = was


def _pipe_closed(stdout: Any) -> int:
    """End quietly when the reader went away, as Python's documentation of SIGPIPE advises.

    The standard output is pointed at ``os.devnull`` so that the interpreter's own flush at exit
    does not fail again; the status is 128 + SIGPIPE, what a shell shows for a Unix tool there.
    """
    _discard_output(stdout)
    return EXIT_PIPE


def _discard_output(stdout: Any) -> None:
    """Point the standard output at ``os.devnull``: what is still buffered goes nowhere.

    After a write to it failed (a closed pipe, a full disk, ``ulimit -f``), the interpreter's
    own flush at exit would fail again and print "Exception ignored" under our one line.
    """
    with contextlib.suppress(OSError, ValueError, AttributeError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, stdout.fileno())
        os.close(devnull)


def _stopped(signum: int, state: dict[str, Path]) -> int:
    """Say that a signal stopped the command, and give its exit status (128 + its number)."""
    if signum == signal.SIGINT:
        _say(f"interrupted; {_written(state)}")
        return EXIT_INTERRUPTED
    _say(f"stopped by {signal.Signals(signum).name}; {_written(state)}")
    return 128 + int(signum)


def _failed(exc: BaseException, state: dict[str, Path]) -> int:
    """Say what went wrong in one line and give the exit status for it."""
    if isinstance(exc, LinkageError):
        _say(f"error: {exc}")
        return EXIT_ERROR
    if isinstance(exc, MemoryError):
        detail = f": {exc}" if str(exc) else ""
        _say(f"error: out of memory{detail} ({_written(state)})")
        return EXIT_ERROR
    if isinstance(exc, OSError):
        if exc.errno == errno.EPIPE:  # a BrokenPipeError a library wrapped
            return _pipe_closed(sys.stdout)
        if exc.filename == STDOUT:
            # The output is cut short; a report, if any, was written before it was printed.
            report = f" ({_written(state)})" if "written" in state else ""
            _say(
                f"error: cannot write to the standard output: {exc.strerror or exc}; the output "
                f"is incomplete{report}"
            )
            _discard_output(sys.stdout)
            return EXIT_ERROR
        where = f"{exc.filename}: " if exc.filename is not None else ""
        _say(f"error: {where}{exc.strerror or exc} ({_written(state)})")
        return EXIT_ERROR
    # a bug (a Rust panic is a BaseException): say so, no traceback
    _say(
        f"internal error (a bug in linkage, please report it): "
        f"{type(exc).__name__}: {exc} (set {DEBUG_ENV}=1 for the traceback; "
        f"{_written(state)})"
    )
    if os.environ.get(DEBUG_ENV):
        traceback.print_exception(type(exc), exc, exc.__traceback__)
    return EXIT_INTERNAL


@contextlib.contextmanager
def _signals_noted(signals: list[int]) -> Iterator[None]:
    """Note every Ctrl-C, SIGTERM and SIGHUP in ``signals``, and raise as Python does for Ctrl-C.

    ``KeyboardInterrupt`` for Ctrl-C, :class:`Stopped` for the others. Main thread only
    (elsewhere Python delivers no signals), and only for a signal whose handler is still Python's
    own (Ctrl-C) or the default (the others); the previous handlers are restored on the way out.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def note(signum: int, frame: object) -> None:
        signals.append(signum)
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        raise Stopped(signum)

    previous = {}
    for signum in (signal.SIGINT, *STOP_SIGNALS):
        was = signal.getsignal(signum)
        default = signal.default_int_handler if signum == signal.SIGINT else signal.SIG_DFL
        if was is default:
            previous[signum] = was
            signal.signal(signum, note)
    try:
        yield
    finally:
        for signum, was in previous.items():
            signal.signal(signum, was)


def _written(state: dict[str, Path]) -> str:
    if "written" in state:
        return f"the report was written to {state['written']}/"
    if "checkpoint" in state:
        return "no report was written"
    return "nothing was written"


@contextlib.contextmanager
def _warnings_said() -> Iterator[None]:
    """Print each warning a command raises as one ``linkage: warning: ...`` line.

    Python's own format (the library's file and line, then its source line) is for programmers;
    the message is what the user needs. The previous handler is restored afterwards.
    """

    def show(
        message: Warning | str,
        category: type[Warning],
        filename: str,
        lineno: int,
        file: Any = None,
        line: str | None = None,
    ) -> None:
        # Another library's deprecation notice (pyparsing's, met through ezdxf) is for that
        # library's programmers, not for the user of the command: Python hides it by default,
        # but not under a test runner or -W, and it would print as if linkage said it.
        if issubclass(category, DeprecationWarning) and _PACKAGE not in Path(filename).parents:
            return
        _say(f"warning: {message}")

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield


def _say(line: str) -> None:
    """One line on stderr, prefixed with the program name (never raising itself)."""
    with contextlib.suppress(OSError, ValueError):
        print(f"linkage: {line}", file=sys.stderr)
        sys.stderr.flush()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
