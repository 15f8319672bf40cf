"""The ``partfeeder`` command line.

``partfeeder plan``: plan the part through a feeder (a paper preset, 12 values, or a YAML
scene) with one level and one OMPL planner, for one or both entry orientations; prints a
summary (or JSON) and writes a picture of the tree and path. ``partfeeder draw``: pictures of
designs. ``partfeeder simulate``: the passive drop of the part through a feeder with the dynamic
level, per entry orientation. ``partfeeder bench``: speed of the levels and of planning.
``partfeeder feasibility``: the fraction of N Halton designs feasible at one level against
another on the same designs and budgets (is the first level's feasible set a subset?).

Exit status: 0 done (whether or not a plan was found: see the output), 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from experiments.cli_sweep import add_parsers as add_sweep_parsers
from experiments.cli_sweep import cmd_report, cmd_run
from experiments.console import exit_now, set_ompl_logging
from feeders.feeder import ORIENTATIONS


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
        choices=("geometric", "kinematic", "dynamic"),
        help="which level's benchmarks (dynamic: against MuJoCo when installed)",
    )
    bench.add_argument("--quick", action="store_true", help="fewer repeats and seeds")
    bench.add_argument("--repeats", type=int, default=5)
    bench.add_argument("--seed", type=int, default=1)
    bench.add_argument("--json", action="store_true")

    feas = sub.add_parser(
        "feasibility",
        help="fraction of Halton designs feasible at level A vs level B (is A's set within B's?)",
    )
    feas.add_argument(
        "--levels",
        default="kinematic,geometric",
        help=f"two levels A,B; checks that A's feasible designs are feasible at B too "
        f"(levels: {', '.join(LEVELS)}; default: kinematic,geometric)",
    )
    feas.add_argument(
        "--designs", type=int, default=500, help="the first N Halton designs of the Table 2 box"
    )
    feas.add_argument(
        "--planner", default="rrt", help=f"OMPL planner ({', '.join(sorted(PLANNERS))})"
    )
    feas.add_argument(
        "--time", type=float, default=1.0, help="planning budget per orientation (s, wall clock)"
    )
    feas.add_argument("--seed", type=int, default=1, help="seed of the Halton designs and of OMPL")
    feas.add_argument(
        "--workers", type=int, default=None, help="worker processes (default: the CPU count)"
    )
    feas.add_argument(
        "--out",
        type=Path,
        default=None,
        help="directory for the rows (JSON lines written as jobs finish, JSON, CSV), the "
        "figure and the summary",
    )
    feas.add_argument("--json", action="store_true", help="print the summary as JSON")
    add_sweep_parsers(sub)
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
    from experiments.calibration import calibrate, markdown_table
    from feeders.design import PRESETS

    if args.runs < 1:
        raise UsageError(f"--runs = {args.runs} must be >= 1")
    if not (0.0 < args.time <= 3600.0):
        raise UsageError(f"--time = {args.time} is outside the allowed range (0, 3600] s")
    with tqdm(total=len(PRESETS) * len(ORIENTATIONS), desc="calibrating", unit="run") as bar:
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
    if args.level == "kinematic":
        from experiments.bench_kinematic import format_kinematic_report, run_kinematic_benchmarks

        results = run_kinematic_benchmarks(repeats=args.repeats, seed=args.seed, quick=args.quick)
        print(json.dumps(results, indent=2) if args.json else format_kinematic_report(results))
        return 0
    if args.level == "dynamic":
        from experiments.bench_dynamic import format_dynamic_report, run_dynamic_benchmarks

        results = run_dynamic_benchmarks(repeats=args.repeats, quick=args.quick)
        print(json.dumps(results, indent=2) if args.json else format_dynamic_report(results))
        return 0
    results = run_benchmarks(repeats=args.repeats, seed=args.seed, quick=args.quick)
    print(json.dumps(results, indent=2) if args.json else format_report(results))
    return 0


SEED_RANGE = (1, 2**31 - 1)  # OMPL ignores seed 0


def _feasibility_options(args: argparse.Namespace) -> tuple[list[str], int]:
    """The two level names and the worker count, or UsageError naming the flag."""
    import os

    from planners.registry import PLANNERS
    from validity import LEVELS

    levels = [name.strip() for name in args.levels.split(",")]
    if len(levels) != 2 or not all(levels):
        raise UsageError(
            f"--levels '{args.levels}' must be two level names A,B separated by a comma; "
            f"levels: {', '.join(LEVELS)}"
        )
    unknown = [name for name in levels if name not in LEVELS]
    if unknown:
        raise UsageError(
            f"--levels: unknown level(s) {', '.join(unknown)}; levels: {', '.join(LEVELS)}"
        )
    if args.designs < 1:
        raise UsageError(f"--designs = {args.designs} must be >= 1")
    if args.planner.lower() not in PLANNERS:
        raise UsageError(
            f"--planner '{args.planner}' is unknown; planners: {', '.join(sorted(PLANNERS))}"
        )
    if not (0.0 < args.time <= 3600.0):
        raise UsageError(f"--time = {args.time} is outside the allowed range (0, 3600] s")
    if not (SEED_RANGE[0] <= args.seed <= SEED_RANGE[1]):
        raise UsageError(
            f"--seed = {args.seed} is outside the allowed range [{SEED_RANGE[0]}, {SEED_RANGE[1]}]"
        )
    workers = args.workers if args.workers is not None else (os.cpu_count() or 1)
    if workers < 1:
        raise UsageError(f"--workers = {workers} must be >= 1")
    return levels, workers


def _feasibility_report(summary: dict) -> str:
    """The human summary: fraction per level with CI, the 2x2 table, every exception."""
    from feeders.design import PARAMETER_NAMES

    s, g = summary["settings"], summary["agreement"]
    a, b = g["a"], g["b"]
    label_b = f"{b} (run 2)" if a == b else b
    lines = [
        f"{s['designs']} Halton designs (seed {s['seed']}) | planner {s['planner']} | "
        f"{s['time_s']:g} s per orientation | {s['workers']} workers | "
        f"{summary['wall_time_s']:.1f} s",
        f"{'level':<22}{'feasible':>10}{'fraction':>10}{'95% CI (Wilson)':>20}",
    ]
    for name, f in ((a, g["fraction_a"]), (label_b, g["fraction_b"])):
        fraction = "-" if f["fraction"] is None else f"{f['fraction']:.3f}"
        ci = f"[{f['ci95'][0]:.3f}, {f['ci95'][1]:.3f}]"
        lines.append(f"{name:<22}{f['feasible']:>5}/{f['designs']:<4}{fraction:>10}{ci:>20}")
    c = g["counts"]
    lines += [
        "",
        f"designs by verdict (A = {a}, B = {label_b}):",
        f"{'':<10}{'B yes':>8}{'B no':>8}",
        f"{'A yes':<10}{c['both']:>8}{c['a_only']:>8}",
        f"{'A no':<10}{c['b_only']:>8}{c['neither']:>8}",
        f"not built (degenerate, infeasible at both): {g['unbuilt']}",
    ]
    if g["unpaired"]:
        lines.append(f"designs without a verdict at both levels: {g['unpaired']}")
    verdict = "holds" if g["subset_holds"] else f"fails for {c['a_only']} design(s)"
    lines.append(f"feasible at {a} => feasible at {label_b}: {verdict}")
    for e in g["exceptions"]:
        values = ", ".join(
            f"{n}={v:.4g}" for n, v in zip(PARAMETER_NAMES, e["values"], strict=True)
        )
        lines.append(f"  #{e['index']}: {values}")
    for path in summary["files"]:
        lines.append(f"wrote: {path}")
    return "\n".join(lines)


def _cmd_feasibility(args: argparse.Namespace) -> int:
    import csv
    import os
    import time

    from tqdm import tqdm

    from experiments.level_feasibility import (
        agreement,
        compare_levels,
        csv_header,
        csv_record,
        feasibility_figure,
    )

    levels, workers = _feasibility_options(args)
    out = _out_dir(args.out)
    if workers > (os.cpu_count() or 1):
        print(
            f"partfeeder feasibility: note: --workers {workers} > {os.cpu_count()} CPUs; the "
            "budgets are wall-clock time, so busy workers may flip borderline verdicts",
            file=sys.stderr,
        )
    stream = None
    if out is not None:
        # Each finished row is appended and flushed at once: a crash keeps what was done.
        stream = (out / "feasibility_rows.jsonl").open("w", encoding="utf-8")
    t0 = time.perf_counter()
    total = args.designs * len(levels)
    try:
        with tqdm(total=total, desc="feasibility", unit="job", file=sys.stderr) as bar:

            def progress(row: dict) -> None:
                if stream is not None:
                    stream.write(json.dumps(row) + "\n")
                    stream.flush()
                verdict = "feasible" if row["feasible"] else "infeasible"
                bar.set_postfix_str(f"#{row['index']} {row['level']}: {verdict}", refresh=False)
                bar.update()

            rows = compare_levels(
                args.designs,
                levels,
                planner=args.planner,
                time_limit=args.time,
                seed=args.seed,
                workers=workers,
                progress=progress,
            )
    except BaseException:
        if stream is not None:
            stream.close()
            print(
                f"partfeeder feasibility: stopped; finished rows are in {stream.name}",
                file=sys.stderr,
            )
        raise
    wall = time.perf_counter() - t0
    files: list[str] = []
    if stream is not None and out is not None:
        stream.close()
        files.append(stream.name)
        (out / "feasibility_rows.json").write_text(json.dumps(rows, indent=1))
        files.append(str(out / "feasibility_rows.json"))
        with (out / "feasibility_rows.csv").open("w", newline="", encoding="utf-8") as f:
            writer = csv.DictWriter(f, fieldnames=csv_header())
            writer.writeheader()
            writer.writerows(csv_record(row) for row in rows)
        files.append(str(out / "feasibility_rows.csv"))
        files.append(str(feasibility_figure(rows, levels[0], levels[1], out / "feasibility.png")))
        files.append(str(out / "feasibility_summary.json"))
    summary = {
        "settings": {
            "levels": levels,
            "designs": args.designs,
            "planner": args.planner,
            "time_s": args.time,
            "seed": args.seed,
            "workers": workers,
        },
        "wall_time_s": wall,
        "agreement": agreement(rows, levels[0], levels[1]),
        "files": files,
    }
    if out is not None:
        (out / "feasibility_summary.json").write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary, indent=2) if args.json else _feasibility_report(summary))
    return 0


COMMANDS = {
    "plan": _cmd_plan,
    "simulate": _cmd_simulate,
    "draw": _cmd_draw,
    "calibrate": _cmd_calibrate,
    "bench": _cmd_bench,
    "feasibility": _cmd_feasibility,
    "run": lambda args: cmd_run(args, UsageError),
    "report": lambda args: cmd_report(args, UsageError),
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
