"""The optimum beside a baseline on the same fresh draws, from the verdicts the optimiser
stored (no drop is simulated again).

The optimiser gives the optimum and the baseline (the paper's table3 unless ``--baseline``
names another) each a fixed-sample verdict on the same ``final.trials`` trials of seed
``final.seed + 1`` (common random numbers: trial i of both sees the same entry noise,
friction factor and manufacturing errors). This module rebuilds those verdicts from their
stored trials and returns them in the form of
:func:`experiments.drop.compare.compare_designs` (what
:mod:`experiments.report_kit.comparison_section` shows): per design its verdict, its
parameter differences from the baseline and the paired counts of draws only one of them
passed.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

from experiments.drop.compare import paired_counts, parameter_differences
from experiments.drop.verdict import Verdict, decide
from experiments.optimize.objective import trial_from_dict
from feeders.design import DesignParameters
from feeders.feeder import ORIENTATIONS


def verdict_of_trials(
    trial_data: list[dict],
    target: float,
    orientations: Sequence[str] = ORIENTATIONS,
    classes: tuple[tuple[str, ...], tuple[str, ...]] | None = None,
) -> Verdict:
    """The verdict of stored trials (plain data, :func:`experiments.optimize.objective.
    trial_to_dict`) against ``target``: a fixed sample, decided once on all of them;
    ``orientations`` name the trials' entries and ``classes`` (the transition matrix's
    columns and the goal's classes, :func:`experiments.drop.verdict.classes_of`; None: the
    feeder's) their outcomes: a device family's are its own."""
    trials = tuple(trial_from_dict(t) for t in trial_data)
    counts = [sum(t.success[k] for t in trials) for k in range(len(orientations))]
    decision = decide(counts, len(trials), target) if trials else "fails"
    verdict = Verdict(tuple(orientations), trials, target, decision, 0.0)
    if classes is None:
        return verdict
    return dataclasses.replace(verdict, classes=classes[0], success_classes=classes[1])


def stored_comparison(
    designs: dict[str, tuple[list[float], list[dict]]],
    baseline: tuple[str, list[float], list[dict]],
    seed: int,
    target: float,
    wall_time_s: float | None = None,
) -> dict[str, Any]:
    """The comparison of each labelled design (``label -> (12 values, stored trials)``) with
    the ``baseline`` ``(label, 12 values, stored trials)``, all judged on trials of ``seed``
    against ``target``; ``wall_time_s`` is what the verdicts cost when they were run (s,
    None when not recorded). Keys as :func:`experiments.drop.compare.compare_designs`:
    ``seed``, ``drops``, ``target``, ``wall_time_s``, ``baseline``, ``designs``."""
    label, values, trials = baseline
    base_verdict = verdict_of_trials(trials, target)
    base_design = DesignParameters.from_vector(values)
    entries = []
    for name, (design_values, design_trials) in designs.items():
        verdict = verdict_of_trials(design_trials, target)
        entries.append(
            {
                "label": name,
                "values": [float(v) for v in design_values],
                "verdict": verdict.to_dict(),
                "reason": None,
                "differences": parameter_differences(
                    DesignParameters.from_vector(design_values), base_design
                ),
                "paired": paired_counts(verdict, base_verdict),
            }
        )
    return {
        "seed": int(seed),
        "drops": len(trials),
        "target": float(target),
        "baseline": {
            "label": label,
            "values": [float(v) for v in values],
            "verdict": base_verdict.to_dict(),
            "reason": None,
        },
        "designs": entries,
        "wall_time_s": wall_time_s,
    }
