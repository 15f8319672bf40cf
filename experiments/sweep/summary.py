"""What a sweep found and what the ladder bought, from its results database (plain data).

- Per level: designs evaluated, their verdicts, survivors (feasible at this level and every
  one below), evaluation time and designs per second of worker time.
- Per level and planner: runs, solved fraction, median time and tree size (Planner Arena's
  main columns).
- Pruning: on the holdout (a random sample of the designs that climbed every rung), each
  lower level's verdict against the top level's: precision = P(top feasible | passes the
  level), recall = P(passes the level | top feasible), with Wilson 95% intervals. Recall is
  what pruning risks: a design pruned although the top level would pass it. ``ladder``
  gives the same for the ladder's own decision up to a level (passing it and all below).
- Speed-up: the worker time the ladder spent (evaluations of designs that had passed every
  lower rung) against the estimated time of evaluating every design at the top level only
  (the mean top-level evaluation time on the holdout times the number of designs), with a
  seeded bootstrap 95% interval over the holdout.
- Best designs: feasible at the top level, ranked by the slower entry's fastest exit time
  (Eq. 10: both orientations must leave, as fast as possible).
"""

from __future__ import annotations

import json
import math
import sqlite3
from pathlib import Path
from statistics import median
from typing import Any

import numpy as np

from experiments.proportions import wilson_interval
from experiments.sweep import results_db
from feeders.design import PARAMETER_NAMES

BOOTSTRAP_SAMPLES = 2000
BEST_DESIGNS = 6


def _ratio(k: int, n: int) -> dict[str, Any]:
    low, high = wilson_interval(k, n)
    return {"value": k / n if n else None, "ci": [low, high]}


def _confusion(pairs: list[tuple[bool, bool]]) -> dict[str, Any]:
    tp = sum(1 for v, t in pairs if v and t)
    fp = sum(1 for v, t in pairs if v and not t)
    fn = sum(1 for v, t in pairs if not v and t)
    tn = sum(1 for v, t in pairs if not v and not t)
    precision, recall = _ratio(tp, tp + fp), _ratio(tp, tp + fn)
    return {
        "n": len(pairs),
        "tp": tp,
        "fp": fp,
        "fn": fn,
        "tn": tn,
        "precision": precision["value"],
        "precision_ci": precision["ci"],
        "recall": recall["value"],
        "recall_ci": recall["ci"],
    }


def summarise(path: str | Path) -> dict[str, Any]:
    """The summary of the sweep stored at ``path`` (see the module docstring); works on a
    sweep still running or stopped half-way."""
    db = results_db.connect(path, readonly=True)
    try:
        return _summarise(db)
    finally:
        db.close()


def _summarise(db: sqlite3.Connection) -> dict[str, Any]:
    meta = {r["key"]: r["value"] for r in db.execute("SELECT key, value FROM meta")}
    config = json.loads(meta.get("config", "{}"))
    ladder = [r["level"] for r in config.get("ladder", [])]
    designs = {
        r["design_id"]: (bool(r["holdout"]), [r[name] for name in PARAMETER_NAMES])
        for r in db.execute("SELECT * FROM designs")
    }
    status: dict[tuple[int, str], str] = {}
    wall: dict[tuple[int, str], float] = {}
    for r in db.execute("SELECT design_id, level, status, wall_time_s FROM evaluations"):
        status[(r["design_id"], r["level"])] = r["status"]
        wall[(r["design_id"], r["level"])] = r["wall_time_s"]
    quarantined = [dict(r) for r in db.execute("SELECT * FROM quarantine ORDER BY design_id")]

    def passes_up_to(design_id: int, rung: int) -> bool:
        return all(status.get((design_id, ladder[k])) == "feasible" for k in range(rung + 1))

    levels = []
    for rung, level in enumerate(ladder):
        mine = [k for k in status if k[1] == level]
        times = [wall[k] for k in mine]
        total = float(sum(times))
        levels.append(
            {
                "level": level,
                "rung": rung,
                "evaluated": len(mine),
                **{s: sum(1 for k in mine if status[k] == s) for s in results_db.STATUSES},
                "quarantined": sum(1 for q in quarantined if q["level"] == level),
                "survivors": sum(1 for d in designs if passes_up_to(d, rung)),
                "wall_time_s": total,
                "median_wall_time_s": median(times) if times else None,
                "designs_per_s": len(mine) / total if total > 0 else None,
            }
        )

    planners = []
    for r in db.execute(
        "SELECT level, planner, COUNT(*) AS runs, SUM(solved) AS solved FROM runs "
        "GROUP BY level, planner"
    ):
        rows = db.execute(
            "SELECT time_s, tree_size FROM runs WHERE level = ? AND planner = ?",
            (r["level"], r["planner"]),
        ).fetchall()
        planners.append(
            {
                "level": r["level"],
                "planner": r["planner"],
                "runs": r["runs"],
                "solved": r["solved"],
                "solved_fraction": r["solved"] / r["runs"],
                "median_time_s": median(x["time_s"] for x in rows),
                "median_tree_size": median(x["tree_size"] for x in rows),
            }
        )
    order = {level: i for i, level in enumerate(ladder)}
    planners.sort(key=lambda p: (order.get(p["level"], 99), p["planner"]))

    holdout = [d for d, (h, _) in designs.items() if h]
    pruning, ladder_pruning = [], []
    speedup = None
    if ladder:
        top = ladder[-1]
        judged = [d for d in holdout if (d, top) in status]
        truth = {d: status[(d, top)] == "feasible" for d in judged}
        for rung, level in enumerate(ladder[:-1]):
            own = [
                (status[(d, level)] == "feasible", truth[d]) for d in judged if (d, level) in status
            ]
            cumulative = [(passes_up_to(d, rung), truth[d]) for d in judged]
            pruning.append({"level": level, **_confusion(own)})
            ladder_pruning.append({"level": level, **_confusion(cumulative)})
        speedup = _speedup(ladder, designs, wall, passes_up_to, judged)

    best = []
    if ladder:
        top = ladder[-1]
        for d in sorted(d for d in designs if status.get((d, top)) == "feasible"):
            exits = db.execute(
                "SELECT orientation, MIN(exit_time_s) AS t FROM runs WHERE design_id = ? "
                "AND level = ? AND solved = 1 GROUP BY orientation",
                (d, top),
            ).fetchall()
            if len(exits) == 2:
                best.append(
                    {
                        "design_id": d,
                        "values": designs[d][1],
                        "exit_time_s": max(e["t"] for e in exits),
                    }
                )
        best.sort(key=lambda b: (b["exit_time_s"], b["design_id"]))
    return {
        "name": config.get("name", "sweep"),
        "results_key": meta.get("results_key"),
        "designs": len(designs),
        "holdout": len(holdout),
        "ladder": ladder,
        "feeder": config.get("feeder", {}),
        "levels": levels,
        "planners": planners,
        "pruning": pruning,
        "ladder_pruning": ladder_pruning,
        "speedup": speedup,
        "best": best[:BEST_DESIGNS],
        "quarantined": quarantined,
    }


