"""Work a pool worker does, for the kernel cache tests, importable by spawned workers (a test
module is not): each returns what the worker's process compiled and loaded."""

from __future__ import annotations

from validity.kernel_cache import kernel_counts

# A sweep with every rung, budgets in propagations and the verdict's smallest trial budget:
# each rung's job calls every kernel of its level, as a real sweep's do.
EVERY_RUNG = {
    "name": "kernels",
    "designs": {"count": 1, "seed": 0},
    "feeder": {"inputs": {"max_force": 10.0, "max_torque": 2.0}},
    "ladder": [
        {"level": "passive", "verdict": {"min_drops": 1, "batch": 1, "max_drops": 1}},
        {"level": "geometric", "planners": ["rrt"], "budget": {"propagations": 300}},
        {"level": "kinematic", "planners": ["rrt"], "budget": {"propagations": 100}},
        {"level": "dynamic", "planners": ["rrt", "kpiece"], "budget": {"propagations": 50}},
    ],
}


def plan_and_count(level: str) -> tuple[int, int]:
    """Plan table3's heavy-leading entry at ``level`` with OMPL (a planning worker's work);
    ``(compiled, loaded)`` kernel signatures of this process."""
    from feeders.design import preset
    from feeders.feeder import build_feeder
    from planners.plan import plan

    plan(build_feeder(preset("table3"), name="table3"), level, "rrt", propagations=200)
    return kernel_counts()


def sweep_rung_and_count(rung: int) -> tuple[int, int]:
    """Evaluate the first Halton design at rung ``rung`` of :data:`EVERY_RUNG` as a sweep's
    worker does; ``(compiled, loaded)`` kernel signatures of this process."""
    from experiments.sweep.config import config_from_dict
    from experiments.sweep.job import evaluate_design, sweep_job
    from feeders.halton import halton_points

    config = config_from_dict(EVERY_RUNG)
    values = [float(v) for v in halton_points(1, config.seed)[0]]
    evaluate_design(sweep_job(config, 0, values, rung))
    return kernel_counts()
