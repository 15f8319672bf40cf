"""The design optimisation (paper Section 4, Eq. 10-11), made robust: its steps in order.

1. The starts (the config's presets and, with ``--from``, a sweep's best designs by their
   verdict) are clipped into Table 2's box (a device family's: its box) and evaluated.
2. Every method of the config runs once per seed on its budget of evaluations
   (:mod:`experiments.optimize.methods`), all on the same robust objective
   (:mod:`experiments.optimize.objective`) and the same stored evaluations.
3. Validation: the ``final.candidates`` designs with the lowest R get a verdict on fresh
   draws (``final.trials`` trials, seed ``final.seed``): R was selected on the K draws, so
   the best R flatters its design (measured: a design 12 of 12 on its K draws was 98 of 100 on
   fresh ones). The optimum is the candidate with the highest lower bound of P(both) there,
   then the lowest mean G.
4. The optimum and the baseline (the paper's table3 unless another is given) get their
   reported verdict on other fresh draws (seed ``final.seed + 1``, the same for both: a paired
   comparison, :mod:`experiments.optimize.comparison`, and not the draws the optimum was
   chosen on), and one nominal drop per entry each (Eq. 10's G as the paper computes it).
   A device family's baseline is its default vector; the comparison's section (parameter
   differences over Table 2's box, the feeders drawn over each other) is the 12-parameter
   feeder's, so a family's results have the two verdicts without it.
5. When the optimum works on those draws, its tolerance margins
   (:mod:`experiments.optimize.tolerance`; a device family's too): the
   feeder's axes are its 12 parameters, friction and the peg's dimensions, a family's its
   parameters over its box and friction (:mod:`experiments.margins.axes`).

Every evaluation, verdict and margin is stored as it finishes
(:mod:`experiments.optimize.store`): a run started again in the same directory repeats none
of them, and another baseline costs only its own verdict.
"""

from __future__ import annotations

import dataclasses
import math
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from experiments.drop.family_verdict import entry_names
from experiments.drop.passive import eq10_objective, passive_drop
from experiments.drop.sequential import short_of_working
from experiments.drop.verdict import Verdict, classes_of
from experiments.executors import open_pool
from experiments.family_config import family_default, family_record
from experiments.optimize import store
from experiments.optimize.comparison import stored_comparison, verdict_of_trials
from experiments.optimize.config import ROBUSTNESS, OptimizeConfig
from experiments.optimize.evaluator import BudgetSpent, Evaluator, Progress
from experiments.optimize.methods import METHODS, POPULATION_METHODS
from experiments.optimize.objective import eq10_terms
from experiments.optimize.tolerance import (
    AxisCallback,
    family_margins,
    optimum_margins,
    robust_settings_key,
    settings_key,
)
from experiments.proportions import wilson_interval
from feeders.design import DESIGN_SPACE, PARAMETER_NAMES, DesignParameters, preset
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.scene_yaml import environment_from_dict

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily
    from feeders.scene import Scene

DATABASE = "evaluations.sqlite"
REFERENCE = "table3"  # the baseline unless another is given
STARTS_RUN = "starts"
OPTIMUM = "optimum"

Baseline = tuple[str, list[float]]  # (label, the design's values: 12, or a family's)


@dataclasses.dataclass(frozen=True)
class Designed:
    """What an optimisation designs: the parameters' names and box, the entries' names, and
    the device family (None: the paper's 12-parameter feeder, Table 2's box)."""

    names: tuple[str, ...]
    low: np.ndarray
    high: np.ndarray
    entries: tuple[str, ...]
    family: DeviceFamily | None = None

    def scene(self, config: OptimizeConfig, values: list[float], name: str = "") -> Scene:
        """The nominal device of ``values`` (``DegenerateDesign`` when it cannot be built)."""
        if self.family is not None:
            scene = self.family.build(values)
            return dataclasses.replace(scene, name=name) if name else scene
        environment = environment_from_dict(config.feeder)
        part, friction = environment.pop("part"), environment.pop("friction")
        if name:
            environment["name"] = name
        return build_feeder(
            DesignParameters.from_vector(values), part, friction=friction, **environment
        )

    def classes(self) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
        """The verdicts' outcome classes and the goal's (a family's, from its default
        device); None: the feeder's."""
        if self.family is None:
            return None
        return classes_of(self.family.build(self.family.default()))


