"""The compiled cover of each obstacle edge (validity.cover_kernel), against shapely.

What must hold (issue 21, "the cost of a trial": the split a made feeder's level needs once
per trial is compiled): a point of an edge of piece p is in one of the kernel's cover intervals
exactly when the point just beyond the edge (along its outward normal) lies in another piece
or in a disc. Reference: shapely's point-in-polygon of every other piece and the disc's
distance to its centre, at points sampled along every edge, on every preset, on the same
presets as made to tolerance, and on 200 Halton designs of Table 2's box; the split built on
the cover has its cuts exactly at the interval ends, keeps every piece's outline, and inserts
only collinear vertices, none of them a contact corner.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest
import shapely

from experiments.drop.perturbations import Perturbations, draw, toleranced
from feeders.design import PRESETS
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.halton import halton_designs
from feeders.scene import Scene
from validity.cover_kernel import T_TOL, edge_cover, piece_boxes, split_kernel
from validity.solid_surface import split_at_cover

PROBE = 1e-6  # how far beyond the edge its outside is probed (length)
SAMPLES = np.linspace(0.001, 0.999, 61)  # where along each edge (fraction of its length)
NEAR_END = 1e-4  # samples this close (fraction) to a cover end are not judged: the probe's
# offset moves where a slanted piece starts covering by PROBE / tan(angle)


@functools.cache
def _scenes() -> tuple[Scene, ...]:
    scenes = [build_feeder(d, name=name) for name, d in sorted(PRESETS.items())]
    for name, design in sorted(PRESETS.items()):
        for i in range(3):
            made = toleranced(design, draw(Perturbations(), 0, i).design_factors)
            scenes.append(build_feeder(made, name=f"{name} made #{i}"))
    for i, design in enumerate(halton_designs(200, seed=0)):
        try:
            scenes.append(build_feeder(design, name=f"halton seed 0 #{i}"))
        except DegenerateDesign:
            continue
    return tuple(scenes)


def _packed(scene: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    verts, counts, circles = scene.obstacles.packed()
    return verts, counts, np.ascontiguousarray(circles, dtype=np.float64).reshape(-1, 3)


def _check_cover_against_shapely(scene: Scene) -> int:
    """Every judged sample of every edge is covered by the kernel exactly when shapely (or the
    disc) has the probe beyond it inside another piece; returns the number judged."""
    verts, counts, circles = _packed(scene)
    boxes = piece_boxes(verts, counts)
    pieces = [shapely.Polygon(verts[q, : counts[q]]) for q in range(len(counts))]
    judged = 0
    for p in range(len(counts)):
        n = counts[p]
        for i in range(n):
            a, b = verts[p, i], verts[p, (i + 1) % n]
            length = float(np.hypot(*(b - a)))
            if length < 1e-9:
                continue
            normal = np.array([b[1] - a[1], a[0] - b[0]]) / length
            cover = edge_cover(verts, counts, circles, boxes, p, i)
            ends = cover.ravel()
            t = SAMPLES[np.all(np.abs(SAMPLES[:, None] - ends[None, :]) > NEAR_END, axis=1)]
            probes = a + t[:, None] * (b - a) + PROBE * normal
            inside = np.zeros(len(t), dtype=bool)
            for q, piece in enumerate(pieces):
                if q != p:
                    inside |= shapely.contains_xy(piece, probes[:, 0], probes[:, 1])
            for cx, cy, r in circles:
                inside |= np.hypot(probes[:, 0] - cx, probes[:, 1] - cy) < r
            covered = np.any((cover[:, 0] <= t[:, None]) & (t[:, None] <= cover[:, 1]), axis=1)
            wrong = np.flatnonzero(covered != inside)
            assert wrong.size == 0, (
                f"{scene.name}: edge {p}.{i} at t = {t[wrong[0]]:.6f}: kernel says covered = "
                f"{covered[wrong[0]]}, shapely {inside[wrong[0]]} (cover {cover.tolist()})"
            )
            judged += len(t)
    return judged


@pytest.mark.parametrize("shard", range(4))
def test_each_edge_cover_is_where_another_piece_lies_beyond_it(shard: int) -> None:
    scenes = _scenes()[shard::4]
    assert len(scenes) > 40
    assert sum(_check_cover_against_shapely(s) for s in scenes) > 10_000


def test_cover_intervals_are_disjoint_sorted_and_within_the_edge() -> None:
    for scene in _scenes()[::7]:
        verts, counts, circles = _packed(scene)
        boxes = piece_boxes(verts, counts)
        for p in range(len(counts)):
            for i in range(counts[p]):
                cover = edge_cover(verts, counts, circles, boxes, p, i)
                assert np.all(cover[:, 0] >= 0.0) and np.all(cover[:, 1] <= 1.0)
                assert np.all(cover[:, 1] - cover[:, 0] > T_TOL)
                assert np.all(cover[1:, 0] > cover[:-1, 1] + T_TOL)


def test_the_split_cuts_every_edge_exactly_at_its_cover_ends() -> None:
    """Per piece: the sub-edges' vertices are the original vertices and, between them, the
    points a + t (b - a) at the cover ends strictly inside the edge (the same floats), in
    order; a sub-edge is surface exactly when its midpoint is in no cover interval; inserted
    vertices are no contact corners."""
    for scene in _scenes()[::5]:
        verts, counts, circles = _packed(scene)
        boxes = piece_boxes(verts, counts)
        solid = split_at_cover(verts, counts, circles)
        out, out_counts, surface, inserted = split_kernel(verts, counts, circles)
        np.testing.assert_array_equal(out, solid.verts)
        np.testing.assert_array_equal(out_counts, solid.counts)
        np.testing.assert_array_equal(surface, solid.surface)
        assert not np.any(solid.corners & inserted)
        for p in range(len(counts)):
            n, w = counts[p], 0
            for i in range(n):
                a, b = verts[p, i], verts[p, (i + 1) % n]
                cover = edge_cover(verts, counts, circles, boxes, p, i)
                cuts = sorted({t for t in cover.ravel() if T_TOL < t < 1.0 - T_TOL})
                bounds = [0.0, *cuts, 1.0]
                for k in range(len(bounds) - 1):
                    assert np.array_equal(out[p, w], a + bounds[k] * (b - a))
                    assert inserted[p, w] == (k > 0)
                    mid = 0.5 * (bounds[k] + bounds[k + 1])
                    assert surface[p, w] == (not any(lo <= mid <= hi for lo, hi in cover))
                    w += 1
            assert w == out_counts[p]
            assert np.all(out[p, w:] == out[p, w - 1])  # padding repeats the last vertex


def test_no_pieces_give_a_typed_empty_surface() -> None:
    solid = split_at_cover(np.zeros((0, 3, 2)), np.zeros(0, dtype=np.int64), np.zeros((0, 3)))
    assert solid.verts.shape == (0, 3, 2) and solid.counts.shape == (0,)
    assert solid.surface.shape == (0, 3) and solid.corners.shape == (0, 3)


def test_a_disc_alone_covers_the_chord_of_an_edge_through_it() -> None:
    """The square [0, 2] x [-2, 0]'s top edge runs from (2, 0) to (0, 0); a disc of radius
    0.5 at (1, 0.3) covers x in [1 - 0.4, 1 + 0.4], i.e. t in [0.3, 0.7]."""
    square = np.array([[[0.0, -2.0], [2.0, -2.0], [2.0, 0.0], [0.0, 0.0]]])
    counts = np.array([4])
    circles = np.array([[1.0, 0.3, 0.5]])
    cover = edge_cover(square, counts, circles, piece_boxes(square, counts), 0, 2)
    np.testing.assert_allclose(cover, [[0.3, 0.7]], atol=1e-12)
    solid = split_at_cover(square, counts, circles)
    assert solid.counts.tolist() == [6]
    assert solid.surface[0].tolist() == [True, True, True, False, True, True]
