"""A report's "How much tolerance it has" section: the margins of one design
(:meth:`experiments.margins.run.MarginsReport.to_dict`) as the chart a designer reads at a
glance, a table of the room on each side of every nominal, and the tightest axes named.

Room is measured in fractions of the axis's box (Table 2's range for the 12 design
parameters, a stated range for friction and the part), so a 0.01 length unit on ``r``
(box 0.2 wide) and on ``d`` (box 2.5 wide) read as what they are: 5% and 0.4% of the range
a designer may choose from. An end of a margin that reached the box's edge is a lower bound
on the room ("at least"): the search stops at the box.
"""

from __future__ import annotations

import html
import math
from pathlib import Path
from typing import Any

from experiments.margins.robustness import SIDES, at_edge, room
from experiments.report_kit.cells import DASH, cell, quantity
from experiments.report_kit.page import figure_html, html_table

MARGINS = "margins"
TIGHTEST = 3  # axes named in the one-line summary


def margins_figures(
    margins: dict[str, Any] | None,
    figures_dir: Path,
    baseline: dict[str, Any] | None = None,
) -> dict[str, Path]:
    """The margins chart (:func:`experiments.margins.figure.margins_chart`) of a design that
    has margins, beside ``baseline``'s (another design's margins) when given, as
    ``{MARGINS: path}``; nothing for a design without them."""
    if not margins or not margins.get("margins"):
        return {}
    from experiments.margins.figure import margins_chart

    other = baseline if baseline and baseline.get("margins") else None
    return {MARGINS: margins_chart(margins, figures_dir / f"{MARGINS}.png", other)}


def robustness_sentence(margins: dict[str, Any], baseline: dict[str, Any] | None = None) -> str:
    """The design's robustness (its smallest room inside the box over its parameters and
    mu, :func:`experiments.margins.robustness.robustness`), beside ``baseline``'s."""
    from experiments.margins.robustness import robustness

    def said(m: dict[str, Any]) -> str:
        r = robustness(m)
        if not m.get("works"):
            return f"{m.get('design', 'the design')}: none (it {_short(m)} on these draws)"
        if r.unlimited:
            return f"{m.get('design')}: every side reaches the box's edge"
        where = f"{r.axis} {r.side}" if r.side else f"{r.axis} has no margin"
        low, high = r.bracket
        if m.get("stopped"):  # measured until it could not be the most robust
            return (
                f"{m.get('design')}: at most {100 * high:.1f}% of its box ({where}; its "
                f"other axes not measured: {m['stopped']})"
            )
        top = "" if math.isinf(high) else f", between {100 * low:.1f}% and {100 * high:.1f}%"
        return f"{m.get('design')}: {100 * r.value:.1f}% of its box ({where}{top})"

    text = "smallest margin over the parameters and mu, " + said(margins)
    return text if baseline is None else f"{text}; {said(baseline)}"


def tightest(margins: dict[str, Any], count: int = TIGHTEST) -> list[dict[str, Any]]:
    """The ``count`` axes with the least room on their tighter side found inside the box
    (a side that reached the box's edge is the box's limit, not the design's), tightest
    first; an axis without a margin comes before every axis with one. Each entry:
    ``parameter``, ``meaning``, ``below`` and ``above`` (fractions of the box, None without
    a margin) and ``edges`` (whether each side reached the box's edge)."""
    rows = []
    for row in margins.get("margins") or []:
        r = room(row)
        # a side that reached the box's edge is limited by the box, not by the design
        inside = (
            [] if r is None else [x for x, s in zip(r, SIDES, strict=True) if not at_edge(row, s)]
        )
        key = -1.0 if r is None else min(inside, default=math.inf)
        rows.append(
            (
                key,
                {
                    "parameter": row["parameter"],
                    "meaning": row.get("meaning", ""),
                    "below": None if r is None else r[0],
                    "above": None if r is None else r[1],
                    "edges": tuple(at_edge(row, s) for s in SIDES),
                },
            )
        )
    rows.sort(key=lambda item: item[0])
    return [entry for _, entry in rows[:count]]


def _percent(fraction: float | None, edge: bool) -> str:
    if fraction is None:
        return DASH
    return f"{'≥ ' if edge else ''}{100.0 * fraction:.1f}%"


def _short(margins: dict[str, Any]) -> str:
    """What the verdict of a design with no margins says of it: it does not work, or it is
    undecided (:func:`experiments.drop.sequential.short_of_working`)."""
    from experiments.drop.sequential import short_of_working

    return short_of_working((margins.get("verdict") or {}).get("decision"))


