"""A progress bar on stderr for long runs (synthesis, design search), with no dependency."""

from __future__ import annotations

import sys
import time

__all__ = [
    "Bar",
]


class Bar:
    """A one-line progress bar redrawn in place on a terminal; elsewhere a line every tenth.

    ``total`` steps (``None``: unknown, a counter is shown). Draws at most ten times a second.
    A run that finds it needs more work than it planned adds a :meth:`stage`: a line of its own,
    so a bar never runs backwards.

    >>> b = Bar("demo", total=4, enabled=False)
    >>> for _ in range(4):
    ...     b.update()
    >>> b.done
    4
    >>> b.stage("more", 2)
    >>> b.desc, b.done, b.total
    ('demo, more', 0, 2)
    """

    def __init__(self, desc: str, total: int | None = None, enabled: bool = True) -> None:
        self.desc, self.total, self.done = desc, total, 0
        self._base = desc
        self.enabled = enabled
        self.tty = enabled and sys.stderr.isatty()
        self._last = 0.0
        self._tenth = -1

    def update(self, steps: int = 1, note: str = "") -> None:
        """Advance by ``steps``; ``note`` is shown after the count."""
        self.done += steps
        if not self.enabled:
            return
        text = self._text(note)
        if self.tty:
            now = time.monotonic()
            if now - self._last >= 0.1 or (self.total is not None and self.done >= self.total):
                self._last = now
                sys.stderr.write("\r" + text + " " * 4)
                sys.stderr.flush()
        elif self.total:
            tenth = 10 * self.done // self.total
            if tenth != self._tenth:
                self._tenth = tenth
                sys.stderr.write(text + "\n")
                sys.stderr.flush()

    def stage(self, name: str, steps: int) -> None:
        """Start a further stage of ``steps`` steps, named ``name``, counted from zero.

        On a terminal the bar so far keeps its line, redrawn with its last count (a draw is at
        most every tenth of a second, so the line may show an older one), and the stage draws
        its own.
        """
        if self.enabled and self.tty and self._last:
            sys.stderr.write("\r" + self._text("") + " " * 4 + "\n")
            sys.stderr.flush()
        self.desc = f"{self._base}, {name}"
        self.total, self.done, self._tenth, self._last = steps, 0, -1, 0.0

    def _text(self, note: str) -> str:
        if self.total:
            width = 30
            full = min(width, int(width * self.done / self.total))
            count = f"[{'#' * full}{'.' * (width - full)}] {self.done}/{self.total}"
        else:
            count = f"{self.done}"
        return f"{self.desc}: {count}" + (f", {note}" if note else "")

    def close(self) -> None:
        """End the line on a terminal."""
        if self.tty:
            sys.stderr.write("\n")
            sys.stderr.flush()


# These classes' 0.1 module (a re-export of this one) stays their ``__module__``, for pickles and
# reprs; doctest looks for a class's examples in its ``__module__``: ``__test__`` points here.
__test__: dict[str, type] = {"Bar": Bar}
for _cls in __test__.values():
    _cls.__module__ = "linkage._progress"