def _speedup(ladder, designs, wall, passes_up_to, judged) -> dict[str, Any] | None:
    """The ladder's worker time against every design at the top level (see module)."""
    top = ladder[-1]
    needed = 0.0
    for (d, level), t in wall.items():
        rung = ladder.index(level)
        if rung == 0 or passes_up_to(d, rung - 1):
            needed += t
    samples = np.array([wall[(d, top)] for d in judged])
    if len(samples) == 0 or needed <= 0.0:
        return None
    n = len(designs)
    estimate = n * float(samples.mean())
    rng = np.random.default_rng(0)
    means = samples[rng.integers(0, len(samples), (BOOTSTRAP_SAMPLES, len(samples)))].mean(1)
    low, high = (n * float(np.quantile(means, q)) for q in (0.025, 0.975))
    return {
        "ladder_cost_s": needed,
        "dynamic_cost_s": estimate,
        "dynamic_cost_ci": [low, high],
        "speedup": estimate / needed,
        "speedup_ci": [low / needed, high / needed],
        "holdout_n": len(samples),
        "top_level": top,
    }


def summary_table(summary: dict[str, Any]) -> str:
    """The summary as a plain-text table for the terminal."""
    lines = [
        f"sweep '{summary['name']}': {summary['designs']} designs, "
        f"{summary['holdout']} in the holdout",
        f"{'level':<10} {'evaluated':>9} {'feasible':>8} {'infeas.':>7} {'degen.':>6} "
        f"{'quarant.':>8} {'survivors':>9} {'designs/s':>9}",
    ]
    for lv in summary["levels"]:
        rate = lv["designs_per_s"]
        lines.append(
            f"{lv['level']:<10} {lv['evaluated']:>9} {lv['feasible']:>8} {lv['infeasible']:>7} "
            f"{lv['degenerate']:>6} {lv['quarantined']:>8} {lv['survivors']:>9} "
            f"{(f'{rate:.2f}' if rate else '-'):>9}"
        )
    for p in summary["pruning"]:
        if p["n"]:
            lines.append(
                f"pruning by {p['level']} (holdout n={p['n']}): precision {_pct(p['precision'])} "
                f"[{_pct(p['precision_ci'][0])}, {_pct(p['precision_ci'][1])}], "
                f"recall {_pct(p['recall'])} "
                f"[{_pct(p['recall_ci'][0])}, {_pct(p['recall_ci'][1])}]"
            )
    s = summary["speedup"]
    if s:
        lines.append(
            f"speed-up of the ladder over {s['top_level']} only: {s['speedup']:.2f}x "
            f"[{s['speedup_ci'][0]:.2f}, {s['speedup_ci'][1]:.2f}] "
            f"({s['ladder_cost_s']:.0f} s of worker time vs ~{s['dynamic_cost_s']:.0f} s)"
        )
    for b in summary["best"][:3]:
        lines.append(f"best: design {b['design_id']}, exit time {b['exit_time_s']:.2f} s")
    for q in summary["quarantined"]:
        lines.append(f"quarantined: design {q['design_id']} at {q['level']}: {q['reason']}")
    return "\n".join(lines)


def _pct(x: float | None) -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{100 * x:.0f}%"
