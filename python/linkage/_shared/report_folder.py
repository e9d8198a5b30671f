"""Safe report folders: written whole or not at all, and only what linkage wrote is removed.

A report folder is on the user's disk, so this module removes only what it wrote:

- every report folder carries a marker file, ``.linkage-report`` (JSON: tool, version, scene,
  the files written and each one's SHA-256), written last;
- a report is written into a temporary sibling (``.<name>.partial-<pid>``) and renamed into place
  when complete; any failure, ``KeyboardInterrupt`` included, removes the temporary folder and
  leaves an earlier report untouched;
- ``force`` replaces a folder only if it carries the marker and holds nothing but the files the
  marker lists, each as linkage wrote it (a file the user edited, a candidate scene tuned in
  place, is refused by name; a marker without hashes, from a build before they were recorded,
  counts a listed file modified after the marker as edited); the old report is renamed aside,
  the new one renamed in, and then the old one is removed file by file (only the listed files;
  never ``rmtree`` on a folder the tool did not create);
- a target that is a symbolic link (dangling or not), not a folder, the file-system root, the home
  folder, the working directory or one of their ancestors is refused, force or not;
- concurrent runs on one folder do not trip over each other: the check and the swap hold a lock on
  the parent folder (``flock``, where the file system has it), and a check that another run's swap
  overtook is made again on what is there now, so a run is never told the user edited files that
  another run replaced; a run that finds another's report where it found none is told so;
- a later write into the same parent folder sweeps what a killed run (``kill -9``, power loss)
  left there: a temporary folder of a dead process holding nothing but files the tool writes
  (:data:`TOOL_FILE`), and a set-aside old report (put back where it was if nothing replaced it,
  else removed file by file as above, and only if it is whole and holds nothing else);
- a failed write names the file: a full disk, a quota or ``ulimit -f`` report no file name, so the
  last file the run opened for writing in the folder is named.

:func:`prepare` checks a target before anything is computed; :func:`write_folder` writes any
folder of results this way (the run's report, :func:`linkage.report.write`; the design search's,
:func:`linkage.design.report.write_report`). Every refusal is a ``LinkageError`` that names the
folder and the reason.
"""

from __future__ import annotations

import contextlib
import datetime
import errno
import hashlib
import json
import os
import re
import shutil
import signal
import stat
import sys
import threading
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

from linkage._core import LinkageError
from linkage._shared.files import pid_alive
from linkage._shared.version import __version__

__all__ = [
    "DEFAULT_BASE",
    "MARKER",
    "TOOL_FILE",
    "default_folder",
    "prepare",
    "read_marker",
    "recording",
    "sweep",
    "write_folder",
]

MARKER = ".linkage-report"
"""Name of the marker file that makes a folder a report linkage wrote (and may replace)."""

DEFAULT_BASE = Path("linkage-report")
"""Where reports go without ``--out``: ``linkage-report/<scene name>``."""

_SAFE_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,127}")
_NOTHING = "nothing was written"


def default_folder(name: str, base: Path = DEFAULT_BASE) -> Path:
    """Return the default report folder of a scene called ``name``: ``base/name``.

    Refused unless ``name`` is a single plain folder name that stays inside ``base`` (no ``.``,
    ``..``, separators, or a leading dot, which is kept for the tool's temporary folders).

    Examples
    --------
    >>> from linkage.report_folder import default_folder
    >>> default_folder("hoecken").as_posix()
    'linkage-report/hoecken'
    >>> default_folder("../hoecken")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: scene name '../hoecken' cannot name a folder inside linkage-report/ ...
    """
    if not _SAFE_NAME.fullmatch(name) or name in (".", ".."):
        raise LinkageError(
            f"scene name {name!r} cannot name a folder inside {base}/ (it must start with a "
            f"letter or digit and hold only letters, digits, '_', '-' or '.'); give --out "
            f"({_NOTHING})"
        )
    folder = base / name
    try:
        inside = folder.resolve().parent == base.resolve()
    except (OSError, RuntimeError):
        inside = False
    if not inside:
        raise LinkageError(f"{folder} would not be inside {base}/; give --out ({_NOTHING})")
    return folder


