"""The dynamic level planned with OMPL's RRT and KPIECE1 on table3 (SE2 x R^3 states,
external-wrench controls, the C++ position projection for KPIECE1).

The wrench bound here (|f| <= 10, |tau| <= 2, about the peg's weight) is stated by the test:
with it both planners reach the goal quickly. Each found path is re-validated independently of
the planner: its controls are re-simulated from the start, every re-simulated state is checked
with shapely for overlap beyond the level's tolerance, and the last one must be in the goal.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest
import shapely

from feeders.design import PRESETS
from feeders.feeder import ORIENTATIONS, build_feeder
from feeders.scene import InputSet, Scene
from planners.plan import PlannerSettings, plan
from validity import make_level

SEEDS = (1, 2, 3, 4, 5)
# Budgets are counts of propagations, so a loaded machine cannot change a run (issue 22); the
# seconds are only a cap against a hang. Measured on seeds 1-5 and both entries: rrt needs
# 44-693 propagations, kpiece 56-365.
PROPAGATIONS = 5_000
CAP_S = 600.0
STEP = PlannerSettings().step  # OMPL's propagation step (s)
GOAL_THRESHOLD = 1e-9  # OMPL's goal threshold in planners/goals.py GoalBox


@functools.cache
def _scene() -> Scene:
    scene = build_feeder(PRESETS["table3"], name="table3")
    return dataclasses.replace(scene, inputs=InputSet(max_force=10.0, max_torque=2.0))


def _overlap_area(scene: Scene, states: np.ndarray) -> float:
    """Largest shapely overlap area of the part with the obstacles over ``states`` (summed
    piece by piece: intersecting with the union of pieces is not robust when the part slides
    exactly along a wall)."""
    pieces = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    pieces += [shapely.Point(c[:2]).buffer(c[2], 256) for c in scene.obstacles.circles]
    body = scene.part.body_vertices()
    worst = 0.0
    for x, y, th in states[:, :3]:
        c, s = math.cos(th), math.sin(th)
        part = shapely.Polygon(body @ np.array([[c, s], [-s, c]]) + (x, y))
        worst = max(worst, sum(part.intersection(p).area for p in pieces))
    return worst


@pytest.mark.parametrize("planner", ["rrt", "kpiece"])
@pytest.mark.parametrize("orientation", ORIENTATIONS)
def test_planner_reaches_the_goal_with_the_dynamic_level(planner: str, orientation: str) -> None:
    scene = _scene()
    level = make_level("dynamic", scene)
    solved = 0
    for seed in SEEDS:
        result = plan(
            scene, "dynamic", planner, orientation, CAP_S, seed, propagations=PROPAGATIONS
        )
        if not result.solved:
            continue
        solved += 1
        # re-simulate the controls from the start, in OMPL's propagation steps: the planner's
        # states are reproduced
        state = level.state_of_pose(scene.start(orientation))
        for control, duration in zip(result.controls, result.durations, strict=True):
            for _ in range(round(duration / STEP)):
                state = level.propagate(state, control, STEP)
        np.testing.assert_allclose(state, result.path[-1], atol=1e-9)
        np.testing.assert_allclose(result.fine_path[-1], result.path[-1], atol=1e-9)
        # in the goal as the planner judges it (GoalBox's threshold, planners/goals.py): a part
        # resting on the chute's floor heavy end down sits on the box's bottom edge
        # (y_min = floor + heavy end's reach), where rounding puts it 1e-16 either side
        assert scene.goal.position_gap(state[0], state[1]) < GOAL_THRESHOLD
        assert scene.goal.yaw_gap(state[2]) < GOAL_THRESHOLD
        assert all(level.is_valid(s) for s in result.fine_path)
        tolerance_area = level.penetration_tolerance * scene.part.length
        assert _overlap_area(scene, result.fine_path[::5]) < tolerance_area
    assert solved >= len(SEEDS) - 1, f"{planner} {orientation}: {solved}/{len(SEEDS)}"


def test_same_seed_same_tree_and_path() -> None:
    scene = _scene()
    a = plan(scene, "dynamic", "rrt", "heavy_leading", CAP_S, 7, propagations=PROPAGATIONS)
    b = plan(scene, "dynamic", "rrt", "heavy_leading", CAP_S, 7, propagations=PROPAGATIONS)
    assert a.solved and a.tree_size == b.tree_size  # seed 7 needs 477 propagations
    np.testing.assert_array_equal(a.path, b.path)
    assert a.path.shape[1] == 6  # pose and velocity
