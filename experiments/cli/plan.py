"""``partfeeder plan``: plan the part through a feeder with one level and one OMPL planner, for
one or both entry orientations; prints a summary (or JSON) and can draw the tree and path."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from experiments.cli.kernels import compile_once
from experiments.cli.scenes import add_scene_arguments, load_scene, orientations
from experiments.cli.usage import check_seed, check_time, out_dir
from experiments.names import LEVEL_NAMES, PLANNER_NAMES


def add_arguments(plan: argparse.ArgumentParser) -> None:
    add_scene_arguments(plan)
    plan.add_argument("--level", default="geometric", choices=sorted(LEVEL_NAMES))
    plan.add_argument("--planner", default="rrt", choices=sorted(PLANNER_NAMES))
    plan.add_argument(
        "--orientation",
        default="both",
        help="both, or one start of the scene (feeder: heavy_leading, heavy_trailing)",
    )
    plan.add_argument("--time", type=float, default=5.0, help="planning time per run (s)")
    plan.add_argument("--seed", type=int, default=1)
    plan.add_argument("--out", type=Path, default=None, help="directory for the picture")
    plan.add_argument("--json", action="store_true", help="print JSON instead of a table")
    plan.add_argument("--verbose", action="store_true", help="show OMPL's log")


def run(args: argparse.Namespace) -> int:
    """Every value is checked before OMPL, numba or matplotlib is imported (issue 22: a bad
    ``--design`` took 0.5 s, as long as importing them); matplotlib only with ``--out``."""
    check_time(args.time)
    check_seed(args.seed)
    scene = load_scene(args.design, args.scene)
    chosen = orientations(scene, args.orientation)
    out = out_dir(args.out, inputs=[args.scene] if args.scene else [])
    compile_once([args.level])
    from planners.plan import plan

    results = [plan(scene, args.level, args.planner, o, args.time, args.seed) for o in chosen]
    figure = None
    if out is not None:
        from experiments.pictures.scenes import plan_figure

        stem = f"plan_{scene.name}_{args.level}_{args.planner}".replace(" ", "_")
        figure = str(plan_figure(scene, results, out / f"{stem}.png"))
        (out / f"{stem}.json").write_text(json.dumps([r.summary() for r in results], indent=2))
    if args.json:
        print(json.dumps({"runs": [r.summary() for r in results], "figure": figure}, indent=2))
        return 0
    print(
        f"{scene.name} | level {args.level} | planner {args.planner} | seed {args.seed} | "
        f"budget {args.time:g} s"
    )
    print(f"{'orientation':<16}{'solved':>7}{'time (s)':>10}{'tree':>8}{'path length':>13}")
    for r in results:
        print(
            f"{r.orientation:<16}{'yes' if r.solved else 'no':>7}{r.time:>10.3f}"
            f"{r.tree_size:>8}{r.path_length:>13.2f}"
        )
    if figure:
        print(f"picture: {figure}")
    return 0
