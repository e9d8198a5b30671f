"""Files the tool reads from and writes to the user's disk: guarded reads, safe temporaries.

Every cache, checkpoint and user-given data file goes through these helpers:

- :func:`read_bytes` (and :func:`read_text`, :func:`read_json`) opens without blocking (a FIFO
  does not hang it), accepts a regular file only (not a device such as ``/dev/zero``, a pipe or
  a folder, reached directly or through a link), reads at most ``limit`` bytes and bounds the
  nesting of JSON. Every failure is a :class:`LinkageError` naming the file.
- :func:`write_atomic` writes through a temporary file created with ``O_CREAT | O_EXCL`` in the
  target's folder (:func:`tempfile.mkstemp`: a planted symbolic link is never followed), then
  renamed over the target (a link at the target is replaced, not followed). The temporary is
  removed in a ``finally``, whatever stops the write.
- :func:`sweep_stale` removes the temporaries of processes that died before their ``finally``
  ran (kill -9, power loss): only names of this module's pattern, only regular files or folders
  whose process is gone, never through a link.

Temporaries are named ``.<name>.<pid>.<random>.tmp`` so that a later run knows whose they are.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import shutil
import stat
import tempfile
from pathlib import Path
from typing import Any, Union

from linkage._core import LinkageError

__all__ = [
    "TooLarge",
    "json_depth",
    "pid_alive",
    "read_bytes",
    "read_json",
    "read_text",
    "sweep_stale",
    "temp_name_pattern",
    "write_atomic",
]

PathLike = Union[str, "os.PathLike[str]"]

JSON_DEPTH = 32
"""The deepest nesting of lists and objects :func:`read_json` accepts (every file the tool
writes nests three levels at most)."""


class TooLarge(LinkageError):
    """A file larger than the reader's limit (a :class:`LinkageError`, naming the file)."""


def _why(exc: OSError) -> str:
    return exc.strerror or str(exc)


