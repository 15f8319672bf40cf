"""A report's "Why this design" section: a recommended design beside a baseline on the same
fresh draws (the data of :func:`experiments.drop.compare.compare_designs`).

Per design: whether the fresh draws confirm it works (said plainly, from the numbers), per
entry and for both entries the successes, probability with its Wilson 95% interval and mean
exit time of the design and of the baseline, the paired count of draws only one of them
passed, both transition matrices, the two devices drawn over each other, and the
parameters' differences as fractions of their box: the 12-parameter feeder's Table 2 range,
or a device family's own box (issue 24). The entries are the verdicts' own (a family's, in
its file's order), and a family's devices are drawn from the family (``comparison_figures``).
"""

from __future__ import annotations

import html
import re
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments.proportions import wilson_interval
from experiments.report_kit.cells import DASH, cell, interval
from experiments.report_kit.page import figure_html, html_table
from experiments.report_kit.verdict_section import entries_of, outcome_order, success_classes
from feeders.design import PARAMETER_MEANINGS

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

OVERLAY_PREFIX = "overlay_"


def overlay_name(label: str) -> str:
    """The figure name of a design's overlay on the baseline (a file-name-safe label)."""
    return OVERLAY_PREFIX + re.sub(r"[^A-Za-z0-9]+", "_", label).strip("_")


def confirmation(entry: dict[str, Any], drops: int, target: float) -> tuple[bool, str]:
    """Whether the fresh draws confirm that the design works, and the sentence that says so
    with the numbers: confirmed when every entry's Wilson 95% lower bound is above
    ``target`` (the rule the ranking's verdict used), refuted when some entry's upper bound
    is below it, else undecided on ``drops`` draws."""
    v = entry.get("verdict")
    if not v:
        return False, f"not confirmed: the design cannot be built ({entry.get('reason') or DASH})"
    per = v.get("orientations") or {}
    entries = entries_of(v)
    bounds = {o: (per.get(o) or {}).get("interval") or [0.0, 0.0] for o in entries}
    both = v.get("both") or {}
    n = int(v.get("drops") or 0)
    both_text = (
        f"P(both) {cell(both.get('successes'))}/{n}, 95% lower bound "
        f"{cell((both.get('interval') or [None])[0], '.3f')}"
    )
    lows = ", ".join(f"{o.replace('_', ' ')} {bounds[o][0]:.3f}" for o in entries)
    if all(bounds[o][0] > target for o in entries):
        return True, (
            f"confirmed: on {n} fresh draws every entry's 95% lower bound clears the target "
            f"{target:g} ({lows}); {both_text}."
        )
    below = [o for o in entries if bounds[o][1] < target]
    if below:
        highs = ", ".join(f"{o.replace('_', ' ')} {bounds[o][1]:.3f}" for o in below)
        return False, (
            f"not confirmed: on {n} fresh draws the design fails, an entry's 95% upper bound "
            f"is below the target {target:g} ({highs}); {both_text}."
        )
    best_low = wilson_interval(drops, drops)[0]
    return False, (
        f"not confirmed: undecided on {n} fresh draws, not every entry's 95% lower bound "
        f"clears the target {target:g} ({lows}; {drops} of {drops} would give "
        f"{best_low:.3f}); {both_text}."
    )


def comparison_html(comparison: dict[str, Any], figures: dict[str, Path]) -> list[str]:
    """The section's parts: a heading, what was run and its cost, then per design its
    confirmation, numbers, transition matrices, overlay and parameter differences."""
    e = html.escape
    base = comparison["baseline"]
    name = str(base["label"])
    drops = int(comparison["drops"])
    target = float(comparison["target"])
    designs = list(comparison.get("designs") or [])
    entries = entries_of({"orientations": comparison.get("entries")})
    each = "both entries each" if len(entries) == 2 else f"all {len(entries)} entries each"
    parts = [
        f'<h2 id="why">Why this design: compared with {e(name)} on the same fresh draws</h2>',
        f"<p>Each compared design and {e(name)} were judged again on the same {drops} fresh "
        f"perturbed trials ({each}, seed {int(comparison['seed'])}, not a seed any "
        "design was ranked with): trial i of every design sees the same entry noise, friction "
        "and manufacturing errors, so the differences below are the designs', not the draws'. "
        f"{_designed(comparison)}"
        f"Cost: {drops * len(entries) * (len(designs) + 1)} drops"
        + (
            f" in {float(comparison['wall_time_s']):.1f} s.</p>"
            if comparison.get("wall_time_s") is not None
            else " (their time was not recorded).</p>"
        ),
    ]
    if not base.get("verdict"):
        parts.append(f"<p>{e(name)} cannot be built here ({e(str(base.get('reason')))}).</p>")
    family = comparison.get("family")
    for entry in designs:
        parts += _design_parts(entry, base, drops, target, figures, family)
    return parts


