"""Every level takes a part of several pieces (issue 24): the paper's cup, a U of three
rectangles, and a part with a disc.

References that do not come from the code under test: shapely for the geometric level's
non-penetration (the union of the part's pieces against the union of the obstacles), statics
for where a U comes to rest on a floor (:func:`feeders.composite_part.stable_poses`: the
centre of mass above the supporting face, at the face's distance from it), shapely again for
the depth of a pin inside a U that hooks it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from feeders.composite_part import CompositePart, stable_poses
from feeders.cup import CUP_HEIGHT, CUP_WALL, cup_part
from feeders.part_shape import part_geometry
from feeders.scene import Goal, Scene
from feeders.shapes import Obstacles
from validity.dynamic import DynamicLevel
from validity.geometric import GeometricLevel
from validity.kinematic import KinematicLevel
from validity.scene_arrays import PartArrays

CUP = cup_part()
FLOOR = np.array([[-20.0, -2.0], [20.0, -2.0], [20.0, 0.0], [-20.0, 0.0]])
PIN = (0.0, 2.0, 0.2)  # a disc pin B, 0.4 across: fits the cup's 0.7 opening
DEPTH_TOL = 1e-3  # deepest overlap (length) a dynamic run may end with, as for the peg


def _scene(part, obstacles: Obstacles, mu: float = 0.3) -> Scene:
    return Scene(
        name="composite",
        obstacles=obstacles,
        part=part,
        bounds=(-19.0, 19.0, -1.0, 30.0),
        starts={"above": (0.0, 3.0, 0.0)},
        goal=Goal(x_min=-1.0, x_max=1.0, y_min=0.0, y_max=1.0, yaw=-math.pi / 2, yaw_tol=0.3),
        friction=mu,
    )


def _floor_and_pin() -> Scene:
    return _scene(CUP, Obstacles((FLOOR,), np.array([PIN])))


def _solid(scene: Scene) -> shapely.Geometry:
    pieces = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    pieces += [shapely.Point(c[:2]).buffer(c[2], quad_segs=256) for c in scene.obstacles.circles]
    return shapely.union_all(pieces)


def _depth(scene: Scene, part, states: np.ndarray) -> float:
    """Deepest overlap over ``states`` (shapely): of the part's boundary points inside the
    obstacles and of the obstacles' boundary points inside the part, the largest distance to
    the other's boundary. Independent of the contact kernel."""
    solid = _solid(scene)
    shapely.prepare(solid)
    worst = 0.0
    for x, y, yaw in states[:, :3]:
        shape = part_geometry(part, (x, y, yaw))
        if not shape.intersects(solid):
            continue
        overlap = shape.intersection(solid)
        if overlap.area <= 1e-12:
            continue
        for px, py in shapely.get_coordinates(overlap.boundary.segmentize(0.01)):
            point = shapely.Point(px, py)
            worst = max(worst, min(shape.boundary.distance(point), solid.boundary.distance(point)))
    return worst


def test_the_cup_is_three_pieces_with_four_seams_no_surface():
    """The U's walls meet its base along two seams: those sub-edges are no surface, and the
    part's outline has eight corners (the U's four outer and two inner corners and the two
    tips of each wall: its six outer plus its two concave inner corners)."""
    arrays = PartArrays.from_part(CUP)
    assert arrays.body.shape[0] == 3
    seams = ~arrays.surface & (np.arange(arrays.body.shape[1]) < arrays.counts[:, None])
    assert seams.sum() == 2 * 2  # each seam is an edge of both pieces it joins
    outline = part_geometry(CUP).simplify(0.0)  # its flat joints dropped
    assert len(outline.exterior.coords) - 1 == 8
    corners = {
        (round(float(x), 9), round(float(y), 9))
        for q in range(3)
        for k in range(arrays.counts[q])
        if arrays.corners[q, k]
        for x, y in [arrays.body[q, k]]
    }
    expected = {(round(x, 9), round(y, 9)) for x, y in outline.exterior.coords[:-1]}
    assert corners == expected


