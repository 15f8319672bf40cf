"""Plan a part's motion through a scene with one level and one OMPL control planner.

Everything returned is plain data (numpy arrays and numbers): OMPL objects stay inside
:func:`plan`, so results can be pickled, stored and drawn.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from ompl import base as ob
from ompl import control as oc
from ompl import util as ou

from feeders.scene import Scene
from planners.adapters import state_propagator, validity_checker
from planners.exclusive import one_at_a_time
from planners.goals import GoalBox
from planners.projections import register_pose_projection
from planners.registry import make_planner
from planners.spaces import level_spaces, state_codec
from validity import make_level


@dataclass(frozen=True)
class PlannerSettings:
    """How OMPL drives a level: one propagation step, and how many steps a control lasts.

    ``step`` (s) is OMPL's propagation step; each step the level integrates at its own finer
    ``h``. A control is held for ``min_steps``..``max_steps`` propagation steps.
    """

    step: float = 0.05
    min_steps: int = 1
    max_steps: int = 20

    def __post_init__(self) -> None:
        if not (0.0 < self.step <= 10.0):
            raise ValueError(f"planner step = {self.step!r} is outside the allowed range (0, 10]")
        if not (1 <= self.min_steps <= self.max_steps):
            raise ValueError("planner steps: need 1 <= min_steps <= max_steps")


@dataclass(frozen=True)
class PlanResult:
    """One planning run. States are rows of the level's state (pose first: x, y, yaw)."""

    scene: str
    level: str
    planner: str
    orientation: str
    seed: int
    solved: bool
    time: float
    tree_size: int
    goal_distance: float
    path: np.ndarray = field(repr=False)
    controls: np.ndarray = field(repr=False)
    durations: np.ndarray = field(repr=False)
    fine_path: np.ndarray = field(repr=False)
    tree_vertices: np.ndarray = field(repr=False)
    tree_edges: np.ndarray = field(repr=False)
    propagations: int | None = None  # made by the planner (counted with a propagation budget)

    @property
    def path_length(self) -> float:
        """Length travelled by the centre of mass along the fine path (length units)."""
        if len(self.fine_path) < 2:
            return 0.0
        return float(np.sum(np.hypot(*np.diff(self.fine_path[:, :2], axis=0).T)))

    @property
    def path_duration(self) -> float:
        return float(np.sum(self.durations))

    def summary(self) -> dict:
        return {
            "scene": self.scene,
            "level": self.level,
            "planner": self.planner,
            "orientation": self.orientation,
            "seed": self.seed,
            "solved": self.solved,
            "time_s": round(self.time, 6),
            "tree_size": self.tree_size,
            "path_states": len(self.path),
            "path_length": round(self.path_length, 6),
            "path_duration_s": round(self.path_duration, 6),
            "goal_distance": round(self.goal_distance, 6),
        }


def fine_path(
    level,
    path: np.ndarray,
    controls: np.ndarray,
    durations: np.ndarray,
    piece: float,
) -> np.ndarray:
    """Re-propagate a control path as OMPL did, in pieces of ``piece`` seconds (the
    propagation step): every state the level visits. Each piece starts from where the last
    one ended, as in the planner, so the states at piece ends are the planner's own states,
    not a re-integration that a chaotic contact trajectory would amplify. A level with
    ``propagate_path`` gives the states inside a piece from the same run; otherwise a piece
    is split into equal sub-pieces of at most the level's step."""
    if len(path) == 0:
        return np.zeros((0, level.state_dim))
    states = [np.asarray(path[0], dtype=float)]
    inside = getattr(level, "propagate_path", None)
    split = max(1, math.ceil(piece / level.step - 1e-9))
    for i in range(len(controls)):
        state = tuple(path[i])
        for _ in range(max(1, round(durations[i] / piece))):
            if inside is not None:
                run = inside(state, controls[i], piece)
                states.extend(run[1:])
                state = tuple(run[-1])  # what propagate returns, without running it again
                continue
            for _ in range(split):
                state = level.propagate(state, controls[i], piece / split)
                states.append(np.asarray(state, dtype=float))
    return np.array(states)


