"""What a sweep found and what the ladder bought, from its results database (plain data).

- Per level: designs evaluated, their verdicts, survivors (feasible at this level and every
  one below), evaluation time and designs per second of worker time.
- Per level and planner: runs, solved fraction, median time and tree size (Planner Arena's
  main columns).
- The truth: the passive verdict when the ladder has a ``passive`` rung (a feeder is passive;
  the planning levels say whether any input could steer the part, necessary, not
  sufficient), else the top level.
- Pruning: each other level's verdict against the truth. Recall = P(passes the level |
  truth passes) is what pruning risks (a design that works, thrown away); it is measured on
  every design the truth passes that has the level's result, when no rung below the two
  could have stopped it on the way (the passive rung first, planning rungs that do not
  prune: the designs that work climb every rung, a census), else on the holdout (a random
  sample of the designs that climbed every rung); ``recall_n`` and ``recall_basis`` say
  which, and ``thrown_away`` names the designs that work that the level would have pruned
  (not feasible there: infeasible, or ``unknown``: not found within the budget).
  Precision = P(truth passes | passes the level) needs the failing designs' results, so it
  is measured on the holdout (``n``). Wilson 95% intervals. ``ladder_pruning`` gives the
  same on the holdout for the ladder's own decision up to a level below the truth (not
  stopped there or below, by each rung's ``prunes``).
- Speed-up: the worker time the ladder spent up to the truth (evaluations of designs that no
  lower rung had stopped; the rungs above the truth prune nothing and are not counted)
  against the estimated time of evaluating every design at the truth level only (its mean
  evaluation time on the audit, or the holdout, times the number of designs), with a seeded
  bootstrap 95% interval over that sample.
- Pipelines (with a passive rung): every order of rungs that ends with the passive verdict,
  its planning rungs pruning whatever is not feasible: cost per design on the holdout
  (``n``: its failing designs' planning costs are known only there), recall of the designs
  that work on the same basis as a level's recall (``recall_n``, ``recall_basis``), the
  designs that work it would throw away, and the speed-up over the passive rung alone.
- Thrown away (with the passive rung above a rung that prunes, as in ``paper.yaml``): the
  designs outside the holdout that the ladder stopped before their verdict, and how many of
  them work, estimated from the holdout designs it would have stopped (an estimate with a
  Wilson 95% interval: those designs have no verdict).
- Compile time is charged to no level: the workers load the kernels before their first job
  (``job.warm_up``), the parent compiles them before the workers start.
- Passive: verdicts (works / fails / undecided), the fraction of designs that work with its
  interval, drops, trials per verdict and drops per second of worker time.
- Best designs: with a passive rung, the designs that work ranked by the lower bound of
  P(both), then by the slower entry's mean exit time; else feasible at the top level, ranked
  by the slower entry's fastest planned exit time (Eq. 10).
- The design parameters (``parameters``: the database's design columns) and, for a device
  family's sweep (issue 24), the family (``family``: name, parameters, box, entries; None for
  the 12-parameter feeder).
"""

from __future__ import annotations

import json
import math
import sqlite3
from pathlib import Path
from statistics import median
from typing import Any

import numpy as np

from experiments.names import NECESSARY, PASSIVE, SCREEN
from experiments.proportions import wilson_interval
from experiments.sweep import results_db

BOOTSTRAP_SAMPLES = 2000
BEST_DESIGNS = 6