def _designed(comparison: dict[str, Any]) -> str:
    """A device family's comparison says whose devices were judged (nothing for the
    12-parameter feeder's)."""
    family = comparison.get("family")
    if not family:
        return ""
    names = ", ".join(str(n) for n in comparison.get("parameters") or [])
    return (
        f"The designs are device family {html.escape(str(family))}'s ({html.escape(names)}), "
        "each trial's device made to tolerance from the family as its verdict makes it. "
    )


def _design_parts(
    entry: dict[str, Any],
    base: dict[str, Any],
    drops: int,
    target: float,
    figures: dict[str, Path],
    family: str | None = None,
) -> list[str]:
    """One compared design's parts against the baseline; ``family``: the device family's
    name (None: the 12-parameter feeder), whose parameters are measured on its box."""
    e = html.escape
    label, name = str(entry["label"]), str(base["label"])
    entries = entries_of(entry.get("verdict") or base.get("verdict") or {})
    confirmed, sentence = confirmation(entry, drops, target)
    colour = "#2ca02c" if confirmed else "#d62728"
    parts = [
        f"<h3>{e(label)} against {e(name)}</h3>",
        f'<p><b style="color:{colour}">{e(sentence.split(":")[0])}</b>:'
        f"{e(sentence.split(':', 1)[1])}</p>",
    ]
    parts.append(
        html_table(
            ["entry", *_numbers_header(label), *_numbers_header(name)],
            [
                [row, *_numbers(entry.get("verdict"), key), *_numbers(base.get("verdict"), key)]
                for row, key in [
                    *((o.replace("_", " "), o) for o in entries),
                    ("both", "both"),
                ]
            ],
            (0,),
        )
    )
    paired = entry.get("paired")
    if paired:
        parts.append(
            f'<p class="note">Paired, on the {paired["draws"]} draws both counted: {e(label)} '
            f"passed from both entries where {e(name)} did not on {paired['design_only']}, "
            f"{e(name)} where {e(label)} did not on {paired['baseline_only']}.</p>"
        )
    parts.append(_transitions_table(entry, base, entries))
    parts.append(
        figure_html(figures, overlay_name(label), f"{label} (filled) drawn over {name} (outline)")
        or f"<p>No drawing: {e(label)} or {e(name)} cannot be built.</p>"
    )
    parts.append(_differences_table(entry, label, name, family))
    return parts


def _differences_table(entry: dict[str, Any], label: str, name: str, family: str | None) -> str:
    """The parameters' differences from the baseline as fractions of their box: Table 2's
    range and each parameter's meaning for the feeder, a device family's box."""
    box = "of Table 2's range" if not family else "of the family's box"

    def about(d: dict[str, Any]) -> str:
        if not family:
            return PARAMETER_MEANINGS.get(str(d["name"]), "")
        return f"[{cell(d.get('low'), '.4g')}, {cell(d.get('high'), '.4g')}]"

    return html_table(
        ["parameter", "meaning" if not family else "family's box", label, name, "difference", box],
        [
            [
                str(d["name"]),
                about(d),
                cell(d["design"], ".4g"),
                cell(d["baseline"], ".4g"),
                cell(d["difference"], "+.3g"),
                f"{cell(100.0 * d['fraction'], '+.0f')}%",
            ]
            for d in entry.get("differences") or []
        ],
        (0, 1),
    )


def _numbers_header(label: str) -> list[str]:
    return [f"{label}: successes", "P", "95% CI", "mean exit time (s)"]


def _numbers(verdict: dict[str, Any] | None, key: str) -> list[str]:
    """successes / drops, P, interval and mean exit time of one entry (or of both)."""
    if not verdict:
        return [DASH] * 4
    per = verdict.get(key) if key == "both" else (verdict.get("orientations") or {}).get(key)
    per = per or {}
    return [
        f"{cell(per.get('successes'))} / {cell(verdict.get('drops'))}",
        cell(per.get("p"), ".3f"),
        interval(per.get("interval")),
        cell(per.get("mean_exit_time_s"), ".3f") if key != "both" else DASH,
    ]


