"""One job of a sweep: one design at one level, from plain data to plain data.

A job is a dict that pickles (worker processes and Dask workers build their own OMPL objects
from it): ``design_id``, ``values`` (the 12 parameters), ``rung`` (index in the ladder),
``level``, ``planners``, ``runs``, ``time_s``, ``propagations``, ``feeder`` (the scene's
environment), ``planner`` (OMPL's propagation settings), ``seed`` (the sweep's), ``name``.
"""

from __future__ import annotations

import os
import socket
import time
from typing import Any

import numpy as np

from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.scene_yaml import environment_from_dict


def run_seed(sweep_seed: int, design_id: int, rung: int) -> int:
    """The OMPL seed of a design's evaluation at a rung (run r uses this + r): derived
    from the sweep's seed by NumPy's SeedSequence, so designs and rungs do not share streams."""
    state = np.random.SeedSequence([sweep_seed, design_id, rung]).generate_state(1)[0]
    return int(state % (2**31 - 1000))


def evaluate_design(job: dict[str, Any]) -> dict[str, Any]:
    """Is the design feasible at the job's level? Plans it from the heavy-leading entry, then
    the heavy-trailing one, each through OMPL's Benchmark with every planner of the rung,
    ``runs`` runs each. An entry is solved when any run reaches the goal exactly (the planners
    search for the same thing: one plan is a proof that the feeder can do it); the design is
    feasible when both are. Once an entry fails the other is skipped: the verdict is known.
    A design that cannot be built is ``degenerate``, with the reason.

    Returns a dict for :func:`experiments.results_db.record`.
    """
    from ompl import util as ou

    from planners.benchmark import Budget, benchmark_problem
    from planners.plan import PlannerSettings

    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    t0 = time.perf_counter()
    design_id, level = int(job["design_id"]), str(job["level"])
    result: dict[str, Any] = {
        "design_id": design_id,
        "level": level,
        "status": "infeasible",
        "reason": None,
        "orientations": dict.fromkeys(ORIENTATIONS),
        "runs": [],
        "logs": {},
        "worker": f"{socket.gethostname()}:{os.getpid()}",
    }
    values = [float(v) for v in job["values"]]
    try:
        scene = build_feeder(
            DesignParameters.from_vector(values),
            name=f"design {design_id}",
            **environment_from_dict(job["feeder"]),
        )
    except DegenerateDesign as exc:
        result["status"] = "degenerate"
        result["reason"] = exc.reason
        result["wall_time_s"] = time.perf_counter() - t0
        return result
    budget = Budget(float(job["time_s"]), job["propagations"])
    seed = run_seed(int(job["seed"]), design_id, int(job["rung"]))
    parameters: dict[str, float | int | str] = dict(zip(PARAMETER_NAMES, values, strict=True))
    parameters.update(design_id=design_id, level=level, seed=seed)
    feasible = True
    for orientation in ORIENTATIONS:
        bench = benchmark_problem(
            scene,
            level,
            orientation,
            job["planners"],
            int(job["runs"]),
            budget,
            seed,
            experiment=f"{job['name']}: design {design_id}, {level}, {orientation}",
            parameters={**parameters, "orientation": orientation},
            settings=PlannerSettings(**job["planner"]),
        )
        result["logs"][orientation] = bench.log
        result["runs"].extend({"orientation": orientation, **run} for run in bench.runs)
        solved = any(run["solved"] for run in bench.runs)
        result["orientations"][orientation] = solved
        if not solved:
            feasible = False
            break
    result["status"] = "feasible" if feasible else "infeasible"
    result["wall_time_s"] = time.perf_counter() - t0
    return result
