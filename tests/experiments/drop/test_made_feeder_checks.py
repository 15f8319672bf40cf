"""A made feeder's build checks, cheaper per trial, decide as the whole-union checks did
(issue 21, "the cost of a trial": building the toleranced feeder was 12% of a trial).

The part's fit at the top of the input chute is asked of shapely's union of the walls only when
the part is not clearly apart from every piece (more than 1e-9 from each, the pin's disc
included): that shortcut must never pass a part the union overlaps. Walls that cross are found
among the edge pairs whose bounding boxes meet, in the order every pair was asked before.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import shapely

from experiments.drop.perturbations import Perturbations, draw, toleranced
from feeders.design import PRESETS, preset
from feeders.feeder import (
    DegenerateDesign,
    _clearly_apart,
    _pose_polygon,
    build_feeder,
    interior_edges,
    protuberance,
    walls,
)
from feeders.halton import halton_designs
from feeders.part import DEFAULT_PEG


def _union_overlap(design, orientation_pose) -> float:
    """Area of the part at the pose inside shapely's union of the walls, finger and pin."""
    finger, tip = protuberance(design)
    pieces = [shapely.Polygon(w) for w in walls(interior_edges(design))]
    solid = shapely.union_all(
        [*pieces, shapely.Polygon(finger), shapely.Point(tip[:2]).buffer(tip[2])]
    )
    return _pose_polygon(DEFAULT_PEG, orientation_pose).intersection(solid).area


def test_a_finger_under_the_input_chute_leaves_no_room_for_the_part() -> None:
    design = dataclasses.replace(preset("table3"), fx=1.0, fy=2.7916666666666665, r=0.4, e=-2.5)
    with pytest.raises(DegenerateDesign, match=r"does not fit .* \(heavy_leading\)"):
        build_feeder(design)


def test_walls_that_cross_are_named() -> None:
    design = dataclasses.replace(preset("table3"), gx=-4.0, gy=0.8, e=-5.0, theta=0.1, a=1.5)
    with pytest.raises(DegenerateDesign, match="walls cross: the underside of the lip meets"):
        build_feeder(design)


def test_clearly_apart_never_passes_a_part_the_union_overlaps() -> None:
    """On made feeders of every preset and on Halton designs, wherever the shortcut says apart
    the union's overlap is zero; and the shortcut is taken on most of them (it pays)."""
    designs = [
        toleranced(d, draw(Perturbations(tolerance=0.05), 3, i).design_factors)
        for d in PRESETS.values()
        for i in range(4)
    ]
    designs += halton_designs(60, seed=2)
    taken = judged = 0
    for design in designs:
        try:
            scene = build_feeder(design)
        except DegenerateDesign:
            continue
        finger, tip = protuberance(design)
        pieces = [*walls(interior_edges(design)), finger]
        for pose in scene.starts.values():
            judged += 1
            if _clearly_apart([_pose_polygon(DEFAULT_PEG, pose)], pieces, tip):
                taken += 1
                assert _union_overlap(design, pose) == 0.0
    assert judged > 100 and taken > 0.8 * judged


def test_a_part_overlapping_one_piece_is_not_clearly_apart() -> None:
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    far_disc = np.array([10.0, 10.0, 0.5])
    touching = shapely.Polygon(square + np.array([1.0 + 5e-10, 0.0]))
    assert not _clearly_apart([touching], [square], far_disc)
    apart = shapely.Polygon(square + np.array([1.0 + 1e-6, 0.0]))
    assert _clearly_apart([apart], [square], far_disc)
    assert not _clearly_apart([apart], [square], np.array([2.5, 0.5, 0.5 - 1e-12]))
