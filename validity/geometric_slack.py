"""The slack that makes the geometric level (Eq. 9) a relaxation of the verdict's drops (issue 21).

A drop the verdict counts runs in a feeder *made* to tolerance and in the dynamic model, which
rests and slides with small overlaps. For every pose of such a drop to be valid at the
geometric level of the *nominal* design, each nominal obstacle must grant, as penetration
depth, two parts:

* ``contact``: the overlap the dynamic model leaves between part and wall while resting or
  sliding (measured on drops of table3, fig5a and fig6a: at most 2.7e-5, issue 21;
  :data:`validity.necessary.CONTACT_SLACK` = 0.01 keeps a wide margin, the same constant the
  necessary conditions grant);
* ``walls``: how far the made walls can retreat from the nominal ones. Every made free
  interior lies inside the nominal one united with capsules round its segments
  (:func:`validity.made_envelope.made_envelope`, by interval arithmetic over the tolerance
  box), so a point of a nominal wall piece that a made feeder leaves free lies within the
  radius of a capsule that meets the piece of the piece's surface: the piece's part is the
  largest such radius. The finger (a rectangle) is granted the largest move of its corners,
  the tip disc the largest move of its centre plus the largest change of its radius.

The total per obstacle, in the scene's order (polygons, then discs), goes to
:class:`validity.geometric.GeometricLevel` as its ``slack``. See docs/geometric-relaxation.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from feeders.feeder import WALL_THICKNESS
from feeders.scene import Scene
from validity.made_envelope import made_envelope, parameter_intervals, roof_rise_of
from validity.necessary import CONTACT_SLACK

Interval = tuple[float, float]
FINGER = "protuberance finger"  # feeders.feeder.build_feeder's label of the finger


@dataclass(frozen=True)
class RelaxationSlack:
    """The geometric level's slack for one design, with its parts (length).

    ``contact``: the dynamic model's contact overlap granted everywhere; ``walls (P + C,)``:
    per obstacle (polygons, then discs, the scene's order) how far feeders made to
    ``tolerance`` move it back; ``total`` = ``contact + walls``, the level's ``slack``.
    """

    contact: float
    walls: np.ndarray
    tolerance: float

    @property
    def total(self) -> np.ndarray:
        return self.contact + self.walls

    @property
    def uniform(self) -> float:
        """The largest slack of any obstacle: one number that grants every one of them."""
        return float(self.total.max())


def _farthest(nominal: tuple[float, float], xs: Interval, ys: Interval) -> float:
    """The largest distance from ``nominal`` to a point of the box ``xs x ys``."""
    dx = max(abs(xs[0] - nominal[0]), abs(xs[1] - nominal[0]))
    dy = max(abs(ys[0] - nominal[1]), abs(ys[1] - nominal[1]))
    return math.hypot(dx, dy)


def _finger_move(box: dict[str, Interval], design) -> float:
    """The largest move of a finger corner, ``(e - WALL_THICKNESS or fx, fy +- r)``."""
    fy_low = (box["fy"][0] - box["r"][1], box["fy"][1] - box["r"][0])
    fy_high = (box["fy"][0] + box["r"][0], box["fy"][1] + box["r"][1])
    root = (box["e"][0] - WALL_THICKNESS, box["e"][1] - WALL_THICKNESS)
    moves = []
    for xs, x0 in ((root, design.e - WALL_THICKNESS), (box["fx"], design.fx)):
        for ys, y0 in ((fy_low, design.fy - design.r), (fy_high, design.fy + design.r)):
            moves.append(_farthest((x0, y0), xs, ys))
    return max(moves)


def wall_displacement(scene: Scene, tolerance: float) -> np.ndarray:
    """Per obstacle of ``scene`` (a feeder built from a design; polygons then discs), a bound
    (length) on how far any feeder made to ``tolerance`` (relative, per parameter) moves its
    surface back from the nominal one (see the module)."""
    design = scene.design
    if design is None or scene.outline is None:
        raise ValueError("the geometric slack needs a feeder built from a design (scene.design)")
    if not (math.isfinite(tolerance) and 0.0 <= tolerance <= 0.1):
        raise ValueError(f"tolerance = {tolerance!r} is outside the allowed range [0, 0.1]")
    envelope = made_envelope(
        design, scene.part, tolerance, 0.0, 0.0, 0.0, roof_rise_of(design, scene.outline)
    )
    ends = np.stack([envelope.outline, np.roll(envelope.outline, -1, axis=0)], axis=1)
    segments = shapely.linestrings(ends)
    polygons, discs = scene.obstacles.polygons, scene.obstacles.circles
    box = parameter_intervals(design, tolerance)
    out = np.zeros(len(polygons) + len(discs))
    for j, piece in enumerate(polygons):
        if scene.obstacles.labels[j] == FINGER:
            out[j] = _finger_move(box, design)
            continue
        gaps = shapely.distance(segments, shapely.Polygon(piece))
        meeting = envelope.capsules[gaps <= envelope.capsules]
        out[j] = float(meeting.max()) if meeting.size else 0.0
    centre = _farthest((design.fx, design.fy), box["fx"], box["fy"])
    radius = max(abs(box["r"][0] - design.r), abs(box["r"][1] - design.r))
    out[len(polygons) :] = centre + radius
    return out


def relaxation_slack(
    scene: Scene, tolerance: float = 0.01, contact: float = CONTACT_SLACK
) -> RelaxationSlack:
    """The geometric level's slack per obstacle for the nominal feeder ``scene``: the dynamic
    model's ``contact`` overlap (length) plus the walls' move over feeders made to
    ``tolerance`` (relative per parameter; the verdict's default 0.01)."""
    if not (math.isfinite(contact) and 0.0 <= contact <= 0.05):
        raise ValueError(f"contact slack = {contact!r} is outside the allowed range [0, 0.05]")
    return RelaxationSlack(float(contact), wall_displacement(scene, tolerance), float(tolerance))
