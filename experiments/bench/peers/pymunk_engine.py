"""pymunk (Chipmunk2D) on a partfeeder scene: the part as a polygon body among static convex
polygons and circles, stepped with ``Space.step(h)``.

Built from the :class:`feeders.scene.Scene`: the part's body has the scene's mass and moment of
inertia, its shape the part's rectangle in the body frame (origin at the centre of mass); each
convex piece of the obstacles is a static ``Poly``, each disc a static ``Circle``. Chipmunk
multiplies the two shapes' friction coefficients: the part gets mu, the obstacles 1.
Elasticity 0 on both (no restitution, as the dynamic level).

Settings (:data:`SETTINGS`): ``default`` is pymunk's defaults (10 solver iterations, collision
slop 0.1: overlaps up to 0.1 length are left alone, collision bias (1 - 0.1)^60 per second);
``accurate`` uses 100 iterations and a collision slop of 1e-4.

Feeders (:class:`PymunkFeederSimulator`, for the agreement suite): the walls are one chain of
static segments along the solid's outline (:mod:`experiments.bench.peers.outline`), each
segment told its neighbours (``Segment.set_neighbors``; without them the part caught on the
chain's vertices) and of radius :data:`SEGMENT_RADIUS` on a chain moved that far into the solid
(the faces exact, convex corners rounded by 1 mm), not one ``Poly`` per convex piece:
pieces meeting along internal mitre faces gave pymunk ghost normals at the lip and the exit
mouth. Discs are ``Circle`` shapes; settings as ``accurate`` (100 iterations, slop 1e-4).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from experiments.bench.peers.outline import chain_segments, outline_chains
from feeders.scene import Scene

ENGINE = "pymunk"
SETTINGS = {
    "default": "pymunk defaults (10 iterations, collision slop 0.1)",
    "accurate": "100 iterations, collision slop 1e-4",
}
_OPTIONS = {
    "default": {},
    "accurate": {"iterations": 100, "collision_slop": 1e-4},
}


def available() -> bool:
    """True when the optional ``pymunk`` package can be imported."""
    try:
        import pymunk  # noqa: F401
    except ImportError:
        return False
    return True


def _add_discs_and_part(pymunk, space, scene: Scene, start: Sequence[float]):
    """Add the scene's discs (static, friction 1: Chipmunk multiplies the shapes' mu) and the
    part's body and polygon at ``start`` = (x, y, yaw, vx, vy, omega) to ``space``; returns
    the part's body."""
    for cx, cy, radius in scene.obstacles.circles:
        disc = pymunk.Circle(space.static_body, float(radius), (float(cx), float(cy)))
        disc.friction, disc.elasticity = 1.0, 0.0
        space.add(disc)
    body = pymunk.Body(scene.part.mass, scene.part.inertia)
    body.position = (float(start[0]), float(start[1]))
    body.angle = float(start[2])
    body.velocity = (float(start[3]), float(start[4]))
    body.angular_velocity = float(start[5])
    part = pymunk.Poly(body, [tuple(p) for p in scene.part.body_vertices()])
    part.friction, part.elasticity = float(scene.friction), 0.0
    space.add(body, part)
    return body


class PymunkSimulator:
    """A pymunk space of a scene at step h, built afresh for every start (no cached contacts
    carry over from one run to the next)."""

    def __init__(self, scene: Scene, h: float, setting: str = "default"):
        import pymunk

        self.pymunk = pymunk
        self.scene = scene
        self.h = h
        self.options = _OPTIONS[setting]
        self.space = pymunk.Space()
        self.body = pymunk.Body()

    def prepare(self, start: Sequence[float]) -> None:
        pymunk, scene = self.pymunk, self.scene
        space = pymunk.Space()
        space.gravity = tuple(scene.gravity)
        for name, value in self.options.items():
            setattr(space, name, value)
        for polygon in scene.obstacles.polygons:
            shape = pymunk.Poly(space.static_body, [tuple(p) for p in polygon])
            shape.friction, shape.elasticity = 1.0, 0.0
            space.add(shape)
        self.space, self.body = space, _add_discs_and_part(pymunk, space, scene, start)

    def advance(self, steps: int) -> None:
        step, h = self.space.step, self.h
        for _ in range(steps):
            step(h)

    def _state(self) -> tuple[float, ...]:
        b = self.body
        return (b.position.x, b.position.y, b.angle, b.velocity.x, b.velocity.y, b.angular_velocity)

    def record(self, start: Sequence[float], steps: int) -> np.ndarray:
        self.prepare(start)
        out = np.empty((steps + 1, 6))
        out[0] = self._state()
        step, h = self.space.step, self.h
        for k in range(1, steps + 1):
            step(h)
            out[k] = self._state()
        return out


