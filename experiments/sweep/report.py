"""The report of a sweep: one self-contained HTML page with its figures beside it.

``write_report(out_dir, summary, db_path)`` writes ``out_dir/report.html`` and PNG figures in
``out_dir/figures/``, referenced by relative paths: the directory holds everything (no network,
no scripts), so it can be copied, archived or opened from a cluster's file system as is.

The numbers (counts, medians, precision and recall with their intervals, the speed-up) come
from ``summary``, computed elsewhere from the same database: this module only shows them, so
the page and any JSON summary never disagree. The figures that need more than a summary (the
feasible set in design space, the distributions of planner run times and tree sizes) read the
results database (see :mod:`experiments.sweep.results_db`) read-only, which is safe while a sweep is
still writing to it. A sweep still running, or one without a holdout, still gets a report: a
missing number is shown as a dash and a figure without data says so.
"""

from __future__ import annotations

import os
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from experiments.report_kit.comparison_section import OVERLAY_PREFIX, comparison_figures
from experiments.report_kit.margins_section import MARGINS, margins_figures
from experiments.report_kit.verdict_section import STRIP_PREFIX
from experiments.sweep.family import database_family
from experiments.sweep.report_figures import (
    best_figure,
    feasible_set_figure,
    planners_figure,
    pruning_figure,
    survivors_figure,
)
from experiments.sweep.report_html import html_page
from experiments.sweep.report_recommendation import (
    Progress,
    margins_of_contenders,
    recommendation_of,
)
from experiments.sweep.report_verdicts import TRANSITIONS, comparison_of, verdict_figures
from experiments.sweep.results_db import connect, parameter_names

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

FIGURES = ("survivors", "feasible_set", "planners", "pruning", "best_designs")
# what a report finds beyond the sweep's summary, for the summary a job prints
FINDINGS = ("comparison", "recommendation", "margins", "baseline_margins")


def write_report(
    out_dir: str | Path,
    summary: dict,
    db_path: str | Path,
    baseline: tuple[str, list[float]] | None = None,
    workers: int | None = None,
    margins: bool = True,
    progress: Progress | None = None,
) -> Path:
    """Write out_dir/report.html and out_dir/figures/*.png; returns the HTML path
    (:func:`report_with_findings`, without what it found)."""
    page, _ = report_with_findings(out_dir, summary, db_path, baseline, workers, margins, progress)
    return page


def report_with_findings(
    out_dir: str | Path,
    summary: dict,
    db_path: str | Path,
    baseline: tuple[str, list[float]] | None = None,
    workers: int | None = None,
    margins: bool = True,
    progress: Progress | None = None,
) -> tuple[Path, dict[str, Any]]:
    """Write out_dir/report.html and out_dir/figures/*.png; returns the HTML path and what
    the report found beyond ``summary`` (:data:`FINDINGS`: ``comparison``,
    ``recommendation``, ``margins``), for the summary a job prints.

    ``summary`` holds the sweep's statistics (keys ``name``, ``results_key``, ``designs``,
    ``holdout``, ``ladder``, ``feeder``, ``levels``, ``planners``, ``pruning``, ``speedup``,
    ``best``, ``quarantined``, and with a passive rung ``truth``, ``passive``, ``pipelines``);
    the best designs with a verdict get the strips of their nominal drops
    (:mod:`experiments.sweep.report_verdicts`) and, the top ``COMPARED`` of them, the "Why
    this design" section: judged again beside ``baseline`` (``(label, values)``, default
    table3, or a device family's default design) on the same fresh draws, drawn over it
    (:func:`experiments.sweep.report_verdicts.comparison_of`, 40 trials of both entries per
    design and for the baseline). The page opens with the recommendation
    (:func:`experiments.sweep.report_recommendation.recommendation_of`: among the designs
    those draws confirm and the baseline, by reliability on the same draws, then by
    robustness, the smallest margin: a design or "keep the baseline"). The confirmed
    designs' and the baseline's tolerance margins
    (:func:`experiments.sweep.report_recommendation.margins_of_contenders`) are computed on
    ``workers`` processes (default the sweep's) unless ``margins`` is False or the sweep's
    config says ``report.margins: skip``, with ``progress`` told as each axis is done; the
    recommended design's are shown beside the other's (``baseline_margins``: the baseline's,
    or the best design's when the baseline is kept). The database at ``db_path`` gives
    the per-design verdicts and the per-run planner numbers the figures need. Figures of an
    earlier report that this one does not draw (no best designs yet) are removed, so the
    page and the directory agree. The HTML is written to a temporary file and renamed, so a
    browser refreshing the page while a sweep reports never sees half of it.
    """
    out_dir = Path(out_dir)
    figures_dir = out_dir / "figures"
    figures_dir.mkdir(parents=True, exist_ok=True)
    ladder = [str(level) for level in summary.get("ladder") or []]
    data = _read_db(db_path)
    family = _family(db_path)

    figures: dict[str, Path] = {}
    figures["survivors"] = survivors_figure(summary, figures_dir / "survivors.png")
    figures["feasible_set"] = feasible_set_figure(
        summary, ladder, data, figures_dir / "feasible_set.png"
    )
    figures["planners"] = planners_figure(summary, ladder, data, figures_dir / "planners.png")
    figures["pruning"] = pruning_figure(summary, ladder, figures_dir / "pruning.png")
    best = list(summary.get("best") or [])
    if best:
        figures["best_designs"] = best_figure(
            summary, best, figures_dir / "best_designs.png", family
        )
    figures.update(verdict_figures(summary, figures_dir, family))
    comparison: dict[str, Any] | None = None
    if summary.get("passive"):
        comparison = comparison_of(summary, Path(db_path), baseline=baseline, family=family)
        if "absent" not in comparison:
            drawn = {"family": family} if family is not None else _environment(summary)
            figures.update(comparison_figures(comparison, figures_dir, **drawn))
    contenders: dict[str, dict[str, Any]] | None = None
    if margins and comparison is not None and "absent" not in comparison:
        contenders = margins_of_contenders(summary, Path(db_path), comparison, workers, progress)
    recommendation = recommendation_of(summary, comparison, contenders)
    if contenders:
        recommendation["margins_cost"] = margins_cost(contenders)
    margins_data = baseline_margins = None
    if contenders and recommendation["confirmed"]:
        label = recommendation["label"]
        other = recommendation.get("contender") if recommendation.get("kept") else None
        other = other or str(comparison["baseline"]["label"])  # type: ignore[index]
        margins_data = contenders.get(label)
        baseline_margins = contenders.get(other) if other != label else None
        figures.update(margins_figures(margins_data, figures_dir, baseline_margins))
    for name in FIGURES:
        stale = figures_dir / f"{name}.png"
        if name not in figures and stale.exists():
            stale.unlink()
    for stale in [
        *figures_dir.glob(f"{STRIP_PREFIX}*.png"),
        *figures_dir.glob(f"{OVERLAY_PREFIX}*.png"),
        figures_dir / f"{TRANSITIONS}.png",
        figures_dir / f"{MARGINS}.png",
    ]:
        if stale.stem not in figures and stale.exists():
            stale.unlink()

    findings = {
        "comparison": comparison,
        "recommendation": recommendation,
        "margins": margins_data,
        "baseline_margins": baseline_margins,
    }
    page = out_dir / "report.html"
    partial = out_dir / "report.html.partial"
    shown = {**summary, **findings}
    partial.write_text(html_page(shown, ladder, figures, Path(db_path)), encoding="utf-8")
    os.replace(partial, page)
    return page, findings


