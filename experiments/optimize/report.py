"""The report of an optimisation: ``report.html`` with its figures in ``figures/``.

In the order a designer reads it: what to build (the recommendation box,
:mod:`experiments.report_kit.recommendation`), why this design (the optimum beside the
baseline on the same fresh draws: numbers, paired draws, transition matrices, the optimum
drawn over the baseline, parameter differences; :mod:`experiments.report_kit.
comparison_section`), the strips of both designs' nominal drops (the paper's Figs. 10-11), how
much tolerance the optimum has (its margins, :mod:`experiments.report_kit.margins_section`),
then how it was found: Eq. 10 in the same model, the validation of the candidates and the
comparison of methods (convergence curves: best robust objective and best P(both) of the K
draws against evaluations, every seed). The numbers come from the results of
:func:`experiments.optimize.run.results`; this module only shows them.

A device family's optimisation (results with ``family``) shows its own parameters and box, the
optimum beside the family's default on the same fresh draws, and the strips of both designs'
nominal drops from the family's entries and the optimum's margins over the family's parameters
and friction; the comparison section is the 12-parameter feeder's, and the page says so where
it would stand.
"""

from __future__ import annotations

import html
import math
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments.report_kit.cells import DASH, cell, number, quantity
from experiments.report_kit.comparison_section import comparison_html
from experiments.report_kit.margins_section import margins_html, margins_sentence
from experiments.report_kit.page import STYLE, figure_html, html_table
from experiments.report_kit.recommendation import recommendation_html
from experiments.report_kit.verdict_section import strip_name
from feeders.design import PARAMETER_NAMES, TABLE2_BOUNDS

if TYPE_CHECKING:
    from matplotlib.figure import Figure

CONVERGENCE = "convergence"
METHOD_COLOURS = {
    "differential-evolution": "#1f77b4",
    "cma-es": "#d62728",
    "nelder-mead": "#2ca02c",
    "powell": "#9467bd",
}
OPTIMUM = "optimum"


def labels(results: dict[str, Any]) -> tuple[str, str]:
    """The optimum's label and the baseline's (``compared_with``; table3 in older results)."""
    return OPTIMUM, str(results.get("compared_with") or "table3")


NEAR_THE_END = 0.9  # the best found after this fraction of a run's budget: not converged


def convergence_figure(results: dict[str, Any], path: Path) -> Path:
    """The convergence of every run (see :func:`convergence_plot`), as a PNG at ``path``."""
    from experiments.pictures.scenes import save_figure

    return save_figure(convergence_plot(results), path)


def p_both_flat(results: dict[str, Any]) -> bool:
    """Whether P(both) over the K draws of the best design so far never changed, in any run
    (its panel would be a flat line: the figure leaves it out and the page says it)."""
    values = [c[2] for run in results["runs"] for c in run["curve"]]
    return bool(values) and max(values) - min(values) <= 1e-12


def objective_scale(values: list[float]) -> str:
    """The R axis's scale: ``symlog`` (linear below 1, logarithmic above) when R spans
    failed trials (several units above 1), else ``linear``: R below 1 is the Gbar term
    alone, and a log axis over it shows ticks such as ``4.04842 x 10^-1``."""
    finite = [v for v in values if number(v) is not None]
    if not finite or max(finite) <= 2.0:
        return "linear"
    return "symlog"