def _recall(works: list, lost: list, basis: str) -> dict[str, Any]:
    """The recall of the designs that work (``works``) less those a ladder threw away
    (``lost``), with its Wilson interval, count and basis (what "works" was measured by)."""
    ratio = _ratio(len(works) - len(lost), len(works))
    return {
        "recall": ratio["value"],
        "recall_ci": ratio["ci"],
        "recall_n": len(works),
        "recall_basis": basis,
        "thrown_away": lost,
    }


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
    parameters = results_db.parameter_names(db)
    designs = {
        r["design_id"]: (bool(r["holdout"]), [r[name] for name in parameters])
        for r in db.execute("SELECT * FROM designs")
    }
    status: dict[tuple[int, str], str] = {}
    wall: dict[tuple[int, str], float] = {}
    for r in db.execute("SELECT design_id, level, status, wall_time_s FROM evaluations"):
        status[(r["design_id"], r["level"])] = results_db.status_of(r["level"], r["status"])
        wall[(r["design_id"], r["level"])] = r["wall_time_s"]
    quarantined = [dict(r) for r in db.execute("SELECT * FROM quarantine ORDER BY design_id")]
    prunes = _prunes(config.get("ladder", []))

    def passes_up_to(design_id: int, rung: int) -> bool:
        return all(status.get((design_id, ladder[k])) == "feasible" for k in range(rung + 1))

    def kept_up_to(design_id: int, rung: int) -> bool:
        """No rung up to ``rung`` stopped the design (outside the holdout)."""
        return all(
            _climbs(status.get((design_id, ladder[k])), prunes[ladder[k]]) for k in range(rung + 1)
        )

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
    # the audit: designs that reached the verdict whatever the rungs below it said (with the
    # holdout, an unbiased sample of what those rungs stopped)
    audit = sorted(set(holdout) | _audit_ids(config))
    truth_level = PASSIVE if PASSIVE in ladder else (ladder[-1] if ladder else None)
    pruning, ladder_pruning = [], []
    speedup = None
    pipelines: list[dict[str, Any]] = []
    thrown_away = None
    if truth_level is not None:
        replay = _Replay(ladder, prunes, truth_level, (holdout, audit), status)
        judged = [d for d in holdout if (d, truth_level) in status]
        audited = [d for d in audit if (d, truth_level) in status]  # holdout included
        truth = {d: status[(d, truth_level)] == "feasible" for d in audited}
        for rung, level in enumerate(ladder):
            if level == truth_level:
                continue
            below = rung < ladder.index(truth_level)  # the audit reached the truth from here
            sample = audited if below else judged
            own = [
                (status[(d, level)] == "feasible", truth[d]) for d in sample if (d, level) in status
            ]
            pruning.append(
                {
                    "level": level,
                    "prunes": prunes[level],
                    **_confusion(own),
                    "basis": _basis(holdout, audit) if below else "the holdout",
                    **replay.recall([level]),
                }
            )
            if below:
                cumulative = [(kept_up_to(d, rung), truth[d]) for d in audited]
                ladder_pruning.append({"level": level, **_confusion(cumulative)})
        speedup = _speedup(ladder, truth_level, designs, wall, kept_up_to, (judged, audited))
        if speedup is not None:
            speedup.update(_ladder_recall(ladder, truth_level, status, kept_up_to, replay))
        if truth_level == PASSIVE:
            pipelines = _pipelines(ladder, (holdout, audit), status, wall, replay)
            thrown_away = _thrown_away(ladder, designs, audit, status, kept_up_to)

    stored_verdicts = results_db.verdicts(db)
    passive = _passive_summary(ladder, (holdout, audit), status, wall, stored_verdicts)
    if passive is not None:
        rung = next(r for r in config["ladder"] if r["level"] == PASSIVE)
        passive["rule"] = {"rule": "wilson", **(rung.get("verdict") or {})}
    best = (
        _best_by_verdict(designs, stored_verdicts)
        if PASSIVE in ladder
        else _best_by_planning(db, ladder, designs, status)
    )
    return {
        "name": config.get("name", "sweep"),
        "results_key": meta.get("results_key"),
        "designs": len(designs),
        "holdout": len(holdout),
        "ladder": ladder,
        "feeder": config.get("feeder", {}),
        "parameters": list(parameters),
        "family": _family_summary(results_db.stored_family(db)),
        "levels": levels,
        "planners": planners,
        "truth": truth_level,
        "pruning": pruning,
        "ladder_pruning": ladder_pruning,
        "speedup": speedup,
        "passive": passive,
        "pipelines": pipelines,
        "thrown_away": thrown_away,
        "best": best[:BEST_DESIGNS],
        "quarantined": quarantined,
    }


