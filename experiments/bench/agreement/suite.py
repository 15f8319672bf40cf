"""The same perturbed drops in every engine: one made feeder and one start per trial and
entry, from the verdict's own draws.

Trial ``i`` of a design uses :func:`experiments.drop.perturbations.draw` with the suite's seed
and index ``i`` (the verdict's draws: feeder made to +-1%, mu +-20%, entry pose, yaw and
velocity), the feeder :func:`experiments.drop.verdict.made_feeders` builds from it, and per
entry the start :func:`experiments.drop.verdict.entry_state` makes (the offset halved until the
part is clear of every wall, by partfeeder's clearance). That scene and start go to every
engine: partfeeder at its step (the verdict's, 1e-3 s by default), MuJoCo and pymunk at the
peer step (1e-4 s), restitution 0 in all. Drops are plain rows (:class:`DropRow`).
"""

from __future__ import annotations

import math
import time
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field

from experiments.bench.agreement.designs import NamedDesign
from experiments.bench.agreement.drops import Drop, Peer, partfeeder_drop, peer_drop
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import UNBUILDABLE, entry_state, made_feeders
from experiments.executors.local import map_jobs
from feeders.feeder import ORIENTATIONS, DegenerateDesign
from feeders.scene import Scene
from validity.dynamic import DEFAULT_STEP, DynamicLevel

ENGINES = ("partfeeder", "mujoco", "pymunk")
PEER_STEP = 1e-4  # s: both peers (the outside check's step)


@dataclass(frozen=True)
class AgreementSettings:
    """Trials per entry, the draws' seed, partfeeder's and the peers' steps h (s), the
    longest drop (s), the perturbations, the verdict's target and the engines compared."""

    trials: int = 20
    seed: int = 0
    partfeeder_step: float = DEFAULT_STEP
    peer_step: float = PEER_STEP
    t_max: float = 10.0
    perturbations: Perturbations = field(default_factory=Perturbations)
    target: float = 0.9
    engines: tuple[str, ...] = ENGINES

    def __post_init__(self) -> None:
        checks = (
            ("trials", self.trials, 1, 10_000),
            ("seed", self.seed, 0, 2**32 - 1),
            ("partfeeder step", self.partfeeder_step, 1e-6, 0.1),
            ("peer step", self.peer_step, 1e-6, 0.01),
            ("t_max", self.t_max, 1e-3, 100.0),
            ("target", self.target, 0.0, 1.0),
        )
        for name, value, low, high in checks:
            if not (math.isfinite(value) and low <= value <= high):
                raise ValueError(
                    f"{name} = {value!r} is outside the allowed range [{low:g}, {high:g}]"
                )
        unknown = [e for e in self.engines if e not in ENGINES]
        if unknown or not self.engines:
            raise ValueError(f"engines {list(self.engines)}: choose from {', '.join(ENGINES)}")


@dataclass(frozen=True)
class DropRow:
    """One drop of one design's trial from one entry in one engine (plain data): the start
    (x, y, yaw, vx, vy, omega; empty if unbuildable), the made feeder's mu, the ending, the lip
    speed, its closed form and ratio (nan if not reached), steps, step h (s), wall time (s)."""

    design: str
    trial: int
    entry: str
    engine: str
    start: tuple[float, ...]
    friction: float
    success: bool
    outcome: str
    end: str
    T: float
    pose: tuple[float, ...]
    lip_speed: float
    lip_reference: float
    lip_ratio: float
    steps: int
    h: float
    wall_time: float

    def to_dict(self) -> dict:
        return asdict(self)


def _peer(engine: str, scene: Scene, h: float) -> Peer:
    if engine == "mujoco":
        from experiments.bench.peers.mujoco_engine import MujocoFeederSimulator

        return MujocoFeederSimulator(scene, h)
    from experiments.bench.peers.pymunk_engine import PymunkFeederSimulator

    return PymunkFeederSimulator(scene, h)