def convergence_plot(results: dict[str, Any]) -> Figure:
    """Of the best design so far, against evaluations: the robust objective R, P(both) over
    the K draws (left out when flat) and the mean Eq. 10 G; one line per run, coloured by
    method, with the evaluation where each run found its best marked."""
    from matplotlib import pyplot as plt

    from experiments.report_kit.figures import PLAIN_TICKS

    flat = p_both_flat(results)
    panels = 2 if flat else 3
    fig, axes = plt.subplots(1, panels, figsize=(10.0, 4.0), squeeze=False)
    ax_r, ax_g = axes[0, 0], axes[0, -1]
    ax_p = None if flat else axes[0, 1]
    seen = set()
    all_r = []
    found: str | None = "where its best was found"
    for run in results["runs"]:
        curve = run["curve"]
        if not curve:
            continue
        n = [c[0] for c in curve]
        colour = METHOD_COLOURS.get(run["method"], "#444")
        label = None if run["method"] in seen else run["method"]
        seen.add(run["method"])
        all_r += [c[1] for c in curve]
        ax_r.step(n, [c[1] for c in curve], where="post", color=colour, label=label)
        if ax_p is not None:
            ax_p.step(n, [c[2] for c in curve], where="post", color=colour, label=label)
        g = [math.nan if c[3] is None else c[3] for c in curve]
        ax_g.step(n, g, where="post", color=colour, label=label)
        best = run.get("best")
        if best is not None:
            at = int(best["at"])
            ax_r.plot([at], [curve[at - 1][1]], "o", color=colour, ms=6, label=found)
            found = None
    k = results["objective"]["trials"]
    scale = objective_scale(all_r)
    if scale == "symlog":
        ax_r.set_yscale("symlog", linthresh=1.0)
        ax_r.set_ylim(bottom=0.0)  # the linear part below 1 gets its own tick, 0
    ax_r.yaxis.set_major_formatter(PLAIN_TICKS)
    ax_r.set_ylabel("best R (failed trials + Gbar / (Gbar + 10 s))", fontsize=9)
    ax_r.set_title(f"robust objective, K = {k} fixed draws", fontsize=10)
    if ax_p is not None:
        ax_p.set_ylabel("P(both) of the best design, K draws", fontsize=9)
        ax_p.set_ylim(-0.02, 1.02)
        ax_p.set_title("success from both entries", fontsize=10)
    ax_g.yaxis.set_major_formatter(PLAIN_TICKS)
    ax_g.set_ylabel("mean G of the best design (s, Eq. 10)", fontsize=9)
    ax_g.set_title("its mean Eq. 10 objective, K draws", fontsize=10)
    for ax in axes[0]:
        ax.set_xlabel("evaluations", fontsize=9)
        ax.tick_params(labelsize=9)
        ax.grid(alpha=0.3)
    if seen:
        ax_r.legend(fontsize=9)
    if flat:
        fig.suptitle(flat_p_sentence(results), fontsize=9)
    return fig


def flat_p_sentence(results: dict[str, Any]) -> str:
    """What the left-out P(both) panel would have shown: its one value."""
    values = [c[2] for run in results["runs"] for c in run["curve"]]
    shown = cell(values[0], ".3f") if values else DASH
    return (
        f"P(both) of the best design over the K draws was {shown} at every evaluation of every "
        "run (its panel is left out)"
    )


def convergence_notes(results: dict[str, Any]) -> list[str]:
    """Per run, a sentence when its best was found in the last tenth of its budget (the run
    had not converged: more evaluations might find better) or was its first evaluation (the
    start was never improved on)."""
    notes = []
    for run in results["runs"]:
        best = run.get("best")
        if best is None:
            continue
        at, budget = int(best["at"]), int(run["budget"])
        name = f"{run['method']}, seed {run['seed']}"
        if at > NEAR_THE_END * budget and budget > 1:
            notes.append(
                f"{name}: not converged: the best was found at evaluation {at} of {budget}."
            )
        elif at == 1 and run["evaluations"] > 1:
            notes.append(
                f"{name}: the best is its first evaluation: none of the other "
                f"{run['evaluations'] - 1} improved on it."
            )
    return notes


def strip_figures(config, results: dict[str, Any], figures_dir: Path) -> dict[str, Path]:
    """The strips of the nominal drops of the optimum and the baseline (table3, or a device
    family's default) from every entry (Figs. 10-11)."""
    from experiments.drop.passive import passive_drop
    from experiments.drop.pictures import drop_strip
    from experiments.optimize.run import designed
    from feeders.feeder import DegenerateDesign

    space = designed(config)
    out = {}
    for label in labels(results):
        entry = results.get(label)
        if entry is None:
            continue
        values = [entry["values"][n] for n in space.names]
        try:
            scene = space.scene(config, values, name=label)
        except DegenerateDesign:
            continue
        drops = [
            passive_drop(scene, o, step=config.step, t_max=config.t_max) for o in space.entries
        ]
        name = strip_name(label)
        out[name] = drop_strip(scene, drops, figures_dir / f"{name}.png")
    return out


