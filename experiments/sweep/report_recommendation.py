"""What a sweep's report recommends, and with what tolerance (issue 25).

The sweep ranks its designs on the draws their verdicts were reached with, so its best is
the best of a scan and may be a lucky draw. The report judges the top ones again on fresh
draws beside a baseline (:func:`experiments.sweep.report_verdicts.comparison_of`); the
recommendation is the first of them ranked on those draws
(:func:`experiments.report_kit.comparison_section.fresh_ranking`) only when the fresh draws
confirm it works, and only that design gets its tolerance margins
(:func:`experiments.margins.run.margins_of`: per design parameter, friction and part
dimension, the interval over which P(both) stays at or above the passive rung's target; a
device family's design, issue 24: per parameter of the family over its box, and friction).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from experiments.margins.measure import MarginSubject

CONFIRMED = "confirmed"
NOT_REJUDGED = "not re-judged"
MARGINS_TAG = 0x3A261  # mixed into the sweep's seed: the margins' draws are none of its others
MARGINS_DROPS = 20  # trials per value tried, as ``partfeeder margins``'s default

# ``progress(event, info)``: ("margins", {"design", "axes"}) when the margins start, then
# ("axis", {"parameter"}) as each axis is done
Progress = Callable[[str, dict[str, Any]], object]


def fresh_status(comparison: dict[str, Any] | None) -> dict[str, str]:
    """Per compared design's label, what the fresh draws said: ``confirmed``, or ``not
    confirmed (fails)``, ``(undecided)`` or ``(cannot be built)`` (the verdict's decision on
    those draws); empty without a comparison."""
    from experiments.report_kit.comparison_section import confirmation

    if not comparison or "absent" in comparison:
        return {}
    drops, target = int(comparison["drops"]), float(comparison["target"])
    out = {}
    for entry in comparison.get("designs") or []:
        confirmed, _ = confirmation(entry, drops, target)
        verdict = entry.get("verdict")
        if confirmed:
            out[str(entry["label"])] = CONFIRMED
        elif not verdict:
            out[str(entry["label"])] = "not confirmed (cannot be built)"
        else:
            decision = "fails" if verdict.get("decision") == "fails" else "undecided"
            out[str(entry["label"])] = f"not confirmed ({decision})"
    return out


def design_label(design_id: int) -> str:
    """A sweep design's label in the comparison."""
    return f"design {design_id}"


def recommendation_of(summary: dict[str, Any], comparison: dict[str, Any] | None) -> dict:
    """The design to build: ``label`` (None when no design is confirmed), ``confirmed``,
    ``sentence`` (its confirmation on the fresh draws, or why nothing is recommended),
    ``chosen`` (how it was chosen) and ``ranking`` (the compared labels, as ranked on the
    fresh draws)."""
    from experiments.report_kit.comparison_section import fresh_ranking

    works = (summary.get("passive") or {}).get("works")
    if not summary.get("passive"):
        why = "the sweep has no passive rung, so no design has a verdict on whether it works"
        return _none(why)
    if not comparison or "absent" in comparison:
        return _none((comparison or {}).get("absent") or "no design works")
    ranking = fresh_ranking(comparison)
    drops = int(comparison["drops"])
    name = str(comparison["baseline"]["label"])
    compared = len(ranking)
    of = f"the sweep's {works} designs that work" if works is not None else "the designs"
    chosen = (
        f"the best of {of} by its own verdict (its top {compared}), then ranked again on "
        f"{drops} fresh draws shared with {name}: confirmed first, then P(both)'s lower "
        "bound, then the slower entry's exit time"
    )
    labels = [r["label"] for r in ranking]
    top = ranking[0]
    if top["confirmed"]:
        return {
            "label": top["label"],
            "confirmed": True,
            "sentence": top["sentence"],
            "chosen": chosen,
            "ranking": labels,
        }
    status = fresh_status(comparison)
    said = ", ".join(f"{label} {status[label].removeprefix('not confirmed ')}" for label in labels)
    return {
        **_none(
            f"none of the top {compared} of {of} by the sweep's own verdict was confirmed on "
            f"{drops} fresh draws shared with {name} ({said})"
        ),
        "chosen": chosen,
        "ranking": labels,
    }


def _none(why: str) -> dict[str, Any]:
    return {"label": None, "confirmed": False, "sentence": why, "chosen": None, "ranking": []}


def margins_seed(sweep_seed: int, avoid: tuple[int, ...] = ()) -> int:
    """The seed of the recommended design's margins: from the sweep's seed only, and none of
    ``avoid`` (the seeds its verdicts and the fresh comparison used)."""
    from experiments.drop.compare import fresh_seed

    return fresh_seed(sweep_seed, avoid, MARGINS_TAG)


def margins_of_recommended(
    summary: dict[str, Any],
    db_path: Path,
    comparison: dict[str, Any],
    label: str,
    workers: int | None = None,
    progress: Progress | None = None,
) -> dict[str, Any] | None:
    """The margins (:meth:`experiments.margins.run.MarginsReport.to_dict`) of the compared
    design ``label`` (:func:`margin_subject`: the feeder's 16 axes, or a device family's
    parameters over its box and mu) with the sweep's passive rung's target, step and
    perturbations, ``MARGINS_DROPS`` trials per value on a seed derived from the sweep's
    (:func:`margins_seed`), on ``workers`` processes (default the sweep's workers); None
    when the sweep has no passive rung."""
    from experiments.margins.measure import MarginSettings
    from experiments.margins.run import axes_of, margins_of
    from experiments.sweep.report_verdicts import passive_settings, sweep_config

    config = sweep_config(db_path)
    settings = passive_settings(config)
    if settings is None:
        return None
    entry = next(d for d in comparison["designs"] if str(d["label"]) == label)
    subject = margin_subject(summary, db_path, list(entry["values"]), label)
    sweep_seed = int((config.get("designs") or {}).get("seed", 0))
    avoid = (*comparison.get("ranked_with", ()), int(comparison["seed"]))
    margin_settings = MarginSettings(
        drops=MARGINS_DROPS,
        target=settings.target,
        seed=margins_seed(sweep_seed, avoid),
        step=settings.step,
        t_max=settings.t_max,
        perturbations=settings.perturbations,
    )
    count = workers if workers is not None else int(config.get("workers") or 1)
    if progress is not None:
        progress("margins", {"design": label, "axes": len(axes_of(subject))})
    report = margins_of(
        subject,
        margin_settings,
        max(1, count),
        on_axis=None
        if progress is None
        else lambda margin: progress("axis", {"parameter": margin.axis.name}),
    )
    return report.to_dict()


def margin_subject(
    summary: dict[str, Any], db_path: Path, values: list[float], label: str
) -> MarginSubject:
    """What the margins of the design ``values`` (named ``label``) vary: a device family's
    design (:class:`experiments.margins.measure.FamilySubject`, the family and its text as
    the sweep's database keeps them: its parameters over its box and mu, the family's part
    and friction), else the feeder's built with the sweep's part, friction and options
    (:class:`experiments.margins.measure.Subject`: its 12 parameters, mu and the peg)."""
    from experiments.margins.measure import FamilySubject, Subject
    from experiments.sweep.family import database_family
    from feeders.design import DesignParameters
    from feeders.feeder import build_feeder
    from feeders.scene_yaml import environment_from_dict

    found = database_family(db_path)
    if found is not None:
        family, text = found
        return FamilySubject.of_family(family, text, values, name=label)
    environment = environment_from_dict(summary.get("feeder") or {}, prefix="feeder.")
    scene = build_feeder(DesignParameters.from_vector(values), name=label, **environment)
    return Subject.of_scene(scene)
