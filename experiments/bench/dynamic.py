"""Benchmarks of the dynamic level (Eq. 7): run time against error, and what the skips buy.

Measure, never assert. All in one run, so ratios are meaningful on a noisy machine:

* (a) the sliding box (incline scene, mu = 0.3, 1 s): microseconds per step and the error
  against the closed form, for partfeeder and, when installed, MuJoCo (``pip install
  'partfeeder[mujoco]'``), at h = 1e-3 and 1e-4; the sticking box (mu = 0.7): per step and
  creep;
* (b) the passive traversal of table3 from both entry orientations at h = 1e-3: wall time of
  the pair, microseconds per step;
* (c) the skips, each on and off on the same run: free flight without contact search (a drop
  from height and the table3 traversal), frictionless contact (the incline with mu = 0 and the
  LCP of size n_c, against mu = 0.3 and 4 n_c), and the broad phase (table3 with every
  obstacle's bounding box made infinite, so every obstacle reaches the narrow phase);
* (d) the first call in a fresh interpreter: cold (empty numba cache: the compile) and warm
  (cache on disk).

A partfeeder trajectory is one compiled call (Python is crossed once per trajectory); MuJoCo
is stepped from Python with ``mj_step``, as a user of its Python bindings would.
"""

from __future__ import annotations

import dataclasses
import json
import math
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from functools import partial
from typing import TypeVar

import numpy as np

from experiments.bench.peers.mujoco_reference import exact_displacement, mujoco_available
from experiments.bench.timing import REPO_ROOT, machine_info, stats
from feeders.design import PRESETS
from feeders.feeder import build_feeder
from feeders.scene import Scene
from feeders.scene_yaml import load_scene
from validity.dynamic import DynamicLevel

T = TypeVar("T")
INCLINE = REPO_ROOT / "experiments" / "scenes" / "incline.yaml"
PHI = math.radians(30.0)


def _incline(mu: float) -> Scene:
    return dataclasses.replace(load_scene(INCLINE), friction=mu)


def _timed(run: Callable[[], T], repeats: int) -> tuple[list[float], T]:
    """Seconds per call of ``run`` over ``repeats`` calls, after one warm call; last result."""
    result = run()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - t0)
    return times, result


def _slide(level: DynamicLevel, scene: Scene, duration: float):
    start = level.state_of_pose(scene.start("resting"))
    return level.simulate(start, duration=duration)


def _along(run, start) -> float:
    moved = run.final[:2] - np.asarray(start[:2])
    return float(moved @ np.array([math.cos(PHI), -math.sin(PHI)]))


def bench_incline(repeats: int) -> dict:
    """(a) partfeeder vs MuJoCo on the incline: us/step, error against the closed form."""
    out: dict = {"partfeeder": {}, "mujoco": {}}
    for mu, duration in ((0.3, 1.0), (0.7, 1.0)):
        scene = _incline(mu)
        for h in (1e-3, 1e-4):
            level = DynamicLevel(scene, step=h)
            times, run = _timed(partial(_slide, level, scene, duration), repeats)
            start = level.state_of_pose(scene.start("resting"))
            steps = len(run.states) - 1
            out["partfeeder"][f"mu={mu},h={h:g}"] = {
                "us_per_step": stats([t / steps * 1e6 for t in times]),
                "x": _along(run, start),
                "x_exact": exact_displacement(mu, duration),
                "error": abs(_along(run, start) - exact_displacement(mu, duration)),
                "max_penetration": run.summary["max_penetration"],
            }
    if mujoco_available():
        from experiments.bench.peers.mujoco_reference import simulate_incline, time_incline_steps

        for mu in (0.3, 0.7):
            for h in (1e-3, 1e-4):
                sim = simulate_incline(mu, h, duration=1.0)
                timing = time_incline_steps(mu, h, steps=1000, repeats=repeats)
                out["mujoco"][f"mu={mu},h={h:g}"] = {
                    "us_per_step": {
                        "median": timing["median_us"],
                        "min": timing["min_us"],
                        "max": timing["max_us"],
                    },
                    "x": sim["x_along"],
                    "x_exact": sim["x_exact"],
                    "error": sim["error"],
                    "max_penetration": sim["penetration"],
                }
        import mujoco

        out["mujoco_version"] = mujoco.__version__
    else:
        out["mujoco"] = "not installed: pip install 'partfeeder[mujoco]'"
    return out


