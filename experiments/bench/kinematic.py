"""Benchmarks of the kinematic level (Eq. 8, Algorithm 2): measure, never assert.

* (a) microseconds per step of ``KinematicLevel.propagate`` on table3, for propagations in
  which the part meets no wall (each step: one contact search, one advance) and for those
  with impacts (time of impact, Routh impacts, slides), from the same seeded workload, with
  the geometric level's microseconds per step on the same free propagations beside them;
* (b) a part pressed onto a floor, an impact every step (the worst steady case);
* (c) the skip: a step in the open (nothing within the search margin) against a step near a
  wall that it does not reach;
* (d) RRT and KPIECE1 on table3 with the kinematic level: time to the first solution, solved
  fraction, tree size.

Microseconds are medians over repeats of loops long enough to swamp the timer (see
:mod:`experiments.bench.timing`); compare figures from one run only, the machine is noisy.
"""

from __future__ import annotations

import math

import numpy as np

from experiments.bench.timing import bench_planning, machine_info, per_item_us
from feeders.design import PRESETS
from feeders.feeder import build_feeder
from feeders.part import DEFAULT_PEG
from feeders.scene import Goal, Scene
from feeders.shapes import Obstacles
from validity.geometric import GeometricLevel
from validity.kinematic import KinematicLevel
from validity.pose_samples import cross_check_poses

DURATION = 0.5  # s per propagate call: 50 steps at h = 0.01
FLOOR = np.array([[-50.0, -1.0], [50.0, -1.0], [50.0, 0.0], [-50.0, 0.0]])


def _floor_scene() -> Scene:
    return Scene(
        name="floor",
        obstacles=Obstacles((FLOOR,), np.zeros((0, 3))),
        part=DEFAULT_PEG,
        bounds=(-40.0, 40.0, -40.0, 40.0),
        starts={"start": (0.0, 0.5 + 1e-3, 0.0)},
        goal=Goal(x_min=-1.0, x_max=1.0, y_min=-1.0, y_max=1.0, yaw=0.0, yaw_tol=0.5),
    )


def _workload(level: KinematicLevel, seed: int, n: int) -> tuple[list, list]:
    """Seeded (state, control) cases on the level's scene, split into propagations with no
    impact and with at least one."""
    rng = np.random.default_rng(seed)
    free: list[tuple[tuple[float, ...], np.ndarray]] = []
    hit: list[tuple[tuple[float, ...], np.ndarray]] = []
    for pose in cross_check_poses(level.scene, 40 * n, seed):
        state = level.state_of_pose(pose)
        if not level.is_valid(state):
            continue
        u = rng.uniform(*level.control_bounds())
        run = level.run(state, tuple(u), DURATION, record=False)
        if run.end != "duration":
            continue
        (hit if run.summary["impacts"] > 0 else free).append((state, u))
        if len(free) >= n and len(hit) >= n:
            break
    return free[:n], hit[:n]


def _us_per_step(level, cases: list, repeats: int) -> dict:
    steps = len(cases) * math.ceil(DURATION / level.step - 1e-9)

    def run() -> None:
        for state, u in cases:
            level.propagate(state, u, DURATION)

    return per_item_us(run, steps, repeats)


def bench_table3_steps(repeats: int, seed: int, n: int) -> dict:
    """(a) free and impact propagations on table3, and the geometric level on the free ones."""
    scene = build_feeder(PRESETS["table3"], name="table3")
    level = KinematicLevel(scene)
    free, hit = _workload(level, seed, n)
    impacts = [level.run(s, u, DURATION, record=False).summary for s, u in hit]
    per_step = math.ceil(DURATION / level.step - 1e-9)
    geometric = GeometricLevel(scene)
    free_poses = [(s[:3], u) for s, u in free]
    return {
        "free_cases": len(free),
        "impact_cases": len(hit),
        "free_us_per_step": _us_per_step(level, free, repeats),
        "impact_us_per_step": _us_per_step(level, hit, repeats),
        "geometric_free_us_per_step": _us_per_step(geometric, free_poses, repeats),
        "impacts_per_step_in_impact_cases": sum(r["impacts"] for r in impacts)
        / (per_step * len(hit)),
        "sub_steps_per_step_in_impact_cases": sum(r["sub_steps"] for r in impacts)
        / (per_step * len(hit)),
        "jams": sum(r["jams"] for r in impacts),
        "stalls": sum(r["stalls"] for r in impacts),
    }