def read_bytes(path: PathLike, limit: int, what: str = "file", pipe: bool = False) -> bytes:
    """Return the bytes of the regular file ``path``, refusing anything else.

    The file is opened without blocking, checked on the open descriptor (so a file swapped for a
    pipe or a device between a check and the open is still refused), and read up to ``limit``
    bytes; a larger file is refused before it is read. ``what`` names the file in messages.

    With ``pipe``, a pipe is read too (a shell's ``<(command)``), up to ``limit`` bytes: a named
    pipe that no program writes to reads as empty instead of blocking the open.

    Raises
    ------
    LinkageError
        Naming ``path``: missing or unreadable, a folder, a device, a pipe or socket, or larger
        than ``limit`` bytes.

    Examples
    --------
    >>> import tempfile, os
    >>> from linkage._shared.files import read_bytes
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     p = os.path.join(tmp, "a.json")
    ...     _ = open(p, "w").write("[1, 2]")
    ...     read_bytes(p, 100)
    b'[1, 2]'
    >>> read_bytes("/dev/zero", 100, "cache file")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: /dev/zero: the cache file is a device, not a regular file
    """
    p = os.fspath(path)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(p, flags)
    except IsADirectoryError:
        raise LinkageError(f"{p}: the {what} is a folder, not a regular file") from None
    except OSError as exc:
        raise LinkageError(f"{p}: cannot read the {what}: {_why(exc)}") from None
    try:
        info = os.fstat(fd)
        if pipe and stat.S_ISFIFO(info.st_mode):
            os.set_blocking(fd, True)  # a writer's data are awaited; no writer is the end
        elif not stat.S_ISREG(info.st_mode):
            kind = (
                "a folder"
                if stat.S_ISDIR(info.st_mode)
                else "a device"
                if stat.S_ISCHR(info.st_mode) or stat.S_ISBLK(info.st_mode)
                else "a pipe or socket"
            )
            raise LinkageError(f"{p}: the {what} is {kind}, not a regular file")
        if stat.S_ISREG(info.st_mode) and info.st_size > limit:
            raise TooLarge(
                f"{p}: the {what} is {info.st_size} bytes, more than the {limit} it may hold"
            )
        chunks = []
        left = limit + 1
        while left > 0:
            chunk = os.read(fd, min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        data = b"".join(chunks)
        if len(data) > limit:  # it grew while being read
            raise TooLarge(f"{p}: the {what} is more than the {limit} bytes it may hold")
        return data
    except OSError as exc:
        raise LinkageError(f"{p}: cannot read the {what}: {_why(exc)}") from None
    finally:
        os.close(fd)


def read_text(path: PathLike, limit: int, what: str = "file") -> str:
    """Return the UTF-8 text of the regular file ``path`` (as :func:`read_bytes`).

    Bytes that are not UTF-8 are a :class:`LinkageError` naming the file and the offset.
    """
    data = read_bytes(path, limit, what)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise LinkageError(
            f"{os.fspath(path)}: the {what} is not UTF-8 text (byte 0x{data[exc.start]:02x} at "
            f"offset {exc.start})"
        ) from None


def json_depth(text: str) -> int:
    """Return the deepest nesting of ``[`` and ``{`` in the JSON ``text`` (strings skipped).

    Examples
    --------
    >>> from linkage._shared.files import json_depth
    >>> json_depth('{"a": [1, {"b": "[[["}]}')
    3
    """
    depth = deepest = 0
    for token in re.finditer(r'"(?:[^"\\]|\\.)*"|[\[\]{}]', text):
        c = token.group()
        if c in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif c in "]}":
            depth -= 1
    return deepest


def read_json(path: PathLike, limit: int, what: str = "file") -> Any:
    """Return the JSON value in the regular file ``path`` (as :func:`read_text`).

    Nesting deeper than :data:`JSON_DEPTH` and text that is not JSON are a :class:`LinkageError`
    naming the file.

    Examples
    --------
    >>> import tempfile, os
    >>> from linkage._shared.files import read_json
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     p = os.path.join(tmp, "deep.json")
    ...     _ = open(p, "w").write("[" * 100_000 + "]" * 100_000)
    ...     read_json(p, 1 << 20, "cache file")
    Traceback (most recent call last):
    ...
    linkage.LinkageError: ...deep.json: the cache file nests 100000 levels deep, more than 32
    """
    text = read_text(path, limit, what)
    depth = json_depth(text)
    if depth > JSON_DEPTH:
        raise LinkageError(
            f"{os.fspath(path)}: the {what} nests {depth} levels deep, more than {JSON_DEPTH}"
        )
    try:
        return json.loads(text)
    except (ValueError, RecursionError) as exc:
        raise LinkageError(f"{os.fspath(path)}: the {what} is not JSON: {exc}") from None


def temp_name_pattern(name: str) -> re.Pattern[str]:
    """Return the pattern of the temporaries :func:`write_atomic` makes for a file ``name``.

    Group 1 is the pid of the process that made it.
    """
    return re.compile(re.escape(f".{name}.") + r"(\d+)\.[A-Za-z0-9_]+\.tmp")


def write_atomic(path: PathLike, data: bytes | str, mode: int = 0o644) -> None:
    """Write ``data`` to ``path`` whole or not at all, never through a planted link.

    The data go to a new temporary file in the same folder, created exclusively
    (``O_CREAT | O_EXCL``: a name taken by anything, a link included, is not reused), flushed
    to disk and renamed over ``path``. On any failure or interruption the temporary is removed
    and ``path`` is as it was; the ``OSError`` propagates (with ``filename`` set to ``path``
    where the operating system gave none, as for a full disk or ``ulimit -f``).

    Examples
    --------
    >>> import tempfile, os
    >>> from linkage._shared.files import write_atomic
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     p = os.path.join(tmp, "cache.json")
    ...     write_atomic(p, "[1]")
    ...     print(open(p).read(), os.listdir(tmp))
    [1] ['cache.json']
    """
    target = Path(path)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    fd, tmp = tempfile.mkstemp(
        prefix=f".{target.name}.{os.getpid()}.", suffix=".tmp", dir=target.parent
    )
    try:
        try:
            os.fchmod(fd, mode & ~_umask())
            view = memoryview(raw)
            while view:
                view = view[os.write(fd, view) :]
            os.fsync(fd)
        finally:
            os.close(fd)
        os.replace(tmp, target)
    except OSError as exc:
        if exc.filename is None:
            exc.filename = os.fspath(path)
        raise
    finally:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def pid_alive(pid: int) -> bool:
    """Return whether a process ``pid`` exists on this machine (one of any user counts)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    except OSError as exc:
        return exc.errno != errno.ESRCH
    return True


def sweep_stale(folder: PathLike, pattern: re.Pattern[str]) -> list[str]:
    """Remove entries of ``folder`` matching ``pattern`` whose process (group 1) is gone.

    For temporaries this tool left when a process died before cleaning up. An entry is removed
    only if its name matches whole, its pid is not a live process, and it is a regular file or a
    folder (not a link: a link is left alone, and nothing is followed through it); a folder is
    removed with its contents. Returns the names removed; errors are ignored (another run may be
    sweeping the same folder).
    """
    removed: list[str] = []
    try:
        names = os.listdir(folder)
    except OSError:
        return removed
    for name in names:
        m = pattern.fullmatch(name)
        if m is None or pid_alive(int(m.group(1))):
            continue
        entry = os.path.join(folder, name)
        try:
            info = os.lstat(entry)
            if stat.S_ISREG(info.st_mode):
                os.unlink(entry)
            elif stat.S_ISDIR(info.st_mode):
                shutil.rmtree(entry)
            else:
                continue
        except OSError:
            continue
        removed.append(name)
    return removed


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"TooLarge": TooLarge}
for _cls in __test__.values():
    _cls.__module__ = "linkage._files"
