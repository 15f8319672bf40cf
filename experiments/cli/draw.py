"""``partfeeder draw``: a picture of a design (feeder, start poses, goal region)."""

from __future__ import annotations

import argparse
from pathlib import Path

from experiments.cli.scenes import add_scene_arguments, load_scene
from experiments.cli.usage import UsageError


def add_arguments(draw: argparse.ArgumentParser) -> None:
    add_scene_arguments(draw)
    draw.add_argument("--out", type=Path, required=True, help="PNG file to write")


def run(args: argparse.Namespace) -> int:
    from experiments.pictures.scenes import scene_figure

    scene = load_scene(args.design, args.scene)
    try:
        args.out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"--out: cannot create '{args.out.parent}': {exc.strerror}") from None
    print(scene_figure([scene], [scene.name], args.out))
    return 0
