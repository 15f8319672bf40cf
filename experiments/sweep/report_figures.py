"""The figures of a sweep's report (PNG, matplotlib Agg): survivors per level, the feasible
set in design space, planner run times and tree sizes, pruning precision and recall, and the
best designs drawn. Each takes the summary (and the database's verdicts and runs where it
needs them) and writes one file; a figure without data says so instead of failing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Patch

from experiments.pictures.scenes import draw_scene, save_figure
from experiments.report_kit.cells import DASH, cell, number
from feeders.design import PARAMETER_NAMES, TABLE2_BOUNDS, DesignError, DesignParameters
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.scene_yaml import environment_from_dict

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
    fig, ax = plt.subplots(figsize=size)
    ax.text(0.5, 0.5, message, ha="center", va="center", fontsize=11, color="#555555")
    ax.axis("off")
    return save_figure(fig, path)


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
    """The feasible set Z_F in design space (as the paper's Fig. 2): a scatter matrix of the
    12 parameters (lower triangle; stacked histograms on the diagonal), each design coloured
    by the highest level of the ladder it passed, axes limited to Table 2's box."""
    values = data["values"]
    if len(values) == 0:
        return _empty_figure(path, "no designs in the results database yet")
    passed = np.array([highest_passed(i, ladder, data["status"]) for i in data["ids"]])
    classes = ["none", *ladder]
    colours = [NONE_COLOUR] + [_level_colour(k, level) for k, level in enumerate(ladder)]
    n = len(PARAMETER_NAMES)
    fig = plt.figure(figsize=(14, 14))
    for i in range(n):  # row: the y parameter
        for j in range(i + 1):  # column: the x parameter (lower triangle: half the axes)
            ax = fig.add_subplot(n, n, i * n + j + 1)
            xlim = TABLE2_BOUNDS[PARAMETER_NAMES[j]]
            if i == j:
                ax.hist(
                    [values[passed == k, j] for k in range(len(classes))],
                    bins=12,
                    range=xlim,
                    stacked=True,
                    color=colours,
                )
                ax.set_yticks([])
            else:
                for k in range(len(classes)):  # higher levels drawn last, on top
                    chosen = passed == k
                    if chosen.any():
                        ax.scatter(
                            values[chosen, j],
                            values[chosen, i],
                            s=4,
                            c=colours[k],
                            linewidths=0,
                        )
                ax.set_ylim(*TABLE2_BOUNDS[PARAMETER_NAMES[i]])
                ax.locator_params(axis="y", nbins=3)
            ax.set_xlim(*xlim)
            ax.locator_params(axis="x", nbins=3)
            ax.tick_params(labelsize=6, length=2, pad=1)
            if i == n - 1:
                ax.set_xlabel(PARAMETER_NAMES[j], fontsize=9)
            else:
                ax.set_xticklabels([])
            if j == 0:
                ax.set_ylabel(PARAMETER_NAMES[i], fontsize=9)
            elif i != j:
                ax.set_yticklabels([])
    handles = [
        Patch(color=colour, label=f"{name} ({int(np.sum(passed == k))})")
        for k, (name, colour) in enumerate(zip(classes, colours, strict=True))
    ]
    fig.legend(
        handles=handles,
        loc="upper right",
        bbox_to_anchor=(0.97, 0.95),
        fontsize=11,
        title="highest level passed",
        title_fontsize=11,
    )
    fig.suptitle(
        f"{summary.get('name', 'sweep')}: feasible set Z_F of {len(values)} designs (Table 2 box)",
        fontsize=13,
    )
    return save_figure(fig, path, dpi=80)


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


def planners_figure(summary: dict, ladder: list[str], data: dict, path: Path) -> Path:
    """Planner comparison per level, as Planner Arena: one column per level, rows with the
    run time box plots (from the runs table), the solved fraction (from the summary) and
    the tree size box plots. A planner keeps its colour across levels."""
    stats = list(summary.get("planners") or [])
    levels = list(ladder) or sorted({str(r["level"]) for r in data["runs"]})
    if not levels:
        return _empty_figure(path, "no levels in the summary")
    planners: list[str] = []
    for row in [*stats, *data["runs"]]:
        if str(row.get("planner")) not in planners and row.get("planner") is not None:
            planners.append(str(row["planner"]))
    colour_of = {p: PLANNER_COLOURS[k % len(PLANNER_COLOURS)] for k, p in enumerate(planners)}
    fig, axes = plt.subplots(
        3, len(levels), figsize=(max(4.5, 3.6 * len(levels)), 8.5), squeeze=False
    )
    for col, level in enumerate(levels):
        runs = [r for r in data["runs"] if r["level"] == level]
        level_stats = {str(s.get("planner")): s for s in stats if s.get("level") == level}
        names = [p for p in planners if p in level_stats or any(r["planner"] == p for r in runs)]
        time_ax, solved_ax, tree_ax = axes[:, col]
        time_ax.set_title(level, fontsize=10)
        if not names:
            for ax in (time_ax, solved_ax, tree_ax):
                ax.set_xticks([])
                ax.set_yticks([])
            solved_ax.text(0.5, 0.5, "no runs yet", ha="center", va="center", color="#555555")
            continue
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
            solved_ax.text(k, (f or 0.0) + 0.02, label, ha="center", fontsize=8)
        solved_ax.set_ylim(0, 1.12)
        for ax in (time_ax, solved_ax, tree_ax):
            ax.set_xticks(range(len(names)), names, fontsize=8)
            ax.set_xlim(-0.6, len(names) - 0.4)
            ax.tick_params(axis="y", labelsize=7)
        if col == 0:
            time_ax.set_ylabel("run time (s)")
            solved_ax.set_ylabel("solved fraction")
            tree_ax.set_ylabel("tree size (states)")
    fig.suptitle(f"{summary.get('name', 'sweep')}: planners per level", fontsize=11)
    return save_figure(fig, path)


def pruning_figure(summary: dict, ladder: list[str], path: Path) -> Path:
    """Precision and recall of each lower level's verdict against the top level's, on the
    holdout, with their confidence intervals as error bars."""
    rows = list(summary.get("pruning") or [])
    if not rows:
        return _empty_figure(path, "no holdout: the pruning is not measured")
    top = ladder[-1] if ladder else "the top level"
    fig, ax = plt.subplots(figsize=(max(5.0, 2.2 * len(rows) + 2.0), 4.2))
    width = 0.36
    bars = ((-width / 2, "precision", "#6a51a3"), (width / 2, "recall", "#41ab5d"))
    for offset, key, colour in bars:
        labelled = False
        for k, row in enumerate(rows):
            value = number(row.get(key))
            if value is None:
                ax.text(k + offset, 0.02, "n/a", ha="center", fontsize=9, color="#555555")
                continue
            ci = row.get(f"{key}_ci") or [None, None]
            low, high = number(ci[0]), number(ci[1])
            yerr = None
            if low is not None and high is not None:
                yerr = [[max(0.0, value - low)], [max(0.0, high - value)]]
            ax.bar(
                k + offset,
                value,
                width,
                yerr=yerr,
                capsize=5,
                color=colour,
                label=None if labelled else key,
            )
            labelled = True
            ax.text(k + offset, value / 2, f"{value:.2f}", ha="center", fontsize=8, color="w")
    labels = [f"{row.get('level', '?')}\n(n = {cell(row.get('n'))})" for row in rows]
    ax.set_xticks(range(len(rows)), labels)
    ax.set_xlim(-0.6, len(rows) - 0.4)
    ax.set_ylim(0, 1.25)
    ax.set_yticks(np.linspace(0.0, 1.0, 6))
    ax.set_ylabel("vs the top level (95% CI)")
    ax.set_title(f"pruning of the lower levels vs {top}, on the holdout", fontsize=10)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="upper center", ncol=2)
    return save_figure(fig, path)


def best_figure(summary: dict, best: list[dict], path: Path) -> Path:
    """Drawings of the best designs (at most ``MAX_BEST_DRAWN``), each titled with its id and
    exit time; a design whose scene cannot be built says why in its panel."""
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
            design = DesignParameters.from_vector(entry.get("values") or [])
            scene = build_feeder(design, name=f"design {entry.get('design_id')}", **environment)
        except (DegenerateDesign, DesignError) as exc:
            ax.text(
                0.5, 0.5, f"cannot draw:\n{exc}", ha="center", va="center", fontsize=7, wrap=True
            )
            ax.axis("off")
        else:
            draw_scene(ax, scene)
        ax.set_title(title, fontsize=9)
    fig.suptitle(f"{summary.get('name', 'sweep')}: best designs", fontsize=11)
    return save_figure(fig, path)
