"""The peers' compound bodies (issue 35, part 4) as a specification.

A peer models what partfeeder models, or the agreement measures adapters: each engine's part
must be the part's own pieces with the part's own mass, centre of mass and moment of inertia.
References are independent of :mod:`feeders.composite_part`: the rectangles' and discs' closed
forms worked here (m = rho w h, I = m (w^2 + h^2) / 12; a disc's m r^2 / 2; the parallel-axis
theorem) and shapely for the shapes. Then a drop of the cup onto a flat floor must come to rest
on one of its stable faces (:func:`feeders.part_properties.mass_properties`) in every engine.
Skipped without MuJoCo or pymunk (optional extras: ``pip install ".[bench]"``); Box2D's
cases (the arbiter, scaled, its skin part of the shapes) without ``pip install box2d``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

pytest.importorskip("mujoco")
pytest.importorskip("pymunk")

from experiments.bench.agreement.drops import partfeeder_drop, peer_drop
from experiments.bench.peers.compound import (
    MujocoCompoundSimulator,
    PymunkCompoundSimulator,
    part_pieces,
)
from feeders.composite_part import part_from_dict
from feeders.cup import cup_part
from feeders.part import DEFAULT_PEG
from feeders.part_properties import mass_properties
from feeders.scene import Goal, Scene
from feeders.shapes import Obstacles
from validity.dynamic import DynamicLevel

FLOOR = np.array([[-20.0, -1.0], [20.0, -1.0], [20.0, 0.0], [-20.0, 0.0]])
SIDES = (  # far walls, so the free box around the solid holds the part's start
    np.array([[-21.0, -1.0], [-20.0, -1.0], [-20.0, 5.0], [-21.0, 5.0]]),
    np.array([[20.0, -1.0], [21.0, -1.0], [21.0, 5.0], [20.0, 5.0]]),
)


def _rectangle(x0, x1, y0, y1, rho):
    """(mass, centre, moment about its own centre) of a uniform rectangle."""
    w, h = x1 - x0, y1 - y0
    m = rho * w * h
    return m, np.array([(x0 + x1) / 2, (y0 + y1) / 2]), m * (w * w + h * h) / 12


def _disc(cx, cy, r, rho):
    m = rho * math.pi * r * r
    return m, np.array([cx, cy]), 0.5 * m * r * r


def _combined(pieces):
    """Mass, centre of mass and moment about it of pieces (m, centre, own moment)."""
    mass = sum(m for m, _, _ in pieces)
    com = sum(m * c for m, c, _ in pieces) / mass
    inertia = sum(j + m * float((c - com) @ (c - com)) for m, c, j in pieces)
    return mass, com, inertia


L_OUTLINE = [[0, 0], [0.9, 0], [0.9, 1.0], [0.6, 1.0], [0.6, 0.3], [0, 0.3]]  # examples/
PARTS = {
    # the cup: two walls 0.9 x 0.15 and the base 0.15 x 0.7 between them, mass 1
    "cup": (
        cup_part(),
        [
            _rectangle(0, 0.9, -0.5, -0.35, 1 / 0.375),
            _rectangle(0.75, 0.9, -0.35, 0.35, 1 / 0.375),
            _rectangle(0, 0.9, 0.35, 0.5, 1 / 0.375),
        ],
    ),
    # docs/families.md's L bracket: the foot 0.9 x 0.3 and the upright 0.3 x 0.7 on it
    "L": (
        part_from_dict({"outline": L_OUTLINE, "density": 1.0}),
        [_rectangle(0, 0.9, 0, 0.3, 1.0), _rectangle(0.6, 0.9, 0.3, 1.0, 1.0)],
    ),
    # a plate with a denser disc on it (touching at a point)
    "plate with a disc": (
        part_from_dict(
            {
                "pieces": [
                    {"polygon": [[0, 0], [2, 0], [2, 0.3], [0, 0.3]], "density": 1.0},
                    {"disc": {"centre": [1, 0.5], "radius": 0.2}, "density": 3.0},
                ]
            }
        ),
        [_rectangle(0, 2, 0, 0.3, 1.0), _disc(1, 0.5, 0.2, 3.0)],
    ),
}


def _scene(part, start=(0.0, 3.0, 0.0)) -> Scene:
    """A flat floor (top face y = 0, between far walls) and ``part`` above it; the goal out of
    reach."""
    goal = Goal(-1.0, 1.0, -60.0, -59.0, -math.pi / 2, 0.3)
    return Scene(
        "floor", Obstacles((FLOOR, *SIDES), np.zeros((0, 3))), part, (-30, 30, -30, 30),
        {"drop": start}, goal, friction=0.5, restitution=0.0,
    )  # fmt: skip


def _reference_shape(name: str, com: np.ndarray) -> shapely.Geometry:
    """The part's polygons (no discs) by hand, in the body frame (origin at ``com``)."""
    if name == "cup":
        boxes = [(0, 0.9, -0.5, -0.35), (0.75, 0.9, -0.35, 0.35), (0, 0.9, 0.35, 0.5)]
    elif name == "L":
        boxes = [(0, 0.9, 0, 0.3), (0.6, 0.9, 0.3, 1.0)]
    else:
        boxes = [(0, 2, 0, 0.3)]
    shapes = [
        shapely.box(x0 - com[0], y0 - com[1], x1 - com[0], y1 - com[1]) for x0, x1, y0, y1 in boxes
    ]
    return shapely.union_all(shapes)


