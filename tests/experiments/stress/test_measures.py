"""The independent measures against hand-made cases whose answers are known by construction."""

from __future__ import annotations

import math

import numpy as np
import pytest

from experiments.stress.measures import (
    Solid,
    component_of,
    free_components,
    penetration_depths,
    union_of,
)
from feeders.part import Peg
from feeders.scene_checks import overlap_depth

FLOOR = [[-5.0, -1.0], [5.0, -1.0], [5.0, 0.0], [-5.0, 0.0]]
SQUARE = Peg(length=1.0, width=1.0, mass=1.0, com_offset=0.0, inertia=1.0 / 6.0)
BOUNDS = (-5.0, 5.0, -4.0, 6.0)


def _solid(polygons, circles=()):
    return Solid.of_union(union_of(polygons, list(circles)))


def test_square_sunk_into_a_floor_reads_its_depth():
    """A unit square centred 0.4 above the floor's top reaches 0.1 into it."""
    depth = penetration_depths(_solid([FLOOR]), SQUARE, np.array([[0.3, 0.4, 0.0]]))
    assert depth[0] == pytest.approx(0.1, abs=1e-12)


def test_square_apart_or_touching_reads_zero():
    states = np.array([[0.0, 0.5, 0.0], [0.0, 0.7, 0.3], [1.0, 2.0, 1.0]])
    assert np.all(penetration_depths(_solid([FLOOR]), SQUARE, states) == 0.0)


def test_obstacle_corner_inside_the_part_reads_its_depth():
    """A spike whose tip is 0.2 inside the square's bottom side (no square corner inside it)."""
    spike = [[-0.1, -1.0], [0.1, -1.0], [0.0, -0.3]]
    depth = penetration_depths(_solid([spike]), SQUARE, np.array([[0.0, 0.0, 0.0]]))
    assert depth[0] == pytest.approx(0.2, abs=1e-12)


def test_tilted_square_corner_in_a_disc():
    """A square turned 45 degrees with its lowest corner 0.05 inside a disc of radius 1 below it:
    the depth is 0.05 up to the disc's polygon (inscribed, within 5e-6 r)."""
    half_diagonal = math.sqrt(0.5)
    state = np.array([[0.0, 1.0 - 0.05 + half_diagonal, math.pi / 4]])
    depth = penetration_depths(_solid([], [(0.0, 0.0, 1.0)]), SQUARE, state)
    assert depth[0] == pytest.approx(0.05, abs=5e-6)


def test_agrees_with_the_scene_checks_overlap_depth():
    """The vectorised measure and feeders.scene_checks.overlap_depth (one pose at a time, the
    same definition) agree on random poses around a post on a floor."""
    post = [[-0.5, 0.0], [0.5, 0.0], [0.5, 3.0], [-0.5, 3.0]]
    solid = _solid([FLOOR, post])
    part = Peg.two_density(1.6, 1.0)
    rng = np.random.default_rng(3)
    states = np.column_stack(
        [rng.uniform(-2, 2, 200), rng.uniform(-0.2, 1.0, 200), rng.uniform(-3, 3, 200)]
    )
    depths = penetration_depths(solid, part, states)
    from experiments.stress.measures import part_corners

    corners = part_corners(part, states)
    expected = [overlap_depth(solid.union, c) for c in corners]
    assert np.max(depths) > 0.1  # the sample does overlap
    np.testing.assert_allclose(depths, expected, atol=1e-12)


def test_box_teleported_through_the_floor_crossed():
    solid = _solid([FLOOR])
    components = free_components(solid, BOUNDS)
    labels = component_of(components, np.array([[0.0, 1.0, 0.0], [0.0, -2.0, 0.0]]))
    assert labels[0] >= 0 and labels[1] >= 0 and labels[0] != labels[1]


def test_box_moving_above_the_floor_did_not_cross():
    solid = _solid([FLOOR, [[-0.5, 0.0], [0.5, 0.0], [0.5, 3.0], [-0.5, 3.0]]])
    components = free_components(solid, BOUNDS)
    # from the left of the post to its right, over its top: one piece of free space
    labels = component_of(components, np.array([[-3.0, 1.0, 0.0], [3.0, 1.0, 0.0]]))
    assert labels[0] >= 0 and labels[0] == labels[1]


def test_centre_inside_the_solid_has_no_component():
    solid = _solid([FLOOR])
    labels = component_of(free_components(solid, BOUNDS), np.array([[0.0, -0.5, 0.0]]))
    assert labels[0] == -1
