"""The public way in: an OMPL planning problem for a design or a scene at any level.

:func:`problem` turns a design specification (a paper preset's name such as ``"table3"``, the
12 design values, a :class:`~feeders.design.DesignParameters`, a
:class:`~feeders.scene.Scene` or a scene YAML file's path: :mod:`feeders.scene_spec`) into
a :class:`~planners.plan.ControlProblem`: an ``oc.SimpleSetup`` with the level as validity
checker and state propagator, the start and the goal region, the propagation step and
control durations set, and the pose projection registered (KPIECE1, EST), ready for any OMPL
control planner and for OMPL's ``Benchmark``. :func:`level_of` gives a level alone, whose
checker and propagator (:mod:`planners.adapters`) fit a setup of one's own. See docs/api.md.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from feeders.scene_spec import DesignSpec, scene_of
from planners.plan import ControlProblem, PlannerSettings, control_problem
from validity import make_level


def level_of(design: DesignSpec, level: str = "geometric", **options: Any) -> Any:
    """The fidelity level ``level`` (``geometric`` Eq. 9, ``kinematic`` Eq. 8, ``dynamic``
    Eq. 7) on the scene of ``design``: ``is_valid(state)``, ``propagate(state, control,
    duration)`` on tuples, ``state_dim``, ``control_dim``, ``control_bounds()``. ``options``
    go to the level (e.g. ``step``, its own integration step h in seconds)."""
    return make_level(level, scene_of(design), **options)


def problem(
    design: DesignSpec,
    level: str = "geometric",
    orientation: str | None = None,
    *,
    seed: int = 1,
    settings: PlannerSettings | None = None,
    level_options: Mapping[str, Any] | None = None,
) -> ControlProblem:
    """The problem of moving the part from the start ``orientation`` of ``design``'s scene
    (default: its first start, the feeder's ``heavy_leading`` entry) into its goal region
    with the level ``level``.

    ``seed`` seeds OMPL's process-wide generator now (so a planner made after this call
    draws the same sequence) and the goal sampler. ``settings``: the propagation step
    (default 0.05 s) and how many steps a control lasts (1..20), as the sweep's config
    sets them. ``level_options`` go to the level (e.g. ``{"step": 1e-3}``). The problem
    counts its validity checks and propagations (``p.propagations``), so that
    ``p.termination(time, propagations=N)`` gives a budget that does not depend on the
    machine. Raises ValueError (a one-line message naming the field) for a bad design, an
    unknown level or orientation.
    """
    scene = scene_of(design)
    start = orientation if orientation is not None else next(iter(scene.starts))
    scene.start(start)  # an unknown orientation is named before any OMPL object is made
    return control_problem(
        scene, level, start, seed, settings, dict(level_options or {}), count=True
    )
