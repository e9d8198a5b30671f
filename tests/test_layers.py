"""`.ci/layers.py` (run by `make check`) fails on a use that goes up or sideways and on a cycle."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CHECKER = ROOT / ".ci" / "layers.py"
CORE = "crates/linkage-core/src"


def run(root: Path, *only: str) -> subprocess.CompletedProcess[str]:
    """The checker on the tree at `root`."""
    args = [sys.executable, str(CHECKER), str(root)]
    if only:
        args += ["--only", *only]
    return subprocess.run(args, capture_output=True, text=True, check=False)


@pytest.fixture
def tree(tmp_path: Path) -> Path:
    """A copy of the crates' sources."""
    for crate in ("crates/linkage-core/src", "crates/linkage-py/src"):
        shutil.copytree(ROOT / crate, tmp_path / crate)
    return tmp_path


def plant(root: Path, rel: str, line: str) -> int:
    """Append `line` to the core file `rel`; its line number."""
    path = root / CORE / rel
    text = path.read_text(encoding="utf-8")
    path.write_text(text + line + "\n", encoding="utf-8")
    return text.count("\n") + 1


def test_the_core_is_clean() -> None:
    done = run(ROOT, "core")
    assert done.returncode == 0, done.stdout
    assert done.stdout.startswith("layers: "), done.stdout
    assert "every one downward, no cycle" in done.stdout, done.stdout


def test_the_tree_is_clean() -> None:
    done = run(ROOT)
    assert done.returncode == 0, done.stdout


def test_an_upward_use_fails(tree: Path) -> None:
    n = plant(tree, "numeric/scalar.rs", "use crate::mechanism::program::Mechanism;")
    done = run(tree, "core")
    want = f"{CORE}/numeric/scalar.rs:{n}: numeric (layer 0) uses mechanism (layer 4): upward"
    assert done.returncode == 1, done.stdout
    assert want in done.stdout.splitlines(), done.stdout


def test_an_inline_path_and_a_flat_re_export_count(tree: Path) -> None:
    n = plant(tree, "error.rs", "fn f() { let _ = crate::sweep::engine::SWEEP_CHUNK; }")
    k = plant(tree, "choice.rs", "use crate::Mechanism;")
    out = run(tree, "core").stdout.splitlines()
    assert f"{CORE}/error.rs:{n}: error (layer 1) uses sweep (layer 6): upward" in out, out
    flat = (
        f"{CORE}/choice.rs:{k}: choice (layer 2) uses lib (layer 10) (flat re-export `Mechanism`)"
    )
    assert f"{flat}: upward" in out, out


def test_a_sideways_use_fails(tree: Path) -> None:
    n = plant(tree, "constructions/dyad.rs", "use crate::drive::cam::CamPoint;")
    done = run(tree, "core")
    want = (
        f"{CORE}/constructions/dyad.rs:{n}: constructions (layer 3) uses drive (layer 3): sideways"
    )
    assert done.returncode == 1, done.stdout
    assert want in done.stdout.splitlines(), done.stdout


def test_a_cycle_fails(tree: Path) -> None:
    # Inside one folder, so no layer is crossed: only the cycle is wrong.
    plant(tree, "numeric/trig.rs", "use crate::numeric::turns::reduce_angle;")
    plant(tree, "numeric/turns.rs", "use super::trig::sin_cos_f64;")
    done = run(tree, "core")
    assert done.returncode == 1, done.stdout
    cycles = [line for line in done.stdout.splitlines() if line.startswith("cycle: ")]
    assert len(cycles) == 1, done.stdout
    assert cycles[0].startswith("cycle: numeric::trig -> numeric::turns -> numeric::trig ("), cycles


def test_test_modules_and_comments_are_not_uses(tree: Path) -> None:
    plant(tree, "numeric/scalar.rs", "// use crate::catalog;\n/// [`x`](crate::catalog::x)")
    plant(
        tree,
        "error.rs",
        '#[cfg(test)]\nmod planted {\n    use crate::catalog;\n}\nconst S: &str = "crate::sweep::x";',
    )
    done = run(tree, "core")
    assert done.returncode == 0, done.stdout
