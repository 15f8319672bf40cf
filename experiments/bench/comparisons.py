"""Ratios against the peers and the issue's goals, computed from one run's data (no timing).

* per step at one h: partfeeder's microseconds per step over a peer's, same case and h;
* at equal error: partfeeder's wall time per simulated second at the peer's error, read off
  partfeeder's work-precision curve by log-log interpolation between its two measured points
  that bracket that error (the cheapest measured point when even the coarsest h is as
  accurate; None when no measured h reaches it), over the peer's;
* the goals: per step at h = 1e-3 at most 0.5x MuJoCo's on the sliding and sticking box at
  equal or smaller error; creep below 1e-12 after 10 s; both passive drops of table3 under
  10 ms.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

OURS = "partfeeder (default)"
GOAL_H = 1e-3
GOAL_STEP_RATIO = 0.5
GOAL_CREEP = 1e-12
GOAL_DROP_MS = 10.0


def _points(wp: dict, case: str, engine: str) -> list[dict]:
    return [p for p in wp["cases"][case]["points"] if p["engine"] == engine]


def _at(points: Sequence[dict], h: float) -> dict | None:
    return next((p for p in points if math.isclose(p["h"], h)), None)


def cost_at_error(points: Sequence[dict], error: float, key: str = "error") -> float | None:
    """Wall time per simulated second at which ``points`` (one engine's curve) reach ``error``
    in measure ``key`` (see the module docstring)."""
    curve = sorted(points, key=lambda p: p["wall_per_sim_s"])
    k = next((i for i, p in enumerate(curve) if p["errors"][key] <= error), None)
    if k is None:
        return None
    b = curve[k]
    if k == 0:
        return b["wall_per_sim_s"]
    a = curve[k - 1]
    ea, eb = a["errors"][key], b["errors"][key]
    if eb <= 0.0 or error <= 0.0:
        return b["wall_per_sim_s"]
    f = (math.log(ea) - math.log(error)) / (math.log(ea) - math.log(eb))
    la, lb = math.log(a["wall_per_sim_s"]), math.log(b["wall_per_sim_s"])
    return math.exp(la + f * (lb - la))


def peer_ratios(wp: dict, h: float = GOAL_H) -> list[dict]:
    """Per case and peer setting: per-step ratio at h and work ratio at the peer's error."""
    rows = []
    peers = [e["label"] for e in wp["engines"] if e["engine"] != "partfeeder"]
    for case, data in wp["cases"].items():
        key = data["measures"][0]
        ours = _points(wp, case, OURS)
        mine = _at(ours, h)
        for peer in peers:
            theirs = _at(_points(wp, case, peer), h)
            if mine is None or theirs is None:
                rows.append({"case": case, "peer": peer, "measured": False})
                continue
            at_error = cost_at_error(ours, theirs["errors"][key], key)
            rows.append(
                {
                    "case": case,
                    "peer": peer,
                    "measured": True,
                    "h": h,
                    "ours_us_per_step": mine["us_per_step"],
                    "peer_us_per_step": theirs["us_per_step"],
                    "step_ratio": mine["us_per_step"] / theirs["us_per_step"],
                    "ours_error": mine["errors"][key],
                    "peer_error": theirs["errors"][key],
                    "equal_error_ratio": None
                    if at_error is None
                    else at_error / theirs["wall_per_sim_s"],
                }
            )
    return rows


def goals(data: dict) -> list[dict]:
    """The issue's three goals, each with the measured value and whether it is met (None when
    its section did not run or its peer is not installed)."""
    out: list[dict] = []
    wp = data.get("work_precision")
    if wp is not None:
        for case in ("slide", "stick"):
            for row in peer_ratios(wp):
                if row["case"] != case or not row["peer"].startswith("mujoco"):
                    continue
                if not row["measured"]:
                    out.append({"goal": f"{case}: vs {row['peer']}", "met": None, "value": None})
                    continue
                ratio = row["step_ratio"]
                if row["ours_error"] > row["peer_error"]:
                    ratio = row["equal_error_ratio"]  # compare at the peer's error instead
                out.append(
                    {
                        "goal": f"{case} box, h = 1e-3: time per step <= 0.5 x {row['peer']} "
                        "at equal or smaller error",
                        "value": ratio,
                        "met": None if ratio is None else ratio <= GOAL_STEP_RATIO,
                        "detail": row,
                    }
                )
        creep = wp["creep"]["by_engine"].get(OURS)
        out.append(
            {
                "goal": f"creep of the sticking box after {wp['creep']['duration_s']:g} s < 1e-12",
                "value": creep,
                "met": None if creep is None else creep < GOAL_CREEP,
            }
        )
    speed = data.get("speed")
    if speed is not None:
        ms = speed["dynamic_skips"]["table3 drops, all skips on"]["median_ms"]
        out.append(
            {
                "goal": "passive drop of table3, both orientations, < 10 ms",
                "value": ms,
                "met": ms < GOAL_DROP_MS,
            }
        )
    return out