def designed(config: OptimizeConfig) -> Designed:
    """What ``config`` designs: its family's parameters, box and entries, or the feeder's."""
    family = config.device_family()
    if family is None:
        return Designed(PARAMETER_NAMES, DESIGN_SPACE.low, DESIGN_SPACE.high, ORIENTATIONS)
    low, high = family.bounds()
    return Designed(
        tuple(family.vector_names),
        np.asarray(low, dtype=float),
        np.asarray(high, dtype=float),
        entry_names(family),
        family,
    )


def default_baseline(config: OptimizeConfig | None = None) -> Baseline:
    """The paper's table3, as ``(label, 12 values)``; a family's default vector (labelled
    ``default``) when ``config`` designs a family."""
    family = None if config is None else config.device_family()
    if family is not None:
        return family_default(family)
    return REFERENCE, preset(REFERENCE).to_vector().tolist()


def to_unit(values: np.ndarray, space: Designed | None = None) -> np.ndarray:
    """Designs (n, d) as points of the unit cube over the box (Table 2's unless ``space``
    gives a family's), clipped into it."""
    low = DESIGN_SPACE.low if space is None else space.low
    high = DESIGN_SPACE.high if space is None else space.high
    return np.clip((np.asarray(values, dtype=float) - low) / (high - low), 0.0, 1.0)


def from_unit(unit: np.ndarray, space: Designed | None = None) -> np.ndarray:
    """Points of the unit cube (n, d), clipped into it, as designs in the box (Table 2's
    unless ``space`` gives a family's)."""
    unit = np.clip(np.asarray(unit, dtype=float), 0.0, 1.0)
    if space is None:
        return DESIGN_SPACE.scale(unit)
    return space.low + unit * (space.high - space.low)


def start_designs(config: OptimizeConfig, sweep_best: list[dict]) -> dict[str, list[float]]:
    """Name -> design values of every start, in the box (Table 2's, or the family's): the
    presets (a family's ``default``: its default vector), then the sweep's best (named
    ``sweep:<design_id>``)."""
    space = designed(config)
    if space.family is not None:
        family = space.family
        starts = {name: np.asarray(family.default(), dtype=float) for name in config.presets}
    else:
        starts = {name: preset(name).to_vector() for name in config.presets}
    for b in sweep_best[: config.sweep_best]:
        starts[f"sweep:{b['design_id']}"] = np.asarray(b["values"], dtype=float)
    # clipped in design space, not mapped through the unit cube: a design inside the box is
    # kept to the last bit (contact is chaotic: 1e-16 changes a drop)
    return {name: np.clip(v, space.low, space.high).tolist() for name, v in starts.items()}


def run_label(method: str, seed: int) -> str:
    return f"{method}/seed{seed}"


