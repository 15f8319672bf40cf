"""Test-wide set-up: OMPL's console log off (tests read results, not logs)."""

from __future__ import annotations

import pytest
from ompl import util as ou


@pytest.fixture(autouse=True, scope="session")
def _quiet_ompl():
    previous = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    yield
    ou.setLogLevel(previous)
