"""The passive verdict in a sweep's report: what works, with what probability, where the part
ends, and what each order of rungs would cost (issue 13).

``verdict_figures`` draws, for the best designs that carry a verdict, the snapshot strips of
their nominal drops from both entries (the paper's Figs. 10-11) and one figure of their
transition matrices; ``verdict_html`` gives the page's sections from the summary's ``passive``,
``pipelines`` and ``best`` entries (see :mod:`experiments.sweep.summary`). A design that
cannot be built, or a summary without a passive rung, gets a sentence, never an error.
"""

from __future__ import annotations

import dataclasses
import html
import json
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING, Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.figure import Figure

from experiments.drop.verdict_settings import VerdictSettings
from experiments.pictures.scenes import save_figure
from experiments.report_kit.cells import DASH, cell, interval
from experiments.report_kit.comparison_section import comparison_html
from experiments.report_kit.page import figure_html, html_table
from experiments.report_kit.verdict_section import (
    design_verdict_html,
    outcome_colour,
    outcome_order,
    strip_name,
    success_classes,
)
from experiments.sweep.report_figures import MAX_BEST_DRAWN
from feeders.feeder import ORIENTATIONS

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily
    from feeders.feeder_family import Family

TRANSITIONS = "transitions"
COMPARED = 3  # the best designs judged again against the baseline on fresh draws
BASELINE = "table3"


def with_verdicts(summary: dict) -> list[dict]:
    """The best designs that carry a passive verdict, in the summary's order, at most
    ``MAX_BEST_DRAWN``."""
    return [b for b in summary.get("best") or [] if "verdict" in b][:MAX_BEST_DRAWN]


def entries_shown(summary: dict) -> tuple[str, ...]:
    """The entry orientations of the sweep's designs: its device family's (the summary's
    ``family``), else the feeder's."""
    family = summary.get("family")
    return tuple(family["entries"]) if family else ORIENTATIONS


def verdict_figures(
    summary: dict, figures_dir: Path, family: DeviceFamily | None = None
) -> dict[str, Path]:
    """The strips of the best designs' nominal drops and, unless every drop ended the same
    way (then :func:`transitions_sentence` says it), the transition-matrix figure;
    name -> PNG path (a design that cannot be built has no strip). A device family's sweep
    gives its ``family``, whose devices are drawn."""
    best = with_verdicts(summary)
    out: dict[str, Path] = {}
    if not best:
        return out
    if transitions_sentence(best) is None:
        out[TRANSITIONS] = save_figure(
            transitions_plot(summary, best), figures_dir / f"{TRANSITIONS}.png"
        )
    for entry in best:
        path = _strip(summary, entry, figures_dir / f"{strip_name(entry['design_id'])}.png", family)
        if path is not None:
            out[strip_name(entry["design_id"])] = path
    return out


def transitions_sentence(best: list[dict]) -> str | None:
    """When every drop of every design listed, from both entries, ended in one outcome, the
    sentence that says so (a chart of identical full bars would say it worse); else None."""
    outcomes: set[str] = set()
    drops = 0
    for entry in best:
        matrix = (entry.get("verdict") or {}).get("transitions") or {}
        for per_entry in matrix.values():
            for outcome, n in (per_entry or {}).items():
                if n > 0:
                    outcomes.add(outcome)
                    drops += n
    if len(outcomes) != 1 or drops == 0:
        return None
    designs = "the design" if len(best) == 1 else f"all {len(best)} designs"
    return (
        f"Every one of the {drops} perturbed drops of {designs} that work, from both entries, "
        f"ended {next(iter(outcomes))}: no drop ended anywhere else, so there is no transition "
        "chart."
    )


