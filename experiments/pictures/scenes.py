"""Pictures: the feeder, the part, planner trees and paths (as the paper's Figs. 4-9).

Functions draw onto a matplotlib ``Axes`` and take plain data (a scene, a PlanResult), so they
serve the CLI, the docs and notebooks alike. The Agg backend is used: no display needed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.patches import Circle, Polygon, Rectangle

from feeders.part import Peg
from feeders.part_shape import Part, part_geometry
from feeders.scene import Scene
from planners.plan import PlanResult

WALL = "#8c8c8c"
HEAVY = "#c0392b"
LIGHT = "#f5cba7"
ORIENTATION_COLOURS = {"heavy_leading": "#1f77b4", "heavy_trailing": "#9467bd"}


def save_figure(fig: plt.Figure, path: str | Path, dpi: int = 100) -> Path:
    """Lay out, write as PNG at ``path`` and close ``fig``; returns the path."""
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def part_outline(part: Peg, pose: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """World corners of the part's light half and heavy half at ``pose`` (each (4, 2))."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rot = np.array([[c, s], [-s, c]])
    v = part.body_vertices()
    mid_x = v[0, 0] + part.length / 2
    light = np.array([v[0], [mid_x, v[1, 1]], [mid_x, v[2, 1]], v[3]])
    heavy = np.array([[mid_x, v[1, 1]], v[1], v[2], [mid_x, v[2, 1]]])
    return light @ rot + pose[:2], heavy @ rot + pose[:2]


def draw_part(
    ax: plt.Axes, part: Part, pose: Sequence[float], alpha: float = 1.0, edge: str = "k"
) -> None:
    """The part with its centre of mass as a dot: the peg with its heavy half dark, a
    composite part as its outline, its densest pieces dark when its densities differ (the
    cup, of one density, is one dark U: its shape shows which way it points)."""
    if isinstance(part, Peg):
        light, heavy = part_outline(part, pose)
        ax.add_patch(Polygon(light, closed=True, fc=LIGHT, ec=edge, lw=0.6, alpha=alpha, zorder=4))
        ax.add_patch(Polygon(heavy, closed=True, fc=HEAVY, ec=edge, lw=0.6, alpha=alpha, zorder=4))
    else:
        densities = part.polygon_densities + part.disc_densities
        if max(densities) > min(densities):
            dense = max(densities)
            for k, piece in enumerate(part.body_polygons()):
                fill = HEAVY if part.polygon_densities[k] == dense else LIGHT
                c, s = math.cos(pose[2]), math.sin(pose[2])
                world = piece @ np.array([[c, s], [-s, c]]) + np.asarray(pose[:2])
                ax.add_patch(Polygon(world, closed=True, fc=fill, lw=0, alpha=alpha, zorder=4))
        whole = part_geometry(part, pose)
        for ring in getattr(whole, "geoms", [whole]):
            fill = "none" if max(densities) > min(densities) else HEAVY
            outline = np.asarray(ring.exterior.coords)
            ax.add_patch(
                Polygon(outline, closed=True, fc=fill, ec=edge, lw=0.6, alpha=alpha, zorder=4)
            )
    ax.plot(pose[0], pose[1], "o", ms=2.5, color="k", alpha=alpha, zorder=5)


def draw_scene(ax: plt.Axes, scene: Scene, starts: bool = True, goal: bool = True) -> None:
    """Obstacles (grey), the goal region (green) and optionally the start poses."""
    for poly in scene.obstacles.polygons:
        ax.add_patch(Polygon(poly, closed=True, fc=WALL, ec=WALL, lw=0.5, zorder=2))
    for cx, cy, r in scene.obstacles.circles:
        ax.add_patch(Circle((cx, cy), r, fc=WALL, ec=WALL, zorder=2))
    if scene.outline is not None:
        ring = np.vstack([scene.outline, scene.outline[:1]])
        ax.plot(ring[:, 0], ring[:, 1], color="k", lw=0.8, zorder=3)
    if goal:
        g = scene.goal
        ax.add_patch(
            Rectangle(
                (g.x_min, g.y_min),
                g.x_max - g.x_min,
                g.y_max - g.y_min,
                fc="#2ca02c",
                alpha=0.25,
                ec="#2ca02c",
                zorder=1,
            )
        )
    if starts:
        for pose in scene.starts.values():
            draw_part(ax, scene.part, pose, alpha=0.5)
    x0, x1, y0, y1 = scene.bounds
    pad = 0.6
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal")


def draw_tree(ax: plt.Axes, result: PlanResult, colour: str = "#555555") -> None:
    """The planner's tree: centre-of-mass positions joined parent to child (thin lines)."""
    if len(result.tree_edges) == 0:
        return
    xy = result.tree_vertices[:, :2]
    segments = np.stack([xy[result.tree_edges[:, 0]], xy[result.tree_edges[:, 1]]], axis=1)
    ax.add_collection(
        LineCollection(list(segments), colors=colour, linewidths=0.3, alpha=0.5, zorder=3)
    )


def draw_path(
    ax: plt.Axes, result: PlanResult, part: Part, colour: str = "#1f77b4", snapshots: int = 6
) -> None:
    """The centre-of-mass path (thick) and a few poses of the part along it."""
    path = result.fine_path
    if len(path) == 0:
        return
    ax.plot(path[:, 0], path[:, 1], color=colour, lw=2.2, zorder=6)
    for i in np.linspace(0, len(path) - 1, snapshots).round().astype(int):
        draw_part(ax, part, path[i], alpha=0.55)


def plan_figure(scene: Scene, results: Sequence[PlanResult], path: str | Path) -> Path:
    """One panel per result (tree thin, path thick, as Fig. 4), saved as PNG at ``path``."""
    n = max(1, len(results))
    fig, axes = plt.subplots(1, n, figsize=(5.2 * n, 6.4), squeeze=False)
    for ax, res in zip(axes[0], results, strict=False):
        draw_scene(ax, scene, starts=False)
        draw_tree(ax, res)
        draw_path(ax, res, scene.part, ORIENTATION_COLOURS.get(res.orientation, "#1f77b4"))
        if len(res.path) == 0:
            draw_part(ax, scene.part, scene.start(res.orientation), alpha=0.8)
        verdict = "solved" if res.solved else "not solved"
        ax.set_title(
            f"{res.orientation.replace('_', ' ')}: {verdict}\n"
            f"{res.level}, {res.planner}, {res.time:.2f} s, {res.tree_size} states",
            fontsize=9,
        )
    fig.suptitle(f"{scene.name}", fontsize=11)
    return save_figure(fig, path, dpi=110)


def scene_figure(scenes: Sequence[Scene], titles: Sequence[str], path: str | Path) -> Path:
    """Scenes side by side with their start poses and goal region, saved as PNG."""
    n = len(scenes)
    cols = min(n, 4)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 5.2 * rows), squeeze=False)
    for ax in axes.ravel()[n:]:
        ax.axis("off")
    for ax, scene, title in zip(axes.ravel(), scenes, titles, strict=False):
        draw_scene(ax, scene)
        ax.set_title(title, fontsize=9)
    return save_figure(fig, path)
