"""`.ci/long_functions.py` (run by `make check`): no function over 150 lines outside marked kernels.

It checks the source tree, not the installed package: `make wheel-test` leaves this file out of
the copy of the suite it runs against the wheel (`TREE_ONLY` in tests/test_wheel.py).
"""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CHECKER = ROOT / ".ci" / "long_functions.py"


def run(*args: str | Path) -> subprocess.CompletedProcess[str]:
    """Run the checker with `args`, capturing its output."""
    cmd = [sys.executable, str(CHECKER), *map(str, args)]
    return subprocess.run(cmd, capture_output=True, text=True, check=False)


def test_the_tree_has_no_long_function() -> None:
    done = run(ROOT)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "none over 150 lines" in done.stdout


def python_function(length: int, above: str = "") -> str:
    """Source of a function `length` lines long (the `def` line to the last)."""
    body = "".join(f"    x{i} = {i}\n" for i in range(length - 2))
    return f'{above}def planted():\n    """Doc."""\n{body}'


def rust_function(length: int, above: str = "") -> str:
    """Source of a `fn` `length` lines long, with braces in a string and a comment."""
    body = "".join(f"    let _x{i} = {i};\n" for i in range(length - 4))
    tricky = '    let _s = "}}}"; // {{{\n'
    return f"{above}#[inline]\nfn planted() {{\n{tricky}{body}    let _c = '{{';\n}}\n"


@pytest.mark.parametrize(
    ("name", "make"), [("long.py", python_function), ("long.rs", rust_function)]
)
def test_a_planted_long_function_fails(tmp_path: Path, name: str, make: Callable[..., str]) -> None:
    (tmp_path / name).write_text(make(151), encoding="utf-8")
    done = run(tmp_path, tmp_path / name)
    assert done.returncode == 1, done.stdout
    assert "long" in done.stdout and "planted 151 lines" in done.stdout


@pytest.mark.parametrize(
    ("name", "make"), [("long.py", python_function), ("long.rs", rust_function)]
)
def test_150_lines_pass(tmp_path: Path, name: str, make: Callable[..., str]) -> None:
    (tmp_path / name).write_text(make(150), encoding="utf-8")
    done = run(tmp_path, tmp_path / name)
    assert done.returncode == 0, done.stdout


@pytest.mark.parametrize(
    ("name", "make", "comment"),
    [
        ("long.py", python_function, "# numeric kernel: one loop the vectoriser keeps fused\n"),
        ("long.rs", rust_function, "// numeric kernel: one loop the vectoriser keeps fused\n"),
    ],
)
def test_a_marked_numeric_kernel_passes(
    tmp_path: Path, name: str, make: Callable[..., str], comment: str
) -> None:
    (tmp_path / name).write_text(make(151, comment), encoding="utf-8")
    assert run(tmp_path, tmp_path / name).returncode == 0
    # The mark must give a reason.
    (tmp_path / name).write_text(make(151, comment.split(":")[0] + ":\n"), encoding="utf-8")
    assert run(tmp_path, tmp_path / name).returncode == 1
