"""Box2D (pybox2d 2.3) on any part and device: the arbiter where two engines disagree (issue 35).

Box2D is tuned for moving objects of 0.1-10 m and gives every polygon and edge a skin of
``b2_polygonRadius`` (0.01 m): shapes collide when their cores are that far apart. So the scene
is **scaled** by ``scale`` (lengths x S, gravity x S, velocities x S, the moment of inertia x
S^2; time, angles, mass and friction unchanged) and the skin is made part of the shape: every
convex piece of the part is shrunk by r = 0.01 / S (scene units, mitred, so it stays convex)
and the walls' outline chain (:mod:`.outline`, one ``b2LoopShape`` per ring, Box2D's ghost
vertices its fix for seams) is moved r into the solid. With the skin added back, every face is
where the scene has it and every **convex corner is rounded by r** (1/400 of a unit at S = 4,
1/800 at S = 8). Discs are circles (no skin). The part is one body whose mass and moment about
its centre of mass (the body's origin) are set to the part's own (``massData``; the fixtures
have no density). Friction mu on every fixture (Box2D mixes by the geometric mean: mu),
restitution 0, sleeping off (the end rule decides rest), 8 velocity and 3 position iterations
(Box2D's defaults).

Box2D computes in float32: positions of up to ~60 m (the device at S = 4) carry about 4e-6 m,
1e-6 scene units.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import shapely

from experiments.bench.peers.compound import part_pieces
from experiments.bench.peers.outline import outline_chains
from feeders.scene import Scene

ENGINE = "box2d"
SKIN = 0.01  # m: b2_polygonRadius of pybox2d 2.3
SCALES = (4.0, 8.0)
"""The scales the suite compares: the cup (1.0 x 0.9) becomes 4 m and 8 m, within Box2D's
0.1-10 m; its thinnest piece (0.15) 0.6 m and 1.2 m."""
VELOCITY_ITERATIONS = 8
POSITION_ITERATIONS = 3


def available() -> bool:
    """True when the optional ``Box2D`` package (pip ``box2d``) can be imported."""
    try:
        import Box2D  # noqa: F401
    except ImportError:
        return False
    return True


def shrunk(polygon: np.ndarray, distance: float) -> np.ndarray:
    """A convex polygon with every face moved ``distance`` inward (mitred: still convex, its
    vertex count unchanged), counter-clockwise."""
    inner = shapely.Polygon(polygon).buffer(-distance, join_style="mitre", mitre_limit=100.0)
    ring = shapely.simplify(inner, 0.0).exterior
    coords = np.asarray(ring.coords)[:-1]
    return coords if ring.is_ccw else coords[::-1]


class Box2DCompoundSimulator:
    """A device and any part in Box2D at step ``h`` (s), the scene scaled by ``scale``; the
    state is reported in scene units: (x, y, yaw, vx, vy, omega) of the centre of mass."""

    def __init__(self, scene: Scene, h: float, scale: float = SCALES[0]):
        from Box2D import b2

        self.b2 = b2
        self.scene = scene
        self.h = float(h)
        self.scale = float(scale)
        r = SKIN / self.scale  # the skin in scene units
        self.chains = [c * self.scale for c in outline_chains(scene, offset=r)]
        pieces = part_pieces(scene.part)
        self.polygons = [shrunk(p, r) * self.scale for p in pieces.polygons]
        self.discs = pieces.discs * self.scale
        self.mass = pieces.mass
        self.inertia = pieces.inertia * self.scale**2
        self.world: Any = None  # Box2D's world and body, made by reset()
        self.body: Any = None

    def reset(self, start: Sequence[float]) -> None:
        """A new world with the part at ``start`` = (x, y, yaw, vx, vy, omega)."""
        b2, s, scene = self.b2, self.scale, self.scene
        mu = float(scene.friction)
        world = b2.world(gravity=(scene.gravity[0] * s, scene.gravity[1] * s), doSleep=False)
        walls = world.CreateStaticBody()
        for chain in self.chains:
            shape = b2.loopShape(vertices=[tuple(map(float, v)) for v in chain])
            walls.CreateFixture(b2.fixtureDef(shape=shape, friction=mu, restitution=0.0))
        for cx, cy, radius in scene.obstacles.circles:
            shape = b2.circleShape(radius=float(radius) * s, pos=(float(cx) * s, float(cy) * s))
            walls.CreateFixture(b2.fixtureDef(shape=shape, friction=mu, restitution=0.0))
        body = world.CreateDynamicBody(
            position=(float(start[0]) * s, float(start[1]) * s), angle=float(start[2])
        )
        body.bullet = True  # continuous collision against the static walls
        for polygon in self.polygons:
            shape = b2.polygonShape(vertices=[tuple(map(float, v)) for v in polygon])
            body.CreateFixture(b2.fixtureDef(shape=shape, density=0.0, friction=mu))
        for cx, cy, radius in self.discs:
            shape = b2.circleShape(radius=float(radius), pos=(float(cx), float(cy)))
            body.CreateFixture(b2.fixtureDef(shape=shape, density=0.0, friction=mu))
        mass = b2.massData()
        mass.mass, mass.center, mass.I = self.mass, (0.0, 0.0), self.inertia
        body.massData = mass
        body.linearVelocity = (float(start[3]) * s, float(start[4]) * s)
        body.angularVelocity = float(start[5])
        self.world, self.body = world, body

    def run(self, out: np.ndarray) -> None:
        """Take ``len(out)`` steps; row k of ``out`` gets the state after step k + 1."""
        step, h, b, s = self.world.Step, self.h, self.body, self.scale
        for k in range(out.shape[0]):
            step(h, VELOCITY_ITERATIONS, POSITION_ITERATIONS)
            p, v = b.position, b.linearVelocity
            out[k] = (p[0] / s, p[1] / s, b.angle, v[0] / s, v[1] / s, b.angularVelocity)
