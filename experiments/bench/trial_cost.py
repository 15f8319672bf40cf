"""``partfeeder bench --trial``: what one verdict trial costs, and where (issue 21).

A trial (:func:`experiments.drop.verdict.run_trial`) draws its perturbation, makes the feeder
to tolerance, builds its dynamic level (the cover split of the walls) and drops the part once
from each entry. The verdict of a design is tens of trials, a sweep thousands of verdicts, so
the per-trial cost is what the ladder's budget is made of. Reported: the median and mean wall
time (ms) of whole trials of one design, then each part timed on its own on the same trials:
its mean and its share of the sum of the parts' means, so the shares add up to 100% (issue
39: each part's median as a share of the whole's median printed "drops 59.9 ms 114.0%" of a
52.5 ms trial, since medians do not add and the parts run apart from the timed whole); each
part's median is given too. Kernels are loaded (a few trials run first), one process, one
core.

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
    """Median and mean ms of a whole trial of the preset ``design`` over ``trials`` trials of
    a verdict with ``seed`` (default settings), and of each of :data:`PARTS` timed alone on
    the same trials: ``{"design", "trials", "seed", "trial_ms" (median), "trial_mean_ms",
    "parts_ms" (the sum of the parts' means), "parts": {part: {"ms" (mean), "median_ms",
    "share" (of parts_ms)}}}``."""
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
    means = {p: 1e3 * statistics.fmean(v) for p, v in parts.items()}
    parts_ms = sum(means.values())
    return {
        "design": design,
        "trials": trials,
        "seed": seed,
        "trial_ms": 1e3 * statistics.median(whole),
        "trial_mean_ms": 1e3 * statistics.fmean(whole),
        "parts_ms": parts_ms,
        "parts": {
            p: {
                "ms": means[p],
                "median_ms": 1e3 * statistics.median(v),
                "share": means[p] / parts_ms if parts_ms > 0 else 0.0,
            }
            for p, v in parts.items()
        },
    }


def format_trial_cost(results: dict) -> str:
    """The numbers as a few lines of text: the whole trial, then its parts' means with their
    shares of the parts' sum (they add up to 100%) and their medians."""
    lines = [
        f"one verdict trial of {results['design']} ({results['trials']} trials, seed "
        f"{results['seed']}): median {results['trial_ms']:.2f} ms, mean "
        f"{results['trial_mean_ms']:.2f} ms",
        f"its parts, each timed alone on the same trials: mean, share of the parts' sum "
        f"({results['parts_ms']:.2f} ms), median",
    ]
    for part, v in results["parts"].items():
        lines.append(
            f"  {part:12s} {v['ms']:7.3f} ms  {100 * v['share']:5.1f}%  "
            f"(median {v['median_ms']:.3f} ms)"
        )
    return "\n".join(lines)
