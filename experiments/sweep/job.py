"""One job of a sweep: one design at one level, from plain data to plain data.

A job is a :class:`SweepJob`, a dict of declared shape that pickles (worker processes and Dask
workers build their own OMPL objects from it); :func:`sweep_job` makes it from the config, the
only place its keys are filled, and :func:`job_from_dict` checks one that arrived from
elsewhere. The result is a dict for :func:`experiments.sweep.results_db.record`.

A job of a device family's sweep (issue 24) carries the family file's text and name: each
worker reads the family from it (a few ms, no cache) and builds the design's scene with
:meth:`feeders.device_family.DeviceFamily.build`; the entries are the family's, in its file's
order, where the feeder's are ``heavy_leading`` and ``heavy_trailing``.
"""

from __future__ import annotations

import dataclasses
import os
import socket
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypedDict

import numpy as np

from experiments.family_config import family_of_text
from experiments.names import DROP_RUNGS, NECESSARY, PASSIVE, SCREEN
from experiments.sweep.results_db import SAMPLED_LEVELS
from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.scene_yaml import environment_from_dict

if TYPE_CHECKING:
    from experiments.sweep.config import SweepConfig
    from feeders.device_family import DeviceFamily
    from feeders.scene import Scene


class SweepJob(TypedDict):
    """One design at one rung of the ladder, as a worker receives it."""

    design_id: int
    values: list[float]  # the 12 parameters, order of PARAMETER_NAMES (a family's: its order)
    rung: int  # index in the ladder
    level: str
    planners: list[str]
    runs: int  # per planner and entry orientation
    time_s: float  # budget per run (s)
    propagations: int | None  # budget per run in propagations, or None
    feeder: dict[str, Any]  # the scene's environment (config's ``feeder``)
    planner: dict[str, Any]  # OMPL's propagation settings (config's ``planner``)
    seed: int  # the sweep's
    name: str  # the sweep's
    verdict: dict[str, Any]  # the passive rung's VerdictSettings fields, the screen's
    # ScreenSettings fields ({} for a level)
    perturbations: dict[str, float]  # the drop rungs' Perturbations fields ({} for a level)
    family: dict[str, str] | None  # {"name", "yaml"}: the device family; None: the feeder


def sweep_job(config: SweepConfig, design_id: int, values: list[float], rung: int) -> SweepJob:
    """The job of design ``design_id`` (with ``values``) at rung ``rung`` of ``config``."""
    r = config.ladder[rung]
    return SweepJob(
        design_id=design_id,
        values=values,
        rung=rung,
        level=r.level,
        planners=list(r.planners),
        runs=r.runs,
        time_s=r.time_s,
        propagations=r.propagations,
        feeder=config.feeder,
        planner=config.planner,
        seed=config.seed,
        name=config.name,
        verdict=dict(r.verdict),
        perturbations=dict(r.perturbations),
        family=(
            None
            if config.family is None
            else {"name": Path(config.family).stem, "yaml": config.family_yaml}
        ),
    )


def job_family(job: SweepJob) -> DeviceFamily | None:
    """The job's device family, read from the text it carries (None: the 12-parameter
    feeder)."""
    if job["family"] is None:
        return None
    return family_of_text(job["family"]["yaml"], job["family"]["name"])


def entries_of(family: DeviceFamily | None) -> tuple[str, ...]:
    """The entry orientations a design is judged from: the family's, in its file's order, or
    the feeder's :data:`feeders.feeder.ORIENTATIONS`."""
    return ORIENTATIONS if family is None else tuple(name for name, _ in family.entries)


def job_from_dict(data: dict[str, Any]) -> SweepJob:
    """``data`` as a :class:`SweepJob`; ValueError naming a missing or unknown key."""
    keys = set(SweepJob.__annotations__)
    missing, unknown = sorted(keys - set(data)), sorted(set(data) - keys)
    if missing or unknown:
        raise ValueError(f"sweep job: missing keys {missing}, unknown keys {unknown}")
    return SweepJob(**data)  # type: ignore[typeddict-item]


def run_seed(sweep_seed: int, design_id: int, rung: int) -> int:
    """The OMPL seed of a design's evaluation at a rung (run r uses this + r): derived
    from the sweep's seed by NumPy's SeedSequence, so designs and rungs do not share streams."""
    state = np.random.SeedSequence([sweep_seed, design_id, rung]).generate_state(1)[0]
    return int(state % (2**31 - 1000))


