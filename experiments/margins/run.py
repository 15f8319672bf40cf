"""The margins of one design: its passive verdict first (a design that does not work has no
margins), then every axis's margin (:func:`experiments.margins.measure.measure_axis`), one
job per axis in the local worker pool. The design is the 12-parameter feeder's
(:class:`~experiments.margins.measure.Subject`: its parameters, mu and the peg) or a device
family's (:class:`~experiments.margins.measure.FamilySubject`: its parameters and mu, its
verdict :func:`experiments.drop.family_verdict.family_verdict`)."""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass

from experiments.drop.family_verdict import family_verdict
from experiments.drop.verdict import Verdict, design_verdict
from experiments.executors.local import map_jobs
from experiments.margins.axes import Axis, axes, family_axes
from experiments.margins.measure import (
    AxisJob,
    AxisMargin,
    FamilySubject,
    MarginSettings,
    MarginSubject,
    measure_axis,
)
from experiments.margins.search import FIRST_STEP, RESOLUTION
from feeders.part import Peg

MEANING = (
    "per axis, with the others at nominal: the values between which the estimated P(both) "
    "(successes of the planned trials, each a perturbed drop from both entries, on the same "
    "seeded draws at every value) stays at or above the target; each end is the last value "
    "found inside, within the resolution of the first found outside (or the box's edge)"
)


@dataclass(frozen=True)
class MarginsReport:
    """The margins of a subject (empty when its verdict is not "works"), the verdict, and the
    cost: trials (a perturbed made feeder, one drop from each entry) and wall time (s)."""

    subject: MarginSubject
    settings: MarginSettings
    verdict: Verdict
    margins: tuple[AxisMargin, ...]
    wall_time: float
    workers: int

    @property
    def trials(self) -> int:
        return len(self.verdict.trials) + sum(m.drops for m in self.margins)

    def to_dict(self) -> dict:
        s = self.subject
        verdict = self.verdict.to_dict()
        verdict.pop("transitions")
        rows = []
        for m in self.margins:
            a = m.axis
            interval = m.interval
            rows.append(
                {
                    "parameter": a.name,
                    "kind": a.kind,
                    "meaning": a.meaning,
                    "unit": a.unit,
                    "nominal": s.value(a),
                    "box": list(m.box),
                    "box_source": a.source,
                    "interval": None if interval is None else list(interval),
                    "nominal_estimate": m.nominal.to_dict(),
                    "low": None if m.low is None else m.low.to_dict(),
                    "high": None if m.high is None else m.high.to_dict(),
                    "trials": m.drops,
                    "wall_time_s": m.wall_time,
                }
            )
        if isinstance(s, FamilySubject):
            part: dict | None = None  # the family's own: no part axes
            family: dict | None = {
                "name": s.family_name,
                "parameters": list(s.names),
                "entries": list(s.entries),
            }
        else:
            part = {
                "length": s.length,
                "width": s.width,
                "mass": s.mass,
                "heavy_fraction": s.heavy_fraction,
            }
            family = None
        return {
            "design": s.name,
            "family": family,
            "values": s.values,
            "part": part,
            "friction": s.friction,
            "target": self.settings.target,
            "drops_per_value": self.settings.drops,
            "seed": self.settings.seed,
            "search": {
                "first_step": FIRST_STEP,
                "resolution": RESOLUTION,
                "unit": "fraction of the box's width",
            },
            "meaning": MEANING,
            "verdict": verdict,
            "works": self.verdict.works,
            "margins": rows,
            "cost": {
                "trials": self.trials,
                "drops": self.trials * len(s.orientations),
                "wall_time_s": self.wall_time,
                "workers": self.workers,
            },
        }


def axes_of(subject: MarginSubject, kinds: Collection[str] | None = None) -> tuple[Axis, ...]:
    """The axes of ``subject``: the feeder's 16 (:func:`experiments.margins.axes.axes`) or a
    family's parameters and mu (:func:`experiments.margins.axes.family_axes`); only those of
    ``kinds`` ("design", "friction", "part") when given."""
    found = family_axes(subject.family()) if isinstance(subject, FamilySubject) else axes()
    return found if kinds is None else tuple(a for a in found if a.kind in kinds)


def design_verdict_of(subject: MarginSubject, settings: MarginSettings) -> Verdict:
    """The verdict of ``subject`` at nominal on the margins' seed, as ``simulate --samples``
    gives it (the family's verdict for a family's design)."""
    if isinstance(subject, FamilySubject):
        return family_verdict(
            subject.family(),
            subject.vector,
            settings.verdict_settings(),
            seed=settings.seed,
            friction=subject.friction,
        )
    return design_verdict(
        subject.design,
        Peg.two_density(subject.length, subject.width, subject.mass, subject.heavy_fraction),
        subject.friction,
        settings.verdict_settings(),
        seed=settings.seed,
        gravity=subject.gravity,
        restitution=subject.restitution,
        inputs=subject.inputs,
        name=subject.name,
    )


def margins_of(
    subject: MarginSubject,
    settings: MarginSettings,
    workers: int = 1,
    on_axis: Callable[[AxisMargin], object] | None = None,
    kinds: Collection[str] | None = None,
) -> MarginsReport:
    """The verdict of ``subject`` (sequential, as ``simulate --samples``), then, if it works,
    the margin of every axis (:func:`axes_of`, those of ``kinds`` when given) on ``workers``
    processes; ``on_axis`` is called here as each axis finishes."""
    return margins_of_each({"": subject}, settings, workers, on_axis, kinds)[""]


def margins_of_each(
    subjects: Mapping[str, MarginSubject],
    settings: MarginSettings,
    workers: int = 1,
    on_axis: Callable[[AxisMargin], object] | None = None,
    kinds: Collection[str] | None = None,
) -> dict[str, MarginsReport]:
    """:func:`margins_of` for several designs by label, every axis of every design that works
    in one pool (the workers stay busy across designs); each report's wall time is the
    whole call's."""
    t0 = time.perf_counter()
    verdicts = {label: design_verdict_of(s, settings) for label, s in subjects.items()}
    jobs: list[AxisJob] = []
    owners: list[str] = []
    for label, subject in subjects.items():
        if verdicts[label].works:
            for axis in axes_of(subject, kinds):
                jobs.append(AxisJob(subject, axis, settings))
                owners.append(label)
    found = (
        map_jobs(
            measure_axis,
            jobs,
            workers,
            on_result=None if on_axis is None else lambda _i, m: on_axis(m),
            ompl=False,
        )
        if jobs
        else []
    )
    wall = time.perf_counter() - t0
    return {
        label: MarginsReport(
            subject,
            settings,
            verdicts[label],
            tuple(m for m, owner in zip(found, owners, strict=True) if owner == label),
            wall,
            workers,
        )
        for label, subject in subjects.items()
    }
