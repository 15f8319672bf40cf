"""One level's planning problem through OMPL's Benchmark: the standard log and our own metrics.

OMPL's ``Benchmark`` runs each planner ``runs`` times on one setup and writes the log that
``ompl_benchmark_statistics`` turns into the database Planner Arena reads. Three things it does
not do are added here, without changing what it measures:

- a machine-independent budget: a count of propagations. ``Benchmark`` only takes a time
  limit, so each planner is wrapped in one whose ``solve`` ORs OMPL's timed termination
  condition with "propagations >= budget" (the time limit stays as a cap). A run ends after
  the planner iteration in which the count reaches the budget (a few dozen propagations);
- metrics of our own: whether the goal was reached exactly, propagations and validity checks
  made while solving (not the ones Benchmark makes afterwards to check the path), the
  duration of the solution's controls (the time the part takes to leave, Eq. 10). OMPL drops
  properties added in a post-run event, so they are collected in the wrapper and the
  post-run event and appended to the log as run properties (Planner Arena shows them);
- the wrapped planner's tree and parameters: OMPL cannot call a Python override of
  ``getPlannerData`` or ``params``, so the wrapper's "graph states" and "graph motions" are
  replaced by its inner planner's, and the inner planner's parameters (``goal_bias``,
  KPIECE1's ``border_fraction`` ...) are added to the log's "common properties", which OMPL
  filled from the wrapper (space information settings only): Planner Arena's
  ``plannerConfigs`` then holds them. The wrapper's name is the inner planner's ("RRT",
  "KPIECE1", "EST", or a researcher's own planner's ``getName()``).

Every run is seeded (OMPL's generator and the goal sampler) with ``seed + run``, so planner A's
run r and planner B's run r start from the same seed, and the same arguments give the same
log when the budget is a count of propagations.

With ``progress_every`` (a count of propagations) each run also records its progress, which
OMPL's log carries as "progress properties" and Planner Arena plots over time: every
``progress_every`` propagations, the propagations made, the tree's size and the best distance
to the goal of any state the planner has checked against it so far in the run. The clock of
those plots is the machine-independent one: the progress's "time" is the count of
propagations, and so is the experiment's time limit (the log's "seconds per run" line holds
the propagation budget; the experiment parameter ``time_unit`` = ``propagations`` says so).
The runs' own "time" stays OMPL's wall-clock seconds.
"""

from __future__ import annotations

import math
import re
import tempfile
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeAlias

import numpy as np
from ompl import base as ob
from ompl import control as oc
from ompl import tools as ot

from feeders.scene import Scene
from planners.exclusive import one_at_a_time
from planners.plan import ControlProblem, PlannerSettings, control_problem, seed_ompl
from planners.registry import PLANNERS, make_planner

MEMORY_LIMIT_MB = 4096.0  # OMPL's per-run memory limit; far above what a control tree needs

# The progress properties of a run (with ``progress_every``): "time" is the propagation count.
PROGRESS_PROPERTIES = {
    "time": "REAL",
    "propagations": "INTEGER",
    "tree size": "INTEGER",
    "best goal distance": "REAL",
}
TIME_UNIT_PARAMETER = "time_unit"  # the experiment parameter naming the time axis' unit

# The run properties appended to OMPL's log, with their OMPL types.
EXTRA_PROPERTIES = {
    "exact solution": "BOOLEAN",
    "propagations": "INTEGER",
    "validity checks": "INTEGER",
    "exit time": "REAL",
}


@dataclass(frozen=True)
class Budget:
    """How long one planner run may search.

    ``time_s``: OMPL wall-clock seconds (``Request.maxTime``). ``propagations``: if set, a run
    also ends after this many calls of the propagator, which does not depend on the machine
    or its load (a run's result is then reproducible anywhere); ``time_s`` stays as a cap.
    """

    time_s: float
    propagations: int | None = None

    def __post_init__(self) -> None:
        if not (math.isfinite(self.time_s) and 0.0 < self.time_s <= 86400.0):
            raise ValueError(f"budget time = {self.time_s!r} s is outside the range (0, 86400]")
        if self.propagations is not None and not (1 <= self.propagations <= 10**9):
            raise ValueError(
                f"budget propagations = {self.propagations!r} is outside the range [1, 1e9]"
            )