def read_marker(folder: Path) -> dict[str, Any] | None:
    """Read the marker of a report folder written by linkage, or ``None`` if it has none.

    A marker that does not parse as a linkage marker counts as none: such a folder is treated as the
    user's.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.report_folder import MARKER, read_marker, write_folder
    >>> tmp = tempfile.TemporaryDirectory()
    >>> out = Path(tmp.name) / "out"
    >>> _ = write_folder(out, "demo", lambda f: [(f / "a.txt").write_text("a") and "a.txt"])
    >>> marker = read_marker(out)
    >>> marker["tool"], marker["scene"], marker["files"]
    ('linkage', 'demo', ['a.txt'])
    >>> _ = (out / MARKER).write_text('{"tool": "other"}')
    >>> read_marker(out), read_marker(Path(tmp.name))     # not linkage's; no marker
    (None, None)
    >>> tmp.cleanup()
    """
    path = folder / MARKER
    try:
        if not path.is_file() or path.is_symlink():
            return None
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("tool") != "linkage":
        return None
    files = data.get("files")
    if not isinstance(files, list) or not all(_plain_name(f) for f in files):
        return None
    digests = data.get(_DIGESTS, {})
    if not isinstance(digests, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in digests.items()
    ):
        return None
    return data


_DIGESTS = "sha256"
"""The marker's key for the SHA-256 (hex) of each file written, by name."""


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with path.open("rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _edited(folder: Path, where: str, marker: dict[str, Any]) -> list[str]:
    """Return the listed files in ``folder`` whose content is not what linkage wrote.

    A marker with hashes is compared file by file. A marker without them (written before they
    were recorded) cannot tell, so a file modified after the marker (which is written last) counts
    as edited. A listed file that is gone is not edited: there is nothing to lose.
    """
    digests = marker.get(_DIGESTS)
    try:
        since = None if digests is not None else (folder / MARKER).stat().st_mtime_ns
    except OSError as exc:
        raise LinkageError(f"{where}: cannot read {MARKER}: {exc.strerror} ({_NOTHING})") from None
    edited = []
    for name in marker["files"]:
        path = folder / name
        if not path.is_file() or path.is_symlink():
            continue
        try:
            if digests is None:
                assert since is not None
                changed = path.stat().st_mtime_ns > since
            else:
                changed = digests.get(name) != _sha256(path)
        except OSError as exc:
            raise LinkageError(
                f"{where}: cannot read {name}: {exc.strerror} ({_NOTHING})"
            ) from None
        if changed:
            edited.append(name)
    return edited


def _some(names: Sequence[str]) -> str:
    """Name at most five of ``names``, then how many more."""
    more = f" and {len(names) - 5} more" if len(names) > 5 else ""
    return ", ".join(names[:5]) + more


def _plain_name(f: object) -> bool:
    return (
        isinstance(f, str) and f not in ("", ".", "..", MARKER) and "/" not in f and "\\" not in f
    )


def _describe(folder: Path, target: Path) -> str:
    return str(folder) if Path(os.path.abspath(folder)) == target else f"{folder} (= {target})"


def _resolve(folder: Path) -> Path:
    """Return the real path the report would occupy, refusing every target not a folder of its own.

    Refused: a link, the root, home, the working directory or an ancestor of those.
    """
    if folder.is_symlink():
        try:
            to = os.readlink(folder)
        except OSError:
            to = "?"
        dangling = "dangling " if not folder.exists() else ""
        raise LinkageError(
            f"{folder} is a {dangling}symbolic link (to {to}); give a real folder ({_NOTHING})"
        )
    try:
        target = folder.resolve()
    except (OSError, RuntimeError) as exc:
        raise LinkageError(f"{folder}: cannot resolve the path: {exc} ({_NOTHING})") from None
    where = _describe(folder, target)
    if target.parent == target:
        raise LinkageError(f"{where} is the root of the file system; refused ({_NOTHING})")
    protected: list[tuple[Path, str]] = []
    with contextlib.suppress(OSError, RuntimeError):
        protected.append((Path.cwd().resolve(), "the working directory"))
    with contextlib.suppress(OSError, RuntimeError, KeyError):
        protected.append((Path.home().resolve(), "the home folder"))
    for base, what in protected:
        if target == base:
            raise LinkageError(
                f"{where} is {what}; a report needs a folder of its own ({_NOTHING})"
            )
        if target in base.parents:
            raise LinkageError(
                f"{where} holds {what}; a report needs a folder of its own ({_NOTHING})"
            )
    if os.path.lexists(target) and not target.is_dir():
        raise LinkageError(f"{where} exists and is not a folder ({_NOTHING})")
    return target


_RECHECKS = 5
"""How many times a check overtaken by another run's swap is made again before giving up."""


def _identity(target: Path) -> tuple[int, int, bytes] | None:
    """Return what changes when another run swaps ``target``: its inode and its marker's bytes.

    ``None`` if there is no folder.
    """
    try:
        info = os.lstat(target)
    except OSError:
        return None
    marker = b""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0)
    with contextlib.suppress(OSError):
        fd = os.open(target / MARKER, flags | os.O_CLOEXEC)
        try:
            if stat.S_ISREG(os.fstat(fd).st_mode):  # not a pipe or a device
                marker = os.read(fd, 1 << 20)
        finally:
            os.close(fd)
    return info.st_dev, info.st_ino, marker