@pytest.mark.parametrize("name", list(PARTS))
def test_the_parts_closed_forms_are_the_rectangles_and_discs_by_hand(name):
    part, pieces = PARTS[name]
    mass, com, inertia = _combined(pieces)
    own = part_pieces(part)
    assert own.mass == pytest.approx(mass, rel=1e-12)
    assert own.inertia == pytest.approx(inertia, rel=1e-12)
    assert mass_properties(part).com == pytest.approx(com, abs=1e-12)


@pytest.mark.parametrize("name", list(PARTS))
def test_pymunk_body_has_the_parts_mass_properties_and_pieces(name):
    part, pieces = PARTS[name]
    mass, com, inertia = _combined(pieces)
    sim = PymunkCompoundSimulator(_scene(part), 1e-4)
    sim.reset((0.0, 3.0, 0.0, 0.0, 0.0, 0.0))
    body = sim.body
    assert body.mass == pytest.approx(mass, rel=1e-12)
    assert body.moment == pytest.approx(inertia, rel=1e-12)
    assert tuple(body.center_of_gravity) == (0.0, 0.0)  # the body's origin is the centre of mass
    polygons = [s for s in body.shapes if hasattr(s, "get_vertices")]
    circles = [s for s in body.shapes if not hasattr(s, "get_vertices")]
    shape = shapely.union_all(
        [shapely.Polygon([tuple(v) for v in s.get_vertices()]) for s in polygons]
    )
    reference = _reference_shape(name, com)
    assert shape.symmetric_difference(reference).area < 1e-12
    if name == "plate with a disc":
        (c,) = circles
        assert c.radius == pytest.approx(0.2)
        assert tuple(c.offset) == pytest.approx((1 - com[0], 0.5 - com[1]), abs=1e-12)
    else:
        assert not circles
    assert all(s.mass == 0 and s.density == 0 for s in body.shapes)  # no mass of their own


