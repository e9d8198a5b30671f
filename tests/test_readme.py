"""The README and the pages under docs/ stay true: their Python runs and their links resolve.

Every ```python block of README.md, and of each page docs/*.md, runs in order in one namespace
per page: the Python there is what a new user types, so it must work as written. A failure names
the page, the block and its line. A block that cannot run on its own (it reads a user's file, or
shows a call's shape only) is marked by the line ``<!-- not run: <why> -->`` right above its
fence; the reason is required, and a marker anywhere else fails.

Every relative link ``[text](path)`` of README.md, docs/*.md and ARCHITECTURE.md must name a file
or folder that exists. In the source tree every link is checked; in the copy of the tests that
``make wheel-test`` runs against the installed wheel (tests, examples, docs, README.md,
ARCHITECTURE.md), links into folders that copy leaves out (``crates/``, ``bench/``) and to the
tests of the tree it leaves out (``TREE_ONLY`` in tests/test_wheel.py) are not.
"""

from __future__ import annotations

import re
import traceback
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
SOURCE_TREE = (ROOT / "Cargo.toml").is_file()
# Tests of the source tree that tests/test_wheel.py leaves out of the wheel's copy of the suite.
TREE_ONLY = ("test_layers.py", "test_long_functions.py", "test_binding_constants_source.py")
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)
NOT_RUN = re.compile(r"^<!-- not run: (.*?) -->[ \t]*$", re.M)
ANY_FENCE = re.compile(r"^```.*?^```[ \t]*$", re.S | re.M)
CODE_SPAN = re.compile(r"`[^`\n]*`")
LINK = re.compile(r"\]\(([^)\s]+)\)")


def pages() -> list[Path]:
    """Return README.md and every docs/*.md page, sorted."""
    return [README, *sorted((ROOT / "docs").glob("*.md"))]


def linked_pages() -> list[Path]:
    """Return the pages whose links are checked: the above and ARCHITECTURE.md."""
    return [*pages(), ROOT / "ARCHITECTURE.md"]


def name(page: Path) -> str:
    return page.relative_to(ROOT).as_posix()


def blocks(page: Path = README) -> list[tuple[int, str]]:
    """Return the page's runnable ```python blocks as (first code line, source)."""
    text = page.read_text(encoding="utf-8")
    found: list[tuple[int, str]] = []
    for m in FENCE.finditer(text):
        before = text[: m.start()].rstrip("\n").rsplit("\n", 1)[-1]
        if NOT_RUN.fullmatch(before):
            continue
        found.append((text.count("\n", 0, m.start(1)) + 1, m.group(1)))
    return found


def test_the_readme_has_python_blocks() -> None:
    assert blocks(), "README.md has no ```python block"


@pytest.mark.parametrize("page", pages(), ids=name)
def test_not_run_markers_sit_on_a_python_block_and_say_why(page: Path) -> None:
    text = page.read_text(encoding="utf-8")
    for m in NOT_RUN.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        assert m.group(1).strip(), f"{name(page)}:{line}: a 'not run' marker needs a reason"
        after = text[m.end() :].lstrip("\n")
        assert after.startswith("```python"), f"{name(page)}:{line}: no ```python block follows"


@pytest.mark.parametrize("page", pages(), ids=name)
def test_every_python_block_runs_in_order(
    page: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, linkage_cache_dir: Path
) -> None:
    # Caches (the catalogue table, the synthesis atlases) go to this run's shared folder, and
    # files the blocks write to a folder of their own.
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(linkage_cache_dir))
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "__readme__"}
    for k, (line, source) in enumerate(blocks(page), 1):
        # Compiled with the page's line numbers, so a traceback points into the page.
        code = compile("\n" * (line - 1) + source, str(page), "exec")
        try:
            exec(code, namespace)
        except Exception:
            pytest.fail(
                f"{name(page)} python block {k} (line {line}) failed:\n{traceback.format_exc()}",
                pytrace=False,
            )


def links(page: Path) -> list[tuple[int, str]]:
    """Return the page's relative link targets as (line, target), code left out."""
    text = page.read_text(encoding="utf-8")
    # Blank code out (keeping line breaks), so `[[x, y]](...)`-like code is never a link.
    text = ANY_FENCE.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)
    text = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), text)
    found = []
    for m in LINK.finditer(text):
        target = m.group(1)
        if re.match(r"[a-z][a-z0-9+.-]*:", target, re.I) or target.startswith("#"):
            continue  # a URL, a mail address or an anchor on the same page
        found.append((text.count("\n", 0, m.start()) + 1, target.split("#", 1)[0]))
    return found


def test_the_front_page_links_to_the_docs() -> None:
    targets = {t for _, t in links(README)}
    assert {"docs/numerics.md", "docs/evidence.md", "docs/scenes.md"} <= targets, targets
    assert "ARCHITECTURE.md" in targets and (ROOT / "ARCHITECTURE.md").is_file()


@pytest.mark.parametrize("page", linked_pages(), ids=name)
def test_every_relative_link_points_to_a_file(page: Path) -> None:
    missing = []
    for line, target in links(page):
        path = (page.parent / target).resolve()
        if not SOURCE_TREE:
            top = path.relative_to(ROOT).parts[0] if ROOT in path.parents else None
            if top is None or not (ROOT / top).exists() or path.name in TREE_ONLY:
                continue  # a folder or a tree-only test the wheel-test copy leaves out
        if not path.exists():
            missing.append(f"{name(page)}:{line}: {target}")
    assert not missing, "links to files that do not exist:\n" + "\n".join(missing)