def _check_existing(folder: Path, target: Path, force: bool) -> dict[str, Any] | None:
    """For an existing ``target``: its marker if ``force`` may replace it; otherwise refuse.

    The check reads the marker and then every file: another linkage run that swaps its own
    report in meanwhile would make the files disagree with the marker read before. So the folder
    and its marker are compared before and after, and an overtaken check is made again on what
    is there now (a folder that is gone by then needs no check: ``None``).
    """
    for _ in range(_RECHECKS):
        before = _identity(target)
        if before is None and not os.path.lexists(target):
            return None
        try:
            marker = _check_once(folder, target, force)
        except LinkageError:
            if _identity(target) == before:
                raise
            continue
        if _identity(target) == before:
            return marker
    raise LinkageError(
        f"{_describe(folder, target)} changed while linkage checked it, {_RECHECKS} times over "
        f"(other runs writing it?); run again when they are done ({_NOTHING})"
    )


def _check_once(folder: Path, target: Path, force: bool) -> dict[str, Any] | None:
    """:func:`_check_existing` once, on a folder that does not change meanwhile."""
    where = _describe(folder, target)
    marker = read_marker(target)
    if marker is None:
        raise LinkageError(
            f"{where} exists and is not a report written by linkage (no readable {MARKER} "
            f"marker); --force replaces only folders linkage wrote: choose another --out or "
            f"remove it yourself ({_NOTHING})"
        )
    if not force:
        raise LinkageError(
            f"{where} holds an earlier report; pass --force to replace it ({_NOTHING})"
        )
    listed = set(marker["files"])
    try:
        entries = sorted(os.listdir(target))
    except OSError as exc:
        raise LinkageError(
            f"{where}: cannot list the folder: {exc.strerror} ({_NOTHING})"
        ) from None
    foreign = [
        e
        for e in entries
        if e != MARKER
        and (e not in listed or not (target / e).is_file() or (target / e).is_symlink())
    ]
    if foreign:
        raise LinkageError(
            f"{where} holds files linkage did not write ({_some(foreign)}); --force replaces "
            f"only a folder holding nothing but a linkage report: move them or choose another "
            f"--out ({_NOTHING})"
        )
    edited = _edited(target, where, marker)
    if edited:
        raise LinkageError(
            f"{where} holds files changed since linkage wrote them ({_some(edited)}); --force "
            f"would lose the changes: move them out or choose another --out ({_NOTHING})"
        )
    return marker


