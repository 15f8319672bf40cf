"""``partfeeder bench --part``: what a step of the dynamic level costs for a part of several
pieces against the peg (issue 24).

The cup (:func:`feeders.cup.cup_part`, three rectangles) is dropped through the packaged
fig1-cup family's default device, the peg (one rectangle to the kernels) through the paper's
table3, each in the verdict's perturbed trials (devices made to tolerance, both entries, the
verdict's step). Reported per part: the median over trials of the drops' wall time per step
(microseconds; the compiled run alone, as :func:`experiments.drop.passive.passive_drop` times
it), the share of steps in contact, and the ratio of the medians. The two parts' trials are
interleaved so that a load on the machine falls on both. One process, one core.

Measure, never assert: these return numbers for reports, they judge nothing.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable, Sequence

from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.passive import passive_drop
from experiments.drop.perturbations import DropDraw, draw
from experiments.drop.verdict import entry_state, made_feeders
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import PARAMETER_NAMES, preset
from feeders.device_family import load_family, packaged_family
from feeders.feeder import ORIENTATIONS
from feeders.scene import Scene
from validity.dynamic import DynamicLevel

FAMILY = "fig1-cup"
WARM_TRIALS = 3  # trials run first (kernels loaded); not timed


def _trial_steps(
    make_scene: Callable[[DropDraw], Scene],
    orientations: Sequence[str],
    parameters: int,
    settings: VerdictSettings,
    seed: int,
    index: int,
) -> tuple[float, int, int]:
    """``(seconds, steps, contact steps)`` of trial ``index``'s drops (both entries)."""
    d = draw(settings.perturbations, seed, index, len(orientations), parameters)
    scene = make_scene(d)
    level = DynamicLevel(scene, step=settings.step)
    seconds, steps, contact = 0.0, 0, 0
    for k, orientation in enumerate(orientations):
        start = entry_state(
            level, scene.start(orientation), d.entry_offsets[k], d.entry_velocities[k]
        )
        result = passive_drop(scene, orientation, t_max=settings.t_max, level=level, start=start)
        seconds += result.wall_time
        steps += result.steps
        contact += int(result.trajectory.summary["contact_steps"])
    return seconds, steps, contact


def part_cost(trials: int = 50, seed: int = 0) -> dict:
    """Per part (``cup``, ``peg``): ``{"device", "us_per_step", "steps", "contact_share"}``
    over ``trials`` verdict trials with ``seed``, and ``ratio`` (cup's median over the
    peg's)."""
    settings = VerdictSettings()
    family = load_family(packaged_family(FAMILY) or FAMILY)
    cases = {
        "cup": (
            f"{FAMILY} default",
            made_devices(family, family.default()),
            entry_names(family),
            len(family.vector_names),
        ),
        "peg": ("table3", made_feeders(preset("table3")), ORIENTATIONS, len(PARAMETER_NAMES)),
    }
    for _, make_scene, orientations, n in cases.values():
        for i in range(WARM_TRIALS):
            _trial_steps(make_scene, orientations, n, settings, seed, i)
    per_step: dict[str, list[float]] = {name: [] for name in cases}
    totals = {name: [0, 0] for name in cases}
    for i in range(trials):
        for name, (_, make_scene, orientations, n) in cases.items():
            seconds, steps, contact = _trial_steps(make_scene, orientations, n, settings, seed, i)
            per_step[name].append(seconds / steps * 1e6)
            totals[name][0] += steps
            totals[name][1] += contact
    out: dict = {"trials": trials, "seed": seed, "step": settings.step}
    for name, (device, *_) in cases.items():
        out[name] = {
            "device": device,
            "us_per_step": statistics.median(per_step[name]),
            "steps": totals[name][0],
            "contact_share": totals[name][1] / max(totals[name][0], 1),
        }
    out["ratio"] = out["cup"]["us_per_step"] / out["peg"]["us_per_step"]
    return out


def format_part_cost(results: dict) -> str:
    """``part_cost``'s results as a short table."""
    lines = [
        f"dynamic level, h = {results['step']:g} s: median wall time per step over "
        f"{results['trials']} verdict trials (both entries, seed {results['seed']})",
        f"{'part':6s} {'device':18s} {'us/step':>8s} {'steps':>9s} {'in contact':>11s}",
    ]
    for name in ("cup", "peg"):
        r = results[name]
        lines.append(
            f"{name:6s} {r['device']:18s} {r['us_per_step']:8.2f} {r['steps']:9d} "
            f"{r['contact_share']:10.0%}"
        )
    lines.append(f"cup / peg: {results['ratio']:.2f}x per step")
    return "\n".join(lines)