FEEDER_ITERATIONS = 100
FEEDER_SLOP = 1e-4
SEGMENT_RADIUS = 1e-3
"""Radius (length) of the chain's segments, the chain moved that far into the solid so the
faces stay where they are (the convex corners rounded by it). With radius 0 pymunk took the
part's speed at the lip in about 8% of drops (the ratio to the sliding closed form down to
0.42, the part stopped dead and spun as its leading corner passed the lip; docs/agreement.md);
with 1e-3 it kept it in every drop tried."""


class PymunkFeederSimulator:
    """A feeder scene in pymunk at step ``h`` (s): walls as segment chains, discs as circles,
    the part a polygon with the scene's mass and inertia; restitution 0, friction mu (the
    walls 1: Chipmunk multiplies). ``reset`` builds a fresh space (no contact cache carries
    over); ``run`` steps and records."""

    def __init__(
        self,
        scene: Scene,
        h: float,
        iterations: int = FEEDER_ITERATIONS,
        collision_slop: float = FEEDER_SLOP,
        radius: float = SEGMENT_RADIUS,
    ):
        import pymunk

        self.pymunk = pymunk
        self.scene = scene
        self.h = float(h)
        self.iterations = int(iterations)
        self.collision_slop = float(collision_slop)
        self.radius = float(radius)
        self.chains = outline_chains(scene, offset=self.radius)
        self.space = pymunk.Space()
        self.body = pymunk.Body()

    def reset(self, start: Sequence[float]) -> None:
        """A new space with the part at ``start`` = (x, y, yaw, vx, vy, omega)."""
        pymunk, scene = self.pymunk, self.scene
        space = pymunk.Space()
        space.gravity = (float(scene.gravity[0]), float(scene.gravity[1]))
        space.iterations = self.iterations
        space.collision_slop = self.collision_slop
        for chain in self.chains:
            for before, a, b, after in chain_segments(chain):
                seg = pymunk.Segment(
                    space.static_body, tuple(map(float, a)), tuple(map(float, b)), self.radius
                )
                seg.set_neighbors(tuple(map(float, before)), tuple(map(float, after)))
                seg.friction, seg.elasticity = 1.0, 0.0
                space.add(seg)
        self.space, self.body = space, self._add_part(space, start)

    def _add_part(self, space, start: Sequence[float]):
        """Add the discs and the part at ``start`` to ``space``; returns the part's body (the
        peg as one polygon here; :class:`.compound.PymunkCompoundSimulator`: any part)."""
        return _add_discs_and_part(self.pymunk, space, self.scene, start)

    def run(self, out: np.ndarray) -> None:
        """Take ``len(out)`` steps; row k of ``out`` gets the state after step k + 1."""
        step, h, b = self.space.step, self.h, self.body
        for k in range(out.shape[0]):
            step(h)
            p, v = b.position, b.velocity
            out[k] = (p.x, p.y, b.angle, v.x, v.y, b.angular_velocity)


def builder(setting: str) -> Callable[[Scene, float], PymunkSimulator]:
    """``build(scene, h)`` for one setting (checked now, built later)."""
    if setting not in _OPTIONS:
        raise ValueError(f"pymunk setting {setting!r}; settings: {', '.join(_OPTIONS)}")
    return lambda scene, h: PymunkSimulator(scene, h, setting)
