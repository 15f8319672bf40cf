"""Speed tables: what one check, step, LCP and drop costs, and what each skip saves.

All on table3 (the paper's design) unless said, in one run:

* microseconds per validity check from Python, per level (the same seeded poses, half of
  them touching a wall: :func:`experiments.bench.geometric.table3_workload`);
* microseconds per propagation step, per level (the same valid starts; controls uniform in
  each level's input set, seeded; 0.5 s per call);
* microseconds per LCP solve (:func:`validity.lcp.solve_lcp`, compiled loop) by size 4 n_c,
  over seeded contact LCPs of Eq. 7 (n_c contacts on a 2 x 1 box, mu 0.3, approaching);
* milliseconds per passive drop of table3 from both entry orientations (h = 1e-3);
* the dynamic level's skips, each on and off, interleaved: free flight without contact search
  (``skip_free``), the previous step's basis (``warm_start``), frictionless LCPs (mu = 0
  against 0.3 on the sliding incline) and the broad phase (every obstacle box made infinite).

Ratios against the peer engines come from the work-precision run (same process, same
minutes): see :mod:`experiments.bench.summary`.
"""

from __future__ import annotations

import dataclasses
import math
import statistics
from functools import partial
from typing import Any

import numpy as np
from numba import njit

from experiments.bench.analytic import case
from experiments.bench.geometric import PROPAGATION_DURATION, table3_workload
from experiments.bench.timing import interleaved_seconds, per_item_us
from experiments.drop.passive import passive_drop
from feeders.design import PRESETS
from feeders.feeder import ORIENTATIONS, build_feeder
from validity.contact_lcp import assemble_lcp, contact_jacobians, lcp_columns
from validity.dynamic import DynamicLevel
from validity.kinematic import KinematicLevel
from validity.lcp import LCP_REGULARISED, solve_lcp

LCP_CONTACTS = (1, 2, 4, 8)  # n_c: LCP sizes 4, 8, 16, 32
LCP_MU = 0.3


@njit(cache=True)
def _solve_all(Bs: np.ndarray, bs: np.ndarray, zs: np.ndarray) -> int:
    """Solve every LCP(Bs[k], bs[k]) into zs[k]; how many were solved (compiled loop)."""
    solved = 0
    for k in range(Bs.shape[0]):
        status, _, _, _ = solve_lcp(Bs[k], bs[k], zs[k])
        if status <= LCP_REGULARISED:
            solved += 1
    return solved


