"""The agreement suite on a device family (issue 35, part 4): the family verdict's own perturbed
drops of any part through the family's devices, in partfeeder, MuJoCo and pymunk.

Trial ``i`` of a design is the family verdict's trial ``i``
(:func:`experiments.drop.verdict.run_trial` with
:func:`experiments.drop.family_verdict.made_devices`): the draw
:func:`experiments.drop.perturbations.draw` (seed, ``i``, the family's entries, its n design
factors), the device that draw makes, and per entry (the family's, in the file's order) the
start :func:`experiments.drop.verdict.entry_state` makes. That scene and start go to every
engine: partfeeder at its step, the peers' compound bodies
(:mod:`experiments.bench.peers.compound`: the part's own convex pieces, mass and inertia; the
device's pieces) at the peer step. Rows and tables are the peg feeder's
(:class:`.suite.DropRow`, :mod:`.tables`): no lip speed (a family names no lip).

Designs are named ``default`` (the family's defaults), ``halton:SEED:INDEX`` (the INDEX-th
point of the family's box, as ``partfeeder run`` numbers a family's sweep) or the n values.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from experiments.bench.agreement.drops import Peer, partfeeder_drop, peer_drop
from experiments.bench.agreement.suite import AgreementSettings, DropRow, _row
from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import UNBUILDABLE, entry_state
from experiments.executors.local import map_jobs
from feeders.device_family import DeviceFamily, load_family
from feeders.feeder import DegenerateDesign
from feeders.halton import halton_points
from feeders.scene import Scene
from validity.dynamic import DynamicLevel

MAX_HALTON_INDEX = 100_000


@dataclass(frozen=True)
class FamilyDesign:
    """A family's design (n values in the family's order) and the name it is reported under."""

    name: str
    values: tuple[float, ...]


def family_design(family: DeviceFamily, token: str) -> FamilyDesign:
    """The design ``token`` names in ``family``; ValueError (one line naming it) otherwise."""
    token = token.strip()
    names = family.vector_names
    if token == "default":
        return FamilyDesign(token, tuple(float(v) for v in family.default()))
    if token.startswith("halton:"):
        fields = token.split(":")
        try:
            if len(fields) != 3:
                raise ValueError
            seed, index = int(fields[1]), int(fields[2])
        except ValueError:
            raise ValueError(f"design {token!r}: a Halton design is halton:SEED:INDEX") from None
        if not (0 <= seed < 2**32 and 0 <= index < MAX_HALTON_INDEX):
            raise ValueError(
                f"design {token!r}: SEED in [0, 2^32), INDEX in [0, {MAX_HALTON_INDEX})"
            )
        point = halton_points(index + 1, seed, family.space())[index]
        return FamilyDesign(token, tuple(float(v) for v in point))
    try:
        values = tuple(float(v) for v in token.split(","))
    except ValueError:
        raise ValueError(
            f"design {token!r}: default, halton:SEED:INDEX or {len(names)} comma-separated "
            f"numbers ({','.join(names)})"
        ) from None
    if len(values) != len(names) or not all(math.isfinite(v) for v in values):
        raise ValueError(
            f"design {token!r}: {len(values)} values; the family {family.name} needs "
            f"{len(names)} finite numbers ({','.join(names)})"
        )
    return FamilyDesign(token, values)


@dataclass(frozen=True)
class FamilySuite:
    """What every worker needs: the family file (each worker loads it), the suite's settings
    and pymunk's wall rounding radius (length; :data:`.compound.ROUNDING`)."""

    family_file: str
    settings: AgreementSettings
    pymunk_radius: float


def family_peer(engine: str, scene: Scene, h: float, pymunk_radius: float) -> Peer:
    """A peer's compound model of ``scene`` at step ``h`` (s)."""
    from experiments.bench.peers.compound import MujocoCompoundSimulator, PymunkCompoundSimulator

    if engine == "mujoco":
        return MujocoCompoundSimulator(scene, h)
    return PymunkCompoundSimulator(scene, h, radius=pymunk_radius)


def trial_scene(
    family: DeviceFamily, design: FamilyDesign, index: int, settings: AgreementSettings
) -> tuple[Scene, DynamicLevel, dict[str, tuple[float, ...]]] | None:
    """Trial ``index``'s made device (restitution 0), its dynamic level and per entry the
    start, as the family verdict makes them; None when the made device cannot be built."""
    entries = entry_names(family)
    n = len(family.vector_names)
    perturbation = draw(settings.perturbations, settings.seed, index, len(entries), n)
    try:
        scene = made_devices(family, design.values)(perturbation)
    except DegenerateDesign:
        return None
    scene = dataclasses.replace(scene, restitution=0.0)
    level = DynamicLevel(scene, step=settings.partfeeder_step)
    starts = {
        o: entry_state(
            level, scene.start(o), perturbation.entry_offsets[k], perturbation.entry_velocities[k]
        )
        for k, o in enumerate(entries)
    }
    return scene, level, starts