def _family_summary(family: dict[str, Any] | None) -> dict[str, Any] | None:
    """The sweep's device family as the summary shows it (its name, parameters, box and
    entries, not its file's text), or None: the 12-parameter feeder."""
    if family is None:
        return None
    return {k: family[k] for k in ("name", "parameters", "low", "high", "entries")}


def _best_by_planning(db, ladder, designs, status) -> list[dict[str, Any]]:
    """Without a passive rung: feasible at the top level, ranked by the slower entry's
    fastest planned exit time (Eq. 10)."""
    best: list[dict[str, Any]] = []
    if not ladder:
        return best
    top = ladder[-1]
    for d in sorted(d for d in designs if status.get((d, top)) == "feasible"):
        exits = db.execute(
            "SELECT orientation, MIN(exit_time_s) AS t FROM runs WHERE design_id = ? "
            "AND level = ? AND solved = 1 GROUP BY orientation",
            (d, top),
        ).fetchall()
        if len(exits) == 2:
            best.append(
                {"design_id": d, "values": designs[d][1], "exit_time_s": max(e["t"] for e in exits)}
            )
    best.sort(key=lambda b: (b["exit_time_s"], b["design_id"]))
    return best


def _best_by_verdict(designs, stored: dict[int, dict[str, Any]]) -> list[dict[str, Any]]:
    """With a passive rung: the designs that work, ranked by the lower bound of P(both)
    (the probability that one part goes through heavy end down from either entry), then by
    the slower entry's mean exit time T (Eq. 10's second term), then by id."""
    best = []
    for d, verdict in stored.items():
        if verdict["decision"] != "works" or d not in designs:
            continue
        means = [per["mean_exit_time_s"] for per in verdict["orientations"].values()]
        exit_time = max(means) if all(m is not None for m in means) else None
        best.append(
            {"design_id": d, "values": designs[d][1], "exit_time_s": exit_time, "verdict": verdict}
        )
    best.sort(
        key=lambda b: (
            -b["verdict"]["both"]["interval"][0],
            math.inf if b["exit_time_s"] is None else b["exit_time_s"],
            b["design_id"],
        )
    )
    return best


def _passive_summary(ladder, samples, status, wall, stored) -> dict[str, Any] | None:
    """The passive rung's counts, the fraction of designs that work (over every design when
    the rung is first, else over the audit or the holdout, whose designs reach it whatever the
    rungs below say: an unbiased sample), and the verdicts' cost."""
    if PASSIVE not in ladder:
        return None
    holdout, audit = samples
    evaluated = [d for (d, level) in status if level == PASSIVE]
    decisions = {d: stored[d]["decision"] for d in evaluated if d in stored}
    # first, or after sound or tested rungs only: every design has a verdict, a proof that
    # it fails or a failed test
    first = all(level in (*SOUND, *TESTED) for level in ladder[: ladder.index(PASSIVE)])
    proven = sorted(
        {
            d
            for (d, level), s in status.items()
            if level in (*SOUND, *TESTED) and s == "infeasible" and (d, PASSIVE) not in status
        }
    )
    basis = [*evaluated, *proven] if first else [d for d in audit if (d, PASSIVE) in status]
    works = sum(1 for d in basis if status.get((d, PASSIVE)) == "feasible")
    fraction = _ratio(works, len(basis))
    trials = [stored[d]["drops"] for d in decisions]
    seconds = sum(wall[(d, PASSIVE)] for d in evaluated)
    drops = 2 * sum(trials)
    return {
        "evaluated": len(evaluated),
        **{k: sum(1 for v in decisions.values() if v == k) for k in results_db.DECISIONS},
        "degenerate": sum(1 for d in evaluated if status[(d, PASSIVE)] == "degenerate"),
        "works_fraction": fraction["value"],
        "works_ci": fraction["ci"],
        "works_basis": "every design" if first else _basis(holdout, audit),
        "works_n": len(basis),
        "works_in_basis": works,
        "drops": drops,
        "mean_trials": sum(trials) / len(trials) if trials else None,
        "drops_per_s": drops / seconds if seconds > 0 else None,
        "target": next(iter(stored.values()))["target"] if stored else None,
    }