def write_report(out: Path, config, results: dict[str, Any]) -> Path:
    """Write ``out/report.html`` and its figures, unless the report there was written from the
    same results by the same code and is intact (:mod:`experiments.optimize.report_cache`);
    returns the page's path."""
    from experiments.optimize.report_cache import report_current, report_key, save_cache

    page = out / "report.html"
    key = report_key(results, config.to_dict())
    if report_current(out, key):
        return page
    figures_dir = out / "figures"
    figures_dir.mkdir(parents=True, exist_ok=True)
    figures = {}
    if results.get("runs"):  # the robust goal without Eq. 10 methods has no convergence
        figures[CONVERGENCE] = convergence_figure(results, figures_dir / f"{CONVERGENCE}.png")
    figures.update(strip_figures(config, results, figures_dir))
    figures.update(report_figures(config, results, figures_dir))
    page.write_text(html_page(results, figures))
    save_cache(out, key)
    return page


def report_figures(config, results: dict[str, Any], figures_dir: Path) -> dict[str, Path]:
    """The optimum drawn over the baseline (the comparison's overlay) and the margins chart."""
    from experiments.report_kit.comparison_section import comparison_figures
    from experiments.report_kit.margins_section import margins_figures
    from feeders.scene_yaml import environment_from_dict

    figures: dict[str, Path] = {}
    comparison = results.get("comparison")
    if comparison and not results.get("optimum_is_baseline"):  # no outline over itself
        environment = environment_from_dict(config.feeder)
        figures.update(comparison_figures(comparison, figures_dir, **environment))
    baseline = results.get("baseline_margins")  # the robust goal's: table3's beside
    figures.update(margins_figures(results.get("margins"), figures_dir, baseline=baseline))
    return figures


def _interval(ci: Any) -> str:
    if not isinstance(ci, (list, tuple)) or len(ci) != 2:
        return DASH
    return f"[{cell(ci[0], '.3f')}, {cell(ci[1], '.3f')}]"


def parameter_box(results: dict[str, Any]) -> dict[str, tuple[float, float]]:
    """Name -> (low, high) of each design parameter: Table 2's, or the device family's box."""
    family = results.get("family")
    if not family:
        return {name: TABLE2_BOUNDS[name] for name in PARAMETER_NAMES}
    return {
        name: (float(lo), float(hi))
        for name, lo, hi in zip(family["parameters"], family["low"], family["high"], strict=True)
    }


def design_table_rows(results: dict[str, Any]) -> list[list[str]]:
    """Table 3's layout: per parameter its range (Table 2's, or the family's box), the
    baseline's value and the optimum's."""
    optimum, baseline = labels(results)
    rows = []
    for name, (low, high) in parameter_box(results).items():
        row = [name, f"[{low:g}, {high:g}]"]
        for label in (baseline, optimum):
            entry = results.get(label)
            row.append(cell(entry["values"][name], ".4f") if entry else DASH)
        rows.append(row)
    return rows


def comparison_rows(results: dict[str, Any]) -> list[list[str]]:
    """Per method: seeds, budget, and over its seeds the best R (median, range), best P(both)
    of the K draws (median) and the evaluation at which the best was found (median)."""
    by_method: dict[str, list[dict]] = {}
    for run in results["runs"]:
        if run["best"] is not None:
            by_method.setdefault(run["method"], []).append(run)
    rows = []
    k = results["objective"]["trials"]
    for method, runs in by_method.items():
        values = sorted(r["best"]["value"] for r in runs)
        ps = sorted(r["best"]["both"] / k for r in runs)
        ats = sorted(r["best"]["at"] for r in runs)
        rows.append(
            [
                method,
                cell(len(runs)),
                cell(runs[0]["budget"]),
                cell(_median(values), ".4f"),
                f"[{cell(values[0], '.4f')}, {cell(values[-1], '.4f')}]",
                cell(_median(ps), ".3f"),
                cell(_median(ats), ".0f"),
            ]
        )
    return rows


