"""The paper's cup-shaped part (Section 1, Fig. 1) as a composite part: a U of uniform density.

Fig. 1's device must turn the cup so that it leaves chute C open end up, from either entry
("open end up", "open end down"); the paper gives no dimensions, so they are chosen to fit the
same device as the peg (length 2.2, width 0.7; chutes of width a in [1.1, 1.2], b in [1.1, 1.3]):

* outer width 1.0 across the chute: 0.1-0.3 of play in the chutes (the peg has 0.4-0.6; the
  cup is shorter, so it must be wider not to turn round);
* height 0.9 from the base to the rim: the diagonal sqrt(1.0^2 + 0.9^2) = 1.345 exceeds the
  widest chute (1.3), so, as the peg, the cup cannot turn round inside a chute (turning in a
  strip needs the strip at least as wide as the part's largest width, its diagonal);
* wall and base thickness 0.15: the opening is 0.7 wide, so the pin B (radius r in [0.1, 0.3],
  at most 0.6 across) fits inside the cup, which is how Fig. 1's device turns it.

Body frame as the peg's: the x axis runs along the cup's axis from the open end toward the base
(the heavier end: the centre of mass is 0.345 from the base's outer face, 0.555 from the rim),
so "open end up" (base down) is ``yaw = -pi/2``, as "heavy end down" is for the peg.
"""

from __future__ import annotations

import numpy as np

from feeders.composite_part import CompositePart

CUP_WIDTH = 1.0
CUP_HEIGHT = 0.9
CUP_WALL = 0.15


def cup_part(
    width: float = CUP_WIDTH,
    height: float = CUP_HEIGHT,
    wall: float = CUP_WALL,
    mass: float = 1.0,
) -> CompositePart:
    """The cup as three rectangles of one density (``mass`` over the U's area): two walls of
    ``wall`` x ``height`` and the base between them, ``wall`` thick (lengths in the paper's
    units). Part frame: the open end at x = 0, the base's outer face at x = ``height``, the axis
    on y = 0."""
    half = width / 2.0
    inner = half - wall
    walls = [
        np.array([[0.0, -half], [height, -half], [height, -inner], [0.0, -inner]]),
        np.array([[0.0, inner], [height, inner], [height, half], [0.0, half]]),
    ]
    base = np.array(
        [[height - wall, -inner], [height, -inner], [height, inner], [height - wall, inner]]
    )
    area = 2.0 * wall * height + (width - 2.0 * wall) * wall
    density = mass / area
    return CompositePart(
        (walls[0], base, walls[1]),
        (density,) * 3,
        labels=("cup wall y < 0", "cup base", "cup wall y > 0"),
    )