# Rungs whose "infeasible" is a proof that the design cannot work (docs/necessary.md): a design
# they stop is a failing design, not a lost one, so they neither hide a design that works from
# a recall nor throw one away.
SOUND = (NECESSARY,)
# Rungs whose "infeasible" is a sequential test's, with a stated error rate (the screen:
# docs/verdict.md): their stops count as failing designs in the passive fraction (as the
# verdict's own "fails" does, which is a test too), but they may hide a design that works, so
# their recall and what they threw away are measured on the holdout.
TESTED = (SCREEN,)


def _audit_ids(config: dict[str, Any]) -> set[int]:
    """The audit's design ids from the stored config (none before audits existed)."""
    audit = config.get("audit") or {}
    if not audit.get("fraction"):
        return set()
    from experiments.sweep.ladder import holdout_ids

    count = int(config["designs"]["count"])
    return holdout_ids(count, float(audit["fraction"]), int(audit.get("seed", 0)))


def _basis(holdout: list[int], sample: list[int]) -> str:
    """What a sample of designs that reached the verdict whatever is called."""
    return "the audit" if len(sample) > len(holdout) else "the holdout"


def _prunes(rungs: list[dict[str, Any]]) -> dict[str, bool]:
    """Level -> whether a design not shown feasible there stopped climbing (outside the
    holdout), from the stored config: a planning rung's ``prunes`` (absent in a database
    written before it existed, whose sweep pruned on every planning rejection: True); the
    passive rung always stops a design that does not work; the screen stops the designs it
    fails (a test: :data:`TESTED`), not the ones it leaves undecided."""
    return {
        str(r["level"]): r["level"] != SCREEN
        and (bool(r.get("prunes", True)) or r["level"] == PASSIVE)
        for r in rungs
    }


def _climbs(status: str | None, prunes: bool) -> bool:
    """Whether a design with ``status`` at a rung that ``prunes`` (or not) went on up."""
    return status == "feasible" or (status == "unknown" and not prunes)


class _Replay:
    """Which designs a recall rests on: for the levels ``needed`` (and the truth), every
    design the truth passes that has all their results, when no rung below the highest of
    them (the truth aside) could have stopped a design on its way up (each such rung does
    not prune, so reaching them did not depend on their verdicts, or stops only designs
    that fail: proven, or by a test with a stated error) and none of them is such a test;
    else the holdout's."""

    def __init__(self, ladder, prunes, truth_level, samples, status):
        self.ladder, self.prunes, self.truth = ladder, prunes, truth_level
        self.holdout, self.audit = samples
        self.status = status
        self.designs = sorted({d for d, _ in status})

    def census(self, needed: list[str]) -> bool:
        """No rung below the highest of ``needed`` and the truth could stop a design on its
        way up but by a proof or a test (whose stops are failing designs)."""
        top = max(self.ladder.index(level) for level in [*needed, self.truth])
        return not any(
            self.prunes[level]
            for level in self.ladder[:top]
            if level != self.truth and level not in (*SOUND, *TESTED)
        )

    def pool(self, needed: list[str]) -> tuple[list[int], str]:
        """The designs a recall of ``needed`` counts, and what they are called: every design
        on a census with no test among ``needed``; the audit's (holdout included: they
        reached the verdict whatever the rungs below it said) when the tests among
        ``needed`` stand below the truth and either the rest is a census or every level is
        below the truth; else the holdout's."""
        truth = self.ladder.index(self.truth)
        census = self.census(needed)
        tested = [level for level in needed if level in TESTED]
        if census and not tested:
            return self.designs, "every design"
        below = all(self.ladder.index(level) < truth for level in needed)
        tests_below = all(self.ladder.index(level) < truth for level in tested)
        if below or (census and tests_below):
            return self.audit, _basis(self.holdout, self.audit)
        return self.holdout, "the holdout"

    def recall(self, needed: list[str]) -> dict[str, Any]:
        pool, basis = self.pool(needed)
        works = [
            d
            for d in pool
            if self.status.get((d, self.truth)) == "feasible"
            and all((d, level) in self.status for level in needed)
        ]
        lost = [d for d in works if any(self.status[(d, lv)] != "feasible" for lv in needed)]
        return _recall(works, lost, basis)


