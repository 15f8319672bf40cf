"""The margins of one design: its passive verdict first (a design that does not work has no
margins), then every axis's margin (:func:`experiments.margins.measure.measure_axis`), one
job per axis in the local worker pool."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from experiments.drop.verdict import Verdict, design_verdict
from experiments.executors.local import map_jobs
from experiments.margins.axes import axes
from experiments.margins.measure import AxisJob, AxisMargin, MarginSettings, Subject, measure_axis
from experiments.margins.search import FIRST_STEP, RESOLUTION
from feeders.design import PARAMETER_NAMES
from feeders.feeder import ORIENTATIONS
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

    subject: Subject
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
                    "box_source": "Table 2" if a.table2 else "stated range",
                    "interval": None if interval is None else list(interval),
                    "nominal_estimate": m.nominal.to_dict(),
                    "low": None if m.low is None else m.low.to_dict(),
                    "high": None if m.high is None else m.high.to_dict(),
                    "trials": m.drops,
                    "wall_time_s": m.wall_time,
                }
            )
        return {
            "design": s.name,
            "values": dict(zip(PARAMETER_NAMES, s.design.to_vector().tolist(), strict=True)),
            "part": {
                "length": s.length,
                "width": s.width,
                "mass": s.mass,
                "heavy_fraction": s.heavy_fraction,
            },
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
                "drops": self.trials * len(ORIENTATIONS),
                "wall_time_s": self.wall_time,
                "workers": self.workers,
            },
        }


def margins_of(
    subject: Subject,
    settings: MarginSettings,
    workers: int = 1,
    on_axis: Callable[[AxisMargin], object] | None = None,
) -> MarginsReport:
    """The verdict of ``subject`` (sequential, as ``simulate --samples``), then, if it works,
    the margin of every axis (:func:`experiments.margins.axes.axes`) on ``workers`` processes;
    ``on_axis`` is called here as each axis finishes."""
    t0 = time.perf_counter()
    verdict = design_verdict(
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
    margins: list[AxisMargin] = []
    if verdict.works:
        jobs = [AxisJob(subject, axis, settings) for axis in axes()]
        margins = map_jobs(
            measure_axis,
            jobs,
            workers,
            on_result=None if on_axis is None else lambda _i, m: on_axis(m),
            ompl=False,
        )
    return MarginsReport(
        subject, settings, verdict, tuple(margins), time.perf_counter() - t0, workers
    )