def _strip(
    summary: dict, entry: dict, path: Path, family: DeviceFamily | None = None
) -> Path | None:
    """The design's nominal passive drops from both entries, drawn as Figs. 10-11 (a
    family's design: its device, from the family's entries)."""
    from experiments.drop.passive import passive_drop
    from experiments.drop.pictures import drop_strip
    from feeders.design import DesignError, DesignParameters
    from feeders.feeder import DegenerateDesign, build_feeder
    from feeders.scene_yaml import environment_from_dict

    name = f"design {entry['design_id']}"
    try:
        if family is not None:
            scene = dataclasses.replace(family.build(list(entry.get("values") or [])), name=name)
        else:
            environment = environment_from_dict(summary.get("feeder") or {}, prefix="feeder.")
            design = DesignParameters.from_vector(list(entry.get("values") or []))
            scene = build_feeder(design, name=name, **environment)
    except (DegenerateDesign, DesignError, ValueError):
        return None
    results = [passive_drop(scene, o) for o in entries_shown(summary)]
    figure = drop_strip(scene, results, path)
    plt.close("all")
    return figure


def transitions_plot(summary: dict, best: list[dict]) -> Figure:
    """Per best design and entry orientation, a bar of its drops split by where they ended,
    each part labelled with its count; the legend names every outcome drawn."""
    rows: list[tuple[str, dict[str, int], tuple[str, ...]]] = []
    for entry in best:
        matrix = entry["verdict"].get("transitions") or {}
        success = success_classes(entry["verdict"])
        for orientation in entries_shown(summary):
            label = f"design {entry['design_id']}, {orientation.replace('_', ' ')}"
            rows.append((label, dict(matrix.get(orientation) or {}), success))
    fig, ax = plt.subplots(figsize=(9.5, 0.45 * len(rows) + 1.6))
    seen: set[str] = set()
    widest = max([sum(c.values()) for _, c, _ in rows] + [1])
    for y, (_, counts, success) in enumerate(rows):
        left = 0.0
        for outcome in outcome_order({"": counts}, success):
            n = counts[outcome]
            if n <= 0:
                continue
            colour = outcome_colour(outcome, success)
            ax.barh(
                y,
                n,
                left=left,
                color=colour,
                edgecolor="white",
                label=None if outcome in seen else outcome,
            )
            if n >= 0.06 * widest:
                ax.text(left + n / 2, y, str(n), ha="center", va="center", fontsize=9, color="w")
            seen.add(outcome)
            left += n
    ax.set_yticks(range(len(rows)), [label for label, _, _ in rows], fontsize=9)
    ax.invert_yaxis()
    ax.set_xlim(0.0, widest)
    ax.set_xlabel("drops (perturbed, from this entry)")
    ax.set_title(
        f"{summary.get('name', 'sweep')}: where the part ends, per design and entry", fontsize=11
    )
    ax.legend(fontsize=9, loc="upper left", bbox_to_anchor=(1.0, 1.0), title="ended")
    return fig


