"""``partfeeder stress``: the numerical stress suite of the levels (issue 11).

Arguments only at import time (``--help`` stays fast); numba, shapely and the levels are
imported when the command runs.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from experiments.stress.case import LEVEL_NAMES

MAX_CASES = 10_000_000  # also where the composite-part cases' indices begin (generate.py)
MAX_WORKERS = 256
MAX_SEED = 2**32 - 1  # the seeds numpy draws from, as the verdict's and the sweeps' seeds
MIN_STEP, MAX_STEP = 1e-6, 0.1  # s: the range of a case file's h (experiments.stress.case)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``partfeeder stress``."""
    parser.add_argument("--seed", type=int, default=0, help="seed of the cases (default 0)")
    parser.add_argument(
        "--cases", type=int, default=300, help="number of peg cases (default 300; 0: none)"
    )
    parser.add_argument(
        "--composite",
        type=int,
        default=None,
        help="composite-part cases run besides the peg's --cases (a scaled cup, a non-convex "
        "outline, a plate with discs; default a third of --cases; 0: the peg's alone)",
    )
    parser.add_argument(
        "--ramp-foot",
        type=int,
        default=None,
        help="ramp-foot cases run besides the others (issue 35: a corner sliding at 2-20 "
        "length/s down a 40-75 degree ramp, or at 14-17 down a wall it is slightly inside, "
        "into the foot where it meets the floor; default a thirtieth of --cases; 0: none)",
    )
    parser.add_argument(
        "--step",
        type=float,
        default=None,
        help="run every case at this step h (s, 1e-6 to 0.1) instead of its own, with the "
        "same number of steps (default: each case's drawn h)",
    )
    parser.add_argument(
        "--levels",
        default=",".join(LEVEL_NAMES),
        help="comma-separated levels, dealt in turn (default geometric,kinematic,dynamic)",
    )
    parser.add_argument("--workers", type=int, default=1, help="worker processes (default 1)")
    parser.add_argument(
        "--out", type=Path, default=None, help="directory for the failing cases' YAML files"
    )
    parser.add_argument(
        "--case",
        type=int,
        default=None,
        help="instead: run case N of --seed alone; with --out its file is written, "
        "whatever its result (a case to --replay, or to send with a report); "
        f"composite case j is case {MAX_CASES} + j",
    )
    parser.add_argument("--replay", type=Path, default=None, help="run one case file again")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    parser.add_argument("--quiet", action="store_true", help="no progress bar or lines")


def _levels(text: str) -> tuple[str, ...]:
    """The levels of ``--levels``: each named once, none empty."""
    levels = tuple(name.strip() for name in text.split(","))
    bad = [name for name in levels if name not in LEVEL_NAMES]
    if bad or len(set(levels)) != len(levels):
        raise ValueError(
            f"--levels = {text!r}: expected a comma-separated subset of {', '.join(LEVEL_NAMES)}, "
            "each named once"
        )
    return levels


def _check(args: argparse.Namespace) -> tuple[str, ...]:
    if not 0 <= args.cases <= MAX_CASES:
        raise ValueError(f"--cases = {args.cases} is outside the allowed range [0, {MAX_CASES}]")
    if args.ramp_foot is not None and not 0 <= args.ramp_foot <= MAX_CASES:
        raise ValueError(
            f"--ramp-foot = {args.ramp_foot} is outside the allowed range [0, {MAX_CASES}]"
        )
    if args.step is not None and not MIN_STEP <= args.step <= MAX_STEP:
        raise ValueError(
            f"--step = {args.step} is outside the allowed range [{MIN_STEP}, {MAX_STEP}]"
        )
    if not 1 <= args.workers <= MAX_WORKERS:
        raise ValueError(
            f"--workers = {args.workers} is outside the allowed range [1, {MAX_WORKERS}]"
        )
    if not 0 <= args.seed <= MAX_SEED:
        raise ValueError(f"--seed = {args.seed} is outside the allowed range [0, {MAX_SEED}]")
    if args.composite is not None and not 0 <= args.composite <= MAX_CASES:
        raise ValueError(
            f"--composite = {args.composite} is outside the allowed range [0, {MAX_CASES}]"
        )
    if args.case is not None and not 0 <= args.case < 3 * MAX_CASES:
        raise ValueError(
            f"--case = {args.case} is outside the allowed range [0, {3 * MAX_CASES - 1}] "
            f"(from {MAX_CASES}: the composite-part cases; from {2 * MAX_CASES}: ramp-foot)"
        )
    if args.case is not None and args.replay is not None:
        raise ValueError("--case and --replay: give one of them")
    return _levels(args.levels)


