"""Work-precision data of the analytic scenes: error against wall time per simulated second.

For every case of :mod:`experiments.bench.analytic`, every engine setting of
:mod:`experiments.bench.engines` and every step h: the errors of one recorded run against the
closed form (runs are deterministic, so one suffices), and the wall time of the run without
recording, the median of ``repeats`` timings interleaved across all cases, settings and h of
the run (so ratios between engines come from the same minutes of a noisy machine). Also the
creep of the sticking box after a long run (10 s by default) per setting at h = 1e-3.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence
from functools import partial

from experiments.bench.analytic import CASES, AnalyticCase, case, steps_for
from experiments.bench.engines import EngineSetting, Simulator, engine_settings
from experiments.bench.timing import interleaved_seconds

H_FULL = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4)
H_QUICK = (1e-2, 1e-3, 1e-4)
CREEP_H = 1e-3
NOT_INSTALLED = "not installed"


def _point(c: AnalyticCase, s: EngineSetting, sim: Simulator, h: float) -> dict:
    steps = steps_for(c.duration, h)
    states = sim.record(c.start, steps)
    return {
        "engine": s.label,
        "h": h,
        "steps": steps,
        "errors": c.errors(states, h),
    }


def run_work_precision(
    h_values: Sequence[float] = H_FULL,
    repeats: int = 5,
    cases: Sequence[AnalyticCase] = CASES,
    creep_duration: float = 10.0,
) -> dict:
    """Every case x setting x h: errors and median wall time (see the module docstring)."""
    settings = engine_settings()
    points: dict[tuple[str, str, float], dict] = {}
    runs = {}
    for c in cases:
        for s in settings:
            if not s.available:
                continue
            for h in h_values:
                sim = s.build(c.scene, h)
                point = _point(c, s, sim, h)
                key = f"{c.name}|{s.label}|{h:g}"
                points[(c.name, s.label, h)] = point
                runs[key] = (partial(sim.prepare, c.start), partial(sim.advance, point["steps"]))
    seconds = interleaved_seconds(runs, repeats)
    for (name, label, h), point in points.items():
        times = seconds[f"{name}|{label}|{h:g}"]
        wall = statistics.median(times)
        duration = point["steps"] * h
        point.update(
            wall_s=wall,
            wall_per_sim_s=wall / duration,
            us_per_step=wall / point["steps"] * 1e6,
            wall_s_all=times,
        )
    stick = case("stick")
    creep: dict[str, float | str] = {}
    for s in settings:
        if not s.available:
            creep[s.label] = NOT_INSTALLED
            continue
        states = s.build(stick.scene, CREEP_H).record(
            stick.start, steps_for(creep_duration, CREEP_H)
        )
        creep[s.label] = stick.errors(states, CREEP_H)["error"]
    return {
        "h": list(h_values),
        "repeats": repeats,
        "engines": [
            {
                "label": s.label,
                "engine": s.engine,
                "setting": s.setting,
                "description": s.description,
                "available": s.available,
            }
            for s in settings
        ],
        "cases": {
            c.name: {
                "title": c.title,
                "scene": f"experiments/scenes/{c.scene_file}",
                "duration_s": c.duration,
                "measures": list(c.measures),
                "points": [p for (name, _, _), p in points.items() if name == c.name],
            }
            for c in cases
        },
        "creep": {"duration_s": creep_duration, "h": CREEP_H, "by_engine": creep},
    }
