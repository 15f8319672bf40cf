"""``partfeeder plan``: plan the part through a feeder with one level and one OMPL planner, for
one or both entry orientations; prints a summary (or JSON) and can draw the tree and path.

The budget per run is wall-clock seconds (``--time``) or, machine-independent, a count of
propagations (``--propagations``; ``--time`` is then a cap, 600 s unless given, as a sweep's
``budget: {propagations: N}``): the same seed and count give the same run on any machine."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from experiments.cli.kernels import compile_once
from experiments.cli.scenes import (
    add_scene_arguments,
    design_starts,
    load_scene,
    orientations,
    orientations_of,
)
from experiments.cli.usage import check_count, check_seed, check_time, out_dir
from experiments.names import LEVEL_NAMES, PLANNER_NAMES

DEFAULT_TIME_S = 5.0  # the wall-clock budget without --propagations
CAP_TIME_S = 600.0  # the cap with --propagations, as a sweep's
MAX_PROPAGATIONS = 10**9  # as a sweep's budget.propagations


def add_arguments(plan: argparse.ArgumentParser) -> None:
    add_scene_arguments(plan)
    plan.add_argument("--level", default="geometric", choices=sorted(LEVEL_NAMES))
    plan.add_argument("--planner", default="rrt", choices=sorted(PLANNER_NAMES))
    plan.add_argument(
        "--orientation",
        default="both",
        help="both, or one start of the scene (feeder: heavy_leading, heavy_trailing)",
    )
    plan.add_argument(
        "--time",
        type=float,
        default=None,
        help=f"planning time per run (s, wall clock; default {DEFAULT_TIME_S:g}); with "
        f"--propagations only a cap (default {CAP_TIME_S:g})",
    )
    plan.add_argument(
        "--propagations",
        type=int,
        default=None,
        help="planning budget per run in propagations (machine-independent: the same seed "
        "gives the same run on any machine and under any load)",
    )
    plan.add_argument("--seed", type=int, default=1)
    plan.add_argument("--out", type=Path, default=None, help="directory for the picture")
    plan.add_argument("--json", action="store_true", help="print JSON instead of a table")
    plan.add_argument("--verbose", action="store_true", help="show OMPL's log")


def run(args: argparse.Namespace) -> int:
    """Every value is checked before OMPL, numba or matplotlib is imported (issue 22: a bad
    ``--design`` took 0.5 s, as long as importing them); matplotlib only with ``--out``."""
    if args.time is not None:
        check_time(args.time)
    if args.propagations is not None:
        check_count(args.propagations, "--propagations", MAX_PROPAGATIONS)
    check_seed(args.seed)
    if args.time is not None:
        time_limit = float(args.time)
    else:
        time_limit = DEFAULT_TIME_S if args.propagations is None else CAP_TIME_S
    out = out_dir(args.out, inputs=[args.scene] if args.scene else [])
    starts = design_starts(args.scene) if args.family is None else None
    if starts is not None:  # checked before the feeder is built (its kernels load numba)
        orientations_of(starts, args.orientation)
    scene = load_scene(args.design, args.scene, args.family, args.values)
    chosen = orientations(scene, args.orientation)
    compile_once([args.level])
    from planners.plan import plan

    results = [
        plan(
            scene,
            args.level,
            args.planner,
            o,
            time_limit,
            args.seed,
            propagations=args.propagations,
        )
        for o in chosen
    ]
    figure = None
    if out is not None:
        from experiments.pictures.scenes import plan_figure

        stem = f"plan_{scene.name}_{args.level}_{args.planner}".replace(" ", "_")
        figure = str(plan_figure(scene, results, out / f"{stem}.png"))
        (out / f"{stem}.json").write_text(json.dumps([r.summary() for r in results], indent=2))
    if args.json:
        print(json.dumps({"runs": [r.summary() for r in results], "figure": figure}, indent=2))
        return 0
    budget = f"{time_limit:g} s"
    if args.propagations is not None:
        budget = f"{args.propagations} propagations (cap {budget})"
    print(
        f"{scene.name} | level {args.level} | planner {args.planner} | seed {args.seed} | "
        f"budget {budget}"
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
