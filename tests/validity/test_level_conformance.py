"""The contract every fidelity level keeps (:class:`validity.level.Level`), for each level.

Planners and experiments treat the levels alike, so each is held to the same specification:
the starts of a feeder are valid, propagation is a pure function (same input, same output,
its input untouched, also on a fresh instance), results stay within the scene's bounds with a
yaw in [-pi, pi), chained propagations equal one long one, and the states a level reports
along a propagation end exactly at its result.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from feeders.design import PRESETS
from feeders.feeder import build_feeder
from feeders.scene import Scene
from validity import LEVELS, make_level
from validity.pose_samples import cross_check_poses

DURATION = {"geometric": 1.0, "kinematic": 1.0, "dynamic": 0.2}  # s: ~100-200 steps each


@functools.cache
def _table3() -> Scene:
    return build_feeder(PRESETS["table3"], name="table3")


def _cases(level, n: int, seed: int) -> list[tuple[tuple[float, ...], np.ndarray]]:
    """``n`` valid states of table3 (from seeded poses) with controls uniform in U."""
    rng = np.random.default_rng(seed)
    poses = cross_check_poses(level.scene, 50 * n, seed)
    states = [level.state_of_pose(p) for p in poses]
    states = [s for s in states if level.is_valid(s)][:n]
    assert len(states) == n
    low, high = level.control_bounds()
    return [(s, rng.uniform(low, high)) for s in states]


@pytest.fixture(params=sorted(LEVELS))
def level(request):
    return make_level(request.param, _table3())


def test_the_feeders_starts_are_valid(level) -> None:
    for orientation in ("heavy_leading", "heavy_trailing"):
        state = level.state_of_pose(_table3().start(orientation))
        assert len(state) == level.state_dim and level.is_valid(state)


def test_controls_and_states_have_the_declared_sizes(level) -> None:
    low, high = level.control_bounds()
    assert low.shape == high.shape == (level.control_dim,) and np.all(low <= high)
    state = level.state_of_pose(_table3().start("heavy_leading"))
    assert len(level.propagate(state, high, 0.1)) == level.state_dim


def test_propagate_is_pure(level) -> None:
    """Same input, same output (also from a fresh instance); lists and arrays passed in are
    unchanged."""
    cases = _cases(level, 10, seed=5)
    duration = DURATION[level.name]
    first = [level.propagate(s, u, duration) for s, u in cases]
    fresh = make_level(level.name, _table3())
    assert [level.propagate(s, u, duration) for s, u in cases] == first
    assert [fresh.propagate(s, u, duration) for s, u in cases] == first
    for s, u in cases[:3]:
        state, control = list(s), np.array(u)
        state_before, control_before = list(state), control.copy()
        level.propagate(state, control, duration)
        assert state == state_before and np.array_equal(control, control_before)


def test_results_stay_in_bounds_with_a_wrapped_yaw(level) -> None:
    b = _table3().bounds
    for s, u in _cases(level, 20, seed=7):
        out = level.propagate(s, u, DURATION[level.name])
        assert b[0] <= out[0] <= b[1] and b[2] <= out[1] <= b[3]
        assert -math.pi <= out[2] < math.pi
        assert all(math.isfinite(v) for v in out)


def test_chained_propagation_equals_one_long_propagation(level) -> None:
    """OMPL propagates a control in pieces of its propagation step: two pieces of T/2 must give
    what one T gives, bit for bit (each piece is a whole number of the level's steps)."""
    half = 50 * level.step
    for s, u in _cases(level, 5, seed=9):
        assert level.propagate(level.propagate(s, u, half), u, half) == level.propagate(
            s, u, 2 * half
        )


def test_a_reported_path_ends_where_propagate_ends(level) -> None:
    path_of = getattr(level, "propagate_path", None)
    if path_of is None:
        pytest.skip(f"the {level.name} level reports no states between")
    for s, u in _cases(level, 5, seed=11):
        path = path_of(s, u, DURATION[level.name])
        assert tuple(path[0]) == tuple(s)
        assert tuple(path[-1]) == level.propagate(s, u, DURATION[level.name])
