"""The passive verdict in a sweep's report: what works, with what probability, where the part
ends, and what each order of rungs would cost (issue 13).

``verdict_figures`` draws, for the best designs that carry a verdict, the snapshot strips of
their nominal drops from both entries (the paper's Figs. 10-11) and one figure of their
transition matrices; ``verdict_html`` gives the page's sections from the summary's ``passive``,
``pipelines`` and ``best`` entries (see :mod:`experiments.sweep.summary`). A design that
cannot be built, or a summary without a passive rung, gets a sentence, never an error.
"""

from __future__ import annotations

import html
from collections.abc import Callable
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from experiments.drop.outcomes import HEAVY_DOWN
from experiments.pictures.scenes import save_figure
from experiments.sweep.report_figures import DASH, MAX_BEST_DRAWN, cell, number
from feeders.feeder import ORIENTATIONS

STRIP_PREFIX = "strip_design"
TRANSITIONS = "transitions"
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


def with_verdicts(summary: dict) -> list[dict]:
    """The best designs that carry a passive verdict, in the summary's order, at most
    ``MAX_BEST_DRAWN``."""
    return [b for b in summary.get("best") or [] if "verdict" in b][:MAX_BEST_DRAWN]


def strip_name(design_id: Any) -> str:
    """The figure name of a design's strip: a sweep's design id, or a label (``optimum``)."""
    if isinstance(design_id, str):
        return f"{STRIP_PREFIX}_{design_id}"
    return f"{STRIP_PREFIX}{int(design_id):06d}"


def verdict_figures(summary: dict, figures_dir: Path) -> dict[str, Path]:
    """The strips of the best designs' nominal drops and the transition-matrix figure;
    name -> PNG path (a design that cannot be built has no strip)."""
    best = with_verdicts(summary)
    out: dict[str, Path] = {}
    if not best:
        return out
    out[TRANSITIONS] = transitions_figure(summary, best, figures_dir / f"{TRANSITIONS}.png")
    for entry in best:
        path = _strip(summary, entry, figures_dir / f"{strip_name(entry['design_id'])}.png")
        if path is not None:
            out[strip_name(entry["design_id"])] = path
    return out


def _strip(summary: dict, entry: dict, path: Path) -> Path | None:
    """The design's nominal passive drops from both entries, drawn as Figs. 10-11."""
    from experiments.drop.passive import passive_drop
    from experiments.drop.pictures import drop_strip
    from feeders.design import DesignError, DesignParameters
    from feeders.feeder import DegenerateDesign, build_feeder
    from feeders.scene_yaml import environment_from_dict

    try:
        environment = environment_from_dict(summary.get("feeder") or {}, prefix="feeder.")
        design = DesignParameters.from_vector(list(entry.get("values") or []))
        scene = build_feeder(design, name=f"design {entry['design_id']}", **environment)
    except (DegenerateDesign, DesignError, ValueError):
        return None
    results = [passive_drop(scene, o) for o in ORIENTATIONS]
    figure = drop_strip(scene, results, path)
    plt.close("all")
    return figure


def transitions_figure(summary: dict, best: list[dict], path: Path) -> Path:
    """Per best design and entry orientation, a bar split by where its drops ended."""
    rows: list[tuple[str, dict[str, int]]] = []
    for entry in best:
        matrix = entry["verdict"].get("transitions") or {}
        for orientation in ORIENTATIONS:
            label = f"design {entry['design_id']}, {orientation.replace('_', ' ')}"
            rows.append((label, dict(matrix.get(orientation) or {})))
    fig, ax = plt.subplots(figsize=(9.0, 0.45 * len(rows) + 1.8))
    seen: set[str] = set()
    for y, (_, counts) in enumerate(rows):
        total = sum(counts.values()) or 1
        left = 0.0
        for outcome, n in counts.items():
            if n <= 0:
                continue
            width = n / total
            colour = OUTCOME_COLOURS.get(outcome, OTHER_COLOUR)
            ax.barh(
                y,
                width,
                left=left,
                color=colour,
                edgecolor="white",
                label=None if outcome in seen else outcome,
            )
            seen.add(outcome)
            left += width
    ax.set_yticks(range(len(rows)), [label for label, _ in rows], fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(0.0, 1.0)
    ax.set_xlabel("fraction of drops")
    ax.set_title(
        f"{summary.get('name', 'sweep')}: where the part ends (entry orientation -> outcome)",
        fontsize=10,
    )
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=3)
    return save_figure(fig, path)


def _interval(ci: Any) -> str:
    if not isinstance(ci, (list, tuple)) or len(ci) != 2:
        return DASH
    low, high = number(ci[0]), number(ci[1])
    if low is None or high is None:
        return DASH
    return f"[{low:.2f}, {high:.2f}]"


