"""The bounds a stress case is held to, each a named constant with its reason, and the verdict.

Hard bounds fail the run (exit status 1): an uncaught exception, a NaN or inf in a state,
penetration deeper than allowed, energy gained without input beyond what the model may add,
and a contact level's part ending on the far side of a wall. Soft ones are counted and shown
(they are how the levels report trouble they handle): LCP failures and frictionless fallbacks
of the dynamic level, jams and stalls of the kinematic level, and a push-out faster than the
cap.
"""

from __future__ import annotations

HARD = ("exception", "nonfinite", "penetration", "energy", "crossing")
SOFT = ("push_out", "lcp_failure", "fallback", "jam", "stall")

EXACT_PENETRATION = 1e-9
"""Geometric and kinematic levels (length): they promise psi_n >= 0 exactly (Eq. 9 checks every
pose, Eq. 8 advances conservatively), so only round-off may show; shapely's distances on
coordinates of size 10 are good to ~1e-14, so 1e-9 leaves five orders of slack and is far
below anything physical."""

DYNAMIC_PENETRATION = 0.01
"""Dynamic level (length): validity.dynamic.PENETRATION_TOLERANCE, the deepest overlap a valid
dynamic state may have (what a planner accepts); a part started deeper (it never is here) may
keep its start depth. On top of it the linearisation errors of the run, summed over each
stretch of steps the part spends overlapping (:func:`experiments.stress.measures.
accumulated_errors`; an overlap is only kept from approaching, so it may grow by each step's
error), their largest sum; each step's error is
(:func:`experiments.stress.measures.linearisation_errors`): Eq. 7 keeps the gaps linearised at
the start of a step non-negative, and the true gap of a contact the part has in that step
leaves its linearisation by at most |b| dtheta^2 / 2 for a point of the part at b against an
obstacle (faces, vertices and discs alike: their gaps are convex in the point), and by
|c - x| dtheta^2 / 2 + |dx| |dtheta| for an obstacle vertex or disc centre c against a face of
the part, which turns with it (issue 35: derived from the features within the step's reach,
not from the scene's smallest disc). Negligible at h = 1e-3 (about 1e-4 at 20 rad/s); at
h = 5e-2 it reaches tenths of a length, where the bound says little: the report counts the
cases whose allowance exceeds VACUOUS_FRACTION of the part's size. A run whose overlap grows
beyond it (a contact missed for a step: first order in h, not second) fails."""

VACUOUS_FRACTION = 0.05
"""A dynamic case whose one-step linearisation allowance exceeds this fraction of the part's
size (:func:`feeders.part_shape.part_extent`) is counted and listed by the report as one whose
bound says little: 5 % of a part is already five times the validity tolerance for a part of
size 1 (issue 35: "0 beyond the bound" must not rest on a vacuous bound)."""


TRUSTED_STEP = 2.5e-2
"""Steps h (s) up to which every hard bound is meant to hold (issue 35's band); the report
counts hard failures and vacuous allowances on both sides of it."""


def vacuous(record: dict) -> bool:
    """The case's linearisation allowance exceeds :data:`VACUOUS_FRACTION` of the part's size."""
    return record.get("step_error", 0.0) > VACUOUS_FRACTION * record.get("part_size", 0.0)


KINEMATIC_ENERGY_REL = 1e-9
"""Kinematic level: every step starts at the commanded velocity u, and an impact never adds
kinetic energy (Stronge's restitution), so after a step T <= T(u); relative slack 1e-9 for
round-off over at most MAX_IMPACTS = 32 closed-form impacts (each good to ~1e-15)."""

DYNAMIC_ENERGY_REL = 1e-6
"""Dynamic level: with the wrench's work subtracted, Eq. 7 stepped semi-implicitly loses
energy in free flight (m |g|^2 h^2 / 2 per step) and at every contact (no restitution,
Coulomb friction); an overlap is corrected in the pose, not the velocity, so its one source of
energy is the lift of those corrections through gravity and the wrench, which is subtracted
(measured from the states: experiments.stress.measures.correction_work).
1e-6 of the case's energy scale covers the LCP's residual and its regularised retries."""

PUSH_OUT_SLACK = 1e-9
"""Dynamic level (length/s): a pose correction moves no point of the part faster than the
push-out cap; slack for round-off."""


def penetration_allowance(level: str, start_depth: float, step_error: float = 0.0) -> float:
    """Deepest overlap (length) a run of ``level`` may reach from a start ``start_depth`` deep;
    ``step_error`` is the dynamic level's largest sum of linearisation errors over a stretch of
    overlap (:func:`experiments.stress.measures.accumulated_errors`)."""
    if level == "dynamic":
        return max(start_depth, DYNAMIC_PENETRATION) + step_error + EXACT_PENETRATION
    return max(start_depth, 0.0) + EXACT_PENETRATION


def dynamic_energy_allowance(scale: float) -> float:
    """Energy (mass length^2/s^2) a run may gain without input, once the wrench's work and the
    pose corrections' lift are subtracted: DYNAMIC_ENERGY_REL of the case's energy ``scale``."""
    return DYNAMIC_ENERGY_REL * scale


def broken(record: dict) -> tuple[list[str], list[str]]:
    """``(hard, soft)``: the kinds of bound a case's record breaks."""
    hard, soft = [], []
    if record["error"]:
        hard.append("exception")
    if record["nonfinite"]:
        hard.append("nonfinite")
    if record["max_depth"] > record["depth_allowed"]:
        hard.append("penetration")
    if record["energy_gain"] > record["energy_allowed"]:
        hard.append("energy")
    if record["crossed_step"] is not None:
        hard.append("crossing")
    if record["push_out"] > record["push_out_allowed"]:
        soft.append("push_out")
    for kind, key in (
        ("lcp_failure", "lcp_failures"),
        ("fallback", "fallbacks"),
        ("jam", "jams"),
        ("stall", "stalls"),
    ):
        if record[key] > 0:
            soft.append(kind)
    return hard, soft
