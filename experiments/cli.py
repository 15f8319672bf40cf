"""The ``partfeeder`` command line.

``partfeeder plan``: plan the part through a feeder (a paper preset, 12 values, or a YAML
scene) with one level and one OMPL planner, for one or both entry orientations; prints a
summary (or JSON) and writes a picture of the tree and path. ``partfeeder draw``: pictures of
designs. ``partfeeder simulate``: the passive drop of the part through a feeder with the dynamic
level, per entry orientation. ``partfeeder bench``: speed of the levels and of planning.

Exit status: 0 done (whether or not a plan was found: see the output), 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from experiments.console import exit_now, set_ompl_logging

ORIENTATIONS = ("heavy_leading", "heavy_trailing")


class UsageError(Exception):
    """Bad input from the user: printed as one line, exit status 2."""


def _parser() -> argparse.ArgumentParser:
    from feeders.design import PRESETS
    from planners.registry import PLANNERS
    from validity import LEVELS

    parser = argparse.ArgumentParser(
        prog="partfeeder",
        description="Design part feeders by motion planning with physics (geometric, "
        "kinematic and dynamic levels on OMPL).",
    )
    sub = parser.add_subparsers(dest="command", required=True)

    def scene_args(p: argparse.ArgumentParser) -> None:
        group = p.add_mutually_exclusive_group()
        group.add_argument(
            "--design",
            default=None,
            help=f"a paper preset ({', '.join(sorted(PRESETS))}) or the 12 values "
            "a,b,c,d,e,fx,fy,gx,gy,r,theta,alpha separated by commas (default: table3)",
        )
        group.add_argument("--scene", type=Path, help="a scene YAML file")

    plan = sub.add_parser("plan", help="plan the part through a scene with OMPL")
    scene_args(plan)
    plan.add_argument("--level", default="geometric", choices=sorted(LEVELS))
    plan.add_argument("--planner", default="rrt", choices=sorted(PLANNERS))
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

    sim = sub.add_parser(
        "simulate", help="drop the part passively through a scene with the dynamic level"
    )
    scene_args(sim)
    sim.add_argument(
        "--orientation",
        default="both",
        help="both, or one start of the scene (feeder: heavy_leading, heavy_trailing)",
    )
    sim.add_argument("--step", type=float, default=1e-3, help="time step h (s)")
    sim.add_argument("--time", type=float, default=10.0, help="longest simulated time (s)")
    sim.add_argument(
        "--out", type=Path, default=None, help="directory for the snapshot strip and animation"
    )
    sim.add_argument("--no-animation", action="store_true", help="write the strip only")
    sim.add_argument("--json", action="store_true", help="print JSON instead of a table")

    draw = sub.add_parser("draw", help="draw designs (feeder, start poses, goal region)")
    scene_args(draw)
    draw.add_argument("--out", type=Path, required=True, help="PNG file to write")

    cal = sub.add_parser("calibrate", help="the geometric level's verdict on the paper's designs")
    cal.add_argument("--runs", type=int, default=3, help="seeded RRT runs per orientation")
    cal.add_argument("--time", type=float, default=10.0, help="budget per run (s)")
    cal.add_argument(
        "--out",
        type=Path,
        default=None,
        help="directory for pictures of table3 and of the box's corners",
    )

    bench = sub.add_parser("bench", help="measure the speed of checks, propagation, planning")
    bench.add_argument(
        "--level",
        default="geometric",
        choices=("geometric", "dynamic"),
        help="which level's benchmarks (dynamic: against MuJoCo when installed)",
    )
    bench.add_argument("--quick", action="store_true", help="fewer repeats and seeds")
    bench.add_argument("--repeats", type=int, default=5)
    bench.add_argument("--seed", type=int, default=1)
    bench.add_argument("--json", action="store_true")
    return parser


def _load_scene(design: str | None, scene_file: Path | None):
    from feeders.design import DesignError, DesignParameters, preset
    from feeders.feeder import DegenerateDesign, build_feeder
    from feeders.scene_yaml import SceneError, load_scene

    try:
        if scene_file is not None:
            return load_scene(scene_file)
        spec = design or "table3"
        if "," in spec:
            try:
                values = [float(v) for v in spec.split(",")]
            except ValueError:
                raise UsageError(f"--design: '{spec}' is not 12 comma-separated numbers") from None
            return build_feeder(DesignParameters.from_vector(values), name="custom design")
        return build_feeder(preset(spec), name=spec)
    except (DesignError, SceneError) as exc:
        raise UsageError(str(exc)) from None
    except DegenerateDesign as exc:
        raise UsageError(f"degenerate design: {exc}") from None


def _orientations(scene, choice: str) -> list[str]:
    """``both`` (the feeder's two entries, or every start of a free-form scene) or one start."""
    if choice == "both":
        return [o for o in ORIENTATIONS if o in scene.starts] or list(scene.starts)
    if choice in scene.starts:
        return [choice]
    raise UsageError(
        f"--orientation '{choice}' is not a start of this scene; "
        f"choose both or one of: {', '.join(scene.starts)}"
    )


def _out_dir(out: Path | None) -> Path | None:
    if out is not None:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise UsageError(f"--out: cannot create directory '{out}': {exc.strerror}") from None
    return out


def _cmd_plan(args: argparse.Namespace) -> int:
    from experiments.plotting import plan_figure
    from planners.plan import plan

    if not (0.0 < args.time <= 3600.0):
        raise UsageError(f"--time = {args.time} is outside the allowed range (0, 3600] s")
    scene = _load_scene(args.design, args.scene)
    orientations = _orientations(scene, args.orientation)
    out = _out_dir(args.out)
    results = [plan(scene, args.level, args.planner, o, args.time, args.seed) for o in orientations]
    figure = None
    if out is not None:
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


def _cmd_simulate(args: argparse.Namespace) -> int:
    from experiments.passive_drop import eq10_objective, passive_drop

    if not (1e-6 <= args.step <= 0.1):
        raise UsageError(f"--step = {args.step} is outside the allowed range [1e-06, 0.1] s")
    if not (0.0 < args.time <= 3600.0):
        raise UsageError(f"--time = {args.time} is outside the allowed range (0, 3600] s")
    scene = _load_scene(args.design, args.scene)
    orientations = _orientations(scene, args.orientation)
    out = _out_dir(args.out)
    results = [passive_drop(scene, o, step=args.step, t_max=args.time) for o in orientations]
    files: list[str] = []
    if out is not None:
        from experiments.drop_plots import drop_animation, drop_strip

        stem = f"drop_{scene.name}".replace(" ", "_")
        files.append(str(drop_strip(scene, results, out / f"{stem}.png")))
        if not args.no_animation:
            files.append(str(drop_animation(scene, results, out / f"{stem}.gif")))
        summaries = {"runs": [r.summary() for r in results]}
        (out / f"{stem}.json").write_text(json.dumps(summaries, indent=2))
        files.append(str(out / f"{stem}.json"))
    objective = eq10_objective(results)
    if args.json:
        report = {"runs": [r.summary() for r in results], "eq10_objective": objective}
        print(json.dumps({**report, "files": files}, indent=2))
        return 0
    print(
        f"{scene.name} | dynamic level, h = {args.step:g} s | passive drop, up to {args.time:g} s"
    )
    print(
        f"{'orientation':<16}{'goal':>6}{'end':>12}{'T (s)':>8}{'overlap':>10}"
        f"{'E rise':>10}{'LCP fail':>10}{'wall (ms)':>11}"
    )
    for r in results:
        print(
            f"{r.orientation:<16}{'yes' if r.success else 'no':>6}{r.end:>12}{r.T:>8.3f}"
            f"{r.max_penetration:>10.1e}{r.energy_rise:>10.1e}{r.lcp_failures:>10d}"
            f"{r.wall_time * 1e3:>11.1f}"
        )
    print(f"Eq. 10 objective (w = 5): {objective:.3f}")
    for f in files:
        print(f"wrote: {f}")
    return 0


def _cmd_draw(args: argparse.Namespace) -> int:
    from experiments.plotting import scene_figure

    scene = _load_scene(args.design, args.scene)
    try:
        args.out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"--out: cannot create '{args.out.parent}': {exc.strerror}") from None
    print(scene_figure([scene], [scene.name], args.out))
    return 0