def _median(xs: list[float]) -> float:
    n = len(xs)
    return xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])


def eq10_rows(results: dict[str, Any]) -> list[list[str]]:
    """Per design: Eq. 10's G of the nominal drops, mean G and P(both) over the K draws and
    over the fresh verdict draws with its interval."""
    rows = []
    for label in labels(results):
        entry = results.get(label)
        if entry is None:
            continue
        nominal = entry.get("nominal") or {}
        verdict = entry.get("verdict") or {}
        both = verdict.get("both") or {}
        objective = entry["objective"]
        rows.append(
            [
                label,
                cell(nominal.get("G"), ".3f"),
                cell(objective.get("mean_g"), ".3f"),
                cell(objective.get("p_both"), ".3f"),
                cell(verdict.get("mean_g"), ".3f"),
                f"{cell(both.get('successes'))} / {cell(verdict.get('drops'))}",
                _interval(both.get("interval")),
                str(verdict.get("decision", DASH)),
            ]
        )
    return rows


def candidate_rows(results: dict[str, Any]) -> list[list[str]]:
    """Per validated candidate: R and P(both) on the K draws, its verdict on fresh draws."""
    return [
        [
            cell(c["rank"] + 1),
            cell(c["value"], ".4f"),
            cell(c["p_both_k"], ".3f"),
            f"{cell(c['both'])} / {cell(c['drops'])}",
            _interval(c["interval"]),
            cell(c["mean_g"], ".3f"),
            "optimum" if c["chosen"] else "",
        ]
        for c in results.get("candidates") or []
    ]


CANDIDATE_HEADERS = [
    "rank by R",
    "R (K draws)",
    "P(both) (K draws)",
    "both (fresh draws)",
    "95% CI",
    "mean G (fresh)",
    "",
]
EQ10_HEADERS = [
    "design",
    "G nominal",
    "mean G (K draws)",
    "P(both) (K draws)",
    "mean G (verdict)",
    "both (verdict)",
    "95% CI",
    "decision",
]
COMPARISON_HEADERS = [
    "method",
    "seeds",
    "budget",
    "best R (median)",
    "range",
    "P(both) (median)",
    "found at (median)",
]


def chosen_sentence(results: dict[str, Any]) -> str:
    """How the optimum was chosen, with the numbers of this run."""
    final = results.get("final") or {}
    k = results["objective"]["trials"]
    return (
        f"of the {cell(final.get('candidates'))} designs with the lowest robust objective R "
        f"over K = {cell(k)} fixed draws, the one with the highest 95% lower bound of P(both) "
        f"on {cell(final.get('trials'))} fresh trials (seed {cell(final.get('seed'))}), then "
        "the lowest mean Eq. 10 G; its numbers here are on other fresh trials again (seed "
        f"{cell((final.get('seed') or 0) + 1)}), the baseline's on the same ones"
    )


def family_sentence(results: dict[str, Any]) -> str:
    """What a device family's optimisation found, in one paragraph: the optimum's verdict on
    fresh draws beside the baseline's (the family's default) on the same draws."""
    family = results["family"]
    optimum, baseline = labels(results)
    parts = [
        f"Device family {family['name']} ({len(family['parameters'])} parameters; entries "
        f"{', '.join(family['entries'])})."
    ]
    for label in (optimum, baseline):
        verdict = (results.get(label) or {}).get("verdict")
        if not verdict:
            parts.append(f"{label}: not judged yet.")
            continue
        both = verdict["both"]
        parts.append(
            f"{label}: {verdict['decision']}, both entries {both['successes']} of "
            f"{verdict['drops']} fresh trials, P(both) 95% interval {_interval(both['interval'])}, "
            f"mean Eq. 10 G {quantity(verdict.get('mean_g'), 's', '.2f')}."
        )
    robust = results.get("robust")
    chosen = robust_chosen_sentence(results) if robust else chosen_sentence(results)
    parts.append(f"Chosen: {chosen}.")
    return " ".join(parts)


