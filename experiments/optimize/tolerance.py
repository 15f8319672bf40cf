"""The tolerance margins of the optimum (:mod:`experiments.margins`), measured once the
optimisation is done and stored with it.

The margins use the optimisation's scene (part, friction, restitution: the config's
``feeder``), its drop settings (``objective.step``, ``objective.t_max``), its perturbations,
the target of its final verdicts (``final.target``), ``MARGIN_DROPS`` trials per value and
their own seed, ``final.seed + MARGIN_SEED_OFFSET`` (neither the validation's draws, seed
``final.seed``, nor the reported verdicts', ``final.seed + 1``). They are stored in the
optimisation's database under the design and a digest of those settings, so a run started
again in the same directory measures nothing again.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import sqlite3
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from experiments.optimize import store
from experiments.optimize.config import OptimizeConfig

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

MARGIN_DROPS = 20  # trials per value tried (the margins command's default)
MARGIN_SEED_OFFSET = 2  # the margins' draws: seed final.seed + 2
AXES = 16  # the 12 design parameters, friction, the part's length, width and mass split

AxisCallback = Callable[[Any], object]


def margin_settings(config: OptimizeConfig) -> Any:
    """The :class:`experiments.margins.measure.MarginSettings` of ``config``'s optimum."""
    from experiments.drop.perturbations import Perturbations
    from experiments.margins.measure import MarginSettings

    return MarginSettings(
        drops=MARGIN_DROPS,
        target=config.final_target,
        seed=config.final_seed + MARGIN_SEED_OFFSET,
        step=config.step,
        t_max=config.t_max,
        perturbations=Perturbations(**config.perturbations),
    )


def settings_key(config: OptimizeConfig) -> str:
    """A digest of what decides the margins of a design: the settings and the scene."""
    settings = dataclasses.asdict(margin_settings(config))
    text = json.dumps({"settings": settings, "feeder": config.feeder}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def robust_settings(config: OptimizeConfig) -> Any:
    """The :class:`experiments.margins.measure.MarginSettings` of the robust objective's
    evaluations (issue 34): the optimum's (:func:`margin_settings`) with
    ``centering.drops`` trials per value."""
    return dataclasses.replace(margin_settings(config), drops=config.centering.drops)


def robust_settings_key(config: OptimizeConfig) -> str:
    """A digest of what decides a robust evaluation: :func:`robust_settings`, the scene, and
    that only the device's axes are measured (not the part's)."""
    settings = dataclasses.asdict(robust_settings(config))
    text = json.dumps(
        {"settings": settings, "feeder": config.feeder, "axes": "device"}, sort_keys=True
    )
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def device_margins_of(
    subject: Any, settings: Any, workers: int = 1, on_axis: AxisCallback | None = None
) -> Any:
    """:func:`experiments.margins.run.margins_of` over the device's axes only (the design's
    parameters and mu; a feeder's part axes left out: robustness never reads them)."""
    from experiments.margins.robustness import DEVICE_KINDS
    from experiments.margins.run import margins_of

    return margins_of(subject, settings, workers, on_axis=on_axis, kinds=DEVICE_KINDS)


def _stored_or_measured(
    db: sqlite3.Connection,
    config: OptimizeConfig,
    key: str,
    subject: Callable[[], Any],
    workers: int,
    on_axis: AxisCallback | None,
    measure: Callable[..., Any] | None,
    robust: bool = False,
) -> dict[str, Any]:
    """The margins of design ``key``: stored ones when measured before with the same
    settings, else those of ``subject()`` (made only then) measured on ``workers`` processes
    (``on_axis`` called as each axis finishes) and stored. ``measure`` replaces
    :func:`experiments.margins.run.margins_of` (tests count calls). ``robust``: the robust
    objective's evaluation (:func:`robust_settings`, the device's axes only)."""
    digest = robust_settings_key(config) if robust else settings_key(config)
    stored = store.stored_margins(db, key, digest)
    if stored is not None:
        return stored
    from experiments.margins.run import margins_of

    run = measure or (device_margins_of if robust else margins_of)
    settings = robust_settings(config) if robust else margin_settings(config)
    data = run(subject(), settings, workers, on_axis=on_axis).to_dict()
    store.record_margins(db, key, digest, data)
    return data


def optimum_margins(
    db: sqlite3.Connection,
    config: OptimizeConfig,
    key: str,
    label: str = "optimum",
    workers: int = 1,
    on_axis: AxisCallback | None = None,
    measure: Callable[..., Any] | None = None,
    robust: bool = False,
) -> dict[str, Any]:
    """The margins of the feeder's design ``key`` (:meth:`experiments.margins.run.
    MarginsReport.to_dict`, named ``label``), stored or measured (:func:`_stored_or_measured`)
    on the config's feeder: its 16 axes."""

    def subject() -> Any:
        from experiments.margins.measure import Subject
        from feeders.design import DesignParameters
        from feeders.feeder import build_feeder
        from feeders.scene_yaml import environment_from_dict

        environment = environment_from_dict(config.feeder)
        part, friction = environment.pop("part"), environment.pop("friction")
        scene = build_feeder(
            DesignParameters.from_vector(store.design_of_key(key)),
            part,
            friction=friction,
            name=label,
            **environment,
        )
        return Subject.of_scene(scene)

    return _stored_or_measured(db, config, key, subject, workers, on_axis, measure, robust)


def family_margins(
    db: sqlite3.Connection,
    config: OptimizeConfig,
    family: DeviceFamily,
    key: str,
    label: str = "optimum",
    workers: int = 1,
    on_axis: AxisCallback | None = None,
    measure: Callable[..., Any] | None = None,
    robust: bool = False,
) -> dict[str, Any]:
    """The margins of the device family's design ``key``, named ``label``, stored or measured
    as the feeder's (:func:`_stored_or_measured`): the axes the family's parameters over its
    box and friction (:class:`experiments.margins.measure.FamilySubject`, the family's text
    from the config)."""

    def subject() -> Any:
        from experiments.margins.measure import FamilySubject

        vector = store.design_of_key(key)
        return FamilySubject.of_family(family, config.family_yaml, vector, name=label)

    return _stored_or_measured(db, config, key, subject, workers, on_axis, measure, robust)
