"""``partfeeder planners``: every OMPL control planner that runs from Python on a suite of
contact-rich problems (the paper's designs, Halton designs that work and fail, the cup
through the fig1-cup family) at the three levels from both entries, N seeded runs each with
budgets in propagations (the same results on any machine), on the local pool. Prints the
headline table per level (solved fraction with Wilson intervals, the best planner by the
performance profile with a bootstrap interval); ``--json`` prints the report's data;
``--out DIR`` writes the report (markdown, HTML with figures, JSON), OMPL's logs and Planner
Arena's database (docs/planners.md)."""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

from experiments.cli.usage import UsageError, check_count, check_seed, out_dir

MAX_WORKERS = 1024
MAX_RUNS = 1000
QUICK = "planners-quick"  # experiments/planner_comparison/shipped.py
FULL = "planners"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "config",
        nargs="?",
        default=None,
        help=f"a comparison config (YAML, docs/planners.md) or the name of a shipped suite "
        f"({FULL}, {QUICK}); default: {FULL}, the full suite",
    )
    p.add_argument(
        "--quick",
        action="store_true",
        help=f"the quick suite ({QUICK}: 5 designs, 5 planners, 3 runs; a few minutes on 2 cores)",
    )
    p.add_argument("--out", type=Path, default=None, help="directory for the report and database")
    p.add_argument("--json", action="store_true", help="print the report's data as JSON")
    p.add_argument(
        "--workers", type=int, default=None, help="worker processes (default: the CPU count)"
    )
    p.add_argument("--runs", type=int, default=None, help="runs per planner and problem")
    p.add_argument("--seed", type=int, default=None, help="run r of every planner: seed + r")


def run(args: argparse.Namespace) -> int:
    """Every option is checked before OMPL, numba or matplotlib is imported."""
    if args.quick and args.config is not None:
        raise UsageError("give a config or --quick, not both (--quick is the config " + QUICK + ")")
    workers = (os.cpu_count() or 1) if args.workers is None else args.workers
    check_count(workers, "--workers", MAX_WORKERS)
    if args.runs is not None:
        check_count(args.runs, "--runs", MAX_RUNS)
    if args.seed is not None:
        check_seed(args.seed)
    import dataclasses

    from experiments.planner_comparison.shipped import SUITES
    from experiments.planner_comparison.suite import load_suite, suite_from_dict

    name = args.config or (QUICK if args.quick else FULL)
    if name in SUITES and not Path(name).is_file():
        out = out_dir(args.out)
        suite = suite_from_dict(SUITES[name])
    else:
        out = out_dir(args.out, inputs=[Path(name)])
        suite = load_suite(Path(name))
    if args.runs is not None:
        suite = dataclasses.replace(suite, runs=args.runs)
    if args.seed is not None:
        suite = dataclasses.replace(suite, seed=args.seed)
    from experiments.cli.kernels import compile_once

    compile_once(list(suite.levels))
    from experiments.planner_comparison.report import text_table
    from experiments.planner_comparison.run import compare

    report = compare(suite, out, workers, quiet=args.json)
    if args.json:
        print(json.dumps(report, indent=1, allow_nan=False))
        return 0
    print(text_table(report))
    c = report["cost"]
    print(
        f"cost: {c['problems_planned']} problems planned, {c['runs']} runs, "
        f"{c['propagations']} propagations, {c['wall_s']:.0f} s on {c['workers']} worker(s)"
    )
    for f in report["files"]:
        print(f"wrote: {f}")
    return 0
