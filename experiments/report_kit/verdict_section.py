"""One design's passive verdict in a report: per entry its successes, probability with the
Wilson 95% interval and mean exit time, P(both), the transition matrix (entry orientation ->
where the part ended) with the selector efficiency, and the strip of its nominal drops (the
paper's Figs. 10-11).

Both the sweep's report (its best designs) and the optimiser's (the optimum and table3) show
verdicts this way, from the verdict's plain-data form (see :mod:`experiments.drop.verdict`).
"""

from __future__ import annotations

import html
from pathlib import Path
from typing import Any

from experiments.drop.outcomes import HEAVY_DOWN
from experiments.report_kit.cells import DASH, cell, interval
from experiments.report_kit.page import figure_html, html_table
from feeders.feeder import ORIENTATIONS

STRIP_PREFIX = "strip_design"
# where a drop ended -> its colour in every report (heavy end down green, heavy end up red)
OUTCOME_COLOURS = {
    HEAVY_DOWN: "#2ca02c",
    "heavy end up": "#d62728",
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


def strip_name(design_id: Any) -> str:
    """The figure name of a design's strip: a sweep's design id, or a label (``optimum``)."""
    if isinstance(design_id, str):
        return f"{STRIP_PREFIX}_{design_id}"
    return f"{STRIP_PREFIX}{int(design_id):06d}"


def outcome_order(matrix: dict[str, dict[str, int]]) -> list[str]:
    """The outcomes with at least one drop in the transition matrix (orientation -> outcome
    -> count), in ``OUTCOME_COLOURS``' order, unknown outcomes last."""
    outcomes = [
        c
        for c in OUTCOME_COLOURS.keys() | {c for m in matrix.values() for c in m}
        if any((matrix.get(o) or {}).get(c, 0) > 0 for o in ORIENTATIONS)
    ]
    outcomes.sort(key=lambda c: list(OUTCOME_COLOURS).index(c) if c in OUTCOME_COLOURS else 99)
    return outcomes


def design_verdict_html(entry: dict[str, Any], figures: dict[str, Path]) -> list[str]:
    """The page's parts for one design: ``entry`` holds ``design_id`` (an id or a label) and
    ``verdict``; its strip is shown when ``figures`` has it, else a sentence says why not."""
    v = entry["verdict"]
    d = entry["design_id"]
    rows = []
    for orientation in ORIENTATIONS:
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
    outcomes = outcome_order(matrix)
    if outcomes:
        drops_in = sum(sum((matrix.get(o) or {}).values()) for o in ORIENTATIONS)
        out_right = sum((matrix.get(o) or {}).get(HEAVY_DOWN, 0) for o in ORIENTATIONS)
        parts.append(
            html_table(
                ["entry", *outcomes],
                [
                    [
                        o.replace("_", " "),
                        *(cell((matrix.get(o) or {}).get(c, 0)) for c in outcomes),
                    ]
                    for o in ORIENTATIONS
                ],
                (0,),
            )
        )
        efficiency = out_right / drops_in if drops_in else None
        parts.append(
            f'<p class="note">Selector efficiency (parts out heavy end down / parts in): '
            f"{html.escape(cell(efficiency, '.3f'))}.</p>"
        )
    name = strip_name(d)
    if name in figures:
        parts.append(figure_html(figures, name, f"nominal drops of design {d} from both entries"))
    else:
        parts.append("<p>No strip: the design cannot be built with this sweep's feeder.</p>")
    return parts
