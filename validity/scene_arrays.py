"""A scene as the flat arrays the kernels take (shapes and units checked once, here)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from feeders.part_shape import Part, body_pieces
from feeders.scene import Scene
from feeders.shapes import Obstacles
from validity.geometry_kernel import part_clearance_at_pose, polygon_aabbs
from validity.solid_surface import split_at_cover


@dataclass(frozen=True)
class PartArrays:
    """The part as the kernels take it, in the body frame (origin at the centre of mass):
    convex pieces ``body (Q, K, 2)`` with ``counts (Q,)`` vertices (padding repeats the last),
    their edges split where another piece of the part covers them, ``surface (Q, K)`` False
    for the seams between pieces, ``corners (Q, K)`` False for vertices that are no corner of
    the part's outline (flat joints, concave corners where cover begins, points between
    seams), and discs ``discs (D, 3)`` (cx, cy, radius). The peg is one rectangle."""

    body: np.ndarray
    counts: np.ndarray
    surface: np.ndarray
    corners: np.ndarray
    discs: np.ndarray

    @classmethod
    def from_part(cls, part: Part) -> PartArrays:
        polygons, discs = body_pieces(part)
        verts, counts, circles = Obstacles(tuple(polygons), discs).packed()
        circles = np.ascontiguousarray(circles, dtype=np.float64).reshape(-1, 3)
        solid = split_at_cover(verts, counts, circles)
        corners = solid.corners.copy()
        for q, n in enumerate(solid.counts):  # a vertex between two seams is inside the part
            for k in range(n):
                corners[q, k] &= bool(solid.surface[q, k] or solid.surface[q, (k - 1) % n])
        return cls(solid.verts, solid.counts, solid.surface, corners, circles)


@dataclass(frozen=True)
class SceneArrays:
    """``part``: the part's pieces in the body frame (:class:`PartArrays`);
    ``verts (P, K, 2)``, ``counts (P,)``, ``aabbs (P, 4)`` static convex polygons, their
    edges split where another piece starts or stops covering them
    (:func:`validity.solid_surface.split_at_cover`);
    ``circles (C, 3)`` static discs; ``bounds (4,)`` = x_min, x_max, y_min, y_max of the
    centre of mass; ``surface (P, K)`` True for polygon edges that are real surfaces, False
    for seams between pieces of one solid; ``corners (P, K)`` True for polygon vertices that
    are convex corners of the solid."""

    part: PartArrays
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
            part=PartArrays.from_part(scene.part),
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
        np.ndarray,
        np.ndarray,
        np.ndarray,
        np.ndarray,
    ]:
        """``(body, body_counts, body_surface, body_corners, body_discs, verts, counts, aabbs,
        circles, surface, corners, bounds)``: the part and the scene as the contact levels'
        time-stepping kernels take them, in that order."""
        p = self.part
        return (
            p.body,
            p.counts,
            p.surface,
            p.corners,
            p.discs,
            self.verts,
            self.counts,
            self.aabbs,
            self.circles,
            self.surface,
            self.corners,
            self.bounds,
        )

    @cached_property
    def pose_scene(
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
        """``(body, body_counts, body_discs, verts, counts, aabbs, circles, bounds)``: the part
        and the scene as the geometric level's pose kernels take them, in that order."""
        p = self.part
        return (
            p.body,
            p.counts,
            p.discs,
            self.verts,
            self.counts,
            self.aabbs,
            self.circles,
            self.bounds,
        )

    def clearance(self, x: float, y: float, yaw: float, stop_below: float = -np.inf) -> float:
        """Smallest signed distance (length) from the part at pose ``(x, y, yaw)`` to the
        obstacles (negative: penetration depth); it may stop at the first value below
        ``stop_below`` (``-inf``: the exact minimum)."""
        return float(
            part_clearance_at_pose(
                self.part.body,
                self.part.counts,
                self.part.discs,
                x,
                y,
                yaw,
                self.verts,
                self.counts,
                self.aabbs,
                self.circles,
                stop_below,
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
