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

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments.report_kit.recommendation import KEEP

if TYPE_CHECKING:
    from experiments.margins.measure import MarginSubject
    from experiments.margins.robustness import Robustness

CONFIRMED = "confirmed"
NOT_REJUDGED = "not re-judged"
MARGINS_TAG = 0x3A261  # mixed into the sweep's seed: the margins' draws are none of its others
MARGINS_DROPS = 20  # trials per value tried, as ``partfeeder margins``'s default
RELIABILITY_ALPHA = 0.05  # one-sided level of the paired test "more reliable than"
BUILD, NONE = "build", "none"
MARGIN_AXES = {"device": ("design", "friction"), "all": None}  # a sweep's ``margins.axes``

# ``progress(event, info)``: ("margins", {"design", "axes"}) when the margins start, then
# ("axis", {"parameter"}) as each axis is done and ("skipped", {"design", "axes"}) for the
# axes of a design not measured (it does not work, or it was outranked)
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


def recommendation_of(
    summary: dict[str, Any],
    comparison: dict[str, Any] | None,
    margins: Mapping[str, dict[str, Any]] | None = None,
) -> dict:
    """The design to build: ``label`` (None when no design is confirmed), ``confirmed``,
    ``sentence`` (its confirmation on the fresh draws, or why nothing is recommended),
    ``chosen`` (how it was chosen), ``ranking`` (the compared labels, as ranked on the fresh
    draws) and ``decision`` ("build", "keep the baseline" or "none").

    With ``margins`` (per label, the baseline's included: :func:`margins_of_contenders`)
    the confirmed designs are ranked by reliability, then by robustness
    (:func:`robust_choice`): the baseline is kept unless a design is more reliable on the
    same draws by the paired exact test, or more robust beyond the margins' resolution."""
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
        first = {
            "label": top["label"],
            "confirmed": True,
            "sentence": top["sentence"],
            "chosen": chosen + "; robustness not measured (margins skipped)",
            "ranking": labels,
            "decision": BUILD,
        }
        return first if margins is None else robust_choice(first, comparison, ranking, margins)
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


def reliability(entry: dict[str, Any]) -> dict[str, Any]:
    """How a compared design's reliability stands against the baseline's on the same fresh
    draws: the discordant draws (``design_only``, ``baseline_only``) and the one-sided exact
    paired test each way (``p_better``, ``p_worse``; McNemar's,
    :func:`experiments.proportions.paired_exact_p`); ``better`` / ``worse`` when the p-value
    is below :data:`RELIABILITY_ALPHA`."""
    from experiments.proportions import paired_exact_p

    paired = entry.get("paired") or {"draws": 0, "design_only": 0, "baseline_only": 0}
    mine, theirs = int(paired["design_only"]), int(paired["baseline_only"])
    p_better, p_worse = paired_exact_p(mine, theirs), paired_exact_p(theirs, mine)
    return {
        "draws": int(paired["draws"]),
        "design_only": mine,
        "baseline_only": theirs,
        "p_better": p_better,
        "p_worse": p_worse,
        "better": p_better < RELIABILITY_ALPHA,
        "worse": p_worse < RELIABILITY_ALPHA,
    }


def _percent(r: Robustness, margins: dict[str, Any] | None = None) -> str:
    """A design's robustness in words ("at most" for a design whose margins were stopped,
    :func:`outranked`)."""
    from experiments.margins.robustness import in_words

    return in_words(r, bool(margins and margins.get("stopped")))


def robust_choice(
    first: dict[str, Any],
    comparison: dict[str, Any],
    ranking: list[dict[str, Any]],
    margins: Mapping[str, dict[str, Any]],
) -> dict[str, Any]:
    """The recommendation once the confirmed designs' and the baseline's robustness is known
    (issue 34): among the confirmed designs, the one more reliable than the baseline by the
    paired test first, then the most robust (:func:`experiments.margins.robustness.robustness`,
    the fresh ranking breaking ties); that design is built only when it is more reliable than
    the baseline, or the baseline was not confirmed, or it is more robust than the baseline
    beyond the resolution (:func:`experiments.margins.robustness.more_robust`) and not less
    reliable; otherwise the baseline is kept. ``robustness`` (per label, its ``to_dict``),
    ``reliability`` (per design, :func:`reliability`), ``contender`` (the best design
    against the baseline) and ``baseline`` are added."""
    from experiments.margins.robustness import more_robust, robustness

    base = comparison["baseline"]
    name = str(base["label"])
    entries = {str(d["label"]): d for d in comparison.get("designs") or []}
    confirmed = [r["label"] for r in ranking if r["confirmed"]]
    robust = {label: robustness(m) for label, m in margins.items()}
    zero = robustness({"works": False})
    reliable = {label: reliability(entries[label]) for label in confirmed}
    order = sorted(
        confirmed,
        key=lambda label: (
            not reliable[label]["better"],
            (margins.get(label) or {}).get("stopped") is not None,  # outranked while measured
            -robust.get(label, zero).value,
            confirmed.index(label),
        ),
    )
    best = order[0]
    mine, theirs = robust.get(best, zero), robust.get(name, zero)
    base_confirmed = _confirmed(base, comparison)
    rel = reliable[best]
    d_only, b_only = rel["design_only"], rel["baseline_only"]
    paired = (
        f"on the same {rel['draws']} draws {best} succeeded alone on {d_only} and {name} alone "
        f"on {b_only} (paired exact test, one-sided p = {rel['p_better']:.3g})"
    )
    robust_text = (
        f"smallest margin {_percent(mine, margins.get(best))} of its box against {name}'s "
        f"{_percent(theirs, margins.get(name))}"
    )
    if not base_confirmed:
        decision, why = BUILD, f"{name} is not confirmed on the same draws; {robust_text}"
    elif rel["better"]:
        decision, why = BUILD, f"more reliable than {name}: {paired}; {robust_text}"
    elif rel["worse"]:
        decision, why = KEEP, f"less reliable than {name}: {paired}"
    elif more_robust(mine, theirs):
        decision, why = BUILD, f"as reliable as {name} ({paired}) and more robust: {robust_text}"
    else:
        decision, why = (
            KEEP,
            (
                f"{best} is no more reliable ({paired}) and not more robust beyond the margins' "
                f"resolution: {robust_text}"
            ),
        )
    chosen = first["chosen"].removesuffix("; robustness not measured (margins skipped)")
    chosen += (
        f"; the confirmed designs and {name} then ranked by reliability against {name} "
        "(paired exact test, one-sided 5%), then by robustness (the smallest margin over the "
        "design's parameters and friction, as a fraction of its box)"
    )
    out = {
        **first,
        "chosen": chosen,
        "decision": decision,
        "why": why,
        "contender": best,
        "baseline": name,
        "robustness": {label: r.to_dict() for label, r in robust.items()},
        "reliability": reliable,
    }
    if decision == KEEP:
        _, sentence = _confirmation(base, comparison)
        out.update(label=name, sentence=sentence, kept=True)
    else:
        out.update(label=best, sentence=_confirmation(entries[best], comparison)[1])
    return out


