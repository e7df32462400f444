"""Fixtures for the emitter tests."""

from __future__ import annotations

import pytest


@pytest.fixture
def update_goldens(request: pytest.FixtureRequest) -> bool:
    """True under `pytest --update-goldens` (the option lives in tests/conftest.py)."""
    try:
        return bool(request.config.getoption("--update-goldens"))
    except ValueError:  # the option is not registered: plain comparison
        return False
