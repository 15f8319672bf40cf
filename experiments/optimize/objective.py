"""The objective of the design optimisation: Eq. 10 of the paper, made robust.

Eq. 10 scores one drop per entry: G = sum_i w ||q_i(T_i) - q_goal|| + T_i. It misleads an
optimiser twice (issue 14, measured): among failures it rewards jamming near the goal, and
among successes its optima are the fast, marginal designs, whose success probability under
the small perturbations of a real feeder is 0.2-0.45. So the optimiser here minimises a robust
objective over K fixed perturbation draws (the verdict's perturbations,
:mod:`experiments.drop.perturbations`; the same K draws for every design: common random
numbers, so two designs differ by their geometry, not by their luck):

    R = (K - S) + Gbar / (Gbar + G_SCALE)

where S is the number of the K trials that succeed from both entries and Gbar the mean of G
over the trials whose feeder could be made. The first term dominates: R ranks designs by S
(the same ranking as the Wilson lower bound of P(both), which grows with S at fixed K), and
Gbar breaks ties (Gbar / (Gbar + G_SCALE) lies in [0, 1) and grows with Gbar). A design that
cannot be built gets R = K + 1, above every buildable design, with the reason recorded.

A job is plain data (the design values and a range of trial indices; a device family's design
carries the family file's text), so it pickles to a worker; :func:`evaluate_trials` runs it,
:func:`robust_value` combines the trials of one design. A family's trials are the verdict's
(:func:`experiments.drop.family_verdict.made_devices`: the device made to tolerance per trial,
dropped from each of the family's entries).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any, TypedDict

from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.perturbations import Perturbations
from experiments.drop.verdict import Trial, VerdictSettings, made_feeders, run_trial
from experiments.family_config import family_of_text
from feeders.design import PARAMETER_NAMES, DesignParameters
from feeders.feeder import ORIENTATIONS, DegenerateDesign
from feeders.scene_yaml import environment_from_dict

G_SCALE = 10.0  # s: Gbar / (Gbar + G_SCALE) maps Gbar in [0, inf) onto [0, 1), order kept


class TrialsJob(TypedDict):
    """Trials ``first`` .. ``first + count - 1`` of one design, as a worker receives them."""

    key: str  # the design's key (its values, exactly)
    values: list[float]  # the 12 parameters, order of PARAMETER_NAMES (a family's: its own)
    first: int
    count: int
    seed: int  # of the perturbation draws
    feeder: dict[str, Any]  # the scene's environment (config's ``feeder``)
    step: float  # the dynamic level's h (s)
    t_max: float  # longest drop (s)
    perturbations: dict[str, float]
    family: str  # a device family file's text ("": the 12-parameter feeder)
    family_name: str  # the family's name unless its text names it


def trial_to_dict(trial: Trial) -> dict[str, Any]:
    """A trial as JSON-ready plain data (nan as None)."""

    def num(v: float) -> float | None:
        return None if math.isnan(v) else float(v)

    return {
        "index": trial.index,
        "success": list(trial.success),
        "outcome": list(trial.outcome),
        "T": [num(v) for v in trial.T],
        "goal_error": [num(v) for v in trial.goal_error],
    }


def trial_from_dict(data: dict[str, Any]) -> Trial:
    """The inverse of :func:`trial_to_dict`."""

    def num(v: float | None) -> float:
        return math.nan if v is None else float(v)

    return Trial(
        int(data["index"]),
        tuple(bool(s) for s in data["success"]),
        tuple(str(o) for o in data["outcome"]),
        tuple(num(v) for v in data["T"]),
        tuple(num(v) for v in data["goal_error"]),
    )


def evaluate_trials(job: TrialsJob) -> dict[str, Any]:
    """Run the job's trials of its design: ``{"key", "trials": [...], "reason": None}``, or
    with ``reason`` (and no trials) when the nominal design cannot be built."""
    t0 = time.perf_counter()
    environment = environment_from_dict(job["feeder"])
    settings = VerdictSettings(
        step=job["step"],
        t_max=job["t_max"],
        perturbations=Perturbations(**job["perturbations"]),
    )
    out: dict[str, Any] = {"key": job["key"], "first": job["first"], "trials": [], "reason": None}
    orientations: tuple[str, ...] = ORIENTATIONS
    parameters = len(PARAMETER_NAMES)  # design factors each trial draws (a family's: its own)
    try:
        if job.get("family"):
            family = family_of_text(job["family"], job["family_name"])
            orientations, parameters = entry_names(family), len(family.vector_names)
            make_scene = made_devices(family, job["values"])
        else:
            make_scene = made_feeders(
                DesignParameters.from_vector(job["values"]),
                part=environment.pop("part"),
                friction=environment.pop("friction"),
                **environment,
            )
    except DegenerateDesign as exc:
        out["reason"] = exc.reason
    else:
        for index in range(job["first"], job["first"] + job["count"]):
            trial = run_trial(
                make_scene, orientations, settings, job["seed"], index, parameters=parameters
            )
            out["trials"].append(trial_to_dict(trial))
    out["wall_time_s"] = time.perf_counter() - t0
    return out


def eq10_terms(trial: Trial, weight: float) -> float:
    """G of one trial (paper Eq. 10): sum over its entries of w ||q(T) - q_goal|| + T; nan
    when its feeder could not be made."""
    return float(sum(weight * e + t for e, t in zip(trial.goal_error, trial.T, strict=True)))


def robust_value(
    trials: Sequence[Trial], weight: float, reason: str | None = None, expected: int | None = None
) -> dict[str, Any]:
    """The robust objective R of one design from its trials (module docstring), with what it
    is made of: ``both`` (S), per entry successes, ``mean_g`` (Gbar, None if no trial's feeder
    could be made), and ``reason`` when the design is degenerate (no trials: R = K + 1, with
    K = ``expected``)."""
    k = len(trials) if expected is None else expected
    if reason is not None or not trials:
        return {
            "value": float(k + 1),
            "both": 0,
            "trials": k,
            "successes": [0] * len(ORIENTATIONS),  # a family has two entries too (config)
            "mean_g": None,
            "reason": reason or "no trials",
        }
    both = sum(all(t.success) for t in trials)
    g = [eq10_terms(t, weight) for t in trials]
    g = [v for v in g if not math.isnan(v)]
    mean_g = sum(g) / len(g) if g else None
    tie = 1.0 if mean_g is None else mean_g / (mean_g + G_SCALE)
    return {
        "value": float(len(trials) - both) + tie,
        "both": both,
        "trials": len(trials),
        "successes": [sum(t.success[i] for t in trials) for i in range(len(ORIENTATIONS))],
        "mean_g": mean_g,
        "reason": None,
    }