def _transitions_table(
    entry: dict[str, Any], base: dict[str, Any], entries: tuple[str, ...]
) -> str:
    """Both transition matrices in one table: a row per design and entry (``entries``), a
    column per outcome either of them reached, the goal's classes first."""
    rows = [
        (str(x["label"]), (x.get("verdict") or {}).get("transitions") or {}) for x in (entry, base)
    ]
    success = success_classes(entry.get("verdict") or base.get("verdict") or {})
    outcomes: list[str] = []
    for _, matrix in rows:
        outcomes += [c for c in outcome_order(matrix, success) if c not in outcomes]
    if not outcomes:
        return ""
    return html_table(
        ["design", "entry", *outcomes],
        [
            [
                label,
                o.replace("_", " "),
                *(cell((matrix.get(o) or {}).get(c, 0)) for c in outcomes),
            ]
            for label, matrix in rows
            for o in entries
        ],
        (0, 1),
    )


def comparison_figures(
    comparison: dict[str, Any],
    figures_dir: Path,
    family: DeviceFamily | None = None,
    **feeder_options: Any,
) -> dict[str, Path]:
    """Per design that can be built (and a baseline that can), its device filled over the
    baseline's (:func:`experiments.pictures.overlay.overlay_figure`); name -> PNG. A device
    family's comparison gives its ``family``, whose devices are built; else
    ``feeder_options`` (part, friction, ...) go to :func:`feeders.feeder.build_feeder`."""
    import dataclasses

    from experiments.pictures.overlay import overlay_figure
    from feeders.design import DesignError, DesignParameters
    from feeders.feeder import DegenerateDesign, build_feeder

    def scene(entry: dict[str, Any]) -> Any:
        label = str(entry["label"])
        try:
            if family is not None:
                return dataclasses.replace(family.build(list(entry["values"])), name=label)
            design = DesignParameters.from_vector(list(entry["values"]))
            return build_feeder(design, name=label, **feeder_options)
        except (DegenerateDesign, DesignError, ValueError):
            return None

    base = comparison["baseline"]
    baseline = scene(base)
    out: dict[str, Path] = {}
    if baseline is None:
        return out
    for entry in comparison.get("designs") or []:
        built = scene(entry)
        if built is None:
            continue
        name = overlay_name(str(entry["label"]))
        out[name] = overlay_figure(
            built, baseline, (str(entry["label"]), str(base["label"])), figures_dir / f"{name}.png"
        )
    return out


def slower_exit_time(entry: dict[str, Any]) -> float | None:
    """The larger of the entries' mean exit times (s) on the fresh draws: what a feeder's
    rate is limited by; None when unknown."""
    verdict = entry.get("verdict") or {}
    per = verdict.get("orientations") or {}
    entries = entries_of(verdict)
    times = [(per.get(o) or {}).get("mean_exit_time_s") for o in entries]
    known = [float(t) for t in times if t is not None]
    return max(known) if len(known) == len(entries) else None


def fresh_ranking(comparison: dict[str, Any]) -> list[dict[str, Any]]:
    """The compared designs ranked on the fresh draws, not on the draws they were selected
    on: confirmed ones first, then by the Wilson 95% lower bound of P(both), then by the
    slower entry's mean exit time (faster first). Each entry: ``label``, ``confirmed``,
    ``sentence`` (:func:`confirmation`), ``lower`` (P(both)'s lower bound) and
    ``exit_time_s``."""
    drops, target = int(comparison["drops"]), float(comparison["target"])
    ranked = []
    for entry in comparison.get("designs") or []:
        confirmed, sentence = confirmation(entry, drops, target)
        both = (entry.get("verdict") or {}).get("both") or {}
        lower = (both.get("interval") or [0.0])[0]
        ranked.append(
            {
                "label": str(entry["label"]),
                "confirmed": confirmed,
                "sentence": sentence,
                "lower": float(lower or 0.0),
                "exit_time_s": slower_exit_time(entry),
            }
        )
    ranked.sort(key=_fresh_order)
    return ranked


def _fresh_order(r: dict[str, Any]) -> tuple[bool, float, float]:
    time = r["exit_time_s"]
    return (not r["confirmed"], -float(r["lower"]), float("inf") if time is None else time)
