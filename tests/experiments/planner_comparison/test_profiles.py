"""Performance profiles (Dolan and Moré 2002) and the cost they rank by, against a case
worked by hand and against a numerical integration of the profile."""

from __future__ import annotations

import math

import numpy as np
import pytest

from experiments.planner_comparison import profiles

INF = math.inf
# three problems x planners A, B, C (costs in propagations)
COSTS = np.array([[10.0, 20.0, INF], [30.0, 10.0, 15.0], [5.0, INF, 20.0]])
# by hand: each row over its smallest entry
RATIOS = np.array([[1.0, 2.0, INF], [3.0, 1.0, 1.5], [1.0, INF, 4.0]])


def test_ratios_are_each_cost_over_the_problems_best() -> None:
    assert np.array_equal(profiles.ratio_matrix(COSTS), RATIOS)


def test_a_problem_no_planner_solved_has_no_ratios() -> None:
    with pytest.raises(ValueError, match="no planner solved"):
        profiles.ratio_matrix(np.array([[INF, INF]]))


def test_the_profile_counts_problems_within_a_factor_tau_of_the_best() -> None:
    rho = profiles.profile(RATIOS, [1.0, 1.5, 2.0, 3.0, 4.0, 100.0])
    # hand count, A B C per row: tau = 1: A best on P1, P3; B on P2; C on none ...
    expected = np.array(
        [
            [2 / 3, 1 / 3, 0.0],
            [2 / 3, 1 / 3, 1 / 3],
            [2 / 3, 2 / 3, 1 / 3],
            [1.0, 2 / 3, 1 / 3],
            [1.0, 2 / 3, 2 / 3],
            [1.0, 2 / 3, 2 / 3],  # a planner that never solved P stays below 1
        ]
    )
    assert np.allclose(rho, expected)


def test_the_horizon_is_log2_of_the_largest_finite_ratio() -> None:
    assert profiles.horizon(RATIOS) == pytest.approx(2.0)
    assert profiles.horizon(np.ones((2, 2))) == 1.0  # never below one doubling


def test_the_profile_area_by_hand() -> None:
    # share of problem p: max(0, 1 - log2 r / L) with L = 2
    area = profiles.profile_area(RATIOS, 2.0)
    expected = [
        (1 + (1 - math.log2(3) / 2) + 1) / 3,
        ((1 - 1 / 2) + 1 + 0) / 3,
        (0 + (1 - math.log2(1.5) / 2) + (1 - 2 / 2)) / 3,
    ]
    assert area == pytest.approx(expected)


def test_the_profile_area_is_the_integral_of_the_step_profile_over_log2_tau() -> None:
    # an independent reference: the profile on a fine grid of log2 tau, integrated
    grid = np.linspace(0.0, 2.0, 200_001)
    rho = profiles.profile(RATIOS, 2.0**grid)
    numeric = rho[:-1].mean(axis=0)  # left Riemann sum over [0, 2], divided by 2
    assert profiles.profile_area(RATIOS, 2.0) == pytest.approx(numeric, abs=1e-4)


def test_cost_to_solve_is_all_runs_propagations_over_the_runs_solved() -> None:
    runs = [
        {"solved": True, "propagations": 100},
        {"solved": False, "propagations": 1000},
        {"solved": True, "propagations": 300},
    ]
    assert profiles.cost_to_solve(runs) == 700.0
    assert profiles.cost_to_solve([{"solved": False, "propagations": 5}]) == INF


def test_the_bootstrap_of_a_planner_best_on_every_problem() -> None:
    ratios = np.array([[1.0, 2.0], [1.0, 4.0], [1.0, INF]])
    boot = profiles.bootstrap_best(ratios, 2.0, 500, seed=3)
    assert boot["best_share"].tolist() == [1.0, 0.0]
    assert boot["low"][0] == boot["high"][0] == 1.0
    assert 0.0 <= boot["low"][1] <= boot["area"][1] <= boot["high"][1] <= 0.5


def test_the_bootstrap_is_seeded() -> None:
    a = profiles.bootstrap_best(RATIOS, 2.0, 200, seed=7)
    b = profiles.bootstrap_best(RATIOS, 2.0, 200, seed=7)
    assert all(np.array_equal(a[k], b[k]) for k in a)


def test_a_tie_shares_the_resample() -> None:
    boot = profiles.bootstrap_best(np.ones((4, 2)), 1.0, 50, seed=1)
    assert boot["best_share"].tolist() == [0.5, 0.5]


def test_the_ecdf_is_a_fraction_of_all_runs() -> None:
    xs, ys = profiles.ecdf([30, 10, 20], total=6)
    assert xs == [10.0, 20.0, 30.0]
    assert ys == [1 / 6, 2 / 6, 3 / 6]
