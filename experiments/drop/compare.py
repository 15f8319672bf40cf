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

One mechanism serves every device: :func:`compare_family_designs` judges the designs of a
family (a YAML device family, issue 24, or the paper's 12-parameter feeder as one,
:class:`feeders.feeder_family.FeederFamily`), each trial's device made as the family's verdict
makes it (:func:`experiments.drop.family_verdict.made_devices`), and measures parameter
differences in fractions of the family's box (Table 2's for the feeder);
:func:`compare_designs` is the feeder's designs through it, trial for trial the feeder's own
verdicts.

Everything returned is plain data (JSON-ready), for a report to show.
"""

from __future__ import annotations

import time
from collections.abc import Collection, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from experiments.drop.family_verdict import Vector, entry_names, made_devices
from experiments.drop.verdict import Verdict, verdict_of
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import DESIGN_SPACE, PARAMETER_NAMES, DesignParameters
from feeders.feeder import DEFAULT_FRICTION, DegenerateDesign
from feeders.feeder_family import Family, FeederFamily
from feeders.part import DEFAULT_PEG, Peg

Numbers = Sequence[float] | np.ndarray  # a parameter vector or box: a list or an array

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
    """The 12-parameter feeder's designs compared (:func:`compare_family_designs` on the
    feeder as a family, :class:`feeders.feeder_family.FeederFamily`, whose verdicts are the
    feeder's own trial for trial): ``part``, ``friction`` (None: the feeder's default mu)
    and ``feeder_options`` (gravity, restitution, inputs) are the feeder's environment."""
    family = FeederFamily(
        part=part,
        friction=DEFAULT_FRICTION if friction is None else float(friction),
        **feeder_options,
    )
    label, design = baseline
    return compare_family_designs(
        family,
        {name: d.to_vector() for name, d in designs.items()},
        (label, design.to_vector()),
        settings,
        seed,
        drops,
    )


def compare_family_designs(
    family: Family,
    designs: Mapping[str, Vector],
    baseline: tuple[str, Vector],
    settings: VerdictSettings,
    seed: int,
    drops: int = FRESH_DROPS,
) -> dict[str, Any]:
    """The fixed-sample verdicts (``drops`` trials, ``seed``) of each labelled design of
    ``family`` (a device family, or the paper's feeder as one) and of the baseline
    ``(label, values)``, all on the same draws: each trial's device made by
    :func:`experiments.drop.family_verdict.made_devices` (the family's part and friction),
    dropped from every entry of the family, decided by
    :func:`experiments.drop.verdict.verdict_of`, as the family's own verdict is. A vector
    that is not the family's raises ``ValueError`` before any drop.

    Returns ``seed``, ``drops``, ``target``, ``wall_time_s`` (s, all verdicts),
    ``family`` (the device family's name; None for the 12-parameter feeder),
    ``parameters`` (the family's names), ``entries`` (its entries, the verdicts'
    orientations), ``baseline`` and ``designs`` (a list); each design entry has ``label``,
    ``values`` (in the order of ``parameters``), ``verdict`` (``Verdict.to_dict()``, or
    None with ``reason`` when the design cannot be built), and the designs' entries
    ``differences`` (:func:`box_differences` against the baseline, over the family's box:
    Table 2's for the feeder) and ``paired`` (:func:`paired_counts`).
    """
    t0 = time.perf_counter()
    fixed = fixed_settings(settings, drops)
    vectors = {label: family.values(v) for label, v in designs.items()}
    base_label, base_values = baseline[0], family.values(baseline[1])
    low, high = family.bounds()

    def judged(label: str, values: dict[str, float]) -> tuple[dict[str, Any], Verdict | None]:
        entry: dict[str, Any] = {
            "label": label,
            "values": list(values.values()),
            "verdict": None,
            "reason": None,
        }
        try:
            make_scene = made_devices(family, values)
        except DegenerateDesign as exc:
            entry["reason"] = str(exc.reason)
            return entry, None
        n = len(family.vector_names)
        verdict = verdict_of(make_scene, entry_names(family), fixed, seed, n)
        entry["verdict"] = verdict.to_dict()
        return entry, verdict

    base, base_verdict = judged(base_label, base_values)
    out = []
    for label, values in vectors.items():
        entry, verdict = judged(label, values)
        entry["differences"] = box_differences(
            family.vector_names, entry["values"], base["values"], low, high
        )
        entry["paired"] = paired_counts(verdict, base_verdict)
        out.append(entry)
    return {
        "seed": int(seed),
        "drops": int(drops),
        "target": float(settings.target),
        "family": None if isinstance(family, FeederFamily) else family.name,
        "parameters": list(family.vector_names),
        "entries": list(entry_names(family)),
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
    """The 12-parameter feeder's :func:`box_differences`: per parameter (order of
    ``PARAMETER_NAMES``) over Table 2's range."""
    return box_differences(
        PARAMETER_NAMES,
        design.to_vector(),
        baseline.to_vector(),
        DESIGN_SPACE.low,
        DESIGN_SPACE.high,
    )


def box_differences(
    names: Sequence[str],
    design: Numbers,
    baseline: Numbers,
    low: Numbers,
    high: Numbers,
) -> list[dict[str, Any]]:
    """Per parameter (order of ``names``): ``name``, ``design``, ``baseline``,
    ``difference`` (design - baseline, the parameter's unit), ``fraction`` (the difference
    over the width of the parameter's box, ``high - low``: 1.0 is the whole box; Table 2's
    for the feeder, a family's own) and the box, ``low`` and ``high``."""
    rows = []
    for name, x, y, lo, hi in zip(names, design, baseline, low, high, strict=True):
        rows.append(
            {
                "name": str(name),
                "design": float(x),
                "baseline": float(y),
                "difference": float(x - y),
                "fraction": float((x - y) / (hi - lo)),
                "low": float(lo),
                "high": float(hi),
            }
        )
    return rows
