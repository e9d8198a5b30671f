"""Shared fixtures."""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator
from pathlib import Path

import pytest

import linkage


def pytest_report_header() -> str:
    """Name the package under test and where it was imported from (the tree or a wheel)."""
    return f"linkage {linkage.__version__}: {linkage.__file__}"


def pytest_configure(config: pytest.Config) -> None:
    """Give Ctrl-C its own handler back where the tests were started with it ignored.

    A background job of a script (``make test &``, ``nohup make test &``) starts with SIGINT
    ignored, an ignored signal stays ignored across exec, and Python then installs no handler:
    the tests that interrupt a run in this process or in a child would find Ctrl-C doing nothing.
    With Python's handler here, every child starts with the default, as from a terminal.
    """
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture(scope="session")
def linkage_cache_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Return this run's one cache folder (catalogue table, synthesis atlases), made empty.

    The tests that build an atlas or the catalogue table point ``LINKAGE_CACHE_DIR`` here, so
    a run builds each at most once and never reads or fills the user's cache. Under
    pytest-xdist the workers' temporary folders share a parent, and so share this folder (the
    caches are written through temporary files and renamed, so two workers may race safely).
    """
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent
    folder = base / "linkage-cache"
    folder.mkdir(exist_ok=True)
    return folder


@pytest.fixture(autouse=True, scope="session")
def _one_cache_per_run(linkage_cache_dir: Path) -> Iterator[None]:
    """Point ``LINKAGE_CACHE_DIR`` at this run's cache for every test and its children.

    A test that needs a cache of its own (a corrupt one, a first build) still sets its own.
    """
    before = os.environ.get("LINKAGE_CACHE_DIR")
    os.environ["LINKAGE_CACHE_DIR"] = str(linkage_cache_dir)
    yield
    if before is None:
        os.environ.pop("LINKAGE_CACHE_DIR", None)
    else:
        os.environ["LINKAGE_CACHE_DIR"] = before


@pytest.fixture
def hoecken():
    return linkage.catalog.hoecken()