def bench_pressed(repeats: int) -> dict:
    """(b) pushed diagonally into a floor: an impact every step."""
    scene = _floor_scene()
    level = KinematicLevel(scene)
    state = level.state_of_pose(scene.start("start"))
    summary = level.run(state, (1.0, -1.0, 0.0), DURATION, record=False).summary
    result = _us_per_step(level, [(state, (1.0, -1.0, 0.0))], repeats)
    return {**result, "impacts_per_step": summary["impacts"] / summary["steps"]}


def bench_skip(repeats: int) -> dict:
    """(c) a step with nothing within the search margin, and one beside a wall (the floor
    0.02 below) moving parallel to it: the second searches and finds candidates every step."""
    scene = _floor_scene()
    level = KinematicLevel(scene)
    open_case = [((0.0, 20.0, 0.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0))]
    near_case = [((0.0, 0.52, 0.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0))]
    return {
        "open_us_per_step": _us_per_step(level, open_case, repeats),
        "near_wall_us_per_step": _us_per_step(level, near_case, repeats),
    }


def run_kinematic_benchmarks(repeats: int = 5, seed: int = 1, quick: bool = False) -> dict:
    """All measurements (a)-(d); ``quick`` uses 20 cases instead of 100 per class and 3
    planning seeds instead of 10. OMPL's log is silenced while planning."""
    from ompl import util as ou

    if repeats < 1:
        raise ValueError(f"repeats = {repeats} must be >= 1")
    previous = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    try:
        seeds = 3 if quick else 10
        scene = build_feeder(PRESETS["table3"], name="table3")
        return {
            "machine": machine_info(),
            "settings": {"repeats": repeats, "seed": seed, "quick": quick, "duration_s": DURATION},
            "table3": bench_table3_steps(repeats, seed, 20 if quick else 100),
            "pressed": bench_pressed(repeats),
            "skip": bench_skip(repeats),
            "planning": {
                planner: bench_planning(scene, seeds, 10.0, "kinematic", planner)
                for planner in ("rrt", "kpiece")
            },
        }
    finally:
        ou.setLogLevel(previous)


def _row(label: str, r: dict) -> str:
    return (
        f"{label:<44} {r['median']:>8.3g} {r['min']:>8.3g} {r['max']:>8.3g} "
        f"{r['q3'] - r['q1']:>8.2g}"
    )


def format_kinematic_report(results: dict) -> str:
    """The results of :func:`run_kinematic_benchmarks` as a plain-text table."""
    m, s, t = results["machine"], results["settings"], results["table3"]
    lines = [
        f"partfeeder benchmarks: kinematic level (h = 0.01 s), seed {s['seed']}, "
        f"{s['repeats']} repeats{' (quick)' if s['quick'] else ''}",
        f"machine: {m['platform']}, {m['cores']} cores; Python {m['python']}, "
        f"numba {m['numba']}, ompl {m['ompl']}",
        "",
        f"{'us per propagation step':<44} {'median':>8} {'min':>8} {'max':>8} {'IQR':>8}",
        _row(f"(a) table3, no impact ({t['free_cases']} calls)", t["free_us_per_step"]),
        _row(f"(a) table3, with impacts ({t['impact_cases']} calls)", t["impact_us_per_step"]),
        _row("(a) geometric level, same free calls", t["geometric_free_us_per_step"]),
        _row(
            f"(b) pressed onto a floor ({results['pressed']['impacts_per_step']:.1f} impacts/step)",
            results["pressed"],
        ),
        _row("(c) open space (search finds nothing)", results["skip"]["open_us_per_step"]),
        _row("(c) sliding beside a wall", results["skip"]["near_wall_us_per_step"]),
        f"impact cases: {t['impacts_per_step_in_impact_cases']:.2f} impacts and "
        f"{t['sub_steps_per_step_in_impact_cases']:.2f} advances per step; jams {t['jams']:.0f},"
        f" stalls {t['stalls']:.0f}",
        "",
        "(d) table3, time to first solution (s; unsolved runs count as the 10 s limit)",
        f"{'planner':<8} {'orientation':<16} {'solved':>7} {'median':>8} {'max':>8} {'tree':>7}",
    ]
    for planner, by_orientation in results["planning"].items():
        for orientation, r in by_orientation.items():
            lines.append(
                f"{planner:<8} {orientation:<16} {100 * r['solved_fraction']:>6.0f}% "
                f"{r['median']:>8.3g} {r['max']:>8.3g} {r['median_tree_size']:>7.0f}"
            )
    return "\n".join(lines)
