"""The HTML page of a sweep's report: the summary's numbers as tables, each section followed
by its figure. Every cell is escaped; a missing number is a dash. No scripts, no network: the
page and its ``figures/`` directory are the whole report.
"""

from __future__ import annotations

import html
import time
from pathlib import Path

from experiments.report_kit.cells import DASH, cell, interval, number, quantity
from experiments.report_kit.margins_section import margins_html
from experiments.report_kit.page import STYLE, figure_html, html_table
from experiments.report_kit.recommendation import recommendation_html
from experiments.sweep.report_figures import MAX_BEST_DRAWN
from experiments.sweep.report_recommendation import NOT_REJUDGED, design_label, fresh_status
from experiments.sweep.report_verdicts import verdict_html
from feeders.design import PARAMETER_NAMES


def _speedup_text(speedup: dict | None) -> str:
    if not speedup:
        return "Not measured (no holdout, or no holdout design evaluated at every level yet)."
    ladder_cost = number(speedup.get("ladder_cost_s"))
    dynamic_cost = number(speedup.get("dynamic_cost_s"))
    factor = number(speedup.get("speedup"))
    top = speedup.get("top_level") or "the top level"
    basis = str(speedup.get("basis", "the holdout")).removeprefix("the ")
    return (
        f"The ladder up to {top} cost {quantity(ladder_cost, 's')} of worker time; evaluating "
        f"every design at {top} alone would cost about {quantity(dynamic_cost, 's')} "
        f"(95% CI {interval(speedup.get('dynamic_cost_ci'), '.3g')}): "
        f"a speed-up of {cell(factor)}x (95% CI {interval(speedup.get('speedup_ci'), '.3g')}), "
        f"estimated on {cell(speedup.get('holdout_n'))} {basis} designs, "
        f"{_recall_text(speedup)}."
    )


def _recall_text(row: dict) -> str:
    """The recall a speed-up was bought at, with its basis (issue 36: never one without
    the other)."""
    if "recall" not in row:
        return "its recall not recorded"
    n = row.get("recall_n")
    basis = row.get("recall_basis", "the holdout")
    if n == 0:
        return f"its recall unmeasured (no design that works in {basis})"
    kept = (n or 0) - len(row.get("thrown_away") or [])
    return (
        f"at a recall of {cell(row.get('recall'), '.2f')} "
        f"(95% CI {interval(row.get('recall_ci'), '.2f')}; {kept} of {n} designs that work "
        f"kept, {basis})"
    )


def _pruning_table(rows: list[dict]) -> str:
    """Each level's precision on the designs it was measured on (``n``, ``basis``: the
    audit's below the verdict, else the holdout's; its confusion counts) and its recall on
    the designs that work it rests on (``recall_n``, which designs; a summary written before
    those existed: the holdout's)."""
    return html_table(
        [
            "level",
            "n",
            "on",
            "tp",
            "fp",
            "fn",
            "tn",
            "precision",
            "95% CI",
            "recall",
            "95% CI",
            "designs that work",
            "of",
        ],
        [
            [
                str(row.get("level", "")),
                cell(row.get("n")),
                str(row.get("basis", "the holdout")),
                *(cell(row.get(k)) for k in ("tp", "fp", "fn", "tn")),
                cell(row.get("precision"), ".3f"),
                interval(row.get("precision_ci")),
                cell(row.get("recall"), ".3f"),
                interval(row.get("recall_ci")),
                cell(row.get("recall_n", row.get("tp", 0) + row.get("fn", 0))),
                str(row.get("recall_basis", "the holdout")),
            ]
            for row in rows
        ],
        text_columns=(0, 2, 12),
    )


def _ids(designs: list) -> str:
    return ", ".join(str(d) for d in designs)


def thrown_away_parts(summary: dict) -> list[str]:
    """The designs that work that a rung or a pipeline would have thrown away (by id), and,
    for a ladder that prunes before the verdict, how many working designs it threw away: an
    estimate from the holdout, since those designs have no verdict."""
    e = html.escape
    truth = str(summary.get("truth") or "the top level")
    parts = [f"<h3>Designs that work ({e(truth)}) that pruning would have thrown away</h3>"]
    lines = []
    for row in summary.get("pruning") or []:
        lost = row.get("thrown_away")
        if lost is None:  # a summary written before the list existed
            continue
        what = _ids(lost) if lost else "none"
        lines.append(
            f"{row.get('level')}{' (prunes)' if row.get('prunes') else ''}: {what} "
            f"(of {cell(row.get('recall_n'))} designs that work, {row.get('recall_basis')})"
        )
    for pipe in summary.get("pipelines") or []:
        lost = pipe.get("thrown_away")
        if lost and len(pipe.get("rungs") or []) > 2:  # one rung's are listed above
            lines.append(f"pipeline {' → '.join(pipe['rungs'])}: {_ids(lost)}")
    if not lines:
        return []
    parts.append("<ul>" + "".join(f"<li>{e(line)}</li>" for line in lines) + "</ul>")
    parts.append(
        '<p class="note">A planning rung throws a design away when its planners do not show it '
        "feasible: not found within the budget (unknown) proves nothing, so a rung prunes on it "
        "only when its config says <code>prunes: true</code>.</p>"
    )
    lost = summary.get("thrown_away")
    if lost:
        parts.append(f"<p>{e(_thrown_away_text(lost))}</p>")
    return parts


