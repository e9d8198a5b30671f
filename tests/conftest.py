"""Shared fixtures."""

from __future__ import annotations

import pytest


@pytest.fixture
def hoecken():
    import linkage

    return linkage.catalog.hoecken()
