"""``partfeeder calibrate``: the geometric level's verdict on the paper's designs, and which
corners of the Table 2 box build."""

from __future__ import annotations

import argparse
from pathlib import Path

from experiments.cli.usage import UsageError, check_time


def add_arguments(cal: argparse.ArgumentParser) -> None:
    cal.add_argument("--runs", type=int, default=3, help="seeded RRT runs per orientation")
    cal.add_argument("--time", type=float, default=10.0, help="budget per run (s)")
    cal.add_argument(
        "--out",
        type=Path,
        default=None,
        help="directory for pictures of table3 and of the box's corners",
    )


def run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from experiments.pictures.atlas import corner_census, draw_atlas
    from experiments.verdicts.calibration import calibrate, markdown_table
    from feeders.design import PRESETS
    from feeders.feeder import ORIENTATIONS

    if args.runs < 1:
        raise UsageError(f"--runs = {args.runs} must be >= 1")
    check_time(args.time)
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
