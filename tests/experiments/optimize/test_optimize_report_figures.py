"""The optimiser's convergence figure reads (issue 25): plain tick labels, no flat P(both)
panel, and a sentence when a run's best came near the end of its budget."""

from __future__ import annotations

import matplotlib.pyplot as plt

from experiments.optimize.report import (
    convergence_notes,
    convergence_plot,
    objective_scale,
    p_both_flat,
)
from experiments.report_kit.figures import PLAIN_TICKS


def _results(p_values: list[float], at: int, budget: int = 480) -> dict:
    curve = [[n + 1, 17.0 - n * 0.03, p, 6.0] for n, p in enumerate(p_values)]
    return {
        "objective": {"trials": 16},
        "runs": [
            {
                "method": "differential-evolution",
                "seed": 0,
                "budget": budget,
                "evaluations": len(curve),
                "best": {"at": at, "value": curve[at - 1][1], "both": 16},
                "curve": curve,
            }
        ],
    }


def test_a_flat_p_both_panel_is_left_out_and_a_moving_one_kept():
    flat = _results([1.0] * 10, at=10, budget=10)
    assert p_both_flat(flat)
    fig = convergence_plot(flat)
    assert len(fig.axes) == 2
    assert "1.000" in fig.get_suptitle()
    plt.close(fig)
    moving = _results([0.5] * 5 + [1.0] * 5, at=10, budget=10)
    fig = convergence_plot(moving)
    assert [ax.get_xlabel() for ax in fig.axes] == ["evaluations"] * 3
    assert all(ax.get_ylabel() for ax in fig.axes)
    plt.close(fig)


def test_the_objective_axis_is_linear_below_one_failed_trial_and_its_ticks_are_plain():
    assert objective_scale([0.36, 0.40]) == "linear"
    assert objective_scale([0.36, 12.4]) == "symlog"
    assert PLAIN_TICKS(0.404842, 0) == "0.405"
    assert PLAIN_TICKS(362631.0, 0) == "3.63e+05"


def test_a_best_found_in_the_last_tenth_of_the_budget_is_called_not_converged():
    late = _results([1.0] * 480, at=470)
    assert convergence_notes(late) == [
        "differential-evolution, seed 0: not converged: the best was found at evaluation "
        "470 of 480."
    ]
    assert convergence_notes(_results([1.0] * 480, at=200)) == []
    first = convergence_notes(_results([1.0] * 40, at=1, budget=40))
    assert first and "none of the other 39 improved" in first[0]
