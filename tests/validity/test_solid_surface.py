"""The real surface of overlapping convex pieces (validity.solid_surface), as a specification.

What must hold (issue 11, fault 1): every point of the boundary of the union of the obstacles
is on a surface sub-edge (or a disc's circle), and no point strictly inside the union is.
Reference: shapely's union of the original pieces (an independent implementation): a point just
beyond a sub-edge, along its outward normal, is in the union exactly when the sub-edge is a
seam, at several points along every sub-edge; and points sampled along shapely's boundary of the
union lie on a surface sub-edge or a circle.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import shapely
from test_geometry_kernel import _free_form

from feeders.design import PRESETS
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.halton import halton_designs
from feeders.scene import Scene
from feeders.shapes import Obstacles
from validity.scene_arrays import SceneArrays
from validity.solid_surface import covered_intervals, split_at_cover

PROBE = 1e-6  # how far beyond a sub-edge the union is probed (length)
ALONG = (0.02, 0.25, 0.5, 0.75, 0.98)  # where along each sub-edge (fraction of its length)
ON_BOUNDARY = 1e-7  # a boundary sample this close to a surface sub-edge or circle is covered


FLOOR = np.array([[-5.0, -1.0], [5.0, -1.0], [5.0, 0.0], [-5.0, 0.0]])


def _post(x: float) -> np.ndarray:
    return np.array([[x - 0.5, 0.0], [x + 0.5, 0.0], [x + 0.5, 3.0], [x - 0.5, 3.0]])


def _packed(polygons: list[np.ndarray], circles: tuple = ()):
    return Obstacles(tuple(polygons), np.asarray(circles, dtype=float).reshape(-1, 3)).packed()


def _union(scene: Scene):
    """Shapely's union of the pieces, with cracks narrower than 1e-7 closed (mitred walls meet
    along clipped edges that round-off leaves a few 1e-8 apart: no part fits in there)."""
    pieces = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    pieces += [shapely.Point(c[:2]).buffer(c[2], 512) for c in scene.obstacles.circles]
    return (
        shapely.union_all(pieces).buffer(1e-7, join_style="mitre").buffer(-1e-7, join_style="mitre")
    )


def _scenes() -> list[Scene]:
    scenes = [build_feeder(design, name=name) for name, design in sorted(PRESETS.items())]
    for i, design in enumerate(halton_designs(60, seed=0)):
        try:
            scenes.append(build_feeder(design, name=f"halton seed 0 #{i}"))
        except DegenerateDesign:
            continue
    return [*scenes, _free_form()]


@functools.cache
def _all_scenes() -> list[Scene]:
    return _scenes()


def test_a_post_on_a_floor_splits_the_floor_top_into_surface_seam_surface() -> None:
    """Hand-worked: the post [-0.5, 0.5] x [0, 3] covers the middle of the floor's top edge
    (from (5, 0) to (-5, 0)); that edge becomes three sub-edges, exposed, covered, exposed; the
    two inserted vertices are concave corners of the solid (no contact corners); the post's
    bottom edge is a seam along its whole length."""
    verts, counts, circles = _packed([FLOOR, _post(0.0)])
    solid = split_at_cover(verts, counts, circles)
    floor = solid.verts[0, : solid.counts[0]]
    np.testing.assert_array_equal(floor, [[-5, -1], [5, -1], [5, 0], [0.5, 0], [-0.5, 0], [-5, 0]])
    assert solid.surface[0, : solid.counts[0]].tolist() == [True, True, True, False, True, True]
    assert solid.corners[0, : solid.counts[0]].tolist() == [True, True, True, False, False, True]
    assert solid.counts[1] == 4
    assert solid.surface[1, :4].tolist() == [False, True, True, True]


def test_covered_intervals_of_a_partly_covered_edge_are_exact() -> None:
    """Edge 2 of the floor runs from (5, 0) to (-5, 0): the post at x = 2 covers x in
    [1.5, 2.5], i.e. t in [0.25, 0.35]; a disc of radius 1 at (-3, 0) covers x in [-4, -2]."""
    verts, counts, circles = _packed([FLOOR, _post(2.0)], ((-3.0, 0.0, 1.0),))
    got = covered_intervals(verts, counts, circles, 0, 2)
    np.testing.assert_allclose(got, [(0.25, 0.35), (0.7, 0.9)], atol=1e-12)


def test_pieces_sharing_a_whole_edge_keep_it_whole_and_a_seam() -> None:
    """Two squares sharing x = 0: no edge is split, the shared edges are seams."""
    left = np.array([[-2.0, -2.0], [0.0, -2.0], [0.0, 0.0], [-2.0, 0.0]])
    right = np.array([[0.0, -2.0], [2.0, -2.0], [2.0, 0.0], [0.0, 0.0]])
    solid = split_at_cover(*_packed([left, right]))
    assert solid.counts.tolist() == [4, 4]
    assert solid.surface.tolist() == [[True, False, True, True], [True, True, True, False]]
    assert solid.corners.tolist() == [[True, False, False, True], [False, True, True, False]]


def test_pieces_touching_flush_on_the_outside_cover_nothing() -> None:
    """Two squares stacked with collinear outer faces (x = 1 for both): the outer faces stay
    surfaces; only the shared y = 1 edges are seams."""
    low = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    high = low + np.array([0.0, 1.0])
    solid = split_at_cover(*_packed([low, high]))
    assert solid.surface.tolist() == [[True, True, False, True], [False, True, True, True]]


def _check_surface_against_shapely(scene: Scene) -> tuple[int, int]:
    """Every sub-edge's outward probe is in shapely's union exactly when it is a seam; every
    sample of the union's boundary lies on a surface sub-edge or a circle. Returns the numbers
    of sub-edges checked and of boundary samples checked."""
    arrays = SceneArrays.from_scene(scene)
    union = _union(scene)
    shapely.prepare(union)
    edges = 0
    surface_lines = []
    for p in range(arrays.verts.shape[0]):
        n = arrays.counts[p]
        for i in range(n):
            a, b = arrays.verts[p, i], arrays.verts[p, (i + 1) % n]
            length = math.dist(a, b)
            if length < 1e-9:
                continue
            normal = np.array([b[1] - a[1], a[0] - b[0]]) / length
            probes = [a + t * (b - a) + PROBE * normal for t in ALONG]
            inside = [union.contains(shapely.Point(q)) for q in probes]
            if arrays.surface[p, i]:
                assert not any(inside), f"{scene.name}: surface edge {p}.{i} is covered"
                surface_lines.append(shapely.LineString([a, b]))
            else:
                assert all(inside), f"{scene.name}: seam {p}.{i} faces free space"
            edges += 1
    surface = shapely.union_all(surface_lines)
    samples = 0
    rings = [union.exterior, *union.interiors] if union.geom_type == "Polygon" else []
    for geom in getattr(union, "geoms", []):
        rings += [geom.exterior, *geom.interiors]
    circles = arrays.circles
    for ring in rings:
        for s in np.linspace(0.0, ring.length, 400, endpoint=False):
            point = ring.interpolate(s)
            on_circle = any(
                abs(math.dist((point.x, point.y), c[:2]) - c[2]) < 1e-3 for c in circles
            )
            if on_circle:
                continue  # the disc's own contact covers it (polygonised circle: 1e-3)
            assert surface.distance(point) < ON_BOUNDARY, (
                f"{scene.name}: boundary point ({point.x:.6f}, {point.y:.6f}) of the solid has "
                "no surface edge"
            )
            samples += 1
    return edges, samples


@pytest.mark.parametrize("index", range(8))
def test_surface_is_exactly_the_boundary_of_the_union(index: int) -> None:
    """The presets, the first Halton designs of seed 0 and the free-form scene, in 8 shards."""
    scenes = _all_scenes()[index::8]
    total_edges = total_samples = 0
    for scene in scenes:
        edges, samples = _check_surface_against_shapely(scene)
        total_edges += edges
        total_samples += samples
    assert total_edges > 50 and total_samples > 1000


def test_a_partly_covered_edge_exists_in_the_presets_and_is_split() -> None:
    """fig9's left cavity wall is covered where the pin's finger grows out of it: its inner
    face must be split, not dropped (the fault: the whole face was a seam)."""
    scene = build_feeder(PRESETS["fig9"], name="fig9")
    _, counts, _ = scene.obstacles.packed()
    arrays = SceneArrays.from_scene(scene)
    assert arrays.counts.sum() > counts.sum()  # some edges were split
    left = scene.obstacles.labels.index("left cavity wall")
    n = arrays.counts[left]
    assert n > counts[left]
    assert arrays.surface[left, :n].sum() >= 2  # the face above and below the finger
