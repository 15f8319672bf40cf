"""A scene as the flat arrays the kernels take (shapes and units checked once, here)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from feeders.scene import Scene
from validity.contact_kernel import corner_vertices, surface_edges
from validity.geometry_kernel import clearance_at_pose, polygon_aabbs


@dataclass(frozen=True)
class SceneArrays:
    """``body (4, 2)`` part corners in the body frame (centre of mass at the origin);
    ``verts (P, K, 2)``, ``counts (P,)``, ``aabbs (P, 4)`` static convex polygons;
    ``circles (C, 3)`` static discs; ``bounds (4,)`` = x_min, x_max, y_min, y_max of the
    centre of mass; ``surface (P, K)`` True for polygon edges that are real surfaces, False
    for seams between pieces of one solid; ``corners (P, K)`` True for polygon vertices that
    are convex corners of the solid."""

    body: np.ndarray
    verts: np.ndarray
    counts: np.ndarray
    aabbs: np.ndarray
    circles: np.ndarray
    bounds: np.ndarray
    surface: np.ndarray
    corners: np.ndarray

    @classmethod
    def from_scene(cls, scene: Scene) -> SceneArrays:
        verts, counts, circles = scene.obstacles.packed()
        if verts.shape[0] == 0:  # numba needs a typed, non-ragged array even when empty
            verts = np.zeros((0, 3, 2))
        return cls(
            body=np.ascontiguousarray(scene.part.body_vertices(), dtype=np.float64),
            verts=np.ascontiguousarray(verts, dtype=np.float64),
            counts=np.ascontiguousarray(counts, dtype=np.int64),
            aabbs=polygon_aabbs(np.ascontiguousarray(verts), counts),
            circles=np.ascontiguousarray(circles, dtype=np.float64).reshape(-1, 3),
            bounds=np.asarray(scene.bounds, dtype=np.float64),
            surface=surface_edges(np.ascontiguousarray(verts), np.asarray(counts, dtype=np.int64)),
            corners=corner_vertices(
                np.ascontiguousarray(verts), np.asarray(counts, dtype=np.int64)
            ),
        )

    @cached_property
    def contact_scene(
        self,
    ) -> tuple[
        np.ndarray,
        np.ndarray,
        np.ndarray,
        np.ndarray,
        np.ndarray,
        np.ndarray,
        np.ndarray,
        np.ndarray,
    ]:
        """``(body, verts, counts, aabbs, circles, surface, corners, bounds)``: the scene as
        the contact levels' time-stepping kernels take it, in that order."""
        return (
            self.body,
            self.verts,
            self.counts,
            self.aabbs,
            self.circles,
            self.surface,
            self.corners,
            self.bounds,
        )

    def clearance(self, x: float, y: float, yaw: float, stop_below: float = -np.inf) -> float:
        """Smallest signed distance (length) from the part at pose ``(x, y, yaw)`` to the
        obstacles (negative: penetration depth); it may stop at the first value below
        ``stop_below`` (``-inf``: the exact minimum)."""
        return float(
            clearance_at_pose(
                self.body, x, y, yaw, self.verts, self.counts, self.aabbs, self.circles, stop_below
            )
        )

    def moving_state_is_valid(
        self, state: Sequence[float], velocity_limit: float, penetration_tolerance: float
    ) -> bool:
        """A pose-and-velocity state ``(x, y, yaw, vx, vy, omega)`` is valid when the centre of
        mass is within the bounds, no speed exceeds ``velocity_limit`` and the part overlaps
        no obstacle deeper than ``penetration_tolerance`` (length; 0: psi_n >= 0 exactly)."""
        b = self.bounds
        if not (b[0] <= state[0] <= b[1] and b[2] <= state[1] <= b[3]):
            return False
        if max(abs(state[3]), abs(state[4]), abs(state[5])) > velocity_limit:
            return False
        floor = -penetration_tolerance
        return self.clearance(state[0], state[1], state[2], stop_below=floor) >= floor
