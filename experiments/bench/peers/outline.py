"""The solid's outline as seen from the free space the part moves in: chains of segments.

A feeder's walls are convex pieces mitred where the solid has a convex corner (the lip, the
exit mouth): neighbouring pieces meet along internal faces. An engine that collides the part
with each piece on its own sees those faces, and at a seam it can return a normal that belongs
to no face of the solid (a "ghost" normal: Box2D's "Ghost Collisions" note, 2020; Chipmunk's
segment neighbours are its fix). Colliding with the outline of the union of the pieces instead
leaves no internal face to catch on.

The union of the pieces may touch itself only at a vertex (where the interior turns left, the
walls part on the outside), so it is not one polygon. The outline is therefore taken from the
free side: the region of a box around the solid minus the union of the polygon pieces, the
component of it that holds the part's start; its rings (outer boundary and any islands) are
the chains (the box's own ring, which an open scene's free region reaches, is not a wall and
is left out). Discs are not part of the chains (an engine takes them as exact circles); a polygon
face hidden inside a disc (the protuberance finger's end, on the tip disc's diameter) stays in
the chain, where the part cannot reach it without touching the disc first.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import shapely
from shapely.geometry import Point, Polygon, box

from feeders.scene import Scene

MARGIN = 1.0  # the free box's overhang around the solid (length)


def outline_chains(
    scene: Scene, inside: Sequence[float] | None = None, offset: float = 0.0
) -> list[np.ndarray]:
    """Closed chains (each (n, 2), first vertex not repeated, collinear vertices removed) of
    the solid's polygon pieces around the free region holding ``inside`` (x, y; default the
    first start pose). ValueError when ``inside`` lies in the solid.

    ``offset`` > 0 moves every face that far into the solid (mitred joins), for segments of
    that radius: their surface is then the solid's faces exactly, its convex corners rounded
    by ``offset`` (length)."""
    polygons = [Polygon(p) for p in scene.obstacles.polygons]
    if not polygons:
        return []
    solid = shapely.unary_union(polygons)
    x0, y0, x1, y1 = solid.bounds
    free = box(x0 - MARGIN, y0 - MARGIN, x1 + MARGIN, y1 + MARGIN).difference(solid)
    if inside is None:
        inside = next(iter(scene.starts.values()))[:2]
    point = Point(float(inside[0]), float(inside[1]))
    parts = list(getattr(free, "geoms", [free]))
    holding = [g for g in parts if g.contains(point)]
    if not holding:
        raise ValueError(f"the point {tuple(inside)} is not in the free space of {scene.name}")
    region = holding[0]
    if offset > 0.0:
        region = region.buffer(offset, join_style="mitre", mitre_limit=100.0)
    region = shapely.simplify(region, 0.0)  # drops collinear vertices, keeps the shape
    bx0, by0, bx1, by1 = free.bounds
    outer = (bx0 - offset, by0 - offset, bx1 + offset, by1 + offset)
    chains = []
    for ring in [region.exterior, *region.interiors]:
        coords = np.asarray(ring.coords)[:-1]
        if len(coords) >= 3 and not _on_box(coords, outer):
            chains.append(coords)
    return chains


def _on_box(coords: np.ndarray, bounds: tuple[float, float, float, float]) -> bool:
    """True for the free box's own outer ring (an open scene's free region reaches it): not a
    face of the solid, so not a wall."""
    x0, y0, x1, y1 = bounds
    return bool(
        np.any(np.isclose(coords[:, 0], x0) | np.isclose(coords[:, 0], x1))
        or np.any(np.isclose(coords[:, 1], y0) | np.isclose(coords[:, 1], y1))
    )


def chain_segments(
    chain: np.ndarray,
) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Each edge of a closed chain as (previous vertex, start, end, next vertex): the edge and
    its neighbours' far ends (for engines that drop contacts outside an edge's voronoi region,
    e.g. Chipmunk's ``Segment.set_neighbors``)."""
    n = len(chain)
    return [
        (chain[(i - 1) % n], chain[i], chain[(i + 1) % n], chain[(i + 2) % n]) for i in range(n)
    ]
