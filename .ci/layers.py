"""The Rust crates' layers: a module uses only modules of lower layers, and no modules form a cycle.

Run by `make check`. For each crate below, every `.rs` file under its `src/` is read (comments,
strings and `#[cfg(...test...)]` modules masked out: test code may use a higher layer's fixtures)
and every path into the crate is collected: `use crate::a::...` (with `{...}` groups),
inline `crate::a::...` paths, and `super::` paths that leave a top-level folder. A file belongs to
the unit named by its first path component under `src/` (`src/sweep/engine.rs` -> `sweep`,
`src/error.rs` -> `error`); a flat re-export (`crate::Vec2`) is a use of `lib`, the top.

It fails with `file:line: <unit> (layer N) uses <unit> (layer M): upward` (or `sideways`, for
two peers on one layer), and with `cycle: a -> b -> a` for every cycle between file modules
(`sweep::engine`, `sweep::held`, ...), found by Tarjan's strongly connected components. Clean,
it prints one summary line and exits 0.

    python3 .ci/layers.py [REPO_ROOT] [--only core|binding]
"""

from __future__ import annotations

import os
import re
import sys

from rust_source import mask

# Lowest layer first; units on one line are peers and may not use each other.
CORE_LAYERS = [
    ["numeric"],  # scalar helpers, trig, turns, pow2 scaling, thread split
    ["error"],  # the typed Error (formats numbers with numeric)
    ["choice"],  # string choices; their parse errors are `Error`s
    ["constructions", "drive"],  # dyad, slider dyad | motion laws, gears, schedules, cams
    ["mechanism"],  # program, rates, bodies; every `impl Mechanism`
    ["motion"],  # instant centres, inflection, straightness
    ["sweep"],  # tracker, engine, output layout, block kernels
    ["linkages", "kinetostatics"],  # four-bar, uniform sweep, batch, slider-crank | forces
    ["catalog", "walking"],  # the source documents' linkages | gait, support
    ["synthesis"],  # precision points, EFD, atlases, circuits, curve equations
    ["lib"],  # the crate root: flat re-exports only
]

# The binding: helpers at the bottom, `lib` on top, every other module one peer layer between
# (one module per core folder, each with its own `register`). A name not listed here is a peer
# of the middle layer, so a new binding module fits without a change to this table.
# The shared helpers use each other in this order: `error` (the Python exceptions), `memory`
# (size wording, MemoryError), then `args` and any conversion helper (`convert*`, `conv*`),
# `module` (the joint capacity, the submodule maker) and `simd` (the CPU check of the fast sweeps).
BINDING_BOTTOM = {"error": 0, "memory": 1, "args": 2, "module": 2, "simd": 2}
BINDING_CONVERT = ("convert", "conv")
BINDING_MIDDLE = 3


# True: a binding module named after a core folder takes that folder's order (binding
# `linkages` may then use binding `mechanism`, as the core's do); other modules stay peers above
# them. False: every such module is a peer of every other.
# True, because the binding mirrors the core (issue 30, item 4): its pyclasses wrap core types
# that are layered the same way. A Python `Mechanism` is the binding `mechanism`'s pyclass, and
# `linkages` (`FourBar.mechanism()`), `sweep` (sweeps of many mechanisms), `kinetostatics`,
# `catalog` and `synthesis` take or return one, as their core folders use core `mechanism`.
# Moving that 700-line wrapper to a bottom helper would leave `mechanism` an empty shell; with
# the core's order the binding has the core's one direction and still no peer or upward use.
BINDING_MIRRORS_CORE = True


def binding_layer(unit: str) -> int:
    """0-2 for the shared helpers, the top for `lib`, one middle layer for every other module."""
    if unit in BINDING_BOTTOM:
        return BINDING_BOTTOM[unit]
    if unit.startswith(BINDING_CONVERT):
        return BINDING_BOTTOM["args"]
    top = BINDING_MIDDLE + (len(CORE_LAYERS) if BINDING_MIRRORS_CORE else 1)
    if unit == "lib":
        return top
    core = core_layer(unit) if BINDING_MIRRORS_CORE else None
    return BINDING_MIDDLE + core if core is not None else top - 1


def core_layer(unit: str) -> int | None:
    """Return the layer of a core unit, None for a unit the table does not know."""
    for n, units in enumerate(CORE_LAYERS):
        if unit in units:
            return n
    return None


