"""Every ```python block of README.md runs, in order, in one namespace: the README's Python is
what a new user types, so it must work as written. A failure names the block and its line."""

import re
import traceback
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)


def blocks():
    text = README.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start(1)) + 1, m.group(1)) for m in FENCE.finditer(text)]


def test_the_readme_has_python_blocks():
    assert blocks(), "README.md has no ```python block"


def test_every_python_block_runs_in_order(tmp_path, monkeypatch):
    # The catalogue table is cached in the user's cache folder: keep the test's cache apart.
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__readme__"}
    for k, (line, source) in enumerate(blocks(), 1):
        # Compiled with the README's line numbers, so a traceback points into README.md.
        code = compile("\n" * (line - 1) + source, str(README), "exec")
        try:
            exec(code, namespace)
        except Exception:
            pytest.fail(
                f"README.md python block {k} (line {line}) failed:\n{traceback.format_exc()}",
                pytrace=False,
            )