def problem_name(sweep: str, design_id: int, level: str, orientation: str) -> str:
    """The OMPL experiment (Planner Arena's problem) of one design at one level from one
    entry, as one word: OMPL's log reader keeps only the last whitespace-separated word of a
    log's experiment line (a name's inner spaces become '_')."""
    return "/".join(("_".join(sweep.split()), f"design-{design_id}", level, orientation))


def verdict_seed(sweep_seed: int, design_id: int) -> int:
    """The seed of a design's passive verdict: from the sweep's seed and the design only (not
    the rung), so a design's verdict is the same whatever the ladder's order."""
    state = np.random.SeedSequence([sweep_seed, design_id, 0x5EED]).generate_state(1)[0]
    return int(state % (2**31 - 1))


def screen_seed(sweep_seed: int, design_id: int) -> int:
    """The seed of a design's screen: from the sweep's seed and the design, a stream apart
    from :func:`verdict_seed`'s, so the screen's drops and the verdict's are independent (the
    operating characteristic of the two together is then exact:
    :func:`experiments.drop.operating.screened_operating_point`)."""
    state = np.random.SeedSequence([sweep_seed, design_id, 0x5C2EE7]).generate_state(1)[0]
    return int(state % (2**31 - 1))


def warm_up(levels: tuple[str, ...]) -> None:
    """Load what the evaluations at ``levels`` (rung names) use before a worker's first job,
    so that no evaluation's ``wall_time_s`` counts it: the modules imported inside the
    evaluations and every kernel of their levels from numba's cache (the passive rung drops
    with the dynamic level). Measured on the default sweep before this existed: each
    worker's first passive verdict took 0.65-0.78 s against a median of 0.19 s."""
    from experiments.drop import verdict  # noqa: F401  (imported here for its load time)
    from validity.kernel_cache import compile_kernels

    if any(level not in (*DROP_RUNGS, NECESSARY) for level in levels):
        from planners import benchmark  # noqa: F401
    kernels = {"dynamic" if level in DROP_RUNGS else level for level in levels}
    compile_kernels(level for level in (*SAMPLED_LEVELS, NECESSARY) if level in kernels)


def evaluate_design(job: SweepJob) -> dict[str, Any]:
    """The design's evaluation at the job's rung: its passive verdict at the passive rung
    (:func:`evaluate_passive`), else whether it is feasible at the job's planning level."""
    job = job_from_dict(dict(job))
    if job["level"] == PASSIVE:
        return evaluate_passive(job)
    if job["level"] == NECESSARY:
        return evaluate_necessary(job)
    if job["level"] == SCREEN:
        return evaluate_screen(job)
    return evaluate_planning(job)


def evaluate_necessary(job: SweepJob) -> dict[str, Any]:
    """Can the design work at all? :func:`validity.necessary.necessary_conditions` of its
    feeder (the sweep's part and feeder options), for feeders made to the rung's tolerance
    and entries perturbed by its position and yaw: "infeasible", with the failed test as the
    reason, only when no drop can succeed (no design that works is pruned:
    docs/necessary.md); else "feasible"."""
    from experiments.drop.perturbations import Perturbations
    from validity.necessary import necessary_conditions

    t0 = time.perf_counter()
    result = _new_result(job)
    noise = Perturbations(**job["perturbations"])
    scene = _scene_or_degenerate(job, result, t0)
    if scene is None:
        return result
    verdict = necessary_conditions(scene, noise.tolerance, position=noise.position, yaw=noise.yaw)
    result["status"] = "feasible" if verdict.passes else "infeasible"
    if not verdict.passes:
        result["reason"] = f"fails the necessary {verdict.failed} test"
    result["wall_time_s"] = time.perf_counter() - t0
    return result


def _scene_or_degenerate(job: SweepJob, result: dict[str, Any], t0: float) -> Scene | None:
    """The job's feeder (its 12 values, the sweep's part and feeder options), or its
    family's device (:meth:`feeders.device_family.DeviceFamily.build`); None with
    ``result`` made "degenerate", with the reason and the time since ``t0``, when the design
    cannot be built."""
    values = [float(v) for v in job["values"]]
    name = f"design {int(job['design_id'])}"
    family = job_family(job)
    try:
        if family is not None:
            return dataclasses.replace(family.build(values), name=name)
        return build_feeder(
            DesignParameters.from_vector(values), name=name, **environment_from_dict(job["feeder"])
        )
    except DegenerateDesign as exc:
        result["status"] = "degenerate"
        result["reason"] = exc.reason
        result["wall_time_s"] = time.perf_counter() - t0
        return None


