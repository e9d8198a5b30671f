"""Shared fixtures."""

from __future__ import annotations

import signal

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


@pytest.fixture
def hoecken():
    return linkage.catalog.hoecken()
