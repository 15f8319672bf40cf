"""A scene as the flat arrays the kernels take (shapes and units checked once, here)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from feeders.scene import Scene
from validity.geometry_kernel import clearance_at_pose, polygon_aabbs
from validity.solid_surface import split_at_cover


@dataclass(frozen=True)
class SceneArrays:
    """``body (4, 2)`` part corners in the body frame (centre of mass at the origin);
    ``verts (P, K, 2)``, ``counts (P,)``, ``aabbs (P, 4)`` static convex polygons, their
    edges split where another piece starts or stops covering them
    (:func:`validity.solid_surface.split_at_cover`);
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
        circles = np.ascontiguousarray(circles, dtype=np.float64).reshape(-1, 3)
        solid = split_at_cover(verts, counts, circles)
        return cls(
            body=np.ascontiguousarray(scene.part.body_vertices(), dtype=np.float64),
            verts=solid.verts,
            counts=solid.counts,
            aabbs=polygon_aabbs(solid.verts, solid.counts),
            circles=circles,
            bounds=np.asarray(scene.bounds, dtype=np.float64),
            surface=solid.surface,
            corners=solid.corners,
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
