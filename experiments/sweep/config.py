"""The experiment config of ``partfeeder run``: which designs, which ladder, which budgets.

Read from YAML with ``yaml.safe_load`` and validated field by field; an error names the field
and its allowed range. Example (``experiments/configs/default.yaml``)::

    name: default
    family: fig1                          # optional: a device family (issue 24), packaged by
                                          # name or a file relative to this one; absent: the
                                          # paper's 12-parameter feeder
    designs: {count: 24, seed: 1}        # the first `count` points of the scrambled Halton
                                          # sequence over Table 2's box (a family's: its
                                          # parameters' box), seeded by `seed`
    feeder:                               # what every design's scene shares (all optional;
                                          # a family's file holds its own, so not with one)
      friction: 0.3
      restitution: 0.3
      inputs: {max_speed: 1, max_turn: 1, max_force: 10, max_torque: 2}
    planner: {step: 0.05, min_steps: 1, max_steps: 20}   # OMPL's propagation (optional)
    ladder:                               # climbed in this order
      - level: necessary                  # exact tests a design that works passes
      - level: screen                     # coarse-step drops, one entry at a time, that
        screen: {step: 0.004, false_fails: 0.001, false_works: 0.1, max_drops: 60}
                                          # fail a design only on strong evidence
      - level: geometric
        planners: [rrt]                   # rrt, kpiece, est
        runs: 1                           # runs per planner and entry orientation
        budget: {time: 0.5}               # s per run; or {propagations: 20000, time: 60}
        prunes: false                     # a design not planned within the budget
                                          # ("unknown") still climbs; true: it stops here
      - ...
      - level: passive                    # the design's verdict: success probability over
        verdict: {target: 0.9, min_drops: 5, batch: 10, max_drops: 200}   # perturbed
        perturbations: {position: 0.05, yaw: 0.05, speed: 0.05, friction: 0.2, tolerance: 0.01}
        # or Wald's SPRT per entry, a look after every trial (docs/verdict.md):
        # verdict: {rule: sprt, works_p: 0.95, fails_p: 0.8, error: 0.01, min_drops: 1, batch: 1}
    holdout: {fraction: 0.25, seed: 7}    # designs that climb every rung whatever their
                                          # verdicts: the sample that measures the pruning
    audit: {fraction: 1.0, seed: 11}      # designs that reach the verdict whatever the
                                          # rungs below it say (they climb no further unless
                                          # they work): what the screen and any rung that
                                          # stops designs before the verdict threw away
    workers: 2                            # processes (local executor)
    max_attempts: 2                       # worker deaths before a design is quarantined
    report: {margins: device}             # whose margins the report measures: device (the
                                          # confirmed designs' and the baseline's, over the
                                          # parameters and mu, to rank them by robustness),
                                          # all (the part's axes too) or skip

A family config may not have the ``necessary`` rung (its tests are the 12-parameter feeder's)
and its family must have two entries (the results' two entry columns hold them, in the file's
order).

Everything is plain data, so a config travels to worker processes and Dask workers as is.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments.config_files import resolve_config
from experiments.family_config import family_of_text, read_family_field, text_digest
from experiments.names import LEVEL_NAMES, NECESSARY, PASSIVE, PLANNER_NAMES, RUNG_NAMES, SCREEN
from experiments.sweep.family import column_problem
from feeders.fields import (
    FieldError,
    field_errors_as,
    integer_field,
    mapping_field,
    name_field,
    number_field,
    read_yaml,
    shown,
    shown_value,
)
from feeders.scene_yaml import ENVIRONMENT_KEYS, environment_from_dict

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

MAX_DESIGNS = 1_000_000
_FAMILY_RUNGS = tuple(r for r in RUNG_NAMES if r != NECESSARY)


class ConfigError(FieldError):
    """An experiment config that cannot be read or is not valid; names the field."""


@dataclass(frozen=True)
class Rung:
    """One rung of the ladder. A planning level: its planners, runs per planner and
    orientation, budget, and ``prunes``: whether a design its planners did not solve within
    the budget (status ``unknown``: a sampling planner proves nothing by failing) stops
    climbing here (False, the default: it climbs on as if feasible; True: the paper's
    pruning, which can throw away designs that work, issue 21). The passive rung (``level:
    passive``): the verdict's settings and perturbations
    (:class:`experiments.drop.verdict.VerdictSettings`,
    :class:`experiments.drop.perturbations.Perturbations`), every field filled in."""

    level: str
    planners: tuple[str, ...]
    runs: int = 1
    time_s: float = 1.0
    propagations: int | None = None
    verdict: dict[str, Any] = field(default_factory=dict)
    perturbations: dict[str, float] = field(default_factory=dict)
    prunes: bool = False

    def to_dict(self) -> dict[str, Any]:
        """The rung as its YAML mapping (normalised; plain data)."""
        if self.level == PASSIVE:
            return {
                "level": self.level,
                "verdict": dict(self.verdict),
                "perturbations": dict(self.perturbations),
            }
        if self.level == NECESSARY:
            return {"level": self.level, "perturbations": dict(self.perturbations)}
        if self.level == SCREEN:
            return {
                "level": self.level,
                "screen": dict(self.verdict),
                "perturbations": dict(self.perturbations),
            }
        budget: dict[str, Any] = {"time": self.time_s}
        if self.propagations is not None:
            budget["propagations"] = self.propagations
        return {
            "level": self.level,
            "planners": list(self.planners),
            "runs": self.runs,
            "budget": budget,
            "prunes": self.prunes,
        }


@dataclass(frozen=True)
class SweepConfig:
    """A validated experiment config (see the module docstring for the fields)."""

    name: str
    count: int
    seed: int
    ladder: tuple[Rung, ...]
    feeder: dict[str, Any] = field(default_factory=dict)
    planner: dict[str, Any] = field(default_factory=dict)
    holdout_fraction: float = 0.0
    holdout_seed: int = 0
    audit_fraction: float = 0.0
    audit_seed: int = 0
    workers: int = 2
    max_attempts: int = 2
    family: str | None = None  # the family file's absolute path; None: the 12-parameter feeder
    family_yaml: str = ""  # the family file's text, as read when the config was
    report_margins: str = "device"  # whose margins the report measures, and on which axes

    def device_family(self) -> DeviceFamily | None:
        """The config's device family (None: the 12-parameter feeder), read from its text."""
        if self.family is None:
            return None
        return family_of_text(self.family_yaml, Path(self.family).stem)

    def to_dict(self) -> dict[str, Any]:
        """The config as the YAML document it came from (normalised; plain data)."""
        ladder = [r.to_dict() for r in self.ladder]
        return {
            "name": self.name,
            **({"family": self.family} if self.family is not None else {}),
            "designs": {"count": self.count, "seed": self.seed},
            "feeder": dict(self.feeder),
            "planner": dict(self.planner),
            "ladder": ladder,
            "holdout": {"fraction": self.holdout_fraction, "seed": self.holdout_seed},
            **(
                {"audit": {"fraction": self.audit_fraction, "seed": self.audit_seed}}
                if self.audit_fraction > 0.0
                else {}  # no audit: the document (and the results key) it had before audits
            ),
            "workers": self.workers,
            "max_attempts": self.max_attempts,
            # the default is left out: the document a config had before ``report``
            **(
                {"report": {"margins": self.report_margins}}
                if self.report_margins != REPORT_MARGINS[0]
                else {}
            ),
        }

    def results_key(self) -> str:
        """A digest of everything that decides the results (not ``workers``, which only
        decides how fast they come): a results database belongs to one key."""
        data = self.to_dict()
        data.pop("workers")
        data.pop("name")
        data.pop("report", None)  # what the report measures decides no result
        if "family" in data:  # what the family says, not where its file lies
            data["family"] = text_digest(self.family_yaml)
        for rung in data["ladder"]:  # the default is left out: such a config keeps the key
            if rung.get("prunes") is False:  # it had before ``prunes`` existed
                del rung["prunes"]
        return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()[:16]


