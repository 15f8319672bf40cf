"""The kinematic level planned with OMPL's RRT and KPIECE1 on table3 (SE2 x R^3 states,
velocity controls from the scene's U, the pose projection for KPIECE1).

Each found path is re-validated independently of the planner: its controls are re-propagated
from the start in OMPL's propagation steps and must reproduce the planner's states, every
state of the fine path must be free of overlap by shapely's measure, and the last must lie in
the goal.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import shapely

from feeders.design import PRESETS
from feeders.feeder import ORIENTATIONS, build_feeder
from feeders.scene import Scene
from planners.plan import PlannerSettings, PlanResult, plan
from validity import make_level

STEP = PlannerSettings().step  # OMPL's propagation step (s)
AREA_TOL = 1e-12  # shapely overlap area still counted as touching (length^2)


@functools.cache
def _scene() -> Scene:
    return build_feeder(PRESETS["table3"], name="table3")


def _largest_overlap(scene: Scene, states: np.ndarray) -> float:
    pieces = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    body = scene.part.body_vertices()
    parts = []
    for x, y, th in states[:, :3]:
        c, s = math.cos(th), math.sin(th)
        parts.append(shapely.Polygon(body @ np.array([[c, s], [-s, c]]) + (x, y)))
    parts_arr = np.array(parts)
    worst = max(float(np.max(shapely.area(shapely.intersection(parts_arr, p)))) for p in pieces)
    for cx, cy, r in scene.obstacles.circles:
        gap = float(np.min(shapely.distance(parts_arr, shapely.Point(cx, cy)))) - r
        worst = max(worst, math.inf if gap < -1e-9 else 0.0)
    return worst


def _revalidate(scene: Scene, result: PlanResult) -> None:
    level = make_level("kinematic", scene)
    state = level.state_of_pose(scene.start(result.orientation))
    for control, duration in zip(result.controls, result.durations, strict=True):
        for _ in range(round(duration / STEP)):
            state = level.propagate(state, control, STEP)
    np.testing.assert_array_equal(state, result.path[-1])
    np.testing.assert_array_equal(result.fine_path[-1], result.path[-1])
    assert scene.goal.contains(tuple(state[:3]))
    assert all(level.is_valid(s) for s in result.fine_path)
    assert _largest_overlap(scene, result.fine_path) <= AREA_TOL


@pytest.mark.parametrize(
    "orientation",
    [o if o == "heavy_leading" else pytest.param(o, marks=pytest.mark.slow) for o in ORIENTATIONS],
)  # heavy_trailing: CI's longer job (~5 s)
@pytest.mark.parametrize(
    "planner,seeds,propagations,needed",
    [
        pytest.param("rrt", 20, 30_000, 19, marks=pytest.mark.slow),  # statistical: CI's longer job
        ("kpiece", 5, 20_000, 4),
    ],
)
def test_planner_solves_table3_and_every_path_revalidates(
    planner: str, seeds: int, propagations: int, needed: int, orientation: str
) -> None:
    """RRT: 20 seeded runs of 30,000 propagations each, at least 19 (95%) solved (measured: the
    hardest seed, heavy trailing, needs 20,674; about 4 s here). KPIECE1 with the pose
    projection (x, y, yaw): 5 runs of 20,000, at least 4 solved (they need 1,738-5,291). The
    budget is a count of propagations, not seconds, so the verdict is the same on a loaded
    machine (a 5 s budget failed 2 seeds of 20 once in CI); 120 s is only a cap."""
    scene = _scene()
    solved = 0
    for seed in range(1, seeds + 1):
        result = plan(
            scene, "kinematic", planner, orientation, 120.0, seed, propagations=propagations
        )
        if result.solved:
            solved += 1
            _revalidate(scene, result)
    assert solved >= needed, f"{planner} {orientation}: {solved}/{seeds}"


def test_same_seed_same_tree_and_path() -> None:
    """With a count budget (not seconds: issue 22), so a loaded machine cannot cut a run."""
    a = plan(_scene(), "kinematic", "rrt", "heavy_trailing", 600.0, 7, propagations=30_000)
    b = plan(_scene(), "kinematic", "rrt", "heavy_trailing", 600.0, 7, propagations=30_000)
    assert a.solved and a.tree_size == b.tree_size and a.path.shape[1] == 6
    np.testing.assert_array_equal(a.path, b.path)
    np.testing.assert_array_equal(a.fine_path, b.fine_path)


def test_a_propagation_budget_gives_the_same_run_whatever_the_time_allowed() -> None:
    """The budget in propagations is machine-independent: with the same seed, a run capped at
    10 s and one capped at 100 s stop at the same count with the same tree and path."""
    scene = _scene()
    short = plan(scene, "kinematic", "rrt", "heavy_leading", 10.0, 3, propagations=300)
    long = plan(scene, "kinematic", "rrt", "heavy_leading", 100.0, 3, propagations=300)
    assert short.propagations == long.propagations
    assert 300 <= short.propagations < 400  # stops within a planner iteration of the budget
    np.testing.assert_array_equal(short.tree_vertices, long.tree_vertices)
    np.testing.assert_array_equal(short.path, long.path)
