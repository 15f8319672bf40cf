"""Issue 36's analysis of the pool of paired drops (``issue36_pool.py``), no simulation:

- the paired coarse/fine shift of every entry of every design that works (McNemar), and
  pooled over them;
- per design, the screen's false-fail rate over ``--seeds`` resampled screens
  (:func:`experiments.drop.resampled.false_fail_rate`) for issue 21's screen, this issue's
  default, and each with the confirmation at the verdict's step, with the mean drops a
  screen ran (its cost in drops at each step: coarse + fine); without confirmation also the
  rate exactly for the pool's per-entry p at the coarse step (each resampled entry is a coin
  of that p: :func:`experiments.drop.operating.screen_operating_point`).

``python docs/measurements/issue36_replay.py docs/measurements/issue36_pool.json``
prints markdown tables.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from experiments.drop.operating import screen_operating_point
from experiments.drop.resampled import EntryPool, false_fail_rate, paired_shift
from experiments.drop.screen_settings import ScreenSettings

COARSE, FINE = "0.004", "0.001"
RULES = {
    "issue 21 (0.95 vs 0.5)": ScreenSettings(
        works_p=0.95, fails_p=0.5, false_works=0.1, first_entry=0
    ),
    "issue 21, confirmed at 1e-3": ScreenSettings(
        works_p=0.95, fails_p=0.5, false_works=0.1, first_entry=0, confirm_step=1e-3
    ),
    "default (0.85 vs 0.1)": ScreenSettings(),
    "default, confirmed at 1e-3": ScreenSettings(confirm_step=1e-3),
}


def pools_of(entry_pools: dict[str, dict[str, str]]) -> list[EntryPool]:
    return [EntryPool(steps[COARSE], steps[FINE]) for steps in entry_pools.values()]


def p_of(outcomes: str) -> float:
    counted = [c for c in outcomes if c != "x"]
    return sum(c == "1" for c in counted) / len(counted)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pool", type=Path)
    parser.add_argument("--seeds", type=int, default=1000)
    parser.add_argument("--rates-for", default="", help="design ids (default: the nearest)")
    args = parser.parse_args()
    data = json.loads(args.pool.read_text())
    pool = {int(d): v for d, v in data["pool"].items()}

    print("| design | entry | draws | p at 4e-3 | p at 1e-3 | only 4e-3 | only 1e-3 | McNemar p |")
    print("|---|---|---|---|---|---|---|---|")
    totals = [0, 0, 0, 0]
    nearest = []
    for d in sorted(pool):
        low = 1.0
        for entry, steps in pool[d].items():
            s = paired_shift(EntryPool(steps[COARSE], steps[FINE]))
            totals = [
                totals[0] + s.n,
                totals[1] + s.coarse_successes,
                totals[2] + s.coarse_only,
                totals[3] + s.fine_only,
            ]
            pc, pf = s.coarse_successes / s.n, s.fine_successes / s.n
            low = min(low, pf)
            mark = " **" if s.p_value < 0.01 else ""
            print(
                f"| {d} | {entry} | {s.n} | {pc:.3f} | {pf:.3f} | {s.coarse_only} | "
                f"{s.fine_only} | {s.p_value:.2g}{mark} |"
            )
        nearest.append((low, d))
    n, coarse, c_only, f_only = totals
    print(
        f"\npooled over {len(pool)} designs, {n} paired drops: p {coarse / n:.4f} at 4e-3, "
        f"{(coarse - c_only + f_only) / n:.4f} at 1e-3 ({c_only} succeed only at 4e-3, "
        f"{f_only} only at 1e-3)\n"
    )
    chosen = (
        [int(x) for x in args.rates_for.split(",")]
        if args.rates_for
        else [d for _, d in sorted(nearest)[:6]]
    )
    print(f"false-fail rate over {args.seeds} resampled screens (Clopper-Pearson 95%):\n")
    print("| design | p at 1e-3 (entries) | " + " | ".join(RULES) + " |")
    print("|---|---|" + "---|" * len(RULES))
    for d in chosen:
        pools = pools_of(pool[d])
        ps = ", ".join(f"{p_of(e.fine):.3f}" for e in pools)
        cells = []
        for settings in RULES.values():
            r = false_fail_rate(pools, settings, args.seeds)
            exact = ""
            if settings.confirm_step is None:  # the pool's coarse p per entry, exactly
                survive = 1.0
                for e in pools:
                    survive *= 1.0 - screen_operating_point(p_of(e.coarse), settings, 1).fails
                exact = f"; exact {100 * (1.0 - survive):.2f}%"
            cells.append(
                f"{100 * r.rate:.1f}% [{100 * r.ci[0]:.1f}, {100 * r.ci[1]:.1f}]{exact} "
                f"({r.mean_coarse_drops:.1f} + {r.mean_fine_drops:.1f} drops)"
            )
        print(f"| {d} | {ps} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