@pytest.mark.parametrize("name", list(PARTS))
def test_mujoco_body_has_the_parts_mass_properties_and_pieces(name):
    import mujoco

    part, pieces = PARTS[name]
    mass, com, inertia = _combined(pieces)
    sim = MujocoCompoundSimulator(_scene(part), 1e-4)
    model, data = sim.model, sim.data
    body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "part")
    assert model.body_mass[body] == pytest.approx(mass, rel=1e-12)
    assert model.body_inertia[body][1] == pytest.approx(inertia, rel=1e-12)  # about the hinge
    assert np.allclose(model.body_ipos[body], 0.0)
    sim.reset((0.0, 0.0, 0.0, 0.0, 0.0, 0.0))  # the body frame is the world's
    shapes, spheres = [], []
    for g in range(model.ngeom):
        if model.geom_bodyid[g] != body:
            continue
        if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH:
            m = model.geom_dataid[g]
            start, count = model.mesh_vertadr[m], model.mesh_vertnum[m]
            local = model.mesh_vert[start : start + count]
            world = data.geom_xpos[g] + local @ data.geom_xmat[g].reshape(3, 3).T
            shapes.append(shapely.MultiPoint(world[:, [0, 2]]).convex_hull)  # x, z: the plane
        else:
            assert model.geom_type[g] == mujoco.mjtGeom.mjGEOM_SPHERE
            spheres.append((data.geom_xpos[g][[0, 2]], model.geom_size[g][0]))
    reference = _reference_shape(name, com)
    # MuJoCo stores mesh vertices as float32: 6e-8 of 1 length, along a perimeter of ~5
    assert shapely.union_all(shapes).symmetric_difference(reference).area < 1e-6
    if name == "plate with a disc":
        ((centre, radius),) = spheres
        assert radius == pytest.approx(0.2)
        assert centre == pytest.approx((1 - com[0], 0.5 - com[1]), abs=1e-9)
    else:
        assert not spheres


def test_a_convex_part_of_several_pieces_is_one_piece_without_a_seam():
    pieces = part_pieces(DEFAULT_PEG)  # the peg's two halves: one rectangle
    assert len(pieces.polygons) == 1
    assert shapely.Polygon(pieces.polygons[0]).area == pytest.approx(
        DEFAULT_PEG.length * DEFAULT_PEG.width
    )
    assert pieces.mass == DEFAULT_PEG.mass
    assert pieces.inertia == pytest.approx(DEFAULT_PEG.inertia, rel=1e-12)


def _resting_check(part, ending):
    """The drop ended at rest on a stable face: its yaw is a stable pose's, and the part's
    lowest point there is on the floor (y = 0)."""
    stable = [pose.yaw for pose in mass_properties(part).resting]
    _, y, yaw = ending.pose
    gap = min(abs(math.remainder(yaw - s, 2 * math.pi)) for s in stable)
    assert gap < 0.02, (yaw, stable)
    c, s = math.cos(yaw), math.sin(yaw)
    lowest = min(y + s * px + c * py for v in part.body_polygons() for px, py in v)
    assert abs(lowest) < 2e-3


@pytest.mark.parametrize("yaw", [0.4, -1.3, 2.2])
def test_a_cup_dropped_onto_a_floor_rests_on_a_stable_face_in_every_engine(yaw):
    cup = cup_part()
    start = (0.0, 1.2, yaw)
    scene = _scene(cup, start)
    state = (*start, 0.0, 0.0, 0.0)
    endings = {"partfeeder": partfeeder_drop(scene, "drop", state, DynamicLevel(scene), 10.0)}
    endings["mujoco"] = peer_drop(scene, state, MujocoCompoundSimulator(scene, 1e-4), 10.0)
    endings["pymunk"] = peer_drop(scene, state, PymunkCompoundSimulator(scene, 1e-4), 10.0)
    for engine, drop in endings.items():
        assert drop.ending.end == "at_rest", engine
        _resting_check(cup, drop.ending)


@pytest.mark.parametrize("name", list(PARTS))
@pytest.mark.parametrize("scale", [4.0, 8.0])
def test_box2d_body_has_the_parts_mass_properties_and_its_pieces_with_the_skin(name, scale):
    """Box2D's body (scaled by S): mass m, moment I S^2 about its origin, the centre of mass;
    its polygons shrunk by the skin 0.01 / S and grown back by it (Box2D's polygon radius) are
    the part's own, up to the corners' rounding (area (4 - pi) r^2 per corner)."""
    pytest.importorskip("Box2D")
    from experiments.bench.peers.box2d_engine import SKIN, Box2DCompoundSimulator

    part, pieces = PARTS[name]
    mass, com, inertia = _combined(pieces)
    sim = Box2DCompoundSimulator(_scene(part), 1e-4, scale)
    sim.reset((0.0, 3.0, 0.0, 0.0, 0.0, 0.0))
    body = sim.body
    assert body.mass == pytest.approx(mass, rel=1e-6)  # float32
    assert body.inertia == pytest.approx(inertia * scale**2, rel=1e-6)
    assert tuple(body.localCenter) == pytest.approx((0.0, 0.0), abs=1e-6)
    r = SKIN / scale
    cores = [f.shape for f in body.fixtures if hasattr(f.shape, "vertices")]
    grown = shapely.union_all(
        [shapely.Polygon(np.asarray(c.vertices) / scale).buffer(r, quad_segs=32) for c in cores]
    )
    reference = _reference_shape(name, com)
    corners = 4 * len(cores)
    assert grown.symmetric_difference(reference).area < corners * (4 - math.pi) * r * r + 1e-6


