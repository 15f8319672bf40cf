"""A part's mass properties and resting poses in one record (issue 39: ``partfeeder part``).

Nothing is computed here that :mod:`feeders.composite_part` does not compute already: mass,
area, centre of mass and inertia are :class:`~feeders.composite_part.CompositePart`'s closed
forms, the resting poses its :func:`~feeders.composite_part.stable_poses` (an edge of the
convex hull on a horizontal floor, gravity -y, is stable when the centre of mass projects
strictly inside it). The peg is taken as its two halves
(:meth:`CompositePart.from_peg`, its geometric centre at the origin of its part frame). What
this adds is the frame a user wrote the part in: faces in the part frame, the order in which
the resting poses are numbered (by yaw), and the part's extent about its centre of mass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from feeders.composite_part import CompositePart, stable_poses
from feeders.part import Peg
from feeders.part_shape import Part, part_geometry


@dataclass(frozen=True)
class RestingPose:
    """The part resting on a horizontal floor: ``yaw`` (rad, in [-pi, pi)) places its body
    frame; ``face`` (``(2, 2)``, part frame) is the segment of its convex hull on the floor,
    listed counter-clockwise along the hull (the part on its left), one point twice for a
    disc's arc. ``on_outline``: the face is a side of the part itself, not a hull edge that
    bridges a hollow (the cup's rim, an L's diagonal)."""

    yaw: float
    face: np.ndarray
    on_outline: bool


@dataclass(frozen=True)
class MassProperties:
    """``mass``; ``area`` (length^2); ``com`` (part frame); ``inertia`` about the centre of
    mass (mass x length^2); ``extent`` (x_min, x_max, y_min, y_max of the part about its
    centre of mass, body frame axes); ``hull`` (part frame, CCW); ``resting`` (the stable
    resting poses, by yaw)."""

    mass: float
    area: float
    com: np.ndarray
    inertia: float
    extent: tuple[float, float, float, float]
    hull: np.ndarray
    resting: tuple[RestingPose, ...]

    def as_dict(self) -> dict[str, Any]:
        """Plain data (floats and lists) for JSON."""
        return {
            "mass": self.mass,
            "area": self.area,
            "centre_of_mass": [float(v) for v in self.com],
            "inertia": self.inertia,
            "extent": dict(zip(("x_min", "x_max", "y_min", "y_max"), self.extent, strict=True)),
            "stable_poses": [
                {
                    "face_number": k + 1,
                    "yaw": pose.yaw,
                    "yaw_degrees": math.degrees(pose.yaw),
                    "face": pose.face.tolist(),
                    "on_outline": pose.on_outline,
                }
                for k, pose in enumerate(self.resting)
            ],
        }


def as_composite(part: Part) -> CompositePart:
    """``part`` as pieces: a composite part itself, the peg as its two halves."""
    return CompositePart.from_peg(part) if isinstance(part, Peg) else part


def mass_properties(part: Part) -> MassProperties:
    """Mass, area, centre of mass, inertia, extent, hull and stable resting poses of ``part``."""
    pieces = as_composite(part)
    hull = pieces.convex_hull()
    points = np.vstack(pieces.body_polygons()) if pieces.polygons else np.zeros((0, 2))
    discs = pieces.body_discs()
    low = np.vstack([points, discs[:, :2] - discs[:, 2:]]).min(axis=0)  # exact for discs too,
    high = np.vstack([points, discs[:, :2] + discs[:, 2:]]).max(axis=0)  # unlike the hull
    extent = (float(low[0]), float(high[0]), float(low[1]), float(high[1]))
    outline = part_geometry(pieces).boundary  # body frame
    tol = 1e-9 * pieces.bounding_radius()
    resting = tuple(
        RestingPose(pose.yaw, pose.face + pieces.com, _on_outline(outline, pose.face, tol))
        for pose in stable_poses(pieces)
    )
    return MassProperties(
        mass=pieces.mass,
        area=pieces.area,
        com=pieces.com.copy(),
        inertia=pieces.inertia,
        extent=extent,
        hull=hull + pieces.com,
        resting=resting,
    )


def _on_outline(outline: shapely.Geometry, face: np.ndarray, tol: float) -> bool:
    """Whether ``face`` (body frame) is a side of the part: its midpoint on the part's boundary,
    or a point (a disc's arc, on the part by construction)."""
    if np.allclose(face[0], face[1]):
        return True
    return float(outline.distance(shapely.Point(face.mean(axis=0)))) <= tol
