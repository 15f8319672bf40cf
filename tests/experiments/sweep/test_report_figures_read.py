"""The sweep report's figures read (issue 25): each answers one question with labelled axes,
the designs that pass stand out, a rung without planners is left out and said so, titles say
what is compared, and a chart of identical bars becomes a sentence."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from experiments.sweep.report_figures import (
    PLANNER_ROWS,
    feasible_set_plot,
    planners_plot,
    pruning_plot,
    pruning_title,
)
from experiments.sweep.report_verdicts import transitions_plot, transitions_sentence
from feeders.design import PARAMETER_NAMES, TABLE2_BOUNDS

LADDER = ["passive", "geometric"]


def _designs() -> dict:
    low = np.array([TABLE2_BOUNDS[n][0] for n in PARAMETER_NAMES])
    high = np.array([TABLE2_BOUNDS[n][1] for n in PARAMETER_NAMES])
    values = np.array([low + f * (high - low) for f in (0.1, 0.4, 0.6, 0.9)])
    status = {
        (1, "passive"): "feasible",
        (1, "geometric"): "feasible",
        (2, "passive"): "feasible",
        (2, "geometric"): "infeasible",
        (3, "passive"): "infeasible",
        (4, "passive"): "infeasible",
    }
    return {"ids": [1, 2, 3, 4], "values": values, "status": status, "runs": []}


def test_the_design_space_shows_each_parameter_on_a_labelled_axis_and_who_passes():
    fig = feasible_set_plot({"name": "t"}, LADDER, _designs())
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.get_xticklabels()] == list(PARAMETER_NAMES)
    assert "Table 2" in ax.get_ylabel() and "rad" in ax.get_xlabel()
    assert "2 of 4 designs pass passive, 1 every rung up to geometric" in ax.get_title()
    widths = sorted(
        {line.get_linewidth() for line in ax.get_lines() if len(line.get_xdata()) == 12}
    )
    assert len(widths) == 2 and widths[1] >= 2.5 * widths[0]  # passers drawn thick
    plt.close(fig)


def test_the_planners_figure_leaves_out_a_rung_without_planners_and_labels_its_rows():
    data = _designs()
    data["runs"] = [
        {"level": "geometric", "planner": "RRT", "time_s": t, "tree_size": 100 + t}
        for t in (0.1, 0.2, 0.3)
    ]
    summary = {
        "name": "t",
        "planners": [{"level": "geometric", "planner": "RRT", "solved_fraction": 1.0}],
    }
    fig = planners_plot(summary, LADDER, data)
    axes = [ax for ax in fig.axes]
    assert len(axes) == 3  # one column: geometric; passive has no planner
    assert [ax.get_ylabel() for ax in axes] == list(PLANNER_ROWS)
    assert axes[0].get_title() == "geometric"
    assert "passive left out" in fig.get_suptitle()
    plt.close(fig)


def test_the_pruning_title_names_the_truth_it_is_compared_with():
    summary = {"truth": "passive", "holdout": 8, "pruning": [{"level": "dynamic", "n": 8}]}
    title = pruning_title(summary, ["passive", "geometric", "dynamic"])
    assert "vs passive" in title and "vs dynamic" not in title and "8 holdout" in title
    assert "vs dynamic" in pruning_title({}, ["geometric", "dynamic"])
    fig = pruning_plot(summary, ["passive", "geometric", "dynamic"])
    assert "passive" in fig.axes[0].get_ylabel()
    plt.close(fig)


def _best(*matrices: dict) -> list[dict]:
    return [
        {"design_id": k, "verdict": {"transitions": m}} for k, m in enumerate(matrices, start=1)
    ]


def test_drops_that_all_end_one_way_are_a_sentence_not_a_chart():
    uniform = {"heavy_leading": {"heavy end down": 20}, "heavy_trailing": {"heavy end down": 10}}
    sentence = transitions_sentence(_best(uniform, uniform))
    assert sentence is not None
    assert "60 perturbed drops of all 2 designs" in sentence and "heavy end down" in sentence


def test_drops_that_end_several_ways_are_counted_in_the_chart():
    mixed = {"heavy_leading": {"heavy end down": 18, "heavy end up": 2}, "heavy_trailing": {}}
    best = _best(mixed)
    assert transitions_sentence(best) is None
    fig = transitions_plot({"name": "t"}, best)
    ax = fig.axes[0]
    assert ax.get_xlabel().startswith("drops")
    assert {t.get_text() for t in ax.get_legend().get_texts()} == {"heavy end down", "heavy end up"}
    assert "18" in {t.get_text() for t in ax.texts}
    plt.close(fig)
