"""A second, independent yes/no penetration test built on FCL (python-fcl), for cross-checks.

The geometry kernel (:mod:`validity.geometry_kernel`) is this project's own code; FCL, the
Flexible Collision Library, is the field's standard collision checker. Answering the same
question with it, from the scene's shapes rather than the kernel's packed arrays, tests the
kernel against an implementation that shares none of its code.

The plane is embedded in 3-D: every obstacle is a prism over ``z in [-OBSTACLE_HALF_HEIGHT,
+OBSTACLE_HALF_HEIGHT]`` (convex polygons as ``fcl.Convex``, discs as ``fcl.Cylinder`` with
their axis along z) and the part is an ``fcl.Box`` of height ``2 * PART_HALF_HEIGHT`` centred
on ``z = 0``. The part's slab lies strictly inside the obstacles' slab, so the 3-D shapes
intersect exactly when their 2-D cross-sections do and no two z faces ever coincide (which
would be a degenerate face-on-face contact for GJK). Broad phase: an FCL
``DynamicAABBTreeCollisionManager`` holding the obstacles; narrow phase: GJK/EPA (libccd).

Semantics, unlike the kernel's: FCL's GJK decides contact with a tolerance, so shapes that
touch, or are apart or overlap by less than about 1e-6 (lengths in the part's units;
libccd's tolerances are of that order), may be reported either way, whereas the kernel
counts exact touching as valid (``psi_n >= 0``) and any overlap as penetration. Which way
depends on the GJK solver: with ``GST_INDEP`` we saw exact touching (and gaps of 1e-8)
reported as collision; with the default libccd, used here, exact touching and overlaps up to
2.2e-7 deep were reported free, and apart shapes never in collision. Compare the two only
outside a band of signed distance around zero: ``FCL_TOLERANCE_BAND`` = 1e-6, about four
times the deepest miss observed (30,000 poses within 1e-4 of contact on table3).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import fcl
import numpy as np

from feeders.scene import Scene

OBSTACLE_HALF_HEIGHT = 1.0  # z half-extent of every obstacle prism (length units)
PART_HALF_HEIGHT = 0.5  # z half-extent of the part's box: strictly inside the obstacles' slab
FCL_TOLERANCE_BAND = 1e-6  # |signed distance| below which FCL and the kernel may disagree


def _prism(polygon: np.ndarray, half_height: float) -> fcl.Convex:
    """A convex CCW polygon ``(n, 2)`` extruded to ``z in [-half_height, half_height]``.

    Faces in FCL's flat format ``[k, i_0, ..., i_{k-1}, k, ...]``, each counter-clockwise seen
    from outside: the bottom cap reversed, the top cap as given, one quad per side.
    """
    n = len(polygon)
    bottom = np.column_stack([polygon, np.full(n, -half_height)])
    top = np.column_stack([polygon, np.full(n, half_height)])
    vertices = np.vstack([bottom, top]).astype(np.float64)
    faces: list[int] = [n, *range(n - 1, -1, -1), n, *range(n, 2 * n)]
    for i in range(n):
        j = (i + 1) % n
        faces += [4, i, j, n + j, n + i]
    return fcl.Convex(vertices, n + 2, faces)


def _stop_at_first_collision(
    o1: fcl.CollisionObject, o2: fcl.CollisionObject, cdata: fcl.CollisionData
) -> bool:
    """Broad-phase callback: run the narrow phase on one candidate pair, stop at a hit."""
    if cdata.done:
        return True
    fcl.collide(o1, o2, cdata.request, cdata.result)
    cdata.done = bool(cdata.result.is_collision)
    return cdata.done


class FclScene:
    """The scene's obstacles in an FCL broad phase and the part as a box: ``penetrates(pose)``.

    Only penetration is tested (the scene's bounds on the centre of mass are not): the same
    question as :func:`validity.geometry_kernel.penetrates`, up to the tolerance described in
    the module docstring.
    """

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        body = np.asarray(scene.part.body_vertices(), dtype=np.float64)
        # The box is centred on the part's geometric centre, which sits at this offset from
        # the centre of mass (the pose's origin) in the body frame.
        self._centre = body.mean(axis=0)
        extent = body.max(axis=0) - body.min(axis=0)
        self._part = fcl.CollisionObject(
            fcl.Box(float(extent[0]), float(extent[1]), 2.0 * PART_HALF_HEIGHT)
        )
        self._obstacles: list[fcl.CollisionObject] = []
        for polygon in scene.obstacles.polygons:
            geometry = _prism(np.asarray(polygon, dtype=np.float64), OBSTACLE_HALF_HEIGHT)
            self._obstacles.append(fcl.CollisionObject(geometry, fcl.Transform()))
        for cx, cy, r in scene.obstacles.circles:
            cylinder = fcl.Cylinder(float(r), 2.0 * OBSTACLE_HALF_HEIGHT)
            where = fcl.Transform(np.array([float(cx), float(cy), 0.0]))
            self._obstacles.append(fcl.CollisionObject(cylinder, where))
        self._manager = fcl.DynamicAABBTreeCollisionManager()
        self._manager.registerObjects(self._obstacles)
        self._manager.setup()

    def _place(self, pose: Sequence[float]) -> None:
        x, y, yaw = float(pose[0]), float(pose[1]), float(pose[2])
        c, s = math.cos(yaw), math.sin(yaw)
        cx, cy = self._centre
        rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        translation = np.array([x + c * cx - s * cy, y + s * cx + c * cy, 0.0])
        self._part.setTransform(fcl.Transform(rotation, translation))

    def penetrates(self, pose: Sequence[float]) -> bool:
        """True when FCL finds the part at ``pose = (x, y, yaw)`` (centre of mass, radians)
        in collision with an obstacle; touching may count as collision (see the module)."""
        self._place(pose)
        cdata = fcl.CollisionData(fcl.CollisionRequest(), fcl.CollisionResult())
        self._manager.collide(self._part, cdata, _stop_at_first_collision)
        return bool(cdata.result.is_collision)