def test_geometric_validity_of_the_cup_is_shapelys_outside_a_thin_band():
    """On random poses around a floor and a pin, the geometric level calls a pose valid
    exactly when the U (union of its pieces) and the obstacles do not overlap by more than a
    band of 1e-6 (shapely); poses of both kinds are asked."""
    scene = _floor_and_pin()
    level = GeometricLevel(scene)
    solid = _solid(scene)
    rng = np.random.default_rng(4)
    valid = invalid = 0
    for _ in range(3000):
        pose = (rng.uniform(-1.5, 1.5), rng.uniform(-0.2, 3.2), rng.uniform(-math.pi, math.pi))
        shape = part_geometry(CUP, pose)
        overlap = shape.intersection(solid)
        gap = shape.distance(solid)
        if gap < 1e-6 and overlap.area < 1e-6:
            continue  # touching: inside the band
        ok = level.is_valid(pose)
        assert ok == (overlap.area == 0.0), pose
        valid += ok
        invalid += not ok
        clearance = level.clearance(pose)
        if gap > 0:
            assert clearance == pytest.approx(gap, abs=2e-3)  # the disc is a 256-gon here
    assert valid > 300 and invalid > 300


def test_a_part_with_a_disc_is_checked_against_shapely_too():
    """A dumbbell (a bar with a disc at one end): the disc's contacts with the pin and the
    floor count as the polygons' do."""
    bar = np.array([[0.0, -0.15], [1.5, -0.15], [1.5, 0.15], [0.0, 0.15]])
    part = CompositePart((bar,), (1.0,), np.array([[1.85, 0.0, 0.35]]), (2.0,))
    scene = _scene(part, Obstacles((FLOOR,), np.array([PIN])))
    level = GeometricLevel(scene)
    solid = _solid(scene)
    rng = np.random.default_rng(5)
    asked = 0
    for _ in range(2000):
        pose = (rng.uniform(-2.0, 2.0), rng.uniform(-0.2, 3.5), rng.uniform(-math.pi, math.pi))
        shape = part_geometry(part, pose)
        if shape.distance(solid) < 2e-3 and shape.intersection(solid).area < 2e-3:
            continue  # the discs are polygons to shapely: a band of their difference
        assert level.is_valid(pose) == (shape.intersection(solid).area == 0.0), pose
        asked += 1
    assert asked > 1500


@pytest.mark.parametrize("index", range(4))
def test_the_cup_settles_in_each_stable_pose_statics_predicts(index):
    """Dropped 0.05 above a floor, tilted 0.05 rad off each of its stable poses (base down,
    rim down, on either side), the cup comes back to that pose: its yaw the pose's, its centre
    of mass at the supporting face's distance above the floor, at rest, never deeper in the
    floor than the tolerance."""
    poses = stable_poses(CUP)
    assert len(poses) == 4
    pose = poses[index]
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    height = -float((pose.face @ np.array([s, c]))[0])  # the face's world y below the com
    scene = _scene(CUP, Obstacles((FLOOR,), np.zeros((0, 3))))
    level = DynamicLevel(scene)
    start = level.state_of_pose((0.0, height + 0.05, pose.yaw + 0.05))
    run = level.simulate(start, duration=3.0, rest_speed=1e-3, rest_time=0.2)
    _, y, yaw = run.final[:3]
    assert run.end == "at_rest"
    assert abs(math.remainder(yaw - pose.yaw, 2 * math.pi)) < 2e-3
    assert y == pytest.approx(height, abs=2e-3)
    assert _depth(scene, CUP, run.states[::10]) < DEPTH_TOL
    assert run.energy_rise() <= 1e-9


def test_the_cup_hooks_a_pin_without_passing_through_it():
    """Open end down, dropped onto a pin 0.15 off its axis, the cup swallows the pin, tips over
    and hangs from it by a wall's inner face, rocking on it (a flat face rolling on a circle
    without slipping dissipates nothing, so the rocking goes on): over its last second the pin
    stays inside the U's opening (within its hull, not in the U) and the cup never reaches
    the floor; the pin is never deeper in the cup than the tolerance (shapely); energy never
    rises."""
    scene = _floor_and_pin()
    level = DynamicLevel(scene)
    start = level.state_of_pose((0.15, PIN[1] + 0.3, math.pi / 2))
    run = level.simulate(start, duration=4.0)
    pin = shapely.Point(PIN[:2])
    for x, y, yaw in run.states[-1000::50, :3]:
        shape = part_geometry(CUP, (x, y, yaw))
        assert shape.convex_hull.contains(pin) and not shape.contains(pin)
        assert shape.bounds[1] > 0.5  # hanging, far above the floor
    assert _depth(scene, CUP, run.states[::5]) < DEPTH_TOL
    assert run.energy_rise() <= 1e-9


