"""``partfeeder calibrate``: the geometric level's verdict on the paper's designs, and which
corners of the Table 2 box build; with ``--part``, the calibration of what the paper does not
give (peg length, width, mass split, friction; :mod:`experiments.verdicts.part_calibration`)."""

from __future__ import annotations

import argparse
from pathlib import Path

from experiments.cli.kernels import compile_once
from experiments.cli.usage import UsageError, check_count, check_time, out_dir

PART_FILES = ("part-calibration.md", "part-calibration.json", "calibration-landscape.png")


def add_arguments(cal: argparse.ArgumentParser) -> None:
    cal.add_argument("--runs", type=int, default=3, help="seeded RRT runs per orientation")
    cal.add_argument("--time", type=float, default=10.0, help="budget per run (s)")
    cal.add_argument(
        "--out",
        type=Path,
        default=None,
        help="directory for pictures of table3 and of the box's corners; with --part, for "
        f"the calibration's table, data and heatmap ({', '.join(PART_FILES)})",
    )
    cal.add_argument(
        "--part",
        action="store_true",
        help="calibrate the part and friction instead: the landscape over peg length, width, "
        "heavy fraction and mu (needs --out; ~15-20 min on 2 cores; --runs/--time not used)",
    )
    cal.add_argument("--quick", action="store_true", help="with --part: a tiny grid and budget")
    cal.add_argument(
        "--workers", type=int, default=2, help="with --part: worker processes (1: no pool)"
    )


def run(args: argparse.Namespace) -> int:
    """Every value is checked before numba, OMPL or matplotlib is imported."""
    if args.part:
        return _run_part(args)
    if args.quick:
        raise UsageError("--quick needs --part")
    check_count(args.runs, "--runs", 1000)
    check_time(args.time)
    out = out_dir(args.out)
    compile_once(["geometric"])
    from experiments.pictures.atlas import corner_census, draw_atlas
    from experiments.progress import bar as progress_bar
    from experiments.verdicts.calibration import calibrate, markdown_table
    from feeders.design import PRESETS
    from feeders.feeder import ORIENTATIONS

    with progress_bar(len(PRESETS) * len(ORIENTATIONS), "calibrating", "run") as bar:
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
    if out is not None:
        for path in draw_atlas(out):
            print(f"picture: {path}")
    return 0


def _run_part(args: argparse.Namespace) -> int:
    """The part calibration: landscape, choice, Markdown table + JSON + heatmap into --out."""
    import json

    if args.out is None:
        raise UsageError("--part needs --out DIR (where the table, data and heatmap go)")
    if not 1 <= args.workers <= 64:
        raise UsageError(f"--workers = {args.workers} is outside the allowed range [1, 64]")
    out = out_dir(args.out)
    assert out is not None
    compile_once(["geometric", "dynamic"])  # the paper's verdicts, then the passive drops
    from experiments.progress import PhaseBars
    from experiments.verdicts import part_calibration as pc

    grid, budget = (
        (pc.QUICK_GRID, pc.QUICK_BUDGET) if args.quick else (pc.FULL_GRID, pc.FULL_BUDGET)
    )
    with PhaseBars("part calibration", unit="job") as bars:
        landscape = pc.run_landscape(grid, budget, workers=args.workers, progress=bars.note)
    table = pc.markdown(landscape)
    md, data, png = (out / name for name in PART_FILES)
    md.write_text(table + "\n")
    data.write_text(json.dumps(landscape.to_dict(), indent=1) + "\n")
    pc.heatmap(landscape, png)
    print(table)
    for path in (md, data, png):
        print(f"written: {path}")
    return 0
