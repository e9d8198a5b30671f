"""The package's imports run one way: down a table of layers, and in no cycle.

Read from the sources with ``ast``. Every import counts: at module level, inside a function
(run when it is called) and under ``if TYPE_CHECKING:`` (a type checker follows it, and it
would close a cycle the day it runs). A submodule's implicit import of its packages'
``__init__`` is not counted (a package is always imported first).

:data:`LAYERS` gives each module or package its layer, lowest first; a module imports only from a
lower layer, or from its own layer inside its own subpackage (``linkage.walking.walker`` from
``linkage.walking.legs``; never ``linkage.catalog`` from ``linkage.drawing``). The 0.1 paths
(``linkage.walker``, ``linkage._arrays``, ...) are re-export shims: an import of one is an
import of what it re-exports, and a shim imports nothing else.

The scene modules (the schema, the builders, the facade) once had a cycle hidden by a
function-local import, and the walker and its searches one hidden behind ``TYPE_CHECKING`` and
an ABC registration (``linkage.gait_search`` now imports ``linkage.walker``, not the other way).
"""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import linkage
from linkage import scene
from linkage.scene import schema as _schema

ROOT = Path(linkage.__file__).parent

# Module or package -> layer, lowest first. A module takes the layer of its longest listed prefix.
LAYERS = {
    "linkage._core": 0,  # the compiled extension: imports nothing of the package
    "linkage._shared": 1,  # arrays, files, caches, choices, sizes, progress, version, TOML lines
    "linkage.kinematics": 2,  # mechanism, four-bar, slider-crank, sweep, mobility, batch
    "linkage.motion": 3,  # geometry of motion (linkage.geometry)
    "linkage.drives": 4,  # linkage.drive, linkage.cam
    "linkage.kinetostatics": 4,  # linkage.forces
    "linkage.walking": 5,  # walker, legs, gait searches
    "linkage.synthesis": 5,  # path and precision-point synthesis
    "linkage.catalog": 6,
    "linkage.drawing": 6,
    "linkage.design": 6,
    "linkage": 7,  # the package's own names (its __init__ only)
    "linkage.scene": 8,  # schema, builders, facade
    "linkage.report": 9,  # the report folder, HTML page, figures, stage rows, stages, export
    "linkage.cli": 10,
    "linkage.__main__": 11,  # python -m linkage
}

# Imports known to go the wrong way and being removed: none (keep it so; an entry here is a
# debt with a name).
KNOWN_BEING_FIXED: set[tuple[str, str]] = set()


def dotted(path: Path, root: Path = ROOT) -> str:
    parts = [*path.relative_to(root.parent).parent.parts, path.name.split(".")[0]]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def sources(root: Path = ROOT) -> dict[str, Path]:
    return {dotted(p, root): p for p in root.rglob("*.py")}


def modules(root: Path = ROOT) -> set[str]:
    # Also the compiled extension (linkage._core), which imports nothing of the package.
    return set(sources(root)) | {
        dotted(p, root) for p in root.rglob("*") if p.name.endswith((".pyi", ".so", ".pyd"))
    }


def imports(path: Path) -> Iterator[tuple[ast.Import | ast.ImportFrom, str]]:
    """Each import statement and how it runs: "top", "lazy" (in a function) or "typing"."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    lazy: set[ast.AST] = set()
    typing: set[ast.AST] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            lazy.update(n for n in ast.walk(node) if n is not node)
        elif isinstance(node, ast.If) and ast.unparse(node.test).endswith("TYPE_CHECKING"):
            typing.update(n for stmt in node.body for n in ast.walk(stmt))
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node, "typing" if node in typing else "lazy" if node in lazy else "top"


def graph(kinds: tuple[str, ...] = ("top", "lazy", "typing"), root: Path = ROOT):
    """The package's modules and, for each, the package modules it imports (as written)."""
    known = modules(root)
    edges: dict[str, set[str]] = {m: set() for m in known}
    for module, path in sources(root).items():
        for node, kind in imports(path):
            if kind not in kinds:
                continue
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                assert node.level == 0 and node.module, f"{path}: a relative import"
                # `from linkage import build` imports a module, `from linkage import FourBar` not.
                names = [
                    f"{node.module}.{a.name}" if f"{node.module}.{a.name}" in known else node.module
                    for a in node.names
                ]
            edges[module] |= {n for n in names if n in known and n != module}
    return edges


def shims(root: Path = ROOT) -> dict[str, str]:
    """The 0.1 paths kept as re-exports: module -> the module it re-exports (its star import)."""
    found = {}
    for module, path in sources(root).items():
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.ImportFrom) and [a.name for a in node.names] == ["*"]:
                if not module.startswith(("linkage.scene.", "linkage.report.", "linkage.cli.")):
                    found[module] = str(node.module)
    return found


def unit(module: str) -> str:
    """The listed module or package a module belongs to (its longest prefix in LAYERS)."""
    best = max((k for k in LAYERS if module == k or module.startswith(k + ".")), key=len)
    return best if module != "linkage" else "linkage"


def layer(module: str) -> int:
    return LAYERS[unit(module)]


