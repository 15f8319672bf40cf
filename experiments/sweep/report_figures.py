"""The figures of a sweep's report (PNG, matplotlib Agg): survivors per level, the feasible
set in design space, planner run times and tree sizes, pruning precision and recall, and the
best designs drawn. Each takes the summary (and the database's verdicts and runs where it
needs them) and writes one file; a figure without data says so instead of failing.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from experiments.pictures.scenes import draw_scene, save_figure
from experiments.report_kit.cells import DASH, cell, number
from experiments.report_kit.figures import empty_plot
from feeders.design import PARAMETER_NAMES, TABLE2_BOUNDS, DesignError, DesignParameters
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.scene_yaml import environment_from_dict

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

MAX_BEST_DRAWN = 6
NONE_COLOUR = "#c7c7c7"
# highest level passed: the top of the ladder green, as "feasible at both" elsewhere
LEVEL_COLOURS = {"geometric": "#e6a532", "kinematic": "#3b7dd8", "dynamic": "#2ca02c"}
EXTRA_COLOURS = ("#9467bd", "#8c564b", "#e377c2", "#17becf")
PLANNER_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b")


def highest_passed(
    design_id: int, ladder: Sequence[str], status: dict[tuple[int, str], str]
) -> int:
    """How many rungs of ``ladder`` the design passed from the bottom without a miss: 0 for
    none, ``len(ladder)`` for all. A rung passes when its evaluation is 'feasible'; a holdout
    design feasible at a higher rung after failing a lower one is counted at the lower one,
    as the ladder would have pruned it there."""
    passed = 0
    for level in ladder:
        if status.get((design_id, level)) != "feasible":
            break
        passed += 1
    return passed


def _level_colour(index: int, level: str) -> str:
    return LEVEL_COLOURS.get(level, EXTRA_COLOURS[index % len(EXTRA_COLOURS)])


def _empty_figure(path: Path, message: str, size: tuple[float, float] = (6.0, 2.5)) -> Path:
    """A figure that says why there is nothing to draw (the page keeps its layout)."""
    return save_figure(empty_plot(message, size), path)


def survivors_figure(summary: dict, path: Path) -> Path:
    """Per level (ladder order): designs evaluated and designs surviving it and every level
    below it, side by side, with the sweep's design count as a dashed line."""
    levels = list(summary.get("levels") or [])
    if not levels:
        return _empty_figure(path, "no levels in the summary")
    fig, ax = plt.subplots(figsize=(max(5.0, 1.8 * len(levels) + 2.0), 4.2))
    x = np.arange(len(levels))
    width = 0.38
    for offset, key, colour, label in (
        (-width / 2, "evaluated", "#c6dbef", "evaluated"),
        (width / 2, "survivors", "#2171b5", "survivors (passed this level and all below)"),
    ):
        counts = [number(row.get(key)) for row in levels]
        heights = [c or 0.0 for c in counts]
        ax.bar(x + offset, heights, width, color=colour, edgecolor="#555555", label=label)
        for k, (h, c) in enumerate(zip(heights, counts, strict=True)):
            text = DASH if c is None else f"{c:g}"
            ax.text(x[k] + offset, h, text, ha="center", va="bottom", fontsize=8)
    total = number(summary.get("designs"))
    if total is not None:
        ax.axhline(total, color="k", ls="--", lw=0.8, label=f"designs in the sweep ({total:g})")
    ax.set_xticks(x, [str(row.get("level", "?")) for row in levels])
    ax.set_ylabel("designs")
    ax.set_ylim(
        0, max([total or 0.0] + [number(r.get("evaluated")) or 0.0 for r in levels]) * 1.15 + 1
    )
    ax.set_title(f"{summary.get('name', 'sweep')}: survivors up the ladder", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    return save_figure(fig, path)


def feasible_set_figure(summary: dict, ladder: list[str], data: dict, path: Path) -> Path:
    """The feasible set Z_F in design space (as the paper's Fig. 2), drawn by
    :func:`feasible_set_plot`; a database without designs gets a sentence."""
    if len(data["values"]) == 0:
        return _empty_figure(path, "no designs in the results database yet")
    return save_figure(feasible_set_plot(summary, ladder, data), path)


def feasible_set_plot(summary: dict, ladder: list[str], data: dict) -> Figure:
    """Which designs pass, and where they lie in Table 2's box: parallel coordinates of the
    12 parameters (each axis Table 2's range of one parameter, bottom to top), one line per
    design (a device family's sweep: its parameters, ``data["parameters"]``, and box).
    Designs that fail the first rung are thin grey lines behind; the others are thick
    lines with markers, coloured by the highest rung they passed with every rung below it (the
    paper's Z_F is the top one), so a few that pass among many that fail stand out."""
    values = np.asarray(data["values"], dtype=float)
    passed = np.array([highest_passed(i, ladder, data["status"]) for i in data["ids"]])
    classes = ["fails the first rung", *ladder]
    colours = [NONE_COLOUR] + [_level_colour(k, level) for k, level in enumerate(ladder)]
    family = summary.get("family")
    names = list(data.get("parameters") or PARAMETER_NAMES)
    if family:
        low, high = np.array(family["low"], dtype=float), np.array(family["high"], dtype=float)
    else:
        low = np.array([TABLE2_BOUNDS[n][0] for n in PARAMETER_NAMES])
        high = np.array([TABLE2_BOUNDS[n][1] for n in PARAMETER_NAMES])
    unit = (values - low) / (high - low)
    x = np.arange(len(names))
    width = max(8.0, 10.0 * len(names) / 12)  # inches; the legend takes about a third
    fig, ax = plt.subplots(figsize=(width, 5.4))
    for k in range(len(names)):
        ax.plot([k, k], [0.0, 1.0], color="#888888", lw=0.8, zorder=1)
        for y, bound, va in ((-0.05, low[k], "top"), (1.05, high[k], "bottom")):
            ax.text(k, y, f"{bound:g}", ha="center", va=va, fontsize=9, color="#333333")
    for k in range(len(classes)):  # higher rungs drawn last, on top
        chosen = np.flatnonzero(passed == k)
        for row in chosen:
            if k == 0:
                ax.plot(x, unit[row], color=colours[k], lw=0.8, alpha=0.7, zorder=2)
            else:
                ax.plot(x, unit[row], color=colours[k], lw=2.4, marker="o", ms=6, zorder=3 + k)
    long_names = max(len(n) for n in names) > 5  # a family's: slanted, clear of each other
    ax.set_xticks(
        x,
        names,
        fontsize=10,
        rotation=30 if long_names else 0,
        ha="right" if long_names else "center",
    )
    ax.set_xlim(-0.4, len(names) - 0.6)
    ax.set_ylim(-0.14, 1.14)
    ax.set_yticks([0.0, 0.5, 1.0], ["low", "middle", "high"], fontsize=9)
    if family:
        ax.set_ylabel(f"value within the range of family {family['name']}")
        ax.set_xlabel("design parameter (the family file's units)", fontsize=9)
    else:
        ax.set_ylabel("value within Table 2's range")
        ax.set_xlabel(
            "design parameter (a-gy, r: lengths in the paper's units, the peg is 2 x 1; "
            "theta, alpha: rad)",
            fontsize=9,
        )
    for side in ("top", "right", "left"):
        ax.spines[side].set_visible(False)
    handles = [
        Line2D(
            [],
            [],
            color=colour,
            lw=0.8 if k == 0 else 2.4,
            marker=None if k == 0 else "o",
            label=f"{name} ({int(np.sum(passed == k))})",
        )
        for k, (name, colour) in enumerate(zip(classes, colours, strict=True))
    ]
    ax.legend(
        handles=handles,
        title="highest rung passed (designs)",
        fontsize=9,
        title_fontsize=9,
        loc="upper left",
        bbox_to_anchor=(1.0, 1.0),
    )
    ax.set_title(
        textwrap.fill(
            f"{summary.get('name', 'sweep')}: {feasible_set_headline(passed, ladder)}",
            int(6.5 * width),
        ),
        fontsize=11,
    )
    return fig


def feasible_set_headline(passed: np.ndarray, ladder: Sequence[str]) -> str:
    """The design-space figure's title from the counts: how many of the designs pass the
    first rung and how many the whole ladder."""
    n = len(passed)
    if not ladder:
        return f"{n} designs, no rungs"
    first = int(np.sum(passed >= 1))
    top = int(np.sum(passed >= len(ladder)))
    if len(ladder) == 1:
        return f"{first} of {n} designs pass {ladder[0]}"
    return f"{first} of {n} designs pass {ladder[0]}, {top} every rung up to {ladder[-1]}"


def _box(ax: plt.Axes, samples: list[list[float]], colours: list[str]) -> None:
    """Box plots at positions 0..n-1, skipping planners without a sample."""
    present = [k for k, s in enumerate(samples) if s]
    if not present:
        return
    boxes = ax.boxplot(
        [samples[k] for k in present],
        positions=present,
        widths=0.6,
        patch_artist=True,
        flierprops={"markersize": 3},
        medianprops={"color": "k"},
    )
    for patch, k in zip(boxes["boxes"], present, strict=True):
        patch.set_facecolor(colours[k])
        patch.set_alpha(0.6)


def planner_levels(ladder: Sequence[str], stats: list[dict], runs: list[dict]) -> list[str]:
    """The levels that have planner runs or statistics, in ladder order (then any others):
    a rung without planners (the passive verdict) has nothing to compare."""
    with_planners = {str(r.get("level")) for r in [*stats, *runs] if r.get("planner")}
    ordered = [level for level in ladder if level in with_planners]
    return ordered + sorted(with_planners - set(ordered))


def planners_figure(summary: dict, ladder: list[str], data: dict, path: Path) -> Path:
    """The planners per level (see :func:`planners_plot`); without runs, a sentence."""
    stats = list(summary.get("planners") or [])
    if not planner_levels(ladder, stats, data["runs"]):
        return _empty_figure(path, "no planner runs yet")
    return save_figure(planners_plot(summary, ladder, data), path)


PLANNER_ROWS = ("run time (s)", "solved fraction of runs", "tree size (states)")


def planners_plot(summary: dict, ladder: list[str], data: dict) -> Figure:
    """Planner comparison per level, as Planner Arena: one column per level with planner
    runs (a rung without planners is left out, and the title says so), rows with the run
    time box plots (from the runs table), the solved fraction (from the summary) and the
    tree size box plots. A planner keeps its colour across levels."""
    stats = list(summary.get("planners") or [])
    levels = planner_levels(ladder, stats, data["runs"])
    left_out = [level for level in ladder if level not in levels]
    planners: list[str] = []
    for row in [*stats, *data["runs"]]:
        if str(row.get("planner")) not in planners and row.get("planner") is not None:
            planners.append(str(row["planner"]))
    colour_of = {p: PLANNER_COLOURS[k % len(PLANNER_COLOURS)] for k, p in enumerate(planners)}
    fig, axes = plt.subplots(
        3, len(levels), figsize=(min(10.0, max(4.5, 3.0 * len(levels) + 1.0)), 8.0), squeeze=False
    )
    for row, label in zip(axes, PLANNER_ROWS, strict=True):
        row[0].set_ylabel(label, fontsize=10)
    for col, level in enumerate(levels):
        runs = [r for r in data["runs"] if r["level"] == level]
        level_stats = {str(s.get("planner")): s for s in stats if s.get("level") == level}
        names = [p for p in planners if p in level_stats or any(r["planner"] == p for r in runs)]
        time_ax, solved_ax, tree_ax = axes[:, col]
        time_ax.set_title(level, fontsize=11)
        colours = [colour_of[p] for p in names]
        for ax, key in ((time_ax, "time_s"), (tree_ax, "tree_size")):
            samples = [
                [float(r[key]) for r in runs if r["planner"] == p and r[key] is not None]
                for p in names
            ]
            _box(ax, samples, colours)
        fractions = [number(level_stats.get(p, {}).get("solved_fraction")) for p in names]
        solved_ax.bar(
            range(len(names)), [f or 0.0 for f in fractions], color=colours, edgecolor="#555555"
        )
        for k, f in enumerate(fractions):
            label = DASH if f is None else f"{f:.2f}"
            solved_ax.text(k, (f or 0.0) + 0.02, label, ha="center", fontsize=9)
        solved_ax.set_ylim(0, 1.12)
        for ax in (time_ax, solved_ax, tree_ax):
            ax.set_xticks(range(len(names)), names, fontsize=9)
            ax.set_xlim(-0.6, len(names) - 0.4)
            ax.tick_params(axis="y", labelsize=9)
    title = f"{summary.get('name', 'sweep')}: planners per level"
    if left_out:
        title += f"\n({', '.join(left_out)} left out: no planner runs at that rung)"
    fig.suptitle(title, fontsize=11)
    return fig


def pruning_title(summary: dict, ladder: Sequence[str]) -> str:
    """The pruning figure's title: what each level is compared against (the summary's
    truth, the passive verdict when there is one, else the top of the ladder) and on what."""
    truth = str(summary.get("truth") or (ladder[-1] if ladder else "the top level"))
    n = summary.get("holdout")
    on = f"the {n} holdout designs" if isinstance(n, int) else "the holdout"
    rows = summary.get("pruning") or []
    if any(row.get("recall_basis") == "every design" for row in rows):
        return (
            f"each level's verdict vs {truth}'s: precision on {on}, "
            "recall on every design that works"
        )
    return f"each level's verdict vs {truth}'s, on {on}"


def pruning_figure(summary: dict, ladder: list[str], path: Path) -> Path:
    """Precision and recall per level (see :func:`pruning_plot`); without a holdout, a
    sentence."""
    if not summary.get("pruning"):
        return _empty_figure(path, "no holdout: the pruning is not measured")
    return save_figure(pruning_plot(summary, ladder), path)


def pruning_plot(summary: dict, ladder: list[str]) -> Figure:
    """Precision and recall of each level's verdict against the truth's, on the holdout,
    with their confidence intervals as error bars; an undefined one says why."""
    rows = list(summary.get("pruning") or [])
    truth = str(summary.get("truth") or (ladder[-1] if ladder else "the top level"))
    width = min(10.0, max(5.0, 2.2 * len(rows) + 2.0))  # inches
    title = textwrap.fill(pruning_title(summary, ladder), int(8 * width))
    fig, ax = plt.subplots(figsize=(width, 4.2 + 0.3 * title.count("\n")))
    width = 0.36
    bars = ((-width / 2, "precision", "#6a51a3"), (width / 2, "recall", "#41ab5d"))
    why = {
        "precision": "n/a:\npasses none",
        "recall": f"n/a: none\npass {truth}",
    }
    for offset, key, colour in bars:
        for k, row in enumerate(rows):
            value = number(row.get(key))
            if value is None:
                ax.text(k + offset, 0.03, why[key], ha="center", fontsize=8, color="#555555")
                continue
            ci = row.get(f"{key}_ci") or [None, None]
            low, high = number(ci[0]), number(ci[1])
            yerr = None
            if low is not None and high is not None:
                yerr = [[max(0.0, value - low)], [max(0.0, high - value)]]
            ax.bar(k + offset, value, width, yerr=yerr, capsize=5, color=colour)
            if value >= 0.15:
                ax.text(k + offset, value / 2, f"{value:.2f}", ha="center", fontsize=9, color="w")
            else:  # above the whisker, clear of it
                top = high if high is not None else value
                ax.text(k + offset, top + 0.03, f"{value:.2f}", ha="center", fontsize=9)
    labels = [
        f"{row.get('level', '?')}\n(n = {cell(row.get('n'))}"
        + (f", recall n = {cell(row['recall_n'])})" if "recall_n" in row else ")")
        for row in rows
    ]
    ax.set_xticks(range(len(rows)), labels, fontsize=10)
    ax.set_xlim(-0.6, len(rows) - 0.4)
    ax.set_ylim(0, 1.25)
    ax.set_yticks(np.linspace(0.0, 1.0, 6))
    ax.set_ylabel(f"fraction, vs {truth} (95% CI)")
    ax.set_title(title, fontsize=11)
    ax.legend(
        handles=[Patch(color=c, label=key) for _, key, c in bars],
        fontsize=9,
        loc="upper center",
        ncol=2,
    )
    return fig


def best_figure(
    summary: dict, best: list[dict], path: Path, family: DeviceFamily | None = None
) -> Path:
    """Drawings of the best designs (at most ``MAX_BEST_DRAWN``), each titled with its id and
    exit time; a design whose scene cannot be built says why in its panel. A device
    family's sweep gives its ``family``, whose devices are drawn."""
    shown = best[:MAX_BEST_DRAWN]
    environment = environment_from_dict(summary.get("feeder") or {}, prefix="feeder.")
    cols = min(len(shown), 3)
    rows = math.ceil(len(shown) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 5.2 * rows), squeeze=False)
    for ax in axes.ravel()[len(shown) :]:
        ax.axis("off")
    for ax, entry in zip(axes.ravel(), shown, strict=False):
        exit_time = number(entry.get("exit_time_s"))
        title = f"design {entry.get('design_id')}: exit " + (
            DASH if exit_time is None else f"{exit_time:.2f} s"
        )
        try:
            if family is not None:
                scene = family.build(list(entry.get("values") or []))
            else:
                design = DesignParameters.from_vector(entry.get("values") or [])
                scene = build_feeder(design, name=f"design {entry.get('design_id')}", **environment)
        except (DegenerateDesign, DesignError, ValueError) as exc:
            ax.text(
                0.5, 0.5, f"cannot draw:\n{exc}", ha="center", va="center", fontsize=7, wrap=True
            )
            ax.axis("off")
        else:
            draw_scene(ax, scene)
        ax.set_title(title, fontsize=9)
    fig.suptitle(
        f"{summary.get('name', 'sweep')}: the top designs by the sweep's own verdict", fontsize=11
    )
    return save_figure(fig, path)
