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
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

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
        self.space, self.body = space, body

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


def builder(setting: str) -> Callable[[Scene, float], PymunkSimulator]:
    """``build(scene, h)`` for one setting (checked now, built later)."""
    if setting not in _OPTIONS:
        raise ValueError(f"pymunk setting {setting!r}; settings: {', '.join(_OPTIONS)}")
    return lambda scene, h: PymunkSimulator(scene, h, setting)