def _pipelines(ladder, samples, status, wall, replay: _Replay) -> list[dict[str, Any]]:
    """What each pipeline would cost and keep: every ordered subset of the ladder's other
    rungs followed by the passive rung, each rung pruning what it does not show feasible.
    Cost: replayed on the designs evaluated at every rung of the pipeline whatever the
    rungs' verdicts (the audit's when every rung stands below the verdict, else the
    holdout's: ``n`` designs, ``basis``), from their stored times: the mean worker seconds
    per design (seeded bootstrap 95% interval); a design pays for each rung it reaches.
    Recall: the fraction of the designs that work that reach the passive rung, on
    :class:`_Replay`'s basis (Wilson 95%; ``recall_n`` designs), with the ones it would
    throw away. The speed-up is over the passive rung alone on the same designs, with a
    paired bootstrap 95% interval (the same resampled designs for both costs)."""
    holdout, audit = samples
    others = [level for level in ladder if level != PASSIVE]
    top = ladder.index(PASSIVE)
    out = []
    for mask in range(2 ** len(others)):
        rungs = [level for k, level in enumerate(others) if mask >> k & 1] + [PASSIVE]
        pool = audit if all(ladder.index(level) < top for level in rungs[:-1]) else holdout
        full = [d for d in pool if all((d, level) in wall for level in rungs)]
        costs = np.array([_replayed_cost(d, rungs, status, wall) for d in full])
        alone = np.array([wall[(d, PASSIVE)] for d in full])
        mean: float | None = None
        ci: list[float | None] = [None, None]
        speedup: float | None = None
        speedup_ci: list[float | None] = [None, None]
        depth = [_reached(d, rungs, status) for d in full]
        reached = [sum(1 for k in depth if k > rung) for rung in range(len(rungs))]
        # a rung after the first that no design of the sample reached: the row's cost is its
        # first rungs' alone, and a speed-up from it would be the screen's (issue 36: 14.73x)
        unreached = [level for level, n in zip(rungs, reached, strict=True) if n == 0]
        if len(full) and not unreached:
            resample = np.random.default_rng(0).integers(
                0, len(full), (BOOTSTRAP_SAMPLES, len(full))
            )
            means, alone_means = costs[resample].mean(1), alone[resample].mean(1)
            mean = float(costs.mean())
            ci = [float(np.quantile(means, 0.025)), float(np.quantile(means, 0.975))]
            if mean > 0.0:
                speedup = float(alone.mean()) / mean
            if bool(np.all(means > 0.0)):
                ratios = alone_means / means
                speedup_ci = [float(np.quantile(ratios, 0.025)), float(np.quantile(ratios, 0.975))]
        out.append(
            {
                "rungs": rungs,
                "cost_s": mean,
                "cost_ci": ci,
                "n": len(full),
                "reached": reached,
                "unreached": unreached,
                "basis": _basis(holdout, pool),
                **replay.recall(rungs[:-1]),
                "speedup": speedup,
                "speedup_ci": speedup_ci,
            }
        )
    return out


def _ladder_recall(ladder, truth_level, status, kept_up_to, replay: _Replay) -> dict[str, Any]:
    """The recall of the ladder's own decisions up to the truth (the designs that work that
    no rung below it stopped), on :class:`_Replay`'s basis for the rungs below the truth: the
    recall that goes beside the ladder's speed-up (issue 36: "4.26x [2.63, 6.55]" was printed
    for a ladder whose recall was 0 of 2). With nothing below the truth, every design that
    works is kept (``recall_basis`` "every design")."""
    top = ladder.index(truth_level)
    below = ladder[:top]
    pool, basis = replay.pool(below) if below else (replay.designs, "every design")
    works = [
        d
        for d in pool
        if status.get((d, truth_level)) == "feasible"
        and all((d, level) in status for level in below)
    ]
    lost = [d for d in works if below and not kept_up_to(d, top - 1)]
    return _recall(works, lost, basis)