def bench_traversal(repeats: int, **level_options) -> dict:
    """(b) both passive drops through table3; wall time of the pair and per step."""
    from experiments.drop.passive import passive_drop

    scene = build_feeder(PRESETS["table3"], name="table3")
    level = DynamicLevel(scene, **level_options)

    def both():
        return [passive_drop(scene, o, level=level) for o in ("heavy_leading", "heavy_trailing")]

    times, results = _timed(both, repeats)
    steps = sum(r.steps for r in results)
    return {
        "pair_ms": stats([t * 1e3 for t in times]),
        "us_per_step": stats([t / steps * 1e6 for t in times]),
        "steps": steps,
        "contact_searches": sum(r.contact_searches for r in results),
        "lcp_solves": sum(r.lcp_solves for r in results),
        "outcomes": {r.orientation: f"{r.end}, T = {r.T:.3f} s" for r in results},
    }


def _no_broad_phase(level: DynamicLevel) -> DynamicLevel:
    """The same level with every obstacle box infinite: the broad phase culls nothing."""
    boxes = np.tile([-np.inf, -np.inf, np.inf, np.inf], (len(level.arrays.aabbs), 1))
    level.arrays = dataclasses.replace(level.arrays, aabbs=boxes)
    return level


def bench_skips(repeats: int) -> dict:
    """(c) each skip on and off, same runs."""
    out: dict = {}
    floor = _incline(0.3)
    for skip in (True, False):
        level = DynamicLevel(floor, skip_free=skip)
        start = (5.0, 12.5, 0.3, 0.0, 0.0, 0.0)  # above the wedge: 0.5 s of free fall
        times, run = _timed(partial(level.simulate, start, duration=0.5), repeats)
        out[f"free_fall_skip={skip}"] = {
            "us_per_step": stats([t / 500 * 1e6 for t in times]),
            "contact_searches": run.summary["contact_searches"],
        }
    for skip in (True, False):
        out[f"table3_skip={skip}"] = bench_traversal(repeats, skip_free=skip)
    for mu in (0.0, 0.3):
        scene = _incline(mu)
        level = DynamicLevel(scene)
        times, run = _timed(partial(_slide, level, scene, 1.0), repeats)
        sizes = run.telemetry[:, 6]
        out[f"incline_mu={mu}"] = {
            "us_per_step": stats([t / 1000 * 1e6 for t in times]),
            "lcp_size": float(np.median(sizes[sizes > 0])),
        }
    scene = build_feeder(PRESETS["table3"], name="table3")
    for broad in (True, False):
        level = DynamicLevel(scene)
        if not broad:
            _no_broad_phase(level)
        begin = level.state_of_pose(scene.start("heavy_trailing"))
        times, run = _timed(partial(level.simulate, begin, duration=3.0), repeats)
        out[f"table3_broad_phase={broad}"] = {
            "us_per_step": stats([t / 3000 * 1e6 for t in times]),
            "final": [round(v, 12) for v in run.final[:3]],
        }
    return out


_FIRST_CALL = """
import json, time
t0 = time.perf_counter()
from feeders.design import PRESETS
from feeders.feeder import build_feeder
from validity.dynamic import DynamicLevel
t1 = time.perf_counter()
scene = build_feeder(PRESETS["table3"], name="table3")
level = DynamicLevel(scene)
start = level.state_of_pose(scene.start("heavy_leading"))
t2 = time.perf_counter()
level.simulate(start, duration=1.0)
t3 = time.perf_counter()
level.simulate(start, duration=1.0)
t4 = time.perf_counter()
print(json.dumps({"import_s": t1 - t0, "first_s": t3 - t2, "warm_s": t4 - t3}))
"""


def bench_first_call() -> dict:
    """(d) a fresh interpreter's first simulate: with an empty numba cache (cold compile) and
    again with the cache that run wrote (what every later process pays)."""
    out = {}
    with tempfile.TemporaryDirectory() as cache:
        env = {"NUMBA_CACHE_DIR": cache, "PATH": "/usr/bin:/bin"}
        for label in ("cold", "cached"):
            done = subprocess.run(
                [sys.executable, "-c", _FIRST_CALL],
                cwd=REPO_ROOT,
                capture_output=True,
                text=True,
                check=True,
                env=env,
            )
            out[label] = json.loads(done.stdout.strip().splitlines()[-1])
    return out