@dataclass(frozen=True)
class BenchmarkResult:
    """OMPL's log (augmented, see the module docstring) and one plain dict per run, in the
    log's order (planner by planner, run by run): ``planner``, ``run``, ``seed``, ``solved``
    (goal reached exactly), ``approximate``, ``time_s``, ``tree_size``, ``tree_edges``,
    ``propagations``, ``validity_checks``, ``exit_time_s`` (NaN when not solved); with
    ``progress_every`` also ``progress``: ``(propagations, tree size, best goal distance)``
    samples in the run's order, and ``best_goal_distance`` at the run's end (inf: no state
    was checked against the goal)."""

    log: str = field(repr=False)
    runs: list[dict]


class _Counted(ob.Planner):
    """``inner``, with the propagations and validity checks it made while solving (OMPL's
    Benchmark re-propagates the solution afterwards to check it: that is not the planner's
    work) and, with a ``budget``, stopped once it has made that many propagations in this run
    (or by OMPL's own condition)."""

    def __init__(
        self,
        si,
        inner,
        counts: list[int],
        budget: int | None,
        progress_every: int | None = None,
        best: list[float] | None = None,
    ):
        super().__init__(si, inner.getName())
        self.inner = inner
        self.counts = counts
        self.budget = budget
        self.spent = [0, 0]
        self.settings: dict[str, str] = {}  # the inner planner's parameters, once set up
        self.progress_every = progress_every
        self.best = best if best is not None else [math.inf]  # best goal distance this run
        self.samples: list[tuple[int, int, float]] = []  # this run's progress

    def clear(self) -> None:
        super().clear()
        self.inner.clear()

    def solve(self, ptc):
        self.inner.setProblemDefinition(self.getProblemDefinition())
        self.inner.setup()
        self.settings = planner_parameters(self.inner)
        start = list(self.counts)
        self.samples = []
        if self.progress_every is not None:
            ptc = ob.plannerOrTerminationCondition(ptc, self._sampling(start[1]))
        elif self.budget is not None:
            stop_at = start[1] + self.budget
            spent = ob.PlannerTerminationCondition(lambda: self.counts[1] >= stop_at)
            ptc = ob.plannerOrTerminationCondition(ptc, spent)
        try:
            return self.inner.solve(ptc)
        finally:
            self.spent = [self.counts[0] - start[0], self.counts[1] - start[1]]
            if self.progress_every is not None:
                self._sample(self.spent[1])

    def _sampling(self, start: int) -> ob.PlannerTerminationCondition:
        """The budget's condition (if any) that also takes a progress sample each time
        another ``progress_every`` propagations have been made (OMPL evaluates it between
        the planner's iterations, so the tree is whole when it is read)."""
        every = int(self.progress_every or 1)
        stop_at = None if self.budget is None else start + self.budget
        due = [start + every]

        def check() -> bool:
            done = self.counts[1]
            if done >= due[0]:
                self._sample(done - start)
                due[0] = done + every
            return stop_at is not None and done >= stop_at

        return ob.PlannerTerminationCondition(check)

    def _sample(self, spent: int) -> None:
        if self.samples and self.samples[-1][0] == spent:
            return  # one sample per count: (run, time) is the progress table's key
        data = ob.PlannerData(self.getSpaceInformation())
        self.inner.getPlannerData(data)
        self.samples.append((int(spent), int(data.numVertices()), float(self.best[0])))