def margins_cost(margins: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """What measuring ``margins`` (per label) cost in all: designs, trials (a perturbed made
    device dropped from every entry), drops and the wall time of the one pool (s)."""
    costs = [m.get("cost") or {} for m in margins.values()]
    return {
        "designs": len(margins),
        "trials": sum(int(c.get("trials") or 0) for c in costs),
        "drops": sum(int(c.get("drops") or 0) for c in costs),
        "wall_time_s": max((float(c.get("wall_time_s") or 0.0) for c in costs), default=0.0),
    }


def _environment(summary: dict) -> dict[str, Any]:
    """The sweep's part, friction and feeder options, for drawing its designs."""
    from feeders.scene_yaml import environment_from_dict

    return dict(environment_from_dict(summary.get("feeder") or {}, prefix="feeder."))


def _family(db_path: str | Path) -> DeviceFamily | None:
    """The device family the sweep at ``db_path`` designs (None: the 12-parameter feeder)."""
    found = database_family(db_path)
    return None if found is None else found[0]


def _read_db(db_path: str | Path) -> dict[str, Any]:
    """What the figures need from the database: design values, verdicts and planner runs.

    Returns ``ids`` (design ids, ascending), ``parameters`` (the design columns: the 12
    ``PARAMETER_NAMES``, or a family's), ``values`` (array (n, parameters), in their order),
    ``status`` ((design_id, level) -> status) and ``runs`` (rows with level, planner,
    time_s, tree_size). Read-only, so a running sweep is not disturbed.
    """
    with closing(connect(db_path, readonly=True)) as db:
        parameters = parameter_names(db)
        columns = ", ".join(f'"{name}"' for name in parameters)
        designs = db.execute(
            f"SELECT design_id, {columns} FROM designs ORDER BY design_id"
        ).fetchall()
        status = {
            (int(r["design_id"]), str(r["level"])): str(r["status"])
            for r in db.execute("SELECT design_id, level, status FROM evaluations")
        }
        runs = [
            dict(r)
            for r in db.execute(
                "SELECT level, planner, time_s, tree_size FROM runs "
                "ORDER BY level, planner, design_id, orientation, run"
            )
        ]
    values = np.array(
        [[float(r[name]) for name in parameters] for r in designs], dtype=float
    ).reshape(-1, len(parameters))
    return {
        "ids": [int(r["design_id"]) for r in designs],
        "parameters": list(parameters),
        "values": values,
        "status": status,
        "runs": runs,
    }
