"""Run one stress case at its level and measure it independently: the case's record.

The record is plain data (JSON- and YAML-ready) and a function of the case alone: running a
case again gives the same record, bit for bit (wall time is measured beside it, not in it).
"""

from __future__ import annotations

import dataclasses
import math
import traceback
from typing import Any

import numpy as np

from experiments.stress.bounds import (
    KINEMATIC_ENERGY_REL,
    PUSH_OUT_SLACK,
    broken,
    dynamic_energy_allowance,
    penetration_allowance,
)
from experiments.stress.case import Case
from experiments.stress.measures import (
    PartShape,
    Solid,
    accumulated_errors,
    component_of,
    correction_work,
    free_components,
    kinetic_energy,
    linearisation_errors,
    mechanical_energy,
    penetration_depths,
    placed_points,
    pose_corrections,
    wrench_work,
)
from experiments.stress.parts import (
    FEEDER_STAND_IN,
    FREE_FORM_STAND_IN,
    is_composite,
    read_part,
    with_mass,
)
from feeders.part_shape import part_extent
from feeders.scene import Scene
from feeders.scene_yaml import checked_scene, scene_from_dict


def scene_of(case: Case) -> Scene:
    """The case's scene with its mass, moment of inertia and friction. A composite part
    (:mod:`experiments.stress.parts`) replaces a stand-in peg the scene is read with: a feeder
    is built around the peg cases' part (its chutes are made for it; its entries are not the
    composite part's and are not checked), a free-form scene's start is checked with the
    composite part itself."""
    spec = case.scene.get("part")
    if not is_composite(spec):
        scene = scene_from_dict(case.scene, name="stress")
        part = dataclasses.replace(scene.part, mass=case.mass, inertia=case.inertia)
        return dataclasses.replace(scene, part=part, friction=case.friction)
    composite = read_part(spec)
    feeder = "feeder" in case.scene
    stand_in = FEEDER_STAND_IN if feeder else FREE_FORM_STAND_IN
    # the stand-in's start is not checked: the composite part's is, below (case 41/518: the
    # stand-in peg overlapped a free-form scene where the composite part did not)
    scene = scene_from_dict({**case.scene, "part": stand_in}, name="stress", check=feeder)
    composite = with_mass(composite, case.mass, case.inertia)  # type: ignore[arg-type]
    # Scene.part is typed Peg; the levels take any part (feeders.part_shape.Part)
    scene = dataclasses.replace(scene, part=composite, friction=case.friction)  # type: ignore[arg-type]
    return scene if feeder else checked_scene(scene)


def _simulate(case: Case, scene: Scene) -> tuple[np.ndarray, dict[str, Any]]:
    """The recorded states of the case's run (rows, start first) and the level's telemetry."""
    from validity import make_level  # numba: compiled on first use, so imported here

    level = make_level(case.level, scene, step=case.h)
    if case.level == "geometric":
        final = level.propagate(case.state, case.control, case.duration)
        states = np.array([case.state, final], dtype=float)
        return states, {"end": "duration", "push_cap": 0.0}
    if case.level == "kinematic":
        run = level.run(case.state, case.control, case.duration, record=True)
        return run.states, {**run.summary, "end": run.end, "push_cap": 0.0}
    traj = level.simulate(case.state, case.control, case.duration)
    return traj.states, {
        **traj.summary,
        "end": traj.end,
        "push_cap": level.push_cap,
        "h": traj.h,
    }


def _energy(case: Case, scene: Scene, states: np.ndarray, h: float) -> tuple[float, float]:
    """``(gain, allowed)``: energy gained without input and the bound on it. At the dynamic
    level the wrench's work and the most the pose corrections can have lifted the part through
    gravity and the wrench (:func:`correction_work`) are subtracted."""
    mass, inertia = scene.part.mass, scene.part.inertia
    if case.level == "kinematic":
        commanded = float(kinetic_energy(np.array(case.control), mass, inertia)[0])
        after = kinetic_energy(states[1:, 3:6], mass, inertia)
        gain = float(np.max(after - commanded, initial=0.0))
        return gain, KINEMATIC_ENERGY_REL * commanded
    if case.level == "geometric":
        return 0.0, 0.0
    g = math.hypot(*scene.gravity)
    work = wrench_work(states, case.control)
    lift = correction_work(pose_corrections(states, h), case.control, mass, scene.gravity)
    energy = mechanical_energy(states, mass, inertia, scene.gravity)
    gain = float(np.max(energy - energy[0] - work - lift, initial=0.0))
    start_kinetic = float(kinetic_energy(states[0, 3:6], mass, inertia)[0])
    scale = mass * g * part_extent(scene.part) + start_kinetic + float(np.max(np.abs(work)))
    return gain, dynamic_energy_allowance(scale)