def _passive_rung(spec: Any, field_name: str) -> Rung:
    """The passive rung: its settings checked by the classes that use them."""
    from experiments.drop.verdict_settings import VerdictSettings

    settings = _drop_settings(spec, field_name, "verdict", VERDICT_KEYS, VerdictSettings)
    return Rung(
        PASSIVE,
        (),
        verdict={
            **{k: getattr(settings, k) for k in sorted(WILSON_KEYS)},
            **settings.rule_fields(),
        },
        perturbations=settings.perturbations.to_dict(),
    )


def _drop_settings(spec: Any, field_name: str, key: str, keys: set[str], kind: Any) -> Any:
    """A drop rung's settings (``kind``: the verdict's or the screen's, read from the rung's
    ``key`` with the fields ``keys``) with the rung's ``perturbations``, checked by the
    classes that use them; :class:`ConfigError` naming the field."""
    from experiments.drop.perturbations import Perturbations

    spec = mapping_field(spec, field_name, {"level", key, "perturbations"})
    given = mapping_field(spec.get(key, {}) or {}, f"{field_name}.{key}", keys)
    noise = mapping_field(
        spec.get("perturbations", {}) or {},
        f"{field_name}.perturbations",
        set(Perturbations.__dataclass_fields__),
    )
    try:
        return kind(**given, perturbations=Perturbations(**noise))
    except ValueError as exc:
        raise ConfigError(f"{field_name}.{exc}") from None


