"""``partfeeder bench --trial``: what one verdict trial costs, and where (issue 21).

A trial (:func:`experiments.drop.verdict.run_trial`) draws its perturbation, makes the feeder
to tolerance, builds its dynamic level (the cover split of the walls) and drops the part once
from each entry. The verdict of a design is tens of trials, a sweep thousands of verdicts, so
the per-trial cost is what the ladder's budget is made of. Reported: the median wall time
(ms) of whole trials of one design, and of each part measured on its own the same way, with
its share of the whole trial's median. Kernels are loaded (a few trials run first), one
process, one core.

Measure, never assert: these return numbers for reports, they judge nothing.
"""

from __future__ import annotations

import statistics
import time

from experiments.drop.outcomes import classify
from experiments.drop.passive import passive_drop
from experiments.drop.perturbations import draw
from experiments.drop.verdict import entry_state, made_feeders, run_trial
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import preset
from feeders.feeder import ORIENTATIONS
from validity.dynamic import DynamicLevel

PARTS = ("draw", "made feeder", "level", "drops")
WARM_TRIALS = 5  # trials run first (kernels loaded, caches warm); not timed


def trial_cost(design: str = "table3", trials: int = 200, seed: int = 0) -> dict:
    """Median ms of a whole trial of the preset ``design`` over ``trials`` trials of a
    verdict with ``seed`` (default settings), and of each of :data:`PARTS` timed alone on the
    same trials: ``{"design", "trials", "trial_ms", "parts": {part: {"ms", "share"}}}``."""
    settings = VerdictSettings()
    make_scene = made_feeders(preset(design))
    for i in range(WARM_TRIALS):
        run_trial(make_scene, ORIENTATIONS, settings, seed, i)
    whole: list[float] = []
    parts: dict[str, list[float]] = {p: [] for p in PARTS}
    for i in range(trials):
        t0 = time.perf_counter()
        run_trial(make_scene, ORIENTATIONS, settings, seed, i)
        whole.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        d = draw(settings.perturbations, seed, i, len(ORIENTATIONS))
        t1 = time.perf_counter()
        scene = make_scene(d)
        t2 = time.perf_counter()
        level = DynamicLevel(scene, step=settings.step)
        t3 = time.perf_counter()
        for k, orientation in enumerate(ORIENTATIONS):
            start = entry_state(
                level, scene.start(orientation), d.entry_offsets[k], d.entry_velocities[k]
            )
            result = passive_drop(
                scene, orientation, t_max=settings.t_max, level=level, start=start
            )
            classify(scene, result.end, result.final_pose, result.success)
        t4 = time.perf_counter()
        for part, seconds in zip(PARTS, (t1 - t0, t2 - t1, t3 - t2, t4 - t3), strict=True):
            parts[part].append(seconds)
    trial_ms = 1e3 * statistics.median(whole)
    return {
        "design": design,
        "trials": trials,
        "seed": seed,
        "trial_ms": trial_ms,
        "parts": {
            p: {
                "ms": 1e3 * statistics.median(v),
                "share": 1e3 * statistics.median(v) / trial_ms,
            }
            for p, v in parts.items()
        },
    }


def format_trial_cost(results: dict) -> str:
    """The numbers as a few lines of text."""
    lines = [
        f"one verdict trial of {results['design']} (median of {results['trials']}, seed "
        f"{results['seed']}): {results['trial_ms']:.2f} ms"
    ]
    for part, v in results["parts"].items():
        lines.append(f"  {part:12s} {v['ms']:7.3f} ms  {100 * v['share']:5.1f}%")
    return "\n".join(lines)