def planner_parameters(planner: ob.Planner) -> dict[str, str]:
    """The parameters ``planner`` declares (OMPL's ``params()``, e.g. RRT's ``goal_bias`` and
    ``intermediate_states``) with their values as OMPL prints them. ``params()`` itself has no
    Python binding in OMPL 2; ``printSettings()`` lists the same, one ``name = value`` a line."""
    pairs = (line.split(" = ", 1) for line in planner.printSettings().splitlines()[1:])
    return {p[0].strip(): p[1].strip() for p in pairs if len(p) == 2}


def _tree_size(planner, si) -> tuple[int, int]:
    data = ob.PlannerData(si)
    planner.inner.getPlannerData(data)
    return int(data.numVertices()), int(data.numEdges())


PlannerFactory: TypeAlias = Callable[[oc.SpaceInformation], ob.Planner]
"""A researcher's own planner: called with the problem's space information, it returns any
OMPL control planner (``lambda si: oc.RRT(si)`` with a changed goal bias, or a Python
subclass of ``ob.Planner``)."""

PlannerSpec: TypeAlias = str | PlannerFactory
"""A planner by name (``planners.registry.PLANNERS``: rrt, kpiece, est) or by factory."""


def _make_planner(spec: PlannerSpec, si: oc.SpaceInformation) -> ob.Planner:
    if isinstance(spec, str):
        return make_planner(spec, si)
    if not callable(spec):
        raise TypeError(
            f"planner {spec!r} is neither a name ({', '.join(PLANNERS)}) nor a factory "
            "si -> ob.Planner"
        )
    planner = spec(si)
    if not isinstance(planner, ob.Planner):
        raise TypeError(f"planner factory returned {type(planner).__name__}, not an ob.Planner")
    return planner


def _check_property_name(name: str) -> None:
    """Refuse an experiment parameter OMPL's log reader cannot take (it adds the property as
    a column without quoting): :func:`planners.sql_names.column_name_problem`. A column of
    OMPL's experiments table of the same spelling (``seed``) is let through: the reader keeps
    its own value."""
    from planners.sql_names import OMPL_EXPERIMENT_COLUMNS, RULE, column_name_problem

    problem = column_name_problem(name)
    if problem is not None and name not in OMPL_EXPERIMENT_COLUMNS:
        raise ValueError(f"parameter '{name[:100]}': {problem}; a parameter is {RULE}")


@one_at_a_time
def benchmark_problem(
    scene: Scene,
    level_name: str,
    orientation: str,
    planners: Sequence[PlannerSpec],
    runs: int,
    budget: Budget,
    seed: int,
    experiment: str,
    parameters: Mapping[str, float | int | str] | None = None,
    settings: PlannerSettings | None = None,
    level_options: Mapping[str, Any] | None = None,
    start_region: tuple[float, float] | None = None,
    *,
    progress_every: int | None = None,
) -> BenchmarkResult:
    """Benchmark ``planners`` on the problem of reaching the scene's goal from entry
    ``orientation`` at level ``level_name``, ``runs`` runs each: the problem of
    :func:`planners.plan.control_problem` (seeded by ``seed``, with ``settings``) through
    :func:`benchmark_control_problem`, which says what the arguments mean.
    ``level_options`` go to the level (e.g. ``{"slack": ...}``: the geometric level as a
    relaxation, :func:`validity.geometric_slack.relaxation_slack`); ``start_region`` adds
    the entry region's corners as start states (:func:`planners.plan.control_problem`).

    >>> from feeders.design import PRESETS
    >>> from feeders.feeder import build_feeder
    >>> from ompl import control as oc
    >>> def rrt_greedy(si):
    ...     planner = oc.RRT(si)
    ...     planner.setGoalBias(0.2)
    ...     return planner
    >>> scene = build_feeder(PRESETS["table3"], name="table3")
    >>> result = benchmark_problem(scene, "geometric", "heavy_leading", ["kpiece", rrt_greedy],
    ...                            runs=2, budget=Budget(10.0, 2000), seed=1, experiment="demo")
    >>> [(r["planner"], r["run"]) for r in result.runs]
    [('KPIECE1', 0), ('KPIECE1', 1), ('RRT', 0), ('RRT', 1)]
    """
    problem = control_problem(
        scene,
        level_name,
        orientation,
        seed,
        settings or PlannerSettings(),
        dict(level_options or {}),
        count=True,
        start_region=start_region,
    )
    return benchmark_control_problem(
        problem, planners, runs, budget, seed, experiment, parameters, progress_every=progress_every
    )


