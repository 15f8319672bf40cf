"""The config of ``partfeeder optimize``: the objective, where to start, which methods, how
the optimum is judged.

Read from YAML with ``yaml.safe_load`` and validated field by field; an error names the field
and its allowed range. Example (``experiments/configs/optimize.yaml``)::

    name: optimize
    family: fig1-cup      # optional: a device family (issue 24), packaged by name or a file
                          # relative to this one; absent: the paper's 12-parameter feeder
    feeder: {friction: 0.05, restitution: 0.3}   # the scene's environment, as a sweep's
                          # (not with a family: its file holds its part, friction, inputs)
    objective:
      trials: 16          # K: fixed perturbation draws per evaluation (common to all designs)
      seed: 0             # of those draws
      weight: 5.0         # w of Eq. 10
      step: 0.001         # the dynamic level's h (s)
      t_max: 10.0         # longest drop (s): Eq. 10's T is capped there
    perturbations: {position: 0.05, yaw: 0.05, speed: 0.05, friction: 0.2, tolerance: 0.01}
    start:
      presets: [table3]   # named designs of the paper (feeders.design.PRESETS); with a
                          # family: [default], the family's default vector
      sweep_best: 6       # with --from SWEEP_DIR: that sweep's best designs by their verdict
    methods:              # each run on the same budget of evaluations, once per seed
      - {method: differential-evolution, budget: 600, seeds: [0], population: 20}
      - {method: cma-es, budget: 200, seeds: [0], start: best}   # refines the best so far
    final:                # fresh draws: the best `candidates` by R are validated on
      trials: 150         # `trials` trials (seed), the best of them is the optimum, whose
      seed: 1000          # reported verdict uses other draws again (seed + 1)
      target: 0.9
      candidates: 4
    workers: 2
    max_attempts: 2

With a family the design vector is the family's (its parameters, in its file's order, within
its box) and the family must have two entries (the store's two entry columns hold them).

Everything is plain data, so a config travels to worker processes and Dask workers as is (a
family as its file's text).
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments.config_files import resolve_config
from experiments.drop.perturbations import Perturbations
from experiments.family_config import (
    FAMILY_DEFAULT,
    family_of_text,
    read_family_field,
    text_digest,
)
from experiments.names import OPTIMIZER_NAMES, PRESET_NAMES
from experiments.optimize.centering import CenteringSettings
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

MAX_BUDGET = 1_000_000
MAX_TRIALS = 10_000
MAX_CENTERING_BUDGET = 10_000  # margins evaluations of design centering
METHOD_STARTS = ("starts", "best")
EQ10 = "eq10"  # minimise R, the robust form of Eq. 10 (the default)
ROBUSTNESS = "robustness"  # maximise the smallest normalised margin at the target (issue 34)
GOALS = (EQ10, ROBUSTNESS)
CENTERING_FIELDS = {
    "budget",
    "step",
    "min_step",
    "explore",
    "spread",
    "seed",
    "starts",
    "drops",
    "focus",
}


class OptimizeConfigError(FieldError):
    """An optimisation config that cannot be read or is not valid; names the field."""


@dataclass(frozen=True)
class Method:
    """One optimisation method, run once per seed on ``budget`` evaluations; ``population``
    for the population methods (differential evolution, CMA-ES; None: the method's own);
    ``start``: from the config's starts (``starts``), or from the best design the methods
    before it in the config found (``best``: a second stage that refines the first's)."""

    method: str
    budget: int
    seeds: tuple[int, ...] = (0,)
    population: int | None = None
    start: str = "starts"

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "method": self.method,
            "budget": self.budget,
            "seeds": list(self.seeds),
        }
        if self.population is not None:
            out["population"] = self.population
        if self.start != "starts":
            out["start"] = self.start
        return out


@dataclass(frozen=True)
class OptimizeConfig:
    """A validated optimisation config (module docstring for the fields)."""

    name: str
    methods: tuple[Method, ...]
    feeder: dict[str, Any] = field(default_factory=dict)
    trials: int = 16
    seed: int = 0
    weight: float = 5.0
    step: float = 0.001
    t_max: float = 10.0
    perturbations: dict[str, float] = field(default_factory=lambda: Perturbations().to_dict())
    presets: tuple[str, ...] = ("table3",)
    sweep_best: int = 6
    final_trials: int = 150
    final_seed: int = 1000
    final_target: float = 0.9
    final_candidates: int = 4
    workers: int = 2
    max_attempts: int = 2
    family: str | None = None  # the family file's absolute path; None: the 12-parameter feeder
    family_yaml: str = ""  # the family file's text, as read when the config was
    goal: str = EQ10  # what is optimised: Eq. 10's R (eq10) or the robustness (robustness)
    centering: CenteringSettings = field(default_factory=CenteringSettings)

    def device_family(self) -> DeviceFamily | None:
        """The config's device family (None: the 12-parameter feeder), read from its text."""
        if self.family is None:
            return None
        return family_of_text(self.family_yaml, Path(self.family).stem)

    def to_dict(self) -> dict[str, Any]:
        """The config as the YAML document it came from (normalised; plain data)."""
        return {
            "name": self.name,
            **({"family": self.family} if self.family is not None else {}),
            "feeder": dict(self.feeder),
            "objective": {
                "trials": self.trials,
                "seed": self.seed,
                "weight": self.weight,
                "step": self.step,
                "t_max": self.t_max,
            },
            "perturbations": dict(self.perturbations),
            "start": {"presets": list(self.presets), "sweep_best": self.sweep_best},
            "methods": [m.to_dict() for m in self.methods],
            "final": {
                "trials": self.final_trials,
                "seed": self.final_seed,
                "target": self.final_target,
                "candidates": self.final_candidates,
            },
            "workers": self.workers,
            "max_attempts": self.max_attempts,
            # only when not the default: an Eq. 10 config's dict (and digest) as before
            **(
                {"goal": self.goal, "centering": self.centering.to_dict()}
                if self.goal != EQ10
                else {}
            ),
        }

    def objective_key(self) -> str:
        """A digest of what decides an evaluation's value (feeder or the family file's text,
        objective, perturbations): the stored evaluations belong to one key."""
        data = self.to_dict()
        keep = {k: data[k] for k in ("feeder", "objective", "perturbations")}
        if self.family is not None:  # what the family says, not where its file lies
            keep["family"] = text_digest(self.family_yaml)
        return hashlib.sha256(json.dumps(keep, sort_keys=True).encode()).hexdigest()[:16]


def _method(spec: Any, field_name: str) -> Method:
    spec = mapping_field(spec, field_name, {"method", "budget", "seeds", "population", "start"})
    name = spec.get("method")
    if name not in OPTIMIZER_NAMES:
        raise OptimizeConfigError(
            f"{field_name}.method = {shown_value(name)}; allowed: {', '.join(OPTIMIZER_NAMES)}"
        )
    if "budget" not in spec:
        raise OptimizeConfigError(f"{field_name}.budget is required (evaluations per seed)")
    budget = integer_field(spec["budget"], f"{field_name}.budget", 1, MAX_BUDGET)
    seeds_spec = spec.get("seeds", [0])
    if not isinstance(seeds_spec, list) or not seeds_spec or len(seeds_spec) > 1000:
        raise OptimizeConfigError(
            f"{field_name}.seeds: expected a list of 1 to 1000 seeds, got {shown_value(seeds_spec)}"
        )
    seeds = tuple(
        integer_field(s, f"{field_name}.seeds[{i}]", 0, 2**31 - 1) for i, s in enumerate(seeds_spec)
    )
    if len(set(seeds)) != len(seeds):
        raise OptimizeConfigError(f"{field_name}.seeds: {list(seeds)} has a seed twice")
    population = None
    if spec.get("population") is not None:
        population = integer_field(spec["population"], f"{field_name}.population", 5, 10_000)
    start = spec.get("start", "starts")
    if start not in METHOD_STARTS:
        raise OptimizeConfigError(
            f"{field_name}.start = {shown_value(start)}; allowed: {', '.join(METHOD_STARTS)}"
        )
    return Method(name, budget, seeds, population, start)


def config_from_dict(data: Any, name: str = "optimize", base: str | Path = ".") -> OptimizeConfig:
    """Validate a parsed YAML document; raises :class:`OptimizeConfigError` naming the field.
    A ``family`` file is found relative to ``base`` (the config file's folder)."""
    with field_errors_as(OptimizeConfigError):
        return _config_from_dict(data, name, Path(base))


def _family_field(value: Any, base: Path) -> tuple[str, str]:
    """The ``family`` field: the family file's absolute path and text, the family checked (it
    reads, builds its default, has the two entries the store's columns hold)."""
    path, text, family = read_family_field(value, base, OptimizeConfigError)
    entries = [n for n, _ in family.entries]
    if len(entries) != 2:
        raise OptimizeConfigError(
            f"family: {shown(path)} has {len(entries)} entries {entries}; the optimiser needs 2 "
            "(the evaluations' two entry columns)"
        )
    return path, text


def _presets(start: dict[str, Any], family: str | None) -> list[str]:
    """``start.presets``: the paper's designs by name, or with a family ``default``."""
    allowed = [FAMILY_DEFAULT] if family is not None else list(PRESET_NAMES)
    presets = start.get("presets", [allowed[0]] if family is not None else ["table3"])
    if not isinstance(presets, list) or len(presets) > len(allowed):
        raise OptimizeConfigError(
            f"start.presets: expected a list of preset names, got {shown_value(presets)}"
        )
    for i, preset in enumerate(presets):
        if preset not in allowed:
            allowed_text = (
                f"allowed with family: {FAMILY_DEFAULT} (the family's default vector)"
                if family is not None
                else f"presets: {', '.join(allowed)}"
            )
            raise OptimizeConfigError(f"start.presets[{i}] = {shown_value(preset)}; {allowed_text}")
    return presets


def _config_from_dict(data: Any, name: str, base: Path) -> OptimizeConfig:
    data = mapping_field(
        data,
        "config",
        {
            "name",
            "family",
            "feeder",
            "objective",
            "perturbations",
            "start",
            "methods",
            "final",
            "workers",
            "max_attempts",
            "goal",
            "centering",
        },
    )
    goal = data.get("goal", EQ10)
    if goal not in GOALS:
        raise OptimizeConfigError(f"goal = {shown_value(goal)}; allowed: {', '.join(GOALS)}")
    centering = _centering(data.get("centering", {}) or {}, goal)
    family, family_yaml = None, ""
    if "family" in data:
        family, family_yaml = _family_field(data["family"], base)
    feeder = mapping_field(data.get("feeder", {}) or {}, "feeder", set(ENVIRONMENT_KEYS))
    if family is not None and feeder:
        raise OptimizeConfigError(
            f"feeder: {sorted(feeder)} given with family; allowed: none (the family's file "
            "holds its part, friction, restitution, gravity and inputs)"
        )
    environment_from_dict(feeder, prefix="feeder.")  # validate now, not in a worker
    objective = mapping_field(
        data.get("objective", {}) or {}, "objective", {"trials", "seed", "weight", "step", "t_max"}
    )
    noise = mapping_field(
        data.get("perturbations", {}) or {},
        "perturbations",
        set(Perturbations.__dataclass_fields__),
    )
    try:
        perturbations = Perturbations(**noise)
    except ValueError as exc:
        raise OptimizeConfigError(str(exc)) from None
    start = mapping_field(data.get("start", {}) or {}, "start", {"presets", "sweep_best"})
    presets = _presets(start, family)
    methods_spec = data.get("methods", [] if goal == ROBUSTNESS else None)
    if (
        not isinstance(methods_spec, list)
        or (not methods_spec and goal == EQ10)
        or len(methods_spec) > 100
    ):
        raise OptimizeConfigError(
            "methods: expected a list of 1 to 100 methods to run"
            + (" (0 to 100 with goal: robustness)" if goal == ROBUSTNESS else "")
        )
    methods = tuple(_method(m, f"methods[{i}]") for i, m in enumerate(methods_spec))
    names = [m.method for m in methods]
    if len(set(names)) != len(names):
        raise OptimizeConfigError(f"methods: {names} has a method twice (give it more seeds)")
    final = mapping_field(
        data.get("final", {}) or {}, "final", {"trials", "seed", "target", "candidates"}
    )
    return OptimizeConfig(
        name=name_field(data.get("name", name)),
        methods=methods,
        feeder=dict(feeder),
        trials=integer_field(objective.get("trials", 16), "objective.trials", 1, MAX_TRIALS),
        seed=integer_field(objective.get("seed", 0), "objective.seed", 0, 2**31 - 1),
        weight=number_field(objective.get("weight", 5.0), "objective.weight", 0.0, 1e6),
        step=number_field(objective.get("step", 0.001), "objective.step", 1e-6, 0.1),
        t_max=number_field(objective.get("t_max", 10.0), "objective.t_max", 1e-3, 3600.0),
        perturbations=perturbations.to_dict(),
        presets=tuple(presets),
        sweep_best=integer_field(start.get("sweep_best", 6), "start.sweep_best", 0, 1000),
        final_trials=integer_field(final.get("trials", 150), "final.trials", 1, MAX_TRIALS),
        final_seed=integer_field(final.get("seed", 1000), "final.seed", 0, 2**31 - 1),
        final_target=number_field(final.get("target", 0.9), "final.target", 0.0, 1.0),
        final_candidates=integer_field(final.get("candidates", 4), "final.candidates", 1, 100),
        workers=integer_field(data.get("workers", 2), "workers", 1, 1024),
        max_attempts=integer_field(data.get("max_attempts", 2), "max_attempts", 1, 100),
        family=family,
        family_yaml=family_yaml,
        goal=goal,
        centering=centering,
    )


def _centering(spec: Any, goal: str) -> CenteringSettings:
    """The ``centering`` section (design centering, the robust goal's method)."""
    spec = mapping_field(spec, "centering", CENTERING_FIELDS)
    if spec and goal != ROBUSTNESS:
        raise OptimizeConfigError(
            f"centering: given with goal {goal}; allowed only with goal: {ROBUSTNESS}"
        )
    d = CenteringSettings()
    return CenteringSettings(
        budget=integer_field(
            spec.get("budget", d.budget), "centering.budget", 1, MAX_CENTERING_BUDGET
        ),
        step=number_field(spec.get("step", d.step), "centering.step", 1e-3, 1.0),
        min_step=number_field(spec.get("min_step", d.min_step), "centering.min_step", 0.0, 1.0),
        explore=integer_field(spec.get("explore", d.explore), "centering.explore", 0, 100),
        spread=number_field(spec.get("spread", d.spread), "centering.spread", 0.0, 1.0),
        seed=integer_field(spec.get("seed", d.seed), "centering.seed", 0, 2**31 - 1),
        starts=integer_field(spec.get("starts", d.starts), "centering.starts", 1, 100),
        drops=integer_field(spec.get("drops", d.drops), "centering.drops", 1, MAX_TRIALS),
        focus=number_field(spec.get("focus", d.focus), "centering.focus", 0.0, 1e6),
    )


def with_budget(
    config: OptimizeConfig, evaluations: int | None = None, trials: int | None = None
) -> OptimizeConfig:
    """``config`` on another budget (``optimize --evaluations/--trials``), so a short run
    needs no edited copy of the YAML. ``evaluations``: every method's budget of evaluations
    per seed (``methods[].budget``) and, with goal robustness, the margins evaluations of
    design centering (``centering.budget``); ``trials``: the trials of every verdict on
    fresh draws (``final.trials``: the candidates', the optimum's, the baseline's). None
    keeps the config's. The objective's K draws (``objective.trials``) stay: they define
    the objective, so a resumed run's stored evaluations still count."""
    changed = config
    if evaluations is not None:
        changed = replace(
            changed,
            methods=tuple(replace(m, budget=evaluations) for m in changed.methods),
            centering=replace(changed.centering, budget=evaluations),
        )
    if trials is not None:
        changed = replace(changed, final_trials=trials)
    return changed


def load_config(path: str | Path) -> OptimizeConfig:
    """Read a config file (or a shipped one by name, e.g. ``optimize``)."""
    path = resolve_config(path)
    data = read_yaml(path, "config", OptimizeConfigError)
    try:
        return config_from_dict(data, name=path.stem, base=path.parent)
    except OptimizeConfigError as exc:
        raise OptimizeConfigError(f"{shown(path)}: {exc}") from None
