"""The main job: Halton designs climb the ladder of levels; only survivors go up (Sec. 4).

Every design is evaluated at the first rung; a design goes up a rung when the one below did
not prune it (:func:`climbs`): it is feasible there (both entry orientations solved, or the
passive verdict says it works), or its planners did not find a path within the budget
(``unknown``, which proves nothing) and the rung does not prune on that (``prunes: false``,
the default; issue 21). Only a proof stops a design by default: it cannot be built, the
verdict says it fails, or an exact test says it is infeasible. The
designs of the holdout, a seeded random sample, climb every rung whatever their verdicts:
their verdicts at the top level measure how well each lower level prunes (precision and
recall) and what evaluating every design at the top would have cost (the speed-up). The
designs of the audit, a second seeded sample, reach the passive verdict whatever the rungs
below it say (and climb no further unless they work): they measure, at the cost of verdicts
only, what a rung that stops designs before the verdict (the screen) threw away.

A design's next rung is submitted as soon as its result arrives, so the workers never wait
for a whole level to end. Results are stored as they come (see ``results_db``); a sweep
started again in the same directory resumes: what is stored is not run again.

Outputs in the sweep's directory: ``results.sqlite``, ``ompl/logs/*.log`` (OMPL's benchmark
logs), ``ompl/benchmark.db`` (made from them by OMPL's ``ompl_benchmark_statistics``; Planner
Arena reads it), ``summary.json`` and the report.
"""

from __future__ import annotations

import contextlib
import functools
import io
import sqlite3
import tempfile
from collections.abc import Callable
from collections.abc import Set as AbstractSet
from pathlib import Path
from typing import Any

import numpy as np

from experiments.executors.cluster import run_dask
from experiments.executors.local import LocalPool
from experiments.family_config import family_record
from experiments.names import PASSIVE
from experiments.sweep import results_db
from experiments.sweep.config import Rung, SweepConfig
from experiments.sweep.job import SweepJob, evaluate_design, sweep_job, warm_up
from feeders.design import DESIGN_SPACE, PARAMETER_NAMES
from feeders.halton import halton_points

RESULTS_FILE = "results.sqlite"


def holdout_ids(count: int, fraction: float, seed: int) -> set[int]:
    """The design ids of the holdout: round(fraction * count) of them, drawn without
    replacement by a generator seeded with ``seed`` (independent of the Halton seed)."""
    n = round(fraction * count)
    if n == 0:
        return set()
    return {int(i) for i in np.random.default_rng(seed).choice(count, size=n, replace=False)}


def audited(config: SweepConfig) -> set[int]:
    """The design ids of the audit (:attr:`SweepConfig.audit_fraction`), drawn as the
    holdout is, with the audit's seed."""
    return holdout_ids(config.count, config.audit_fraction, config.audit_seed)


def goes_on(
    config: SweepConfig,
    rung: int,
    status: str,
    design_id: int,
    holdout: AbstractSet[int],
    audit: AbstractSet[int] = frozenset(),
) -> bool:
    """Whether design ``design_id`` goes on from ``rung`` after ``status``: :func:`climbs`
    says so, or it is in the holdout (every rung), or in the audit below the passive rung
    (the verdict)."""
    if climbs(config.ladder[rung], status) or design_id in holdout:
        return True
    levels = [r.level for r in config.ladder]
    return design_id in audit and PASSIVE in levels and rung < levels.index(PASSIVE)


def climbs(rung: Rung, status: str) -> bool:
    """Whether a design outside the holdout goes on up after ``status`` at ``rung``: when it
    is feasible, or ``unknown`` at a rung that does not prune (:attr:`Rung.prunes`)."""
    status = results_db.status_of(rung.level, status)
    return status == "feasible" or (status == "unknown" and not rung.prunes)


def pending_jobs(
    config: SweepConfig,
    designs: dict[int, list[float]],
    holdout: set[int],
    done: dict[tuple[int, str], str],
    audit: AbstractSet[int] = frozenset(),
) -> list[SweepJob]:
    """The next job of every design, from what is stored: each design climbs from rung 0
    while :func:`goes_on` says so (and it is not quarantined); its first
    rung that is not stored is its job. Designs that are finished have none."""
    jobs = []
    for design_id, values in designs.items():
        for rung, r in enumerate(config.ladder):
            status = done.get((design_id, r.level))
            if status is None:
                jobs.append(sweep_job(config, design_id, values, rung))
                break
            if status == "quarantined" or not goes_on(
                config, rung, status, design_id, holdout, audit
            ):
                break
    return jobs