def contact_lcps(nc: int, count: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """``count`` seeded LCPs of Eq. 7 (size 4 nc): a 2 x 1 box of mass 1 with nc contacts at
    points on its boundary, normals within 60 degrees of pointing at its centre, a velocity
    approaching them, mu = 0.3 (:func:`validity.contact_lcp.assemble_lcp`)."""
    rng = np.random.default_rng([seed, nc])
    minv = np.array([1.0, 1.0, 1.0 / (5.0 / 12.0)])
    n = 4 * nc
    Bs, bs = np.zeros((count, n, n)), np.zeros((count, n))
    for k in range(count):
        contacts = np.zeros((nc, 5))
        for i in range(nc):
            side = rng.integers(4)
            u = rng.uniform(-1.0, 1.0)
            point = [(u, -0.5), (1.0, 0.5 * u), (u, 0.5), (-1.0, 0.5 * u)][side]
            inward = -np.array(point) / np.hypot(*point)
            turn = rng.uniform(-math.pi / 3, math.pi / 3)
            c, s = math.cos(turn), math.sin(turn)
            normal = np.array([c * inward[0] - s * inward[1], s * inward[0] + c * inward[1]])
            contacts[i] = (0.0, normal[0], normal[1], point[0], point[1])
        wn, wt = np.zeros((3, nc)), np.zeros((3, nc))
        contact_jacobians(contacts, nc, 0.0, 0.0, wn, wt)
        cols = np.zeros((3, 3 * nc))
        m = lcp_columns(wn, wt, nc, True, cols)
        vstar = -contacts[:, 1:3].mean(axis=0) * rng.uniform(0.5, 2.0)
        vstar = np.array([vstar[0], vstar[1], rng.uniform(-1.0, 1.0)])
        assemble_lcp(cols, m, nc, True, LCP_MU, minv, np.zeros(nc), vstar, Bs[k], bs[k])
    return Bs, bs


def bench_lcp(repeats: int, seed: int, count: int) -> dict:
    """Microseconds per solve, by size."""
    out = {}
    for nc in LCP_CONTACTS:
        Bs, bs = contact_lcps(nc, count, seed)
        zs = np.zeros_like(bs)
        solved = _solve_all(Bs, bs, zs)
        out[str(4 * nc)] = {
            **per_item_us(partial(_solve_all, Bs, bs, zs), count, repeats),
            "contacts": nc,
            "solved": solved,
            "count": count,
        }
    return out


def _state(pose) -> tuple[float, ...]:
    return (float(pose[0]), float(pose[1]), float(pose[2]), 0.0, 0.0, 0.0)


def bench_levels(repeats: int, seed: int, n_poses: int, n_cases: int) -> dict:
    """Per level: microseconds per validity check and per propagation step on table3."""
    work = table3_workload(seed, n_poses=n_poses, n_cases=n_cases)
    scene = work.scene
    levels: dict[str, Any] = {
        "geometric": work.level,
        "kinematic": KinematicLevel(scene),
        "dynamic": DynamicLevel(scene),
    }
    rng = np.random.default_rng(seed)
    starts = [q for q, _, _ in work.free_cases]
    out = {}
    for name, level in levels.items():
        states = work.pose_tuples if name == "geometric" else [_state(p) for p in work.poses]
        is_valid = level.is_valid

        def checks(states=states, is_valid=is_valid) -> None:
            for s in states:
                is_valid(s)

        if name == "geometric":  # the workload's free propagations, every step taken
            cases = [(q, u) for q, u, _ in work.free_cases]
            steps = sum(n for *_, n in work.free_cases)
        else:  # the same starts at rest, inputs uniform in the level's set
            low, high = level.control_bounds()
            cases = [(_state(q), tuple(rng.uniform(low, high))) for q in starts]
            # steps taken (a propagation stops early before a step leaving the bounds)
            steps = sum(len(level.propagate_path(s, u, PROPAGATION_DURATION)) - 1 for s, u in cases)

        def propagate(cases=cases, level=level) -> None:
            for state, u in cases:
                level.propagate(state, u, PROPAGATION_DURATION)

        out[name] = {
            "step_h": level.step,
            "check_us": per_item_us(checks, len(states), repeats),
            "step_us": per_item_us(propagate, steps, repeats),
            "checks": len(states),
            "propagations": len(cases),
        }
    return out


def _no_broad_phase(level: DynamicLevel) -> DynamicLevel:
    """The level with every obstacle box infinite: the broad phase culls nothing."""
    boxes = np.tile([-np.inf, -np.inf, np.inf, np.inf], (len(level.arrays.aabbs), 1))
    level.arrays = dataclasses.replace(level.arrays, aabbs=boxes)
    return level


def _both_drops(scene, level: DynamicLevel) -> list:
    return [passive_drop(scene, o, level=level) for o in ORIENTATIONS]


def bench_skips_and_drops(repeats: int) -> dict:
    """The passive drop of table3 (both entries) and each skip on and off, interleaved."""
    table3 = build_feeder(PRESETS["table3"], name="table3")
    slide, stick, flight = case("slide"), case("stick"), case("flight")
    variants = {
        "table3 drops, all skips on": DynamicLevel(table3),
        "table3 drops, skip_free off": DynamicLevel(table3, skip_free=False),
        "table3 drops, warm_start off": DynamicLevel(table3, warm_start=False),
        "table3 drops, broad phase off": _no_broad_phase(DynamicLevel(table3)),
    }
    runs: dict = {}
    outcomes = {}
    for label, level in variants.items():
        results = _both_drops(table3, level)
        outcomes[label] = {
            "steps": sum(r.steps for r in results),
            "contact_searches": sum(r.contact_searches for r in results),
            "lcp_solves": sum(r.lcp_solves for r in results),
            "T": [r.T for r in results],
            "success": [r.success for r in results],
        }
        runs[label] = (lambda: None, partial(_both_drops, table3, level))
    one_second = {
        "flight 1 s, skip_free on": (flight, DynamicLevel(flight.scene)),
        "flight 1 s, skip_free off": (flight, DynamicLevel(flight.scene, skip_free=False)),
        "sticking box 1 s, warm_start on": (stick, DynamicLevel(stick.scene)),
        "sticking box 1 s, warm_start off": (stick, DynamicLevel(stick.scene, warm_start=False)),
        "sliding box 1 s, mu 0.3": (slide, DynamicLevel(slide.scene)),
        "sliding box 1 s, mu 0 (no friction unknowns)": (
            slide,
            DynamicLevel(dataclasses.replace(slide.scene, friction=0.0)),
        ),
    }
    for label, (c, level) in one_second.items():
        run = level.simulate(c.start, duration=c.duration)
        sizes = run.telemetry[:, 6]
        outcomes[label] = {
            "steps": int(run.summary["steps"]),
            "contact_searches": int(run.summary["contact_searches"]),
            "lcp_solves": int(run.summary["lcp_solves"]),
            "warm_starts": int(run.summary["warm_starts"]),
            "median_lcp_size": float(np.median(sizes[sizes > 0])) if (sizes > 0).any() else 0.0,
        }
        runs[label] = (
            lambda: None,
            partial(level.propagate, c.start, (0.0, 0.0, 0.0), c.duration),
        )
    seconds = interleaved_seconds(runs, repeats)
    out = {}
    for label, times in seconds.items():
        row = {"median_ms": statistics.median(times) * 1e3, **outcomes[label]}
        row["us_per_step"] = row["median_ms"] * 1e3 / max(row["steps"], 1)
        out[label] = row
    return out


def run_speed(repeats: int = 5, seed: int = 1, quick: bool = False) -> dict:
    """Every table of the module docstring."""
    return {
        "levels": bench_levels(repeats, seed, 300 if quick else 2000, 5 if quick else 20),
        "lcp": bench_lcp(repeats, seed, 16 if quick else 256),
        "dynamic_skips": bench_skips_and_drops(repeats),
    }