def _reached(d: int, rungs: list[str], status) -> int:
    """How many of ``rungs`` design ``d`` reaches, stopping at the first it does not pass."""
    for k, level in enumerate(rungs):
        if status[(d, level)] != "feasible":
            return k + 1
    return len(rungs)


def _replayed_cost(d: int, rungs: list[str], status, wall) -> float:
    """Worker seconds design ``d`` would cost climbing ``rungs``, stopping at the first rung
    it does not pass."""
    cost = 0.0
    for level in rungs:
        cost += wall[(d, level)]
        if status[(d, level)] != "feasible":
            break
    return cost


def _thrown_away(ladder, designs, holdout, status, kept_up_to) -> dict[str, Any] | None:
    """With the passive rung above a rung that stopped designs: the designs outside the
    ``holdout`` (here: the holdout and the audit, which reach the verdict whatever) stopped
    before their verdict (``pruned``), and how many of them work, estimated as ``pruned``
    times the fraction that work of the sample's designs the ladder would have stopped there
    (Wilson 95% interval): those designs have no verdict to count."""
    top = ladder.index(PASSIVE)
    if all(level in SOUND for level in ladder[:top]):
        return None  # nothing below the verdict, or only proofs

    def stopped(d: int) -> bool:
        """Stopped below the verdict by a rung that is not sound (a sound rung's stop is a
        proof that the design fails)."""
        for k in range(top):
            if (d, ladder[k]) in status and not kept_up_to(d, k):
                return ladder[k] not in SOUND
        return False

    inside = set(holdout)
    pruned = [d for d in designs if d not in inside and stopped(d)]
    sample = [d for d in holdout if (d, PASSIVE) in status and stopped(d)]
    working = [d for d in sample if status[(d, PASSIVE)] == "feasible"]
    low, high = wilson_interval(len(working), len(sample))
    share = len(working) / len(sample) if sample else None
    return {
        "basis": _basis([d for d, (h, _) in designs.items() if h], holdout),
        "pruned": len(pruned),
        "holdout_pruned": len(sample),
        "holdout_pruned_working": working,
        "estimate": None if share is None else share * len(pruned),
        "ci": [low * len(pruned), high * len(pruned)] if sample else [None, None],
    }


def _speedup(ladder, truth_level, designs, wall, kept_up_to, samples) -> dict[str, Any] | None:
    """The ladder's worker time up to the truth level against every design at the truth
    level only (see module); the rungs above the truth (planning the designs that work) prune
    nothing and are not counted. The truth's mean cost is taken on the audit (the holdout
    when there is none: ``samples`` is both)."""
    judged, audited = samples
    top = ladder.index(truth_level)
    needed = 0.0
    for (d, level), t in wall.items():
        rung = ladder.index(level)
        if rung <= top and (rung == 0 or kept_up_to(d, rung - 1)):
            needed += t
    sample = audited if len(audited) > len(judged) else judged
    samples = np.array([wall[(d, truth_level)] for d in sample])
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
        "basis": "the audit" if sample is audited and len(audited) > len(judged) else "the holdout",
        "top_level": truth_level,
    }


