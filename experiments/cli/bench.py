"""``partfeeder bench``: run time against error. Work-precision diagrams of the analytic
scenes beside MuJoCo and pymunk (when installed), the feeder's convergence, the ladder's cost
against its verdicts' error, speed tables; or, with ``--level``, one level's detailed speed;
or, with ``--agreement``, the same perturbed feeder drops in partfeeder, MuJoCo and pymunk and
how they agree (:mod:`experiments.bench.agreement`; with ``--family``, a device family's
verdict drops of its own part, and ``--arbiter``, Box2D on the drops they dispute: issue 35);
or, with ``--trial``, the cost of one
verdict trial and its parts (:mod:`experiments.bench.trial_cost`); or, with ``--verdict``, the
cost of deciding designs by the full verdict alone and by the screen then the verdict
(:mod:`experiments.bench.verdict_cost`); or, with ``--part``, a step's cost for the cup (three
pieces) against the peg (:mod:`experiments.bench.part_cost`). ``--quick`` makes every mode
small (the suite's sections, ``--level``, ``--agreement``, and the N of ``--trial``,
``--verdict``, ``--part`` unless given) and writes no files unless ``--out`` is given."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from experiments.cli.kernels import compile_once
from experiments.cli.usage import UsageError, check_count, check_out_dir, check_seed

SECTIONS = ("analytic", "speed", "feeder", "ladder")  # experiments.bench.suite.SECTIONS
DETAIL_LEVELS = ("geometric", "kinematic")
DEFAULT_OUT = "bench-out"  # the suite's and --agreement's files, unless --quick


class DefaultN:
    """The value of ``--trial`` / ``--verdict`` / ``--part`` given without N: the mode's
    default, full or quick (a class, not a string: argparse would convert a string const)."""


# N of --trial, --verdict, --part: full, and with --quick (a smoke test of seconds)
COUNTS = {"trial": (200, 20), "verdict": (200, 10), "part": (50, 5)}


def add_arguments(bench: argparse.ArgumentParser) -> None:
    bench.add_argument(
        "--out",
        default=None,
        help=f"directory for bench.json, perf-*.png, summary.md (default {DEFAULT_OUT}; with "
        "--quick none: the results are printed, no file is written unless --out is given)",
    )
    bench.add_argument(
        "--quick",
        action="store_true",
        help="smoke test: every section small (under a minute), and with --trial, --verdict, "
        "--part their quick N ("
        + ", ".join(f"{k} {q}" for k, (_, q) in COUNTS.items())
        + ") unless N is given",
    )
    bench.add_argument(
        "--sections",
        default=",".join(SECTIONS),
        help=f"comma-separated subset of {','.join(SECTIONS)}",
    )
    bench.add_argument(
        "--repeats", type=int, default=None, help="timings per measurement (default 5; quick 2)"
    )
    bench.add_argument(
        "--seed", type=int, default=1, help="seed of the workloads, in [1, 2^31 - 1] (default 1)"
    )
    bench.add_argument(
        "--level",
        choices=DETAIL_LEVELS,
        default=None,
        help="instead: one level's detailed speed report as text (no files)",
    )
    bench.add_argument(
        "--trial",
        type=int,
        nargs="?",
        const=DefaultN,
        default=None,
        metavar="N",
        help="instead: median ms of a verdict trial of table3 over N trials (default 200) and "
        "each part's share, as text (no files)",
    )
    bench.add_argument(
        "--verdict",
        type=int,
        nargs="?",
        const=DefaultN,
        default=None,
        metavar="N",
        help="instead: the worker time of deciding the first N Halton designs (default 200) by "
        "the full verdict alone (Wilson, SPRT) and by the screen then the SPRT verdict, in one "
        "run, with their ratios, as text (no files)",
    )
    bench.add_argument(
        "--part",
        type=int,
        nargs="?",
        const=DefaultN,
        default=None,
        metavar="N",
        help="instead: median us per dynamic step of the cup (three pieces) through the "
        "fig1-cup device and of the peg through table3 over N verdict trials each (default 50), "
        "and their ratio, as text (no files)",
    )
    bench.add_argument(
        "--halton-seed",
        type=int,
        default=0,
        help="--verdict's designs: the Halton seed (default 0, the default sweep's)",
    )
    bench.add_argument("--json", action="store_true", help="print the data as JSON")
    agreement = bench.add_argument_group(
        "agreement", "the same perturbed drops in partfeeder, MuJoCo and pymunk (issue 26)"
    )
    agreement.add_argument(
        "--agreement",
        action="store_true",
        help="instead: the agreement suite (agreement.json, .md, .png in --out)",
    )
    agreement.add_argument(
        "--design",
        action="append",
        default=None,
        metavar="DESIGN",
        help="a preset, halton:SEED:INDEX or 12 values; repeat for more (default: the suite's "
        "set of presets and Halton designs)",
    )
    agreement.add_argument(
        "--trials", type=int, default=None, help="trials per design and entry (default 20)"
    )
    agreement.add_argument(
        "--draw-seed", type=int, default=0, help="seed of the perturbation draws (default 0)"
    )
    agreement.add_argument(
        "--peer-step", type=float, default=1e-4, help="MuJoCo's and pymunk's step h in s"
    )
    agreement.add_argument(
        "--engines",
        default="partfeeder,mujoco,pymunk",
        help="comma-separated subset of partfeeder,mujoco,pymunk",
    )
    agreement.add_argument("--workers", type=int, default=1, help="worker processes (default 1)")
    agreement.add_argument(
        "--family",
        type=Path,
        default=None,
        help="a device family YAML file (docs/families.md), or the name of one packaged with "
        "partfeeder (fig1, fig1-cup): the family verdict's drops of its part through its "
        "devices, the peers' bodies built from the part's pieces (issue 35); --design then "
        "takes default, halton:SEED:INDEX or the family's values",
    )
    agreement.add_argument(
        "--arbiter",
        default=None,
        metavar="SCALES",
        help="with --family: then drop again in Box2D (pip install box2d), at each of these "
        "comma-separated scales (e.g. 4,8: the scene x S into Box2D's 0.1-10 m), the drops "
        "where the engines disagree on success and a control set where they agree",
    )
    agreement.add_argument(
        "--pymunk-radius",
        type=float,
        default=None,
        help="with --family: pymunk's wall segment radius, the rounding of the walls' convex "
        "corners (default 1e-3, length)",
    )


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


def _count(args: argparse.Namespace, option: str) -> int:
    """The N of ``--trial`` / ``--verdict`` / ``--part``: as given, else the mode's default
    (:data:`COUNTS`: the full one, or the quick one with ``--quick``), checked."""
    value = getattr(args, option)
    if value is DefaultN:
        value = COUNTS[option][1 if args.quick else 0]
    check_count(value, f"--{option}", 100_000)
    return int(value)


def _out(args: argparse.Namespace) -> Path | None:
    """Where the files go: ``--out``, else bench-out, or nowhere with ``--quick`` (a smoke
    test leaves no directory behind unless asked: issue 39)."""
    if args.out is not None:
        return Path(args.out)
    return None if args.quick else Path(DEFAULT_OUT)


def _part(args: argparse.Namespace) -> int:
    """``--part N``: a step's cost for a part of several pieces against the peg (issue 24)."""
    count = _count(args, "part")
    check_seed(args.seed)
    from experiments.bench.part_cost import format_part_cost, part_cost

    results = part_cost(count, args.seed)
    print(json.dumps(results, indent=2) if args.json else format_part_cost(results))
    return 0


