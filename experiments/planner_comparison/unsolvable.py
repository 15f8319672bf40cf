"""Which problems cannot be solved at all: the necessary conditions of the design's feeder.

:func:`validity.necessary.necessary_conditions` tests consequences of any continuous motion
of the part from an entry to the goal region through the feeder's free space (its walls
overlapped by at most a small slack). Every level's motion is such a motion (the geometric
level's pose increments, the kinematic and dynamic levels' trajectories, with any input), so
a problem whose design fails a test is unsolvable at every level, and a planner's failure on
it is not counted against the planner. Here the tests are run on the nominal feeder (no
tolerance) from the nominal entries (no perturbation): the planning problem's own.

Which entries a failed test speaks for:

- ``corridor``: both (the part's inscribed disc cannot reach the goal from the entry);
- ``turn``: the heavy-trailing entry (the part cannot turn horizontal anywhere it can reach);
- ``sliced``: at least one of the two (the test floods both entries together). When a
  planner solved one entry at some level, the other is the unsolvable one
  (:func:`resolve`); otherwise both are "one of the two is unsolvable" and neither counts.

A passive drop that fails proves nothing here: the planning levels have inputs (a wrench at
the dynamic level), so a design that does not work passively may still be steered to the
goal. A device family's design or a scene file is not a 12-parameter feeder: its problems
are "not tested".
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from feeders.scene import Scene

HEAVY_TRAILING = "heavy_trailing"
PROVEN = "unsolvable"  # status of an entry the tests prove unsolvable
ONE_OF_TWO = "one of two unsolvable"  # the sliced test, entries not told apart
OPEN = "open"  # no test failed for it, or none applies


def necessary_status(scene: Scene, entries: Iterable[str]) -> dict[str, Any]:
    """``{"tested": bool, "failed": test or None, "entries": {entry: (status, reason)}}``
    for the scene's ``entries`` (statuses :data:`PROVEN`, :data:`ONE_OF_TWO`, :data:`OPEN`)."""
    entries = list(entries)
    if scene.design is None or scene.outline is None:
        return {
            "tested": False,
            "failed": None,
            "entries": {e: (OPEN, "necessary conditions not applicable") for e in entries},
        }
    from validity.necessary import necessary_conditions

    verdict = necessary_conditions(scene, 0.0, position=0.0, yaw=0.0)
    return {
        "tested": True,
        "failed": verdict.failed,
        "entries": entry_statuses(verdict.failed, entries),
    }


def entry_statuses(failed: str | None, entries: list[str]) -> dict[str, tuple[str, str]]:
    """Each entry's status after the necessary test ``failed`` (None: all passed)."""
    if failed is None:
        return {e: (OPEN, "passes the necessary conditions") for e in entries}
    if failed == "corridor":
        return {e: (PROVEN, "fails the necessary corridor test") for e in entries}
    if failed == "turn":
        return {
            e: (PROVEN, "fails the necessary turn test")
            if e == HEAVY_TRAILING
            else (OPEN, "the turn test is for the heavy-trailing entry")
            for e in entries
        }
    return {
        e: (ONE_OF_TWO, f"the necessary {failed} test fails for one entry or both") for e in entries
    }


def resolve(statuses: dict[str, tuple[str, str]], solved: set[str]) -> dict[str, tuple[str, str]]:
    """The statuses with a :data:`ONE_OF_TWO` pair told apart by ``solved`` (the entries some
    planner solved at some level): if one was solved, the other is :data:`PROVEN`."""
    pair = [e for e, (status, _) in statuses.items() if status == ONE_OF_TWO]
    if len(pair) != 2:
        return dict(statuses)
    out = dict(statuses)
    for entry, other in (pair, pair[::-1]):
        if entry in solved:
            out[entry] = (OPEN, f"solved by a planner ({statuses[entry][1]}: the other entry)")
            out[other] = (PROVEN, f"{statuses[other][1]}, and the other entry was solved")
    return out
