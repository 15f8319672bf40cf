"""A design against a baseline on the same fresh draws: why this design, not the baseline.

A design ranked best by its verdict was selected on that verdict's draws, so its numbers
flatter it (the best of a scan can be a lucky draw, issue 25). Here each design and the
baseline (the paper's table3 by default) get a fixed-sample verdict of ``drops`` trials on
the same seed (common random numbers: trial ``i`` of every design sees the same entry
noise, friction factor and relative manufacturing errors, :func:`experiments.drop.
perturbations.draw`), a seed different from every seed the designs were ranked with
(:func:`fresh_seed`). A trial whose drop ends inside a wall is replaced by the next draw, so
the draws stay common up to the first such fault. The verdict's decision on these draws is
the confirmation: "works" (every entry's Wilson 95% lower bound above the target) confirms
the ranking; "fails" or "undecided" does not.

Everything returned is plain data (JSON-ready), for a report to show.
"""

from __future__ import annotations

import time
from collections.abc import Collection, Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from experiments.drop.verdict import Verdict, design_verdict
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import PARAMETER_NAMES, TABLE2_BOUNDS, DesignParameters
from feeders.feeder import DegenerateDesign
from feeders.part import DEFAULT_PEG, Peg

FRESH_DROPS = 40  # trials per design: 40 of 40 has a Wilson lower bound of 0.912 > 0.9
FRESH_TAG = 0xC0DE  # mixed into the fresh seed so that it is no verdict's seed


def fresh_seed(base: int, avoid: Collection[int] = (), tag: int = FRESH_TAG) -> int:
    """A seed derived from ``base`` (e.g. the sweep's seed) and ``tag`` (what it is for) that
    is none of ``avoid`` (the seeds the designs were ranked with), so the comparison's draws
    are not the ranking's."""
    state = np.random.SeedSequence([int(base), int(tag)]).generate_state(1)[0]
    seed = int(state % (2**31 - 1))
    while seed in set(avoid):
        seed = (seed + 1) % (2**31 - 1)
    return seed


def fixed_settings(settings: VerdictSettings, drops: int = FRESH_DROPS) -> VerdictSettings:
    """``settings`` with one look after exactly ``drops`` trials (no early stop), so every
    design of a comparison costs the same and runs on the same draws."""
    return replace(settings, min_drops=drops, batch=drops, max_drops=drops)


def compare_designs(
    designs: Mapping[str, DesignParameters],
    baseline: tuple[str, DesignParameters],
    settings: VerdictSettings,
    seed: int,
    drops: int = FRESH_DROPS,
    part: Peg = DEFAULT_PEG,
    friction: float | None = None,
    **feeder_options: Any,
) -> dict[str, Any]:
    """The fixed-sample verdicts (``drops`` trials, ``seed``) of each labelled design and of
    the baseline ``(label, design)``, all on the same draws, with each design's parameter
    differences from the baseline.

    Returns ``seed``, ``drops``, ``target``, ``wall_time_s`` (s, all verdicts), ``baseline``
    and ``designs`` (a list); each design entry has ``label``, ``values`` (12, in the order
    of ``PARAMETER_NAMES``), ``verdict`` (``Verdict.to_dict()``, or None with ``reason``
    when the design cannot be built), and the designs' entries ``differences``
    (:func:`parameter_differences` against the baseline) and ``paired``
    (:func:`paired_counts`).
    """
    t0 = time.perf_counter()
    fixed = fixed_settings(settings, drops)

    def judged(label: str, design: DesignParameters) -> tuple[dict[str, Any], Verdict | None]:
        entry: dict[str, Any] = {
            "label": label,
            "values": [float(v) for v in design.to_vector()],
            "verdict": None,
            "reason": None,
        }
        try:
            verdict = design_verdict(design, part, friction, fixed, seed, **feeder_options)
        except DegenerateDesign as exc:
            entry["reason"] = str(exc.reason)
            return entry, None
        entry["verdict"] = verdict.to_dict()
        return entry, verdict

    base, base_verdict = judged(*baseline)
    out = []
    for label, design in designs.items():
        entry, verdict = judged(label, design)
        entry["differences"] = parameter_differences(design, baseline[1])
        entry["paired"] = paired_counts(verdict, base_verdict)
        out.append(entry)
    return {
        "seed": int(seed),
        "drops": int(drops),
        "target": float(settings.target),
        "baseline": base,
        "designs": out,
        "wall_time_s": time.perf_counter() - t0,
    }


def paired_counts(design: Verdict | None, baseline: Verdict | None) -> dict[str, int] | None:
    """Over the trials both verdicts counted with the same index (the same draw): ``draws``,
    ``design_only`` (the design succeeded from every entry, the baseline did not) and
    ``baseline_only`` (the reverse); None when either design cannot be built. The discordant
    pairs are what a paired comparison (McNemar's) rests on."""
    if design is None or baseline is None:
        return None
    mine = {t.index: all(t.success) for t in design.counted}
    theirs = {t.index: all(t.success) for t in baseline.counted}
    common = sorted(mine.keys() & theirs.keys())
    return {
        "draws": len(common),
        "design_only": sum(mine[i] and not theirs[i] for i in common),
        "baseline_only": sum(theirs[i] and not mine[i] for i in common),
    }


def parameter_differences(
    design: DesignParameters, baseline: DesignParameters
) -> list[dict[str, Any]]:
    """Per parameter (order of ``PARAMETER_NAMES``): ``name``, ``design``, ``baseline``,
    ``difference`` (design - baseline, the parameter's unit) and ``fraction`` (the
    difference over the width of Table 2's range of that parameter: 1.0 is the whole box)."""
    rows = []
    for name, x, y in zip(PARAMETER_NAMES, design.to_vector(), baseline.to_vector(), strict=True):
        low, high = TABLE2_BOUNDS[name]
        rows.append(
            {
                "name": name,
                "design": float(x),
                "baseline": float(y),
                "difference": float(x - y),
                "fraction": float((x - y) / (high - low)),
            }
        )
    return rows
