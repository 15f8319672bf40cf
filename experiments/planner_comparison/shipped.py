"""The shipped suites, by name: ``planners-quick`` (``--quick``) and ``planners`` (the
default). Kept as Python data beside the job, so they ship with the package whatever its
data files are; a config file of one's own has the same fields (:mod:`.suite`).

The quick suite (a few minutes on 2 cores): two of the paper's designs, a Halton design that
passes the necessary conditions, one whose heavy-trailing entry fails the turn test, the cup
through the fig1-cup family, x the three levels x both entries; five planners, three seeded
runs each, budgets in propagations (the default sweep's rungs, chosen there by replaying runs:
docs/planner-arena.md). Problems known to be unsolvable are not planned (the full suite plans
them, as a check of the necessary conditions).

The full suite: every design of the paper (Figs. 4-9, Table 3; fig7a fails the sliced test),
six Halton designs of seed 1 (four that pass the necessary conditions, one whose heavy-trailing
entry fails the turn test, one that fails the sliced test), and the cup; five runs each.
"""

from __future__ import annotations

from typing import Any

from experiments.names import PRESET_NAMES

PLANNERS = ["rrt", "rrt-greedy", "rrt-intermediate", "kpiece", "est"]
LEVELS = ["geometric", "kinematic", "dynamic"]
BUDGETS = {"geometric": 30000, "kinematic": 3000, "dynamic": 1000}

SUITES: dict[str, dict[str, Any]] = {
    "planners-quick": {
        "name": "planners-quick",
        "designs": [
            {"preset": "table3"},
            {"preset": "fig4"},
            {"halton": {"seed": 1, "index": 1}},
            {"halton": {"seed": 1, "index": 7}},
            {"family": "fig1-cup"},
        ],
        "levels": LEVELS,
        "planners": PLANNERS,
        "runs": 3,
        "budgets": BUDGETS,
        "seed": 1,
        "plan_unsolvable": False,
        "bootstrap": 1000,
        "progress_samples": 20,
    },
    "planners": {
        "name": "planners",
        "designs": [
            *({"preset": name} for name in ("table3", *(n for n in PRESET_NAMES if n != "table3"))),
            *({"halton": {"seed": 1, "index": i}} for i in (0, 1, 2, 3, 5, 7)),
            {"family": "fig1-cup"},
        ],
        "levels": LEVELS,
        "planners": PLANNERS,
        "runs": 5,
        "budgets": BUDGETS,
        "seed": 1,
        "plan_unsolvable": True,
        "bootstrap": 2000,
        "progress_samples": 20,
    },
}
