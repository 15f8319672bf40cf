"""Plan through a scene of one's own: a funnel with a pin (``funnel.yaml``, next to this file).

The scene is read from YAML (free-form polygons and circles, bounds, start, goal; see
``feeders/scene_yaml.py``), changed in Python if asked (``dataclasses.replace``: a scene is an
immutable value), and planned at any level with any OMPL control planner under a budget of
propagations. Prints whether the goal was reached, the work done and the path's end.

    python examples/custom_scene.py                        # kinematic level, KPIECE1
    python examples/custom_scene.py --level dynamic --friction 0.05
    python examples/custom_scene.py --planner RRT-greedy     # RRT with a goal bias of 0.2
    python examples/custom_scene.py --scene my_scene.yaml --level geometric
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

from ompl import control as oc
from ompl import util as ou

from planners import problem, scene_of

PLANNERS = {
    "RRT": lambda p: oc.RRT(p.si),
    "KPIECE1": lambda p: oc.KPIECE1(p.si),  # uses the pose projection the problem registered
    "EST": lambda p: oc.EST(p.si),
    "RRT-greedy": lambda p: greedy_rrt(p.si),
}


def greedy_rrt(si: oc.SpaceInformation) -> oc.RRT:
    """OMPL's RRT with its own settings: a goal bias of 0.2 (OMPL's default is 0.05)."""
    planner = oc.RRT(si)
    planner.setGoalBias(0.2)
    return planner


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", type=Path, default=Path(__file__).with_name("funnel.yaml"))
    parser.add_argument("--level", default="kinematic", help="geometric, kinematic or dynamic")
    parser.add_argument("--planner", default="KPIECE1", choices=sorted(PLANNERS))
    parser.add_argument("--friction", type=float, help="change the scene's Coulomb mu")
    parser.add_argument("--propagations", type=int, default=20000, help="the budget")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    ou.setLogLevel(ou.LogLevel.LOG_WARN)
    scene = scene_of(args.scene)
    if args.friction is not None:
        scene = dataclasses.replace(scene, friction=args.friction)
    p = problem(scene, args.level, seed=args.seed)
    p.ss.setPlanner(PLANNERS[args.planner](p))
    p.warm_up()  # compile the level's kernels before planning (seconds on a first run)
    p.ss.solve(p.termination(time=120.0, propagations=args.propagations))

    solved = p.ss.haveExactSolutionPath()
    print(f"scene {scene.name}, friction {scene.friction:g}, start pose {p.start[:3]}")
    print(f"{args.level} level, {args.planner}: {'solved' if solved else 'not solved'}")
    print(f"propagations {p.propagations}, validity checks {p.validity_checks}")
    if p.ss.haveSolutionPath():
        path = p.ss.getSolutionPath()
        end = p.read(path.getState(path.getStateCount() - 1))
        duration = sum(path.getControlDuration(i) for i in range(path.getControlCount()))
        print(f"path: {path.getStateCount()} states, {duration:.2f} s of motion")
        print(f"end pose: x {end[0]:.3f}, y {end[1]:.3f}, yaw {end[2]:.3f}")


if __name__ == "__main__":
    main()
