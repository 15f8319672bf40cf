"""The optimisers on an analytic objective (reference: a known minimum in the unit cube):
each improves its start, stays in the box, spends no more than its budget, and the same seed
gives the same sequence of points."""

import numpy as np
import pytest

from experiments.optimize.evaluator import BudgetSpent
from experiments.optimize.methods import METHODS, POPULATION_METHODS

MINIMUM = np.linspace(0.2, 0.8, 12)


class Budgeted:
    """A stand-in for the evaluator: a shifted sphere, every point recorded, BudgetSpent past
    the budget (as Evaluator.batch)."""

    def __init__(self, budget):
        self.budget = budget
        self.points = []

    def __call__(self, unit):
        unit = np.asarray(unit, dtype=float)
        room = self.budget - len(self.points)
        take = unit[:room]
        self.points.extend(p.copy() for p in take)
        values = [float(np.sum((p - MINIMUM) ** 2)) for p in take]
        if len(unit) > room:
            raise BudgetSpent("test")
        return values


def run(method, budget=300, seed=0):
    f = Budgeted(budget)
    start = np.full(12, 0.95)
    first = np.vstack([start, np.full(12, 0.05)]) if method in POPULATION_METHODS else start
    try:
        METHODS[method](f, first, budget, seed, None)
    except BudgetSpent:
        pass
    return f


@pytest.mark.parametrize("method", sorted(METHODS))
def test_improves_its_start_inside_the_box_within_budget(method):
    f = run(method)
    points = np.array(f.points)
    start_value = float(np.sum((np.full(12, 0.95) - MINIMUM) ** 2))
    best = min(float(np.sum((p - MINIMUM) ** 2)) for p in points)
    assert len(points) <= 300
    assert np.all(points >= 0.0) and np.all(points <= 1.0)
    assert best < 0.5 * start_value


@pytest.mark.parametrize("method", sorted(METHODS))
def test_same_seed_same_points(method):
    a, b = run(method, budget=60, seed=3), run(method, budget=60, seed=3)
    assert np.array_equal(np.array(a.points), np.array(b.points))
