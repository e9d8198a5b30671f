"""The package's imports run one way: no module imports, even through another, one that
imports it. Read from the sources with ``ast``: an import inside a function is counted as lazy,
one under ``if TYPE_CHECKING:`` not at all (it never runs), and a submodule's implicit import
of ``linkage/__init__.py`` is not counted (the package is always imported first). The scene
modules (the schema, the build step, the facade) had a cycle hidden by a function-local import:
``linkage.scene`` imported ``linkage.build`` inside ``parse``, and ``build`` imports the schema;
so had the walker and its searches (``Walker.search_phases`` imported ``linkage.gait_search``,
which imported ``linkage.walker``)."""

from __future__ import annotations

import ast
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import linkage
from linkage import _schema, scene

ROOT = Path(linkage.__file__).parent
SCENE_MODULES = {
    "linkage._schema",
    "linkage.build",
    "linkage.figures",
    "linkage.runner",
    "linkage.scene",
    "linkage.stage_figures",
}


def dotted(path: Path) -> str:
    parts = [*path.relative_to(ROOT.parent).parent.parts, path.name.split(".")[0]]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


SOURCES = {dotted(p): p for p in ROOT.rglob("*.py")}
# Also the compiled extension (linkage._core), which imports nothing of the package.
MODULES = set(SOURCES) | {
    dotted(p) for p in ROOT.rglob("*") if p.name.endswith((".pyi", ".so", ".pyd"))
}


def imports(path: Path) -> Iterator[tuple[ast.Import | ast.ImportFrom, bool]]:
    """Each import statement that runs, and whether it runs only when a function is called."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    lazy: set[ast.AST] = set()
    never: set[ast.AST] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            lazy.update(n for n in ast.walk(node) if n is not node)
        elif isinstance(node, ast.If) and ast.unparse(node.test).endswith("TYPE_CHECKING"):
            never.update(n for stmt in node.body for n in ast.walk(stmt))
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)) and node not in never:
            yield node, node in lazy


def graph(with_lazy: bool) -> dict[str, set[str]]:
    """The package's modules and, for each, the package modules it imports."""
    edges: dict[str, set[str]] = {m: set() for m in MODULES}
    for module, path in SOURCES.items():
        for node, lazy in imports(path):
            if lazy and not with_lazy:
                continue
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                assert node.level == 0 and node.module, f"{path}: a relative import"
                # `from linkage import build` imports a module, `from linkage import FourBar` not.
                names = [
                    f"{node.module}.{a.name}"
                    if f"{node.module}.{a.name}" in MODULES
                    else node.module
                    for a in node.names
                ]
            edges[module] |= {n for n in names if n in MODULES and n != module}
    return edges


def cycles(edges: dict[str, set[str]]) -> list[set[str]]:
    """The import cycles: each set of modules that all reach one another (more than one)."""
    reach: dict[str, set[str]] = {}
    for start in edges:
        seen: set[str] = set()
        todo = list(edges[start])
        while todo:
            m = todo.pop()
            if m not in seen:
                seen.add(m)
                todo.extend(edges[m])
        reach[start] = seen
    parts = {frozenset(n for n in reach[m] if m in reach[n]) for m in edges if m in reach[m]}
    return sorted((set(p) for p in parts), key=sorted)


def test_the_graph_sees_the_scene_modules_imports():
    top = graph(with_lazy=False)
    assert {"linkage._schema", "linkage.figures"} <= top["linkage.build"]
    assert "linkage.build" in top["linkage.scene"]
    assert "linkage._schema" in top["linkage.runner"]
    assert {"linkage.figures", "linkage.stage_figures"} <= top["linkage.runner"]
    assert {"linkage.report", "linkage.runner"} <= graph(with_lazy=True)["linkage.cli"]
    assert "linkage._core" in top["linkage._arrays"] and "linkage" not in top["linkage._arrays"]


def test_the_package_has_no_import_cycle_at_import_time():
    assert cycles(graph(with_lazy=False)) == []


def test_no_import_cycle_runs_through_the_scene_modules_even_inside_functions():
    # The scene modules need no lazy import to avoid a cycle.
    assert [c for c in cycles(graph(with_lazy=True)) if c & SCENE_MODULES] == []


def test_no_import_cycle_even_inside_functions():
    # The package's version lives in linkage._version, so catalog and the report writers do not
    # import the package's __init__.
    assert cycles(graph(with_lazy=True)) == []


def test_the_walker_imports_its_searches_and_not_the_other_way():
    # Walker.search_phases and the old names linkage.walker.search_* are linkage.gait_search's;
    # gait_search checks its walker against a type Walker registers with (gait_search._Walkers).
    every = graph(with_lazy=True)
    assert "linkage.gait_search" in graph(with_lazy=False)["linkage.walker"]
    assert "linkage.walker" not in every["linkage.gait_search"]


def test_the_schema_imports_neither_build_nor_the_facade():
    code = (
        "import sys, linkage._schema; "
        "print(sorted(m for m in sys.modules if m in ('linkage.build', 'linkage.scene')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[]"


def test_the_facade_exports_every_public_name_of_the_schema():
    tree = ast.parse(Path(_schema.__file__).read_text(encoding="utf-8"))
    defined = {
        target.id
        for node in tree.body
        for target in (
            node.targets
            if isinstance(node, ast.Assign)
            else [node.target]
            if isinstance(node, ast.AnnAssign)
            else []
        )
        if isinstance(target, ast.Name)
    } | {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    public = {n for n in defined if not n.startswith("_")}
    # The parser's two steps, which the facade's load and parse wrap with the build step.
    assert {"parse_only", "read_text"} <= public
    assert set(scene.__all__) == public - {"parse_only", "read_text"} | {"load", "parse"}
    for name in public & set(scene.__all__):
        assert getattr(scene, name) is getattr(_schema, name), name