def _thrown_away_text(lost: dict) -> str:
    working = lost.get("holdout_pruned_working") or []
    head = (
        f"The ladder stopped {cell(lost.get('pruned'))} designs outside the holdout before "
        "their passive verdict, so they have none."
    )
    if lost.get("estimate") is None:
        return head + " How many of them work is not estimated: no holdout design was stopped."
    return (
        f"{head} An estimated {cell(lost.get('estimate'), '.1f')} of them work (95% CI "
        f"{interval(lost.get('ci'), '.1f')}): an estimate from the holdout, where "
        f"{len(working)} of the {cell(lost.get('holdout_pruned'))} designs the ladder would "
        f"have stopped work{': ' + _ids(working) if working else ''}."
    )


def _recommendation_box(summary: dict) -> str:
    """The box the page opens with: the design to build, or why there is none."""
    recommendation = summary.get("recommendation")
    if not recommendation:
        return ""
    comparison = summary.get("comparison")
    return recommendation_html(
        recommendation.get("label"),
        None if not comparison or "absent" in comparison else comparison,
        summary.get("margins"),
        str(recommendation.get("chosen") or ""),
        absent=str(recommendation.get("sentence") or ""),
        decision=recommendation,
        baseline_margins=summary.get("baseline_margins"),
    )


def _margins_parts(summary: dict, figures: dict[str, Path]) -> list[str]:
    """The recommended design's margins, or why there are none (nothing without a passive
    rung: no design has a verdict)."""
    recommendation = summary.get("recommendation")
    if not summary.get("passive") or not recommendation:
        return []
    if summary.get("margins") is None:
        why = (
            "not measured in this report"
            if recommendation.get("confirmed")
            else "no design is recommended, so none has its margins measured"
        )
        return margins_html(None, figures, absent=why)
    return margins_html(summary["margins"], figures, baseline=summary.get("baseline_margins"))


def _designed(family: dict | None) -> str:
    """What the sweep designs: the paper's feeder, or a device family with its entries."""
    if not family:
        return "the paper's 12-parameter feeder"
    return (
        f"device family {family['name']} ({', '.join(family['parameters'])}; entries "
        f"{', '.join(family['entries'])})"
    )