def test_the_kinematic_level_pushes_the_cup_onto_a_pin_without_overlap():
    """Eq. 8 with impulses: the cup driven open end first onto the pin for 2 s stops with the
    pin in its opening, never overlapping it (shapely)."""
    scene = _floor_and_pin()
    level = KinematicLevel(scene)
    state = level.state_of_pose((-2.0, PIN[1], math.pi))  # open end (body -x) toward +x
    states = level.run(state, (1.0, 0.0, 0.0), 2.0, record=True).states
    final = states[-1]
    assert final[0] > -1.0  # it moved in ...
    shape = part_geometry(CUP, final[:3])
    assert shape.convex_hull.contains(shapely.Point(PIN[:2]))  # ... and swallowed the pin
    assert _depth(scene, CUP, states[::5]) < DEPTH_TOL


def test_the_cup_slides_base_down_over_its_own_flat_joints_as_coulomb_says():
    """Base down, the cup's bottom face is three collinear edges (a wall's end, the base, the
    other wall's end): the flat joints between them must not catch on the floor. Sliding at
    2 length/s it stops after v^2 / (2 mu g), the closed form of Coulomb friction, and never
    tips."""
    mu, v0, g = 0.3, 2.0, 9.81
    scene = _scene(CUP, Obstacles((FLOOR,), np.zeros((0, 3))), mu=mu)
    level = DynamicLevel(scene)
    base_down = next(p for p in stable_poses(CUP) if abs(p.yaw + math.pi / 2) < 1e-9)
    height = float(np.max(base_down.face[:, 0]))  # body x of the base's outer face
    start = (0.0, height, -math.pi / 2, v0, 0.0, 0.0)
    run = level.simulate(start, duration=1.0)
    x, y = run.final[:2]
    assert x == pytest.approx(v0**2 / (2 * mu * g), rel=5e-3)
    assert np.max(np.abs(run.states[:, 2] + math.pi / 2)) < 1e-3
    assert y == pytest.approx(height, abs=1e-3)


def test_the_cup_comes_down_over_a_post_and_rests_on_it_flush():
    """Open end down over a post 0.4 wide and 0.9 tall (the opening is 0.7 wide, 0.75 deep),
    0.1 off its axis: the post goes into the opening and the base's inner face comes down flat
    on the post's top (flush faces, inside the part's concave opening). The centre of mass is
    over the post, so statics says it hangs there: yaw pi/2, centre of mass 0.195 (the inner
    face's distance from it) below the post's top, the rims clear of the floor. The post is
    never deeper in the cup than the tolerance (shapely); energy never rises."""
    post = np.array([[-0.2, 0.0], [0.2, 0.0], [0.2, 0.9], [-0.2, 0.9]])
    scene = _scene(CUP, Obstacles((FLOOR, post), np.zeros((0, 3))))
    level = DynamicLevel(scene)
    start = level.state_of_pose((0.1, 1.4, math.pi / 2))
    run = level.simulate(start, duration=4.0, rest_speed=1e-3, rest_time=0.2)
    assert run.end == "at_rest"
    x, y, yaw = run.final[:3]
    assert abs(math.remainder(yaw - math.pi / 2, 2 * math.pi)) < 1e-3
    inner = CUP_HEIGHT - 0.555 - CUP_WALL  # the base's inner face, above the centre of mass
    assert y == pytest.approx(0.9 - inner, abs=1e-3)
    assert abs(x - 0.1) < 0.05
    assert _depth(scene, CUP, run.states[::5]) < DEPTH_TOL
    assert run.energy_rise() <= 1e-9
