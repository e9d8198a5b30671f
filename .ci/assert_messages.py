#!/usr/bin/env python3
"""Every assertion in linkage-core's test code says what failed (kurbo's `missing_assert_message`).

Clippy checks `missing_assert_message` everywhere but inside `#[test]` functions; this checks
those: crates/linkage-core/tests/**/*.rs, the `#[cfg(...test...)] mod NAME { ... }` blocks of
crates/linkage-core/src/**/*.rs, and whole files that are such a module (`mod tests;` ->
straightness/tests.rs). Comments (so `///` doc tests), strings and char literals are skipped by
a small lexer. An invocation lacks a message when its top-level comma-separated argument count
(a trailing comma dropped) is below the macro's: 2 for assert!/debug_assert!/prop_assert!, 3
for the _eq/_ne forms. Exits 1, listing them, when any lacks one (`make check` runs it).

Usage: assert_messages.py [--list]
"""

import os
import re
import sys

CRATE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "crates", "linkage-core")
MIN_ARGS = {}
for base in ("assert", "debug_assert", "prop_assert"):
    MIN_ARGS[base] = 2
    MIN_ARGS[base + "_eq"] = 3
    MIN_ARGS[base + "_ne"] = 3


def mask(src):
    """src with comments, strings and char literals replaced by spaces (newlines kept)."""
    out = list(src)
    i, n = 0, len(src)

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            blank(i, j); i = j
        elif src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j): depth += 1; j += 2
                elif src.startswith("*/", j): depth -= 1; j += 2
                else: j += 1
            blank(i, j); i = j
        elif (m := re.compile(r'b?r(#*)"').match(src, i)) and (i == 0 or not (src[i-1].isalnum() or src[i-1] == "_")):
            end = '"' + m.group(1)
            j = src.find(end, m.end())
            j = n if j < 0 else j + len(end)
            blank(i + 1, j - 1) if j - i >= 2 else None; i = j
        elif c == '"':
            j = i + 1
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            blank(i + 1, j); i = j + 1
        elif c == "'":
            m = re.compile(r"'(\\.[^']*|[^\\'])'").match(src, i)
            if m:
                blank(i + 1, m.end() - 1); i = m.end()
            else:
                i += 1  # lifetime
        else:
            i += 1
    return "".join(out)


def match_close(s, i):
    """index past the bracket matching the one at s[i]."""
    pairs = {"(": ")", "[": "]", "{": "}"}
    stack = [pairs[s[i]]]
    j = i + 1
    while stack:
        ch = s[j]
        if ch in pairs: stack.append(pairs[ch])
        elif ch in ")]}": stack.pop()
        j += 1
    return j


def top_args(s, a, b):
    """top-level comma-separated pieces of s[a:b] (inside the brackets)."""
    parts, depth, start = [], 0, a
    for k in range(a, b):
        ch = s[k]
        if ch in "([{": depth += 1
        elif ch in ")]}": depth -= 1
        elif ch == "," and depth == 0:
            parts.append(s[start:k]); start = k + 1
    parts.append(s[start:b])
    if parts and not parts[-1].strip():
        parts.pop()
    return parts


def test_regions(rel, m):
    """(start, end) offsets of the test code in a file given its masked text."""
    if rel.startswith("tests/") or rel == "src/straightness/tests.rs":
        return [(0, len(m))]
    regions = []
    for cfg in re.finditer(r"#\[cfg\(([^\]]*)\)\]", m):
        if not re.search(r"\btest\b", cfg.group(1)):
            continue
        mm = re.compile(r"\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*([{;])").match(m, cfg.end())
        if mm and mm.group(1) == "{":
            regions.append((cfg.start(), match_close(m, mm.end() - 1)))
    return regions


def macro_regions(m):
    out = []
    for mr in re.finditer(r"\bmacro_rules!\s*\w+\s*([({\[])", m):
        out.append((mr.start(), match_close(m, mr.end() - 1)))
    return out


def scan(path, rel):
    src = open(path, encoding="utf-8").read()
    m = mask(src)
    regions = test_regions(rel, m)
    macros = macro_regions(m)
    found = []
    pat = re.compile(r"(?<![\w:])(?:(?:proptest|core|std)::)?(" + "|".join(sorted(MIN_ARGS, key=len, reverse=True)) + r")!\s*([(\[{])")
    for inv in pat.finditer(m):
        pos = inv.start()
        if not any(a <= pos < b for a, b in regions):
            continue
        name = inv.group(1)
        close = match_close(m, inv.end() - 1)
        nargs = len(top_args(m, inv.end(), close - 1))
        in_macro = any(a <= pos < b for a, b in macros)
        line = src.count("\n", 0, pos) + 1
        found.append((rel, line, name, nargs >= MIN_ARGS[name], in_macro, src[pos:close].split("\n")[0]))
    return found


def files():
    for sub in ("src", "tests"):
        for d, _, fs in os.walk(os.path.join(CRATE, sub)):
            for f in sorted(fs):
                if f.endswith(".rs"):
                    p = os.path.join(d, f)
                    yield p, os.path.relpath(p, CRATE).replace(os.sep, "/")


allf = [x for p, rel in sorted(files()) for x in scan(p, rel)]
bare = [x for x in allf if not x[3]]
for rel, line, name, _, in_macro, text in bare:
    where = " [in macro_rules]" if in_macro else ""
    print(f"crates/linkage-core/{rel}:{line}: {name}!{where} without a message: {text.strip()[:90]}")
if "--list" in sys.argv or bare:
    print(f"{len(allf)} assertions in the core's tests, {len(bare)} without a message")
if len(allf) < 500:
    sys.exit(f"only {len(allf)} assertions found: is the crate where this script expects it?")
sys.exit(1 if bare else 0)
