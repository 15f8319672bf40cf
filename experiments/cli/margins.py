"""``partfeeder margins``: a design's tolerance margins, per design parameter (Table 2's box),
friction and the part's length, width and mass split, the interval over which P(both) stays
at or above the target with the others at nominal (:mod:`experiments.margins`); prints the
table and its cost, ``--json`` for scripts, ``--out`` for the chart and the JSON. A design
that does not work has no margins: its verdict is printed (exit 0). ``--family`` (with
``--values``) measures a device family's design instead: each of its parameters over the
family's box, and friction (no part axes: the family's entry poses are written for its
part)."""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path
from typing import Any

from experiments.cli.kernels import compile_once
from experiments.cli.scenes import load_family_design, load_scene
from experiments.cli.usage import UsageError, check_count, out_dir
from experiments.names import PRESET_NAMES

MAX_DROPS = 10_000
MAX_WORKERS = 1024  # as a sweep's workers
DEFAULT_DROPS = 20


def add_arguments(p: argparse.ArgumentParser) -> None:
    group = p.add_mutually_exclusive_group()
    group.add_argument(
        "--design",
        default=None,
        help=f"a paper preset ({', '.join(sorted(PRESET_NAMES))}) or the 12 values "
        "a,b,c,d,e,fx,fy,gx,gy,r,theta,alpha separated by commas (default: table3)",
    )
    group.add_argument(
        "--family",
        type=Path,
        default=None,
        help="a device family YAML file (docs/families.md), or the name of one packaged with "
        "partfeeder (fig1, fig1-cup): the margins of its default design, or of --values, over "
        "its parameters' box and friction",
    )
    p.add_argument(
        "--values",
        default=None,
        help="with --family: the design's values, comma-separated in the order of the "
        "family's parameters (default: the family's defaults)",
    )
    p.add_argument(
        "--drops",
        type=int,
        default=DEFAULT_DROPS,
        help="perturbed drops per entry at each value tried (the same seeded draws at every "
        f"value; default {DEFAULT_DROPS})",
    )
    p.add_argument(
        "--target", type=float, default=0.9, help="P(both) a value must reach (default 0.9)"
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the perturbation draws")
    p.add_argument(
        "--workers", type=int, default=None, help="worker processes (default: the CPU count)"
    )
    p.add_argument("--out", type=Path, default=None, help="directory for the chart and the JSON")
    p.add_argument("--json", action="store_true", help="print the margins as JSON")


def run(args: argparse.Namespace) -> int:
    """Every value is checked before numba or matplotlib is imported."""
    check_count(args.drops, "--drops", MAX_DROPS)
    if not 0.0 < args.target <= 1.0:
        raise UsageError(f"--target = {args.target} is outside the allowed range (0, 1]")
    check_count(args.seed, "--seed", 2**32 - 1, low=0)
    workers = (os.cpu_count() or 1) if args.workers is None else args.workers
    check_count(workers, "--workers", MAX_WORKERS)
    out = out_dir(args.out)
    subject = _subject(args)
    compile_once(["dynamic"])
    from experiments.cli.report import MarginsProgress
    from experiments.margins.measure import MarginSettings
    from experiments.margins.run import axes_of, margins_of

    settings = MarginSettings(drops=args.drops, target=args.target, seed=args.seed)
    t0 = time.perf_counter()
    bars = MarginsProgress(quiet=args.json)  # a bar on a terminal, lines in a log
    bars("margins", {"design": subject.name, "axes": len(axes_of(subject))})
    try:
        report = margins_of(
            subject, settings, workers, on_axis=lambda m: bars("axis", {"parameter": m.axis.name})
        )
        if not report.margins and bars.bar is not None:
            bars.bar.set_postfix_str("no axis measured: see the verdict at nominal", refresh=False)
    finally:
        bars.close()
    data = report.to_dict()
    files: list[str] = []
    if out is not None:
        stem = f"margins_{subject.name}".replace(" ", "_")
        if report.margins:
            from experiments.margins.figure import margins_chart

            files.append(str(margins_chart(data, out / f"{stem}.png")))
        files.append(str(out / f"{stem}.json"))
        data["files"] = files
        (out / f"{stem}.json").write_text(json.dumps(data, indent=2))
    data["files"] = files
    data["cost"]["total_wall_time_s"] = time.perf_counter() - t0
    if args.json:
        print(json.dumps(data, indent=2))
        return 0
    print(text_table(data))
    for f in files:
        print(f"wrote: {f}")
    return 0


def _subject(args: argparse.Namespace) -> Any:
    """The design ``--design`` or ``--family`` with ``--values`` names, checked (a family's
    design must build): UsageError naming the option."""
    if args.family is None:
        if args.values is not None:
            raise UsageError("--values needs --family (a design's values are --design's)")
        scene = load_scene(args.design, None)  # checked before the margins' heavy imports
        from experiments.margins.measure import Subject

        return Subject.of_scene(scene)
    from experiments.cli.scenes import family_path
    from experiments.margins.measure import FamilySubject
    from feeders.feeder import DegenerateDesign

    family, vector = load_family_design(args.family, args.values)
    try:
        family.build(vector)
    except DegenerateDesign as exc:
        raise UsageError(f"--values: the family's design cannot be built: {exc}") from None
    except ValueError as exc:  # a value that is not finite
        raise UsageError(f"--values: {exc}") from None
    from feeders.device_family import FamilyError
    from feeders.fields import read_text

    text = read_text(family_path(args.family), "device family", FamilyError)  # bounded
    return FamilySubject.of_family(family, text, vector)


def _number(value: float) -> str:
    return f"{value:.4g}"


def _end(side: dict) -> str:
    """One end of a margin: P(both) at the last value inside with its Wilson 95% interval,
    and at the first outside (``box edge`` when the edge itself is inside)."""
    e = side["last_inside"]
    text = f"{e['successes']}/{e['drops']} [{e['interval'][0]:.2f}, {e['interval'][1]:.2f}]"
    out = side["first_outside"]
    if out is None:
        return f"{text}, box edge"
    return f"{text}, {out['successes']}/{out['drops']} at {_number(out['value'])}"


def text_table(data: dict) -> str:
    """The margins as the table a designer reads (the JSON's content)."""
    v = data["verdict"]
    lo, hi = v["both"]["interval"]
    lines = [
        f"{data['design']} | verdict over {v['drops']} perturbed drops per entry (seed "
        f"{data['seed']}): {v['decision'].upper()}, P(both) {v['both']['p']:.3f} "
        f"[{lo:.3f}, {hi:.3f}] (target {data['target']:g})"
    ]
    if not data["works"]:
        from experiments.drop.sequential import short_of_working

        lines.append(f"the design {short_of_working(v['decision'])} at nominal: no margins")
        return "\n".join(line.rstrip() for line in lines)
    lines.append(
        f"margins: values where the estimated P(both) over {data['drops_per_value']} "
        f"drops per entry (the same draws at every value) stays >= {data['target']:g}, "
        "the others at nominal; ends within 1/128 of the box's width"
    )
    lines.append(
        f"{'parameter':<15}{'nominal':>9}{'allowed interval':>22}{'box':>20}"
        f"  {'P(both) at the low / high end: inside [95%], outside':<60}"
    )
    for row in data["margins"]:
        box = f"[{_number(row['box'][0])}, {_number(row['box'][1])}]"
        if row["interval"] is None:
            e = row["nominal_estimate"]
            lines.append(
                f"{row['parameter']:<15}{_number(row['nominal']):>9}{'none':>22}{box:>20}"
                f"   nominal: {e['successes']}/{e['drops']}, below the target"
            )
            continue
        low, high = row["interval"]
        ends = [_end(row[side]) for side in ("low", "high")]
        lines.append(
            f"{row['parameter']:<15}{_number(row['nominal']):>9}"
            f"{f'[{_number(low)}, {_number(high)}]':>22}{box:>20}"
            f"  {' / '.join(ends):<60}"
        )
    c = data["cost"]
    lines.append(
        f"cost: {c['trials']} trials ({c['drops']} drops), {c['wall_time_s']:.1f} s on "
        f"{c['workers']} worker(s)"
    )
    return "\n".join(line.rstrip() for line in lines)