def optimise(
    config: OptimizeConfig,
    out: Path,
    sweep_best: list[dict] | None = None,
    executor: str = "local",
    scheduler: str | None = None,
    progress: Progress | None = None,
    baseline: Baseline | None = None,
    margins: bool = True,
    measure: Any = None,
) -> dict[str, Any]:
    """Run the optimisation of ``config`` in directory ``out`` (resuming what is stored there)
    and return its results as plain data (:func:`results`). ``baseline`` ``(label, values)``,
    table3 (a family's default) unless given, is judged on the optimum's fresh draws;
    ``margins``: the optimum's margins are measured (or read from the store) when it works
    (the 12-parameter feeder's only). With ``goal: robustness`` the optimum is design
    centering's (:func:`_robust`), ``measure`` replacing the margins' measurement (tests)."""
    starts = start_designs(config, sweep_best or [])
    if not starts:
        raise ValueError("start: no start designs (give start.presets, or --from a sweep)")
    space = designed(config)
    baseline = baseline or default_baseline(config)
    label, base_values = baseline[0], [float(v) for v in baseline[1]]
    base_key = store.design_key(base_values)
    db = store.connect(out / DATABASE)
    try:
        claimed = {**config.to_dict(), "starts": starts}
        if space.family is not None:  # the family as it was: its record, the file's text
            claimed["family_record"] = family_record(space.family, config.family_yaml)
        store.claim(db, claimed, config.objective_key())
        t0 = time.perf_counter()
        with open_pool(executor, config.workers, config.max_attempts, scheduler) as pool:
            ev = Evaluator(db, pool, config, progress, workers=config.workers)
            if progress:
                progress(
                    "start",
                    {
                        "runs": _runs(config),
                        "starts": len(starts),
                        "evaluations": evaluations_total(config, len(starts)),
                    },
                )
            _run_methods(ev, config, starts, progress, space)
            # the baseline's objective, to compare (stored already if it was a start)
            ev.batch(baseline_run(base_key), 1, [base_values])
            if config.goal == ROBUSTNESS:
                optimum = _robust(ev, config, starts, space, base_key, progress, measure)
            else:
                optimum = _validate(ev, config, _runs(config))
            _verdicts(ev, config, {OPTIMUM: optimum, label: base_key}, 1)
        if margins and config.goal != ROBUSTNESS and _works(db, config, OPTIMUM):
            measured = store.stored_margins(db, optimum, settings_key(config)) is not None
            if space.family is None:
                on_axis = None if measured else _axis_progress(progress)
                optimum_margins(db, config, optimum, OPTIMUM, config.workers, on_axis=on_axis)
            else:
                on_axis = None if measured else _axis_progress(progress, len(space.names) + 1)
                family_margins(db, config, space.family, optimum, OPTIMUM, config.workers, on_axis)
        wall = time.perf_counter() - t0
        out_results = results(db, config, starts, wall, baseline)
        out_results["new_evaluations"] = ev.computed
        return out_results
    finally:
        db.close()


CENTERING_META = "centering"  # the meta row holding the centring chains (JSON)


def robust_measure(
    ev: Evaluator,
    config: OptimizeConfig,
    space: Designed,
    progress: Progress | None = None,
    measure: Any = None,
) -> Any:
    """values -> the robust objective's margins of that design (the device's axes,
    :func:`experiments.optimize.tolerance.robust_settings`), stored or measured."""
    digest = robust_settings_key(config)

    def of(values: list[float]) -> dict[str, Any]:
        key = store.design_key(values)
        stored = store.stored_margins(ev.db, key, digest)
        if stored is not None:
            return stored
        axes = len(space.names) + 1
        on_axis = _axis_progress(progress, axes)
        if space.family is None:
            return optimum_margins(
                ev.db, config, key, "design", config.workers, on_axis, measure, robust=True
            )
        return family_margins(
            ev.db, config, space.family, key, "design", config.workers, on_axis, measure, True
        )

    return of


