"""Any part, in any device, as a compound body in MuJoCo and pymunk (issue 35, part 4).

The peg feeder's peers (:mod:`.mujoco_engine`, :mod:`.pymunk_engine`) model the part as one
box. A composite part (:class:`feeders.composite_part.CompositePart`: the cup, an L split into
convex pieces, plates with discs) is built here from **the same convex pieces** the levels use
(:func:`part_pieces`, body frame: origin at the centre of mass), on one rigid body whose mass
and moment of inertia about the centre of mass are **the part's own closed forms**
(:func:`feeders.part_properties.mass_properties`), set explicitly: the shapes carry no mass of
their own, so no engine recomputes them from its geometry (a test checks each engine's body
against the closed form and shapely). A part whose pieces make one convex polygon (the peg's
two halves) is one piece, its hull: there is then no internal seam for an engine to catch on.

The walls are the peers' as for the peg feeder: MuJoCo every convex piece of the device as an
exact prism mesh and every disc as a sphere in the part's plane
(:func:`.mujoco_engine.feeder_model_xml`), pymunk one chain of segments along the solid's
outline with neighbours, rounded by ``radius`` (:class:`.pymunk_engine.PymunkFeederSimulator`).

Model choices (docs/agreement.md, "Peers for any part and device"):

* MuJoCo: each part polygon a mesh prism of depth ``PART_DEPTH`` (MuJoCo collides a mesh as
  its convex hull, exact for a convex piece), each part disc a sphere centred in the plane
  (its section there is the disc); the pieces of one body never collide with each other.
* pymunk: each part polygon a ``Poly`` of radius 0 (sharp corners, as the peg's), each part
  disc a ``Circle``; the walls' segment radius (their convex corners' rounding) is the choice
  the suite varies (:data:`ROUNDING`), the chain moved that far into the solid so the faces stay
  where they are.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely

from experiments.bench.peers.mujoco_engine import (
    PART_DEPTH,
    MujocoFeederSimulator,
    _vec,
    feeder_model_xml,
)
from experiments.bench.peers.pymunk_engine import SEGMENT_RADIUS, PymunkFeederSimulator
from feeders.part_properties import as_composite, mass_properties
from feeders.part_shape import Part
from feeders.scene import Scene

ROUNDING = (SEGMENT_RADIUS, 3e-3)
"""pymunk's wall segment radii the suite compares (length): the peg feeder's 1 mm, and 3 mm."""

CONVEX_TOLERANCE = 1e-9  # relative area: pieces whose union is their hull are one piece


@dataclass(frozen=True)
class PartPieces:
    """A part as an engine builds it: convex polygons (each ``(K, 2)``, CCW) and discs
    (``(D, 3)``: cx, cy, radius), body frame (origin at the centre of mass, the pose's frame),
    the mass and the moment of inertia about the centre of mass (mass x length^2)."""

    polygons: tuple[np.ndarray, ...]
    discs: np.ndarray
    mass: float
    inertia: float


def part_pieces(part: Part) -> PartPieces:
    """The part's pieces in its body frame with its closed-form mass and inertia; a part whose
    polygons (no discs) make one convex polygon becomes that polygon (no seam)."""
    pieces = as_composite(part)
    props = mass_properties(part)
    polygons = tuple(np.asarray(p, dtype=float) for p in pieces.body_polygons())
    discs = np.asarray(pieces.body_discs(), dtype=float).reshape(-1, 3)
    if len(polygons) > 1 and len(discs) == 0:
        union = shapely.unary_union([shapely.Polygon(p) for p in polygons])
        hull = union.convex_hull
        if abs(hull.area - union.area) <= CONVEX_TOLERANCE * hull.area:
            ring = np.asarray(shapely.simplify(hull, 0.0).exterior.coords)[:-1]
            polygons = (ring,)
    return PartPieces(polygons, discs, float(props.mass), float(props.inertia))


def mujoco_part_body(scene: Scene, mu: str) -> tuple[list[str], str]:
    """The part as MJCF: its polygons' mesh assets, and the body (slide x, slide z, a hinge
    about -y: the joint values are the scene's x, y and counter-clockwise yaw) with the part's
    mass and moment about its centre of mass (the body's origin) and one geom per piece."""
    pieces = part_pieces(scene.part)
    assets, geoms = [], []
    for k, polygon in enumerate(pieces.polygons):
        vertices = []
        for x, y in polygon:
            vertices += [x, -PART_DEPTH / 2, y, x, PART_DEPTH / 2, y]
        assets.append(f'    <mesh name="part{k}" vertex="{_vec(vertices)}"/>')
        geoms.append(
            f'      <geom name="part{k}" type="mesh" mesh="part{k}" friction="{mu}" mass="0"/>'
        )
    for k, (cx, cy, radius) in enumerate(pieces.discs):
        geoms.append(
            f'      <geom name="partdisc{k}" type="sphere" size="{float(radius):.17g}" '
            f'pos="{_vec((cx, 0.0, cy))}" friction="{mu}" mass="0"/>'
        )
    inertia = _vec((pieces.inertia,) * 3)
    body = f"""    <body name="part">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="y" type="slide" axis="0 0 1"/>
      <joint name="yaw" type="hinge" axis="0 -1 0"/>
      <inertial pos="0 0 0" mass="{pieces.mass:.17g}" diaginertia="{inertia}"/>
{chr(10).join(geoms)}
    </body>"""
    return assets, body


def compound_model_xml(scene: Scene, h: float) -> str:
    """MJCF of a device (convex pieces and discs) with a compound part, timestep ``h``."""
    return feeder_model_xml(scene, h, part_body=mujoco_part_body)


class MujocoCompoundSimulator(MujocoFeederSimulator):
    """A device and any part in MuJoCo at step ``h`` (s) (:func:`compound_model_xml`); the
    state is (qpos, qvel) = (x, y, yaw, vx, vy, omega) of the centre of mass."""

    def __init__(self, scene: Scene, h: float):
        super().__init__(scene, h, compound_model_xml(scene, h))


def add_pymunk_part(pymunk, space, scene: Scene, start: Sequence[float]):
    """Add the scene's discs (static, friction 1: Chipmunk multiplies the shapes' mu) and the
    compound part (one body of the part's mass and moment, a shape per piece, friction mu,
    elasticity 0) at ``start`` = (x, y, yaw, vx, vy, omega) to ``space``; returns the body."""
    for cx, cy, radius in scene.obstacles.circles:
        disc = pymunk.Circle(space.static_body, float(radius), (float(cx), float(cy)))
        disc.friction, disc.elasticity = 1.0, 0.0
        space.add(disc)
    pieces = part_pieces(scene.part)
    body = pymunk.Body(pieces.mass, pieces.inertia)
    body.position = (float(start[0]), float(start[1]))
    body.angle = float(start[2])
    body.velocity = (float(start[3]), float(start[4]))
    body.angular_velocity = float(start[5])
    shapes = [pymunk.Poly(body, [tuple(map(float, p)) for p in poly]) for poly in pieces.polygons]
    shapes += [pymunk.Circle(body, float(r), (float(cx), float(cy))) for cx, cy, r in pieces.discs]
    for shape in shapes:
        shape.friction, shape.elasticity = float(scene.friction), 0.0
    space.add(body, *shapes)
    return body


class PymunkCompoundSimulator(PymunkFeederSimulator):
    """A device and any part in pymunk at step ``h`` (s): the walls as the peg feeder's
    (segment chains of radius ``radius``), the part a compound body (:func:`add_pymunk_part`)."""

    def __init__(self, scene: Scene, h: float, radius: float = SEGMENT_RADIUS):
        super().__init__(scene, h, radius=radius)

    def _add_part(self, space, start: Sequence[float]):
        return add_pymunk_part(self.pymunk, space, self.scene, start)
