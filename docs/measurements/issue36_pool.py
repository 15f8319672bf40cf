"""Issue 36's pool of paired drops: the screen's false-fail rate at the verdict's step,
measured by resampling instead of by re-running sweeps.

The screen's decisions depend only on the outcomes of the drops it sees (success, failure or
a simulation fault per drop of an entry), so a pool of perturbed drops of a design, each
simulated once at the screen's step (h = 4e-3) and once at the verdict's (h = 1e-3) on the
same draw, lets any number of screens be replayed by drawing from it
(:mod:`experiments.drop.resampled`). Three phases, each writing its part of the JSON:

1. ``working``: the SPRT verdict (default.yaml's passive rung, the sweep's verdict seed) of
   each of the first ``--designs`` Halton designs (seed 0): the designs that work.
2. ``pool``: for every design that works, ``--draws`` draws (``--near`` of them for the
   designs named by ``--near-ids``: those nearest the threshold), each a made feeder, a
   friction and both entries' noise, dropped from both entries at both steps. Outcomes are
   stored as strings per entry and step: ``1`` success, ``0`` failure, ``x`` fault.
3. analysis: ``python docs/measurements/issue36_replay.py`` (no simulation).

Run (about 5 minutes of CPU on one core, at the lowest priority):
``nice python docs/measurements/issue36_pool.py --out docs/measurements/issue36_pool.json``.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from experiments.drop.outcomes import SIMULATION_FAULT
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import design_verdict, entry_drop, made_feeders
from experiments.drop.verdict_settings import VerdictSettings
from experiments.sweep.job import verdict_seed
from feeders.design import DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign
from feeders.halton import halton_points
from feeders.scene_yaml import environment_from_dict
from validity.dynamic import DynamicLevel

FEEDER = {"friction": 0.05, "restitution": 0.3}  # default.yaml's feeder (drops use no inputs)
VERDICT = VerdictSettings(
    rule="sprt", works_p=0.95, fails_p=0.8, error=0.01, min_drops=1, batch=1, max_drops=200
)
STEPS = (4e-3, 1e-3)  # the screen's, the verdict's
POOL_SEED = 36  # the pool's draws: apart from the sweep's verdict and screen seeds


def environment() -> dict:
    return environment_from_dict(dict(FEEDER))


def working_designs(count: int) -> dict[int, dict]:
    """The SPRT verdict of the first ``count`` Halton designs (seed 0): id -> decision and
    per-entry successes of the designs that work."""
    points = halton_points(count, 0)
    out = {}
    for d in range(count):
        env = environment()
        part, friction = env.pop("part"), env.pop("friction")
        try:
            v = design_verdict(
                DesignParameters.from_vector(points[d]),
                part=part,
                friction=friction,
                settings=VERDICT,
                seed=verdict_seed(0, d),
                **env,
            )
        except DegenerateDesign:
            continue
        if v.decision == "works":
            out[d] = {o: [v.successes(o), v.drops] for o in ORIENTATIONS}
    return out


def pool_of(design_id: int, draws: int, count: int) -> dict[str, dict[str, str]]:
    """``draws`` paired drops of design ``design_id``: entry -> step -> outcome string."""
    values = halton_points(count, 0)[design_id]
    env = environment()
    part, friction = env.pop("part"), env.pop("friction")
    make_scene = made_feeders(DesignParameters.from_vector(values), part, friction, **env)
    seed = int(np.random.SeedSequence([POOL_SEED, design_id]).generate_state(1)[0] % (2**31 - 1))
    out = {o: {str(h): [] for h in STEPS} for o in ORIENTATIONS}
    for i in range(draws):
        perturbation = draw(Perturbations(), seed, i, len(ORIENTATIONS))
        try:
            scene = make_scene(perturbation)
        except DegenerateDesign:
            for o in ORIENTATIONS:
                for h in STEPS:
                    out[o][str(h)].append("0")
            continue
        for h in STEPS:
            level = DynamicLevel(scene, step=h)
            for k, o in enumerate(ORIENTATIONS):
                result = entry_drop(scene, level, o, perturbation, k, VERDICT.t_max)
                mark = "x" if result.outcome == SIMULATION_FAULT else "01"[result.success]
                out[o][str(h)].append(mark)
    return {o: {h: "".join(v) for h, v in steps.items()} for o, steps in out.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--draws", type=int, default=100)
    parser.add_argument("--near", type=int, default=600)
    parser.add_argument("--near-ids", default="181,214")
    args = parser.parse_args()
    data = json.loads(args.out.read_text()) if args.out.exists() else {}
    cpu = time.process_time()
    if "working" not in data:
        data["working"] = working_designs(args.designs)
        data["working_cpu_s"] = time.process_time() - cpu
        args.out.write_text(json.dumps(data, indent=1))
        print(f"{len(data['working'])} designs work ({data['working_cpu_s']:.0f} s)", flush=True)
    near = {int(d) for d in args.near_ids.split(",") if d}
    data.setdefault("pool", {})
    for d in sorted({int(d) for d in data["working"]} | near):
        draws = args.near if d in near else args.draws
        if str(d) in data["pool"] and len(data["pool"][str(d)][ORIENTATIONS[0]]["0.001"]) >= draws:
            continue
        t = time.process_time()
        data["pool"][str(d)] = pool_of(d, draws, args.designs)
        args.out.write_text(json.dumps(data, indent=1))
        print(f"design {d}: {draws} draws, {time.process_time() - t:.1f} s", flush=True)
    data["pool_settings"] = {"seed": POOL_SEED, "steps": list(STEPS), "feeder": FEEDER}
    args.out.write_text(json.dumps(data, indent=1))


if __name__ == "__main__":
    main()
