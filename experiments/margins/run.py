"""The margins of one design: its passive verdict first (a design that does not work has no
margins), then every axis's margin (:func:`experiments.margins.measure.measure_axis`), one
job per axis in the local worker pool. The design is the 12-parameter feeder's
(:class:`~experiments.margins.measure.Subject`: its parameters, mu and the peg) or a device
family's (:class:`~experiments.margins.measure.FamilySubject`: its parameters and mu, its
verdict :func:`experiments.drop.family_verdict.family_verdict`)."""

from __future__ import annotations

import contextlib
import functools
import math
import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass
from typing import Any

from experiments.drop.family_verdict import family_verdict
from experiments.drop.verdict import Verdict, design_verdict
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
    stopped: str | None = None  # why the axes after ``margins`` were not measured
    wasted: int = 0  # trials of axes that were running when it stopped, not in ``margins``

    @property
    def trials(self) -> int:
        return len(self.verdict.trials) + sum(m.drops for m in self.margins) + self.wasted

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
                "look": self.settings.look,
                "unit": "fraction of the box's width",
            },
            "stopped": self.stopped,
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


Stop = Callable[[str, Mapping[str, dict]], str | None]


def margins_of_each(
    subjects: Mapping[str, MarginSubject],
    settings: MarginSettings,
    workers: int = 1,
    on_axis: Callable[[AxisMargin], object] | None = None,
    kinds: Collection[str] | None = None,
    stop: Stop | None = None,
    on_skip: Callable[[str, int], object] | None = None,
) -> dict[str, MarginsReport]:
    """:func:`margins_of` for several designs by label, in one pool that stays warm across
    them, one design after the other in the order given (each one's axes on every worker);
    from the second design on, the axes the first found tightest go first. ``stop(label,
    so_far)`` is asked after each axis of a design other than the first (in the order the
    axes were handed out, so the answer does not depend on which worker was faster;
    ``so_far``: the reports of the designs before it and of this one so far, by label, as
    :meth:`MarginsReport.to_dict`); a reason it returns ends that design: its report holds
    the axes judged before, says why in ``stopped``, and counts in its cost the trials of
    axes that were already running. ``on_skip(label, n)`` is called once a design is done
    with the number of its axes that were not measured (all of a design that does not work,
    the rest of one stopped), so a progress bar's total stays true. Each report's wall time
    is the whole call's."""
    t0 = time.perf_counter()
    labels = list(subjects)
    verdicts = {label: design_verdict_of(subjects[label], settings) for label in labels}
    done: dict[str, list[AxisMargin]] = {label: [] for label in labels}
    wasted: dict[str, int] = dict.fromkeys(labels, 0)
    stopped: dict[str, str | None] = dict.fromkeys(labels)

    def report(label: str) -> MarginsReport:
        return MarginsReport(
            subjects[label],
            settings,
            verdicts[label],
            tuple(done[label]),
            time.perf_counter() - t0,
            workers,
            stopped[label],
            wasted[label],
        )

    def axes_in_order(k: int) -> list[Axis]:
        axes = list(axes_of(subjects[labels[k]], kinds)) if verdicts[labels[k]].works else []
        if k == 0 or not done[labels[0]]:
            return axes
        from experiments.margins.robustness import SIDES, at_edge, room

        rooms = {}  # the first design's smallest room inside the box, per axis
        for row in report(labels[0]).to_dict()["margins"]:
            r = room(row)
            if r is None:
                rooms[row["parameter"]] = -1.0
                continue
            inside = [x for x, side in zip(r, SIDES, strict=True) if not at_edge(row, side)]
            rooms[row["parameter"]] = min(inside, default=math.inf)
        return sorted(axes, key=lambda a: rooms.get(a.name, math.inf))  # stable: ties keep order

    def judged(label: str, margin: AxisMargin, first: bool = False) -> bool:
        """Take one axis's margin in hand-out order; False once the design is stopped."""
        if stopped[label] is not None:
            wasted[label] += margin.drops
            return False
        done[label].append(margin)
        if on_axis is not None:
            on_axis(margin)
        if stop is not None and not first:
            so_far = {lb: report(lb).to_dict() for lb in labels if done[lb] or lb == label}
            stopped[label] = stop(label, so_far)
        return stopped[label] is None

    def _skipped(label: str) -> None:
        unmeasured = len(axes_of(subjects[label], kinds)) - len(done[label])
        if on_skip is not None and unmeasured > 0:
            on_skip(label, unmeasured)

    pool = None
    if workers > 1:
        from experiments.executors.local import LocalPool

        pool = LocalPool(workers, 1, None, False)
    with pool if pool is not None else contextlib.nullcontext():
        for k, label in enumerate(labels):
            jobs = [AxisJob(subjects[label], axis, settings) for axis in axes_in_order(k)]
            if pool is None:
                for job in jobs:
                    if not judged(label, measure_axis(job), k == 0):
                        break
                _skipped(label)
                continue
            _in_order(pool, jobs, functools.partial(judged, label, first=k == 0))
            _skipped(label)
    for label in labels:  # the designs' axes in their usual order
        order = {a.name: i for i, a in enumerate(axes_of(subjects[label], kinds))}
        done[label].sort(key=lambda m: order[m.axis.name])
    return {label: report(label) for label in labels}


def _in_order(pool: Any, jobs: list[AxisJob], take: Callable[[AxisMargin], bool]) -> None:
    """Run ``jobs`` on ``pool``, handing each result to ``take`` in the jobs' order (later
    ones wait for earlier ones); once ``take`` says False, no job is handed out again, and
    the results of those already running go to ``take`` too (it counts them)."""
    from experiments.executors.local import JobFailed

    results: dict[int, AxisMargin] = {}
    queue = iter(enumerate(jobs))
    state = {"next": 0, "open": True}

    def hand_out() -> list[tuple[int, AxisJob]]:
        item = next(queue, None) if state["open"] else None
        return [] if item is None else [item]

    def on_done(item: tuple[int, AxisJob], margin: AxisMargin, _attempts: int) -> list:
        results[item[0]] = margin
        while state["next"] in results:
            state["open"] = take(results.pop(state["next"])) and state["open"]
            state["next"] += 1
        return hand_out()

    def failed(item: tuple[int, AxisJob], _attempts: int, reason: str) -> None:
        raise JobFailed(item[0], f"axis {item[1].axis.name}: {reason}")

    first = [item for _ in range(pool.workers) for item in hand_out()]
    if first:
        pool.run(_indexed_axis, first, on_done, failed)


def _indexed_axis(item: tuple[int, AxisJob]) -> AxisMargin:
    return measure_axis(item[1])
