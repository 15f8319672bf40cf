"""P(both) at one value of one axis, with common random numbers, and one axis's margin.

Every value of an axis is judged on the same trials: trial i uses the verdict's draw i
(:func:`experiments.drop.perturbations.draw` with the same seed: entry pose and velocity per
entry, friction factor, manufacturing factor of each design parameter), except the
perturbation of the axis varied, which is set to the value exactly (a design parameter made
without tolerance, mu without its per-part factor; the part is not perturbed by the verdict).
So two values differ by the axis only, and the comparison between them is not sampling noise.
A trial whose drop ends inside a wall (a fault of the simulation) is left out and the next
draw taken, as the verdict does.

A device family's design (:class:`FamilySubject`, issue 24) is judged the same way on the
family's verdict trials (:func:`experiments.drop.family_verdict.made_devices`: each parameter
times its factor of the draw, the family's entries, ``parameters=n`` factors per draw): trial
i at a value is the family verdict's trial i with the varied parameter's factor set to 1 and
its value set exactly (mu: the friction factor set to 1). A value whose nominal device cannot
be built is judged as the verdict judges an unbuildable made device: failed trials.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.perturbations import DropDraw, Perturbations, toleranced
from experiments.drop.verdict import run_trial
from experiments.drop.verdict_settings import VerdictSettings
from experiments.family_config import family_of_text
from experiments.margins.axes import DESIGN, FRICTION, PART, Axis
from experiments.margins.search import (
    LOOK,
    Bracket,
    Estimate,
    NominalFailed,
    Sampler,
    nominal_estimate,
    required,
    search,
)
from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.part import Peg
from feeders.scene import InputSet, Scene

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily


@dataclass(frozen=True)
class Subject:
    """The design whose margins are measured, as plain data for a worker: the 12 values, the
    part as two halves (length, width, mass, heavy half's share), mu and the feeder's other
    options."""

    design: DesignParameters
    length: float
    width: float
    mass: float
    heavy_fraction: float
    friction: float
    gravity: tuple[float, float] = (0.0, -9.81)
    restitution: float = 0.3
    inputs: InputSet = field(default_factory=InputSet)
    name: str = "feeder"

    @classmethod
    def of_scene(cls, scene: Scene) -> Subject:
        """The subject of a feeder scene; the part's mass split from its centre-of-mass
        offset, c = (h - 1/2) L / 2 (:func:`feeders.part.two_density_moments`)."""
        if scene.design is None:
            raise ValueError("margins need a feeder design, not a free-form scene")
        part = scene.part
        heavy = min(1.0, max(0.5, 0.5 + 2.0 * part.com_offset / part.length))
        return cls(
            scene.design,
            part.length,
            part.width,
            part.mass,
            heavy,
            scene.friction,
            tuple(scene.gravity),  # type: ignore[arg-type]
            scene.restitution,
            scene.inputs,
            scene.name,
        )

    @property
    def orientations(self) -> tuple[str, ...]:
        """The entries a trial drops the part from: the feeder's two."""
        return tuple(ORIENTATIONS)

    @property
    def parameters(self) -> int:
        """Design factors per draw: the feeder's 12."""
        return len(PARAMETER_NAMES)

    @property
    def values(self) -> dict[str, float]:
        """The design's values by parameter name."""
        return dict(zip(PARAMETER_NAMES, self.design.to_vector().tolist(), strict=True))

    def value(self, axis: Axis) -> float:
        """The nominal value of ``axis``."""
        if axis.kind == DESIGN:
            return float(getattr(self.design, axis.name))
        if axis.kind == FRICTION:
            return self.friction
        return float(getattr(self, axis.name))


@dataclass(frozen=True)
class FamilySubject:
    """A device family's design whose margins are measured (issue 24), as plain data for a
    worker: the family file's text (read by :func:`experiments.family_config.family_of_text`
    with ``family_name``: a worker on another machine has no such file), the design's
    ``vector`` in the family's parameter order, the parameters' and entries' names, the walls'
    mu (the family's unless the caller gave another) and the design's label ``name``."""

    text: str
    family_name: str
    vector: tuple[float, ...]
    names: tuple[str, ...]
    entries: tuple[str, ...]
    friction: float
    name: str

    @classmethod
    def of_family(
        cls,
        family: DeviceFamily,
        text: str,
        vector: Sequence[float],
        name: str | None = None,
        friction: float | None = None,
    ) -> FamilySubject:
        """The subject of ``family`` (read from ``text``: ValueError when the text is another
        family) at ``vector``; ``name`` defaults to the family's name."""
        if family_of_text(text, family.name) != family:
            raise ValueError(f"the text given is not the family {family.name}'s")
        values = family.values(vector)
        return cls(
            text,
            family.name,
            tuple(float(v) for v in values.values()),
            tuple(values),
            entry_names(family),
            family.friction if friction is None else float(friction),
            family.name if name is None else name,
        )

    def family(self) -> DeviceFamily:
        """The family, read from its text."""
        return family_of_text(self.text, self.family_name)

    @property
    def orientations(self) -> tuple[str, ...]:
        """The entries a trial drops the part from: the family's, in its file's order."""
        return self.entries

    @property
    def parameters(self) -> int:
        """Design factors per draw: one per parameter of the family."""
        return len(self.names)

    @property
    def values(self) -> dict[str, float]:
        """The design's values by parameter name."""
        return dict(zip(self.names, self.vector, strict=True))

    def value(self, axis: Axis) -> float:
        """The nominal value of ``axis`` (a parameter of the family, or mu)."""
        if axis.kind == DESIGN:
            return self.vector[self.names.index(axis.name)]
        if axis.kind == FRICTION:
            return self.friction
        raise ValueError(f"a device family's design has no part axis ({axis.name})")


MarginSubject = Subject | FamilySubject


@dataclass(frozen=True)
class MarginSettings:
    """How margins are measured: ``drops`` trials per value (each a drop from every entry),
    the ``target`` P(both), the draws' ``seed``, the dynamic level's step h (s) and longest
    drop (s), the verdict's perturbations, and the successes of a ``look`` (a value the
    search only passes is accepted, tentatively, on that many: the ends reported have the
    full rule over ``drops``; :mod:`experiments.margins.search`)."""

    drops: int = 20
    target: float = 0.9
    seed: int = 0
    step: float = 1e-3
    t_max: float = 10.0
    perturbations: Perturbations = field(default_factory=Perturbations)
    look: int = LOOK

    def verdict_settings(self) -> VerdictSettings:
        return VerdictSettings(
            target=self.target, step=self.step, t_max=self.t_max, perturbations=self.perturbations
        )


def made_at(subject: MarginSubject, axis: Axis, value: float) -> Callable[[DropDraw], Scene]:
    """The feeder (or the family's device) as made for one trial's draw with ``axis`` at
    ``value`` exactly."""
    if isinstance(subject, FamilySubject):
        return family_made_at(subject, axis, value)
    design, friction = subject.design, subject.friction
    length, width, heavy = subject.length, subject.width, subject.heavy_fraction
    exact = -1
    if axis.kind == DESIGN:
        design = dataclasses.replace(design, **{axis.name: value})
        exact = PARAMETER_NAMES.index(axis.name)
    elif axis.kind == PART:
        length = value if axis.name == "length" else length
        width = value if axis.name == "width" else width
        heavy = value if axis.name == "heavy_fraction" else heavy
    part = Peg.two_density(length, width, subject.mass, heavy)

    def make(d: DropDraw) -> Scene:
        factors = tuple(1.0 if k == exact else f for k, f in enumerate(d.design_factors))
        mu = value if axis.kind == FRICTION else friction * d.friction_factor
        return build_feeder(
            toleranced(design, factors),
            part,
            inputs=subject.inputs,
            friction=mu,
            gravity=subject.gravity,
            name=subject.name,
            restitution=subject.restitution,
        )

    return make


def family_made_at(subject: FamilySubject, axis: Axis, value: float) -> Callable[[DropDraw], Scene]:
    """The family's device as the verdict makes it for one trial's draw
    (:func:`experiments.drop.family_verdict.made_devices`), with the draw's factor of the
    axis varied set to 1 and the axis at ``value``: a parameter's value, or mu. When the
    device at that value cannot be built, every trial is refused as the verdict refuses an
    unbuildable made device (:class:`feeders.feeder.DegenerateDesign`)."""
    vector = list(subject.vector)
    friction, exact = subject.friction, -1
    if axis.kind == DESIGN:
        exact = subject.names.index(axis.name)
        vector[exact] = value
    elif axis.kind == FRICTION:
        friction = value
    else:
        raise ValueError(f"a device family's design has no part axis ({axis.name})")
    try:
        make = made_devices(subject.family(), vector, friction=friction)
    except DegenerateDesign as exc:
        refused = exc

        def unbuildable(_: DropDraw) -> Scene:
            raise refused

        return unbuildable

    def make_exact(d: DropDraw) -> Scene:
        factors = tuple(1.0 if k == exact else f for k, f in enumerate(d.design_factors))
        scale = 1.0 if axis.kind == FRICTION else d.friction_factor
        return make(dataclasses.replace(d, design_factors=factors, friction_factor=scale))

    return make_exact


def sampler(subject: MarginSubject, axis: Axis, settings: MarginSettings) -> Sampler:
    """The trials of ``axis``: trial i at a value is draw i of ``settings.seed`` with the
    axis at that value exactly (:func:`made_at`), made once and kept
    (:class:`experiments.margins.search.Sampler`)."""
    verdict = settings.verdict_settings()
    made: dict[float, Callable[[DropDraw], Scene]] = {}

    def outcome(value: float, index: int) -> bool | None:
        if value not in made:
            made[value] = made_at(subject, axis, value)
        trial = run_trial(
            made[value], subject.orientations, verdict, settings.seed, index, subject.parameters
        )
        return None if trial.fault else all(trial.success)

    return Sampler(outcome, settings.drops, settings.target)


def estimate(
    subject: MarginSubject, axis: Axis, value: float, settings: MarginSettings
) -> Estimate:
    """P(both) with ``axis`` at ``value`` by the full rule: over the first
    ``settings.drops`` trials (draws 0, 1, ... of ``settings.seed``, faults skipped), stopped
    as soon as so many failed that the target can no longer be reached (the same
    inside/outside answer, fewer drops)."""
    make = made_at(subject, axis, value)
    verdict = settings.verdict_settings()
    planned = settings.drops
    allowed = planned - required(settings.target, planned)  # failures the target allows
    successes = counted = index = 0
    while counted < planned and index < 2 * planned:
        trial = run_trial(
            make, subject.orientations, verdict, settings.seed, index, subject.parameters
        )
        index += 1
        if trial.fault:
            continue
        counted += 1
        successes += all(trial.success)
        if counted - successes > allowed:
            break
    return Estimate(value, successes, counted, planned)


@dataclass(frozen=True)
class AxisJob:
    """One axis of one subject: a job for a worker (plain data)."""

    subject: MarginSubject
    axis: Axis
    settings: MarginSettings


@dataclass(frozen=True)
class AxisMargin:
    """One axis's margin: the nominal estimate (its look, or its full estimate when the
    look failed or a side's search came back to it), the low and high sides (None when the
    nominal itself is outside: no margin), the box searched, and the cost (``discarded``:
    trials of a side searched before the nominal failed its confirmation, counted in
    ``drops``)."""

    axis: Axis
    nominal: Estimate
    low: Bracket | None
    high: Bracket | None
    box: tuple[float, float]
    wall_time: float
    discarded: int = 0

    @property
    def interval(self) -> tuple[float, float] | None:
        if self.low is None or self.high is None:
            return None
        return self.low.limit, self.high.limit

    @property
    def drops(self) -> int:
        sides = [s.drops for s in (self.low, self.high) if s is not None]
        return self.nominal.drops + sum(sides) + self.discarded


def measure_axis(job: AxisJob) -> AxisMargin:
    """The margin of ``job.axis``: the nominal's look (its full estimate when the look
    fails: outside, no margin), then the search toward each end of the box (the axis's:
    Table 2's, a stated range or the family's; widened to hold a nominal outside it) on the
    same kept trials (:func:`experiments.margins.search.search`: values passed on a look,
    each end confirmed by the full rule; the nominal confirmed only when a side comes back
    to it)."""
    t0 = time.perf_counter()
    subject, axis, settings = job.subject, job.axis, job.settings
    nominal_value = subject.value(axis)
    box = (min(axis.low, nominal_value), max(axis.high, nominal_value))
    trials = sampler(subject, axis, settings)
    nominal = nominal_estimate(trials, nominal_value, settings.look)
    if not nominal.inside(settings.target):
        return AxisMargin(axis, nominal, None, None, box, time.perf_counter() - t0)
    width = box[1] - box[0]
    sides: list[Bracket] = []
    try:
        for edge in box:
            sides.append(search(trials, nominal_value, edge, width, look=settings.look))
    except NominalFailed as failed:
        discarded = trials.made - failed.estimate.drops
        return AxisMargin(
            axis, failed.estimate, None, None, box, time.perf_counter() - t0, discarded
        )
    low, high = sides
    return AxisMargin(
        axis, trials.estimate(nominal_value), low, high, box, time.perf_counter() - t0
    )
