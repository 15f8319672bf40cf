"""Feasibility of Halton designs at two levels of fidelity, on the same designs and budgets.

The question this answers: of the first N designs of the seeded Halton sequence over the
Table 2 box, what fraction is feasible at level A, what fraction at level B, and is A's
feasible set (nearly) a subset of B's? With A = "kinematic" and B = "geometric" it checks that
adding a model of motion only removes designs (a kinematically feasible design must also be
geometrically feasible, up to the planner's failures within its budget).

A design is *feasible at a level* when the planner reaches the goal from both entry
orientations within its budget each: wall-clock seconds, or, machine-independent, a count of
the planner's propagations (then the verdicts are the same on any machine and under any load).
Everything here passes plain data (lists, dicts, numbers, a :class:`FeasibilityJob` per
design x level): OMPL objects cannot be pickled, so each job builds its own scene and planner,
which lets jobs run in worker processes. The picture of the rows is
:mod:`experiments.verdicts.feasibility_figure`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

from experiments.executors.local import map_jobs
from experiments.proportions import wilson_interval
from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.halton import halton_points

# The four cells of the 2x2 agreement table, in display order.
AGREEMENT_CLASSES = ("both", "a_only", "b_only", "neither")


def _check_level(level: str) -> None:
    from validity import LEVELS

    if level not in LEVELS:
        raise ValueError(f"unknown level '{level}'; levels: {', '.join(LEVELS)}")


def _check_planner(planner: str) -> None:
    from planners.registry import PLANNERS

    if planner.lower() not in PLANNERS:
        raise ValueError(f"unknown planner '{planner}'; planners: {', '.join(PLANNERS)}")


def design_verdict(
    values: Sequence[float],
    level: str,
    planner: str,
    time_limit: float,
    seed: int,
    propagations: int | None = None,
) -> dict:
    """Is the design with these 12 values feasible at ``level``? One plain-data row.

    The design is built from ``values`` (order of ``PARAMETER_NAMES``) and planned with
    ``planner`` from the heavy-leading entry, then the heavy-trailing one, each within
    ``time_limit`` seconds of OMPL wall-clock time and, when ``propagations`` is given, within
    that many propagations (``time_limit`` is then only a cap), seeded by ``seed``. It is
    feasible when both are solved; if the first is not, the second is not run (``ran`` is
    False for it and its numbers are None), since the verdict is already known. A design that
    cannot be built (:class:`DegenerateDesign`) is infeasible at every level; its ``reason``
    says why.

    Returns a dict: ``values`` (list of 12 floats), ``level``, ``planner``, ``time_limit_s``,
    ``propagations`` (the budget, None for wall-clock only), ``seed``, ``built``, ``reason``
    (None when built), ``orientations`` (per entry: ``ran``, ``solved``, ``time_s`` = planning
    time, ``tree_size`` = states in the tree, ``propagations`` = made, None without a
    propagation budget), ``feasible`` and ``wall_time_s`` (everything, including building the
    scene and the level).

    Raises ValueError for an unknown level or planner (before building anything, so a
    degenerate design cannot hide a typo) and DesignError for unphysical values.
    """
    from planners.plan import plan

    _check_level(level)
    _check_planner(planner)
    t0 = time.perf_counter()
    design = DesignParameters.from_vector(list(values))
    row: dict = {
        "values": [float(v) for v in design.to_vector()],
        "level": level,
        "planner": planner,
        "time_limit_s": float(time_limit),
        "propagations": None if propagations is None else int(propagations),
        "seed": int(seed),
        "built": True,
        "reason": None,
        "orientations": {
            o: {
                "ran": False,
                "solved": None,
                "time_s": None,
                "tree_size": None,
                "propagations": None,
            }
            for o in ORIENTATIONS
        },
        "feasible": False,
    }
    try:
        scene = build_feeder(design, name="halton design")
    except DegenerateDesign as exc:
        row["built"] = False
        row["reason"] = exc.reason
    else:
        feasible = True
        for orientation in ORIENTATIONS:
            result = plan(
                scene, level, planner, orientation, time_limit, seed, propagations=propagations
            )
            row["orientations"][orientation] = {
                "ran": True,
                "solved": bool(result.solved),
                "time_s": float(result.time),
                "tree_size": int(result.tree_size),
                "propagations": result.propagations,
            }
            if not result.solved:
                feasible = False
                break  # infeasible already: the other entry cannot change the verdict
        row["feasible"] = feasible
    row["wall_time_s"] = time.perf_counter() - t0
    return row


@dataclass(frozen=True)
class FeasibilityJob:
    """One design x level, as a worker receives it: plain data that pickles."""

    index: int  # the design's position in the Halton sequence
    slot: int  # the level's position in ``levels`` (a level may appear twice)
    values: tuple[float, ...]  # the 12 parameters, order of PARAMETER_NAMES
    level: str
    planner: str
    time_limit: float  # s per orientation (a cap when ``propagations`` is set)
    seed: int
    propagations: int | None = None  # per orientation; None: the budget is wall-clock


def _job(job: FeasibilityJob) -> dict:
    """One design x level, as run in a worker: the verdict tagged with where it belongs."""
    row = design_verdict(
        list(job.values), job.level, job.planner, job.time_limit, job.seed, job.propagations
    )
    return {"index": job.index, "slot": job.slot, **row}


def compare_levels(
    n: int,
    levels: Sequence[str],
    planner: str = "rrt",
    time_limit: float = 1.0,
    seed: int = 1,
    workers: int = 1,
    progress: Callable[[dict], object] | None = None,
    propagations: int | None = None,
) -> list[dict]:
    """Verdicts of the first ``n`` Halton designs (``halton_points(n, seed)``) at each level.

    Every design x level is one job (:func:`design_verdict` with ``planner``, ``time_limit``
    seconds and, when given, ``propagations`` per orientation, and OMPL seed ``seed``). With
    ``workers`` > 1 the jobs run in the shared local pool of that many processes
    (:func:`experiments.executors.local.map_jobs`); with 1 they run here, one after the other.

    Returns one row per job, ordered by design index, then by position in ``levels`` (rows carry
    ``index`` and ``slot`` = that position; a level may appear twice, e.g. to measure how
    often a level disagrees with itself). ``progress(row)`` is called in this process as each
    job finishes, in completion order: the place to show progress and to save rows as they
    come, so that a failure later does not lose them. If a job fails, no job starts after it
    and the error is raised once the running ones end.

    Reproducibility: the designs depend on ``seed`` only and each plan is seeded with ``seed``,
    so with a budget in ``propagations`` the same arguments give the same verdicts on any
    machine, under any load and whatever ``workers`` (as long as ``time_limit``, then a cap,
    is not reached first). With a wall-clock budget only, a design solved near the end of its
    budget may flip when the machine is slower or busier (more workers than cores, other
    load), so borderline verdicts are reproducible only on an equally loaded machine.
    """
    if n < 1:
        raise ValueError(f"number of designs n = {n} must be >= 1")
    if not levels:
        raise ValueError("need at least one level")
    if workers < 1:
        raise ValueError(f"workers = {workers} must be >= 1")
    if not (time_limit > 0.0 and math.isfinite(time_limit)):
        raise ValueError(f"time_limit = {time_limit} s must be a positive number")
    if propagations is not None and propagations < 1:
        raise ValueError(f"propagations = {propagations} must be >= 1")
    for level in levels:
        _check_level(level)
    _check_planner(planner)
    points = halton_points(n, seed)
    jobs = [
        FeasibilityJob(
            i,
            slot,
            tuple(float(v) for v in points[i]),
            level,
            planner,
            float(time_limit),
            int(seed),
            None if propagations is None else int(propagations),
        )
        for i in range(n)
        for slot, level in enumerate(levels)
    ]
    return map_jobs(
        _job,
        jobs,
        workers,
        on_result=None if progress is None else lambda _index, row: progress(row),
    )


def _fraction(successes: int, trials: int) -> dict:
    low, high = wilson_interval(successes, trials)
    return {
        "feasible": successes,
        "designs": trials,
        "fraction": successes / trials if trials else None,
        "ci95": [low, high],
    }


def paired_rows(rows: Iterable[dict], a: str, b: str) -> tuple[list[tuple[dict, dict]], int]:
    """Per design index, (row at a, row at b); b's row is never a's row (a == b: two runs)."""
    by_index: dict[int, list[dict]] = {}
    for position, row in enumerate(rows):
        by_index.setdefault(row.get("index", position), []).append(row)
    pairs, unpaired = [], 0
    for index in sorted(by_index):
        group = sorted(by_index[index], key=lambda r: r.get("slot", 0))
        row_a = next((r for r in group if r["level"] == a), None)
        row_b = next((r for r in group if r["level"] == b and r is not row_a), None)
        if row_a is None or row_b is None:
            unpaired += 1
        else:
            pairs.append((row_a, row_b))
    return pairs, unpaired


def classify(feasible_a: bool, feasible_b: bool) -> str:
    """The cell of the 2x2 table: 'both', 'a_only', 'b_only' or 'neither'."""
    if feasible_a:
        return "both" if feasible_b else "a_only"
    return "b_only" if feasible_b else "neither"


def agreement(rows: Iterable[dict], a: str, b: str) -> dict:
    """How the verdicts at level ``a`` and level ``b`` agree, design by design.

    ``rows`` are :func:`compare_levels` rows (each with ``index``, ``level``, ``feasible``,
    ``values``; ``slot`` orders two runs of one level). A design counts when it has a row at
    both levels; with ``a == b`` its first and second run are compared (self-agreement: the
    noise of wall-clock budgets). Designs without both are counted in ``unpaired``.

    Returns ``counts`` of the 2x2 table (``both``, ``a_only``, ``b_only``, ``neither``),
    ``fraction_a`` and ``fraction_b`` (feasible count, designs, fraction and its Wilson 95%
    interval, see :func:`wilson_interval`), ``unbuilt`` (degenerate designs, infeasible at
    both), ``subset_holds`` (no design feasible at ``a`` but not ``b``) and ``exceptions``:
    those designs, each with its ``index``, ``values`` and ``design`` (values by name).
    """
    pairs, unpaired = paired_rows(rows, a, b)
    counts = dict.fromkeys(AGREEMENT_CLASSES, 0)
    exceptions = []
    for row_a, row_b in pairs:
        cell = classify(bool(row_a["feasible"]), bool(row_b["feasible"]))
        counts[cell] += 1
        if cell == "a_only":
            values = [float(v) for v in row_a["values"]]
            exceptions.append(
                {
                    "index": row_a.get("index"),
                    "values": values,
                    "design": dict(zip(PARAMETER_NAMES, values, strict=True)),
                }
            )
    n = len(pairs)
    return {
        "a": a,
        "b": b,
        "designs": n,
        "unpaired": unpaired,
        "unbuilt": sum(not row_a["built"] for row_a, _ in pairs),
        "counts": counts,
        "fraction_a": _fraction(counts["both"] + counts["a_only"], n),
        "fraction_b": _fraction(counts["both"] + counts["b_only"], n),
        "subset_holds": counts["a_only"] == 0,
        "exceptions": exceptions,
    }


def csv_header() -> list[str]:
    """Columns of :func:`csv_record`: the row's scalars, the design values, per-entry numbers."""
    entry = ("ran", "solved", "time_s", "tree_size", "propagations")
    per_entry = [f"{o}_{k}" for o in ORIENTATIONS for k in entry]
    scalars = ["index", "slot", "level", "planner", "time_limit_s", "propagations", "seed"]
    scalars += ["built", "reason"]
    return [*scalars, "feasible", "wall_time_s", *PARAMETER_NAMES, *per_entry]


def csv_record(row: dict) -> dict:
    """A row flattened for CSV (columns of :func:`csv_header`; None becomes empty)."""
    record = {k: row.get(k) for k in csv_header() if k in row}
    record.update(zip(PARAMETER_NAMES, row["values"], strict=True))
    for o in ORIENTATIONS:
        for k, v in row["orientations"][o].items():
            record[f"{o}_{k}"] = v
    return {k: ("" if v is None else v) for k, v in record.items()}