def _robust(
    ev: Evaluator,
    config: OptimizeConfig,
    starts: dict[str, list[float]],
    space: Designed,
    base_key: str,
    progress: Progress | None,
    measure: Any = None,
) -> str:
    """The robust objective's optimum (issue 34): design centering
    (:func:`experiments.optimize.centering.design_centering`) from the ``centering.starts``
    best designs by R (the starts', and the methods' if the config has any), the budget of
    margins evaluations split between them; then the accepted designs, most robust first
    (then the shortest mean exit time), each get the reported verdict on fresh draws
    (``final.seed + 1``) until one works at the target, up to ``final.candidates`` (none:
    the most robust). The baseline's margins are measured too (the report shows both). The
    chains are kept in the store's meta (``centering``)."""
    from experiments.optimize.centering import better, design_centering

    settings = config.centering
    runs = [(STARTS_RUN, len(starts)), *_runs(config)]
    keys = ranked_keys(ev.db, runs, settings.starts)
    names = {store.design_key(v): n for n, v in starts.items()}
    of = robust_measure(ev, config, space, progress, measure)
    chains = []
    for i, key in enumerate(keys):
        budget = settings.budget // len(keys) + (i < settings.budget % len(keys))
        chain = design_centering(
            store.design_of_key(key),
            space.names,
            space.low.tolist(),
            space.high.tolist(),
            of,
            settings,
            budget=budget,
            label=names.get(key, key),
        )
        chains.append(chain)
    store.record_meta(ev.db, CENTERING_META, [c.to_dict() for c in chains])
    accepted: list[tuple[list[float], dict[str, Any]]] = []
    for chain in chains:
        for s in chain.steps:
            if s.accepted:
                accepted.append((s.values, of(s.values)))
    if not accepted:  # no start works: the best start by R, whose verdict says so
        return keys[0]
    ranked: list[tuple[list[float], dict[str, Any]]] = []
    for values, margins in accepted:  # an insertion sort by better(): most robust first
        at = next((j for j, (_, m) in enumerate(ranked) if better(margins, m)), len(ranked))
        ranked.insert(at, (values, margins))
    candidates = list(dict.fromkeys(store.design_key(v) for v, _ in ranked))
    candidates = candidates[: config.final_candidates]
    of(store.design_of_key(base_key))  # the baseline's margins, for the report
    if ev.progress:
        ev.progress("verdicts", {"verdicts": len(candidates) + 1, "trials": config.final_trials})
    chosen = candidates[0]
    for rank, key in enumerate(candidates):
        _verdicts(ev, config, {robust_label(rank): key}, 1)
        if _works(ev.db, config, robust_label(rank)):
            chosen = key
            break
    # its R over the K draws, as every design in the results has (Eq. 10's table)
    ev.batch(f"robust {chosen}", 1, [store.design_of_key(chosen)])
    return chosen


def robust_label(rank: int) -> str:
    """The label of the ``rank``-th most robust design's verdict on fresh draws."""
    return f"robust{rank}"


def baseline_run(key: str) -> str:
    """The run label under which the baseline's objective is asked (one per design)."""
    return f"baseline {key}"


def _works(db, config: OptimizeConfig, label: str) -> bool:
    stored = store.stored_verdict(db, label)
    return stored is not None and verdict_of_trials(stored["trial_data"], config.final_target).works


def _axis_progress(progress: Progress | None, axes: int | None = None) -> AxisCallback | None:
    """The margins' progress: a ``margins`` event with the fixed number of axes (``axes``;
    None: the feeder's), then an ``axis`` event as each finishes."""
    if progress is None:
        return None
    from experiments.optimize.tolerance import AXES

    progress("margins", {"axes": AXES if axes is None else axes})

    def on_axis(margin: Any) -> None:
        progress("axis", {"axis": margin.axis.name})

    return on_axis


def evaluations_total(config: OptimizeConfig, starts: int) -> int:
    """The evaluations an optimisation asks for, as its progress counts them: the starts,
    every run's budget (a run that stops early is counted as having spent it) and the
    baseline's (compared with the optimum). Fixed before the first evaluation, so a progress
    bar's total and time estimate hold."""
    return starts + sum(budget for _, budget in _runs(config)) + 1