# ``report.margins``: "device" measures the margins of the confirmed designs and the baseline
# over the device's axes (parameters, mu) to rank them by robustness; "all" adds the part's
# axes; "skip" measures none (the recommendation is then by reliability alone)
REPORT_MARGINS = ("device", "all", "skip")
WILSON_KEYS = {"target", "min_drops", "batch", "max_drops", "step", "t_max"}
# the SPRT's, held only when it is the rule (a Wilson config keeps its results key)
VERDICT_KEYS = WILSON_KEYS | {"rule", "works_p", "fails_p", "error"}


NECESSARY_NOISE = ("tolerance", "position", "yaw")  # what the necessary tests allow for


def _necessary_rung(spec: Any, field_name: str) -> Rung:
    """The necessary-conditions rung: the made feeders' tolerance and the entry's position
    and yaw perturbations it allows for (default: the verdict's, ``Perturbations()``). It
    prunes: its tests fail only designs that cannot work (docs/necessary.md)."""
    from experiments.drop.perturbations import Perturbations

    spec = mapping_field(spec, field_name, {"level", "perturbations"})
    noise = mapping_field(
        spec.get("perturbations", {}) or {}, f"{field_name}.perturbations", set(NECESSARY_NOISE)
    )
    try:
        perturbations = Perturbations(**noise)
    except ValueError as exc:
        raise ConfigError(f"{field_name}.{exc}") from None
    kept = {k: getattr(perturbations, k) for k in NECESSARY_NOISE}
    return Rung(NECESSARY, (), perturbations=kept, prunes=True)


def _screen_rung(spec: Any, field_name: str) -> Rung:
    """The screen rung: its test's settings and the perturbations of its drops (default:
    the verdict's), checked by the classes that use them. A design the screen fails stops
    (a statistical prune, with the stated error); one it leaves undecided climbs on
    (an undecided screen proves nothing)."""
    from experiments.drop.screen_settings import ScreenSettings

    keys = set(ScreenSettings.__dataclass_fields__) - {"perturbations"}
    settings = _drop_settings(spec, field_name, "screen", keys, ScreenSettings)
    return Rung(
        SCREEN, (), verdict=settings.fields(), perturbations=settings.perturbations.to_dict()
    )