CRATES = {
    "core": ("crates/linkage-core/src", core_layer),
    "binding": ("crates/linkage-py/src", binding_layer),
}


TEST_ATTR = re.compile(r"#\[cfg\([^\n]*\btest\b[^\n]*\)\]")


def strip_tests(text: str) -> tuple[str, set[str]]:
    """Blank `#[cfg(test)] mod x { ... }` blocks; return the text and the `mod x;` test files."""
    out = list(text)
    test_files: set[str] = set()
    for m in TEST_ATTR.finditer(text):
        rest = re.match(
            r"\s*(?:#\[[^\n]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*([;{])", text[m.end() :]
        )
        if not rest:
            continue
        if rest.group(2) == ";":
            test_files.add(rest.group(1))
            continue
        start = m.end() + rest.end() - 1
        depth, j = 0, start
        while j < len(text):
            if text[j] == "{":
                depth += 1
            elif text[j] == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        for k in range(m.start(), min(j + 1, len(text))):
            if out[k] != "\n":
                out[k] = " "
    return "".join(out), test_files


def module_of(rel: str) -> list[str]:
    """`sweep/engine.rs` -> [sweep, engine]; `sweep/mod.rs` -> [sweep]; `lib.rs` -> []."""
    parts = rel[:-3].split("/")
    if parts[-1] == "mod" or parts == ["lib"] or parts == ["main"]:
        parts = parts[:-1]
    return parts


def group_heads(body: str) -> list[list[str]]:
    """Return the paths of a `{a::b, c::{d, e}, f}` group as segment lists (nested: heads)."""
    items, depth, cur = [], 0, ""
    for ch in body:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        if ch == "," and depth == 0:
            items.append(cur)
            cur = ""
        else:
            cur += ch
    items.append(cur)
    paths = []
    for item in items:
        item = item.strip()
        if not item:
            continue
        segs = [s.strip() for s in item.split("::")]
        paths.append([s for s in segs if s and not s.startswith("{") and re.fullmatch(r"\w+", s)])
    return [p for p in paths if p]


PATH = re.compile(r"\b(crate|super)((?:\s*::\s*(?:super\b|\w+))*)\s*::\s*(\{)?")


def inline_modules(text: str) -> list[tuple[int, int, str]]:
    """(start, end, name) of every inline `mod name { ... }` of a masked text."""
    spans = []
    for m in re.finditer(r"\bmod\s+(\w+)\s*\{", text):
        depth, j = 0, m.end() - 1
        while j < len(text):
            depth += {"{": 1, "}": -1}.get(text[j], 0)
            if depth == 0:
                break
            j += 1
        spans.append((m.start(), j, m.group(1)))
    return spans


def uses(text: str) -> list[tuple[int, str, list[str], list[str]]]:
    """Return (line, crate/super..., segments, enclosing inline mods) per path into the crate."""
    found = []
    spans = inline_modules(text)
    for m in PATH.finditer(text):
        if m.start() > 0 and (text[m.start() - 1].isalnum() or text[m.start() - 1] in "_:"):
            continue
        line = text.count("\n", 0, m.start()) + 1
        head = [s.strip() for s in m.group(2).split("::") if s.strip()]
        kind = m.group(1)
        supers = 1 if kind == "super" else 0
        while head and head[0] == "super":
            supers += 1
            head.pop(0)
        base = "crate" if kind == "crate" else "super" * supers
        inside = [name for a, b, name in spans if a < m.start() < b]
        if m.group(3):  # a group: crate::a::{b, c}
            depth, j = 1, m.end()
            while j < len(text) and depth:
                depth += {"{": 1, "}": -1}.get(text[j], 0)
                j += 1
            for tail in group_heads(text[m.end() : j - 1]):
                found.append((line, base, head + tail, inside))
        else:
            rest = re.match(r"\w+", text[m.end() :])
            found.append((line, base, head + ([rest.group(0)] if rest else []), inside))
    return found


