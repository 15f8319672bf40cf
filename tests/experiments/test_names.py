"""Specification of experiments.names: the light lists of names equal the real registries.

The reference is each registry itself (validity.LEVELS, planners.registry.PLANNERS,
feeders.design.PRESETS), in its own order, so a level, planner or preset added there and not
here (or the other way round) fails this test instead of a CLI choice going missing.
"""

from __future__ import annotations

from experiments.names import EXECUTOR_NAMES, LEVEL_NAMES, PLANNER_NAMES, PRESET_NAMES
from feeders.design import PRESETS
from planners.registry import PLANNERS
from validity import LEVELS


def test_level_names_are_the_levels_in_ladder_order():
    assert list(LEVEL_NAMES) == list(LEVELS)


def test_planner_names_are_the_registered_planners():
    assert list(PLANNER_NAMES) == list(PLANNERS)


def test_preset_names_are_the_paper_presets():
    assert list(PRESET_NAMES) == list(PRESETS)


def test_executor_names_are_the_executors_the_ladder_runs():
    from experiments.executors import cluster, local

    assert EXECUTOR_NAMES == ("local", "dask")
    assert callable(local.run_local) and callable(cluster.run_dask)
