"""Shared fixtures."""

from __future__ import annotations

import pytest

import linkage


def pytest_report_header() -> str:
    """Name the package under test and where it was imported from (the tree or a wheel)."""
    return f"linkage {linkage.__version__}: {linkage.__file__}"


@pytest.fixture
def hoecken():
    return linkage.catalog.hoecken()