def _row(named: str, index: int, entry: str, engine: str, start, scene: Scene, d: Drop) -> DropRow:
    lip = d.lip
    return DropRow(
        named,
        index,
        entry,
        engine,
        tuple(float(v) for v in start),
        float(scene.friction),
        d.ending.success,
        d.ending.outcome,
        d.ending.end,
        d.ending.T,
        d.ending.pose,
        lip.speed if lip else math.nan,
        lip.reference if lip else math.nan,
        lip.ratio if lip else math.nan,
        d.steps,
        d.h,
        d.wall_time,
    )


def trial_starts(scene: Scene, level: DynamicLevel, perturbation) -> dict[str, tuple[float, ...]]:
    """Per entry orientation the perturbed start state of a trial, as the verdict makes it."""
    return {
        o: entry_state(
            level, scene.start(o), perturbation.entry_offsets[k], perturbation.entry_velocities[k]
        )
        for k, o in enumerate(ORIENTATIONS)
    }


def run_trial(named: NamedDesign, index: int, settings: AgreementSettings) -> list[DropRow]:
    """Trial ``index`` of a design in every engine of ``settings``: rows per entry and engine."""
    perturbation = draw(settings.perturbations, settings.seed, index, len(ORIENTATIONS))
    try:
        scene = made_feeders(named.design)(perturbation)
    except DegenerateDesign:
        return [
            DropRow(named.name, index, o, e, (), math.nan, False, UNBUILDABLE, "unbuilt",
                    math.nan, (), math.nan, math.nan, math.nan, 0, math.nan, 0.0)
            for o in ORIENTATIONS
            for e in settings.engines
        ]  # fmt: skip
    scene = _plastic(scene)
    level = DynamicLevel(scene, step=settings.partfeeder_step)
    starts = trial_starts(scene, level, perturbation)
    rows = []
    for engine in settings.engines:
        peer = None if engine == "partfeeder" else _peer(engine, scene, settings.peer_step)
        for o in ORIENTATIONS:
            if peer is None:
                d = partfeeder_drop(scene, o, starts[o], level, settings.t_max)
            else:
                d = peer_drop(scene, starts[o], peer, settings.t_max)
            rows.append(_row(named.name, index, o, engine, starts[o], scene, d))
    return rows


def _plastic(scene: Scene) -> Scene:
    """The scene with restitution 0 (the dynamic level ignores it; the peers are built with
    elasticity 0 and critically damped contacts: said here so the scene says it too)."""
    import dataclasses

    return dataclasses.replace(scene, restitution=0.0)


def _job(args: tuple[NamedDesign, int, AgreementSettings]) -> list[DropRow]:
    return run_trial(*args)


def run_agreement(
    designs: Sequence[NamedDesign],
    settings: AgreementSettings,
    workers: int = 1,
    progress: Callable[[str], None] | None = None,
) -> tuple[list[DropRow], float]:
    """Every trial of every design in every engine; (rows in design, trial order, wall time
    in s). ``workers`` > 1 runs trials in that many spawned processes."""
    jobs = [(d, i, settings) for d in designs for i in range(settings.trials)]
    finished: Counter[str] = Counter()

    def note(index: int, _rows: list[DropRow]) -> None:
        name = jobs[index][0].name
        finished[name] += 1
        if progress and finished[name] == settings.trials:
            progress(f"{name}: {settings.trials} trials done")

    t0 = time.perf_counter()
    results = map_jobs(_job, jobs, workers, on_result=note, ompl=False)
    rows = [row for trial in results for row in trial]
    return rows, time.perf_counter() - t0


def agreement_data(
    designs: Sequence[NamedDesign],
    settings: AgreementSettings,
    workers: int = 1,
    progress: Callable[[str], None] | None = None,
) -> dict:
    """Run the suite and gather everything the report shows (plain data)."""
    from experiments.bench.agreement.provenance import kernel_state, versions
    from experiments.bench.agreement.tables import all_tables

    kernel = kernel_state()
    rows, wall = run_agreement(designs, settings, workers, progress)
    s = asdict(settings)
    s["perturbations"] = settings.perturbations.to_dict()
    return {
        "settings": s,
        "engines": list(settings.engines),
        "designs": {d.name: d.design.to_dict() for d in designs},
        "versions": versions(),
        "kernel": kernel,
        "workers": workers,
        "wall_time_s": wall,
        "tables": all_tables(rows, settings.target),
        "drops": [r.to_dict() for r in rows],
    }