def _family_box(results: dict[str, Any]) -> str:
    """A family's "what to build": the optimum named when its fresh verdict works."""
    verdict = (results.get(OPTIMUM) or {}).get("verdict") or {}
    kind = "recommendation" if verdict.get("works") else "recommendation none"
    title = "What to build: the optimum" if verdict.get("works") else "No design confirmed"
    values = (results.get(OPTIMUM) or {}).get("values") or {}
    shown = ", ".join(f"{n} = {v:.4f}" for n, v in values.items())
    margins = results.get("margins")
    tolerance = (
        f'</p><p>Tolerance: {html.escape(margins_sentence(margins))} (<a href="#margins">'
        "margins</a>)."
        if margins
        else ""
    )
    return (
        f'<div class="{kind}"><h2>{html.escape(title)}</h2><p>'
        + html.escape(family_sentence(results))
        + (f"</p><p>The optimum: {html.escape(shown)}." if shown else "")
        + tolerance
        + "</p></div>"
    )


def _recommendation(results: dict[str, Any]) -> str:
    comparison = results.get("comparison")
    if results.get("family"):
        return _family_box(results)
    if not comparison:
        return recommendation_html(
            None, None, None, "", absent="the optimisation has not judged its optimum yet"
        )
    margins = results.get("margins")
    optimum, baseline = labels(results)
    g = [
        ((results.get(label) or {}).get("verdict") or {}).get("mean_g")
        for label in (optimum, baseline)
    ]
    notes = []
    if None not in g:
        notes.append(
            (
                "What it minimised",
                f"Eq. 10's G (both entries' exit times plus w times their "
                f"distances from the goal; lower is better), mean {g[0]:.2f} s against "
                f"{baseline}'s {g[1]:.2f} s on the same draws.",
            )
        )
    robust = results.get("robust")
    if robust:
        notes = [("What it maximised", robust_sentence(results))]
    same = same_design_sentence(results)
    if same:
        notes.insert(0, ("The baseline itself", same[0].upper() + same[1:] + "."))
    chosen = robust_chosen_sentence(results) if robust else chosen_sentence(results)
    return recommendation_html(OPTIMUM, comparison, margins, chosen, notes=notes)


def _robustness_text(r: dict[str, Any] | None) -> str:
    if not r:
        return "not measured"
    if r.get("unlimited"):
        return "unlimited within the box"
    side = f" {r['side']}" if r.get("side") else ""
    return f"{r['value']:.3f} of its box ({r.get('axis')}{side})"


def robust_sentence(results: dict[str, Any]) -> str:
    """The robust goal's result in one sentence: the optimum's robustness beside the
    baseline's, on the same margins draws."""
    robust = results["robust"]
    _, baseline = labels(results)
    return (
        f"the robustness, the smallest room over the parameters and mu before P(both) falls "
        f"below the target: {_robustness_text(robust.get('optimum'))} against {baseline}'s "
        f"{_robustness_text(robust.get('baseline'))}, on the same margins draws"
    )


def robust_chosen_sentence(results: dict[str, Any]) -> str:
    """How the robust goal's optimum was chosen, with this run's numbers."""
    robust, final = results["robust"], results.get("final") or {}
    return (
        f"design centering from the best start by R, {cell(robust.get('evaluations'))} margins "
        "evaluations; of the designs it accepted (each works and is more robust than the one "
        f"before), the most robust whose verdict on {cell(final.get('trials'))} fresh trials "
        f"(seed {cell((final.get('seed') or 0) + 1)}) works at the target "
        f"{cell(final.get('target'))}, the baseline judged on the same trials"
    )


ROBUST_HEADERS = [
    "evaluation",
    "move",
    "step factor",
    "works",
    "robustness",
    "limiting axis",
    "mean exit time (s)",
    "accepted",
]