def _rung(spec: Any, field_name: str) -> Rung:
    if isinstance(spec, dict) and spec.get("level") == PASSIVE:
        return _passive_rung(spec, field_name)
    if isinstance(spec, dict) and spec.get("level") == SCREEN:
        return _screen_rung(spec, field_name)
    if isinstance(spec, dict) and spec.get("level") == NECESSARY:
        return _necessary_rung(spec, field_name)
    spec = mapping_field(spec, field_name, {"level", "planners", "runs", "budget", "prunes"})
    level = spec.get("level")
    if not isinstance(level, str) or level not in LEVEL_NAMES:
        raise ConfigError(
            f"{field_name}.level = {shown_value(level)}; allowed: {', '.join(RUNG_NAMES)}"
        )
    planners = spec.get("planners", ["rrt"])
    if not isinstance(planners, list) or not planners:
        raise ConfigError(f"{field_name}.planners: expected a non-empty list of planner names")
    for i, p in enumerate(planners):
        if not isinstance(p, str) or p.lower() not in PLANNER_NAMES:
            raise ConfigError(
                f"{field_name}.planners[{i}] = {shown_value(p)}; "
                f"allowed: {', '.join(PLANNER_NAMES)}"
            )
    planners = [p.lower() for p in planners]
    if len(set(planners)) != len(planners):
        raise ConfigError(
            f"{field_name}.planners: {planners} names a planner twice; each at most once"
        )
    runs = integer_field(spec.get("runs", 1), f"{field_name}.runs", 1, 1000)
    budget = mapping_field(spec.get("budget", {}), f"{field_name}.budget", {"time", "propagations"})
    if not budget:
        raise ConfigError(f"{field_name}.budget: give 'time' (s) and/or 'propagations'")
    propagations = None
    if "propagations" in budget:
        propagations = integer_field(
            budget["propagations"], f"{field_name}.budget.propagations", 1, 10**9
        )
    # With a count budget the time is only a cap: generous unless given.
    default_time = 600.0 if propagations is not None else 1.0
    time_s = number_field(
        budget.get("time", default_time), f"{field_name}.budget.time", 1e-3, 86400.0
    )
    prunes = spec.get("prunes", False)
    if not isinstance(prunes, bool):
        raise ConfigError(f"{field_name}.prunes = {shown_value(prunes)}; allowed: true, false")
    return Rung(level, tuple(planners), runs, time_s, propagations, prunes=prunes)


def config_from_dict(data: Any, name: str = "sweep", base: str | Path = ".") -> SweepConfig:
    """Validate a parsed YAML document; raises :class:`ConfigError` naming the field. A
    ``family`` file is found relative to ``base`` (the config file's folder)."""
    with field_errors_as(ConfigError):
        return _config_from_dict(data, name, Path(base))


def _family_field(value: Any, base: Path) -> tuple[str, str]:
    """The ``family`` field: the family file's absolute path and text, the family checked
    (it reads, its parameters can name results columns, it has two entries)."""
    path, text, family = read_family_field(value, base, ConfigError)
    problem = column_problem(family)
    if problem:
        raise ConfigError(f"family: {shown(path)}: {problem}")
    entries = [n for n, _ in family.entries]
    if len(entries) != 2:
        raise ConfigError(
            f"family: {shown(path)} has {len(entries)} entries {entries}; a sweep needs 2 "
            "(the verdict's two entry columns)"
        )
    return str(path), text


