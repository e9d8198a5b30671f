"""Every docstring example of the public API runs pasted into a fresh Python session.

``pytest --doctest-modules`` runs an example with its module's globals at hand, so a bare
``hoecken()`` or ``np`` passes there and fails for a user who pastes the example after
``import linkage``. Here each example (one docstring) runs in an empty namespace: it must import
what it uses itself.

The public modules are ``linkage`` and every module under it with no underscore in its dotted
name; a public module's ``__all__`` names defined in an underscore module (``linkage.FourBar``
in ``linkage._fourbar``, ``linkage.synthesis.motion`` in ``linkage._precision``) count as
public too. Outputs are compared as plain :mod:`doctest` does (whitespace normalised, ``...``
allowed), without pytest's ``NUMBER``: what an example shows is what a user sees.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import io
import pkgutil

import pytest

import linkage


def _public_modules() -> list[str]:
    found = ["linkage"]
    for info in pkgutil.walk_packages(linkage.__path__, "linkage."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            found.append(info.name)
    return sorted(found)


PUBLIC_MODULES = _public_modules()


def _doctests(name: str) -> list[doctest.DocTest]:
    """The module's examples and those of its ``__all__`` names defined in private modules."""
    module = importlib.import_module(name)
    finder = doctest.DocTestFinder(exclude_empty=True)
    tests = finder.find(module, globs={})
    for attr in getattr(module, "__all__", ()):
        obj = getattr(module, attr)
        home = getattr(obj, "__module__", None) or ""
        if home.startswith("linkage._") and (inspect.isclass(obj) or inspect.isfunction(obj)):
            tests += finder.find(obj, f"{name}.{attr}", globs={})
    return [t for t in tests if t.examples]


def test_public_modules_are_found() -> None:
    for name in ("linkage", "linkage.catalog", "linkage.synthesis", "linkage.design.search"):
        assert name in PUBLIC_MODULES
    assert not [m for m in PUBLIC_MODULES if "._" in m or m.endswith("__main__")]


@pytest.mark.parametrize("name", PUBLIC_MODULES)
def test_docstring_examples_run_pasted_into_a_fresh_session(name: str) -> None:
    """Each example runs in an empty namespace (as pasted into a new session), not only with the
    module's own names at hand as ``--doctest-modules`` runs it."""
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    report = io.StringIO()
    failing = []
    for t in _doctests(name):
        t.globs = {}
        if runner.run(t, out=report.write).failed:
            failing.append(t.name)
    assert not failing, (
        f"{len(failing)} example(s) of {name} fail in a fresh namespace: {', '.join(failing)}\n"
        + report.getvalue()
    )