def margins_sentence(margins: dict[str, Any]) -> str:
    """One sentence: the tightest axes with their room either side (or that the design has
    no margins, and why)."""
    if not margins.get("works"):
        return (
            f"{margins.get('design', 'the design')} {_short(margins)} at nominal on the "
            "margins' draws, so it has no margins"
        )
    parts = []
    for t in tightest(margins):
        if t["below"] is None:
            parts.append(f"{t['parameter']} none (below the target at nominal)")
        else:
            low_edge, high_edge = t["edges"]
            parts.append(
                f"{t['parameter']} {_percent(t['below'], low_edge)} / "
                f"{_percent(t['above'], high_edge)}"
            )
    return (
        "the tightest, as room below / above the nominal in fractions of the axis's box: "
        + ", ".join(parts)
    )


def margins_html(
    margins: dict[str, Any] | None,
    figures: dict[str, Path],
    absent: str | None = None,
    baseline: dict[str, Any] | None = None,
) -> list[str]:
    """The section's parts: heading, what was measured and its cost, the tightest axes, the
    robustness (beside ``baseline``'s: another design's margins), the chart and the table of
    every axis (with ``baseline``'s room beside); ``absent`` (why there are no margins) when
    ``margins`` is None."""
    e = html.escape
    if margins is None:
        return [
            "<h2>How much tolerance it has: margins</h2>",
            f"<p>No margins: {e(absent or 'nothing to measure')}.</p>",
        ]
    name = str(margins.get("design", "the design"))
    other = str(baseline.get("design", "the baseline")) if baseline else None
    meaning = str(margins.get("meaning", ""))
    cost = margins.get("cost") or {}
    beside = f" beside {e(other)}'s" if other else ""
    parts = [
        f'<h2 id="margins">How much tolerance it has: the margins of {e(name)}{beside}</h2>',
        f"<p>{e(meaning[:1].upper() + meaning[1:])}. "
        f"Target {cell(margins.get('target'))}, {cell(margins.get('drops_per_value'))} "
        f"trials per value (seed {cell(margins.get('seed'))}). Cost: "
        f"{cell(cost.get('drops'))} drops, {quantity(cost.get('wall_time_s'), 's', '.1f')} on "
        f"{cell(cost.get('workers'))} worker(s).</p>",
    ]
    if not margins.get("works"):
        parts.append(f"<p>{e(margins_sentence(margins))}.</p>")
        return parts
    sentence = margins_sentence(margins)
    parts.append(f"<p><b>{e(sentence[0].upper() + sentence[1:])}.</b></p>")
    robust = robustness_sentence(margins, baseline)
    parts.append(f"<p><b>Robustness:</b> {e(robust[0].upper() + robust[1:])}.</p>")
    parts.append(figure_html(figures, MARGINS, f"tolerance margins of {name}{beside}"))
    theirs = {str(r["parameter"]): r for r in (baseline or {}).get("margins") or []}
    rows = []
    for row in margins.get("margins") or []:
        r = room(row)
        interval = row.get("interval")
        cells = [
            str(row["parameter"]),
            str(row.get("meaning", "")),
            cell(row.get("nominal"), ".4g"),
            DASH if interval is None else f"[{interval[0]:.4g}, {interval[1]:.4g}]",
            f"[{row['box'][0]:.4g}, {row['box'][1]:.4g}] ({row.get('box_source', '')})",
            _percent(None if r is None else r[0], at_edge(row, "low")),
            _percent(None if r is None else r[1], at_edge(row, "high")),
        ]
        if other is not None:
            b = theirs.get(str(row["parameter"]))
            rb = None if b is None else room(b)
            cells += [
                DASH if b is None else _percent(None if rb is None else rb[0], at_edge(b, "low")),
                DASH if b is None else _percent(None if rb is None else rb[1], at_edge(b, "high")),
            ]
        rows.append(cells)
    header = [
        "axis",
        "meaning",
        "nominal",
        "allowed interval",
        "box",
        "room below (of box)",
        "room above (of box)",
    ]
    if other is not None:
        header += [f"{other}: room below", f"{other}: room above"]
    parts.append(html_table(header, rows, (0, 1, 4)))
    parts.append(
        '<p class="note">"≥": the end reached the box\'s edge, so the room may be larger; '
        "the search stops at the box.</p>"
    )
    return parts