def verdict_html(summary: dict, figures: dict[str, Path]) -> list[str]:
    """The page's sections on the passive verdict (empty without a passive rung)."""
    e = html.escape
    passive = summary.get("passive")
    if not passive:
        return []
    parts = ["<h2>Passive verdict: does the feeder work?</h2>"]
    target = e(cell(passive.get("target")))
    rule = passive.get("rule") or {}
    if rule.get("rule") == "sprt":
        parts.append(
            "<p>A design works when, over drops perturbed as a real feeder sees them, Wald's "
            "sequential test of each entry accepts a success probability of "
            f"{e(cell(rule.get('works_p')))} over {e(cell(rule.get('fails_p')))} (error "
            f"{e(cell(rule.get('error')))} each way): it looks after every trial, and stops as "
            "soon as both entries work or one fails (docs/verdict.md: its exact operating "
            "characteristic). The intervals are Wilson 95% intervals of the same drops.</p>"
        )
    else:
        parts.append(
            "<p>A design works when, over drops perturbed as a real feeder sees them, the "
            f"Wilson 95% lower bound of each entry's success probability clears {target}; "
            "trials stop as soon as that is decided either way.</p>"
        )
    parts.append(
        html_table(
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
                    interval(passive.get("works_ci")),
                    f"{passive.get('works_basis', DASH)} (n = {cell(passive.get('works_n'))})",
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
        parts.append("<h3>Which rungs are worth climbing</h3>")
        parts.append(
            '<p class="note">Each order of the ladder\'s other rungs before the passive '
            "verdict, each rung stopping what it does not pass: worker seconds per design, "
            "replayed on the designs evaluated at every rung of the pipeline whatever their "
            "verdicts (n, on: the audit's when every rung stands below the verdict, else the "
            "holdout's, since the failing designs' planning costs are known only there); the "
            "fraction of the designs that work which it would keep (recall), on the designs "
            "that work counted (every design when none could have been stopped on its way, "
            "else the audit's or the holdout's); and its speed-up over the passive verdict "
            "alone on the same designs (none when a rung after the first saw no design of "
            "the sample: how many reached each rung says so).</p>"
        )
        parts.append(
            html_table(
                [
                    "pipeline",
                    "s/design (95% CI)",
                    "n",
                    "on",
                    "reached each rung",
                    "recall (95% CI)",
                    "of the designs that work",
                    "would throw away",
                    "speed-up (95% CI)",
                ],
                [
                    [
                        " → ".join(str(r) for r in p.get("rungs") or []),
                        _with_interval(cell(p.get("cost_s"), ".3g"), p.get("cost_ci"), ".3g"),
                        cell(p.get("n")),
                        str(p.get("basis", "the holdout")).removeprefix("the "),
                        ", ".join(str(k) for k in p.get("reached") or []) or DASH,
                        _with_interval(cell(p.get("recall"), ".2f"), p.get("recall_ci")),
                        f"{cell(p.get('recall_n'))}, {p.get('recall_basis', 'the holdout')}",
                        ", ".join(str(d) for d in p.get("thrown_away") or []) or DASH,
                        _with_interval(cell(p.get("speedup"), ".2f"), p.get("speedup_ci")),
                    ]
                    for p in pipelines
                ],
                text_columns=(0, 3, 4, 6, 7),
            )
        )
    best = with_verdicts(summary)
    parts.append("<h3>The designs that work</h3>")
    if not best:
        parts.append("<p>No design works (yet).</p>")
        parts += _comparison_parts(summary, figures)
        return parts
    parts.append(
        '<p class="note">Ranked by the lower bound of P(both), the probability that one part '
        "leaves heavy end down from either entry, then by the slower entry's mean exit time. "
        "The strips are each design's nominal drops (no perturbation), as the paper's Figs. "
        "10-11.</p>"
    )
    sentence = transitions_sentence(best)
    if sentence is not None:
        parts.append(f"<p>{e(sentence)}</p>")
    parts.append(figure_html(figures, TRANSITIONS, "transition matrices of the designs that work"))
    for entry in best:
        parts += design_verdict_html(entry, figures)
    parts += _comparison_parts(summary, figures)
    return parts


def _comparison_parts(summary: dict, figures: dict[str, Path]) -> list[str]:
    """The "Why this design" section from the summary's ``comparison`` (set by the report,
    :func:`comparison_of`), or the sentence that says why there is none."""
    comparison = summary.get("comparison")
    if not comparison:
        return []
    if "absent" in comparison:
        name = str((comparison.get("baseline") or {}).get("label") or BASELINE)
        return [
            '<h2 id="why">Why this design</h2>',
            f"<p>No comparison with {html.escape(name)} on fresh draws: "
            f"{html.escape(str(comparison['absent']))}.</p>",
        ]
    return comparison_html(comparison, figures)


def sweep_config(db_path: Path) -> dict[str, Any]:
    """The sweep's config as its results database keeps it (``{}`` when it holds none)."""
    from experiments.sweep.results_db import connect

    with closing(connect(db_path, readonly=True)) as db:
        row = db.execute("SELECT value FROM meta WHERE key = 'config'").fetchone()
    return json.loads(row["value"]) if row is not None else {}


def passive_settings(config: dict[str, Any]) -> VerdictSettings | None:
    """The verdict settings of the sweep's passive rung (target, trials, step, perturbations),
    None without one."""
    from experiments.drop.perturbations import Perturbations
    from experiments.names import PASSIVE

    rungs = [r for r in config.get("ladder") or [] if r.get("level") == PASSIVE]
    if not rungs:
        return None
    return VerdictSettings(
        **(rungs[0].get("verdict") or {}),
        perturbations=Perturbations(**(rungs[0].get("perturbations") or {})),
    )


def default_baseline(family: DeviceFamily | None = None) -> tuple[str, list[float]]:
    """``(BASELINE, its 12 values)``: the paper's table3; a device family's default design,
    labelled ``default`` (:func:`experiments.family_config.family_default`)."""
    from experiments.family_config import family_default
    from feeders.design import preset

    if family is not None:
        return family_default(family)
    return BASELINE, [float(v) for v in preset(BASELINE).to_vector()]


def compared_device(summary: dict, family: DeviceFamily | None) -> Family:
    """What the comparison judges designs of: the sweep's device ``family``, else the
    12-parameter feeder as a family (:class:`feeders.feeder_family.FeederFamily`) with the
    sweep's part, friction and feeder options (the feeder's own verdicts, trial for
    trial)."""
    from feeders.feeder_family import FeederFamily
    from feeders.scene_yaml import environment_from_dict

    if family is not None:
        return family
    return FeederFamily(**environment_from_dict(summary.get("feeder") or {}, prefix="feeder."))


def comparison_of(
    summary: dict,
    db_path: Path,
    drops: int | None = None,
    baseline: tuple[str, list[float]] | None = None,
    family: DeviceFamily | None = None,
) -> dict[str, Any]:
    """The best designs that work by the sweep's own verdict (at most ``COMPARED``) judged
    again beside ``baseline`` (``(label, values)``; default the paper's table3, or a device
    family's default design, :func:`default_baseline`) on the same fresh draws
    (:func:`experiments.drop.compare.compare_family_designs`, ``drops`` trials each,
    default ``FRESH_DROPS``) with the sweep's passive settings, on a seed that is no design's
    verdict seed; the designs are the sweep's device (:func:`compared_device`: its
    ``family``, read from the database when the summary names one and none is given, or the
    feeder with the sweep's part and options), each made per trial as its verdict made it.
    The designs come in the order of
    :func:`experiments.report_kit.comparison_section.fresh_ranking` (confirmed first), not
    the order they were selected in. ``{"absent": reason, "baseline": {"label": ...}}``
    when there is nothing to compare."""
    from experiments.drop.compare import FRESH_DROPS, compare_family_designs, fresh_seed
    from experiments.report_kit.comparison_section import fresh_ranking
    from experiments.sweep.family import database_family
    from experiments.sweep.job import verdict_seed

    if family is None and summary.get("family"):
        found = database_family(db_path)
        family = None if found is None else found[0]
    name, base_values = baseline or default_baseline(family)
    best = with_verdicts(summary)[:COMPARED]
    if not best:
        return {"absent": "no design works, so none is recommended", "baseline": {"label": name}}
    config = sweep_config(db_path)
    settings = passive_settings(config)
    if settings is None:
        return {
            "absent": "the results database holds no sweep config with a passive rung",
            "baseline": {"label": name},
        }
    sweep_seed = int((config.get("designs") or {}).get("seed", 0))
    ranked_with = [verdict_seed(sweep_seed, int(b["design_id"])) for b in best]
    device = compared_device(summary, family)
    try:  # the designs' and the baseline's values are the device's, before any drop
        designs = {f"design {b['design_id']}": device.values(list(b["values"])) for b in best}
        base = device.values(list(base_values))
    except ValueError as exc:
        return {
            "absent": f"a best design's or the baseline's values are not a design ({exc})",
            "baseline": {"label": name},
        }
    comparison = compare_family_designs(
        device,
        designs,
        (name, base),
        settings,
        fresh_seed(sweep_seed, ranked_with),
        drops or FRESH_DROPS,
    )
    comparison["ranked_with"] = ranked_with
    order = [r["label"] for r in fresh_ranking(comparison)]
    comparison["designs"].sort(key=lambda d: order.index(str(d["label"])))
    return comparison


def _with_interval(value: str, ci: object, spec: str = ".2f") -> str:
    """A value and its 95% interval in one cell that does not wrap inside the interval."""
    return f"{value}\u00a0{interval(ci, spec)}".replace(", ", ",\u00a0")