def _trial(args: argparse.Namespace) -> int:
    """``--trial N``: the cost of one verdict trial and its parts (issue 21)."""
    count = _count(args, "trial")
    check_seed(args.seed)
    from experiments.bench.trial_cost import format_trial_cost, trial_cost

    results = trial_cost("table3", count, args.seed)
    print(json.dumps(results, indent=2) if args.json else format_trial_cost(results))
    return 0


def _verdict(args: argparse.Namespace) -> int:
    """``--verdict N``: the full verdict alone against the screened one (issue 21)."""
    count = _count(args, "verdict")
    check_count(args.halton_seed, "--halton-seed", 2**31 - 1, low=0)
    from experiments.bench.verdict_cost import format_verdict_cost, verdict_cost

    results = verdict_cost(count, args.halton_seed)
    print(json.dumps(results, indent=2) if args.json else format_verdict_cost(results))
    return 0


AGREEMENT_ENGINES = ("partfeeder", "mujoco", "pymunk")
QUICK_DESIGNS = ("table3", "halton:0:3")
QUICK_TRIALS = 2


def _agreement(args: argparse.Namespace) -> int:
    """``--agreement``: checks the options (one line each), then runs the suite."""
    engines = tuple(e.strip() for e in args.engines.split(",") if e.strip())
    unknown = [e for e in engines if e not in AGREEMENT_ENGINES]
    if unknown or len(engines) < 2 or len(set(engines)) != len(engines):
        raise UsageError(
            f"--engines = {args.engines!r}: two or more of {','.join(AGREEMENT_ENGINES)}"
        )
    trials = args.trials if args.trials is not None else (QUICK_TRIALS if args.quick else 20)
    if not 1 <= trials <= 10_000:
        raise UsageError(f"--trials = {trials} is outside the allowed range [1, 10000]")
    if not 0 <= args.draw_seed < 2**32:
        raise UsageError(f"--draw-seed = {args.draw_seed} is outside the allowed range [0, 2^32)")
    if not 1e-6 <= args.peer_step <= 1e-2:  # also refuses nan
        raise UsageError(
            f"--peer-step = {args.peer_step!r} is outside the allowed range [1e-6, 0.01]"
        )
    if not 1 <= args.workers <= 64:
        raise UsageError(f"--workers = {args.workers} is outside the allowed range [1, 64]")
    if args.family is None and args.pymunk_radius is not None:
        raise UsageError("--pymunk-radius needs --family (the peg feeder's radius is fixed)")
    if args.family is None and args.arbiter is not None:
        raise UsageError("--arbiter needs --family")
    scales = _scales(args.arbiter) if args.arbiter is not None else ()
    family_file = _family_file(args) if args.family is not None else None
    out = _out(args)
    if out is not None:
        check_out_dir(out)
    from experiments.bench.peers import mujoco_engine, pymunk_engine

    for module in (mujoco_engine, pymunk_engine):
        if module.ENGINE in engines and not module.available():
            raise UsageError(
                f"{module.ENGINE} is not installed (pip install 'partfeeder[bench]'), or leave it "
                "out with --engines"
            )
    if family_file is not None:
        return _family_agreement(args, family_file, trials, engines, out, scales)
    from experiments.bench.agreement.designs import default_designs, named_design
    from experiments.bench.agreement.suite import AgreementSettings, agreement_data
    from feeders.feeder import DegenerateDesign, build_feeder

    tokens = args.design or (QUICK_DESIGNS if args.quick else None)
    designs = [named_design(t) for t in tokens] if tokens else default_designs()
    for d in designs:
        try:
            build_feeder(d.design)
        except DegenerateDesign as exc:
            raise UsageError(f"--design {d.name}: {exc}") from None
    settings = AgreementSettings(
        trials=trials, seed=args.draw_seed, peer_step=args.peer_step, engines=engines
    )
    if "partfeeder" in engines and args.workers > 1:
        compile_once(["dynamic"])  # before the workers start: they then only load them
    data = agreement_data(
        designs,
        settings,
        args.workers,
        progress=lambda s: print(f"bench --agreement: {s}", file=sys.stderr),
    )
    return _agreement_output(data, out, args.json)