def _confirmed(entry: dict[str, Any], comparison: dict[str, Any]) -> bool:
    return _confirmation(entry, comparison)[0]


def _confirmation(entry: dict[str, Any], comparison: dict[str, Any]) -> tuple[bool, str]:
    from experiments.report_kit.comparison_section import confirmation

    return confirmation(entry, int(comparison["drops"]), float(comparison["target"]))


def _none(why: str) -> dict[str, Any]:
    return {
        "label": None,
        "confirmed": False,
        "sentence": why,
        "chosen": None,
        "ranking": [],
        "decision": NONE,
    }


def margins_seed(sweep_seed: int, avoid: tuple[int, ...] = ()) -> int:
    """The seed of the recommended design's margins: from the sweep's seed only, and none of
    ``avoid`` (the seeds its verdicts and the fresh comparison used)."""
    from experiments.drop.compare import fresh_seed

    return fresh_seed(sweep_seed, avoid, MARGINS_TAG)


def margins_of_contenders(
    summary: dict[str, Any],
    db_path: Path,
    comparison: dict[str, Any],
    workers: int | None = None,
    progress: Progress | None = None,
) -> dict[str, dict[str, Any]] | None:
    """The margins (:meth:`experiments.margins.run.MarginsReport.to_dict`), per label, of
    the designs the fresh draws confirmed and of the baseline (:func:`margin_subject`: the
    feeder's parameters and mu, or a device family's; the part's axes too when the sweep's
    ``report.margins`` is "all"), all in one worker pool, with the sweep's passive rung's
    target, step and perturbations, ``MARGINS_DROPS`` trials per value on a seed derived
    from the sweep's (:func:`margins_seed`), on ``workers`` processes (default the sweep's);
    None when the sweep has no passive rung, its config says ``report.margins: skip``, or
    nothing was confirmed."""
    from experiments.margins.measure import MarginSettings
    from experiments.margins.run import axes_of, margins_of_each
    from experiments.sweep.report_verdicts import passive_settings, sweep_config

    config = sweep_config(db_path)
    settings = passive_settings(config)
    which = str((config.get("report") or {}).get("margins", "device"))
    if settings is None or which == "skip" or not comparison.get("designs"):
        return None
    confirmed = [d for d in comparison["designs"] if _confirmed(d, comparison)]
    if not confirmed:
        return None
    # the baseline first (its margins are shown in any case), then in the fresh ranking's
    # order; a baseline that cannot be built has no margins (nor a verdict to compare)
    base = comparison["baseline"]
    subjects = {
        str(d["label"]): margin_subject(summary, db_path, list(d["values"]), str(d["label"]))
        for d in [*([base] if base.get("verdict") else []), *confirmed]
    }
    kinds = MARGIN_AXES[which]
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
        axes = sum(len(axes_of(s, kinds)) for s in subjects.values())
        progress("margins", {"design": ", ".join(subjects), "axes": axes})
    protected = {str(d["label"]) for d in confirmed if reliability(d)["better"]}
    reports = margins_of_each(
        subjects,
        margin_settings,
        max(1, count),
        on_axis=None
        if progress is None
        else lambda margin: progress("axis", {"parameter": margin.axis.name}),
        kinds=kinds,
        stop=lambda label, so_far: None if label in protected else outranked(label, so_far),
        on_skip=None
        if progress is None
        else lambda label, n: progress("skipped", {"design": label, "axes": n}),
    )
    return {label: report.to_dict() for label, report in reports.items()}


def outranked(label: str, so_far: Mapping[str, dict[str, Any]]) -> str | None:
    """Why the design ``label`` can no longer be recommended on robustness (None while it
    can): the smallest room to a first value outside among its axes measured so far (an upper
    bound of its robustness) is at most the robustness of a design measured before it in
    full, so it cannot be more robust than that design. Its remaining axes need not be
    measured: the choice (:func:`robust_choice`) is the same without them."""
    from experiments.margins.robustness import robustness

    mine = robustness(so_far[label]).bracket[1]
    for other, margins in so_far.items():
        if other == label or margins.get("stopped") is not None:
            continue  # the designs before ``label`` are whole, unless stopped themselves
        theirs = robustness(margins)
        if mine <= theirs.value:
            return (
                f"its smallest margin is at most {100 * mine:.1f}% of its box, "
                f"not above {other}'s {100 * theirs.value:.1f}%"
            )
    return None


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