def summary_table(summary: dict[str, Any]) -> str:
    """The summary as a plain-text table for the terminal."""
    lines = [
        f"sweep '{summary['name']}': {summary['designs']} designs, "
        f"{summary['holdout']} in the holdout",
        f"{'level':<10} {'evaluated':>9} {'feasible':>8} {'infeas.':>7} {'unknown':>7} "
        f"{'degen.':>6} {'quarant.':>8} {'survivors':>9} {'designs/s':>9}",
    ]
    for lv in summary["levels"]:
        rate = lv["designs_per_s"]
        lines.append(
            f"{lv['level']:<10} {lv['evaluated']:>9} {lv['feasible']:>8} {lv['infeasible']:>7} "
            f"{lv.get('unknown', 0):>7} {lv['degenerate']:>6} {lv['quarantined']:>8} "
            f"{lv['survivors']:>9} {(f'{rate:.2f}' if rate else '-'):>9}"
        )
    for p in summary["pruning"]:
        if p["n"] or p.get("recall_n"):
            lines.append(
                f"pruning by {p['level']}: precision {_pct(p['precision'])} "
                f"[{_pct(p['precision_ci'][0])}, {_pct(p['precision_ci'][1])}] "
                f"({p.get('basis', 'the holdout').removeprefix('the ')} n={p['n']}), "
                f"recall {_pct(p['recall'])} "
                f"[{_pct(p['recall_ci'][0])}, {_pct(p['recall_ci'][1])}] {_recall_basis(p)}"
            )
        if p.get("thrown_away"):
            lines.append(
                f"designs that work that {p['level']} would have thrown away: "
                f"{', '.join(str(d) for d in p['thrown_away'])}"
            )
    s = summary["speedup"]
    if s:
        lines.append(
            f"speed-up of the ladder up to {s['top_level']} over {s['top_level']} only: "
            f"{speedup_with_recall(s['speedup'], s.get('speedup_ci'), s)} "
            f"({s['ladder_cost_s']:.0f} s of worker time vs ~{s['dynamic_cost_s']:.0f} s)"
        )
    p = summary.get("passive")
    if p and p["works_n"]:
        trials, rate = p.get("mean_trials"), p.get("drops_per_s")
        lines.append(
            f"passive verdict: {passive_counts(p)}; "
            f"{'n/a' if trials is None else f'{trials:.1f}'} trials per verdict, "
            f"{'n/a' if rate is None else f'{rate:.0f}'} drops/s"
        )
    for pipe in summary.get("pipelines") or []:
        lines.append(pipeline_line(pipe))
    lost = summary.get("thrown_away")
    if lost:
        lines.append(thrown_away_sentence(lost))
    for b in summary["best"][:3]:
        exit_time = "n/a" if b["exit_time_s"] is None else f"{b['exit_time_s']:.2f} s"
        if "verdict" in b:
            lo, hi = b["verdict"]["both"]["interval"]
            lines.append(
                f"top: design {b['design_id']}, P(both) {b['verdict']['both']['p']:.2f} "
                f"[{lo:.2f}, {hi:.2f}], mean exit time {exit_time}"
            )
        else:
            lines.append(f"top: design {b['design_id']}, exit time {exit_time}")
    for q in summary["quarantined"]:
        lines.append(f"quarantined: design {q['design_id']} at {q['level']}: {q['reason']}")
    return "\n".join(lines)


def pipeline_line(pipe: dict[str, Any]) -> str:
    """One pipeline's line: on how many designs it was measured and how many reached each of
    its rungs; its cost and speed-up, the speed-up with its recall beside it
    (:func:`speedup_with_recall`); or, when a rung after the first saw no design of the
    sample, that it did, and no cost or speed-up (issue 36: every pipeline that starts with
    the screen printed the screen's "14.73x" when no holdout design passed it)."""
    rungs = pipe["rungs"]
    basis = pipe.get("basis", "the holdout").removeprefix("the ")
    reached = pipe.get("reached")
    sample = f"{basis} n={pipe['n']}"
    if reached is not None:
        sample += "; reached " + ", ".join(
            f"{level} {n}" for level, n in zip(rungs, reached, strict=True)
        )
    head = f"pipeline {' -> '.join(rungs)}: "
    unreached = pipe.get("unreached") or []
    if pipe["n"] and unreached:
        return (
            head + f"{sample}: no {basis} design reached {unreached[0]}, so its cost would be "
            f"the rungs below alone; no cost or speed-up is given"
        )
    cost = "n/a" if pipe["cost_s"] is None else f"{pipe['cost_s']:.2f} s/design"
    lost = pipe.get("thrown_away") or []
    return (
        head
        + f"{cost} ({sample}), speed-up "
        + speedup_with_recall(pipe["speedup"], pipe.get("speedup_ci"), pipe)
        + (f"; would throw away {', '.join(str(d) for d in lost)}" if lost else "")
    )


