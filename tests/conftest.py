"""Test-wide set-up: OMPL's console log off (tests read results, not logs), and numba's
kernels compiled once before the first test (issue 39)."""

from __future__ import annotations

import pytest
from ompl import util as ou


@pytest.fixture(autouse=True, scope="session")
def _quiet_ompl():
    previous = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    yield
    ou.setLogLevel(previous)


@pytest.fixture(autouse=True, scope="session")
def _kernels_compiled_once() -> None:
    """Every level's kernels compiled (or loaded) here before any test runs, as the CLI does
    before its workers start (:func:`validity.kernel_cache.compile_kernels`): on a cold cache
    the tests that start commands then load them instead of each compiling them in a process
    of its own, and a test run started beside another one waits for that one's compile
    instead of making its own (the compile's file lock). Tests on a cache of their own
    (``NUMBA_CACHE_DIR``) still compile in their processes, as they mean to."""
    from validity import LEVELS
    from validity.kernel_cache import NECESSARY, compile_kernels

    compile_kernels([*LEVELS, NECESSARY])