def run(args: argparse.Namespace) -> int:
    """Run the suite (or replay one case); 0 when every hard bound holds, 1 when one is broken,
    2 on bad input."""
    try:
        levels = _check(args)
    except ValueError as exc:
        print(f"partfeeder stress: error: {exc}", file=sys.stderr)
        return 2
    if args.replay is not None:
        return _replay(args)
    if args.case is not None:
        return _one_case(args, levels)
    from experiments.cli.kernels import compile_once

    compile_once(levels)  # here, once: the workers' warm-up then only loads the kernels
    from experiments.stress.generate import generate_case
    from experiments.stress.pool import progress_bar, run_cases
    from experiments.stress.report import summary, table, write_case

    composite = args.cases // 3 if args.composite is None else args.composite
    ramp = args.cases // 30 if args.ramp_foot is None else args.ramp_foot
    total = args.cases + composite + ramp
    if total == 0:
        print(
            "partfeeder stress: error: no cases (--cases, --composite, --ramp-foot)",
            file=sys.stderr,
        )
        return 2
    update, close = (None, lambda: None) if args.quiet else progress_bar(total)
    try:
        results = run_cases(
            args.seed, args.cases, levels, args.workers, update, composite, ramp, args.step
        )
    finally:
        close()
    data = summary(results, args.seed)
    if args.out is not None:
        data["files"] = [
            str(write_case(args.out, generate_case(args.seed, r["index"], levels, args.step), r))
            for r, _ in results
            if r["hard"] and not str(r["error"]).startswith("generate:")
        ]  # a case the generator could not make has no file: its record names the fault
    print(json.dumps(data, indent=1) if args.json else table(data))
    return 1 if data["hard_failures"] else 0


def _one_case(args: argparse.Namespace, levels: tuple[str, ...]) -> int:
    """Case ``--case`` of ``--seed`` (the same case the full run deals at that index): its
    record, and with ``--out`` its replayable file whatever the result."""
    from experiments.stress.generate import generate_case
    from experiments.stress.report import write_case
    from experiments.stress.runner import record_of

    case = generate_case(args.seed, args.case, levels, args.step)
    record = record_of(case)
    path = None if args.out is None else write_case(args.out, case, record)
    if args.json:
        print(json.dumps({"record": record, "file": None if path is None else str(path)}, indent=1))
    else:
        for key, value in record.items():
            print(f"{key}: {value}")
        if path is not None:
            print(f"case file: {path}")
    return 1 if record["hard"] else 0


def _replay(args: argparse.Namespace) -> int:
    from experiments.stress.case import CaseError
    from experiments.stress.report import read_case
    from experiments.stress.runner import record_of

    try:
        case, stored = read_case(args.replay)
    except CaseError as exc:
        print(f"partfeeder stress: error: {exc}", file=sys.stderr)
        return 2
    record = record_of(case)
    same = stored is not None and record == stored
    if args.json:
        print(json.dumps({"record": record, "same_as_stored": same}, indent=1))
    else:
        for key, value in record.items():
            print(f"{key}: {value}")
        print("same record as stored" if same else "record differs from the stored one")
    return 1 if record["hard"] else 0