PYMUNK_RADIUS_RANGE = (1e-5, 0.05)  # length: the rounding of the walls' convex corners


def _family_file(args: argparse.Namespace) -> str:
    """The file ``--family`` names (a file or a packaged family), loaded once to check it, and
    ``--pymunk-radius`` checked: UsageError (one line) otherwise."""
    from experiments.cli.scenes import family_path
    from feeders.device_family import FamilyError, load_family

    path = family_path(args.family)
    try:
        load_family(path)
    except FamilyError as exc:
        raise UsageError(str(exc)) from None
    radius = args.pymunk_radius
    if radius is not None and not PYMUNK_RADIUS_RANGE[0] <= radius <= PYMUNK_RADIUS_RANGE[1]:
        raise UsageError(
            f"--pymunk-radius = {radius!r} is outside the allowed range "
            f"[{PYMUNK_RADIUS_RANGE[0]:g}, {PYMUNK_RADIUS_RANGE[1]:g}]"
        )
    return str(path)


BOX2D_SCALE_RANGE = (0.1, 100.0)


def _scales(text: str) -> tuple[float, ...]:
    """``--arbiter``'s scales, checked, and Box2D importable: UsageError (one line) otherwise."""
    from experiments.bench.peers import box2d_engine

    try:
        scales = tuple(float(v) for v in text.split(","))
    except ValueError:
        scales = ()
    low, high = BOX2D_SCALE_RANGE
    if not scales or not all(low <= v <= high for v in scales):  # also refuses nan
        raise UsageError(
            f"--arbiter = {text!r}: comma-separated scales, each in [{low:g}, {high:g}]"
        )
    if not box2d_engine.available():
        raise UsageError("--arbiter: Box2D is not installed (pip install box2d)")
    return scales