def _new_result(job: SweepJob, entries: tuple[str, ...] = ORIENTATIONS) -> dict[str, Any]:
    return {
        "design_id": int(job["design_id"]),
        "level": str(job["level"]),
        "status": "infeasible",
        "reason": None,
        "orientations": dict.fromkeys(entries),
        "runs": [],
        "logs": {},
        "worker": f"{socket.gethostname()}:{os.getpid()}",
    }


def evaluate_passive(job: SweepJob) -> dict[str, Any]:
    """Does the design work as a passive feeder? Its verdict
    (:func:`experiments.drop.verdict.design_verdict`) with the rung's settings and
    perturbations, seeded by :func:`verdict_seed`, for the sweep's part and feeder. The
    design passes the rung ("feasible") when it works: the Wilson lower bound of every entry
    clears the target; an entry's flag says whether its own bound does. The verdict
    (``Verdict.to_dict()``) and its seed travel in the result. A family's design: its
    :func:`experiments.drop.family_verdict.family_verdict` from the family's entries, with
    the family's part and friction."""
    from experiments.drop.family_verdict import family_verdict
    from experiments.drop.perturbations import Perturbations
    from experiments.drop.verdict import VerdictSettings, design_verdict

    t0 = time.perf_counter()
    family = job_family(job)
    entries = entries_of(family)
    result = _new_result(job, entries)
    values = [float(v) for v in job["values"]]
    environment = environment_from_dict(job["feeder"])
    settings = VerdictSettings(
        **job["verdict"], perturbations=Perturbations(**job["perturbations"])
    )
    seed = verdict_seed(int(job["seed"]), int(job["design_id"]))
    try:
        if family is not None:
            verdict = family_verdict(family, values, settings, seed)
        else:
            verdict = design_verdict(
                DesignParameters.from_vector(values),
                part=environment.pop("part"),
                friction=environment.pop("friction"),
                settings=settings,
                seed=seed,
                **environment,
            )
    except DegenerateDesign as exc:
        result["status"] = "degenerate"
        result["reason"] = exc.reason
        result["wall_time_s"] = time.perf_counter() - t0
        return result
    result["status"] = "feasible" if verdict.works else "infeasible"
    if verdict.decision == "undecided":
        result["reason"] = f"undecided after {verdict.drops} trials"
    for orientation in entries:
        result["orientations"][orientation] = verdict.interval(orientation)[0] > settings.target
    result["verdict"] = verdict.to_dict()
    result["verdict_seed"] = seed
    result["wall_time_s"] = time.perf_counter() - t0
    return result


def evaluate_screen(job: SweepJob) -> dict[str, Any]:
    """Can the design be shown failing cheaply? Its screen
    (:func:`experiments.drop.screen.design_screen`) with the rung's settings and
    perturbations, seeded by :func:`screen_seed`: "infeasible" when the screen fails it (a
    statistical prune with the stated error ``false_fails``), "feasible" when it passes,
    ``unknown`` when it is undecided (the design goes on to the verdict either way). The
    screen (``Screen.to_dict()``) travels in the result. A family's design: its
    :func:`experiments.drop.family_verdict.family_screen`, with the same seed."""
    from experiments.drop.family_verdict import family_screen
    from experiments.drop.perturbations import Perturbations
    from experiments.drop.screen import PASSES, design_screen
    from experiments.drop.screen_settings import ScreenSettings

    t0 = time.perf_counter()
    family = job_family(job)
    entries = entries_of(family)
    result = _new_result(job, entries)
    environment = environment_from_dict(job["feeder"])
    settings = ScreenSettings(**job["verdict"], perturbations=Perturbations(**job["perturbations"]))
    values = [float(v) for v in job["values"]]
    seed = screen_seed(int(job["seed"]), int(job["design_id"]))
    try:
        if family is not None:
            screen = family_screen(family, values, settings, seed)
        else:
            screen = design_screen(
                DesignParameters.from_vector(values),
                part=environment.pop("part"),
                friction=environment.pop("friction"),
                settings=settings,
                seed=seed,
                **environment,
            )
    except DegenerateDesign as exc:
        result["status"] = "degenerate"
        result["reason"] = exc.reason
        result["wall_time_s"] = time.perf_counter() - t0
        return result
    statuses = dict(zip(screen.orientations, screen.statuses, strict=True))
    result["status"] = {PASSES: "feasible", "fails": "infeasible"}.get(screen.decision, "unknown")
    failed = [o for o, s in statuses.items() if s == "fails"]
    if failed:
        k = screen.orientations.index(failed[0])
        result["reason"] = (
            f"fails the screen from {failed[0]} "
            f"({screen.successes[k]} of {screen.drops[k]} drops at h = {settings.step:g} s)"
        )
    elif screen.decision != PASSES:
        result["reason"] = f"screen undecided after {screen.total_drops} drops"
    for orientation in entries:
        result["orientations"][orientation] = statuses.get(orientation) == "works"
    result["screen"] = screen.to_dict()
    result["wall_time_s"] = time.perf_counter() - t0
    return result


