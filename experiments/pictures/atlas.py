"""Designs at the corners of the Table 2 box: do they build, and what do they look like?

The 2^12 = 4096 corners are the extremes of the design space; building each one is a test of
the reconstruction (docs/feeder-geometry.md) and drawing a few shows its range.
"""

from __future__ import annotations

import itertools
from collections import Counter
from pathlib import Path

import numpy as np

from feeders.design import DESIGN_SPACE, PRESETS, DesignParameters
from feeders.feeder import DegenerateDesign, build_feeder


def corner_designs() -> list[tuple[str, DesignParameters]]:
    """Every corner, named by its low/high pattern in parameter order (e.g. 'LLLLLLLLLLLL')."""
    low, high = DESIGN_SPACE.low, DESIGN_SPACE.high
    out = []
    for bits in itertools.product((0, 1), repeat=len(low)):
        mask = np.array(bits, dtype=bool)
        name = "".join("H" if b else "L" for b in bits)
        out.append((name, DesignParameters.from_vector(np.where(mask, high, low))))
    return out


def corner_census() -> tuple[int, int, Counter]:
    """(corners, corners that build, count of rejection reasons by parameters named)."""
    corners = corner_designs()
    built, reasons = 0, Counter[str]()
    for _, design in corners:
        try:
            build_feeder(design)
            built += 1
        except DegenerateDesign as exc:
            reasons[exc.reason.split("(")[0].split("=")[0].strip()] += 1
    return len(corners), built, reasons


def draw_atlas(out_dir: str | Path, seed: int = 0, extra: int = 6) -> list[Path]:
    """Pictures: table3; the all-high corner and ``extra`` seeded random corners that build.

    (The all-low corner does not build: its protuberance tip lies inside the left wall.)
    """
    from experiments.pictures.scenes import scene_figure

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    corners = corner_designs()
    order = np.random.default_rng(seed).permutation(np.arange(1, len(corners) - 1))
    scenes = [build_feeder(corners[-1][1], name=corners[-1][0])]
    for i in order:
        if len(scenes) > extra:
            break
        name, design = corners[i]
        try:
            scenes.append(build_feeder(design, name=name))
        except DegenerateDesign:
            continue
    paths = [
        scene_figure(
            [build_feeder(PRESETS["table3"], name="table3")], ["table3"], out_dir / "table3.png"
        )
    ]
    titles = [f"corner {s.name}" for s in scenes]
    paths.append(scene_figure(scenes, titles, out_dir / "corners.png"))
    return paths