def robust_rows(results: dict[str, Any]) -> list[list[str]]:
    """Per margins evaluation of every centring chain: the move, its damping, whether the
    design works, its robustness and limiting axis, its mean exit time, accepted or not."""
    rows, n = [], 0
    for chain in (results.get("robust") or {}).get("chains") or []:
        for step in chain["steps"]:
            n += 1
            r = step["robustness"]
            rows.append(
                [
                    cell(n),
                    str(step["move"]),
                    cell(step["step"], ".3g"),
                    "yes" if step["works"] else "no",
                    DASH if r.get("value") is None else f"{r['value']:.4f}",
                    f"{r.get('axis') or DASH} {r.get('side') or ''}".strip(),
                    cell(step.get("mean_exit_time_s"), ".3f"),
                    "yes" if step["accepted"] else "",
                ]
            )
    return rows


def robust_html(results: dict[str, Any]) -> list[str]:
    """The robust goal's "how it was found": its definition, the method and every step."""
    robust = results.get("robust")
    if not robust:
        return []
    e = html.escape
    chains = robust.get("chains") or []
    stopped = "; ".join(f"{c['start']}: {c['stopped']}" for c in chains)
    return [
        "<h2>How it was found: the robust objective</h2>",
        f"<p>{e(robust['definition'][:1].upper() + robust['definition'][1:])}. "
        f"{e(robust['method'][:1].upper() + robust['method'][1:])}. "
        f"{e(robust_sentence(results)[:1].upper() + robust_sentence(results)[1:])}.</p>",
        f'<p class="note">Settings: {e(str(robust.get("centering")))}; stopped: '
        f"{e(stopped or DASH)}.</p>",
        html_table(ROBUST_HEADERS, robust_rows(results), (0,)),
    ]


def _strips(results: dict[str, Any], figures: dict[str, Path]) -> list[str]:
    parts = ["<h2>Nominal drops (the paper's Figs. 10-11)</h2>"]
    for label in labels(results):
        name = strip_name(label)
        if name in figures:
            parts.append(f"<h3>{html.escape(label)}</h3>")
            parts.append(figure_html(figures, name, f"nominal drops of {label} from both entries"))
    return parts if len(parts) > 1 else []


def _family_design_table(results: dict[str, Any]) -> list[str]:
    """A device family's parameters: the family's box, the baseline's and the optimum's values
    (the 12-parameter feeder's are in the comparison section)."""
    if not results.get("family"):
        return []
    baseline = labels(results)[1]
    headers = ["parameter", "family's range", baseline, OPTIMUM]
    return [
        "<h2>The design: the family's parameters</h2>",
        html_table(headers, design_table_rows(results), (0,)),
    ]


def _absent(what: str, why: str | None) -> list[str]:
    """A note saying why a section is not on the page."""
    if not why:
        return []
    return [f'<p class="note">{html.escape(what)} is not shown: {html.escape(why)}.</p>']