def _run_methods(
    ev: Evaluator,
    config: OptimizeConfig,
    starts: dict[str, list[float]],
    progress: Progress | None,
    space: Designed | None = None,
) -> None:
    """Evaluate the starts, then run every method once per seed on its budget, on the unit
    cube over the box (``space``: a family's; None: Table 2's)."""
    start_values = ev.batch(STARTS_RUN, len(starts), list(starts.values()))
    unit_starts = to_unit(np.array(list(starts.values())), space)
    best_start = unit_starts[int(np.argmin(start_values))]
    done = [(STARTS_RUN, len(starts))]
    for method in config.methods:
        first_points = unit_starts
        if method.start == "best":  # the best design of the methods before this one
            best = to_unit(np.array([store.design_of_key(best_key(ev.db, done))]), space)
            first_points = np.vstack([best, unit_starts])
        for seed in method.seeds:
            label = run_label(method.method, seed)
            if progress:
                progress("run", {"run": label, "budget": method.budget})

            def f(unit: np.ndarray, label: str = label, budget: int = method.budget) -> list[float]:
                return ev.batch(label, budget, from_unit(unit, space).tolist())

            if method.method in POPULATION_METHODS:
                first = first_points
            else:
                first = first_points[0] if method.start == "best" else best_start
            try:
                METHODS[method.method](f, first, method.budget, seed, method.population)
            except BudgetSpent:
                pass
            if progress:  # a method that converged leaves the rest of its budget unspent
                asked = min(ev.asked.get(label, 0), method.budget)
                progress("run end", {"run": label, "unspent": method.budget - asked})
        done += [(run_label(method.method, seed), method.budget) for seed in method.seeds]


def _verdicts(ev: Evaluator, config: OptimizeConfig, designs: dict[str, str], offset: int) -> None:
    """The fixed-sample verdict (``final.trials`` trials, seed ``final.seed + offset``) of each
    labelled design key, unless stored already for the same design, seed and trials (under
    its label, or under another: then copied, not run again)."""
    seed, trials = config.final_seed + offset, config.final_trials
    for label, key in designs.items():
        stored = store.stored_verdict(ev.db, label)
        if stored is None or (stored["key"], stored["seed"], len(stored["trial_data"])) != (
            key,
            seed,
            trials,
        ):
            found = store.find_verdict(ev.db, key, seed, trials)
            if found is not None:
                store.record_verdict(ev.db, label, key, seed, found["trial_data"])
            else:
                t0 = time.perf_counter()
                done = ev.run_trials({key: store.design_of_key(key)}, seed, trials)[key]
                if done.reason is not None or len(done.trials) != trials:
                    raise RuntimeError(f"the verdict of the {label} design failed: {done.reason}")
                store.record_verdict(ev.db, label, key, seed, done.trials)
                store.record_verdict_time(ev.db, key, seed, trials, time.perf_counter() - t0)
        if ev.progress:
            ev.progress("verdict", {"label": label})


def _validate(ev: Evaluator, config: OptimizeConfig, runs: list[tuple[str, int]]) -> str:
    """The optimum: of the ``final.candidates`` designs with the lowest R (selected on the K
    draws, so their K-draw probabilities flatter them), the one whose verdict on fresh draws
    (seed ``final.seed``) has the highest lower bound of P(both), then the lowest mean G. Its
    reported verdict is on other fresh draws again (:func:`_verdicts` with offset 1)."""
    keys = ranked_keys(ev.db, runs, config.final_candidates)
    if ev.progress:  # the candidates', then the optimum's and the baseline's (offset 1)
        ev.progress("verdicts", {"verdicts": len(keys) + 2, "trials": config.final_trials})
    _verdicts(ev, config, {candidate_label(i): k for i, k in enumerate(keys)}, 0)
    scored = []
    for i in range(len(keys)):
        stored = store.stored_verdict(ev.db, candidate_label(i))
        assert stored is not None
        verdict = verdict_of_trials(stored["trial_data"], 0.0)
        mean_g = _mean_g(verdict, config.weight)
        scored.append((-verdict.both_interval[0], math.inf if mean_g is None else mean_g, i))
    return keys[min(scored)[2]]


def candidate_label(rank: int) -> str:
    return f"candidate{rank}"


def _mean_g(verdict: Verdict, weight: float) -> float | None:
    g = [eq10_terms(t, weight) for t in verdict.trials]
    g = [x for x in g if not math.isnan(x)]
    return sum(g) / len(g) if g else None


def _runs(config: OptimizeConfig) -> list[tuple[str, int]]:
    return [(run_label(m.method, s), m.budget) for m in config.methods for s in m.seeds]


