"""No function over 150 lines, in Python or Rust, outside numeric kernels that say why.

Run by `make check`. Measures every function (and method) in `python/linkage` with `ast`
(`end_lineno - lineno + 1`: from the `def` line to the last, docstring included)
and every `fn` with a body in `crates/*/src` by brace matching, with comments, strings, raw
strings and character literals skipped. A function over the limit fails with
`file:line name N lines`, unless the line above its signature (or above its decorators or
attributes, doc comments in between allowed) is a comment containing `numeric kernel:` followed
by the reason, e.g. `// numeric kernel: one fused loop, split it and the vectoriser stops`.

    python3 .ci/long_functions.py [ROOT] [PATH ...]

With paths (files or folders, `.py` or `.rs`), only those are measured. Clean, it prints one
summary line and exits 0; otherwise it lists the long functions and exits 1.
"""

from __future__ import annotations

import ast
import re
import sys
from collections.abc import Iterator
from pathlib import Path

from rust_source import mask

LIMIT = 150
MARK = "numeric kernel:"
PY_ROOTS = ("python/linkage",)
RS_GLOB = "crates/*/src"


def marked(lines: list[str], first: int) -> bool:
    """Return whether a `numeric kernel:` comment with a reason sits above line `first` (1-based).

    Attributes (`#[...]`), decorators and doc comments between the comment and the line are
    stepped over.
    """
    i = first - 2
    while i >= 0:
        text = lines[i].strip()
        if text.startswith(("#[", "@", "///", "//!")) and MARK not in text:
            i -= 1
            continue
        if text.endswith("]") and not text.startswith("#"):
            # The last line of an attribute over several lines: step to its `#[`.
            start = next(
                (k for k in range(i - 1, max(i - 30, -1), -1) if lines[k].strip().startswith("#[")),
                None,
            )
            if start is not None:
                i = start - 1
                continue
        if text.startswith(("#", "//")) and MARK in text:
            return bool(text.split(MARK, 1)[1].strip())
        return False
    return False


def python_functions(path: Path) -> Iterator[tuple[int, int, str, int]]:
    """Yield (line, length, name, first line above decorators) of every function in a file."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            end = node.end_lineno or node.lineno
            top = min([node.lineno, *(d.lineno for d in node.decorator_list)])
            yield node.lineno, end - node.lineno + 1, node.name, top


FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def rust_functions(path: Path) -> Iterator[tuple[int, int, str, int]]:
    """Yield (line, length, name, signature line) of every `fn` with a body in a file."""
    text = mask(path.read_text(encoding="utf-8"))
    for m in FN.finditer(text):
        # The body opens at the first `{` at depth zero of () and <>-free context, unless a `;`
        # (a declaration in a trait) comes first.
        j, paren = m.end(), 0
        while j < len(text):
            c = text[j]
            if c in "([":
                paren += 1
            elif c in ")]":
                paren -= 1
            elif paren == 0 and c == ";":
                j = -1
                break
            elif paren == 0 and c == "{":
                break
            j += 1
        if j < 0 or j >= len(text):
            continue
        depth, k = 0, j
        while k < len(text):
            if text[k] == "{":
                depth += 1
            elif text[k] == "}":
                depth -= 1
                if depth == 0:
                    break
            k += 1
        line = text.count("\n", 0, m.start()) + 1
        end = text.count("\n", 0, k) + 1
        yield line, end - line + 1, m.group(1), line


def files(root: Path, paths: list[str]) -> Iterator[Path]:
    """Yield the files to measure: those under `paths`, or by default the package and crates."""
    if paths:
        for p in map(Path, paths):
            p = p if p.is_absolute() else root / p
            yield from ([p] if p.is_file() else sorted(p.rglob("*.py")) + sorted(p.rglob("*.rs")))
        return
    for folder in PY_ROOTS:
        yield from sorted((root / folder).rglob("*.py"))
    for src in sorted(root.glob(RS_GLOB)):
        yield from sorted(src.rglob("*.rs"))


def main(argv: list[str]) -> int:
    """Measure, print the long functions (or one summary line) and return the exit status."""
    root = Path(argv[0]) if argv else Path(__file__).resolve().parent.parent
    counted, long = 0, []
    for path in files(root, argv[1:]):
        if path.suffix not in (".py", ".rs"):
            continue
        lines = path.read_text(encoding="utf-8").splitlines()
        found = python_functions(path) if path.suffix == ".py" else rust_functions(path)
        for line, length, name, top in found:
            counted += 1
            if length > LIMIT and not marked(lines, top):
                shown = path.relative_to(root) if path.is_relative_to(root) else path
                long.append(f"{shown}:{line} {name} {length} lines")
    for entry in long:
        print(entry)
    if long:
        print(f"{len(long)} function(s) over {LIMIT} lines (mark a numeric kernel with a")
        print(f"`{MARK} <reason>` comment above it, or split it)")
        return 1
    print(f"long functions: {counted} functions measured, none over {LIMIT} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