def _push_out(case: Case, scene: Scene, states: np.ndarray, h: float) -> float:
    """Fastest speed (length/s) at which a step's pose correction (:func:`pose_corrections`)
    moved a point of the part (dynamic level; 0 otherwise): |dx, dy| + R |dtheta| over h."""
    if case.level != "dynamic" or len(states) < 2:
        return 0.0
    step = pose_corrections(states, h)
    radius = scene.part.bounding_radius()
    move = np.hypot(step[:, 0], step[:, 1]) + radius * np.abs(step[:, 2])
    return float(np.max(move, initial=0.0) / h)


def _crossed_step(solid: Solid, shape: PartShape, scene: Scene, states: np.ndarray) -> int | None:
    """The first step at which the part's :attr:`PartShape.anchor` (a point of its material:
    the centre of mass unless that lies outside the part, as in a cup's mouth) is in another
    piece of free space than at the start, or inside the solid (0 if it starts there); None
    when it never is. An anchor off the centre of mass may leave the bounds box, where no piece
    is known: those states are skipped."""
    components = free_components(solid, scene.bounds)
    if not shape.anchor.any():
        label = component_of(components, states)
        steps = np.arange(len(states))
    else:
        points = placed_points(shape.anchor[None, :], states)[:, 0, :]
        x0, x1, y0, y1 = scene.bounds
        known = (x0 <= points[:, 0]) & (points[:, 0] <= x1)
        known &= (y0 <= points[:, 1]) & (points[:, 1] <= y1)
        steps = np.nonzero(known)[0]
        if len(steps) == 0:
            return None
        label = component_of(components, points[steps])
    moved = np.nonzero(label != label[0])[0]
    if label[0] < 0 or len(moved):
        return int(steps[moved[0]]) if len(moved) else int(steps[0])
    return None


def record_of(case: Case) -> dict[str, Any]:
    """Run the case and measure it (see :mod:`experiments.stress.bounds` for the bounds)."""
    record: dict[str, Any] = {
        "seed": case.seed,
        "index": case.index,
        "level": case.level,
        "family": case.family,
        "placement": case.placement,
        "h": case.h,
        "steps": 0,
        "end": "",
        "error": None,
        "nonfinite": False,
        "start_depth": 0.0,
        "max_depth": 0.0,
        "depth_allowed": 0.0,
        "step_error": 0.0,
        "part_size": 0.0,
        "energy_gain": 0.0,
        "energy_allowed": 0.0,
        "push_out": 0.0,
        "push_out_allowed": 0.0,
        "crossed_step": None,
        "lcp_failures": 0,
        "fallbacks": 0,
        "jams": 0,
        "stalls": 0,
    }
    try:
        scene = scene_of(case)
        states, telemetry = _simulate(case, scene)
        _measure(case, scene, states, telemetry, record)
    except Exception as exc:  # every exception is a finding, recorded with where it came from
        where = traceback.extract_tb(exc.__traceback__)[-1]
        record["error"] = f"{type(exc).__name__}: {exc} ({where.filename}:{where.lineno})"
    record["hard"], record["soft"] = broken(record)
    return record


def _measure(
    case: Case, scene: Scene, states: np.ndarray, telemetry: dict[str, Any], record: dict
) -> None:
    record["steps"] = len(states) - 1
    record["end"] = str(telemetry["end"])
    record["lcp_failures"] = int(telemetry.get("failures", 0))
    record["fallbacks"] = int(telemetry.get("frictionless_fallbacks", 0))
    record["jams"] = int(telemetry.get("jams", 0))
    record["stalls"] = int(telemetry.get("stalls", 0))
    if not np.all(np.isfinite(states)):
        record["nonfinite"] = True
        states = states[: int(np.argmax(~np.all(np.isfinite(states), axis=1)))]
        if len(states) == 0:
            return
    solid = Solid.of(scene)
    shape = PartShape.of(scene.part)
    depths = penetration_depths(solid, shape, states)
    record["start_depth"] = float(depths[0])
    record["max_depth"] = float(depths.max())
    step_error = 0.0
    if case.level == "dynamic" and len(states) > 1:
        errors = linearisation_errors(states, solid, shape, scene.obstacles.circles)
        step_error = float(accumulated_errors(errors, depths).max())
    record["step_error"] = step_error
    record["part_size"] = float(part_extent(scene.part))
    record["depth_allowed"] = penetration_allowance(case.level, float(depths[0]), step_error)
    if case.level != "geometric":
        gain, allowed = _energy(case, scene, states, float(telemetry.get("h", case.h)))
        record["energy_gain"], record["energy_allowed"] = gain, allowed
        record["crossed_step"] = _crossed_step(solid, shape, scene, states)
    if case.level == "dynamic":
        record["push_out"] = _push_out(case, scene, states, float(telemetry["h"]))
        record["push_out_allowed"] = float(telemetry["push_cap"]) + PUSH_OUT_SLACK