def verdict_html(
    summary: dict,
    figures: dict[str, Path],
    table: Callable[..., str],
    figure: Callable[[dict[str, Path], str, str], str],
) -> list[str]:
    """The page's sections on the passive verdict (empty without a passive rung); ``table``
    and ``figure`` are the page's own builders (they escape every cell)."""
    e = html.escape
    passive = summary.get("passive")
    if not passive:
        return []
    parts = ["<h2>Passive verdict: does the feeder work?</h2>"]
    target = e(cell(passive.get("target")))
    parts.append(
        "<p>A design works when, over drops perturbed as a real feeder sees them, the Wilson "
        f"95% lower bound of each entry's success probability clears {target}; trials stop "
        "as soon as that is decided either way.</p>"
    )
    parts.append(
        table(
            [
                "evaluated",
                "works",
                "fails",
                "undecided",
                "degenerate",
                "fraction that works",
                "95% CI",
                "of",
                "drops",
                "trials per verdict",
                "drops/s",
            ],
            [
                [
                    cell(passive.get("evaluated")),
                    cell(passive.get("works")),
                    cell(passive.get("fails")),
                    cell(passive.get("undecided")),
                    cell(passive.get("degenerate")),
                    cell(passive.get("works_fraction"), ".3f"),
                    _interval(passive.get("works_ci")),
                    str(passive.get("works_basis", DASH)),
                    cell(passive.get("drops")),
                    cell(passive.get("mean_trials"), ".3g"),
                    cell(passive.get("drops_per_s"), ".3g"),
                ]
            ],
            text_columns=(7,),
        )
    )
    pipelines = list(summary.get("pipelines") or [])
    if pipelines:
        parts.append("<h3>Which rungs are worth climbing (replayed on the holdout)</h3>")
        parts.append(
            '<p class="note">Each order of the ladder\'s planning rungs before the passive '
            "verdict: worker seconds per design, the fraction of the designs that work which it "
            "would keep (recall), and its speed-up over the passive verdict alone.</p>"
        )
        parts.append(
            table(
                ["pipeline", "s/design", "95% CI", "recall", "95% CI", "speed-up", "designs"],
                [
                    [
                        " → ".join(str(r) for r in p.get("rungs") or []),
                        cell(p.get("cost_s"), ".3g"),
                        _interval(p.get("cost_ci")),
                        cell(p.get("recall"), ".2f"),
                        _interval(p.get("recall_ci")),
                        cell(p.get("speedup"), ".2f"),
                        cell(p.get("n")),
                    ]
                    for p in pipelines
                ],
                text_columns=(0,),
            )
        )
    best = with_verdicts(summary)
    parts.append("<h3>The designs that work</h3>")
    if not best:
        parts.append("<p>No design works (yet).</p>")
        return parts
    parts.append(
        '<p class="note">Ranked by the lower bound of P(both), the probability that one part '
        "leaves heavy end down from either entry, then by the slower entry's mean exit time. "
        "The strips are each design's nominal drops (no perturbation), as the paper's Figs. "
        "10-11.</p>"
    )
    parts.append(figure(figures, TRANSITIONS, "transition matrices of the designs that work"))
    for entry in best:
        parts += design_verdict_html(entry, figures, table, figure)
    return parts


def design_verdict_html(entry, figures, table, figure) -> list[str]:
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
                _interval(per.get("interval")),
                cell(per.get("mean_exit_time_s"), ".3f"),
            ]
        )
    both = v.get("both") or {}
    rows.append(
        [
            "both",
            f"{cell(both.get('successes'))} / {cell(v.get('drops'))}",
            cell(both.get("p"), ".3f"),
            _interval(both.get("interval")),
            DASH,
        ]
    )
    parts = [
        f"<h4>Design {html.escape(cell(d))}: {html.escape(str(v.get('decision', DASH)))}</h4>",
        table(["entry", "successes", "P", "95% CI", "mean exit time (s)"], rows, (0,)),
    ]
    matrix = v.get("transitions") or {}
    outcomes = [
        c
        for c in OUTCOME_COLOURS.keys() | {c for m in matrix.values() for c in m}
        if any((matrix.get(o) or {}).get(c, 0) > 0 for o in ORIENTATIONS)
    ]
    outcomes.sort(key=lambda c: list(OUTCOME_COLOURS).index(c) if c in OUTCOME_COLOURS else 99)
    if outcomes:
        drops_in = sum(sum((matrix.get(o) or {}).values()) for o in ORIENTATIONS)
        out_right = sum((matrix.get(o) or {}).get(HEAVY_DOWN, 0) for o in ORIENTATIONS)
        parts.append(
            table(
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
        parts.append(figure(figures, name, f"nominal drops of design {d} from both entries"))
    else:
        parts.append("<p>No strip: the design cannot be built with this sweep's feeder.</p>")
    return parts
