"""The verdict and the screen of a device family's design (issue 24).

A family (:mod:`feeders.device_family`) is a parametric device: a vector of its n named
parameters builds a scene. Its verdict is the 12-parameter feeder's
(:mod:`experiments.drop.verdict`, :mod:`experiments.drop.screen`) with the feeder replaced by
the family's device as made: per trial each parameter times its own factor (uniform in
``1 +- tolerance``, the feeder's "each design parameter +-1%"), the walls' friction times the
part batch's factor, and the part dropped from each of the family's entries (their names, in
the file's order, are the verdict's orientations).

Nothing clamps the made values: a family's box is what a sweep samples, not what can be built,
and a made value may leave it (a design at the box's edge made 1% over). The family's rules
and the build's checks decide; a made device they refuse is a failed trial from every entry,
as an unbuildable toleranced feeder is (:data:`experiments.drop.verdict.UNBUILDABLE`).

The outcome classes (:func:`experiments.drop.outcomes.classify`) are named by the family's
orientations (``orientations:``; the peg's "heavy end down" / "heavy end up" when it names
none): a drop in the goal is the goal's class, one below the goal's top the class of its final
yaw, else "stopped in the cavity" (at rest anywhere else), "still moving at t_max", "left the
bounds" or a simulation fault. Fig. 1's landmarks (pin, lip, funnel) name outcomes only for
the 12-parameter feeder.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from experiments.drop.perturbations import DropDraw, toleranced_values
from experiments.drop.screen import Screen, screen_of
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.verdict import Verdict, verdict_of
from experiments.drop.verdict_settings import VerdictSettings
from feeders.feeder_family import Family
from feeders.part import Peg
from feeders.scene import Scene

Vector = Mapping[str, float] | Sequence[float] | np.ndarray


def entry_names(family: Family) -> tuple[str, ...]:
    """The family's entry orientations, in the file's order: the verdict's orientations."""
    return tuple(name for name, _ in family.entries)


def made_devices(
    family: Family,
    values: Vector,
    part: Peg | None = None,
    friction: float | None = None,
) -> Callable[[DropDraw], Scene]:
    """The device of ``values`` (n numbers in ``family.vector_names`` order, or a mapping) as
    made for one trial's draw, for :func:`experiments.drop.verdict.run_trial`: each parameter
    times its design factor, kept within ``family.made_bounds()`` (a YAML family's are none:
    its rules decide; the paper's feeder, :class:`feeders.feeder_family.FeederFamily`, keeps
    within what can be built, as its verdict always has), the walls' friction (None: the
    family's) times the draw's friction factor; ``part`` (None: the family's) replaces the
    family's part. Raises :class:`feeders.feeder.DegenerateDesign` at once if the nominal
    vector cannot be built, ``ValueError`` if the vector is not the family's."""
    if part is not None:
        family = dataclasses.replace(family, part=part)
    nominal = tuple(family.values(values).values())
    n = len(nominal)
    family.build(nominal)
    mu = family.friction if friction is None else float(friction)

    limits = family.made_bounds()
    low, high = limits if limits is not None else (None, None)

    def make_scene(d: DropDraw) -> Scene:
        made = toleranced_values(nominal, d.design_factors[:n], low, high)
        scene = family.build(made)
        return dataclasses.replace(scene, friction=mu * d.friction_factor)

    return make_scene


def family_verdict(
    family: Family,
    values: Vector,
    settings: VerdictSettings | None = None,
    seed: int = 0,
    *,
    part: Peg | None = None,
    friction: float | None = None,
) -> Verdict:
    """The verdict of the family's design ``values``: trials of :func:`made_devices` from
    every entry of the family (:func:`entry_names`) until decided, as
    :func:`experiments.drop.verdict.verdict_of` decides. Raises
    :class:`feeders.feeder.DegenerateDesign` if the nominal vector cannot be built."""
    make_scene = made_devices(family, values, part, friction)
    n = len(family.vector_names)
    return verdict_of(make_scene, entry_names(family), settings or VerdictSettings(), seed, n)


def family_screen(
    family: Family,
    values: Vector,
    settings: ScreenSettings | None = None,
    seed: int = 0,
    *,
    part: Peg | None = None,
    friction: float | None = None,
) -> Screen:
    """The screen of the family's design ``values`` (:func:`experiments.drop.screen.screen_of`)
    over the family's entries, devices made as the verdict makes them. Raises
    :class:`feeders.feeder.DegenerateDesign` if the nominal vector cannot be built."""
    make_scene = made_devices(family, values, part, friction)
    n = len(family.vector_names)
    return screen_of(make_scene, entry_names(family), settings or ScreenSettings(), seed, n)
