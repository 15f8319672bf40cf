"""Compare OMPL control planners on the paper's designs, with budgets in propagations.

For each design and entry orientation, the problem at the chosen level goes through the
repository's benchmark (OMPL's ``Benchmark`` with a propagation budget: the same numbers on any
machine) with every planner, ``--runs`` runs each. Prints one row per design and planner:
runs that reached the goal exactly, median propagations and tree size. ``--out DIR`` also
writes OMPL's log of each problem and, with OMPL's ``ompl_benchmark_statistics``, the database
``DIR/benchmark.db`` that Planner Arena (plannerarena.org) opens.

The defaults (table3, fig4, fig8a from both entries at the dynamic level; 3 runs of at most
5,000 propagations) took 45 s on a 2-core machine shared with other jobs (load 4.7). Most of
it is the heavy trailing entries of fig4 and fig8a: no planner solves them at the dynamic
level (nor with 20,000 propagations, where the former defaults, 5 runs of 20,000, ran more
than 15 minutes on a busy machine), so every run spends its whole budget. The time grows with
``--runs`` times ``--propagations`` on those problems: about 1 ms a propagation.

    python examples/compare_planners.py
    python examples/compare_planners.py --designs table3,fig4,fig8a --level kinematic --out cmp
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

from ompl import util as ou

from planners import Budget, benchmark_control_problem, problem


def arena_database(logs: list[Path], database: Path) -> None:
    """OMPL's own reader: the logs into the SQLite database Planner Arena reads."""
    script = Path(sys.executable).with_name("ompl_benchmark_statistics")
    command = str(script) if script.exists() else shutil.which("ompl_benchmark_statistics")
    if command is None:
        raise SystemExit("ompl_benchmark_statistics (installed with ompl) is not on the PATH")
    database.unlink(missing_ok=True)
    subprocess.run(
        [command, *map(str, logs), "-d", str(database)], check=True, stdout=subprocess.DEVNULL
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--designs", default="table3,fig4,fig8a", help="paper presets")
    parser.add_argument("--level", default="dynamic", help="geometric, kinematic or dynamic")
    parser.add_argument("--planners", default="rrt,kpiece,est")
    parser.add_argument("--orientations", default="heavy_leading,heavy_trailing")
    parser.add_argument("--runs", type=int, default=3, help="runs per planner and problem")
    parser.add_argument("--propagations", type=int, default=5000, help="budget per run")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", type=Path, help="directory for OMPL's logs and benchmark.db")
    args = parser.parse_args()

    ou.setLogLevel(ou.LogLevel.LOG_WARN)
    budget = Budget(time_s=120.0, propagations=args.propagations)  # the time is only a cap
    logs: list[Path] = []
    print(
        f"{args.level} level, {args.runs} runs per planner, "
        f"at most {args.propagations} propagations a run"
    )
    print(f"{'design':<8}{'entry':<16}{'planner':<10}{'solved':>8}{'propagations':>14}{'tree':>7}")
    for design in args.designs.split(","):
        for orientation in args.orientations.split(","):
            p = problem(design, args.level, orientation, seed=args.seed)
            experiment = f"{design}/{args.level}/{orientation}"  # one word: Planner Arena's name
            result = benchmark_control_problem(
                p,
                args.planners.split(","),
                runs=args.runs,
                budget=budget,
                seed=args.seed,
                experiment=experiment,
                parameters={"design": design, "level": args.level, "entry": orientation},
            )
            for planner in dict.fromkeys(r["planner"] for r in result.runs):
                runs = [r for r in result.runs if r["planner"] == planner]
                solved = sum(r["solved"] for r in runs)
                spent = statistics.median(r["propagations"] for r in runs)
                tree = statistics.median(r["tree_size"] for r in runs)
                print(
                    f"{design:<8}{orientation:<16}{planner:<10}{solved:>5}/{len(runs):<2}"
                    f"{spent:>14.0f}{tree:>7.0f}"
                )
            if args.out is not None:
                args.out.mkdir(parents=True, exist_ok=True)
                logs.append(args.out / f"{design}-{args.level}-{orientation}.log")
                logs[-1].write_text(result.log)
    if args.out is not None:
        arena_database(logs, args.out / "benchmark.db")
        print(f"OMPL logs and Planner Arena's database: {args.out / 'benchmark.db'}")


if __name__ == "__main__":
    main()