def run_dynamic_benchmarks(repeats: int = 5, quick: bool = False) -> dict:
    """All of (a)-(d); ``quick`` skips the cold compile (about 30 s)."""
    if repeats < 1:
        raise ValueError(f"repeats = {repeats} must be >= 1")
    results = {
        "machine": machine_info(),
        "settings": {"repeats": repeats, "quick": quick},
        "incline": bench_incline(repeats),
        "table3_traversal": bench_traversal(repeats),
        "skips": bench_skips(repeats),
    }
    if not quick:
        results["first_call"] = bench_first_call()
    return results


def _row(label: str, row: dict, unit: str) -> str:
    return f"{label:<44} {unit:>8} {row['median']:>8.3g} {row['min']:>8.3g} {row['max']:>8.3g}"


def format_dynamic_report(results: dict) -> str:
    """The results of :func:`run_dynamic_benchmarks` as plain text."""
    m = results["machine"]
    lines = [
        f"partfeeder dynamic level benchmarks, {results['settings']['repeats']} repeats",
        f"machine: {m['platform']}, {m['cores']} cores; numba {m['numba']}",
        "",
        "(a) box on a 30 degree incline, 1 s (reference: closed form 1/2 g (sin - mu cos) t^2)",
        f"{'engine, case':<30} {'us/step':>8} {'min':>6} {'max':>6} {'x (m)':>10} "
        f"{'error (m)':>10} {'overlap':>9}",
    ]
    inc = results["incline"]
    for engine in ("partfeeder", "mujoco"):
        if isinstance(inc[engine], str):
            lines.append(f"{engine}: {inc[engine]}")
            continue
        for case, r in inc[engine].items():
            u = r["us_per_step"]
            lines.append(
                f"{engine + ' ' + case:<30} {u['median']:>8.3g} {u['min']:>6.3g} "
                f"{u['max']:>6.3g} {r['x']:>10.6f} {r['error']:>10.2e} "
                f"{r['max_penetration']:>9.1e}"
            )
    if "mujoco_version" in inc:
        lines.append(f"  (MuJoCo {inc['mujoco_version']}, mj_step from Python, default solver)")
    t = results["table3_traversal"]
    lines += [
        "",
        "(b) passive traversal of table3, both orientations, h = 1e-3",
        f"{'measure':<44} {'unit':>8} {'median':>8} {'min':>8} {'max':>8}",
        _row("both drops", t["pair_ms"], "ms"),
        _row("per step", t["us_per_step"], "us/step"),
        f"  {t['steps']} steps, {t['contact_searches']} contact searches, "
        f"{t['lcp_solves']} LCPs; {t['outcomes']}",
        "",
        "(c) skips on/off",
    ]
    s = results["skips"]
    for skip in (True, False):
        r = s[f"free_fall_skip={skip}"]
        label = f"free fall 0.5 s, skip {'on' if skip else 'off'}"
        lines.append(
            _row(label, r["us_per_step"], "us/step") + f"  {r['contact_searches']:.0f} searches"
        )
    for skip in (True, False):
        r = s[f"table3_skip={skip}"]
        label = f"table3 pair, skip {'on' if skip else 'off'}"
        lines.append(_row(label, r["pair_ms"], "ms") + f"  {r['contact_searches']} searches")
    for mu in (0.0, 0.3):
        r = s[f"incline_mu={mu}"]
        label = f"incline, mu = {mu} (LCP size {r['lcp_size']:.0f})"
        lines.append(_row(label, r["us_per_step"], "us/step"))
    for broad in (True, False):
        r = s[f"table3_broad_phase={broad}"]
        label = f"table3 3 s, broad phase {'on' if broad else 'off'}"
        lines.append(_row(label, r["us_per_step"], "us/step"))
    if "first_call" in results:
        f = results["first_call"]
        lines += [
            "",
            "(d) first simulate (1 s of table3) in a fresh interpreter (s)",
            f"  empty numba cache: {f['cold']['first_s']:.2f} (compile); cached: "
            f"{f['cached']['first_s']:.3f}; warm call {f['cached']['warm_s'] * 1e3:.2f} ms",
        ]
    return "\n".join(lines)