def run_sweep(
    config: SweepConfig,
    out_dir: str | Path,
    executor: str = "local",
    scheduler: str | None = None,
    progress: Callable[[str, dict[str, Any]], None] | None = None,
    evaluate: Callable[[SweepJob], dict[str, Any]] = evaluate_design,
) -> Path:
    """Run (or resume) the sweep of ``config`` in ``out_dir``; returns the results database.

    ``progress(event, info)`` is called in this process: ``("start", {"levels", "done",
    "designs", "finished", "waiting"})`` once, then ``("result", {"rung", "level", "status",
    "finished", "wall_time_s"})`` per evaluation and ``("quarantine", {"rung", "level",
    "finished"})`` per job given up. ``designs`` is the number of designs and ``finished`` (at
    the start) how many of them had stopped climbing before this run; an event's ``finished``
    says that its design has stopped climbing now (no rung left, or stopped by :func:`climbs`
    and not in the holdout, or quarantined), so every design finishes exactly once and
    ``designs`` is a total known from the start, though the number of evaluations is not (the
    ladder is adaptive). ``waiting`` is the rung of each unfinished design's next job and
    ``wall_time_s`` the evaluation's time in its worker: what the time estimate is made of
    (:class:`experiments.eta.LadderEta`).
    ``evaluate`` runs in the workers (a function of a module they can import; tests replace
    it to make workers crash). A sweep with nothing left to run starts no worker. A config
    with a device family draws its designs from the family's box
    (:meth:`feeders.device_family.DeviceFamily.space`) and ties the database to the family.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    path = out / RESULTS_FILE
    family = config.device_family()
    if family is None:
        record, space, parameters = None, DESIGN_SPACE, PARAMETER_NAMES
    else:
        record = family_record(family, config.family_yaml)
        space, parameters = family.space(), family.vector_names
    db = results_db.connect(path, parameters=parameters)
    try:
        results_db.claim(db, config.to_dict(), config.results_key(), record)
        points = halton_points(config.count, config.seed, space)
        holdout = holdout_ids(config.count, config.holdout_fraction, config.holdout_seed)
        designs = {i: [float(v) for v in points[i]] for i in range(config.count)}
        results_db.add_designs(db, ((i, i in holdout, v) for i, v in designs.items()))
        done = results_db.finished(db)
        audit = audited(config)
        jobs = pending_jobs(config, designs, holdout, done, audit)
        if progress is not None:
            progress(
                "start",
                {
                    "levels": [r.level for r in config.ladder],
                    "done": done,
                    "designs": len(designs),
                    "finished": len(designs) - len(jobs),
                    "waiting": [int(job["rung"]) for job in jobs],
                },
            )
        if jobs:
            samples = (holdout, audit)
            _climb(config, db, jobs, designs, samples, executor, scheduler, progress, evaluate)
    finally:
        db.close()
    return path


def _climb(
    config: SweepConfig,
    db: sqlite3.Connection,
    jobs: list[SweepJob],
    designs: dict[int, list[float]],
    samples: tuple[set[int], set[int]],
    executor: str,
    scheduler: str | None,
    progress: Callable[[str, dict[str, Any]], None] | None,
    evaluate: Callable[[SweepJob], dict[str, Any]],
) -> None:
    top = len(config.ladder) - 1
    holdout, audit = samples

    def on_done(job: SweepJob, result: dict[str, Any], attempts: int) -> list[SweepJob]:
        rung = int(job["rung"])
        results_db.record(db, result, rung, attempts)
        design_id = int(job["design_id"])
        following = []
        if goes_on(config, rung, result["status"], design_id, holdout, audit) and rung < top:
            following = [sweep_job(config, design_id, designs[design_id], rung + 1)]
        if progress is not None:
            progress(
                "result",
                {
                    "rung": rung,
                    "level": job["level"],
                    "status": result["status"],
                    "finished": not following,
                    "wall_time_s": result.get("wall_time_s"),
                },
            )
        return following

    def on_quarantine(job: SweepJob, attempts: int, reason: str) -> None:
        results_db.quarantine(db, int(job["design_id"]), str(job["level"]), attempts, reason)
        if progress is not None:
            progress(
                "quarantine", {"rung": int(job["rung"]), "level": job["level"], "finished": True}
            )

    if executor == "local":
        levels = tuple(r.level for r in config.ladder)
        warm = functools.partial(warm_up, levels)  # no evaluation's time counts the loading
        with LocalPool(config.workers, config.max_attempts, warm) as pool:
            pool.run(evaluate, jobs, on_done, on_quarantine)
    elif executor == "dask":
        if not scheduler:
            raise ValueError("the dask executor needs --scheduler ADDRESS (tcp://host:port)")
        run_dask(evaluate, jobs, on_done, on_quarantine, scheduler)
    else:
        raise ValueError(f"unknown executor '{executor}'; executors: local, dask")


def export_ompl(results: str | Path, out_dir: str | Path) -> Path:
    """Write every stored OMPL log to ``out_dir/logs`` and make ``out_dir/benchmark.db`` from
    them with OMPL's own ``ompl_benchmark_statistics`` reader (made anew: a resumed sweep's
    database has each experiment once). The design parameters, level, orientation and seed
    are columns of its ``experiments`` table."""
    out = Path(out_dir)
    logs = out / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    db = results_db.connect(results, readonly=True)
    paths = []
    try:
        rows = db.execute(
            "SELECT design_id, level, orientation, log FROM ompl_logs "
            "ORDER BY design_id, level, orientation"
        )
        for row in rows:
            if _unclosed_block(row["log"]):
                raise results_db.damaged(
                    results,
                    f"is damaged: the OMPL log of design {row['design_id']}, level "
                    f"{row['level']}, {row['orientation']} ends inside a <<<| |>>> block",
                )
            p = logs / f"design{row['design_id']:06d}-{row['level']}-{row['orientation']}.log"
            p.write_text(row["log"])
            paths.append(str(p))
    finally:
        db.close()
    target = out / "benchmark.db"
    target.unlink(missing_ok=True)
    try:
        _read_logs(target, paths)
    except Exception as exc:
        target.unlink(missing_ok=True)
        if isinstance(exc, sqlite3.OperationalError) and "disk is full" in str(exc):
            raise  # the disk, not a log: said as such (experiments.cli.errors.disk_full)
        raise _unreadable_log(results, paths) from None
    return target


def _unclosed_block(log: str) -> bool:
    """A ``<<<|`` line with no ``|>>>`` line after it: OMPL's reader (ompl 2.0) loops forever
    on such a log, looking for the end of the block past the end of the file."""
    open_block = False
    for line in log.splitlines():
        if line.startswith("<<<|"):
            open_block = True
        elif line.startswith("|>>>"):
            open_block = False
    return open_block


def _read_logs(target: Path, paths: list[str]) -> None:
    """OMPL's reader: ``paths`` into the database ``target``, with its views."""
    from ompl import _benchmark_statistics as obs

    with contextlib.redirect_stdout(io.StringIO()):  # it prints a line per file
        obs.readBenchmarkLog(str(target), paths, False)
        obs.computeViews(str(target), False)


def _unreadable_log(results: str | Path, paths: list[str]) -> Exception:
    """OMPL's reader failed on the logs together: the first that it cannot read alone, named
    as the database check names a damaged row (the check reads text, not OMPL's format)."""
    with tempfile.TemporaryDirectory() as tmp:
        for k, path in enumerate(paths):
            try:
                _read_logs(Path(tmp) / f"{k}.db", [path])
            except Exception as exc:
                design, level, orientation = Path(path).stem.split("-", 2)
                return results_db.damaged(
                    results,
                    f"is damaged: the OMPL log of design {int(design.removeprefix('design'))}, "
                    f"level {level}, {orientation} is not a log OMPL's reader can read "
                    f"({type(exc).__name__})",
                )
    return RuntimeError("OMPL's reader failed on the logs together, and on none alone")
