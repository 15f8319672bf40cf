"""A planner of one's own, in Python, benchmarked against OMPL's RRT on the same problem.

Random shooting: from the start, apply random controls for random durations (each motion
propagated while valid), up to ``--depth`` controls a shot, and keep the shot that ends nearest
the goal region; stop when a shot ends inside it. A baseline any tree planner should beat.
It is an ``ob.Planner`` subclass, so ``SimpleSetup.solve``, OMPL's ``Benchmark`` and the
repository's benchmark (propagation budgets, our log properties) all take it as they take
``oc.RRT``.

    python examples/custom_planner.py                      # table3, geometric level
    python examples/custom_planner.py --design fig8a --level kinematic --runs 5
"""

from __future__ import annotations

import argparse
import math

from ompl import base as ob
from ompl import control as oc
from ompl import util as ou

from planners import Budget, benchmark_control_problem, problem


class RandomShooting(ob.Planner):
    """Random control sequences from the start; the best shot is the solution."""

    def __init__(self, si: oc.SpaceInformation, start: tuple[float, ...], write, depth: int = 30):
        super().__init__(si, "RandomShooting")
        self.csi = si  # the control space information (getSpaceInformation() is the base one)
        self.start = start  # the start as a tuple, and how to write one into an OMPL state
        self.write = write
        self.depth = depth

    def solve(self, ptc: ob.PlannerTerminationCondition) -> ob.PlannerStatus:
        si = self.csi
        goal = self.getProblemDefinition().getGoal()
        sampler = oc.RealVectorControlUniformSampler(si.getControlSpace())
        rng = ou.RNG()  # draws from OMPL's process-wide seed: seeded runs repeat
        low, high = si.getMinControlDuration(), si.getMaxControlDuration()
        step = si.getPropagationStepSize()
        states = [si.allocState() for _ in range(self.depth + 1)]
        controls = [si.allocControl() for _ in range(self.depth)]
        best: ob.Path | None = None
        best_gap = math.inf
        while not ptc():
            self.write(states[0], self.start)
            shot: list[tuple[int, int]] = []  # (state index, steps) of each motion
            for k in range(self.depth):
                sampler.sample(controls[k])
                steps = si.propagateWhileValid(
                    states[k], controls[k], rng.uniformInt(low, high), states[k + 1]
                )
                if steps == 0:
                    break
                shot.append((k, steps))
                gap = goal.distanceGoal(states[k + 1])
                if gap < best_gap:
                    best_gap = gap
                    best = oc.PathControl(si)
                    best.append(states[0])
                    for i, n in shot:
                        best.append(states[i + 1], controls[i], n * step)
                if goal.isSatisfied(states[k + 1]) or ptc():
                    break
            if best_gap <= 0.0:
                break
        if best is None:
            return ob.PlannerStatus(ob.PlannerStatus.PlannerStatusType.TIMEOUT)
        exact = goal.isSatisfied(best.getState(best.getStateCount() - 1))
        self.getProblemDefinition().addSolutionPath(best, not exact, best_gap, self.getName())
        kind = "EXACT_SOLUTION" if exact else "APPROXIMATE_SOLUTION"
        return ob.PlannerStatus(getattr(ob.PlannerStatus.PlannerStatusType, kind))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--design", default="table3", help="a paper preset or a scene file")
    parser.add_argument("--level", default="geometric")
    parser.add_argument("--runs", type=int, default=10, help="runs per planner")
    parser.add_argument("--propagations", type=int, default=5000, help="budget per run")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    ou.setLogLevel(ou.LogLevel.LOG_WARN)
    p = problem(args.design, args.level, seed=args.seed)

    def shooting(si: oc.SpaceInformation) -> ob.Planner:
        return RandomShooting(si, p.start, p.write)

    result = benchmark_control_problem(
        p,
        [shooting, "rrt"],
        runs=args.runs,
        budget=Budget(time_s=60.0, propagations=args.propagations),
        seed=args.seed,
        experiment=f"{args.design}-{args.level}",
    )
    print(
        f"{p.scene.name}, {args.level} level, "
        f"{args.runs} runs of at most {args.propagations} propagations"
    )
    print(f"{'planner':<16}{'solved':>8}{'mean propagations':>20}{'mean tree':>11}")
    for name in dict.fromkeys(r["planner"] for r in result.runs):
        runs = [r for r in result.runs if r["planner"] == name]
        solved = sum(r["solved"] for r in runs)
        mean_prop = sum(r["propagations"] for r in runs) / len(runs)
        mean_tree = sum(r["tree_size"] for r in runs) / len(runs)
        print(f"{name:<16}{solved:>5}/{len(runs):<2}{mean_prop:>20.0f}{mean_tree:>11.0f}")


if __name__ == "__main__":
    main()