@one_at_a_time
def benchmark_control_problem(
    problem: ControlProblem,
    planners: Sequence[PlannerSpec],
    runs: int,
    budget: Budget,
    seed: int,
    experiment: str,
    parameters: Mapping[str, float | int | str] | None = None,
    *,
    progress_every: int | None = None,
) -> BenchmarkResult:
    """Benchmark ``planners`` on an already built ``problem`` (from
    :func:`planners.plan.control_problem` with ``count=True``, changed as the user likes:
    another propagation step, control durations, start), ``runs`` runs each, every run
    within ``budget``.

    ``planners``: names in ``planners.registry.PLANNERS`` or factories ``si -> ob.Planner``
    (:data:`PlannerFactory`). A planner is logged under its own ``getName()`` (OMPL's log says
    ``control_RRT``), its own parameters (``goal_bias``, KPIECE1's ``border_fraction`` ...,
    as it is set up for the problem) beside the space information's in the log's planner
    configuration; two planners of one name are refused (``planner.setName`` tells them
    apart). Run ``r`` of every planner is seeded with ``seed + r``. ``experiment`` is the
    log's experiment name (Planner Arena's problem: one word, as OMPL's reader keeps only
    the last). ``parameters`` become the experiment's parameters in OMPL's log (REAL for
    floats, INTEGER for ints, STRING otherwise), and so columns of Planner Arena's
    ``experiments`` table. ``progress_every`` (propagations; needs a budget in propagations)
    records each run's progress (the module's docstring): Planner Arena's progress plots,
    over a time axis that counts propagations.

    >>> from feeders.design import PRESETS
    >>> from feeders.feeder import build_feeder
    >>> from planners.plan import control_problem
    >>> scene = build_feeder(PRESETS["table3"], name="table3")
    >>> problem = control_problem(scene, "geometric", "heavy_leading", seed=1, count=True)
    >>> problem.si.setMinMaxControlDuration(1, 10)
    >>> result = benchmark_control_problem(problem, ["rrt", "est"], runs=2,
    ...                                    budget=Budget(10.0, 2000), seed=1, experiment="demo")
    >>> len(result.runs), "max_control_duration = 10" in result.log
    (4, True)
    """
    if runs < 1:
        raise ValueError(f"runs = {runs} must be >= 1")
    if not planners:
        raise ValueError("need at least one planner")
    if problem.counts is None:
        raise ValueError(
            "problem has no counts of propagations: build it with control_problem(..., count=True)"
        )
    if progress_every is not None:
        if budget.propagations is None:
            raise ValueError("progress_every needs a budget in propagations (the plots' clock)")
        if not 1 <= int(progress_every) <= 10**9:
            raise ValueError(f"progress_every = {progress_every!r} is outside the range [1, 1e9]")
    ss, si, level, counts = problem.ss, problem.si, problem.level, problem.counts
    # Compile (or load from cache) the level's kernels before OMPL starts its clock, at the
    # goal's centre (ProblemDefinition.getStartState would hand the start to Python, which
    # frees it: OMPL then reads freed memory).
    goal = problem.goal.goal
    pose = (0.5 * (goal.x_min + goal.x_max), 0.5 * (goal.y_min + goal.y_max), goal.yaw)
    state = level.state_of_pose(pose)
    level.is_valid(state)
    level.propagate(state, np.zeros(level.control_dim), si.getPropagationStepSize())

    bench = ot.Benchmark(ss, experiment)
    wrapped: list[_Counted] = []
    best = [math.inf]  # the best goal distance of the run going on
    for spec in planners:
        inner = _make_planner(spec, si)
        name = inner.getName()
        if any(w.getName() == name for w in wrapped):
            raise ValueError(
                f"two planners named '{name}': give one another name (planner.setName)"
            )
        wrapped.append(_Counted(si, inner, counts, budget.propagations, progress_every, best))
        bench.addPlanner(wrapped[-1])
    extra = dict(parameters or {})
    if progress_every is not None:
        extra[TIME_UNIT_PARAMETER] = "propagations"
    for key, value in extra.items():
        _check_property_name(key)
        kind = "INTEGER" if isinstance(value, (int, np.integer)) else "REAL"
        if isinstance(value, (bool, str)) or not isinstance(value, (int, float, np.number)):
            kind = "STRING"
        bench.addExperimentParameter(key, kind, str(value))

    rows: list[dict] = []

    def pre_run(planner) -> None:
        run = sum(1 for r in rows if r["planner"] == planner.getName())
        seed_ompl(seed + run)
        problem.goal.rng = np.random.default_rng(seed + run)
        best[0] = math.inf

    def post_run(planner, properties) -> None:
        name = planner.getName()
        run = sum(1 for r in rows if r["planner"] == name)
        props = properties.to_dict()
        pdef = planner.getProblemDefinition()
        solved = bool(pdef.hasExactSolution())
        exit_time = math.nan
        if solved:
            path = ss.getSolutionPath()
            steps = range(path.getControlCount())
            exit_time = float(sum(path.getControlDuration(i) for i in steps))
        vertices, edges = _tree_size(planner, si)
        progress = {}
        if progress_every is not None:
            progress = {"progress": list(planner.samples), "best_goal_distance": best[0]}
        rows.append(
            {
                "planner": name,
                "run": run,
                "seed": seed + run,
                "solved": solved,
                "approximate": props.get("approximate solution BOOLEAN") == "1",
                "time_s": float(props.get("time REAL", "nan")),
                "tree_size": vertices,
                "tree_edges": edges,
                "propagations": planner.spent[1],
                "validity_checks": planner.spent[0],
                "exit_time_s": exit_time,
                **progress,
            }
        )

    bench.setPreRunEvent(pre_run)
    bench.setPostRunEvent(post_run)
    request = ot.Request(float(budget.time_s), MEMORY_LIMIT_MB, int(runs))
    request.displayProgress = False
    request.saveConsoleOutput = False  # else an ompl_<host>_<date>.console file per experiment
    untracked = problem.goal.distanceGoal
    if progress_every is not None:
        problem.goal.distanceGoal = _tracking(untracked, best)  # type: ignore[method-assign, assignment]
    try:
        bench.benchmark(request)
    finally:
        if progress_every is not None:
            del problem.goal.distanceGoal  # the class's own again
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "run.log"
        if not bench.saveResultsToFile(str(path)):
            raise RuntimeError("OMPL could not write its benchmark log")
        text = path.read_text()
    log = _augment_log(
        text,
        [[r for r in rows if r["planner"] == w.getName()] for w in wrapped],
        [w.settings for w in wrapped],
    )
    if progress_every is not None:
        log = _propagations_as_time_limit(log, int(budget.propagations or 0))
    return BenchmarkResult(log=log, runs=rows)


