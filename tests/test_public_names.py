"""Every public module (``python/linkage/*.py`` and ``linkage.design``'s, no leading underscore)
says its public names in ``__all__``: each name exists, and every function and class the module
defines without a leading underscore is listed (ruff's RUF022 keeps the lists sorted)."""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path

import pytest

import linkage

ROOT = Path(linkage.__file__).parent
PUBLIC = sorted(
    ".".join(("linkage", *p.relative_to(ROOT).with_suffix("").parts)).removesuffix(".__init__")
    for p in ROOT.rglob("*.py")
    # Not under a private name (``linkage._shared``); ``__init__`` names its package.
    if not any(
        part.startswith("_") and part != "__init__"
        for part in p.relative_to(ROOT).with_suffix("").parts
    )
)

# Public helpers a module keeps out of its user-facing ``__all__`` on purpose: synthesis's
# target normalisation and distance helpers (export and the CLI call them) and its CLI glue.
UNLISTED = {
    "linkage.synthesis": {
        "clean_target",
        "largest_distance",
        "rounded_to",
        "target_size",
        "timed",
    },
}


def test_the_public_modules_are_found():
    assert {"linkage", "linkage.walker", "linkage.export", "linkage.design.search"} <= set(PUBLIC)
    assert not [m for m in PUBLIC if m.split(".")[-1].startswith("_")]


@pytest.mark.parametrize("name", PUBLIC)
def test_all_names_every_public_function_and_class(name):
    module = importlib.import_module(name)
    listed = module.__all__
    assert len(set(listed)) == len(listed), name
    assert [n for n in listed if not hasattr(module, n)] == []
    defined = {
        n
        for n, v in vars(module).items()
        if (inspect.isfunction(v) or inspect.isclass(v))
        and v.__module__ == name
        and not n.startswith("_")
    }
    assert sorted(defined - set(listed) - UNLISTED.get(name, set())) == []
    assert UNLISTED.get(name, set()) <= defined - set(listed)


def test_a_star_import_gives_the_public_names_only():
    names: dict[str, object] = {}
    exec("from linkage.walker import *", names)
    assert {"Walker", "Leg", "gait_phases", "GAITS"} <= set(names)
    assert "Array" not in names and "np" not in names