def _cmd_calibrate(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from experiments.atlas import corner_census, draw_atlas
    from experiments.calibration import ORIENTATIONS as CAL_ORIENTATIONS
    from experiments.calibration import calibrate, markdown_table
    from feeders.design import PRESETS

    if args.runs < 1:
        raise UsageError(f"--runs = {args.runs} must be >= 1")
    if not (0.0 < args.time <= 3600.0):
        raise UsageError(f"--time = {args.time} is outside the allowed range (0, 3600] s")
    with tqdm(total=len(PRESETS) * len(CAL_ORIENTATIONS), desc="calibrating", unit="run") as bar:
        rows = calibrate(
            runs=args.runs,
            time_limit=args.time,
            progress=lambda name, _o: bar.set_postfix_str(name) or bar.update(),
        )
    print(markdown_table(rows))
    corners, built, reasons = corner_census()
    print(f"\ncorners of the Table 2 box that build: {built} of {corners}")
    for reason, count in reasons.most_common():
        print(f"  rejected, {reason}: {count}")
    if args.out is not None:
        for path in draw_atlas(args.out):
            print(f"picture: {path}")
    return 0


def _cmd_bench(args: argparse.Namespace) -> int:
    from experiments.bench import format_report, run_benchmarks

    if args.repeats < 1:
        raise UsageError(f"--repeats = {args.repeats} must be >= 1")
    if args.level == "dynamic":
        from experiments.bench_dynamic import format_dynamic_report, run_dynamic_benchmarks

        results = run_dynamic_benchmarks(repeats=args.repeats, quick=args.quick)
        print(json.dumps(results, indent=2) if args.json else format_dynamic_report(results))
        return 0
    results = run_benchmarks(repeats=args.repeats, seed=args.seed, quick=args.quick)
    print(json.dumps(results, indent=2) if args.json else format_report(results))
    return 0


COMMANDS = {
    "plan": _cmd_plan,
    "simulate": _cmd_simulate,
    "draw": _cmd_draw,
    "calibrate": _cmd_calibrate,
    "bench": _cmd_bench,
}


def run(argv: Sequence[str] | None = None) -> int:
    """Run a command; returns the exit status (for tests; ``main`` also exits)."""
    args = _parser().parse_args(argv)
    set_ompl_logging(getattr(args, "verbose", False))
    try:
        return COMMANDS[args.command](args)
    except UsageError as exc:
        print(f"partfeeder {args.command}: error: {exc}", file=sys.stderr)
        return 2


def main(argv: Sequence[str] | None = None) -> None:
    try:
        code = run(argv)
    except SystemExit as exc:  # argparse: --help, usage errors
        code = exc.code if isinstance(exc.code, int) else 2
    except BrokenPipeError:  # e.g. piped into `head`
        code = 0
    except KeyboardInterrupt:
        print("partfeeder: interrupted", file=sys.stderr)
        code = 130
    exit_now(code)


if __name__ == "__main__":
    main()