def _tracking(distance: Callable[[Any], float], best: list[float]) -> Callable[[Any], float]:
    """``distance`` (the goal's ``distanceGoal``, which OMPL's planners call on every state
    they add to their tree) that also keeps the smallest value in ``best[0]``."""

    def tracked(state: Any) -> float:
        d = distance(state)
        if d < best[0]:
            best[0] = d
        return d

    return tracked


def _propagations_as_time_limit(log: str, budget: int) -> str:
    """OMPL's "T seconds per run" line with the propagation budget for T: the time axis of
    the progress (and Planner Arena's time-limit line) counts propagations."""
    return re.sub(r"^\S+ seconds per run$", f"{budget} seconds per run", log, count=1, flags=re.M)


def _format(value: float | int | bool) -> str:
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float) and not math.isfinite(value):
        return ""  # OMPL's reader stores an empty value as NULL
    return repr(value) if isinstance(value, float) else str(value)


def _progress_block(runs: list[dict]) -> list[str]:
    """The progress properties of ``runs`` in OMPL's log format: their names and types, the
    run count, then per run its samples, each "v1,v2,...," and ended by ";"."""
    lines = [f"{len(PROGRESS_PROPERTIES)} progress properties for each run"]
    lines += [f"{name} {kind}" for name, kind in PROGRESS_PROPERTIES.items()]
    lines.append(f"{len(runs)} runs")
    for row in runs:
        samples = (
            (float(spent), spent, size, distance) for spent, size, distance in row["progress"]
        )
        lines.append("".join(",".join(map(_format, s)) + ",;" for s in samples))
    return lines