def check(root: str, src_rel: str, layer_of) -> tuple[list[str], int, int]:
    """Errors, files read and uses checked of one crate."""
    src = os.path.join(root, src_rel)
    if not os.path.isdir(src):
        return [], 0, 0
    files = {}
    for d, _, names in os.walk(src):
        for name in names:
            if name.endswith(".rs"):
                rel = os.path.relpath(os.path.join(d, name), src).replace(os.sep, "/")
                files[rel] = tuple(module_of(rel))
    modules = set(files.values())
    masked, test_mods = {}, set()
    for rel, mod in files.items():
        with open(os.path.join(src, rel), encoding="utf-8") as f:
            text, tests = strip_tests(mask(f.read()))
        masked[rel] = text
        test_mods |= {(*mod, t) for t in tests}
    errors: list[str] = []
    edges: dict[tuple[str, ...], dict[tuple[str, ...], tuple[str, int]]] = {m: {} for m in modules}
    n_uses = 0
    seen: set[tuple[str, str]] = set()
    for rel, mod in sorted(files.items()):
        if any(mod[: len(t)] == t for t in test_mods):
            continue
        unit = mod[0] if mod else "lib"
        here = layer_of(unit)
        for line, base, segs, inside in uses(masked[rel]):
            if base == "crate":
                target = segs
            else:
                # `super` of an inline `mod named { ... }` is the file's own module
                up = len(base) // len("super")
                at = list(mod) + inside
                target = at[: len(at) - up] + segs
            # the longest prefix that is a module of the crate
            tmod: tuple[str, ...] = ()
            for k in range(len(target), 0, -1):
                if tuple(target[:k]) in modules:
                    tmod = tuple(target[:k])
                    break
            tunit = tmod[0] if tmod else "lib"
            flat = "" if tmod or not target else f" (flat re-export `{target[0]}`)"
            n_uses += 1
            if tmod != mod:
                edges[mod].setdefault(tmod, (rel, line))
            if tunit == unit:
                continue
            there = layer_of(tunit)
            where = f"{src_rel}/{rel}:{line}"
            if (where, tunit) in seen:
                continue
            seen.add((where, tunit))
            if here is None or there is None:
                unknown = unit if here is None else tunit
                errors.append(f"{where}: {unknown} is in no layer of .ci/layers.py's table")
            elif there >= here:
                how = "upward" if there > here else "sideways"
                errors.append(
                    f"{where}: {unit} (layer {here}) uses {tunit} (layer {there}){flat}: {how}"
                )
    errors += cycles(edges, src_rel)
    return errors, len(files), n_uses


def cycles(edges, src_rel: str) -> list[str]:
    """One message per strongly connected component of more than one module (Tarjan)."""
    index: dict = {}
    low: dict = {}
    stack: list = []
    on: set = set()
    comps: list = []
    counter = [0]

    def visit(v) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, {})):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(comp)

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    out = []
    name = lambda m: "::".join(m) or "lib"  # noqa: E731
    for comp in comps:
        members = set(comp)
        # a shortest cycle through the component's first member, by breadth-first search
        start = min(comp)
        prev = {start: None}
        queue = [start]
        found = None
        while queue and found is None:
            v = queue.pop(0)
            for w in sorted(edges[v]):
                if w == start:
                    found = v
                    break
                if w in members and w not in prev:
                    prev[w] = v
                    queue.append(w)
        path = [start]
        v = found
        while v is not None and v != start:
            path.insert(1, v)
            v = prev[v]
        path.append(start)
        steps = " -> ".join(name(m) for m in path)
        at = "; ".join(
            f"{name(a)} at {src_rel}/{edges[a][b][0]}:{edges[a][b][1]}"
            for a, b in zip(path, path[1:])
        )
        out.append(f"cycle: {steps} ({at})")
    return out


def main(argv: list[str]) -> int:
    """Check the crates, print the violations or a summary; 1 on a violation."""
    args = list(argv[1:])
    only = list(CRATES)
    if "--only" in args:
        k = args.index("--only")
        only = [args[k + 1]]
        del args[k : k + 2]
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    errors, files, n = [], 0, 0
    for src_rel, layer_of in (CRATES[c] for c in only):
        e, f, k = check(root, src_rel, layer_of)
        errors += e
        files += f
        n += k
    for e in errors:
        print(e)
    if errors:
        print(f"layers: {len(errors)} violation(s) in {files} files", file=sys.stderr)
        return 1
    print(f"layers: {files} files, {n} paths into their crates, every one downward, no cycle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
