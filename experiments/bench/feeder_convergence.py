"""Convergence of the feeder's passive drop with h: what converges, and what does not.

Contact through a feeder is chaotic: a 1e-9 change of the entry changes where a drop ends, so
the exit pose of one drop does not converge as h shrinks (a smaller h is just another
perturbation). What a design's verdict rests on does: the success fraction over many
perturbed drops, and the distribution of Eq. 10's T. So, for a fixed set of designs and each
h, ``drops`` seeded drops per entry orientation (entry pose perturbed by +-0.05 in x and y and
+-0.05 rad in yaw, uniform: :mod:`experiments.drop.perturbations` with nothing else
perturbed; the same draws at every h), against the same drops at a much finer reference step
``min(h) / REFERENCE_DIVISOR``:

* the success fraction with its Wilson 95% interval, and |p(h) - p(ref)|;
* T's distribution: the two-sample Kolmogorov-Smirnov distance to the reference's T
  (``ks``; the 95% critical value of the KS test for two samples of that size is given as the
  floor below which a distance is indistinguishable from sampling noise) and the difference of
  the medians;
* what does not converge, for contrast: the median over drops of |T(h) - T(ref)| for the same
  drop (same draw).

Wall time is that of the drops themselves (``passive_drop``'s clock, the level built once per
design and h).
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Sequence

import numpy as np
from scipy.stats import ks_2samp

from experiments.drop.passive import passive_drop
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import entry_state
from experiments.proportions import wilson_interval
from feeders.design import PRESETS, DesignParameters
from feeders.feeder import ORIENTATIONS, build_feeder
from feeders.halton import halton_points
from feeders.scene import Scene
from validity.dynamic import DynamicLevel

H_FULL = (1e-2, 4e-3, 2e-3, 1e-3)
H_QUICK = (1e-2, 2e-3)
REFERENCE_DIVISOR = 16
DESIGNS_FULL = ("table3", "fig7a", "fig9", "halton0:6", "halton0:14")
DESIGNS_QUICK = ("table3",)
ENTRY_NOISE = Perturbations(position=0.05, yaw=0.05, speed=0.0, friction=0.0, tolerance=0.0)
KS_C95 = 1.358  # c(0.05) of the two-sample Kolmogorov-Smirnov test
T_MAX = 10.0  # s: longest drop


def design_of(name: str) -> DesignParameters:
    """A preset (``table3``) or a Halton design ``halton<seed>:<index>``."""
    if name in PRESETS:
        return PRESETS[name]
    if name.startswith("halton") and ":" in name:
        seed, index = name[len("halton") :].split(":")
        points = halton_points(int(index) + 1, int(seed))
        return DesignParameters.from_vector([float(v) for v in points[int(index)]])
    raise ValueError(f"design {name!r}: a preset ({', '.join(PRESETS)}) or halton<seed>:<index>")


def ks_critical(n: int, m: int) -> float:
    """The 95% critical value of the two-sample KS distance for samples of sizes n and m."""
    return KS_C95 * math.sqrt((n + m) / (n * m))


def _drops(scene: Scene, h: float, drops: int, seed: int) -> list[dict]:
    """``drops`` perturbed drops per entry orientation at step h (draw i is the same at any h)."""
    level = DynamicLevel(scene, step=h)
    rows = []
    for index in range(drops):
        d = draw(ENTRY_NOISE, seed, index, len(ORIENTATIONS))
        for k, orientation in enumerate(ORIENTATIONS):
            pose = scene.start(orientation)
            start = entry_state(level, pose, d.entry_offsets[k], d.entry_velocities[k])
            r = passive_drop(scene, orientation, t_max=T_MAX, level=level, start=start)
            rows.append(
                {
                    "index": index,
                    "orientation": orientation,
                    "success": bool(r.success),
                    "T": float(r.T),
                    "wall_s": float(r.wall_time),
                    "steps": int(r.steps),
                }
            )
    return rows


def _summary(rows: list[dict], reference: list[dict] | None) -> dict:
    successes = sum(r["success"] for r in rows)
    low, high = wilson_interval(successes, len(rows))
    times = [r["T"] for r in rows]
    out = {
        "drops": len(rows),
        "successes": successes,
        "p": successes / len(rows),
        "interval": [low, high],
        "T_median": statistics.median(times),
        "wall_per_drop_s": statistics.mean(r["wall_s"] for r in rows),
        "wall_per_sim_s": sum(r["wall_s"] for r in rows) / sum(times),
        "T": times,
    }
    if reference is not None:
        ref_times = [r["T"] for r in reference]
        p_ref = sum(r["success"] for r in reference) / len(reference)
        out.update(
            p_error=abs(out["p"] - p_ref),
            ks=float(ks_2samp(times, ref_times).statistic),
            ks_critical=ks_critical(len(times), len(ref_times)),
            median_T_error=abs(out["T_median"] - statistics.median(ref_times)),
            paired_T_error=float(np.median(np.abs(np.asarray(times) - np.asarray(ref_times)))),
        )
    return out


def run_feeder_convergence(
    designs: Sequence[str] = DESIGNS_FULL,
    h_values: Sequence[float] = H_FULL,
    drops: int = 30,
    seed: int = 1,
) -> dict:
    """Per design: the reference and each h (see the module docstring)."""
    if drops < 2:
        raise ValueError(f"drops = {drops} must be >= 2")
    h_ref = min(h_values) / REFERENCE_DIVISOR
    out = {}
    for name in designs:
        scene = build_feeder(design_of(name), name=name)
        reference = _drops(scene, h_ref, drops, seed)
        out[name] = {
            "reference": {"h": h_ref, **_summary(reference, None)},
            "by_h": [
                {"h": h, **_summary(_drops(scene, h, drops, seed), reference)} for h in h_values
            ],
        }
    return {
        "h": list(h_values),
        "h_reference": h_ref,
        "drops_per_orientation": drops,
        "seed": seed,
        "entry_noise": ENTRY_NOISE.to_dict(),
        "designs": out,
    }