def ranked_keys(db, runs: list[tuple[str, int]], count: int) -> list[str]:
    """The ``count`` distinct designs with the lowest robust value asked by any of ``runs``
    (label, budget: a run's calls past its budget, stored by an earlier config with a larger
    one, are not its), best first (ties: the earliest asked, in the order of ``runs``).
    A design that cannot be built (R = K + 1, with its reason) is never one of them: it has
    no verdict to validate nor a centre to move (a small ``--evaluations`` budget may have
    fewer buildable designs than ``final.candidates``)."""
    values = store.evaluations(db)
    calls = store.calls(db)
    first: dict[str, tuple[float, int, int]] = {}
    for r, (run, budget) in enumerate(runs):
        for n, k in enumerate(calls.get(run, [])[:budget]):
            if values[k]["reason"] is None:
                first.setdefault(k, (values[k]["value"], r, n))
    if not first:
        raise ValueError(
            "no method evaluated a design that can be built (every budget is 0, or too small?)"
        )
    return sorted(first, key=first.__getitem__)[:count]


def best_key(db, runs: list[tuple[str, int]]) -> str:
    """The design with the lowest robust value asked by any of ``runs``."""
    return ranked_keys(db, runs, 1)[0]


def _nominal(config: OptimizeConfig, values: list[float], space: Designed) -> dict[str, Any]:
    """One unperturbed drop per entry: success, T, distance to q_goal, and Eq. 10's G."""
    try:
        scene = space.scene(config, values)
    except DegenerateDesign as exc:
        return {"reason": exc.reason}
    drops = [passive_drop(scene, o, step=config.step, t_max=config.t_max) for o in space.entries]
    return {
        "reason": None,
        "G": eq10_objective(drops, config.weight),
        "entries": {
            d.orientation: {
                "success": d.success,
                "T_s": d.T,
                "goal_error": d.goal_error,
                "end": d.end,
            }
            for d in drops
        },
    }


def _design_entry(
    config: OptimizeConfig,
    key: str,
    evaluation: dict[str, Any],
    verdict: dict | None,
    space: Designed,
) -> dict[str, Any]:
    values = store.design_of_key(key)
    k = evaluation["trials"]
    entry: dict[str, Any] = {
        "values": dict(zip(space.names, values, strict=True)),
        "objective": {
            "value": evaluation["value"],
            "both": evaluation["both"],
            "trials": k,
            "p_both": evaluation["both"] / k,
            "interval": list(wilson_interval(evaluation["both"], k)),
            "mean_g": evaluation["mean_g"],
            "reason": evaluation["reason"],
        },
    }
    if verdict is not None:
        v = verdict_of_trials(
            verdict["trial_data"], config.final_target, space.entries, space.classes()
        )
        entry["verdict"] = {**v.to_dict(), "seed": verdict["seed"]}
        entry["verdict"]["mean_g"] = _mean_g(v, config.weight)
    entry["nominal"] = _nominal(config, values, space)
    return entry


