"""Issue 21's cost goal measured as the issue states it: worker time per design of the full
verdict as it was when the issue was filed (commit 5bc2345^: Wilson intervals, a look every
10 trials, h = 1e-3, that day's kernels) against the screened pipeline of this checkout
(screen, then the SPRT verdict), on the first N Halton designs of seed 0, in one run.

Each procedure runs in a worker process of its own checkout (``--before``: a git worktree of
the old commit, e.g. ``git worktree add /tmp/issue21-before 5bc2345^``), one design at a time
and one process at a time, the order alternating design by design; each worker reports the
CPU time it spent on the design (``time.process_time``), so other work on the machine counts
less than in wall time. Kernels are compiled or loaded before any clock.

    python docs/measurements/issue21_before_after.py --before /tmp/issue21-before -n 1000

Prints the means, their ratio with a paired bootstrap 95% interval, and every design on which
the two decisions differ.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parents[2]

WORKER = r"""
import json, sys, time
import numpy as np
from feeders.design import DesignParameters, preset
from feeders.feeder import DegenerateDesign
from feeders.halton import halton_points
from experiments.drop.verdict import design_verdict
from experiments.drop.verdict_settings import VerdictSettings
role = sys.argv[1]
if role == "screened":
    from experiments.drop.screen import design_screen
    SPRT = VerdictSettings(rule="sprt", min_drops=1, batch=1)
def seed_of(seed, design, tag):
    state = np.random.SeedSequence([seed, design, tag]).generate_state(1)[0]
    return int(state % (2**31 - 1))
def run(i, design):
    if role == "before":
        return design_verdict(design, settings=VerdictSettings(), seed=seed_of(0, i, 1)).decision
    if design_screen(design, seed=seed_of(0, i, 2)).decision == "fails":
        return "fails"
    return design_verdict(design, settings=SPRT, seed=seed_of(0, i, 1)).decision
points = halton_points(int(sys.argv[2]), 0)
run(0, preset("table3"))  # kernels compiled or loaded before any clock
print("ready", flush=True)
for line in sys.stdin:
    i = int(line)
    design = DesignParameters.from_vector([float(v) for v in points[i]])
    t0 = time.process_time()
    try:
        decision = run(i, design)
    except DegenerateDesign:
        decision = "unbuildable"
    print(json.dumps([decision, time.process_time() - t0]), flush=True)
"""


def _worker(role: str, checkout: Path, n: int) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(checkout))
    process = subprocess.Popen(
        [sys.executable, "-c", WORKER, role, str(n)],
        cwd="/",
        env=env,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert process.stdout is not None and process.stdout.readline().strip() == "ready"
    return process


def _ask(process: subprocess.Popen, i: int) -> tuple[str, float]:
    assert process.stdin is not None and process.stdout is not None
    process.stdin.write(f"{i}\n")
    process.stdin.flush()
    decision, seconds = json.loads(process.stdout.readline())
    return decision, seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, required=True, help="checkout of 5bc2345^")
    parser.add_argument("-n", type=int, default=1000)
    args = parser.parse_args()
    workers = {"before": _worker("before", args.before, args.n)}
    workers["screened"] = _worker("screened", HERE, args.n)
    rows = []
    for i in range(args.n):
        order = ["before", "screened"] if i % 2 == 0 else ["screened", "before"]
        got = {role: _ask(workers[role], i) for role in order}
        if got["before"][0] != "unbuildable":
            rows.append((i, *got["before"], *got["screened"]))
        if (i + 1) % 100 == 0:
            print(f"{i + 1} designs", file=sys.stderr, flush=True)
    for process in workers.values():
        process.stdin.close()  # type: ignore[union-attr]
        process.wait()
    before = np.array([r[2] for r in rows])
    after = np.array([r[4] for r in rows])
    resample = np.random.default_rng(0).integers(0, len(rows), (2000, len(rows)))
    boot = before[resample].mean(1) / after[resample].mean(1)
    print(f"designs: {args.n}, buildable: {len(rows)}")
    for name, decisions, seconds in (
        ("before (Wilson verdict at 5bc2345^)", [r[1] for r in rows], before),
        ("now (screen, then SPRT verdict)", [r[3] for r in rows], after),
    ):
        print(
            f"{name}: {seconds.mean():.4f} s a design (CPU), {decisions.count('works')} work, "
            f"{decisions.count('undecided')} undecided"
        )
    low, high = np.quantile(boot, 0.025), np.quantile(boot, 0.975)
    ratio = before.mean() / after.mean()
    print(f"speed-up: {ratio:.2f}x [{low:.2f}, {high:.2f}] (paired bootstrap)")
    for i, b, _, a, _ in rows:
        if b != a:
            print(f"  design {i}: before {b}, now {a}")


if __name__ == "__main__":
    main()
