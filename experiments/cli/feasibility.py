"""``partfeeder feasibility``: the fraction of N Halton designs feasible at one level against
another on the same designs and budgets (is the first level's feasible set a subset?).

The budget per orientation is wall-clock seconds (``--time``) or, machine-independent, a count
of propagations (``--propagations``; ``--time`` is then a cap, 600 s unless given, as a
sweep's ``budget: {propagations: N}``), whose verdicts do not depend on the machine's load.

Rows are written as jobs finish (JSON lines), then as JSON and CSV with a figure and a summary.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from experiments.cli.kernels import compile_once
from experiments.cli.usage import UsageError, check_count, check_seed, check_time, out_dir
from experiments.names import LEVEL_NAMES, PLANNER_NAMES

MAX_DESIGNS = 1_000_000  # as a sweep's designs.count
MAX_WORKERS = 1024  # as a sweep's workers
MAX_PROPAGATIONS = 10**9  # as a sweep's budget.propagations
DEFAULT_TIME_S = 1.0  # the wall-clock budget without --propagations
CAP_TIME_S = 600.0  # the cap with --propagations, as a sweep's


def add_arguments(feas: argparse.ArgumentParser) -> None:
    feas.add_argument(
        "--levels",
        default="kinematic,geometric",
        help=f"two levels A,B; checks that A's feasible designs are feasible at B too "
        f"(levels: {', '.join(LEVEL_NAMES)}; default: kinematic,geometric)",
    )
    feas.add_argument(
        "--designs", type=int, default=500, help="the first N Halton designs of the Table 2 box"
    )
    feas.add_argument(
        "--planner", default="rrt", help=f"OMPL planner ({', '.join(sorted(PLANNER_NAMES))})"
    )
    feas.add_argument(
        "--time",
        type=float,
        default=None,
        help=f"planning budget per orientation (s, wall clock; default {DEFAULT_TIME_S:g}); "
        f"with --propagations only a cap (default {CAP_TIME_S:g})",
    )
    feas.add_argument(
        "--propagations",
        type=int,
        default=None,
        help="planning budget per orientation in propagations (machine-independent: the "
        "verdicts are the same on any machine and under any load)",
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


def _options(args: argparse.Namespace) -> tuple[list[str], int]:
    """The two level names and the worker count, or UsageError naming the flag."""
    import os

    levels = [name.strip() for name in args.levels.split(",")]
    if len(levels) != 2 or not all(levels):
        raise UsageError(
            f"--levels '{args.levels}' must be two level names A,B separated by a comma; "
            f"levels: {', '.join(LEVEL_NAMES)}"
        )
    unknown = [name for name in levels if name not in LEVEL_NAMES]
    if unknown:
        raise UsageError(
            f"--levels: unknown level(s) {', '.join(unknown)}; levels: {', '.join(LEVEL_NAMES)}"
        )
    check_count(args.designs, "--designs", MAX_DESIGNS)
    if args.planner.lower() not in PLANNER_NAMES:
        raise UsageError(
            f"--planner '{args.planner}' is unknown; planners: {', '.join(sorted(PLANNER_NAMES))}"
        )
    if args.time is not None:
        check_time(args.time)
    if args.propagations is not None:
        check_count(args.propagations, "--propagations", MAX_PROPAGATIONS)
    check_seed(args.seed)
    workers = args.workers if args.workers is not None else (os.cpu_count() or 1)
    check_count(workers, "--workers", MAX_WORKERS)
    return levels, workers


def _time_limit(args: argparse.Namespace) -> float:
    """The wall-clock seconds per orientation: the budget, or the cap with --propagations."""
    if args.time is not None:
        return float(args.time)
    return DEFAULT_TIME_S if args.propagations is None else CAP_TIME_S


def _budget(settings: dict) -> str:
    """The budget as the summary line says it."""
    if settings.get("propagations") is None:
        return f"{settings['time_s']:g} s"
    return f"{settings['propagations']} propagations (cap {settings['time_s']:g} s)"


def _report(summary: dict) -> str:
    """The human summary: fraction per level with CI, the 2x2 table, every exception."""
    from feeders.design import PARAMETER_NAMES

    s, g = summary["settings"], summary["agreement"]
    a, b = g["a"], g["b"]
    label_b = f"{b} (run 2)" if a == b else b
    lines = [
        f"{s['designs']} Halton designs (seed {s['seed']}) | planner {s['planner']} | "
        f"{_budget(s)} per orientation | {s['workers']} workers | "
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


def run(args: argparse.Namespace) -> int:
    """Every flag is checked before numba, OMPL or matplotlib is imported, and the kernels
    of both levels are compiled here once before the workers start (issue 22)."""
    import csv
    import os
    import time

    levels, workers = _options(args)
    out = out_dir(args.out)
    time_limit = _time_limit(args)
    compile_once(levels)
    from experiments.progress import bar as progress_bar
    from experiments.verdicts.feasibility import (
        agreement,
        compare_levels,
        csv_header,
        csv_record,
    )
    from experiments.verdicts.feasibility_figure import feasibility_figure

    if workers > (os.cpu_count() or 1) and args.propagations is None:
        print(
            f"partfeeder feasibility: note: --workers {workers} > {os.cpu_count()} CPUs; the "
            "budgets are wall-clock time, so busy workers may flip borderline verdicts "
            "(a budget in --propagations does not)",
            file=sys.stderr,
        )
    stream = None
    if out is not None:
        # Each finished row is appended and flushed at once: a crash keeps what was done.
        stream = (out / "feasibility_rows.jsonl").open("w", encoding="utf-8")
    t0 = time.perf_counter()
    total = args.designs * len(levels)
    try:
        with progress_bar(total, "feasibility", "job") as bar:  # lines in a log

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
                time_limit=time_limit,
                seed=args.seed,
                workers=workers,
                progress=progress,
                propagations=args.propagations,
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
            "time_s": time_limit,
            "propagations": args.propagations,
            "seed": args.seed,
            "workers": workers,
        },
        "wall_time_s": wall,
        "agreement": agreement(rows, levels[0], levels[1]),
        "files": files,
    }
    if out is not None:
        (out / "feasibility_summary.json").write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary, indent=2) if args.json else _report(summary))
    return 0