def results(
    db,
    config: OptimizeConfig,
    starts: dict[str, list[float]],
    wall: float | None,
    baseline: Baseline | None = None,
) -> dict[str, Any]:
    """The stored optimisation as plain data: per run its curve (evaluations, and of the best
    design so far: R, P(both) over the K draws, mean G), the starts, the optimum and the
    baseline (table3 unless given; under its label, named by ``compared_with``: values,
    objective, verdict on fresh draws, nominal drops), the validated ``candidates``, the
    ``comparison`` of the optimum with the baseline on the same fresh draws
    (:func:`experiments.optimize.comparison.stored_comparison`) and the optimum's ``margins``
    (None when not measured, ``margins_absent`` says why). A device family's: ``family``
    (name, parameters, box, entries), its own parameter names, no comparison section
    (``comparison_absent`` says why), margins over its own parameters."""
    space = designed(config)
    values = store.evaluations(db)
    calls = store.calls(db)
    runs = []
    for method in config.methods:
        for seed in method.seeds:
            label = run_label(method.method, seed)
            keys = calls.get(label, [])[: method.budget]
            curve, best = [], None
            for n, k in enumerate(keys):
                e = values[k]
                if best is None or e["value"] < best[0]:
                    best = (e["value"], e["both"], k, n, e["mean_g"])
                curve.append([n + 1, best[0], best[1] / config.trials, best[4]])
            runs.append(
                {
                    "run": label,
                    "method": method.method,
                    "seed": seed,
                    "budget": method.budget,
                    "evaluations": len(keys),
                    "best": None
                    if best is None
                    else {
                        "value": best[0],
                        "both": best[1],
                        "values": store.design_of_key(best[2]),
                        "at": best[3] + 1,
                    },
                    "curve": curve,
                }
            )
    start_rows = []
    for name, v in starts.items():
        stored = values.get(store.design_key(v))
        if stored is not None:
            start_rows.append(
                {
                    "name": name,
                    "values": v,
                    "value": stored["value"],
                    "both": stored["both"],
                    "mean_g": stored["mean_g"],
                    "reason": stored["reason"],
                }
            )
    out: dict[str, Any] = {
        "name": config.name,
        "objective": {
            "trials": config.trials,
            "seed": config.seed,
            "weight": config.weight,
            "perturbations": config.perturbations,
            "definition": "R = (K - S) + Gbar / (Gbar + 10 s): S of K trials succeed from "
            "both entries, Gbar their mean Eq. 10 G; degenerate designs R = K + 1",
        },
        "final": {
            "trials": config.final_trials,
            "seed": config.final_seed,
            "target": config.final_target,
            "candidates": config.final_candidates,
        },
        "starts": start_rows,
        "runs": runs,
        "evaluations": len(values),
        "worker_time_s": sum(e["wall_time_s"] for e in values.values()),
        "parameters": list(space.names),
        "entries": list(space.entries),
    }
    if space.family is not None:
        record = family_record(space.family, config.family_yaml)
        out["family"] = {k: v for k, v in record.items() if k != "yaml"}
    if wall is not None:
        out["wall_time_s"] = wall
    label, base_values = baseline or default_baseline(config)
    base_key = store.design_key(base_values)
    out["compared_with"] = label
    seed, trials = config.final_seed + 1, config.final_trials
    verdicts = {}
    for name, want in ((OPTIMUM, None), (label, base_key)):
        stored = store.stored_verdict(db, name)
        if stored is None or (stored["seed"], len(stored["trial_data"])) != (seed, trials):
            continue
        if want is not None and stored["key"] != want:
            continue  # the verdict of another baseline
        key = stored["key"]
        verdicts[name] = stored
        out[name] = _design_entry(config, key, values[key], stored, space)
    out["candidates"] = _candidates(db, config, values, out.get(OPTIMUM), space)
    optimum_entry = out.get(OPTIMUM)
    out["optimum_is_baseline"] = optimum_entry is not None and same_design(
        [optimum_entry["values"][n] for n in space.names], base_values, space
    )
    out["comparison"] = None
    if space.family is not None:
        out["comparison_absent"] = FAMILY_NO_COMPARISON
    elif len(verdicts) == 2:
        optimum = verdicts[OPTIMUM]
        times = [store.verdict_time(db, v["key"], seed, trials) for v in verdicts.values()]
        out["comparison"] = stored_comparison(
            {OPTIMUM: (store.design_of_key(optimum["key"]), optimum["trial_data"])},
            (label, base_values, verdicts[label]["trial_data"]),
            seed,
            config.final_target,
            None if None in times else sum(t for t in times if t is not None),
        )
    out["margins"], out["margins_absent"] = _margins(db, config, out.get(OPTIMUM), space)
    if config.goal == ROBUSTNESS:
        out["robust"] = robust_results(db, config, out, base_key)
        theirs = store.stored_margins(db, base_key, robust_settings_key(config))
        # the stored margins are named as evaluated ("design"): named here as reported
        if out["margins"] is not None:
            out["margins"] = {**out["margins"], "design": OPTIMUM}
        out["baseline_margins"] = None if theirs is None else {**theirs, "design": label}
    return out


