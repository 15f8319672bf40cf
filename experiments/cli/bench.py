"""``partfeeder bench``: run time against error. Work-precision diagrams of the analytic
scenes beside MuJoCo and pymunk (when installed), the feeder's convergence, the ladder's cost
against its verdicts' error, speed tables; or, with ``--level``, one level's detailed speed."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from experiments.cli.usage import UsageError

SECTIONS = ("analytic", "speed", "feeder", "ladder")  # experiments.bench.suite.SECTIONS
DETAIL_LEVELS = ("geometric", "kinematic")


def add_arguments(bench: argparse.ArgumentParser) -> None:
    bench.add_argument(
        "--out", default="bench-out", help="directory for bench.json, perf-*.png, summary.md"
    )
    bench.add_argument(
        "--quick", action="store_true", help="smoke test: every section small (under a minute)"
    )
    bench.add_argument(
        "--sections",
        default=",".join(SECTIONS),
        help=f"comma-separated subset of {','.join(SECTIONS)}",
    )
    bench.add_argument(
        "--repeats", type=int, default=None, help="timings per measurement (default 5; quick 2)"
    )
    bench.add_argument("--seed", type=int, default=1)
    bench.add_argument(
        "--level",
        choices=DETAIL_LEVELS,
        default=None,
        help="instead: one level's detailed speed report as text (no files)",
    )
    bench.add_argument("--json", action="store_true", help="print the data as JSON")


def _detail(args: argparse.Namespace, repeats: int) -> int:
    if args.level == "kinematic":
        from experiments.bench.kinematic import format_kinematic_report, run_kinematic_benchmarks

        results = run_kinematic_benchmarks(repeats=repeats, seed=args.seed, quick=args.quick)
        print(json.dumps(results, indent=2) if args.json else format_kinematic_report(results))
        return 0
    from experiments.bench.geometric import format_report, run_benchmarks

    results = run_benchmarks(repeats=repeats, seed=args.seed, quick=args.quick)
    print(json.dumps(results, indent=2) if args.json else format_report(results))
    return 0


def run(args: argparse.Namespace) -> int:
    repeats = args.repeats if args.repeats is not None else (2 if args.quick else 5)
    if not 1 <= repeats <= 1000:
        raise UsageError(f"--repeats = {repeats} is outside the allowed range [1, 1000]")
    if args.level is not None:
        return _detail(args, repeats)
    from experiments.bench.suite import SuiteSettings, run_suite, sections_of, write_outputs
    from experiments.bench.summary import goal_lines

    try:
        settings = SuiteSettings(args.quick, repeats, args.seed, tuple(sections_of(args.sections)))
    except ValueError as exc:
        raise UsageError(f"--sections: {exc}") from None
    data = run_suite(settings, progress=lambda s: print(f"bench: {s} ...", file=sys.stderr))
    paths = write_outputs(data, Path(args.out))
    if args.json:
        print(json.dumps(data, indent=1))
    else:
        print("\n".join(goal_lines(data)))
        print(f"wrote {', '.join(str(p) for p in paths)}")
    return 0
