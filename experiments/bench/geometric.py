"""Benchmarks of the geometric level on table3: measure, never assert.

What costs what, all in one run and on one seeded workload:

* (a) one validity check, ``GeometricLevel.is_valid`` called from Python (what OMPL pays);
* (b) the same check inside compiled code, a numba loop over the batch calling
  :func:`validity.geometric.pose_is_valid` (the kernel alone, no call overhead);
* (c) the same question asked of the FCL reference (:class:`validity.fcl_reference.FclScene`);
* (d) one propagation step of ``GeometricLevel.propagate``, in free motion and in motion that
  ends at a wall (a step is one ``q <- q + h u`` attempt, i.e. one validity check);
* (e) time to the first solution of RRT on table3 over seeds, for both start orientations,
  with the solved fraction and the tree size;
* (f) the first call in a fresh interpreter (numba compile or cache load), apart from warm
  calls.

Per-check and per-step figures are microseconds; each repeat times a loop long enough
(``MIN_REPEAT_TIME`` seconds) to swamp the timer's resolution, and the report gives the
median, min, max and interquartile range over repeats. Planning times are seconds.
"""

from __future__ import annotations

import json
import math
import statistics
import subprocess
import sys
from dataclasses import dataclass

import numpy as np
from numba import njit

from experiments.bench.timing import (
    REPO_ROOT,
    bench_planning,
    machine_info,
    per_item_us,
)
from feeders.design import PRESETS
from feeders.feeder import build_feeder
from feeders.scene import Scene
from validity.fcl_reference import FCL_TOLERANCE_BAND, FclScene
from validity.geometric import GeometricLevel, pose_is_valid, propagate_increments
from validity.pose_samples import cross_check_poses

PROPAGATION_DURATION = 0.5  # s of motion per propagate call (50 steps at h = 0.01)


@njit(cache=True)
def count_valid(
    poses: np.ndarray,
    body: np.ndarray,
    bcounts: np.ndarray,
    bdiscs: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    bounds: np.ndarray,
) -> int:
    """How many rows ``(x, y, yaw)`` of ``poses`` are valid (compiled loop of (b)); arrays as
    :attr:`validity.scene_arrays.SceneArrays.pose_scene` gives them."""
    valid = 0
    for k in range(poses.shape[0]):
        if pose_is_valid(
            poses[k, 0],
            poses[k, 1],
            poses[k, 2],
            body,
            bcounts,
            bdiscs,
            verts,
            counts,
            aabbs,
            circles,
            bounds,
        ):
            valid += 1
    return valid


@dataclass(frozen=True)
class Workload:
    """The seeded inputs every measurement uses.

    ``poses (n, 3)``: mixed valid and invalid poses of table3 (half uniform over the bounds,
    half in contact with a wall); ``free_cases`` / ``hit_cases``: ``(state, control, steps)``
    for propagations of ``PROPAGATION_DURATION`` that run free / end at a wall, ``steps``
    the number of validity checks each makes.
    """

    scene: Scene
    level: GeometricLevel
    poses: np.ndarray
    free_cases: list[tuple[tuple[float, ...], tuple[float, ...], int]]
    hit_cases: list[tuple[tuple[float, ...], tuple[float, ...], int]]

    @property
    def pose_tuples(self) -> list[tuple[float, float, float]]:
        return [(float(x), float(y), float(t)) for x, y, t in self.poses]


def table3_workload(seed: int = 1, n_poses: int = 2000, n_cases: int = 20) -> Workload:
    """The table3 scene, its geometric level and a seeded batch of poses and propagations.

    Propagation cases start at valid poses of the batch with controls uniform in U, kept in
    the order drawn until ``n_cases`` run free for the whole duration and ``n_cases`` stop
    at a wall after at least 5 steps.
    """
    scene = build_feeder(PRESETS["table3"], name="table3")
    level = GeometricLevel(scene)
    poses = cross_check_poses(scene, n_poses, seed)
    rng = np.random.default_rng(seed)
    low, high = scene.inputs.bounds()
    a = level.arrays
    n_steps = max(1, math.ceil(PROPAGATION_DURATION / level.step - 1e-9))
    free: list = []
    hit: list = []
    for _ in range(100_000):
        if len(free) >= n_cases and len(hit) >= n_cases:
            break
        q = tuple(float(v) for v in poses[rng.integers(len(poses))])
        if not level.is_valid(q):
            continue
        u = tuple(float(v) for v in rng.uniform(low, high))
        geometry = a.pose_scene
        *_, steps, blocked = propagate_increments(
            q[0], q[1], q[2], u[0], u[1], u[2], PROPAGATION_DURATION, level.step, *geometry
        )
        if not blocked and len(free) < n_cases:
            free.append((q, u, n_steps))
        elif blocked and steps >= 5 and len(hit) < n_cases:
            hit.append((q, u, steps + 1))  # the steps taken and the check that failed
    return Workload(scene, level, poses, free, hit)


