"""``partfeeder draw``: a picture of a design (feeder, start poses, goal region)."""

from __future__ import annotations

import argparse
from pathlib import Path

from experiments.cli.scenes import add_scene_arguments, load_scene
from experiments.cli.usage import out_file


def add_arguments(draw: argparse.ArgumentParser) -> None:
    add_scene_arguments(draw)
    draw.add_argument(
        "--out", type=Path, required=True, help="picture file to write (.png, .pdf or .svg)"
    )


def run(args: argparse.Namespace) -> int:
    """The design and ``--out`` are checked before matplotlib is imported."""
    inputs = [p for p in (args.scene, args.family) if p is not None]
    missing = [d for d in (args.out.parent, *args.out.parent.parents) if not d.exists()]
    out = out_file(args.out, inputs=inputs)  # never the scene or family file itself
    try:
        scene = load_scene(args.design, args.scene, args.family, args.values)
    except BaseException:  # refused: the directories made for --out go again (if empty)
        for directory in missing:  # deepest first
            try:
                directory.rmdir()
            except OSError:
                break
        raise
    from experiments.pictures.scenes import scene_figure

    print(scene_figure([scene], [scene.name], out))
    return 0
