"""Seeded poses for cross-checking collision tests: uniform ones and ones grazing obstacles.

Shared by the tests (kernel vs shapely, kernel vs FCL) and the benchmarks, so both look at
the same kind of poses: uniform poses rarely touch anything, contact poses test the band where
implementations disagree.
"""

from __future__ import annotations

import math

import numpy as np

from feeders.scene import Scene


def _contact_pose(
    anchor: np.ndarray, normal: np.ndarray, body: np.ndarray, rng: np.random.Generator
) -> tuple[float, float, float]:
    """A pose of the part close to the obstacle boundary at ``anchor`` (outward unit ``normal``).

    A random edge of the part faces the obstacle's edge (tilted by a small random angle half
    the time), a random point of it at the anchor; then the part moves along the normal until
    its lowest corner is a signed gap away from the obstacle edge's line, the gap's size
    log-uniform in [1e-11, 1e-1] and its sign random.
    """
    edge = int(rng.integers(0, len(body)))
    a, b = body[edge], body[(edge + 1) % len(body)]
    e = b - a
    m = np.array([e[1], -e[0]]) / math.hypot(e[0], e[1])  # the part edge's outward normal
    yaw = math.atan2(-normal[1], -normal[0]) - math.atan2(m[1], m[0])  # m turned onto -normal
    if rng.uniform() < 0.5:
        yaw += rng.normal(0.0, 0.05)
    yaw = (yaw + math.pi) % (2.0 * math.pi) - math.pi
    c, s = math.cos(yaw), math.sin(yaw)
    rotation = np.array([[c, -s], [s, c]])
    p = a + rng.uniform(0.0, 1.0) * e  # the part point put on the anchor
    com = anchor - rotation @ p
    lowest = float(np.min((body @ rotation.T + com - anchor) @ normal))
    gap = rng.choice((-1.0, 1.0)) * 10.0 ** rng.uniform(-11.0, -1.0)
    com = com + (gap - lowest) * normal
    return float(com[0]), float(com[1]), yaw


def cross_check_poses(
    scene: Scene, n: int, rng: np.random.Generator | int, near_fraction: float = 0.5
) -> np.ndarray:
    """``n`` seeded poses ``(x, y, yaw)`` (shape ``(n, 3)``) for cross-checking collision tests.

    ``1 - near_fraction`` of them uniform: centre of mass over ``scene.bounds``, yaw in
    ``[-pi, pi)``. The rest are contact poses (see :func:`_contact_pose`) at a point uniform
    on the boundary of a random obstacle, so touching, grazing (gaps down to 1e-11) and shallow
    penetration are common; their centre of mass may lie outside the bounds. Pass a seed or
    a Generator.
    """
    if n < 0 or not 0.0 <= near_fraction <= 1.0:
        raise ValueError(f"need n >= 0 (got {n}) and near_fraction in [0, 1] (got {near_fraction})")
    rng = np.random.default_rng(rng)
    x0, x1, y0, y1 = scene.bounds
    n_near = round(n * near_fraction)
    n_uniform = n - n_near
    poses = np.empty((n, 3))
    poses[:n_uniform, 0] = rng.uniform(x0, x1, n_uniform)
    poses[:n_uniform, 1] = rng.uniform(y0, y1, n_uniform)
    poses[:n_uniform, 2] = rng.uniform(-math.pi, math.pi, n_uniform)
    polygons = [np.asarray(p, dtype=np.float64) for p in scene.obstacles.polygons]
    circles = scene.obstacles.circles
    n_shapes = len(polygons) + len(circles)
    if n_near and n_shapes == 0:
        raise ValueError("cannot sample poses near obstacles: the scene has none")
    body = np.asarray(scene.part.body_vertices(), dtype=np.float64)
    for k in range(n_uniform, n):
        i = int(rng.integers(0, n_shapes))
        if i < len(polygons):
            p = polygons[i]
            e = np.roll(p, -1, axis=0) - p
            lengths = np.hypot(e[:, 0], e[:, 1])
            edge = int(rng.choice(len(p), p=lengths / lengths.sum()))  # uniform on the boundary
            anchor = p[edge] + rng.uniform(0.0, 1.0) * e[edge]
            normal = np.array([e[edge, 1], -e[edge, 0]]) / lengths[edge]
        else:
            cx, cy, r = circles[i - len(polygons)]
            angle = rng.uniform(-math.pi, math.pi)
            normal = np.array([math.cos(angle), math.sin(angle)])
            anchor = np.array([cx, cy]) + r * normal
        poses[k] = _contact_pose(anchor, normal, body, rng)
    return poses
