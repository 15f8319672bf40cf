"""Planning from the entry region (issue 21): the geometric level as a relaxation of the
perturbed drops asks whether the part can reach the goal from anywhere it may enter, so the
problem has the region's valid corner poses as further start states after the nominal one."""

from __future__ import annotations

import pytest

from feeders.design import preset
from feeders.feeder import build_feeder
from planners.plan import control_problem, region_corners
from planners.registry import make_planner


def test_the_corners_are_the_region_s_eight_extreme_poses():
    corners = region_corners((1.0, 2.0, 0.5), (0.05, 0.1))
    assert len(corners) == 8 and len(set(corners)) == 8
    for x, y, yaw in corners:
        assert abs(x - 1.0) == pytest.approx(0.05) and abs(y - 2.0) == pytest.approx(0.05)
        assert abs(yaw - 0.5) == pytest.approx(0.1)
    assert region_corners((1.0, 2.0, 0.5), None) == []
    assert region_corners((1.0, 2.0, 0.5), (0.0, 0.0)) == []


def test_a_problem_with_a_region_starts_from_the_nominal_pose_and_its_valid_corners():
    """The problem's start states are the nominal one and every corner the level finds valid
    (counted, not read back: reading a start state with OMPL 2's ``getStartState`` makes the
    interpreter crash at exit), and RRT plans from all of them."""
    scene = build_feeder(preset("table3"))
    plain = control_problem(scene, "geometric", "heavy_leading", seed=1)
    assert plain.ss.getProblemDefinition().getStartStateCount() == 1
    region = control_problem(
        scene, "geometric", "heavy_leading", seed=1, start_region=(0.05, 0.05), count=True
    )
    corners = region_corners(scene.start("heavy_leading"), (0.05, 0.05))
    valid = [c for c in corners if region.level.is_valid(region.level.state_of_pose(c))]
    assert 1 <= len(valid) < 8  # table3's chute cap blocks some corners
    assert region.ss.getProblemDefinition().getStartStateCount() == 1 + len(valid)
    region.ss.setPlanner(make_planner("rrt", region.si))
    region.ss.setup()
    region.ss.solve(region.termination(60.0, 50_000))
    assert region.ss.haveExactSolutionPath()
