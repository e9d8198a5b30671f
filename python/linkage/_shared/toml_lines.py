"""Where things are in a scene's TOML text, for messages: ``tomllib`` keeps no positions.

:class:`Locator` finds the line of a key (in a ``[section]``, an ``[[array.of.tables]]`` entry or
an inline table), :func:`decode` turns the file's bytes into text or says where they are not
UTF-8, and :func:`nesting` finds brackets nested deeper than the parser can follow.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Any

__all__ = [
    "MAX_NESTING",
    "Locator",
    "NotText",
    "decode",
    "label",
    "nesting",
]

MAX_NESTING = 32
"""Deepest ``[``/``{`` nesting a scene may use (a scene needs 3; the TOML parser recurses)."""


class NotText(Exception):
    """The scene's bytes are not UTF-8 text: ``line`` (1-based) and ``problem``."""

    def __init__(self, line: int, problem: str) -> None:
        super().__init__(problem)
        self.line, self.problem = line, problem


def decode(data: bytes) -> str:
    """Decode ``data`` as UTF-8 text, a leading BOM dropped.

    Raises
    ------
    NotText
        At the first byte that is not UTF-8.
    """
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[: exc.start]
        line = before.count(b"\n") + 1
        col = exc.start - (before.rfind(b"\n") + 1) + 1
        raise NotText(
            line, f"not UTF-8 text: byte 0x{data[exc.start]:02x} at column {col} ({exc.reason})"
        ) from None
    return text[1:] if text.startswith("\ufeff") else text


def nesting(text: str, limit: int = MAX_NESTING) -> int | None:
    """Return the 1-based line where ``[``/``{`` nesting first exceeds ``limit``, or None.

    Brackets inside strings and comments do not count.
    """
    depth, line, i, n = 0, 1, 0, len(text)
    while i < n:
        ch = text[i]
        if ch == "\n":
            line += 1
        elif ch == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        elif ch in "\"'":
            triple = text.startswith(ch * 3, i)
            close = ch * 3 if triple else ch
            j = i + len(close)
            while j < n:
                if ch == '"' and text[j] == "\\":
                    j += 2
                    continue
                if text.startswith(close, j):
                    break
                if not triple and text[j] == "\n":
                    break  # an unterminated string: the parser reports it
                j += 1
            line += text.count("\n", i, j)
            i = j + len(close)
            continue
        elif ch in "[{":
            depth += 1
            if depth > limit:
                return line
        elif ch in "]}":
            depth = max(0, depth - 1)
        i += 1
    return None


class Locator:
    """Finds the line of a key in the scene text and words located messages."""

    def __init__(self, text: str, file: str) -> None:
        self.lines = text.splitlines()
        self.file = file

    def _header(self, names: Sequence[str]) -> re.Pattern[str]:
        return re.compile(r"^\s*\[\[?\s*" + re.escape(".".join(names)) + r"\s*\]\]?\s*(#.*)?$")

    def line(self, path: Sequence[Any], key: str) -> int:
        """Return the line of ``key`` under ``path`` (section names and array indices).

        For a key that is not written: its section's header, or line 1.
        """
        names = [p for p in path if isinstance(p, str)]
        index = next((p for p in path if isinstance(p, int)), None)
        pattern = re.compile(r"(^|[\s{,])" + re.escape(str(key)) + r"\s*=")
        start, end = 0, len(self.lines)
        if names:
            header = self._header(names)
            hits = [i for i, line in enumerate(self.lines) if header.match(line)]
            if hits:
                start = hits[min(index or 0, len(hits) - 1)] + 1
                nxt = [
                    i for i in range(start, len(self.lines)) if re.match(r"^\s*\[", self.lines[i])
                ]
                end = nxt[0] if nxt else len(self.lines)
            else:
                # An inline array of tables (`legs = [ {…}, {…} ]`): the entry's own line.
                owner = re.compile(r"(^|[\s{,])" + re.escape(names[-1]) + r"\s*=")
                at = next((i for i, line in enumerate(self.lines) if owner.search(line)), None)
                if at is not None:
                    entry = at
                    if index is not None:
                        braces = [i for i in range(at, len(self.lines)) if "{" in self.lines[i]]
                        entry = braces[index] if index < len(braces) else at
                    line = self.lines[entry]
                    return entry + 1 if pattern.search(line) or index is not None else at + 1
        else:
            first = [i for i, line in enumerate(self.lines) if re.match(r"^\s*\[", line)]
            end = first[0] if first else len(self.lines)
        for i in range(start, end):
            if pattern.search(self.lines[i]):
                return i + 1
        # A table written as a section: its header.
        if key:
            own = self._header([*names, str(key)])
            for i, text in enumerate(self.lines):
                if own.match(text):
                    return i + 1
        for i in range(len(self.lines)):
            if pattern.search(self.lines[i]):
                return i + 1
        # A missing key: point at its section's header, or the file's first line.
        return start if names and start else 1

    def message(self, path: Sequence[Any], key: str, problem: str) -> str:
        """``file:line: [section #k] key: problem``."""
        line = self.line(path, key)
        return f"{self.file}:{line}: {label(path)}{key}: {problem}"


def label(path: Sequence[Any]) -> str:
    """``[section #k] `` for ``path`` (empty at the top level)."""
    section = ".".join(str(p) for p in path if isinstance(p, str))
    idx = [p for p in path if isinstance(p, int)]
    return (f"[{section}" + (f" #{idx[0] + 1}" if idx else "") + "] ") if section else ""


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"NotText": NotText, "Locator": Locator}
for _cls in __test__.values():
    _cls.__module__ = "linkage._toml_lines"
