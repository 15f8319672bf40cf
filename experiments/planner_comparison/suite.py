"""The comparison's config: which designs, levels, planners, runs and budgets.

A YAML file (read with the project's safe loader, :func:`feeders.fields.read_yaml`); every
field is checked here, and a bad one is a :class:`SuiteError` naming it and its allowed range
(one line, exit status 2 on the command line). The shipped suites are in :mod:`.shipped`.

A design is one of ``{preset: NAME}`` (Figs. 4-9, Table 3), ``{halton: {seed: S, index:
I}}`` (the I-th scrambled Halton design of seed S, as a sweep draws them), ``{family: NAME or
FILE, values: [...]}`` (a device family's design; default values when ``values`` is left
out) or ``{scene: FILE}`` (a scene YAML file; relative to the config). Every design is
planned from each of its scene's entries.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from feeders.fields import (
    FieldError,
    field_errors_as,
    integer_field,
    mapping_field,
    name_field,
    numbers_field,
    read_yaml,
)

LEVELS = ("geometric", "kinematic", "dynamic")
MAX_RUNS = 1000
MAX_BUDGET = 10**8  # propagations of one run
MAX_DESIGNS = 500
MAX_BOOTSTRAP = 100_000
FIELDS = {
    "name",
    "designs",
    "levels",
    "planners",
    "runs",
    "budgets",
    "seed",
    "plan_unsolvable",
    "bootstrap",
    "progress_samples",
}


class SuiteError(FieldError):
    """A field of a planner comparison config that is missing, of the wrong type or out of
    range."""


@dataclass(frozen=True)
class Suite:
    """A comparison: ``designs`` (plain dicts, one key: preset, halton, family or scene),
    ``levels``, ``planners`` (names of :func:`planners.registry.make_planner`), ``runs`` per
    planner and problem, ``budgets`` (propagations per run, per level), ``seed`` (run r of
    every planner is seeded with seed + r; also the bootstrap's), ``plan_unsolvable``
    (whether problems known to be unsolvable are planned anyway, as a check of the
    necessary conditions), ``bootstrap`` (resamples of the problems for the best planner's
    interval) and ``progress_samples`` (progress points per run in Planner Arena's
    database)."""

    name: str
    designs: tuple[dict[str, Any], ...]
    levels: tuple[str, ...]
    planners: tuple[str, ...]
    runs: int
    budgets: dict[str, int]
    seed: int = 1
    plan_unsolvable: bool = True
    bootstrap: int = 1000
    progress_samples: int = 20
    base: str = field(default=".")  # the directory relative paths in designs are read from

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "designs": [dict(d) for d in self.designs],
            "levels": list(self.levels),
            "planners": list(self.planners),
            "runs": self.runs,
            "budgets": dict(self.budgets),
            "seed": self.seed,
            "plan_unsolvable": self.plan_unsolvable,
            "bootstrap": self.bootstrap,
            "progress_samples": self.progress_samples,
        }


def load_suite(path: Path) -> Suite:
    """The config in ``path`` (SuiteError naming the field for a bad one)."""
    document = read_yaml(Path(path), "planner comparison config", SuiteError)
    return suite_from_dict(document, base=Path(path).resolve().parent)


def suite_from_dict(document: Any, base: Path = Path(".")) -> Suite:
    """A :class:`Suite` from a config's mapping, every field checked."""
    from experiments.names import PRESET_NAMES

    with field_errors_as(SuiteError):
        doc = mapping_field(document, "config", FIELDS)
        for key in ("name", "designs", "planners", "runs", "budgets"):
            if key not in doc:
                raise SuiteError(f"config: missing field '{key}'")
        name = name_field(doc["name"])
        levels = _names(doc.get("levels", list(LEVELS)), "levels", LEVELS)
        planners = _planners(doc["planners"])
        runs = integer_field(doc["runs"], "runs", 1, MAX_RUNS)
        budgets_doc = mapping_field(doc["budgets"], "budgets", set(LEVELS))
        budgets = {}
        for level in levels:
            if level not in budgets_doc:
                raise SuiteError(f"budgets: missing the budget of level '{level}' (propagations)")
            budgets[level] = integer_field(budgets_doc[level], f"budgets.{level}", 1, MAX_BUDGET)
        designs = doc["designs"]
        if not isinstance(designs, list) or not 1 <= len(designs) <= MAX_DESIGNS:
            raise SuiteError(f"designs: expected a list of 1 to {MAX_DESIGNS} designs")
        checked = tuple(_design(d, f"designs[{i}]", PRESET_NAMES) for i, d in enumerate(designs))
        seed = integer_field(doc.get("seed", 1), "seed", 1, 2**31 - 1 - MAX_RUNS)
        plan_unsolvable = doc.get("plan_unsolvable", True)
        if not isinstance(plan_unsolvable, bool):
            raise SuiteError("plan_unsolvable: expected true or false")
        bootstrap = integer_field(doc.get("bootstrap", 1000), "bootstrap", 1, MAX_BOOTSTRAP)
        samples = integer_field(doc.get("progress_samples", 20), "progress_samples", 1, 1000)
    return Suite(
        name=name,
        designs=checked,
        levels=levels,
        planners=planners,
        runs=runs,
        budgets=budgets,
        seed=seed,
        plan_unsolvable=plan_unsolvable,
        bootstrap=bootstrap,
        progress_samples=samples,
        base=str(base),
    )


def _names(value: Any, field_name: str, allowed: tuple[str, ...]) -> tuple[str, ...]:
    if not isinstance(value, list) or not value:
        raise SuiteError(f"{field_name}: expected a list of one or more of {', '.join(allowed)}")
    for i, item in enumerate(value):
        if item not in allowed:
            raise SuiteError(f"{field_name}[{i}] = {item!r}: one of {', '.join(allowed)}")
    if len(set(value)) != len(value):
        raise SuiteError(f"{field_name}: a name is listed twice")
    return tuple(value)


def _planners(value: Any) -> tuple[str, ...]:
    """Planner names, checked against :mod:`planners.registry` (which imports OMPL)."""
    from planners.registry import UNAVAILABLE, planner_names

    AVAILABLE = planner_names()

    if not isinstance(value, list) or not value:
        raise SuiteError(f"planners: expected a list of one or more of {', '.join(AVAILABLE)}")
    for i, item in enumerate(value):
        if item in UNAVAILABLE:
            raise SuiteError(f"planners[{i}] = {item!r} cannot run: {UNAVAILABLE[item]}")
        if item not in AVAILABLE:
            raise SuiteError(f"planners[{i}] = {item!r}: one of {', '.join(AVAILABLE)}")
    if len(set(value)) != len(value):
        raise SuiteError("planners: a planner is listed twice")
    return tuple(value)


def _design(value: Any, where: str, presets: tuple[str, ...]) -> dict[str, Any]:
    d = mapping_field(value, where, {"preset", "halton", "family", "values", "scene"})
    kinds = [k for k in ("preset", "halton", "family", "scene") if k in d]
    if len(kinds) != 1:
        raise SuiteError(f"{where}: give exactly one of preset, halton, family, scene")
    kind = kinds[0]
    if "values" in d and kind != "family":
        raise SuiteError(f"{where}.values: only a family's design has values")
    if kind == "preset":
        if d["preset"] not in presets:
            raise SuiteError(f"{where}.preset = {d['preset']!r}: one of {', '.join(presets)}")
        return {"preset": d["preset"]}
    if kind == "halton":
        h = mapping_field(d["halton"], f"{where}.halton", {"seed", "index"})
        return {
            "halton": {
                "seed": integer_field(h.get("seed", 0), f"{where}.halton.seed", 0, 2**31 - 1),
                "index": integer_field(h.get("index"), f"{where}.halton.index", 0, 100_000),
            }
        }
    if kind == "family":
        family = name_field(d["family"], f"{where}.family")
        out: dict[str, Any] = {"family": family}
        if "values" in d:
            values = d["values"]
            count = len(values) if isinstance(values, list) else -1
            out["values"] = numbers_field(values, f"{where}.values", max(count, 1))
        return out
    scene = d["scene"]
    if not isinstance(scene, str) or not scene:
        raise SuiteError(f"{where}.scene: expected a scene YAML file's path")
    return {"scene": scene}


def design_name(design: dict[str, Any]) -> str:
    """A short name of a design, one word (Planner Arena's problem names are one word)."""
    if "preset" in design:
        return str(design["preset"])
    if "halton" in design:
        h = design["halton"]
        return f"halton-s{h['seed']}-{h['index']}"
    if "family" in design:
        stem = Path(str(design["family"])).stem
        return stem if "values" not in design else f"{stem}-custom"
    return Path(str(design["scene"])).stem
