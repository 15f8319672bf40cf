"""The names users type: levels, OMPL planners and paper presets, without importing them.

The command line offers these as choices and the sweep's config checks against them; importing
the real registries (``validity.LEVELS`` loads numba, ``planners.registry.PLANNERS`` loads OMPL,
``feeders.design.PRESETS`` loads NumPy) would make ``partfeeder --help`` as slow as those
imports. ``tests/experiments/test_names.py`` checks that these lists equal the registries.
"""

from __future__ import annotations

# validity.LEVELS, in the order of the ladder (the order matters: a sweep climbs it).
LEVEL_NAMES = ("geometric", "kinematic", "dynamic")
# The passive rung of a sweep: the design's verdict (experiments.drop.verdict), success
# probability over perturbed passive drops; not a planning level, so not in validity.LEVELS.
PASSIVE = "passive"
# The necessary-conditions rung (validity.necessary): exact geometric tests that a design which
# fails them cannot work; cheap (about 7 ms a design), so it may stand before the verdict and
# prune without losing a design that works (docs/necessary.md).
NECESSARY = "necessary"
# The screen rung (experiments.drop.screen): the verdict's drops at a coarser step, one entry at
# a time, by a sequential test that can only fail a design, with a stated error (0.001 for a
# design that works at p = 0.95); it prunes most failing designs at a fraction of the verdict's
# cost (docs/verdict.md).
SCREEN = "screen"
# The rungs that judge by passive drops with the dynamic level (their kernels are its).
DROP_RUNGS = (PASSIVE, SCREEN)
# What a rung of a sweep's ladder can be.
RUNG_NAMES = (*LEVEL_NAMES, PASSIVE, NECESSARY, SCREEN)
# planners.registry.PLANNERS, in its order.
PLANNER_NAMES = ("rrt", "kpiece", "est")
# feeders.design.PRESETS: the paper's designs (Figs. 4-9, Table 3).
PRESET_NAMES = (
    "fig4",
    "fig5a",
    "fig5b",
    "fig6a",
    "fig6b",
    "fig7a",
    "fig7b",
    "fig8a",
    "fig8b",
    "fig9",
    "table3",
)
# Where a sweep's jobs run (experiments.executors): local processes or a Dask cluster.
EXECUTOR_NAMES = ("local", "dask")
# Derivative-free optimisers of ``partfeeder optimize`` (experiments.optimize.methods).
OPTIMIZER_NAMES = ("differential-evolution", "cma-es", "nelder-mead", "powell")
