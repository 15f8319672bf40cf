"""The whole comparison: the suite's problems, each planned by every planner on the local
pool (:func:`experiments.executors.local.map_jobs`: plain-data jobs, each worker builds its
own scene and OMPL objects), then the report's data, its files and Planner Arena's
database."""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from experiments.planner_comparison.suite import Suite, design_name
from experiments.planner_comparison.unsolvable import PROVEN

LEVEL_ORDER = {"dynamic": 0, "kinematic": 1, "geometric": 2}  # the costliest first


def problems_of(suite: Suite) -> tuple[list[dict[str, Any]], list[dict[str, str]]]:
    """Every (design, level, entry) of the suite with its necessary conditions' status, and
    the designs that cannot be built (``{"design", "reason"}``). Scenes are built here only
    to read their entries and test them; the workers build their own."""
    from experiments.planner_comparison.designs import scene_for
    from experiments.planner_comparison.unsolvable import necessary_status
    from feeders.fields import FieldError

    problems: list[dict[str, Any]] = []
    broken: list[dict[str, str]] = []
    for design in suite.designs:
        name = design_name(design)
        try:
            scene = scene_for(design, suite.base)
        except FieldError:
            raise
        except ValueError as exc:  # a Halton design that cannot be built
            broken.append({"design": name, "reason": str(exc)})
            continue
        status = necessary_status(scene, list(scene.starts))
        for level in suite.levels:
            for entry, (word, reason) in status["entries"].items():
                problems.append(
                    {
                        "design": name,
                        "spec": design,
                        "level": level,
                        "entry": entry,
                        "status": word,
                        "reason": reason,
                    }
                )
    return problems, broken


def jobs_of(suite: Suite, problems: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The plain-data job of every problem to plan (known unsolvable ones only with
    ``plan_unsolvable``), the costliest level first."""
    jobs = []
    for p in problems:
        if p["status"] == PROVEN and not suite.plan_unsolvable:
            continue
        budget = suite.budgets[p["level"]]
        jobs.append(
            {
                "design": p["spec"],
                "design_name": p["design"],
                "base": suite.base,
                "level": p["level"],
                "entry": p["entry"],
                "planners": list(suite.planners),
                "runs": suite.runs,
                "budget": budget,
                "seed": suite.seed,
                "progress_every": max(1, budget // suite.progress_samples),
                "experiment": f"{suite.name}/{p['design']}/{p['level']}/{p['entry']}",
            }
        )
    return sorted(jobs, key=lambda j: LEVEL_ORDER.get(j["level"], 3))


def compare(suite: Suite, out: Path | None, workers: int, quiet: bool = False) -> dict[str, Any]:
    """Run the comparison; with ``out``, write the report, the OMPL logs and Planner Arena's
    database there. Returns the report's data (:func:`.summary.summarise`, with ``cost``,
    ``unavailable``, ``degenerate`` and ``files``)."""
    from experiments.executors.local import map_jobs
    from experiments.planner_comparison.summary import summarise
    from experiments.planner_comparison.work import plan_problem
    from experiments.progress import bar
    from planners.registry import CONFIGURED, UNAVAILABLE

    t0 = time.perf_counter()
    problems, broken = problems_of(suite)
    jobs = jobs_of(suite, problems)
    results: dict[str, dict[str, Any]] = {}
    progress = None if quiet else bar(len(jobs), "planners: problems", "problem")

    def done(index: int, result: dict[str, Any]) -> None:
        results[jobs[index]["experiment"]] = result
        if progress is not None:
            progress.update(1)

    try:
        map_jobs(plan_problem, jobs, workers=workers, on_result=done)
    finally:
        if progress is not None:
            progress.close()
    planning_wall = time.perf_counter() - t0
    for p in problems:
        key = f"{suite.name}/{p['design']}/{p['level']}/{p['entry']}"
        p["runs"] = results[key]["runs"] if key in results else None
    planners = [
        {"name": n, "label": CONFIGURED[n].label, "about": CONFIGURED[n].about}
        for n in suite.planners
    ]
    report = summarise(
        suite.to_dict(),
        planners,
        [{k: v for k, v in p.items() if k != "spec"} for p in problems],
    )
    report["unavailable"] = dict(UNAVAILABLE)
    report["degenerate"] = broken
    report["cost"] = {
        "problems_planned": len(jobs),
        "runs": sum(len(r["runs"]) for r in results.values()),
        "propagations": sum(x["propagations"] for r in results.values() for x in r["runs"]),
        "worker_wall_s": sum(r["wall_s"] for r in results.values()),
        "planning_wall_s": planning_wall,
        "workers": workers,
    }
    files: list[str] = []
    if out is not None:
        from experiments.planner_comparison.report import write_report

        logs = _write_logs(results, out / "ompl" / "logs")
        database = out / "ompl" / "benchmark.db"
        arena_database(logs, database)
        files = [str(f) for f in write_report(report, out)] + [str(database)]
    report["files"] = files
    report["cost"]["wall_s"] = time.perf_counter() - t0
    if out is not None:
        from experiments.planner_comparison.report import write_json

        write_json(report, out / "report.json")
    return report


def _write_logs(results: dict[str, dict[str, Any]], directory: Path) -> list[Path]:
    directory.mkdir(parents=True, exist_ok=True)
    paths = []
    for experiment, result in sorted(results.items()):
        path = directory / (experiment.replace("/", "__") + ".log")
        path.write_text(result["log"])
        paths.append(path)
    return paths


def arena_database(logs: list[Path], database: Path) -> None:
    """OMPL's own reader (``ompl_benchmark_statistics``, installed with OMPL) turns the
    logs into the SQLite database Planner Arena opens."""
    script = Path(sys.executable).with_name("ompl_benchmark_statistics")
    command = str(script) if script.exists() else shutil.which("ompl_benchmark_statistics")
    if command is None:
        raise RuntimeError("ompl_benchmark_statistics (installed with ompl) is not on the PATH")
    database.unlink(missing_ok=True)
    if not logs:
        return
    subprocess.run(
        [command, *map(str, logs), "-d", str(database)],
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