def speedup_with_recall(
    speedup: float | None, ci: list[float | None] | None, row: dict[str, Any]
) -> str:
    """A speed-up with its interval and, beside it, the recall it was bought at with its
    basis: "4.26x [2.63, 6.55] at recall 0% [0%, 66%] (0 of 2 that work, the holdout)". A
    speed-up is never printed alone (issue 36): with no design that works in the basis the
    recall is said to be unmeasured, and a row without a recall says so."""
    text = "-" if speedup is None else f"{speedup:.2f}x"
    low, high = ci or [None, None]
    if speedup is not None and low is not None and high is not None:
        text += f" [{low:.2f}, {high:.2f}]"
    if "recall" not in row:
        return f"{text} (its recall not recorded)"
    if row.get("recall_n") == 0:
        basis = row.get("recall_basis", "the holdout")
        return f"{text} at recall unmeasured (no design that works in {basis})"
    lo, hi = row.get("recall_ci") or [None, None]
    return f"{text} at recall {_pct(row['recall'])} [{_pct(lo)}, {_pct(hi)}] {_recall_basis(row)}"


def passive_counts(p: dict[str, Any]) -> str:
    """The passive verdict's counts, each with its own denominator named (issue 39: "4 of 30
    designs judged work (4 % [2 %, 10 %] of every design, n = 103)" read as three): the
    designs judged and how many work or are undecided, then the fraction that works of the
    basis, with its count: every design (the judged and those a sound rung proved to fail:
    none of them works) or the audit or holdout (designs judged whatever the rungs below said)."""
    lo, hi = p["works_ci"]
    n = p["works_n"]
    basis = p["works_basis"]
    works = p.get("works_in_basis", round(p["works_fraction"] * n))
    if basis == "every design":
        proven = n - p["evaluated"]
        basis = f"every design ({p['evaluated']} judged, {proven} proven to fail below)"
    return (
        f"{p['works']} of {p['evaluated']} designs judged work, {p['undecided']} undecided; "
        f"{works} of {n} in {basis} work: {_pct(p['works_fraction'])} [{_pct(lo)}, {_pct(hi)}]"
    )


def _recall_basis(row: dict[str, Any]) -> str:
    """On which designs a recall rests: '(k of n designs that work, <basis>)'."""
    n = row.get("recall_n")
    if n is None:  # a summary written before recall_n existed: the holdout's
        return "(the holdout)"
    kept = n - len(row.get("thrown_away") or [])
    return f"({kept} of {n} that work, {row.get('recall_basis', 'the holdout')})"


def thrown_away_sentence(lost: dict[str, Any]) -> str:
    """What the ladder's pruning before the verdict threw away (``summary['thrown_away']``),
    as one sentence that says the count of working designs is an estimate."""
    working = lost.get("holdout_pruned_working") or []
    basis = lost.get("basis", "the holdout")
    noun = basis.removeprefix("the ")
    if lost.get("estimate") is None:
        return (
            f"the ladder stopped {lost['pruned']} designs outside {basis} before their passive "
            f"verdict; how many of them work is not estimated (no {noun} design was stopped)"
        )
    found = f"{len(working)} of the {lost['holdout_pruned']} {noun} designs it stopped work" + (
        f": {', '.join(str(d) for d in working)}" if working else ""
    )
    if lost["pruned"] == 0:
        return f"the ladder stopped no design outside {basis} before its passive verdict; {found}"
    low, high = lost["ci"]
    return (
        f"the ladder stopped {lost['pruned']} designs outside {basis} before their passive "
        f"verdict; an estimated {lost['estimate']:.1f} [{low:.1f}, {high:.1f}] of them work "
        f"(an estimate from {basis}: {found})"
    )


def _pct(x: float | None) -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{100 * x:.0f}%"
