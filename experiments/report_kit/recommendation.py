"""The first thing a report says: which design to build and why, in a few lines a designer
reads before anything else, each pointing to the section that holds its evidence.

The recommendation is the design a job chose (the sweep: the best confirmed on fresh draws,
:func:`experiments.report_kit.comparison_section.fresh_ranking`; the optimiser: its
validated optimum); this box only says it, from the comparison with the baseline on the same
fresh draws (:func:`experiments.drop.compare.compare_designs`) and the design's margins
(:meth:`experiments.margins.run.MarginsReport.to_dict`). When nothing was confirmed it says
so, and why, instead of naming a design.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from typing import Any

from experiments.report_kit.cells import cell, quantity
from experiments.report_kit.comparison_section import confirmation
from experiments.report_kit.margins_section import margins_sentence, robustness_sentence
from experiments.report_kit.verdict_section import entries_of

KEEP = "keep the baseline"  # a sweep recommendation's decision to keep its baseline


def _exit_times(entry: dict[str, Any]) -> str:
    """The mean exit time from each of the verdict's entries (a device family's its own)."""
    verdict = entry.get("verdict") or {}
    per = verdict.get("orientations") or {}
    return ", ".join(
        f"{o.replace('_', ' ')} {quantity((per.get(o) or {}).get('mean_exit_time_s'), 's', '.2f')}"
        for o in entries_of(verdict)
    )


def recommendation_html(
    label: str | None,
    comparison: dict[str, Any] | None,
    margins: dict[str, Any] | None,
    chosen: str,
    absent: str | None = None,
    notes: Sequence[tuple[str, str]] = (),
    decision: dict[str, Any] | None = None,
    baseline_margins: dict[str, Any] | None = None,
) -> str:
    """The box: ``label`` (the design to build, an entry of ``comparison["designs"]``, or
    the baseline's label when the job's ``decision`` (a sweep's recommendation: ``decision``,
    ``why``, ``contender``) keeps the baseline) with how it was ``chosen``, its confirmation
    on fresh draws, its numbers beside the other's on the same draws, its reliability and
    robustness against the other's (``baseline_margins``: the other's margins), its tightest
    margins and the job's own ``notes`` (title and plain text: what it optimised, say); with
    ``label`` None, ``absent`` says why no design is recommended."""
    e = html.escape
    if label is None or comparison is None:
        return (
            '<div class="recommendation none"><h2>No design to build yet</h2>'
            f"<p>{e(absent or 'no design was confirmed on fresh draws')}.</p></div>"
        )
    contender = (decision or {}).get("contender")
    kept = bool(decision and decision.get("decision") == KEEP)
    if kept:
        entry = comparison["baseline"]
        base = next(d for d in comparison.get("designs") or [] if str(d["label"]) == contender)
    else:
        entry = next(d for d in comparison.get("designs") or [] if str(d["label"]) == label)
        base = comparison["baseline"]
    name = str(base["label"])
    confirmed, sentence = confirmation(entry, int(comparison["drops"]), float(comparison["target"]))
    both = (entry.get("verdict") or {}).get("both") or {}
    base_both = (base.get("verdict") or {}).get("both") or {}
    drops = int(comparison["drops"])
    lines = [
        f"<b>How chosen:</b> {e(chosen)}.",
        f"<b>Works:</b> {e(sentence)}",
        f"<b>Against {e(name)} on the same {drops} draws:</b> P(both) "
        f"{cell(both.get('successes'))}/{drops} against {cell(base_both.get('successes'))}/"
        f"{drops}; mean exit time {e(_exit_times(entry))} against {e(_exit_times(base))} "
        '(<a href="#why">why this design</a>).',
    ]
    paired = None if kept else entry.get("paired")
    if decision and decision.get("why"):
        verb = "Kept because" if kept else "Built because"
        lines.append(f"<b>{verb}:</b> {e(str(decision['why']))}.")
    if kept:
        lines.append(
            f"<b>To do better than {e(label)}:</b> the robust optimiser searches for a design "
            f"with more margin than {e(label)} at the same reliability (<code>partfeeder "
            "optimize robust --from SWEEP_DIR</code>, docs/optimization.md)."
        )
    if paired:
        lines.append(
            f"<b>Paired draws:</b> {e(label)} passed where {e(name)} failed on "
            f"{paired['design_only']}, the reverse on {paired['baseline_only']}, of "
            f"{paired['draws']}."
        )
    lines += [f"<b>{e(title)}:</b> {e(text)}" for title, text in notes]
    if margins is not None:
        lines.append(
            f'<b>Tolerance:</b> {e(margins_sentence(margins))} (<a href="#margins">margins</a>).'
        )
        robust = robustness_sentence(margins, baseline_margins)
        lines.append(f"<b>Robustness:</b> {e(robust)}.")
    title = f"Build {e(label)}" if confirmed else f"{e(label)}, not confirmed"
    if kept and confirmed:
        title = f"Keep the baseline, {e(label)}"
    kind = "recommendation" if confirmed else "recommendation none"
    items = "".join(f"<li>{line}</li>" for line in lines)
    return f'<div class="{kind}"><h2>{title}</h2><ul>{items}</ul></div>'