def _config_from_dict(data: Any, name: str, base: Path) -> SweepConfig:
    data = mapping_field(
        data,
        "config",
        {
            "name",
            "family",
            "designs",
            "feeder",
            "planner",
            "ladder",
            "holdout",
            "audit",
            "workers",
            "max_attempts",
            "report",
        },
    )
    family, family_yaml = None, ""
    if "family" in data:
        family, family_yaml = _family_field(data["family"], base)
    designs = mapping_field(data.get("designs"), "designs", {"count", "seed"})
    if "count" not in designs:
        raise ConfigError("designs.count is required (number of Halton designs)")
    count = integer_field(designs["count"], "designs.count", 1, MAX_DESIGNS)
    seed = integer_field(designs.get("seed", 1), "designs.seed", 0, 2**31 - 1)
    feeder = mapping_field(data.get("feeder", {}) or {}, "feeder", set(ENVIRONMENT_KEYS))
    if family is not None and feeder:
        raise ConfigError(
            f"feeder: {sorted(feeder)} given with family; allowed: none (the family's file "
            "holds its part, friction, restitution, gravity and inputs)"
        )
    environment_from_dict(feeder, prefix="feeder.")  # validate now, not in a worker
    planner = mapping_field(
        data.get("planner", {}) or {}, "planner", {"step", "min_steps", "max_steps"}
    )
    if "step" in planner:
        number_field(planner["step"], "planner.step", 1e-4, 10.0)
    for key in ("min_steps", "max_steps"):
        if key in planner:
            integer_field(planner[key], f"planner.{key}", 1, 10_000)
    if planner.get("min_steps", 1) > planner.get("max_steps", 20):
        raise ConfigError("planner: need min_steps <= max_steps")
    ladder_spec = data.get("ladder")
    if not isinstance(ladder_spec, list) or not ladder_spec:
        raise ConfigError("ladder: expected a non-empty list of levels to climb")
    ladder = tuple(_rung(spec, f"ladder[{i}]") for i, spec in enumerate(ladder_spec))
    levels = [r.level for r in ladder]
    if family is not None and NECESSARY in levels:
        raise ConfigError(
            f"ladder[{levels.index(NECESSARY)}].level = {NECESSARY}: the necessary conditions "
            f"are the 12-parameter feeder's; allowed with family: {', '.join(_FAMILY_RUNGS)}"
        )
    if len(set(levels)) != len(levels):
        raise ConfigError(f"ladder: {levels} has a level twice")
    order = [LEVEL_NAMES.index(level) for level in levels if level in LEVEL_NAMES]
    if order != sorted(order):
        raise ConfigError(
            f"ladder: {levels} must climb the planning levels in order {', '.join(LEVEL_NAMES)} "
            f"(the {PASSIVE}, {NECESSARY} and {SCREEN} rungs may stand anywhere)"
        )
    holdout = mapping_field(data.get("holdout", {}) or {}, "holdout", {"fraction", "seed"})
    fraction = number_field(holdout.get("fraction", 0.0), "holdout.fraction", 0.0, 1.0)
    holdout_seed = integer_field(holdout.get("seed", 0), "holdout.seed", 0, 2**31 - 1)
    audit = mapping_field(data.get("audit", {}) or {}, "audit", {"fraction", "seed"})
    audit_fraction = number_field(audit.get("fraction", 0.0), "audit.fraction", 0.0, 1.0)
    audit_seed = integer_field(audit.get("seed", 0), "audit.seed", 0, 2**31 - 1)
    workers = integer_field(data.get("workers", 2), "workers", 1, 1024)
    attempts = integer_field(data.get("max_attempts", 2), "max_attempts", 1, 100)
    report = mapping_field(data.get("report", {}) or {}, "report", {"margins"})
    report_margins = report.get("margins", REPORT_MARGINS[0])
    if report_margins not in REPORT_MARGINS:
        raise ConfigError(
            f"report.margins = {shown_value(report_margins)}; allowed: {', '.join(REPORT_MARGINS)}"
        )
    return SweepConfig(
        name=name_field(data.get("name", name)),
        count=count,
        seed=seed,
        ladder=ladder,
        feeder=dict(feeder),
        planner=dict(planner),
        holdout_fraction=fraction,
        holdout_seed=holdout_seed,
        audit_fraction=audit_fraction,
        audit_seed=audit_seed,
        workers=workers,
        max_attempts=attempts,
        family=family,
        family_yaml=family_yaml,
        report_margins=str(report_margins),
    )


def load_config(path: str | Path) -> SweepConfig:
    """Read a config file (or a shipped config by name: ``default``, ``paper``)."""
    path = resolve_config(path)
    data = read_yaml(path, "config", ConfigError)
    try:
        return config_from_dict(data, name=path.stem, base=path.parent)
    except ConfigError as exc:
        raise ConfigError(f"{shown(path)}: {exc}") from None