def html_page(results: dict[str, Any], figures: dict[str, Path]) -> str:
    e = html.escape
    obj = results["objective"]
    comparison = results.get("comparison")
    margins = results.get("margins")
    parts = [
        "<!DOCTYPE html>",
        '<html><head><meta charset="utf-8">',
        f"<title>partfeeder optimize: {e(results['name'])}</title>",
        f"<style>{STYLE}</style></head><body>",
        f"<h1>Design optimisation: {e(results['name'])}</h1>",
        f'<p class="note">Generated {e(time.strftime("%Y-%m-%d %H:%M:%S"))}; '
        f"{cell(results['evaluations'])} designs evaluated, "
        f"{quantity(results.get('worker_time_s'), 's', '.1f')} of worker time; this command "
        f"{quantity(results.get('wall_time_s'), 's', '.1f')}.</p>",
        _recommendation(results),
        *(comparison_html(comparison, figures) if comparison else []),
        *_absent("The comparison", results.get("comparison_absent")),
        *_family_design_table(results),
        *_strips(results, figures),
        *margins_html(
            margins,
            figures,
            results.get("margins_absent"),
            baseline=results.get("baseline_margins"),
        ),
        *robust_html(results),
        "<h2>How it was found: the objective</h2>",
        "<p>The objective (lower is better): "
        f"{e(obj['definition'])}. K = {cell(obj['trials'])} perturbation draws (seed "
        f"{cell(obj['seed'])}), the same for every design; w = {cell(obj['weight'])}. "
        "The verdicts below use fresh draws (another seed), so the optimum's probability is "
        "not the one it was selected on.</p>",
        "<h3>Eq. 10 and the verdicts in the same model</h3>",
        html_table(EQ10_HEADERS, eq10_rows(results), (0, 5, 7)),
        "<h3>Validation: the best designs by R on fresh draws</h3>",
        '<p class="note">R is minimised over K fixed draws, so the best R flatters its '
        "design; the optimum is the candidate with the highest lower bound of P(both) on fresh "
        "draws, then the lowest mean G. Its verdict above uses other fresh draws again.</p>",
        html_table(CANDIDATE_HEADERS, candidate_rows(results), (6,)),
        "<h3>Methods on the same budget</h3>",
        html_table(COMPARISON_HEADERS, comparison_rows(results), (0,)),
        *([f'<p class="note">{e(flat_p_sentence(results))}.</p>'] if p_both_flat(results) else []),
        figure_html(figures, CONVERGENCE, "convergence of every run"),
        *(f'<p class="note">{e(note)}</p>' for note in convergence_notes(results)),
        "</body></html>",
    ]
    return "\n".join(parts)


def same_design_sentence(results: dict[str, Any]) -> str | None:
    """When the optimum is the baseline itself (``optimum_is_baseline``), one sentence that
    says so: its rows are one design's, and the report draws no outline over itself."""
    if not results.get("optimum_is_baseline"):
        return None
    baseline = labels(results)[1]
    return (
        f"the optimum is the baseline, {baseline}, itself: the search found no better design "
        "(a larger --evaluations budget or other starts, --from SWEEP_DIR, may)"
    )


def summary_text(results: dict[str, Any]) -> str:
    """The results as a few plain-text tables, for the terminal."""
    lines = [f"optimisation {results['name']}: {results['evaluations']} designs evaluated"]
    lines.append("")
    baseline = labels(results)[1]
    if results.get("family"):
        lines.append(family_sentence(results))
        lines.append("")
    box = "family's range" if results.get("family") else "Table 2 range"
    lines.append(f"{'parameter':>10} {box:>16} {baseline:>9} {'optimum':>9}")
    for row in design_table_rows(results):
        lines.append(f"{row[0]:>10} {row[1]:>16} {row[2]:>9} {row[3]:>9}")
    same = same_design_sentence(results)
    if same:
        lines.append(same)
    lines.append("")
    lines.append(" | ".join(EQ10_HEADERS))
    for row in eq10_rows(results):
        lines.append(" | ".join(row))
    lines.append("")
    for headers, rows in (
        (CANDIDATE_HEADERS, candidate_rows(results)),
        (COMPARISON_HEADERS, comparison_rows(results)),
    ):
        if rows:  # the robust goal has no Eq. 10 candidates or methods: no empty tables
            lines.append(" | ".join(headers))
            lines.extend(" | ".join(row) for row in rows)
            lines.append("")
    lines.append(margins_line(results))
    if results.get("robust"):
        lines.append(f"robust objective: {robust_sentence(results)}")
    wall = results.get("wall_time_s")
    if wall is not None and not math.isnan(wall):
        lines.append(f"wall time: {wall:.1f} s")
    return "\n".join(lines)


def margins_line(results: dict[str, Any]) -> str:
    """One line: the optimum's tightest margins and what measuring them cost (or why it has
    none)."""
    margins = results.get("margins")
    if margins is None:
        return f"margins of the optimum: none: {results.get('margins_absent') or 'not measured'}"
    cost = margins.get("cost") or {}
    return (
        f"margins of the optimum: {margins_sentence(margins)}; cost {cell(cost.get('drops'))} "
        f"drops, {quantity(cost.get('wall_time_s'), 's', '.1f')} on {cell(cost.get('workers'))} "
        "worker(s)"
    )
