"""The passive drop's final-clearance guard (issue 26): a drop that ends with the part inside a
wall deeper than the level's tolerance is a fault of the simulation, reported as such and
never as an outcome of the design. Reference: shapely's overlap of the part at q(T) with the
walls."""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely

from experiments.drop.outcomes import SIMULATION_FAULT, classify
from experiments.drop.passive import INSIDE_WALL, passive_drop
from experiments.drop.verdict import VerdictSettings, scene_verdict
from feeders.part import Peg
from feeders.scene import Goal, Scene
from feeders.shapes import Obstacles
from validity.dynamic import PENETRATION_TOLERANCE
from validity.geometry_kernel import pose_vertices

PEG = Peg.two_density(length=2.2, width=0.7, heavy_fraction=0.9)
BLOCK = np.array([[-5.0, -5.0], [5.0, -5.0], [5.0, 0.0], [-5.0, 0.0]])


def _scene(start_y: float) -> Scene:
    return Scene(
        name="block",
        obstacles=Obstacles((BLOCK,), np.zeros((0, 3))),
        part=PEG,
        bounds=(-9.0, 9.0, -9.0, 9.0),
        starts={"flat": (0.0, start_y, 0.0)},
        goal=Goal(x_min=-1.0, x_max=1.0, y_min=0.3, y_max=0.4, yaw=0.0, yaw_tol=0.1),
        friction=0.3,
    )


def _shapely_depth(scene: Scene, pose) -> float:
    """Depth of the part at ``pose`` in the block: its lowest corner below the block's top,
    when it overlaps (shapely: the overlap's vertical extent)."""
    world = np.empty((4, 2))
    pose_vertices(scene.part.body_vertices(), *pose, world)
    overlap = shapely.Polygon(world).intersection(shapely.Polygon(BLOCK))
    return 0.0 if overlap.is_empty else overlap.bounds[3] - overlap.bounds[1]


def test_a_drop_that_ends_inside_a_wall_is_a_simulation_fault_not_an_outcome() -> None:
    """Started 0.5 inside the block and stopped after 0.05 s (the pose correction moves at
    most 0.5 length/s), the part ends about 0.48 deep: the drop says so, is no success, and
    its class is the simulation fault."""
    scene = _scene(0.35 - 0.5)
    result = passive_drop(scene, "flat", t_max=0.05)
    assert result.end == INSIDE_WALL and not result.success
    reference = _shapely_depth(scene, result.final_pose)
    assert reference > PENETRATION_TOLERANCE
    assert abs(result.final_depth - reference) < 1e-9
    assert classify(scene, result.end, result.final_pose, result.success) == SIMULATION_FAULT


def test_a_drop_that_lands_in_the_goal_is_clear_of_the_walls() -> None:
    """The same block, the part dropped from 0.1 above it: it lands in the goal and ends with
    no overlap beyond the tolerance."""
    scene = _scene(0.45)
    result = passive_drop(scene, "flat", t_max=2.0)
    assert result.success and result.end != INSIDE_WALL
    assert result.final_depth <= PENETRATION_TOLERANCE
    assert _shapely_depth(scene, result.final_pose) <= PENETRATION_TOLERANCE


def test_the_verdict_leaves_simulation_faults_out_of_its_count() -> None:
    """Every drop of a scene whose start is deep in the block ends inside it: the verdict
    counts none of them (drops 0, undecided) and reports the faults; it stops drawing after
    ``max_drops`` faults past the first look."""
    settings = VerdictSettings(min_drops=3, max_drops=4, t_max=0.05)
    verdict = scene_verdict(_scene(0.35 - 0.5), settings, seed=0)
    assert verdict.drops == 0 and verdict.decision == "undecided"
    assert verdict.faults == len(verdict.trials) == 3 + 4
    assert verdict.to_dict()["simulation_faults"] == 7
    row = verdict.transitions()["flat"]
    assert row[SIMULATION_FAULT] == 7


def test_a_verdict_without_faults_counts_every_trial() -> None:
    settings = VerdictSettings(min_drops=3, max_drops=3, t_max=2.0)
    verdict = scene_verdict(dataclasses.replace(_scene(0.45)), settings, seed=0)
    assert verdict.faults == 0 and verdict.drops == 3
