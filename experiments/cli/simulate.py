"""``partfeeder simulate``: the passive drop of the part through a feeder with the dynamic
level, per entry orientation; prints each run and Eq. 10's objective, can write a snapshot
strip and an animation. With ``--samples N`` it gives the design's verdict instead: the
success probability per entry over up to N perturbed drops (:mod:`experiments.drop.verdict`)."""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING

from experiments.cli.kernels import compile_once
from experiments.cli.scenes import add_scene_arguments, load_scene, orientations
from experiments.cli.usage import UsageError, check_count, check_time, out_dir

if TYPE_CHECKING:
    from feeders.scene import Scene

MAX_SAMPLES = 100_000
MAX_RECORDED_STEPS = 10_000_000  # validity.moving_part's (tests/experiments/cli check they agree)


def add_arguments(sim: argparse.ArgumentParser) -> None:
    add_scene_arguments(sim)
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
    sim.add_argument(
        "--samples",
        type=int,
        default=0,
        help="the verdict over up to N perturbed drops per entry (sequential: stops when "
        "decided; default 0: the nominal drops only)",
    )
    sim.add_argument(
        "--target", type=float, default=0.9, help="success probability a design must clear"
    )
    sim.add_argument("--seed", type=int, default=0, help="seed of the perturbations")


def run(args: argparse.Namespace) -> int:
    """Every value is checked before numba or matplotlib is imported (issue 22: a bad
    ``--samples`` waited 0.3 s for them)."""
    if not (1e-6 <= args.step <= 0.1):
        raise UsageError(f"--step = {args.step} is outside the allowed range [1e-06, 0.1] s")
    check_time(args.time)
    check_count(args.seed, "--seed", 2**32 - 1, low=0)  # numpy's draws, as stress's
    steps = math.ceil(args.time / args.step - 1e-9)
    if steps > MAX_RECORDED_STEPS:
        raise UsageError(
            f"--time / --step = {steps} steps; a recorded drop has at most "
            f"{MAX_RECORDED_STEPS}: a shorter --time or a larger --step"
        )
    if args.samples:
        check_count(args.samples, "--samples", MAX_SAMPLES)
        if not 0.0 <= args.target <= 1.0:
            raise UsageError(f"--target = {args.target} is outside the allowed range [0, 1]")
    scene = load_scene(args.design, args.scene, args.family, args.values)
    if args.samples:
        compile_once(["dynamic"])
        return _verdict(scene, args)
    chosen = orientations(scene, args.orientation)
    out = out_dir(args.out, inputs=[args.scene] if args.scene else [])
    compile_once(["dynamic"])
    from experiments.drop.passive import eq10_objective, passive_drop

    results = [passive_drop(scene, o, step=args.step, t_max=args.time) for o in chosen]
    files: list[str] = []
    if out is not None:
        from experiments.drop.pictures import drop_animation, drop_strip

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


def _verdict(scene: Scene, args: argparse.Namespace) -> int:
    """Print (or write as JSON) the design's passive verdict."""
    from experiments.drop.verdict import VerdictSettings, design_verdict, scene_verdict

    settings = VerdictSettings(
        target=args.target,
        min_drops=min(VerdictSettings.min_drops, args.samples),
        max_drops=args.samples,
        step=args.step,
        t_max=args.time,
    )
    if args.family is not None:  # made to tolerance as the family's parameters say
        from experiments.cli.scenes import load_family_design
        from experiments.drop.family_verdict import family_verdict

        family, vector = load_family_design(args.family, args.values)
        verdict = family_verdict(family, vector, settings, seed=args.seed)
    elif scene.design is not None:
        verdict = design_verdict(
            scene.design,
            scene.part,
            scene.friction,
            settings,
            seed=args.seed,
            gravity=scene.gravity,
            inputs=scene.inputs,
            restitution=scene.restitution,
            name=scene.name,
        )
    else:
        verdict = scene_verdict(scene, settings, seed=args.seed)
    report = verdict.to_dict()
    if args.json:
        print(json.dumps({"scene": scene.name, **report}, indent=2))
        return 0
    print(
        f"{scene.name} | passive verdict over {verdict.drops} perturbed drops "
        f"(seed {args.seed}, h = {args.step:g} s): {verdict.decision.upper()} "
        f"(target {args.target:g})"
    )
    print(f"{'entry':<16}{'P(success)':>11}{'95% interval':>18}{'mean T (s)':>12}")
    for o, row in report["orientations"].items():
        lo, hi = row["interval"]
        t = "-" if row["mean_exit_time_s"] is None else f"{row['mean_exit_time_s']:.3f}"
        print(f"{o:<16}{row['p']:>11.3f}{f'[{lo:.3f}, {hi:.3f}]':>18}{t:>12}")
    lo, hi = report["both"]["interval"]
    print(f"{'both entries':<16}{report['both']['p']:>11.3f}{f'[{lo:.3f}, {hi:.3f}]':>18}")
    print("where the drops ended (entry -> outcome: drops):")
    for o, row in report["transitions"].items():
        ends = ", ".join(f"{c}: {n}" for c, n in row.items() if n)
        print(f"  {o}: {ends}")
    return 0