def bench_validity_python(work: Workload, repeats: int) -> dict:
    """(a) microseconds per ``GeometricLevel.is_valid`` call from Python."""
    poses, is_valid = work.pose_tuples, work.level.is_valid

    def run() -> None:
        for p in poses:
            is_valid(p)

    return per_item_us(run, len(poses), repeats)


def bench_validity_compiled(work: Workload, repeats: int) -> dict:
    """(b) microseconds per check of ``pose_is_valid`` in a compiled loop over the batch."""
    a = work.level.arrays
    poses = np.ascontiguousarray(work.poses)

    def run() -> int:
        return count_valid(poses, *a.pose_scene)

    return per_item_us(run, len(poses), repeats)


def bench_validity_fcl(work: Workload, repeats: int) -> dict:
    """(c) microseconds per ``FclScene.penetrates`` call; with its agreement with the kernel
    outside the band ``FCL_TOLERANCE_BAND`` (FCL tests penetration only, not the bounds)."""
    reference = FclScene(work.scene)
    poses = work.pose_tuples

    def run() -> None:
        for p in poses:
            reference.penetrates(p)

    result = per_item_us(run, len(poses), repeats)
    clearance = np.array([work.level.clearance(p) for p in poses])
    fcl_hit = np.array([reference.penetrates(p) for p in poses])
    outside = np.abs(clearance) >= FCL_TOLERANCE_BAND
    result["compared"] = int(outside.sum())
    result["disagreements"] = int((outside & (fcl_hit != (clearance < 0))).sum())
    return result


def bench_propagation(work: Workload, repeats: int, cases: str) -> dict:
    """(d) microseconds per step of ``GeometricLevel.propagate`` over ``free`` or ``hit``
    cases (a step: one ``q <- q + h u`` attempt and its validity check)."""
    chosen = work.free_cases if cases == "free" else work.hit_cases
    propagate = work.level.propagate

    def run() -> None:
        for q, u, _ in chosen:
            propagate(q, u, PROPAGATION_DURATION)

    result = per_item_us(run, sum(steps for *_, steps in chosen), repeats)
    result["calls"] = len(chosen)
    return result


_FIRST_CALL_SCRIPT = """
import json, time
t0 = time.perf_counter()
from feeders.design import PRESETS
from feeders.feeder import build_feeder
from validity.geometric import GeometricLevel
t1 = time.perf_counter()
scene = build_feeder(PRESETS["table3"], name="table3")
t2 = time.perf_counter()
level = GeometricLevel(scene)
t3 = time.perf_counter()
pose = scene.start("heavy_leading")
level.is_valid(pose)
t4 = time.perf_counter()
level.is_valid(pose)
t5 = time.perf_counter()
level.propagate(pose, (0.0, -1.0, 0.0), 0.5)
t6 = time.perf_counter()
level.propagate(pose, (0.0, -1.0, 0.0), 0.5)
t7 = time.perf_counter()
level.clearance(pose)
t8 = time.perf_counter()
level.clearance(pose)
t9 = time.perf_counter()
print(json.dumps({
    "import_s": t1 - t0, "build_scene_s": t2 - t1, "level_init_s": t3 - t2,
    "is_valid_first_s": t4 - t3, "is_valid_warm_s": t5 - t4,
    "propagate_first_s": t6 - t5, "propagate_warm_s": t7 - t6,
    "clearance_first_s": t8 - t7, "clearance_warm_s": t9 - t8,
}))
"""


def bench_first_call(runs: int) -> dict:
    """(f) seconds for the first calls in a fresh interpreter (numba compiles, or loads its
    on-disk cache, on first use), next to the same calls warm; medians over ``runs``."""
    samples: list[dict] = []
    for _ in range(runs):
        command = [sys.executable, "-c", _FIRST_CALL_SCRIPT]
        done = subprocess.run(command, cwd=REPO_ROOT, capture_output=True, text=True, check=True)
        samples.append(json.loads(done.stdout.strip().splitlines()[-1]))
    medians = {key: statistics.median(s[key] for s in samples) for key in samples[0]}
    return {**medians, "runs": runs}