def _family_agreement(
    args: argparse.Namespace,
    family_file: str,
    trials: int,
    engines: tuple,
    out: Path | None,
    scales: tuple[float, ...] = (),
) -> int:
    """``--agreement --family``: the family verdict's drops in every engine (issue 35)."""
    from experiments.bench.agreement.family import (
        FamilySuite,
        default_family_designs,
        family_agreement_data,
        family_design,
    )
    from experiments.bench.agreement.suite import AgreementSettings
    from experiments.bench.peers.compound import ROUNDING
    from feeders.device_family import load_family
    from feeders.feeder import DegenerateDesign

    family = load_family(family_file)
    tokens = args.design or (("default",) if args.quick else default_family_designs(family))
    designs = []
    for token in tokens:
        try:
            design = family_design(family, token)
            family.build(design.values)
        except (ValueError, DegenerateDesign) as exc:
            raise UsageError(f"--design {token}: {exc}") from None
        designs.append(design)
    settings = AgreementSettings(
        trials=trials, seed=args.draw_seed, peer_step=args.peer_step, engines=engines
    )
    radius = ROUNDING[0] if args.pymunk_radius is None else args.pymunk_radius
    if "partfeeder" in engines and args.workers > 1:
        compile_once(["dynamic"])
    data = family_agreement_data(
        FamilySuite(family_file, settings, radius),
        designs,
        args.workers,
        progress=lambda s: print(f"bench --agreement: {s}", file=sys.stderr),
    )
    if scales:
        from experiments.bench.agreement.arbiter import arbitrate

        data["arbiter"] = arbitrate(
            data,
            scales,
            args.peer_step,
            progress=lambda s: print(f"bench --agreement: {s}", file=sys.stderr),
        )
    return _agreement_output(data, out, args.json)


def _agreement_output(data: dict, out: Path | None, as_json: bool) -> int:
    """The agreement's tables printed (Markdown, or JSON with ``--json``) and its files
    written to ``out`` (none without), for the feeder's and a family's runs alike."""
    from experiments.bench.agreement.report import markdown, write_outputs, written_data

    written = written_data(data)
    paths = write_outputs(data, out) if out is not None else []
    if as_json:
        print(json.dumps(written["tables"], indent=1))
    else:
        print(markdown(written))
        _wrote(paths)
    return 0


def _wrote(paths: list[Path]) -> None:
    """Which files were written, or that none was (``--quick`` without ``--out``)."""
    if paths:
        print(f"wrote {', '.join(str(p) for p in paths)}")
    else:
        print("bench: no files written (--quick without --out)", file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    """Every argument is checked before any work or output (issue 23: an ``--out`` that could
    not be written was refused only after a section had run and printed its progress)."""
    if args.agreement:
        return _agreement(args)
    if args.trial is not None:
        return _trial(args)
    if args.part is not None:
        return _part(args)
    if args.verdict is not None:
        return _verdict(args)
    repeats = args.repeats if args.repeats is not None else (2 if args.quick else 5)
    if not 1 <= repeats <= 1000:
        raise UsageError(f"--repeats = {repeats} is outside the allowed range [1, 1000]")
    check_seed(args.seed)  # the workloads' NumPy seed and the ladder section's OMPL seed
    if args.level is not None:
        return _detail(args, repeats)
    from experiments.bench.suite import SuiteSettings, run_suite, sections_of, write_outputs
    from experiments.bench.summary import goal_lines

    try:
        settings = SuiteSettings(args.quick, repeats, args.seed, tuple(sections_of(args.sections)))
    except ValueError as exc:
        raise UsageError(f"--sections: {exc}") from None
    out = _out(args)
    if out is not None:
        check_out_dir(out)
    data = run_suite(settings, progress=lambda s: print(f"bench: {s} ...", file=sys.stderr))
    paths = write_outputs(data, out) if out is not None else []
    if args.json:
        print(json.dumps(data, indent=1))
    else:
        print("\n".join(goal_lines(data)))
        _wrote(paths)
    return 0