def html_page(summary: dict, ladder: list[str], figures: dict[str, Path], db_path: Path) -> str:
    """The page: summary numbers as tables, each section followed by its figure."""
    e = html.escape
    name = str(summary.get("name", "sweep"))
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en">',
        "<head>",
        '<meta charset="utf-8">',
        f"<title>Sweep report: {e(name)}</title>",
        f"<style>{STYLE}</style>",
        "</head>",
        "<body>",
        f"<h1>Sweep report: {e(name)}</h1>",
        "<p>"
        f"Results key <code>{e(str(summary.get('results_key', '')))}</code>; "
        f"{e(cell(summary.get('designs')))} Halton designs, "
        f"{e(cell(summary.get('holdout')))} in the holdout; "
        f"{e(_designed(summary.get('family')))}; ladder: "
        f"{e(' → '.join(ladder) or DASH)}.<br>"
        f"Database <code>{e(db_path.name)}</code>; report written {e(time.ctime())}."
        "</p>",
        _recommendation_box(summary),
    ]

    parts.append("<h2>Levels</h2>")
    level_rows = [
        [
            str(row.get("level", "")),
            cell(row.get("rung")),
            cell(row.get("evaluated")),
            cell(row.get("feasible")),
            cell(row.get("infeasible")),
            cell(row.get("unknown")),
            cell(row.get("degenerate")),
            cell(row.get("quarantined")),
            cell(row.get("survivors")),
            cell(row.get("wall_time_s"), ".4g"),
            cell(row.get("median_wall_time_s"), ".3g"),
            cell(row.get("designs_per_s"), ".3g"),
        ]
        for row in summary.get("levels") or []
    ]
    parts.append(
        html_table(
            [
                "level",
                "rung",
                "evaluated",
                "feasible",
                "infeasible",
                "unknown",
                "degenerate",
                "quarantined",
                "survivors",
                "wall time (s)",
                "median wall time (s)",
                "designs/s",
            ],
            level_rows,
            text_columns=(0,),
        )
    )
    parts.append(
        '<p class="note">Unknown: not found within the planning budget, which proves nothing '
        "(a sampling planner). Survivors: designs that passed this level and every level below "
        "it. Wall time: the sum over the level's evaluations, in their workers; the workers "
        "load the compiled kernels before their first job, so no level is charged for it.</p>"
    )
    parts.append(figure_html(figures, "survivors", "survivors per level"))

    parts += verdict_html(summary, figures)
    parts += _margins_parts(summary, figures)

    parts.append("<h2>Speed-up of the ladder</h2>")
    parts.append(f"<p>{e(_speedup_text(summary.get('speedup')))}</p>")

    truth = str(summary.get("truth") or (ladder[-1] if ladder else "the top level"))
    parts.append(f"<h2>Pruning (vs {e(truth)})</h2>")
    pruning = list(summary.get("pruning") or [])
    if pruning:
        parts.append(
            f"<p>Each other level's own verdict against {e(truth)}'s. Precision needs the "
            "failing designs' results: on the audit for a rung below the verdict (its designs "
            "reach the verdict whatever), else on the holdout (n, on). Recall, what pruning "
            "risks, rests on the designs that work counted in its row: every design, when none "
            "could have been stopped on its way to the level (planning rungs that do not "
            "prune, a proof's or a test's stops), else the audit's or the holdout's.</p>"
        )
        parts.append(_pruning_table(pruning))
    else:
        parts.append("<p>No level beside the truth: the pruning is not measured.</p>")
    parts += thrown_away_parts(summary)
    cumulative = list(summary.get("ladder_pruning") or [])  # optional: the ladder so far
    if cumulative:
        parts.append(
            "<p>The ladder up to each level (not stopped there or below it, by each rung's "
            f"<code>prunes</code>) against {e(truth)}'s verdict, on the holdout:</p>"
        )
        parts.append(_pruning_table(cumulative))
    parts.append(figure_html(figures, "pruning", "precision and recall per level"))

    parts.append("<h2>Planners</h2>")
    planner_rows = [
        [
            str(row.get("level", "")),
            str(row.get("planner", "")),
            cell(row.get("runs")),
            cell(row.get("solved")),
            cell(row.get("solved_fraction"), ".3f"),
            cell(row.get("median_time_s"), ".3g"),
            cell(row.get("median_tree_size"), ".4g"),
        ]
        for row in summary.get("planners") or []
    ]
    if planner_rows:
        parts.append(
            html_table(
                [
                    "level",
                    "planner",
                    "runs",
                    "solved",
                    "solved fraction",
                    "median time (s)",
                    "median tree size",
                ],
                planner_rows,
                text_columns=(0, 1),
            )
        )
    else:
        parts.append("<p>No planner runs yet.</p>")
    parts.append(figure_html(figures, "planners", "planner comparison per level"))

    parts.append("<h2>Feasible set in design space</h2>")
    family = summary.get("family")
    through = (
        f"its {len(family['parameters'])} parameters, each axis the range of one parameter "
        f"in device family {e(str(family['name']))}"
        if family
        else "its 12 parameters, each axis Table 2's range of one parameter"
    )
    parts.append(
        f'<p class="note">Every design of the database as a line through {through}. Grey: '
        "fails the first rung; coloured, thick: passed that rung and every rung below it (the "
        "top one is the paper's Fig. 2 Z<sub>F</sub>).</p>"
    )
    parts.append(
        figure_html(figures, "feasible_set", "feasible set: the designs in parallel coordinates")
    )

    parts.append("<h2>Top designs by the sweep's own verdict</h2>")
    best = list(summary.get("best") or [])
    status = fresh_status(summary.get("comparison"))
    if best:
        parts.append(
            '<p class="note">Ranked on the draws they were selected on (the top of a scan can be '
            "a lucky draw). Fresh draws: what judging the top ones again on fresh draws "
            "beside the baseline said (Why this design); only a confirmed design is "
            "recommended.</p>"
        )
        parts.append(
            html_table(
                [
                    "design",
                    "P(both)",
                    "95% CI",
                    "exit time (s)",
                    "fresh draws",
                    *(summary.get("parameters") or PARAMETER_NAMES),
                ],
                [
                    [
                        cell(row.get("design_id")),
                        cell(((row.get("verdict") or {}).get("both") or {}).get("p"), ".3f"),
                        interval(((row.get("verdict") or {}).get("both") or {}).get("interval")),
                        cell(row.get("exit_time_s"), ".3f"),
                        status.get(design_label(row.get("design_id")), NOT_REJUDGED),
                        *(cell(v, ".4g") for v in (row.get("values") or [])),
                    ]
                    for row in best
                ],
                text_columns=(4,),
            )
        )
        if len(best) > MAX_BEST_DRAWN:
            parts.append(f'<p class="note">The first {MAX_BEST_DRAWN} are drawn.</p>')
    else:
        parts.append("<p>No design has an exit time yet.</p>")
    parts.append(figure_html(figures, "best_designs", "drawings of the top designs"))

    parts.append("<h2>Quarantined</h2>")
    quarantined = list(summary.get("quarantined") or [])
    if quarantined:
        parts.append(
            html_table(
                ["design", "level", "attempts", "reason"],
                [
                    [
                        cell(row.get("design_id")),
                        str(row.get("level", "")),
                        cell(row.get("attempts")),
                        str(row.get("reason", "")),
                    ]
                    for row in quarantined
                ],
                text_columns=(1, 3),
            )
        )
    else:
        parts.append("<p>None: no worker died on a design.</p>")
    parts += ["</body>", "</html>", ""]
    return "\n".join(p for p in parts if p)