def run_benchmarks(repeats: int = 5, seed: int = 1, quick: bool = False) -> dict:
    """All measurements (a)-(f) on table3 with a workload seeded by ``seed``.

    ``quick``: 500 poses instead of 2,000, planning over seeds 1..3 instead of 1..10 and one
    fresh interpreter for the first-call timing instead of up to three. OMPL's console log is
    silenced during the run and restored afterwards.
    """
    from ompl import util as ou

    if repeats < 1:
        raise ValueError(f"repeats = {repeats} must be >= 1")
    previous = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    try:
        first_call = bench_first_call(1 if quick else min(repeats, 3))
        work = table3_workload(seed, n_poses=500 if quick else 2000)
        valid = sum(work.level.is_valid(p) for p in work.pose_tuples)
        results = {
            "machine": machine_info(),
            "settings": {
                "scene": work.scene.name,
                "repeats": repeats,
                "seed": seed,
                "quick": quick,
                "poses": len(work.poses),
                "valid_fraction": valid / len(work.poses),
                "step_h": work.level.step,
                "propagation_duration_s": PROPAGATION_DURATION,
            },
            "validity_python_us": bench_validity_python(work, repeats),
            "validity_compiled_us": bench_validity_compiled(work, repeats),
            "validity_fcl_us": bench_validity_fcl(work, repeats),
            "propagate_free_us_per_step": bench_propagation(work, repeats, "free"),
            "propagate_hit_us_per_step": bench_propagation(work, repeats, "hit"),
            "planning_rrt": bench_planning(work.scene, 3 if quick else 10),
            "first_call_s": first_call,
        }
    finally:
        ou.setLogLevel(previous)
    return results


_ROWS = (
    ("validity_python_us", "(a) is_valid from Python", "us/check"),
    ("validity_compiled_us", "(b) pose_is_valid, compiled loop", "us/check"),
    ("validity_fcl_us", "(c) FCL reference penetrates", "us/check"),
    ("propagate_free_us_per_step", "(d) propagate, free motion", "us/step"),
    ("propagate_hit_us_per_step", "(d) propagate, hitting a wall", "us/step"),
)


def _fmt(value: float) -> str:
    return f"{value:.3g}" if abs(value) < 1000 else f"{value:.0f}"


def format_report(results: dict) -> str:
    """The results of :func:`run_benchmarks` as a plain-text table."""
    m, s = results["machine"], results["settings"]
    lines = [
        f"partfeeder benchmarks: {s['scene']}, geometric level (h = {s['step_h']:g} s), "
        f"seed {s['seed']}, {s['repeats']} repeats{' (quick)' if s['quick'] else ''}",
        f"machine: {m['platform']}, {m['cores']} cores ({m['usable_cores']} usable); "
        f"Python {m['python']}, numpy {m['numpy']}, numba {m['numba']}, ompl {m['ompl']}, "
        f"python-fcl {m['python-fcl']}, shapely {m['shapely']}",
        f"poses: {s['poses']} ({100 * s['valid_fraction']:.0f}% valid); propagations of "
        f"{s['propagation_duration_s']:g} s",
        "",
        f"{'measure':<36} {'unit':>9} {'median':>8} {'min':>8} {'max':>8} {'IQR':>8}",
    ]
    for key, label, unit in _ROWS:
        r = results[key]
        lines.append(
            f"{label:<36} {unit:>9} {_fmt(r['median']):>8} {_fmt(r['min']):>8} "
            f"{_fmt(r['max']):>8} {_fmt(r['q3'] - r['q1']):>8}"
        )
    fcl = results["validity_fcl_us"]
    lines.append(
        f"  FCL vs kernel outside |d| < {FCL_TOLERANCE_BAND:g}: {fcl['disagreements']} "
        f"disagreements in {fcl['compared']} poses"
    )
    planning = results["planning_rrt"]
    lines += [
        "",
        "(e) RRT, time to first solution (s; unsolved runs count as the time limit)",
        f"{'orientation':<16} {'seeds':>7} {'solved':>7} {'median':>8} {'min':>8} {'max':>8} "
        f"{'tree size':>10}",
    ]
    for orientation, r in planning.items():
        lines.append(
            f"{orientation:<16} {r['seeds'][0]:>3}..{r['seeds'][1]:<2} "
            f"{100 * r['solved_fraction']:>6.0f}% {_fmt(r['median']):>8} {_fmt(r['min']):>8} "
            f"{_fmt(r['max']):>8} {r['median_tree_size']:>10.0f}"
        )
    f = results["first_call_s"]
    lines += [
        "",
        f"(f) first calls in a fresh interpreter (s, median of {f['runs']}): first / warm",
        f"  imports {f['import_s']:.3g}, build table3 {f['build_scene_s']:.3g}, "
        f"GeometricLevel() {f['level_init_s']:.3g}",
        f"  is_valid {f['is_valid_first_s']:.3g} / {f['is_valid_warm_s']:.2g}, "
        f"propagate {f['propagate_first_s']:.3g} / {f['propagate_warm_s']:.2g}, "
        f"clearance {f['clearance_first_s']:.3g} / {f['clearance_warm_s']:.2g}",
    ]
    return "\n".join(lines)
