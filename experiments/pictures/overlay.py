"""Two feeders drawn over each other: a design filled, a baseline as an outline.

What a designer compares at a glance: where the recommended feeder's walls, chutes and pin
differ from the baseline's (the paper's table3). Both are drawn in the same world frame and
scale (the feeder's length unit), each feeder as its free interior (``Scene.outline``) and
its pin (the circles of its obstacles). A device family's device has no such outline (issue
24): it is drawn by its pieces, the design's filled and the baseline's dashed.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Patch, Polygon

from experiments.pictures.scenes import save_figure
from feeders.scene import Scene

DESIGN_COLOUR = "#1f77b4"
BASELINE_COLOUR = "#222222"


def overlay_figure(
    design: Scene, baseline: Scene, labels: tuple[str, str], path: str | Path
) -> Path:
    """``design`` filled (blue) and ``baseline`` as a dashed black outline on one axes,
    labelled ``labels = (design label, baseline label)`` in the legend and title; saved as PNG
    about 900 px wide."""
    fig, ax = plt.subplots(figsize=(9.0, 6.5))
    _interior(ax, design, fill=True)
    _interior(ax, baseline, fill=False)
    points = [_points(s) for s in (design, baseline)]
    points = [p for p in points if len(p)]
    if points:
        xy = np.vstack(points)
        pad = 0.05 * float(np.ptp(xy, axis=0).max())
        ax.set_xlim(xy[:, 0].min() - pad, xy[:, 0].max() + pad)
        ax.set_ylim(xy[:, 1].min() - pad, xy[:, 1].max() + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (length unit of the design)", fontsize=10)
    ax.set_ylabel("y", fontsize=10)
    ax.tick_params(labelsize=9)
    ax.grid(True, color="#eeeeee", zorder=0)
    ax.legend(
        handles=[
            Patch(fc=DESIGN_COLOUR, alpha=0.35, ec=DESIGN_COLOUR, label=f"{labels[0]} (filled)"),
            Line2D([], [], color=BASELINE_COLOUR, ls="--", lw=1.6, label=f"{labels[1]} (outline)"),
        ],
        fontsize=10,
        loc="upper left",
        bbox_to_anchor=(1.02, 1.0),
        title="pin: the circle",
        title_fontsize=9,
    )
    drawn = (
        "the free interior of each feeder"
        if design.outline is not None
        else "the pieces of each device"
    )
    ax.set_title(f"{labels[0]} over {labels[1]}: {drawn}", fontsize=11)
    return save_figure(fig, path, dpi=100)


def _points(scene: Scene) -> np.ndarray:
    """The points the drawing must hold: the outline, else every piece's vertices and the
    pins' extents (n, 2; possibly none)."""
    if scene.outline is not None:
        return np.asarray(scene.outline, dtype=float)
    points = [np.asarray(p, dtype=float) for p in scene.obstacles.polygons]
    points += [
        np.array([[cx - r, cy - r], [cx + r, cy + r]]) for cx, cy, r in scene.obstacles.circles
    ]
    return np.vstack(points) if points else np.empty((0, 2))


def _pieces(ax: plt.Axes, scene: Scene, fill: bool) -> None:
    """A device without an outline (a family's): its polygon pieces, filled or dashed."""
    for poly in scene.obstacles.polygons:
        if fill:
            ax.add_patch(
                Polygon(poly, closed=True, fc=DESIGN_COLOUR, alpha=0.35, ec=DESIGN_COLOUR, zorder=2)
            )
        else:
            ax.add_patch(
                Polygon(
                    poly, closed=True, fill=False, ec=BASELINE_COLOUR, ls="--", lw=1.2, zorder=4
                )
            )


def _interior(ax: plt.Axes, scene: Scene, fill: bool) -> None:
    """The feeder's free interior (a family's device: its pieces) and its pins, filled or as
    a dashed outline."""
    if scene.outline is None:
        _pieces(ax, scene, fill)
    else:
        if fill:
            ax.add_patch(
                Polygon(
                    scene.outline, closed=True, fc=DESIGN_COLOUR, alpha=0.35, ec="none", zorder=2
                )
            )
            ax.add_patch(
                Polygon(scene.outline, closed=True, fill=False, ec=DESIGN_COLOUR, lw=1.4, zorder=3)
            )
        else:
            ax.add_patch(
                Polygon(
                    scene.outline,
                    closed=True,
                    fill=False,
                    ec=BASELINE_COLOUR,
                    ls="--",
                    lw=1.6,
                    zorder=4,
                )
            )
    for cx, cy, r in scene.obstacles.circles:
        colour = DESIGN_COLOUR if fill else BASELINE_COLOUR
        ax.add_patch(
            Circle(
                (cx, cy),
                r,
                fc=colour if fill else "none",
                ec=colour,
                ls="-" if fill else "--",
                lw=1.4,
                zorder=5,
            )
        )