def violations(root: Path = ROOT) -> list[str]:
    """Every import that goes up, or sideways out of its subpackage; every unknown module."""
    edges, alias = graph(root=root), shims(root)
    found = []
    for module in sorted(edges):
        if module not in alias and not any(
            module == k or module.startswith(k + ".") for k in LAYERS if k != "linkage"
        ):
            if module != "linkage":
                found.append(f"{module}: not in the table of layers")
                continue
        if module in alias:
            # A shim imports what it re-exports (and, for older code, the names it used to).
            target = alias[module]
            extra = {t for t in edges[module] if layer(t) > layer(target)}
            found += [f"{module} (a 0.1 path of {target}) imports {t}" for t in sorted(extra)]
            continue
        for written in sorted(edges[module]):
            if (module, written) in KNOWN_BEING_FIXED:
                continue
            target = alias.get(written, written)
            up = layer(target) > layer(module)
            sideways = layer(target) == layer(module) and unit(target) != unit(module)
            if (up or sideways) and unit(module) != "linkage":
                how = "up" if up else "sideways"
                found.append(f"{module} (layer {layer(module)}) imports {written} {how}")
            elif unit(module) == "linkage" and layer(target) > layer(module):
                found.append(f"{module} imports {written} up")
    return found


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


def test_every_import_goes_down_the_table_of_layers():
    assert violations() == []


def test_the_package_has_no_import_cycle_even_inside_functions_or_for_type_checkers():
    assert cycles(graph()) == []


def test_the_allow_list_names_only_edges_that_exist():
    every = graph()
    assert {e for e in KNOWN_BEING_FIXED if e[0] in every and e[1] in every[e[0]]} == {
        e for e in KNOWN_BEING_FIXED if e[0] in every and e[0] in sources()
    }


def test_the_check_fails_on_a_planted_upward_import_and_a_planted_cycle(tmp_path):
    copy = tmp_path / "linkage"
    shutil.copytree(ROOT, copy, ignore=shutil.ignore_patterns("*.so", "*.pyd", "__pycache__"))
    assert violations(copy) == [] and cycles(graph(root=copy)) == []
    sweep = copy / "kinematics" / "sweep.py"
    sweep.write_text(
        sweep.read_text() + "\n\ndef _f() -> None:\n    from linkage.report import figures\n"
    )
    assert violations(copy) == [
        "linkage.kinematics.sweep (layer 2) imports linkage.report.figures up"
    ]
    sweep.write_text(sweep.read_text() + "\nif TYPE_CHECKING:\n    from linkage import walker\n")
    assert "linkage.kinematics.sweep (layer 2) imports linkage.walker up" in violations(copy)
    # A cycle inside one subpackage (which may import sideways) is still found.
    sweep.write_text((ROOT / "kinematics" / "sweep.py").read_text())
    (copy / "drives" / "cam.py").write_text("from linkage.drives import drive\n")
    drive = copy / "drives" / "drive.py"
    drive.write_text(
        drive.read_text() + "\nif TYPE_CHECKING:\n    from linkage.drives import cam\n"
    )
    assert cycles(graph(root=copy)) == [{"linkage.drives.cam", "linkage.drives.drive"}]
    assert violations(copy) == []  # each import alone is allowed: only the cycle is wrong
    # And sideways between two units of one layer.
    cat = copy / "catalog.py"
    cat.write_text(cat.read_text() + "\nfrom linkage import drawing\n")
    assert "linkage.catalog (layer 6) imports linkage.drawing sideways" in violations(copy)


def test_the_graph_sees_the_scene_modules_imports():
    top = graph(("top",))
    assert "linkage.scene.schema" in top["linkage.scene.builders"]
    assert "linkage.scene.builders" in top["linkage.scene.facade"]
    assert "linkage.scene.schema" in top["linkage.report.stages"]
    assert {"linkage.report.figures", "linkage.report.stage_rows"} <= top["linkage.report.stages"]
    assert {"linkage.report", "linkage.report.stages"} <= graph(("lazy",))["linkage.cli"]
    assert "linkage.scene.facade" in graph(("typing",))["linkage.scene"]
    arrays = top["linkage._shared.arrays"]
    assert "linkage._core" in arrays and "linkage" not in arrays


def test_the_walker_does_not_import_its_searches():
    # Walker.search_phases does the work; linkage.gait_search checks its walker is a Walker.
    every = graph()
    assert "linkage.walking.walker" in every["linkage.walking.gait_search"]
    assert "linkage.walking.gait_search" not in every["linkage.walking.walker"]


def test_the_schema_imports_neither_the_builders_nor_the_facade():
    code = (
        "import sys, linkage._schema; print(sorted(m for m in sys.modules if m in "
        "('linkage.build', 'linkage.scene.builders', 'linkage.scene.facade')))"
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


def test_the_package_imports_no_0_1_shim() -> None:
    """Inside the package every module imports the new homes; the 0.1 paths are for users (the
    package's own ``__init__`` names the public modules at their 0.1 paths, on purpose)."""
    edges, alias = graph(), shims()
    found = [
        f"{module} imports the 0.1 path {target} (of {alias[target]})"
        for module in sorted(edges)
        if module not in alias and module != "linkage"
        for target in sorted(edges[module])
        if target in alias
    ]
    assert found == []