@dataclass
class ControlProblem:
    """One level's planning problem as OMPL objects, ready for any OMPL control planner.

    ``ss`` is the ``oc.SimpleSetup`` with start, goal, validity checker and propagator set
    (no planner); ``si`` its space information, with the propagation step and control
    durations of ``settings`` and the pose projection registered (KPIECE1, EST); ``level`` the
    fidelity level (:mod:`validity`) behind them; ``goal`` the goal region; ``read`` and
    ``write`` turn OMPL states into tuples and back (:func:`planners.spaces.state_codec`).
    ``counts`` holds [validity checks, propagations] made so far when counted.
    """

    ss: oc.SimpleSetup
    si: oc.SpaceInformation
    level: Any
    goal: GoalBox
    read: Callable
    counts: list[int] | None = None  # [validity checks, propagations] when counted
    scene: Scene | None = None
    orientation: str = ""
    seed: int = 1
    settings: PlannerSettings = field(default_factory=PlannerSettings)
    write: Callable | None = None

    @property
    def space(self) -> ob.StateSpace:
        """The state space (SE2, or SE2 x R^3 for pose and velocity)."""
        return self.si.getStateSpace()

    @property
    def start(self) -> tuple[float, ...]:
        """The start state as a tuple (the level's state at rest in the start pose)."""
        assert self.scene is not None
        return tuple(self.level.state_of_pose(self.scene.start(self.orientation)))

    @property
    def propagations(self) -> int:
        """Propagations made so far (0 when not counted)."""
        return 0 if self.counts is None else self.counts[1]

    @property
    def validity_checks(self) -> int:
        """Validity checks made so far (0 when not counted)."""
        return 0 if self.counts is None else self.counts[0]

    def termination(
        self, time: float, propagations: int | None = None
    ) -> ob.PlannerTerminationCondition:
        """OMPL's condition to stop after ``time`` seconds or, with ``propagations``, once
        that many more propagations have been made from now (a budget that does not depend
        on the machine: the same seed and budget give the same tree anywhere)."""
        timed = ob.timedPlannerTerminationCondition(float(time))
        if propagations is None:
            return timed
        counts = self.counts
        if counts is None:
            raise ValueError("a propagation budget needs a counted problem (count=True)")
        if not 1 <= int(propagations) <= 10**9:
            raise ValueError(f"propagations = {propagations!r} is outside the range [1, 1e9]")
        stop_at = counts[1] + int(propagations)
        spent = ob.PlannerTerminationCondition(lambda: counts[1] >= stop_at)
        return ob.plannerOrTerminationCondition(timed, spent)

    def warm_up(self) -> None:
        """Compile (or load from numba's cache) the level's kernels now, so that a planner's
        clock measures planning, not compilation (seconds on a first run)."""
        start = self.start
        self.level.is_valid(start)
        self.level.propagate(start, np.zeros(self.level.control_dim), self.settings.step)


def seed_ompl(seed: int) -> None:
    """Seed OMPL's process-wide generator (OMPL 2 restarts it on every seeding)."""
    previous = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)  # "seed changed after start" is expected here
    ou.RNG.setSeed(int(seed))
    ou.setLogLevel(previous)


def region_corners(
    pose: tuple[float, float, float], region: tuple[float, float] | None
) -> list[tuple[float, float, float]]:
    """The 8 corners of the entry region round ``pose``: x and y each moved by +-position,
    yaw by +-yaw (``region``: (position, yaw)); none without a region or with a zero one."""
    if region is None or (region[0] == 0.0 and region[1] == 0.0):
        return []
    p, w = region
    return [
        (pose[0] + sx * p, pose[1] + sy * p, pose[2] + sw * w)
        for sx in (-1.0, 1.0)
        for sy in (-1.0, 1.0)
        for sw in (-1.0, 1.0)
    ]