def robust_results(db, config: OptimizeConfig, out: dict[str, Any], base_key: str) -> dict:
    """The robust objective's part of the results: its definition, the centring settings
    and chains, and the robustness of the optimum and of the baseline (each from its margins
    on the same draws: :func:`experiments.margins.robustness.robustness`)."""
    from experiments.margins.robustness import MEANING, robustness

    digest = robust_settings_key(config)
    mine = out.get("margins")
    theirs = store.stored_margins(db, base_key, digest)
    chains = store.stored_meta(db, CENTERING_META) or []
    return {
        "goal": ROBUSTNESS,
        "definition": f"maximise the robustness ({MEANING}) subject to the verdict at "
        f"{config.final_target} (the design works); Eq. 10's exit time only breaks ties",
        "method": "design centering: each step moves the parameters toward the centres of "
        "their allowed intervals, damped, accepted only when the design works and is more "
        "robust; a rejected step halves the damping",
        "centering": config.centering.to_dict(),
        "evaluations": sum(c["evaluations"] for c in chains),
        "chains": chains,
        "optimum": None if mine is None else robustness(mine).to_dict(),
        "baseline": None if theirs is None else robustness(theirs).to_dict(),
    }


SAME_DESIGN = 1e-9  # of each parameter's box width: closer is the same design


def same_design(a: list[float], b: list[float], space: Designed) -> bool:
    """Whether two designs are one, each parameter within ``SAME_DESIGN`` of its box's width
    (a method's first point is its start moved to the unit cube and back: table3's gx came
    back as 0.7329999999999999, another store key for the same design)."""
    width = space.high - space.low
    return bool(np.all(np.abs(np.asarray(a) - np.asarray(b)) <= SAME_DESIGN * width))


FAMILY_NO_COMPARISON = (
    "the comparison section (parameter differences as fractions of Table 2's box, the "
    "designs drawn over each other, its entries) is the 12-parameter feeder's; a device "
    "family's optimum and baseline (its default) are compared by their verdicts on the same "
    "fresh draws in the table of Eq. 10 and the verdicts"
)


def _margins(
    db, config: OptimizeConfig, optimum: dict[str, Any] | None, space: Designed
) -> tuple[dict[str, Any] | None, str | None]:
    """The optimum's stored margins, or None and why there are none."""
    if optimum is None:
        return None, "there is no optimum yet"
    verdict = optimum.get("verdict") or {}
    if not verdict.get("works"):
        return None, (
            f"the optimum {short_of_working(verdict.get('decision'))} on its "
            f"{verdict.get('drops', '?')} fresh trials, so it has no margins"
        )
    key = store.design_key([optimum["values"][n] for n in space.names])
    digest = robust_settings_key(config) if config.goal == ROBUSTNESS else settings_key(config)
    stored = store.stored_margins(db, key, digest)
    if stored is None:
        return None, "they were not measured (the run was stopped before, or told not to)"
    return stored, None


def _candidates(
    db, config: OptimizeConfig, values, optimum: dict | None, space: Designed
) -> list[dict]:
    """The validated candidates: R and P(both) on the K draws, and on fresh draws."""
    rows = []
    for rank in range(config.final_candidates):
        stored = store.stored_verdict(db, candidate_label(rank))
        if stored is None:
            break
        verdict = verdict_of_trials(stored["trial_data"], config.final_target)
        e = values[stored["key"]]
        design = store.design_of_key(stored["key"])
        rows.append(
            {
                "rank": rank,
                "values": design,
                "value": e["value"],
                "p_both_k": e["both"] / e["trials"],
                "both": verdict.both,
                "drops": verdict.drops,
                "interval": list(verdict.both_interval),
                "mean_g": _mean_g(verdict, config.weight),
                "chosen": optimum is not None
                and design == [optimum["values"][n] for n in space.names],
            }
        )
    return rows
