"""One design's passive verdict in a report: per entry its successes, probability with the
Wilson 95% interval and mean exit time, P(both), the transition matrix (entry orientation ->
where the part ended) with the selector efficiency, and the strip of its nominal drops (the
paper's Figs. 10-11).

Both the sweep's report (its best designs) and the optimiser's (the optimum and table3) show
verdicts this way, from the verdict's plain-data form (see :mod:`experiments.drop.verdict`).
The entries are the verdict's own (a device family's too), and what counts as out right is the
verdict's ``success_classes`` (the goal's orientation classes: "heavy end down" for the
feeder, and for a verdict stored without them).
"""

from __future__ import annotations

import html
import zlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from experiments.drop.outcomes import HEAVY_DOWN, MISSED_GOAL
from experiments.report_kit.cells import DASH, cell, interval
from experiments.report_kit.page import figure_html, html_table
from feeders.feeder import ORIENTATIONS
from feeders.scene import HEAVY_END_UP, OTHER_ORIENTATION

STRIP_PREFIX = "strip_design"
# where a drop ended -> its colour in every report (heavy end down green, heavy end up red)
OUTCOME_COLOURS = {
    HEAVY_DOWN: "#2ca02c",
    HEAVY_END_UP: "#d62728",
    MISSED_GOAL: "#98df8a",
    OTHER_ORIENTATION: "#ff9896",
    "jammed in the exit chute": "#ff7f0e",
    "wedged across the funnel": "#e6a532",
    "caught on the pin": "#9467bd",
    "wedged at the lip": "#8c564b",
    "stuck in the input chute": "#e377c2",
    "stopped in the cavity": "#7f7f7f",
    "still moving at t_max": "#17becf",
    "left the bounds": "#000000",
}
OTHER_COLOUR = "#c7c7c7"
SUCCESS_COLOUR = OUTCOME_COLOURS[HEAVY_DOWN]
WRONG_ORIENTATION_COLOURS = ("#d62728", "#8c2d04", "#e7298a", "#a50f15", "#fb6a4a", "#6a3d9a")
"""A class the goal does not accept that no fixed colour names (a family's orientation
class): one of these, by its name, so a class keeps its colour in every report."""


def outcome_colour(outcome: str, success_classes: Sequence[str] = (HEAVY_DOWN,)) -> str:
    """The colour of ``outcome`` in a verdict whose goal accepts ``success_classes``: green for
    those, the fixed colour of a known failure, a red of :data:`WRONG_ORIENTATION_COLOURS` for
    any other class (heavy end down too, when the goal does not accept it)."""
    if outcome in success_classes:
        return SUCCESS_COLOUR
    if outcome in OUTCOME_COLOURS and outcome != HEAVY_DOWN:
        return OUTCOME_COLOURS[outcome]
    index = zlib.crc32(outcome.encode()) % len(WRONG_ORIENTATION_COLOURS)
    return WRONG_ORIENTATION_COLOURS[index]


def success_classes(verdict: dict[str, Any]) -> tuple[str, ...]:
    """The classes a verdict's goal accepts (its plain-data form); "heavy end down" for one
    stored without them."""
    return tuple(verdict.get("success_classes") or (HEAVY_DOWN,))


def entries_of(verdict: dict[str, Any]) -> tuple[str, ...]:
    """A verdict's entry orientations (its plain-data form), in its order; the feeder's two
    for one stored without them."""
    return tuple(verdict.get("orientations") or ORIENTATIONS)


def strip_name(design_id: Any) -> str:
    """The figure name of a design's strip: a sweep's design id, or a label (``optimum``)."""
    if isinstance(design_id, str):
        return f"{STRIP_PREFIX}_{design_id}"
    return f"{STRIP_PREFIX}{int(design_id):06d}"


def outcome_order(
    matrix: dict[str, dict[str, int]], success: Sequence[str] = (HEAVY_DOWN,)
) -> list[str]:
    """The outcomes with at least one drop in the transition matrix (orientation -> outcome
    -> count): the ``success`` classes first, then in ``OUTCOME_COLOURS``' order, a class it
    does not list (a family's orientation class) after heavy end up in the matrix's order."""
    seen = list(dict.fromkeys(c for m in matrix.values() for c in (m or {})))
    known = list(OUTCOME_COLOURS)
    up = known.index(HEAVY_END_UP)

    def rank(c: str) -> tuple[int, float, int]:
        if c in success:
            return (0, list(success).index(c), 0)
        return (1, known.index(c) if c in known else up + 0.5, seen.index(c))

    outcomes = [c for c in seen if any((m or {}).get(c, 0) > 0 for m in matrix.values())]
    return sorted(outcomes, key=rank)


def design_verdict_html(entry: dict[str, Any], figures: dict[str, Path]) -> list[str]:
    """The page's parts for one design: ``entry`` holds ``design_id`` (an id or a label) and
    ``verdict``; its strip is shown when ``figures`` has it, else a sentence says why not."""
    v = entry["verdict"]
    d = entry["design_id"]
    entries, success = entries_of(v), success_classes(v)
    rows = []
    for orientation in entries:
        per = (v.get("orientations") or {}).get(orientation) or {}
        rows.append(
            [
                orientation.replace("_", " "),
                f"{cell(per.get('successes'))} / {cell(v.get('drops'))}",
                cell(per.get("p"), ".3f"),
                interval(per.get("interval")),
                cell(per.get("mean_exit_time_s"), ".3f"),
            ]
        )
    both = v.get("both") or {}
    rows.append(
        [
            "both",
            f"{cell(both.get('successes'))} / {cell(v.get('drops'))}",
            cell(both.get("p"), ".3f"),
            interval(both.get("interval")),
            DASH,
        ]
    )
    parts = [
        f"<h4>Design {html.escape(cell(d))}: {html.escape(str(v.get('decision', DASH)))}</h4>",
        html_table(["entry", "successes", "P", "95% CI", "mean exit time (s)"], rows, (0,)),
    ]
    matrix = v.get("transitions") or {}
    outcomes = outcome_order({o: matrix.get(o) or {} for o in entries}, success)
    if outcomes:
        drops_in = sum(sum((matrix.get(o) or {}).values()) for o in entries)
        out_right = sum((matrix.get(o) or {}).get(c, 0) for o in entries for c in success)
        parts.append(
            html_table(
                ["entry", *outcomes],
                [
                    [
                        o.replace("_", " "),
                        *(cell((matrix.get(o) or {}).get(c, 0)) for c in outcomes),
                    ]
                    for o in entries
                ],
                (0,),
            )
        )
        efficiency = out_right / drops_in if drops_in else None
        parts.append(
            f'<p class="note">Selector efficiency (parts out {html.escape(" or ".join(success))}'
            " / parts in): "
            f"{html.escape(cell(efficiency, '.3f'))}.</p>"
        )
    name = strip_name(d)
    if name in figures:
        parts.append(figure_html(figures, name, f"nominal drops of design {d} from both entries"))
    else:
        parts.append("<p>No strip: the design cannot be built with this sweep's feeder.</p>")
    return parts