def evaluate_planning(job: SweepJob) -> dict[str, Any]:
    """Is the design feasible at the job's level? Plans it from the heavy-leading entry, then
    the heavy-trailing one, each through OMPL's Benchmark with every planner of the rung,
    ``runs`` runs each. An entry is solved when any run reaches the goal exactly (the planners
    search for the same thing: one plan is a proof that the feeder can do it); the design is
    feasible when both are. An entry no run solved is "not found within budget": the status
    is ``unknown``, never ``infeasible`` (a sampling planner that runs out of budget has
    proved nothing, issue 21), and the other entry is skipped (the design cannot be shown
    feasible any more). A design that cannot be built is ``degenerate``, with the reason.

    A family's design is planned from each of the family's entries to its goal on
    :meth:`~feeders.device_family.DeviceFamily.build`'s scene. Its geometric level is not
    the feeder's relaxation: the slack and the entry region come from the feeder made to
    tolerance (:mod:`validity.made_envelope`), which a family has no counterpart of, so it
    plans with slack 0 from the entry poses only (a stricter geometric level: it may leave
    ``unknown`` a design the relaxation would solve).

    Returns a dict for :func:`experiments.sweep.results_db.record`.
    """
    from ompl import util as ou

    from planners.benchmark import Budget, benchmark_problem
    from planners.plan import PlannerSettings

    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    t0 = time.perf_counter()
    design_id, level = int(job["design_id"]), str(job["level"])
    family = job_family(job)
    entries = entries_of(family)
    result = _new_result(job, entries)
    values = [float(v) for v in job["values"]]
    scene = _scene_or_degenerate(job, result, t0)
    if scene is None:
        return result
    budget = Budget(float(job["time_s"]), job["propagations"])
    seed = run_seed(int(job["seed"]), design_id, int(job["rung"]))
    names = PARAMETER_NAMES if family is None else family.vector_names
    parameters: dict[str, float | int | str] = dict(zip(names, values, strict=True))
    parameters.update(design_id=design_id, level=level, seed=seed)
    level_options: dict[str, Any] = {}
    region = None
    if level == "geometric" and family is None:  # a relaxation: contact, the made walls'
        # tolerance and the entry region granted (the verdict's perturbations)
        from experiments.drop.perturbations import Perturbations
        from validity.geometric_slack import relaxation_slack

        noise = Perturbations(**job["perturbations"])
        level_options["slack"] = relaxation_slack(scene, noise.tolerance).total
        region = (noise.position, noise.yaw)
    feasible = True
    for orientation in entries:
        bench = benchmark_problem(
            scene,
            level,
            orientation,
            job["planners"],
            int(job["runs"]),
            budget,
            seed,
            experiment=problem_name(job["name"], design_id, level, orientation),
            parameters={**parameters, "orientation": orientation},
            settings=PlannerSettings(**job["planner"]),
            level_options=level_options,
            start_region=region,
        )
        result["logs"][orientation] = bench.log
        result["runs"].extend({"orientation": orientation, **run} for run in bench.runs)
        solved = any(run["solved"] for run in bench.runs)
        result["orientations"][orientation] = solved
        if not solved:
            feasible = False
            result["reason"] = f"not found within budget from {orientation}"
            break
    result["status"] = "feasible" if feasible else "unknown"
    result["wall_time_s"] = time.perf_counter() - t0
    return result
