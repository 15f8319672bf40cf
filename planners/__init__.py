"""The OMPL side: state and control spaces, a level as validity checker and propagator, goals,
projections and planners by name, and the public API (docs/api.md)::

    from ompl import control as oc
    from planners import problem

    p = problem("table3", "dynamic")           # an OMPL problem: SimpleSetup, start, goal, ...
    p.ss.setPlanner(oc.KPIECE1(p.si))          # any OMPL control planner
    p.ss.solve(p.termination(10.0, propagations=20_000))

The names below are exported lazily (PEP 562): ``import planners`` or ``import
planners.registry`` loads neither OMPL nor numba for the rest, so the command line starts
fast; a name's module is imported when the name is first used. No exported name is also the
name of a submodule (the import system would replace one with the other): the one-shot
``plan()`` returning plain data stays ``planners.plan.plan``.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from feeders.scene_spec import DesignSpec, scene_of
    from planners.adapters import state_propagator, validity_checker
    from planners.benchmark import (
        BenchmarkResult,
        Budget,
        PlannerFactory,
        PlannerSpec,
        benchmark_control_problem,
        benchmark_problem,
    )
    from planners.exclusive import one_at_a_time
    from planners.goals import GoalBox
    from planners.plan import ControlProblem, PlannerSettings, PlanResult, seed_ompl
    from planners.problems import level_of, problem
    from planners.projections import PoseProjection, register_pose_projection
    from planners.registry import PLANNERS, make_planner
    from planners.spaces import level_spaces, make_control_space, make_state_space, state_codec

# Each public name and the module that defines it.
_EXPORTS: dict[str, str] = {
    "problem": "planners.problems",
    "level_of": "planners.problems",
    "scene_of": "feeders.scene_spec",
    "DesignSpec": "feeders.scene_spec",
    "ControlProblem": "planners.plan",
    "PlannerSettings": "planners.plan",
    "PlanResult": "planners.plan",
    "seed_ompl": "planners.plan",
    "validity_checker": "planners.adapters",
    "state_propagator": "planners.adapters",
    "level_spaces": "planners.spaces",
    "make_state_space": "planners.spaces",
    "make_control_space": "planners.spaces",
    "state_codec": "planners.spaces",
    "GoalBox": "planners.goals",
    "PoseProjection": "planners.projections",
    "register_pose_projection": "planners.projections",
    "PLANNERS": "planners.registry",
    "make_planner": "planners.registry",
    "one_at_a_time": "planners.exclusive",
    "Budget": "planners.benchmark",
    "BenchmarkResult": "planners.benchmark",
    "benchmark_problem": "planners.benchmark",
    "benchmark_control_problem": "planners.benchmark",
    "PlannerFactory": "planners.benchmark",
    "PlannerSpec": "planners.benchmark",
}

__all__ = [
    "PLANNERS",
    "BenchmarkResult",
    "Budget",
    "ControlProblem",
    "DesignSpec",
    "GoalBox",
    "PlanResult",
    "PlannerFactory",
    "PlannerSettings",
    "PlannerSpec",
    "PoseProjection",
    "benchmark_control_problem",
    "benchmark_problem",
    "level_of",
    "level_spaces",
    "make_control_space",
    "make_planner",
    "make_state_space",
    "one_at_a_time",
    "problem",
    "register_pose_projection",
    "scene_of",
    "seed_ompl",
    "state_codec",
    "state_propagator",
    "validity_checker",
]


def __getattr__(name: str) -> Any:
    """The exported ``name``, its module imported on first use."""
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'planners' has no attribute '{name}'")
    return getattr(import_module(module), name)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
