"""What the agreement suite reports, computed from the drop rows alone (plain dicts for JSON).

- success: per design, entry and engine the fraction of drops that left heavy end down, with a
  Wilson 95% interval (:func:`experiments.proportions.wilson_interval`), and P(both entries);
- outcomes: per design and entry the outcome classes (:mod:`experiments.drop.outcomes`) side by
  side, one count per engine;
- pairs: for every pair of engines, over the same drops, how often they agree on success and on
  the outcome class (Wilson intervals), and the 2 x 2 table of successes;
- verdicts: per design and engine the verdict's decision on these trials
  (:func:`experiments.drop.verdict.decide`: works when every entry's lower bound clears the
  target, fails when some upper bound is below it), the pairs' agreement over designs, and the
  designs whose partfeeder verdict differs from both peers while the peers agree;
- lip: per engine the ratio of the speed just past the lip to the sliding closed form
  (:mod:`.lip`): quantiles, minimum, and the drops below ``SLOW``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np

from experiments.bench.agreement.lip import SLOW
from experiments.bench.agreement.suite import DropRow
from experiments.drop.verdict import CLASSES, UNBUILDABLE, decide
from experiments.proportions import wilson_interval


def _fraction(k: int, n: int) -> dict:
    lo, hi = wilson_interval(k, n)
    return {"k": k, "n": n, "p": k / n if n else math.nan, "interval": [lo, hi]}


def _index(rows: Sequence[DropRow]) -> dict[tuple[str, int, str, str], DropRow]:
    return {(r.design, r.trial, r.entry, r.engine): r for r in rows}


def designs_of(rows: Sequence[DropRow]) -> list[str]:
    """The designs in the order they were run."""
    return list(dict.fromkeys(r.design for r in rows))


def engines_of(rows: Sequence[DropRow]) -> list[str]:
    return list(dict.fromkeys(r.engine for r in rows))


def entries_of(rows: Sequence[DropRow]) -> list[str]:
    """The entry orientations in the order they were run (the peg feeder's two, or a device
    family's, issue 35)."""
    return list(dict.fromkeys(r.entry for r in rows))


def success_table(rows: Sequence[DropRow]) -> dict:
    """design -> engine -> {entry: fraction, "both": fraction}."""
    out: dict = {}
    by = _index(rows)
    entries = entries_of(rows)
    for design in designs_of(rows):
        trials = sorted({r.trial for r in rows if r.design == design})
        out[design] = {}
        for engine in engines_of(rows):
            cell = {}
            for entry in entries:
                k = sum(by[(design, t, entry, engine)].success for t in trials)
                cell[entry] = _fraction(k, len(trials))
            both = sum(all(by[(design, t, e, engine)].success for e in entries) for t in trials)
            cell["both"] = _fraction(both, len(trials))
            out[design][engine] = cell
    return out


def outcome_table(rows: Sequence[DropRow]) -> dict:
    """design -> entry -> outcome class -> engine -> drops (classes some engine saw)."""
    out: dict = {}
    engines = engines_of(rows)
    classes = list(dict.fromkeys([*CLASSES, *(r.outcome for r in rows)]))  # a family's too
    for design in designs_of(rows):
        out[design] = {}
        for entry in entries_of(rows):
            counts = {c: dict.fromkeys(engines, 0) for c in classes}
            for r in rows:
                if r.design == design and r.entry == entry:
                    counts[r.outcome][r.engine] += 1
            out[design][entry] = {c: v for c, v in counts.items() if any(v.values())}
    return out


def pair_table(rows: Sequence[DropRow]) -> dict:
    """ "a vs b" -> agreement on success and on outcome over the drops both ran (unbuildable
    trials left out: no engine ran them), the 2 x 2 success table, and per design."""
    by = _index(rows)
    keys = sorted(
        {(r.design, r.trial, r.entry) for r in rows if r.outcome != UNBUILDABLE},
        key=lambda k: (designs_of(rows).index(k[0]), k[1], k[2]),
    )
    out = {}
    for a, b in itertools.combinations(engines_of(rows), 2):
        same_success = same_outcome = 0
        table = {"both": 0, f"{a} only": 0, f"{b} only": 0, "neither": 0}
        per_design: dict[str, list[int]] = {}
        for key in keys:
            ra, rb = by[(*key, a)], by[(*key, b)]
            agree = ra.success == rb.success
            same_success += agree
            same_outcome += ra.outcome == rb.outcome
            cell = (
                "both" if ra.success and rb.success
                else f"{a} only" if ra.success
                else f"{b} only" if rb.success
                else "neither"
            )  # fmt: skip
            table[cell] += 1
            d = per_design.setdefault(key[0], [0, 0])
            d[0] += agree
            d[1] += 1
        out[f"{a} vs {b}"] = {
            "success": _fraction(same_success, len(keys)),
            "outcome": _fraction(same_outcome, len(keys)),
            "table": table,
            "per_design": {d: _fraction(k, n) for d, (k, n) in per_design.items()},
        }
    return out


def verdict_table(rows: Sequence[DropRow], target: float) -> dict:
    """Per design and engine the decision on these trials; per pair the designs agreed on;
    the designs where partfeeder differs from both peers and the peers agree."""
    success = success_table(rows)
    engines = engines_of(rows)
    entries = entries_of(rows)
    decisions: dict[str, dict[str, str]] = {}
    for design, by_engine in success.items():
        decisions[design] = {}
        for engine, cell in by_engine.items():
            counts = [cell[e]["k"] for e in entries]
            decisions[design][engine] = decide(counts, cell[entries[0]]["n"], target)
    pairs = {}
    for a, b in itertools.combinations(engines, 2):
        same = sum(decisions[d][a] == decisions[d][b] for d in decisions)
        pairs[f"{a} vs {b}"] = {"agree": same, "designs": len(decisions)}
    odd = []
    peers = [e for e in engines if e != "partfeeder"]
    if "partfeeder" in engines and len(peers) >= 2:
        for d, by in decisions.items():
            if len({by[p] for p in peers}) == 1 and by["partfeeder"] != by[peers[0]]:
                odd.append(d)
    return {"target": target, "decisions": decisions, "pairs": pairs, "partfeeder_odd": odd}


def lip_table(rows: Sequence[DropRow]) -> dict:
    """engine -> lip-speed ratio statistics over the drops that reached the lip, and per
    design and entry the drops below ``SLOW``."""
    out = {}
    for engine in engines_of(rows):
        mine = [r for r in rows if r.engine == engine and r.outcome != UNBUILDABLE]
        ratios = np.array([r.lip_ratio for r in mine if math.isfinite(r.lip_ratio)])
        slow = int(np.sum(ratios < SLOW))
        per = {}
        for design in designs_of(rows):
            for entry in entries_of(rows):
                sel = [r.lip_ratio for r in mine if r.design == design and r.entry == entry]
                fin = [v for v in sel if math.isfinite(v)]
                per[f"{design} {entry}"] = {
                    "slow": int(sum(v < SLOW for v in fin)),
                    "measured": len(fin),
                    "min": float(min(fin)) if fin else math.nan,
                }
        q = np.quantile(ratios, [0.0, 0.05, 0.25, 0.5, 0.75, 0.95, 1.0]) if len(ratios) else []
        out[engine] = {
            "drops": len(mine),
            "measured": len(ratios),
            "slow": slow,
            "slow_fraction": _fraction(slow, len(ratios)),
            "quantiles": dict(zip(("min", "q05", "q25", "median", "q75", "q95", "max"),
                                  (float(v) for v in q), strict=False)),
            "per_design_entry": per,
        }  # fmt: skip
    return out


def timing_table(rows: Sequence[DropRow]) -> dict:
    """engine -> drops, total and mean wall time (s), mean simulated time per drop (s)."""
    out = {}
    for engine in engines_of(rows):
        mine = [r for r in rows if r.engine == engine and r.outcome != UNBUILDABLE]
        wall = sum(r.wall_time for r in mine)
        out[engine] = {
            "drops": len(mine),
            "wall_s": wall,
            "mean_wall_s": wall / len(mine) if mine else math.nan,
            "mean_T_s": float(np.mean([r.T for r in mine])) if mine else math.nan,
            "h": mine[0].h if mine else math.nan,
        }
    return out


def all_tables(rows: Sequence[DropRow], target: float) -> dict:
    """Every table of the report."""
    return {
        "success": success_table(rows),
        "outcomes": outcome_table(rows),
        "pairs": pair_table(rows),
        "verdicts": verdict_table(rows, target),
        "lip": lip_table(rows),
        "timing": timing_table(rows),
    }
