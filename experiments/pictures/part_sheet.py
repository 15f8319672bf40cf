"""A part's sheet (issue 39, ``partfeeder part --out``): the part with its centre of mass,
convex hull and stable resting faces numbered; the part resting on each of those faces; and,
given a family, its orientation classes drawn on the part.

A class is drawn as the way gravity points in the part when the part is at the class's
centre yaw ``c``: the body direction ``(-sin c, -cos c)`` (the world's ``(0, -1)`` turned
back by ``c``), an arrow from the centre of mass with the class's name, and its window
(``+- tolerance``) as a faint wedge.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Wedge

from experiments.pictures.scenes import draw_part, save_figure
from feeders.part_properties import MassProperties
from feeders.part_shape import Part, part_geometry
from feeders.scene import OrientationClass, orientation_of

FACE = "#1f77b4"
COLUMNS = 3
CLASS_COLOURS = ("#2ca02c", "#d62728", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf")


def down_in_part(yaw: float) -> np.ndarray:
    """The body-frame direction of gravity (world ``(0, -1)``) when the part is at ``yaw``."""
    return np.array([-math.sin(yaw), -math.cos(yaw)])


def _part_panel(
    ax: plt.Axes, part: Part, props: MassProperties, classes: Sequence[OrientationClass]
) -> None:
    com = props.com
    draw_part(ax, part, (com[0], com[1], 0.0))
    hull = np.vstack([props.hull, props.hull[:1]])
    ax.plot(hull[:, 0], hull[:, 1], "--", color="0.5", lw=0.8, label="convex hull")
    size = max(props.extent[1] - props.extent[0], props.extent[3] - props.extent[2])
    for k, pose in enumerate(props.resting):
        face = pose.face
        ax.plot(face[:, 0], face[:, 1], color=FACE, lw=3, solid_capstyle="butt", zorder=6)
        outward = down_in_part(pose.yaw)  # resting on the face, gravity points out through it
        label = face.mean(axis=0) + 0.08 * size * outward
        ax.text(
            float(label[0]),
            float(label[1]),
            str(k + 1),
            color=FACE,
            ha="center",
            va="center",
            fontsize=10,
            zorder=6,
        )
    ax.plot(*com, "+", color="k", ms=12, mew=1.5, zorder=7)
    shown = [0.0 if abs(v) < 1e-12 * size else v for v in com]  # float noise (1e-17) as 0
    ax.annotate(
        f"centre of mass\n({shown[0]:.4g}, {shown[1]:.4g})",
        (float(com[0]), float(com[1])),
        xytext=(8, 8),
        textcoords="offset points",
        fontsize=7,
        zorder=7,
    )
    for n, cls in enumerate(classes):
        colour = CLASS_COLOURS[n % len(CLASS_COLOURS)]
        for centre in cls.centres:
            down = down_in_part(centre)
            tip = com + 0.75 * size * down
            heading = math.degrees(math.atan2(down[1], down[0]))
            tol = math.degrees(cls.tolerance)
            ax.add_patch(
                Wedge(
                    (float(com[0]), float(com[1])),
                    0.75 * size,
                    heading - tol,
                    heading + tol,
                    fc=colour,
                    alpha=0.08,
                    lw=0,
                )
            )
            ax.annotate(
                "",
                (float(tip[0]), float(tip[1])),
                (float(com[0]), float(com[1])),
                arrowprops={"arrowstyle": "->", "color": colour, "lw": 1.2},
                zorder=6,
            )
            ax.text(
                float(tip[0]),
                float(tip[1]),
                f"{cls.name}: down",
                color=colour,
                fontsize=7,
                ha="center",
                zorder=6,
            )
    ax.set_title("the part (faces it rests on, numbered)" if not classes else
                 "the part; arrows: down, per orientation class", fontsize=9)  # fmt: skip
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.margins(0.25)


def _resting_panel(
    ax: plt.Axes, part: Part, number: int, yaw: float, classes: Sequence[OrientationClass]
) -> None:
    lowest = float(np.asarray(part_geometry(part, (0.0, 0.0, yaw)).bounds)[1])
    draw_part(ax, part, (0.0, -lowest, yaw))
    reach = float(part_geometry(part, (0.0, 0.0, yaw)).bounds[2]) + 0.3
    ax.plot([-reach, reach], [0.0, 0.0], color="0.3", lw=2)
    ax.plot([0.0, 0.0], [0.0, -lowest], ":", color="k", lw=0.8)  # the centre of mass, above
    title = f"on face {number}: yaw {math.degrees(yaw):.4g} deg"
    if classes:
        title += f"\nclass: {orientation_of(tuple(classes), yaw)}"
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.margins(0.2)


def part_sheet(
    part: Part,
    props: MassProperties,
    title: str,
    path: str | Path,
    classes: Sequence[OrientationClass] = (),
) -> Path:
    """Write the sheet of ``part`` (with ``props``, its :func:`mass_properties`) at ``path``;
    ``classes``: a family's orientation classes, drawn on the part and naming each pose."""
    panels = 1 + len(props.resting)
    rows = math.ceil(panels / COLUMNS)
    fig, axes = plt.subplots(rows, COLUMNS, figsize=(4.0 * COLUMNS, 3.8 * rows), squeeze=False)
    flat = list(axes.flat)
    _part_panel(flat[0], part, props, classes)
    for k, pose in enumerate(props.resting):
        _resting_panel(flat[k + 1], part, k + 1, pose.yaw, classes)
    for ax in flat[panels:]:
        ax.axis("off")
    fig.suptitle(
        f"{title}: mass {props.mass:.4g}, area {props.area:.4g}, inertia {props.inertia:.4g}",
        fontsize=10,
    )
    return save_figure(fig, path)