def _augment_log(log: str, per_planner: list[list[dict]], parameters: list[dict[str, str]]) -> str:
    """Add each planner's own ``parameters`` to its common properties in OMPL's log (sorted
    by name, as OMPL writes them; a name OMPL wrote stays as written), append
    :data:`EXTRA_PROPERTIES` to its run properties and put the inner planner's tree size in
    "graph states" and "graph motions"."""
    lines = log.splitlines()
    out: list[str] = []
    i = planner = configured = 0
    header = re.compile(r"^(\d+) properties for each run$")
    common = re.compile(r"^(\d+) common properties$")
    while i < len(lines):
        shared = common.match(lines[i])
        if shared:
            count = int(shared.group(1))
            pairs = [line.split(" = ", 1) for line in lines[i + 1 : i + 1 + count]]
            merged = {**parameters[configured], **{p[0]: p[-1] for p in pairs}}
            out.append(f"{len(merged)} common properties")
            out.extend(f"{name} = {value}" for name, value in sorted(merged.items()))
            i += 1 + count
            configured += 1
            continue
        match = header.match(lines[i])
        if not match:
            out.append(lines[i])
            i += 1
            continue
        count = int(match.group(1))
        names = [line.rsplit(" ", 1)[0] for line in lines[i + 1 : i + 1 + count]]
        out.append(f"{count + len(EXTRA_PROPERTIES)} properties for each run")
        out.extend(lines[i + 1 : i + 1 + count])
        out.extend(f"{name} {kind}" for name, kind in EXTRA_PROPERTIES.items())
        i += 1 + count
        n_runs = int(lines[i].split()[0])
        out.append(lines[i])
        runs = per_planner[planner]
        if len(runs) != n_runs:
            raise RuntimeError(f"OMPL logged {n_runs} runs of a planner, we saw {len(runs)}")
        for k in range(n_runs):
            values = [v.strip() for v in lines[i + 1 + k].rstrip().rstrip(";").split(";")]
            row = runs[k]
            for name, key in (("graph states", "tree_size"), ("graph motions", "tree_edges")):
                if name in names:
                    values[names.index(name)] = str(row[key])
            values += [
                _format(row["solved"]),
                _format(row["propagations"]),
                _format(row["validity_checks"]),
                _format(row["exit_time_s"]),
            ]
            out.append("; ".join(values) + "; ")
        i += 1 + n_runs
        if runs and "progress" in runs[0]:
            out.extend(_progress_block(runs))
            if i < len(lines) and lines[i].strip() != ".":
                raise RuntimeError("OMPL logged progress of its own for a wrapped planner")
        planner += 1
    return "\n".join(out) + "\n"
