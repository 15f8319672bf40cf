"""``partfeeder bench --verdict``: what deciding a design costs, the full verdict alone against
the screened one, measured in one run on the same designs (issue 21).

For each of the first N Halton designs (Table 2's box, the sweep's friction), one process and
one core, in turn:

- **wilson**: the full verdict as the default sweep ran it before issue 21 (Wilson intervals,
  a look every 10 trials, h = 1e-3);
- **sprt**: the full verdict by Wald's test, a look after every trial (the default sweep's
  verdict now);
- **screen + sprt**: the screen (:mod:`experiments.drop.screen`, h = 4e-3, fails only), then
  the SPRT verdict for what the screen does not fail: its cost is the screen's plus, when the
  screen does not fail the design, the SPRT verdict's measured above (the same verdict, so
  it is not run twice).

The three are timed design by design with the order rotated, so a change of the machine's load
falls on all three alike. Reported: worker seconds per design (mean) for each, the ratios of
the means with paired bootstrap 95% intervals (the same resampled designs for both), and the
decisions: how many designs each calls working, and every design on which the screened
pipeline and the Wilson verdict disagree (a design that works thrown away would be listed).

Measure, never assert: these return numbers for reports, they judge nothing.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from functools import partial

import numpy as np

from experiments.drop.screen import Screen, design_screen
from experiments.drop.verdict import Verdict, design_verdict
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import DesignParameters, preset
from feeders.feeder import DegenerateDesign
from feeders.halton import halton_points

PROCEDURES = ("wilson", "sprt", "screen + sprt")
WILSON = VerdictSettings()
SPRT = VerdictSettings(rule="sprt", min_drops=1, batch=1)
BOOTSTRAP = 2000


def _seed(seed: int, design: int, tag: int) -> int:
    state = np.random.SeedSequence([seed, design, tag]).generate_state(1)[0]
    return int(state % (2**31 - 1))


def verdict_cost(designs: int = 200, seed: int = 0) -> dict:
    """The three procedures on the first ``designs`` Halton designs of ``seed`` (see the
    module docstring): ``{"designs", "buildable", "seed", "procedures": {name: {"mean_s",
    "total_s", "works"}}, "ratios": {name: {"value", "ci"}}, "disagreements": [...]}``."""
    design_screen(preset("table3"), seed=1)  # kernels loaded before any clock
    design_verdict(preset("table3"), settings=VerdictSettings(max_drops=1, min_drops=1), seed=1)
    costs: dict[str, list[float]] = {p: [] for p in PROCEDURES}
    decisions: dict[str, list[str]] = {p: [] for p in PROCEDURES}
    ids: list[int] = []
    for i, values in enumerate(halton_points(designs, seed)):
        design = DesignParameters.from_vector([float(v) for v in values])
        verdict_seed, screen_seed = _seed(seed, i, 1), _seed(seed, i, 2)
        runs: dict[str, Callable[[], Verdict | Screen]] = {
            "wilson": partial(design_verdict, design, settings=WILSON, seed=verdict_seed),
            "sprt": partial(design_verdict, design, settings=SPRT, seed=verdict_seed),
            "screen": partial(design_screen, design, seed=screen_seed),
        }
        order = list(runs)[i % 3 :] + list(runs)[: i % 3]
        seconds: dict[str, float] = {}
        outcome: dict[str, str] = {}
        try:
            for name in order:
                t0 = time.perf_counter()
                result = runs[name]()
                seconds[name] = time.perf_counter() - t0
                outcome[name] = result.decision
        except DegenerateDesign:
            continue
        ids.append(i)
        screened = outcome["screen"] == "fails"
        for name in ("wilson", "sprt"):
            costs[name].append(seconds[name])
            decisions[name].append(outcome[name])
        costs["screen + sprt"].append(seconds["screen"] + (0.0 if screened else seconds["sprt"]))
        decisions["screen + sprt"].append("fails" if screened else outcome["sprt"])
    arrays = {p: np.array(v) for p, v in costs.items()}
    resample = np.random.default_rng(0).integers(0, len(ids), (BOOTSTRAP, len(ids)))
    ratios = {}
    for name in ("wilson", "sprt"):
        boot = arrays[name][resample].mean(1) / arrays["screen + sprt"][resample].mean(1)
        ratios[f"{name} / screen + sprt"] = {
            "value": float(arrays[name].mean() / arrays["screen + sprt"].mean()),
            "ci": [float(np.quantile(boot, 0.025)), float(np.quantile(boot, 0.975))],
        }
    disagreements = [
        {"design": d, "wilson": w, "screen + sprt": s}
        for d, w, s in zip(ids, decisions["wilson"], decisions["screen + sprt"], strict=True)
        if w != s
    ]
    return {
        "designs": designs,
        "buildable": len(ids),
        "seed": seed,
        "procedures": {
            p: {
                "mean_s": float(arrays[p].mean()),
                "total_s": float(arrays[p].sum()),
                "works": decisions[p].count("works"),
                "undecided": decisions[p].count("undecided"),
            }
            for p in PROCEDURES
        },
        "ratios": ratios,
        "disagreements": disagreements,
    }


def format_verdict_cost(results: dict) -> str:
    """The numbers as a few lines of text."""
    lines = [
        f"deciding {results['buildable']} buildable designs of the first {results['designs']} "
        f"Halton designs (seed {results['seed']}), one core:"
    ]
    for name, v in results["procedures"].items():
        lines.append(
            f"  {name:14s} {1e3 * v['mean_s']:7.1f} ms a design ({v['total_s']:.1f} s), "
            f"{v['works']} work, {v['undecided']} undecided"
        )
    for name, r in results["ratios"].items():
        lines.append(f"  {name}: {r['value']:.2f}x [{r['ci'][0]:.2f}, {r['ci'][1]:.2f}]")
    gone = results["disagreements"]
    lines.append(
        "  decisions: the same as the Wilson verdict's on every design"
        if not gone
        else "  decisions that differ from the Wilson verdict's: "
        + ", ".join(f"{g['design']} ({g['wilson']} -> {g['screen + sprt']})" for g in gone)
    )
    return "\n".join(lines)
