"""The binding's constants are the core's: each read from crates/linkage-core's source, so a
change there that the binding did not follow fails. A check of the tree (left out of the wheel's
copy of the suite: ``TREE_ONLY`` in tests/test_wheel.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_binding_modules import CONSTANTS

CORE = Path(__file__).parent.parent / "crates" / "linkage-core" / "src"
# Values the core does not hold as one `pub const` (derived, or the catalogue's name lists).
DERIVED = ("CAPACITY", "SLIDER_ARC_ENTRY_PARAMS", "FOUR_BARS", "MULTI_LOOP")


def core_constant(name: str) -> str:
    for path in CORE.rglob("*.rs"):
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.startswith(f"pub const {name}:"):
                return line.split("=", 1)[1].strip().rstrip(";")
    raise AssertionError(f"no pub const {name} in the core")


@pytest.mark.parametrize(("module", "name", "value"), [c for c in CONSTANTS if c[1] not in DERIVED])
def test_constant_is_the_cores_source(module: str, name: str, value: object) -> None:
    text = core_constant(name)
    if isinstance(value, (int, float)):
        assert type(value)(text.replace("_", "")) == value, text
    else:
        assert text.replace(" ", "").replace("[", "(").replace("]", ")") == str(
            tuple(value) if isinstance(value, list) else value
        ).replace(" ", ""), text
