"""The derivative-free optimisers compared by ``partfeeder optimize``, on the unit cube.

Every method minimises ``f``, which takes an (n, d) array of points of the unit cube (Table
2's box, scaled, d = 12; a device family's box, d its parameters) and returns their n
objective values: a whole generation at once for the population methods (evaluated in
parallel), one point at a time for the simplex and line-search methods (each point's trials
are then split over the workers). The budget is enforced by ``f``
(it raises :class:`experiments.optimize.evaluator.BudgetSpent`), so every method gets exactly
the same number of evaluations and stops only when spent or converged by its own test.

- ``differential-evolution`` (scipy): the starts and a scrambled Halton set fill the first
  population; best1bin, deferred updating (a generation is one batch), no gradient polish
  (the objective is piecewise constant in its first term).
- ``cma-es`` (``cma``, N. Hansen's reference implementation): from the best start, step 0.2
  of the box, bounds handled by its boundary transformation.
- ``nelder-mead`` (scipy, adaptive parameters for 12 dimensions, with bounds): from the best
  start, a simplex of edge 0.1 of the box.
- ``powell`` (scipy, with bounds): from the best start.

A method's seed: differential evolution and CMA-ES draw their own random numbers from it;
the local methods are deterministic, so seed s > 0 moves their start by a seeded uniform step
of up to 0.1 of the box per parameter (seed 0 starts at the best start itself).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

Objective = Callable[[np.ndarray], list[float]]

SIMPLEX_EDGE = 0.1
CMA_STEP = 0.2
START_JITTER = 0.1


def _jittered(start: np.ndarray, seed: int) -> np.ndarray:
    if seed == 0:
        return start.copy()
    rng = np.random.default_rng([seed, 1])
    return np.clip(start + rng.uniform(-START_JITTER, START_JITTER, start.shape), 0.0, 1.0)


def differential_evolution(
    f: Objective, starts: np.ndarray, budget: int, seed: int, population: int | None
) -> None:
    """scipy's differential evolution from ``starts`` (k, d) filled to ``population``."""
    from scipy.optimize import differential_evolution as scipy_de
    from scipy.stats import qmc

    dimension = starts.shape[1]
    size = max(population or 20, 5, len(starts))
    fill = qmc.Halton(dimension, scramble=True, rng=np.random.default_rng([seed, 2])).random(
        size - len(starts)
    )
    init = np.vstack([np.clip(starts, 0.0, 1.0), fill])

    def whole_generation(_func, points) -> list[float]:
        return f(np.asarray(list(points), dtype=float))

    def not_called(_u: np.ndarray) -> float:
        raise AssertionError("the objective is evaluated a generation at a time")

    scipy_de(
        not_called,
        [(0.0, 1.0)] * dimension,
        init=init,
        maxiter=max(1, budget),
        tol=0.0,
        atol=0.0,
        polish=False,
        updating="deferred",
        workers=whole_generation,
        rng=np.random.default_rng([seed, 3]),
    )


def cma_es(f: Objective, start: np.ndarray, budget: int, seed: int, population: int | None) -> None:
    """CMA-ES (``cma``) from ``start`` with step :data:`CMA_STEP` in the unit box."""
    import cma

    options = {
        "bounds": [0.0, 1.0],
        "seed": seed + 1,  # cma reads 0 as "draw a seed"
        "verbose": -9,
        "maxfevals": budget,
        "tolfun": 0.0,
        "tolflatfitness": 10**9,  # plateaus of the first term are expected, not a stop
    }
    if population is not None:
        options["popsize"] = population
    es = cma.CMAEvolutionStrategy(start.tolist(), CMA_STEP, options)
    while not es.stop():
        points = es.ask()
        es.tell(points, f(np.asarray(points, dtype=float)))


def nelder_mead(
    f: Objective, start: np.ndarray, budget: int, seed: int, population: int | None
) -> None:
    """scipy's Nelder-Mead (adaptive) with bounds, from a simplex of edge 0.1 of the box."""
    from scipy.optimize import minimize

    x0 = _jittered(start, seed)
    simplex = [x0]
    for i in range(len(x0)):
        vertex = x0.copy()
        vertex[i] += SIMPLEX_EDGE if vertex[i] + SIMPLEX_EDGE <= 1.0 else -SIMPLEX_EDGE
        simplex.append(vertex)
    minimize(
        lambda u: f(u[None, :])[0],
        x0,
        method="Nelder-Mead",
        bounds=[(0.0, 1.0)] * len(x0),
        options={
            "maxfev": 10 * budget + 100,
            "initial_simplex": np.array(simplex),
            "adaptive": True,
            "xatol": 1e-6,
            "fatol": 1e-9,
        },
    )


def powell(f: Objective, start: np.ndarray, budget: int, seed: int, population: int | None) -> None:
    """scipy's Powell with bounds."""
    from scipy.optimize import minimize

    x0 = _jittered(start, seed)
    minimize(
        lambda u: f(u[None, :])[0],
        x0,
        method="Powell",
        bounds=[(0.0, 1.0)] * len(x0),
        options={"maxfev": 10 * budget + 100, "xtol": 1e-4, "ftol": 1e-6},
    )


POPULATION_METHODS = {"differential-evolution"}
METHODS: dict[str, Callable[..., None]] = {
    "differential-evolution": differential_evolution,
    "cma-es": cma_es,
    "nelder-mead": nelder_mead,
    "powell": powell,
}
"""Name -> method; differential evolution takes every start, the others the best one."""