@pytest.mark.parametrize("yaw", [0.4, -1.3, 2.2])
@pytest.mark.parametrize("scale", [4.0, 8.0])
def test_a_cup_dropped_onto_a_floor_rests_on_a_stable_face_in_box2d(yaw, scale):
    pytest.importorskip("Box2D")
    from experiments.bench.peers.box2d_engine import Box2DCompoundSimulator

    cup = cup_part()
    start = (0.0, 1.2, yaw)
    scene = _scene(cup, start)
    drop = peer_drop(scene, (*start, 0.0, 0.0, 0.0), Box2DCompoundSimulator(scene, 1e-4, scale), 10)
    assert drop.ending.end == "at_rest"
    _resting_check(cup, drop.ending)


def _cup_on_an_incline(phi: float, mu: float) -> tuple[Scene, tuple[float, ...]]:
    """The cup base down on a slab whose top face rises at ``phi`` through the origin (a far
    wall beyond its lower end, so the free box holds the start)."""
    u, n = np.array([math.cos(phi), math.sin(phi)]), np.array([-math.sin(phi), math.cos(phi)])
    slab = np.array([-20 * u - n, 20 * u - n, 20 * u, -20 * u])
    wall = np.array([-25 * u - n, -20 * u - n, -20 * u + 8 * n, -25 * u + 8 * n])
    yaw = phi - math.pi / 2  # the base (body +x, 0.345 from the centre of mass) toward -n
    com = 5.0 * u + 0.345 * n
    start = (float(com[0]), float(com[1]), yaw)
    goal = Goal(-1.0, 1.0, -60.0, -59.0, -math.pi / 2, 0.3)
    scene = Scene(
        "incline", Obstacles((slab, wall), np.zeros((0, 3))), cup_part(), (-30, 30, -30, 30),
        {"rest": start}, goal, friction=mu, restitution=0.0,
    )  # fmt: skip
    return scene, (*start, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("engine", ["mujoco", "pymunk", "box2d"])
def test_the_cup_slides_down_an_incline_at_the_coulomb_closed_form(engine):
    """Base down on a plane rising at phi with friction mu, the cup slides s = a t^2 / 2,
    a = g (sin phi - mu cos phi), without turning: the compound body's contact and friction
    are the part's, not its pieces' seams'."""
    phi, mu, h, t = 0.5, 0.1, 1e-4, 0.6
    scene, start = _cup_on_an_incline(phi, mu)
    if engine == "box2d":
        pytest.importorskip("Box2D")
        from experiments.bench.peers.box2d_engine import Box2DCompoundSimulator

        sim = Box2DCompoundSimulator(scene, h, 4.0)
    else:
        sim = {"mujoco": MujocoCompoundSimulator, "pymunk": PymunkCompoundSimulator}[engine](
            scene, h
        )
    sim.reset(start)
    out = np.empty((round(t / h), 6))
    sim.run(out)
    u = np.array([math.cos(phi), math.sin(phi)])
    s = float((np.asarray(start[:2]) - out[-1, :2]) @ u)
    accel = 9.81 * (math.sin(phi) - mu * math.cos(phi))
    assert s == pytest.approx(0.5 * accel * t * t, rel=0.01)
    assert abs(out[-1, 2] - start[2]) < 1e-3
