"""OMPL control planners by name."""

from __future__ import annotations

from ompl import control as oc

PLANNERS = {"rrt": oc.RRT, "kpiece": oc.KPIECE1, "est": oc.EST}


def make_planner(name: str, si: oc.SpaceInformation):
    """The planner called ``name`` (rrt, kpiece, est); the error lists the names there are."""
    try:
        cls = PLANNERS[name.lower()]
    except KeyError:
        raise ValueError(f"unknown planner '{name}'; planners: {', '.join(PLANNERS)}") from None
    return cls(si)
