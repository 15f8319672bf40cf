"""What each rung of the ladder buys: cost per design against the error of its verdict.

Every design of a fixed set is judged at every level, as the sweep's holdout is: planned with
RRT at the geometric (Eq. 9), kinematic (Eq. 8) and dynamic (Eq. 7) levels
(:func:`experiments.verdicts.feasibility.design_verdict`: feasible when both entry
orientations reach the goal within the budget), and by the passive drop's verdict
(:func:`experiments.drop.verdict.design_verdict`: perturbed drops until the success
probability of every entry is decided against the target), the top of the ladder: the paper's
feeder must work without input (Section 4).

Per level: the wall time per design (median, mean, designs per second) and its verdict's
agreement with the top verdict: precision (of the designs it passes, the fraction the top
passes) and recall (of the designs the top passes, the fraction it passes), with Wilson 95%
intervals, and the fraction of designs on which they disagree. The same against the dynamic
level (the top of ``partfeeder run``'s ladder). And the skip "levels not climbed": the cost of
the ladder (a design goes up a rung only when feasible at the one below) against judging
every design at every level.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence

from experiments.bench.feeder_convergence import design_of
from experiments.drop.verdict import VerdictSettings
from experiments.drop.verdict import design_verdict as passive_verdict
from experiments.proportions import wilson_interval
from feeders.feeder import DegenerateDesign

PLANNING_LEVELS = ("geometric", "kinematic", "dynamic")
LEVELS = (*PLANNING_LEVELS, "passive")
BUDGETS_FULL = {"geometric": 0.5, "kinematic": 1.0, "dynamic": 2.0}  # s per orientation
BUDGETS_QUICK = {"geometric": 0.1, "kinematic": 0.1, "dynamic": 0.1}
DESIGNS_FULL = (
    "fig4",
    "fig5a",
    "fig5b",
    "fig6a",
    "fig6b",
    "fig7a",
    "fig7b",
    "fig8a",
    "fig8b",
    "fig9",
    "table3",
    *(f"halton0:{i}" for i in range(9)),
)
DESIGNS_QUICK = ("table3", "fig9")
PASSIVE_FULL = VerdictSettings(min_drops=10, batch=10, max_drops=30)
PASSIVE_QUICK = VerdictSettings(min_drops=4, batch=4, max_drops=4)
PASSIVE_WARM_UP = VerdictSettings(min_drops=1, batch=1, max_drops=1)


def _judge(name: str, budgets: dict[str, float], passive: VerdictSettings, seed: int) -> dict:
    from experiments.verdicts.feasibility import design_verdict as planning_verdict

    design = design_of(name)
    row: dict = {"design": name}
    for level in PLANNING_LEVELS:
        v = planning_verdict(list(design.to_vector()), level, "rrt", budgets[level], seed)
        row[level] = {"feasible": bool(v["feasible"]), "wall_s": float(v["wall_time_s"])}
    try:
        verdict = passive_verdict(design, settings=passive, seed=seed)
    except DegenerateDesign:
        row["passive"] = {"feasible": False, "wall_s": 0.0, "decision": "not buildable"}
    else:
        row["passive"] = {
            "feasible": verdict.works,
            "wall_s": verdict.wall_time,
            "decision": verdict.decision,
            "drops": verdict.drops,
        }
    return row


def _rate(k: int, n: int) -> dict:
    return {"k": k, "n": n, "value": k / n if n else None, "interval": list(wilson_interval(k, n))}


def agreement(rows: Sequence[dict], level: str, top: str) -> dict:
    """Precision, recall and disagreement of ``level``'s verdicts against ``top``'s."""
    both = sum(r[level]["feasible"] and r[top]["feasible"] for r in rows)
    passed = sum(r[level]["feasible"] for r in rows)
    top_passed = sum(r[top]["feasible"] for r in rows)
    disagree = sum(r[level]["feasible"] != r[top]["feasible"] for r in rows)
    return {
        "precision": _rate(both, passed),
        "recall": _rate(both, top_passed),
        "disagreement": _rate(disagree, len(rows)),
    }


def ladder_cost(rows: Sequence[dict], levels: Sequence[str] = LEVELS) -> dict:
    """Wall time of the ladder (climb while feasible) and of every design at every level."""
    climbed = 0.0
    for r in rows:
        for level in levels:
            climbed += r[level]["wall_s"]
            if not r[level]["feasible"]:
                break
    every = sum(r[level]["wall_s"] for r in rows for level in levels)
    return {"ladder_s": climbed, "every_level_s": every, "speed_up": every / climbed}


def run_ladder(
    designs: Sequence[str] = DESIGNS_FULL,
    budgets: dict[str, float] | None = None,
    passive: VerdictSettings = PASSIVE_FULL,
    seed: int = 1,
) -> dict:
    """Every design at every level; per level cost and agreement (module docstring)."""
    from ompl import util as ou

    budgets = budgets or BUDGETS_FULL
    previous = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    try:
        # untimed warm-up: compiled kernels loaded, OMPL's classes built, before any clock
        _judge(designs[0], dict.fromkeys(PLANNING_LEVELS, 0.05), PASSIVE_WARM_UP, seed)
        rows = [_judge(name, budgets, passive, seed) for name in designs]
    finally:
        ou.setLogLevel(previous)
    levels = {}
    for level in LEVELS:
        walls = [r[level]["wall_s"] for r in rows]
        levels[level] = {
            "median_s": statistics.median(walls),
            "mean_s": statistics.mean(walls),
            "designs_per_s": len(walls) / sum(walls) if sum(walls) > 0 else None,
            "feasible": sum(r[level]["feasible"] for r in rows),
            "vs_passive": agreement(rows, level, "passive"),
            "vs_dynamic": agreement(rows, level, "dynamic"),
        }
    return {
        "designs": list(designs),
        "budgets_s_per_orientation": budgets,
        "planner": "rrt",
        "passive_settings": {
            "target": passive.target,
            "min_drops": passive.min_drops,
            "batch": passive.batch,
            "max_drops": passive.max_drops,
            "step": passive.step,
        },
        "seed": seed,
        "rows": rows,
        "levels": levels,
        "skip_levels_not_climbed": ladder_cost(rows),
    }
