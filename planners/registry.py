"""OMPL control planners by name.

``PLANNERS`` are the three OMPL classes a sweep's config names (``rrt``, ``kpiece``, ``est``).
``CONFIGURED`` adds named configurations of them with their parameters, for comparisons
(``partfeeder planners``): a sweep keeps to ``PLANNERS``. ``UNAVAILABLE`` says why OMPL's
other control planners cannot run from Python under OMPL 2.0.1's bindings (checked against
its stubs ``ompl/_ompl/control.pyi``: ``oc.SST`` and ``oc.PDST`` are declared without a
constructor; the Syclop planners need a decomposition, and a Python ``oc.GridDecomposition``
never sees a state's coordinates, docs/api.md). Only RRT exposes setters (``setGoalBias``,
``setIntermediateStates``); KPIECE1 and EST run with OMPL's defaults, as ``params()`` is not
bound either.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ompl import base as ob
from ompl import control as oc

PLANNERS = {"rrt": oc.RRT, "kpiece": oc.KPIECE1, "est": oc.EST}


@dataclass(frozen=True)
class PlannerConfig:
    """One OMPL control planner with its parameters: ``kind`` a key of :data:`PLANNERS`,
    ``label`` the name it is logged under (OMPL's ``getName()``; Planner Arena's planner is
    ``control_`` + label), ``goal_bias`` and ``intermediate_states`` RRT's setters (None:
    OMPL's default, 0.05 and off), ``about`` one line for the docs. ``factory``
    (``si -> ob.Planner``, a module-level function so that worker processes can import it)
    makes the planner instead of ``kind``'s class: any other OMPL planner or one written in
    Python (docs/planners.md)."""

    kind: str
    label: str
    about: str
    goal_bias: float | None = None
    intermediate_states: bool | None = None
    factory: Callable[[oc.SpaceInformation], ob.Planner] | None = None

    def make(self, si: oc.SpaceInformation) -> ob.Planner:
        planner = self.factory(si) if self.factory is not None else PLANNERS[self.kind](si)
        if self.goal_bias is not None:
            planner.setGoalBias(self.goal_bias)
        if self.intermediate_states is not None:
            planner.setIntermediateStates(self.intermediate_states)
        planner.setName(self.label)
        return planner


CONFIGURED: dict[str, PlannerConfig] = {
    "rrt": PlannerConfig("rrt", "RRT", "control RRT, OMPL's defaults (goal bias 0.05)"),
    "rrt-greedy": PlannerConfig(
        "rrt", "RRT-greedy", "control RRT with goal bias 0.2 (a goal sample 1 time in 5)", 0.2
    ),
    "rrt-intermediate": PlannerConfig(
        "rrt",
        "RRT-intermediate",
        "control RRT keeping the intermediate states of each control in the tree",
        intermediate_states=True,
    ),
    "kpiece": PlannerConfig(
        "kpiece", "KPIECE1", "KPIECE1 on the pose projection (x, y, yaw), OMPL's defaults"
    ),
    "est": PlannerConfig("est", "EST", "EST on the pose projection (x, y, yaw), OMPL's defaults"),
}

UNAVAILABLE = {
    "sst": "oc.SST has no constructor in OMPL 2.0.1's Python bindings",
    "pdst": "oc.PDST has no constructor in OMPL 2.0.1's Python bindings",
    "syclop-rrt": "oc.SyclopRRT needs a decomposition; a Python oc.GridDecomposition never "
    "sees a state's coordinates in OMPL 2.0.1 (docs/api.md)",
    "syclop-est": "oc.SyclopEST needs a decomposition; a Python oc.GridDecomposition never "
    "sees a state's coordinates in OMPL 2.0.1 (docs/api.md)",
}


def planner_names() -> list[str]:
    """Every name :func:`make_planner` takes: :data:`PLANNERS`, then the other
    :data:`CONFIGURED` ones."""
    return list(dict.fromkeys([*PLANNERS, *CONFIGURED]))


def make_planner(name: str, si: oc.SpaceInformation) -> ob.Planner:
    """The planner called ``name`` (rrt, kpiece, est, or a configuration of
    :data:`CONFIGURED` such as rrt-greedy); the error lists the names there are."""
    key = name.lower()
    if key in PLANNERS:
        return PLANNERS[key](si)
    if key in CONFIGURED:
        return CONFIGURED[key].make(si)
    if key in UNAVAILABLE:
        raise ValueError(f"planner '{name}' cannot run: {UNAVAILABLE[key]}")
    raise ValueError(f"unknown planner '{name}'; planners: {', '.join(planner_names())}")