def run_family_trial(
    family: DeviceFamily, design: FamilyDesign, index: int, suite: FamilySuite
) -> list[DropRow]:
    """Trial ``index`` of a family design in every engine: the verdict's draw, device and
    starts (:mod:`experiments.drop.family_verdict`), rows per entry and engine."""
    settings = suite.settings
    entries = entry_names(family)
    made = trial_scene(family, design, index, settings)
    if made is None:
        return [
            DropRow(design.name, index, o, e, (), math.nan, False, UNBUILDABLE, "unbuilt",
                    math.nan, (), math.nan, math.nan, math.nan, 0, math.nan, 0.0)
            for o in entries
            for e in settings.engines
        ]  # fmt: skip
    scene, level, starts = made
    rows = []
    for engine in settings.engines:
        peer = None
        if engine != "partfeeder":
            peer = family_peer(engine, scene, settings.peer_step, suite.pymunk_radius)
        for o in entries:
            if peer is None:
                d = partfeeder_drop(scene, o, starts[o], level, settings.t_max)
            else:
                d = peer_drop(scene, starts[o], peer, settings.t_max)
            rows.append(_row(design.name, index, o, engine, starts[o], scene, d))
    return rows


def _job(args: tuple[FamilySuite, FamilyDesign, int]) -> list[DropRow]:
    suite, design, index = args
    return run_family_trial(load_family(suite.family_file), design, index, suite)


def run_family_agreement(
    suite: FamilySuite,
    designs: Sequence[FamilyDesign],
    workers: int = 1,
    progress: Callable[[str], None] | None = None,
) -> tuple[list[DropRow], float]:
    """Every trial of every design in every engine; (rows in design, trial order, wall s)."""
    trials = suite.settings.trials
    jobs = [(suite, d, i) for d in designs for i in range(trials)]
    finished: Counter[str] = Counter()

    def note(index: int, _rows: list[DropRow]) -> None:
        name = jobs[index][1].name
        finished[name] += 1
        if progress and finished[name] == trials:
            progress(f"{name}: {trials} trials done")

    t0 = time.perf_counter()
    results = map_jobs(_job, jobs, workers, on_result=note, ompl=False)
    return [row for trial in results for row in trial], time.perf_counter() - t0


def model_note(pymunk_radius: float) -> str:
    """The peers' model choices, one line for the report."""
    from experiments.bench.peers.mujoco_engine import PART_DEPTH

    return (
        f"compound bodies from the part's convex pieces with its own mass and inertia; MuJoCo "
        f"part pieces mesh prisms {PART_DEPTH:g} deep; pymunk wall segments rounded "
        f"{pymunk_radius:g}"
    )


def family_agreement_data(
    suite: FamilySuite,
    designs: Sequence[FamilyDesign],
    workers: int = 1,
    progress: Callable[[str], None] | None = None,
) -> dict:
    """Run the family suite and gather what the report shows (plain data, the peg suite's
    keys, with ``family``: its name, file and the peers' model choices)."""
    from experiments.bench.agreement.provenance import kernel_state, versions
    from experiments.bench.agreement.tables import all_tables

    family = load_family(suite.family_file)
    kernel = kernel_state()
    rows, wall = run_family_agreement(suite, designs, workers, progress)
    s = asdict(suite.settings)
    s["perturbations"] = suite.settings.perturbations.to_dict()
    s["pymunk_radius"] = suite.pymunk_radius
    return {
        "family": {
            "name": family.name,
            "file": str(Path(suite.family_file)),
            "parameters": list(family.vector_names),
            "model": model_note(suite.pymunk_radius),
        },
        "settings": s,
        "engines": list(suite.settings.engines),
        "designs": {d.name: list(d.values) for d in designs},
        "versions": versions(),
        "kernel": kernel,
        "workers": workers,
        "wall_time_s": wall,
        "tables": all_tables(rows, suite.settings.target),
        "drops": [r.to_dict() for r in rows],
    }


DESIGNS = {
    "fig1-cup": (
        "default",  # open end first it comes to rest in the head (docs/cup-example.md)
        "0.6907,1.2855,1.2213,1.8129,1.1795,0.5437,0.1447,0.4392",  # the optimum (same page)
        "halton:0:15",  # both entries 10/10 in a partfeeder scan of the first 80 (10 trials)
        "halton:0:22",  # open_leading 10/10, open_trailing 5/10: near the threshold
        "halton:0:28",  # 7/10 and 2/10
        "halton:0:47",  # 1/10 and 10/10
    ),
    # docs/families.md's L bracket in the fig1-cup device: `partfeeder family new l-fig1
    # --part examples/l-part.yaml` (none of its first 80 Halton designs works in partfeeder)
    "l-fig1": (
        "default",
        "halton:0:10",  # x_axis_up_chute 5/10, x_axis_down_chute 4/10
        "halton:0:18",  # 0/10 and 10/10
        "halton:0:22",  # 7/10 and 0/10
        "halton:0:28",  # 3/10 and 5/10
        "halton:0:40",  # 0/10 and 8/10
    ),
}
"""The measured design sets by family name (docs/agreement.md): chosen from a partfeeder scan
of the family's first 80 Halton designs (seed 0, 10 trials each) to hold designs that work,
fail, and sit near the threshold from either entry."""


def default_family_designs(family: DeviceFamily) -> tuple[str, ...]:
    """The family's measured set (:data:`DESIGNS`), else its default and its first four
    Halton designs (seed 0)."""
    return DESIGNS.get(family.name, ("default", *(f"halton:0:{i}" for i in range(4))))


def settings_of(data: dict) -> AgreementSettings:
    """The suite's settings as ``family_agreement_data`` stored them (agreement.json)."""
    s = dict(data["settings"])
    s.pop("pymunk_radius", None)
    s["perturbations"] = Perturbations(**s["perturbations"])
    s["engines"] = tuple(s["engines"])
    return AgreementSettings(**s)
