"""``partfeeder bench``: the speed of one level's checks and propagation, and of planning
(dynamic: against MuJoCo when it is installed)."""

from __future__ import annotations

import argparse
import json

from experiments.cli.usage import UsageError
from experiments.names import LEVEL_NAMES


def add_arguments(bench: argparse.ArgumentParser) -> None:
    bench.add_argument(
        "--level",
        default="geometric",
        choices=LEVEL_NAMES,
        help="which level's benchmarks (dynamic: against MuJoCo when installed)",
    )
    bench.add_argument("--quick", action="store_true", help="fewer repeats and seeds")
    bench.add_argument("--repeats", type=int, default=5)
    bench.add_argument("--seed", type=int, default=1)
    bench.add_argument("--json", action="store_true")


def run(args: argparse.Namespace) -> int:
    if args.repeats < 1:
        raise UsageError(f"--repeats = {args.repeats} must be >= 1")
    if args.level == "kinematic":
        from experiments.bench.kinematic import format_kinematic_report, run_kinematic_benchmarks

        results = run_kinematic_benchmarks(repeats=args.repeats, seed=args.seed, quick=args.quick)
        print(json.dumps(results, indent=2) if args.json else format_kinematic_report(results))
        return 0
    if args.level == "dynamic":
        from experiments.bench.dynamic import format_dynamic_report, run_dynamic_benchmarks

        results = run_dynamic_benchmarks(repeats=args.repeats, quick=args.quick)
        print(json.dumps(results, indent=2) if args.json else format_dynamic_report(results))
        return 0
    from experiments.bench.geometric import format_report, run_benchmarks

    results = run_benchmarks(repeats=args.repeats, seed=args.seed, quick=args.quick)
    print(json.dumps(results, indent=2) if args.json else format_report(results))
    return 0