def prepare(folder: Path, force: bool) -> None:
    """Check, before anything is computed, that the report can be written to ``folder`` safely.

    Raise ``LinkageError`` naming the folder and the reason when it would lose anything. Nothing is
    created or removed here (``write`` repeats the check just before it moves anything).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.report_folder import prepare
    >>> tmp = tempfile.TemporaryDirectory()
    >>> prepare(Path(tmp.name) / "new", force=False)                # a new folder: fine
    >>> (Path(tmp.name) / "new").exists()
    False
    >>> mine = Path(tmp.name) / "mine"
    >>> mine.mkdir()
    >>> prepare(mine, force=True)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...mine exists and is not a report written by linkage (no readable...
    >>> prepare(Path("/"), force=True)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ... is the root of the file system; refused (nothing was written)
    >>> tmp.cleanup()
    """
    target = _resolve(folder)
    if os.path.lexists(target):
        _check_existing(folder, target, force)


STOP_SIGNALS: tuple[int, ...] = tuple(
    getattr(signal, name) for name in ("SIGTERM", "SIGHUP") if hasattr(signal, name)
)
"""Signals besides Ctrl-C that stop a command as it does (those this platform has): held off
the renames here, turned into :class:`linkage.cli.Stopped` by the command."""


@contextlib.contextmanager
def _sigint_held() -> Iterator[None]:
    """Hold Ctrl-C, SIGTERM and SIGHUP off a few renames or a clean-up: none is cut in half.

    Main thread only; elsewhere signals are not delivered to Python anyway.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {}
    try:
        for signum in (signal.SIGINT, *STOP_SIGNALS):
            previous[signum] = signal.signal(signum, signal.SIG_IGN)
    except (ValueError, OSError):
        pass
    try:
        yield
    finally:
        for signum, was in previous.items():
            signal.signal(signum, was)


def _make_sibling(parent: Path, name: str, kind: str) -> Path:
    """Create a new, empty hidden sibling folder ``.<name>.<kind>-<pid>[-k]`` in ``parent``."""
    stem = f".{name}.{kind}-{os.getpid()}"
    for k in range(1000):
        path = parent / (stem if k == 0 else f"{stem}-{k}")
        try:
            path.mkdir()
        except FileExistsError:
            continue
        return path
    raise FileExistsError(errno.EEXIST, "no free temporary folder name", str(parent / stem))


def _discard_partial(tmp: Path) -> None:
    """Remove a temporary folder this run created (everything in it is this run's)."""
    if tmp.is_dir() and not tmp.is_symlink() and ".partial-" in tmp.name:
        shutil.rmtree(tmp, ignore_errors=True)


def _remove_report(folder: Path, marker: dict[str, Any]) -> bool:
    """Remove a report folder linkage wrote; return whether the folder is gone.

    Only the files its marker lists are removed, then the marker, then the folder if it is empty.
    """
    for name in marker["files"]:
        path = folder / name
        if path.is_file() and not path.is_symlink():
            with contextlib.suppress(OSError):
                path.unlink()
    with contextlib.suppress(OSError):
        (folder / MARKER).unlink()
    try:
        folder.rmdir()
    except OSError:
        return False
    return True


@contextlib.contextmanager
def _parent_locked(parent: Path, wait: bool = True) -> Iterator[bool]:
    """Hold an exclusive ``flock`` on the folder ``parent`` (no file is created for it).

    Concurrent linkage runs writing into one parent check and swap their folders one at a time.
    Yields ``False`` only if ``wait`` is false and another process holds the lock. Where the
    platform or the file system has no ``flock`` the block runs unlocked (the checks are then
    only repeated when overtaken, see :func:`_check_existing`).
    """
    try:
        import fcntl  # noqa: PLC0415 (POSIX only)

        fd = os.open(parent, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | os.O_CLOEXEC)
    except (ImportError, OSError):
        yield True
        return
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX if wait else fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            yield False
            return
        except OSError:
            pass
        yield True
    finally:
        os.close(fd)  # releases the lock


TOOL_FILE = re.compile(
    r"(?:trajectory|rates|torque|cam|gait|stability|slip|synthesis|pareto|designs)\.png"
    r"|animation\.gif|index\.html|(?:data|candidates|front)\.csv|data\.npz|summary\.json"
    r"|mechanism\.(?:dxf|svg)|candidates\.parquet|(?:candidate|design)-\d{1,6}\.toml"
    r"|" + re.escape(MARKER)
)
"""The names of the files linkage writes into a report folder (of a run or a design search).

A temporary folder a dead process left is removed only if it holds nothing else."""

_LEFT = re.compile(r"\.(.+)\.(partial|old)-(\d+)(?:-\d+)?")
"""A temporary (``partial``) or set-aside (``old``) sibling: ``.<name>.<kind>-<pid>[-k]``."""


def sweep(parent: Path) -> list[str]:
    """Clean up what killed linkage runs left in ``parent``; return the names dealt with.

    Only folders (not links) named ``.<name>.partial-<pid>`` or ``.<name>.old-<pid>`` (with an
    optional ``-k``) whose process is gone are looked at, and of those only:

    - a temporary folder holding nothing but regular files of :data:`TOOL_FILE` names, removed
      file by file (the run was killed before its report was complete);
    - a set-aside old report that is whole (its marker lists every file in it, each as written):
      put back at ``<name>`` if nothing is there (the run was killed between its two renames),
      else removed as a replaced report is, listed files only; an empty one is removed.

    Anything else is left as it is: it may hold the user's files. Errors are ignored (another run
    may be sweeping too); call it holding the parent's lock.
    """
    done: list[str] = []
    try:
        names = sorted(os.listdir(parent))
    except OSError:
        return done
    for name in names:
        m = _LEFT.fullmatch(name)
        if m is None or m.group(1) in (".", "..") or pid_alive(int(m.group(3))):
            continue
        path = parent / name
        try:
            if not stat.S_ISDIR(os.lstat(path).st_mode):
                continue
            if m.group(2) == "partial":
                ok = _sweep_partial(path)
            else:
                ok = _sweep_old(path, parent / m.group(1))
        except (OSError, LinkageError):
            continue
        if ok:
            done.append(name)
    return done


def _sweep_partial(path: Path) -> bool:
    entries = os.listdir(path)
    for e in entries:
        if not TOOL_FILE.fullmatch(e) or not stat.S_ISREG(os.lstat(path / e).st_mode):
            return False
    for e in entries:
        os.unlink(path / e)
    path.rmdir()
    return True


def _sweep_old(path: Path, target: Path) -> bool:
    entries = os.listdir(path)
    if not entries:
        path.rmdir()  # killed after its last file and its marker were removed
        return True
    marker = read_marker(path)
    if marker is None:
        return False
    listed = set(marker["files"])
    for e in entries:
        if e != MARKER and (e not in listed or not stat.S_ISREG(os.lstat(path / e).st_mode)):
            return False
    if _edited(path, str(path), marker):
        return False
    if not os.path.lexists(target):
        os.rename(path, target)  # the earlier report, back where it was
        return True
    return _remove_report(path, marker)


_watching: dict[int, tuple[str, list[str]]] = {}
"""By thread: the folder being filled and the files opened for writing in it, in order."""
_hooked: list[bool] = []


def _audit(event: str, args: tuple[Any, ...]) -> None:
    """Note the files opened for writing inside a watched folder (an audit hook: never raises)."""
    if event != "open" or not _watching:
        return
    try:
        watch = _watching.get(threading.get_ident())
        if watch is None:
            return
        path, mode, flags = args
        if isinstance(flags, int) and flags:
            writing = bool(flags & (os.O_WRONLY | os.O_RDWR))
        else:
            writing = isinstance(mode, str) and any(c in mode for c in "wax+")
        if writing and isinstance(path, (str, bytes, os.PathLike)):
            name = os.path.abspath(os.fsdecode(path))
            if name.startswith(watch[0]):
                watch[1].append(name)
    except Exception:  # a hook must not break the open it watches
        pass


@contextlib.contextmanager
def _opened_for_writing(folder: Path, opened: list[str]) -> Iterator[None]:
    """Append to ``opened`` every file this thread opens for writing in ``folder``.

    So that a failed write() that names no file (a full disk, a quota, ``ulimit -f``) can be
    blamed on the file being written: the last one opened. Python's audit hooks see every open,
    by any library (matplotlib, Pillow, NumPy); the hook, added once, costs nothing unwatched.
    """
    if not _hooked:
        with contextlib.suppress(RuntimeError):
            sys.addaudithook(_audit)
        _hooked.append(True)
    key = threading.get_ident()
    previous = _watching.get(key)
    _watching[key] = (os.path.join(os.path.abspath(folder), ""), opened)
    try:
        yield
    finally:
        if previous is None:
            del _watching[key]
        else:
            _watching[key] = previous


_recorders: list[list[Path]] = []


@contextlib.contextmanager
def recording() -> Iterator[list[Path]]:
    """Collect the folders :func:`write_folder` puts in place while the block runs.

    Each is added in the same step as its rename (no signal in between), so that a command
    stopped at any moment knows whether it wrote anything.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from linkage.report_folder import recording, write_folder
    >>> tmp = tempfile.TemporaryDirectory()
    >>> with recording() as written:
    ...     _ = write_folder(Path(tmp.name) / "out", "demo", lambda f: [])
    >>> [p.name for p in written]
    ['out']
    >>> tmp.cleanup()
    """
    written: list[Path] = []
    _recorders.append(written)
    try:
        yield written
    finally:
        for k, w in enumerate(_recorders):
            if w is written:
                del _recorders[k]
                break


def _os_message(exc: OSError, tmp: Path, folder: Path) -> str:
    reason = exc.strerror or str(exc)
    name = exc.filename
    if name is None:
        return reason
    shown = str(name)
    if shown.startswith(str(tmp)):
        shown = str(folder) + shown[len(str(tmp)) :]
    return f"{shown}: {reason}"


def write_folder(
    folder: Path, name: str, fill: Callable[[Path], Sequence[str]], force: bool = False
) -> list[Path]:
    r"""Write a folder of results safely; return the files written (in ``folder``).

    ``fill(tmp)`` writes the files into a temporary sibling of ``folder`` and returns their names;
    the marker (naming them and ``name``) is written last and the folder renamed into place. An
    existing ``folder`` is replaced only with ``force`` and only if linkage wrote it. On any failure
    — an exception, ``KeyboardInterrupt``, a full disk — the temporary folder is removed and an
    earlier folder is left as it was; an ``OSError`` becomes a ``LinkageError`` naming the path.

    Examples
    --------
    >>> import os, tempfile
    >>> from pathlib import Path
    >>> from linkage.report_folder import write_folder
    >>> def fill(folder):
    ...     (folder / "figures.txt").write_text("stride 43.5 mm\n")
    ...     return ["figures.txt"]
    >>> tmp = tempfile.TemporaryDirectory()
    >>> [p.name for p in write_folder(Path(tmp.name) / "out", "demo", fill)]
    ['figures.txt']
    >>> sorted(os.listdir(Path(tmp.name) / "out"))
    ['.linkage-report', 'figures.txt']

    A failure while filling leaves nothing behind (no folder, no temporary sibling):

    >>> def broken(folder):
    ...     raise ValueError("the plot failed")
    >>> write_folder(Path(tmp.name) / "other", "demo", broken)
    Traceback (most recent call last):
    ...
    ValueError: the plot failed
    >>> sorted(os.listdir(tmp.name))
    ['out']

    ``force`` replaces the folder, unless a file in it is not as linkage wrote it:

    >>> [p.name for p in write_folder(Path(tmp.name) / "out", "demo", fill, force=True)]
    ['figures.txt']
    >>> _ = (Path(tmp.name) / "out" / "figures.txt").write_text("stride 44 mm (measured)\n")
    >>> write_folder(Path(tmp.name) / "out", "demo", fill, force=True)
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...out holds files changed since linkage wrote them (figures.txt); ...
    >>> (Path(tmp.name) / "out" / "figures.txt").read_text()
    'stride 44 mm (measured)\n'
    >>> tmp.cleanup()
    """
    target = _resolve(folder)
    parent = target.parent
    if parent.is_dir():
        # Only if no other run holds the folder now (it may be waiting for a run on this one).
        with _parent_locked(parent, wait=False) as free, _sigint_held():
            if free:
                sweep(parent)
    earlier = os.path.lexists(target)
    if earlier:
        _check_existing(folder, target, force)
    created: list[Path] = []
    tmp: Path | None = None
    opened: list[str] = []
    try:
        missing = [p for p in (parent, *parent.parents) if not p.exists()]
        # Held off Ctrl-C so that every folder made here is known to the clean-up below.
        with _sigint_held():
            for p in reversed(missing):
                p.mkdir()
                created.append(p)
            tmp = _make_sibling(parent, target.name, "partial")
        with _opened_for_writing(tmp, opened):
            names = list(fill(tmp))
        marker = {
            "tool": "linkage",
            "version": _version(),
            "scene": name,
            "written": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "files": sorted(names),
            _DIGESTS: {n: _sha256(tmp / n) for n in sorted(names)},
        }
        opened.append(str(tmp / MARKER))
        (tmp / MARKER).write_text(json.dumps(marker, indent=2) + "\n", encoding="utf-8")
        # The lock first, Ctrl-C held off after: waiting for another run's swap can be stopped.
        with _parent_locked(parent), _sigint_held():
            _commit(folder, target, tmp, force, earlier)
            for written in _recorders:
                written.append(folder)
    except BaseException as exc:
        with _sigint_held():
            if tmp is not None:
                _discard_partial(tmp)
            for p in reversed(created):
                with contextlib.suppress(OSError):
                    p.rmdir()
        if isinstance(exc, OSError):
            if exc.filename is None and opened:
                # write() on a full disk, over a quota or over `ulimit -f` names no file
                exc.filename = opened[-1]
            kept = "; the earlier report is unchanged" if earlier else ""
            raise LinkageError(
                f"{folder}: cannot write the report: {_os_message(exc, tmp or target, folder)} "
                f"({_NOTHING}{kept})"
            ) from None
        raise
    return [target / n for n in names]


def _commit(folder: Path, target: Path, tmp: Path, force: bool, earlier: bool) -> None:
    """Move the finished ``tmp`` into place at ``target``, replacing a report linkage wrote.

    ``earlier`` tells whether ``target`` existed when the run began.
    """
    if not os.path.lexists(target):
        os.rename(tmp, target)
        return
    if not earlier and not force and read_marker(target) is not None:
        raise LinkageError(
            f"another linkage run wrote {_describe(folder, target)} while this one ran; its "
            f"report is kept, this one was not written ({_NOTHING}; pass --force to replace it)"
        )
    # Check again: the folder may have changed while the report was computed.
    old = _check_existing(folder, target, force)
    if old is None:  # gone meanwhile (only a run not holding the lock could do that)
        os.rename(tmp, target)
        return
    aside = _make_sibling(target.parent, target.name, "old")
    aside.rmdir()
    os.rename(target, aside)
    try:
        os.rename(tmp, target)
    except BaseException:
        os.rename(aside, target)
        raise
    if not _remove_report(aside, old):
        sys.stderr.write(
            f"linkage: warning: the replaced report was kept in {aside}: it held files linkage "
            f"did not write\n"
        )


def _version() -> str:
    return str(__version__)