def control_problem(
    scene: Scene,
    level_name: str,
    orientation: str,
    seed: int,
    settings: PlannerSettings | None = None,
    level_options: dict | None = None,
    count: bool = False,
    start_region: tuple[float, float] | None = None,
) -> ControlProblem:
    """From the scene's start ``orientation`` into its goal region at level ``level_name``:
    state and control spaces, the level as validity checker and propagator, the propagation
    step and control durations of ``settings``, the pose projection and the goal (its sampler
    seeded by ``seed``, as is OMPL's generator). No planner is set. With ``count``, the
    problem's ``counts`` holds [validity checks, propagations] made so far. The level's
    kernels are compiled (or loaded from numba's cache) before it returns, so a planner's
    clock measures planning: on a cold cache the first propagation took the seconds of a
    compile, and a time budget ran out in it (issue 22). ``start_region`` (position, yaw
    half-ranges: the verdict's entry perturbations) adds the region's 8 corner poses that
    are valid as further start states after the nominal one, so that the problem asks
    whether the part can reach the goal from anywhere it may enter (issue 21: the geometric
    level as a relaxation of the perturbed drops)."""
    settings = settings or PlannerSettings()
    start_pose = scene.start(orientation)
    level = make_level(level_name, scene, **(level_options or {}))
    seed_ompl(seed)
    space, controls = level_spaces(level)
    ss = oc.SimpleSetup(controls)
    counts = [0, 0] if count else None
    ss.setStateValidityChecker(validity_checker(level, counts))
    ss.setStatePropagator(state_propagator(level, counts))
    si = ss.getSpaceInformation()
    si.setPropagationStepSize(settings.step)
    si.setMinMaxControlDuration(settings.min_steps, settings.max_steps)
    register_pose_projection(space, level.state_dim)
    read, write = state_codec(level.state_dim)
    start = space.allocState()
    write(start, level.state_of_pose(start_pose))
    ss.setStartState(start)
    for pose in region_corners(start_pose, start_region):
        state = level.state_of_pose(pose)
        if level.is_valid(state):
            corner = space.allocState()
            write(corner, state)
            ss.addStartState(corner)
    goal = GoalBox(si, scene.goal, level.state_dim, np.random.default_rng(seed))
    ss.setGoal(goal)
    problem = ControlProblem(
        ss=ss,
        si=si,
        level=level,
        goal=goal,
        read=read,
        counts=counts,
        scene=scene,
        orientation=orientation,
        seed=int(seed),
        settings=settings,
        write=write,
    )
    problem.warm_up()
    return problem


@one_at_a_time
def plan(
    scene: Scene,
    level_name: str = "geometric",
    planner_name: str = "rrt",
    orientation: str = "heavy_leading",
    time_limit: float = 5.0,
    seed: int = 1,
    settings: PlannerSettings | None = None,
    level_options: dict | None = None,
    propagations: int | None = None,
) -> PlanResult:
    """Plan from the scene's start ``orientation`` into its goal region.

    ``seed`` seeds OMPL's generator (process-wide; OMPL 2 restarts it on every seeding) and the
    goal sampler, so the same seed gives the same tree and path. ``propagations``: also stop
    once the planner has made that many propagations (a machine-independent budget, as the
    sweep's; ``time_limit`` stays as a cap): the same seed and budget then give the same
    result on any machine and under any load.
    """
    settings = settings or PlannerSettings()
    problem = control_problem(
        scene,
        level_name,
        orientation,
        seed,
        settings,
        level_options,
        count=propagations is not None,
    )
    ss, si, level, goal, read = problem.ss, problem.si, problem.level, problem.goal, problem.read
    ss.setPlanner(make_planner(planner_name, si))
    ss.setup()
    t0 = time.perf_counter()
    before = problem.propagations
    ss.solve(problem.termination(time_limit, propagations))
    elapsed = time.perf_counter() - t0
    solved = bool(ss.haveExactSolutionPath())

    path = np.zeros((0, level.state_dim))
    controls = np.zeros((0, level.control_dim))
    durations = np.zeros(0)
    goal_distance = math.inf
    if ss.haveSolutionPath():
        p = ss.getSolutionPath()
        path = np.array([read(p.getState(i)) for i in range(p.getStateCount())])
        controls = np.array(
            [
                [p.getControl(i)[k] for k in range(level.control_dim)]
                for i in range(p.getControlCount())
            ]
        ).reshape(-1, level.control_dim)
        durations = np.array([p.getControlDuration(i) for i in range(p.getControlCount())])
        goal_distance = goal.distanceGoal(p.getState(p.getStateCount() - 1))

    pd = ob.PlannerData(si)
    ss.getPlannerData(pd)
    nv = pd.numVertices()
    vertices = np.array([read(pd.getVertex(i).getState()) for i in range(nv)]).reshape(
        -1, level.state_dim
    )
    edges = [(i, j) for i in range(nv) for j in pd.getEdges(i)]
    return PlanResult(
        scene=scene.name,
        level=level_name,
        planner=planner_name,
        orientation=orientation,
        seed=int(seed),
        solved=solved,
        time=elapsed,
        tree_size=nv,
        goal_distance=float(goal_distance),
        path=path,
        controls=controls,
        durations=durations,
        fine_path=fine_path(level, path, controls, durations, settings.step),
        tree_vertices=vertices,
        tree_edges=np.array(edges, dtype=np.int64).reshape(-1, 2),
        propagations=None if problem.counts is None else problem.counts[1] - before,
    )
