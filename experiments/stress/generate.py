"""Stress cases from a seed: case ``i`` of seed ``s`` is a function of ``(s, i)`` alone.

Levels and scene families are dealt in turn (case ``i`` runs level ``i mod L`` on family
``(i div L) mod F``), so every few dozen cases cover every pair; everything else is drawn from
``numpy.random.default_rng([s, i])``:

- families: Halton designs of the feeder (the first 128 of seed ``s``) and the free-form
  scenes of :mod:`experiments.stress.scenes`;
- placements: ``free`` (0.05 or more from every wall), ``near`` (gap 1e-6 to 0.03),
  ``flush`` (a side on a face, gap 0 to 1e-3, some tilted by up to 1e-2 rad), ``corner`` (a
  corner on a corner of the solid), ``overlap`` (dynamic level only: up to 0.0095 deep, inside
  its validity tolerance 0.01), ``wedged`` (the peg across a chute, touching both walls),
  ``pin`` (at the junction of the pin's finger and disc), ``drop`` (released above a floor
  with a post), ``entry`` (a feeder's own start poses);
- speeds up to what the levels accept (dynamic: 20 length/s and 20 rad/s, its valid-state
  limit; kinematic and geometric: inputs up to 1000 length/s and 100 rad/s), friction 0 to 2,
  restitution 0 to 1, h from 1e-5 to 1e-1 s, 10 to 1000 steps, mass 1e-3 to 1e3 and the moment
  of inertia up to ten times off the part's own.

Composite parts (issue 24) have cases of their own, beside the peg's: case ``COMPOSITE_BASE +
j`` is composite case ``j`` (:func:`composite_index`), so every peg case keeps its index and
its draws (case 2606 of seed 0 is the case it always was). Composite case ``j`` is dealt as a
peg case is, level ``j mod L`` and family ``(j div L) mod F``, and its part's kind
(:data:`experiments.stress.parts.KINDS`: a scaled cup, a non-convex outline, a plate with
discs) ``(j div L F) mod 3``, so 81 consecutive composite cases hold every (kind, family,
level); its part is drawn by :func:`experiments.stress.parts.draw_part` and its family is
recorded as ``family+kind`` (``chute+cup``). Its placements are the peg's with three changes:
``flush`` and ``pin`` turn a side of the part's convex hull onto the face (the cup's base,
walls or rims), ``wedged`` spans the chute at the yaw where the part's width across it
(its outline projected on the chute's normal) is the chute's (:func:`wedge_angle`; the chute
between the part's narrowest and widest widths), and a feeder's ``entry`` and the issue's
drop (a peg's) are not drawn. ``partfeeder stress --cases N`` runs ``--composite M`` of them
besides the N peg cases (default N / 3, a quarter of the run).

Ramp-foot cases (issue 35) are a third stream, case ``RAMP_FOOT_BASE + j``
(:func:`ramp_foot_case`, ``--ramp-foot M``, default N / 30): a peg's corner sliding fast down a
40-75 degree ramp, or down an upright wall it is already slightly inside, into the concave
corner where the face meets the floor, the geometry where a floor contact hid behind a seam.
``generate_case(..., step=h)`` runs any case at another step with the same number of steps and
every other draw unchanged (``--step``).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import shapely

from experiments.stress.case import Case
from experiments.stress.measures import PartShape, Solid, placed_points, union_of
from experiments.stress.parts import FEEDER_STAND_IN, KINDS, draw_part, read_part
from experiments.stress.placement import (
    Pose,
    boundary_anchors,
    flush_yaw,
    free_pose,
    hull_sides,
    in_bounds,
    side_flush_yaw,
    signed_distance,
    slide_to,
    span_range,
    touching_pose,
    wedge_angle,
    wedge_yaw,
)
from experiments.stress.scenes import (
    BOUNDS,
    FREE_FORM,
    ISSUE_POST,
    Obstacles,
    ramp_foot,
    scale_chute,
)
from feeders.feeder import ORIENTATIONS
from feeders.halton import halton_designs
from feeders.part import Peg
from feeders.part_shape import part_extent
from feeders.scene import wrap_angle
from feeders.scene_yaml import SceneError, scene_from_dict

FAMILIES = ("feeder", *FREE_FORM)
PLACEMENTS = (
    "free",
    "near",
    "flush",
    "corner",
    "overlap",
    "wedged",
    "pin",
    "drop",
    "issue_drop",
    "entry",
)
DYNAMIC_SPEED = 20.0  # validity.dynamic.VELOCITY_LIMIT: the fastest valid dynamic state
OVERLAP_DEPTH = 0.0095  # deepest start overlap: inside the dynamic level's tolerance (0.01)
# and the scene reader's start check (0.01), with room for its coarser discs
HALTON_DESIGNS = 128
_TRIES = 30
COMPOSITE_BASE = 10_000_000
"""Case indices from here on are composite-part cases (``partfeeder stress``'s most cases is
below it): case ``COMPOSITE_BASE + j`` is composite case ``j``."""


RAMP_FOOT_BASE = 20_000_000
"""Case indices from here on are ramp-foot cases (issue 35): case ``RAMP_FOOT_BASE + j`` is
ramp-foot case ``j`` (:func:`ramp_foot_case`)."""
RAMP_FOOT_PLACEMENTS = ("ramp", "wall")
RAMP_SPEED = (2.0, 20.0)  # length/s down a ramp (issue 35)
WALL_SPEED = (14.0, 17.0)  # length/s down a wall the corner is already inside
FOOT_HEIGHT = (0.002, 0.05)  # the corner's height above the foot (length)
WALL_INSIDE = (1e-7, 1e-6)  # how far the corner starts inside the wall (length)
RAMP_FOOT_STEPS = 4000  # most steps of a ramp-foot run: it needs only to reach the foot


def composite_index(j: int) -> int:
    """The case index of composite case ``j``."""
    return COMPOSITE_BASE + j


def ramp_foot_index(j: int) -> int:
    """The case index of ramp-foot case ``j``."""
    return RAMP_FOOT_BASE + j


def _log_uniform(rng: np.random.Generator, low: float, high: float) -> float:
    return float(10.0 ** rng.uniform(math.log10(low), math.log10(high)))


def _part(rng: np.random.Generator, family: str) -> dict[str, float]:
    mass = _log_uniform(rng, 1e-3, 1e3)
    heavy = float(rng.uniform(0.5, 1.0))
    if family == "feeder":
        return {"length": 1.6, "width": 1.0, "mass": mass, "heavy_fraction": heavy}
    length = float(rng.uniform(0.5, 2.5))
    width = float(rng.uniform(0.2, 0.9) * length)
    return {"length": length, "width": width, "mass": mass, "heavy_fraction": heavy}


def _peg(spec: dict[str, float]) -> Peg:
    return Peg.two_density(**spec)


def _feeder_scene(rng: np.random.Generator, seed: int, env: dict[str, Any]) -> dict[str, Any]:
    """A feeder document for one of the first Halton designs of ``seed`` that builds."""
    k = int(rng.integers(HALTON_DESIGNS))
    designs = halton_designs(HALTON_DESIGNS, seed)
    for j in range(HALTON_DESIGNS):
        doc = {"feeder": {"design": designs[(k + j) % HALTON_DESIGNS].to_dict()}, **env}
        try:
            scene_from_dict(doc)
        except SceneError:
            continue  # a degenerate design: take the next one
        return doc
    raise RuntimeError(f"no Halton design of seed {seed} builds a feeder")


def _anchor(rng: np.random.Generator, solid: Solid, draw: Obstacles, corner: bool):
    """A point on the solid's boundary and its outward normal: one of the family's own anchors
    half of the time, else a random edge (its start vertex for a corner contact)."""
    if draw.anchors and rng.uniform() < 0.5:
        anchor = draw.anchors[int(rng.integers(len(draw.anchors)))]
        return np.array(anchor[0], dtype=float), np.array(anchor[1], dtype=float)
    edges = boundary_anchors(solid)
    i = int(rng.integers(len(edges)))
    a, b, normal = edges[i]
    if corner:
        bisector = normal + edges[i - 1][2]
        size = math.hypot(*bisector)
        return a, (bisector / size if size > 1e-9 else normal)
    return a + rng.uniform() * (b - a), normal


def _centre_in(solid: Solid, shape: PartShape, pose: Pose) -> bool:
    """The part's anchor (:attr:`PartShape.anchor`: the centre of mass, unless that is outside
    the part) inside the solid: a slide that ended through a wall, not at it."""
    x, y = placed_points(shape.anchor[None, :], np.array([pose], dtype=float))[0, 0]
    return bool(shapely.contains_xy(solid.union, x, y))


def _target(rng: np.random.Generator, placement: str) -> float:
    if placement == "overlap":
        return -float(rng.uniform(0.0, OVERLAP_DEPTH))
    if placement == "near":
        return _log_uniform(rng, 1e-6, 0.03)
    return 0.0 if rng.uniform() < 0.3 else _log_uniform(rng, 1e-9, 1e-3)


def _contact_pose(rng, solid, draw, shape: PartShape, placement, bounds):
    """A pose of ``placement`` (near, flush, corner, overlap, pin) and the normal it faces,
    or None after a few failed draws."""
    peg = isinstance(shape.part, Peg)
    size = part_extent(shape.part)
    sides = None if peg else hull_sides(shape.part)
    for _ in range(_TRIES):
        corner = placement == "corner" or (placement == "overlap" and rng.uniform() < 0.5)
        point, normal = _anchor(rng, solid, draw, corner)
        if placement in ("flush", "pin") or (placement == "overlap" and not corner):
            if sides is None:
                yaw = flush_yaw(normal, int(rng.integers(4)))
            else:
                yaw = side_flush_yaw(normal, float(sides[int(rng.integers(len(sides)))]))
            if rng.uniform() < 0.3:
                yaw += _log_uniform(rng, 1e-6, 1e-2) * (1 if rng.uniform() < 0.5 else -1)
        else:
            yaw = float(rng.uniform(-math.pi, math.pi))
        start = touching_pose(shape, point, normal, yaw)
        if placement in ("flush", "pin"):  # the contact anywhere along the side
            shift = (rng.uniform() - 0.5) * size * np.array([-normal[1], normal[0]])
            start = (start[0] + shift[0], start[1] + shift[1], yaw)
        target = _target(rng, placement)
        pose = slide_to(solid, shape, start, normal, target)
        if pose is not None and in_bounds(pose, bounds) and not _centre_in(solid, shape, pose):
            return pose, normal
    return None


def _wedged(rng, draw: Obstacles, width: float, peg: Peg, level: str):
    """The pose wedged across the chute ``width`` wide (touching both walls; for the dynamic
    level up to 0.0095 into both) and the normal of one wall."""
    assert draw.wedge is not None
    depth = float(rng.uniform(0.0, OVERLAP_DEPTH)) if level == "dynamic" else 0.0
    gap = 0.0 if level == "dynamic" else _log_uniform(rng, 1e-9, 1e-4)
    phi = wedge_yaw(peg, width + 2.0 * depth - 2.0 * gap)
    assert phi is not None
    cx, cy, angle = draw.wedge
    along = rng.uniform(-1.0, 1.0)
    yaw = angle + (phi if rng.uniform() < 0.5 else -phi) + (math.pi if rng.uniform() < 0.5 else 0)
    # phi turns the long axis off the chute's axis; the centre of mass is off the middle
    middle = np.array([cx, cy]) + along * np.array([math.cos(angle), math.sin(angle)])
    offset = peg.com_offset * np.array([math.cos(yaw), math.sin(yaw)])
    pose = (float(middle[0] + offset[0]), float(middle[1] + offset[1]), float(yaw))
    return pose, np.array([-math.sin(angle), math.cos(angle)])


def _wedged_any(rng, draw: Obstacles, width: float, shape: PartShape, level: str):
    """A composite part's :func:`_wedged`: turned so that its width across the chute (its
    outline projected on the chute's normal, :func:`wedge_angle`) is the chute's (plus twice
    the overlap, for the dynamic level), centred across it; None when no yaw spans it."""
    assert draw.wedge is not None
    depth = float(rng.uniform(0.0, OVERLAP_DEPTH)) if level == "dynamic" else 0.0
    gap = 0.0 if level == "dynamic" else _log_uniform(rng, 1e-9, 1e-4)
    body_angle = wedge_angle(shape, width + 2.0 * depth - 2.0 * gap)
    if body_angle is None:
        return None
    cx, cy, angle = draw.wedge
    normal = np.array([-math.sin(angle), math.cos(angle)])
    yaw = angle + 0.5 * math.pi - body_angle + (math.pi if rng.uniform() < 0.5 else 0.0)
    along = rng.uniform(-1.0, 1.0)
    middle = np.array([cx, cy]) + along * np.array([math.cos(angle), math.sin(angle)])
    across = placed_points(shape.outline, np.array([[0.0, 0.0, yaw]]))[0] @ normal
    centre = middle - 0.5 * (across.max() + across.min()) * normal
    return (float(centre[0]), float(centre[1]), float(yaw)), normal


def _velocity(rng, level: str, toward: np.ndarray, mass: float, size: float, placement: str):
    """``(state velocity, control, inputs)`` for the level; ``mass`` and ``size`` (the part's
    extent) set the wrench's range."""
    if rng.uniform() < 0.6:
        direction = toward
    else:
        angle = rng.uniform(-math.pi, math.pi)
        direction = np.array([math.cos(angle), math.sin(angle)])
    weight = mass * 9.81
    still = placement in ("drop", "issue_drop")  # released at rest, no input but gravity
    if level == "dynamic":
        force, torque = min(1e3, 2.0 * weight), min(1e3, weight * size)
        inputs = {"max_force": force, "max_torque": torque}
        velocity = [0.0, 0.0, 0.0]
        if not still and rng.uniform() < 0.7:
            v = _log_uniform(rng, 1e-3, DYNAMIC_SPEED) * direction
            velocity = [float(v[0]), float(v[1]), float(DYNAMIC_SPEED * rng.uniform(-1, 1) ** 3)]
        wrench = [0.0, 0.0, 0.0]
        if not still and rng.uniform() < 0.4:
            wrench = [float(force * rng.uniform(-1, 1)), float(force * rng.uniform(-1, 1))]
            wrench.append(float(torque * rng.uniform(-1, 1)))
        return velocity, wrench, inputs
    speed, turn = _log_uniform(rng, 0.1, 1e3), _log_uniform(rng, 0.1, 1e2)
    inputs = {"max_speed": speed, "max_turn": turn}
    if still:
        direction = np.array([0.0, -1.0])
    v = np.clip(rng.uniform(0.1, 1.0) * speed * direction, -speed, speed)
    omega = float(turn * rng.uniform(-1, 1)) if rng.uniform() < 0.5 else 0.0
    control = [float(v[0]), float(v[1]), omega]
    return list(control), control, inputs


def generate_case(
    seed: int, index: int, levels: tuple[str, ...], step: float | None = None
) -> Case:
    """Case ``index`` of ``seed`` (see the module docstring): a peg case, a composite-part
    case from :data:`COMPOSITE_BASE` on, a ramp-foot case from :data:`RAMP_FOOT_BASE` on.
    ``step``: run it at that h instead of its own (the same number of steps; every other draw
    unchanged)."""
    if index >= RAMP_FOOT_BASE:
        return ramp_foot_case(seed, index - RAMP_FOOT_BASE, levels, step)
    case = _generate_case(seed, index, levels)
    if step is None:
        return case
    return dataclasses.replace(case, h=float(step), duration=case.duration / case.h * step)


def _generate_case(seed: int, index: int, levels: tuple[str, ...]) -> Case:
    rng = np.random.default_rng([seed, index])
    composite = index >= COMPOSITE_BASE
    deal = index - COMPOSITE_BASE if composite else index
    level = levels[deal % len(levels)]
    family = FAMILIES[(deal // len(levels)) % len(FAMILIES)]
    kind = KINDS[(deal // (len(levels) * len(FAMILIES))) % len(KINDS)] if composite else "peg"
    if composite:
        mass = _log_uniform(rng, 1e-3, 1e3)
        part: dict[str, Any] = draw_part(rng, kind, family, mass)
    else:
        part = _part(rng, family)
        mass = part["mass"]
    env: dict[str, Any] = {
        "part": part,
        "friction": 0.0 if rng.uniform() < 0.2 else float(rng.uniform(0.0, 2.0)),
        "restitution": float(rng.uniform(0.0, 1.0)),
    }
    h = _log_uniform(rng, 1e-5, 1e-1)
    duration = h * int(_log_uniform(rng, 10, 1000))
    choices = ["free", "near", "flush", "corner"] + (["overlap"] if level == "dynamic" else [])
    issue_drop = False
    if family == "feeder":
        doc = _feeder_scene(rng, seed, {**env, "part": FEEDER_STAND_IN} if composite else env)
        scene = scene_from_dict(doc)
        solid, bounds = Solid.of(scene), scene.bounds
        draw = Obstacles([])
        if composite:
            doc["part"] = part
        else:
            choices.append("entry")
    else:
        draw = FREE_FORM[family](rng)
        bounds = BOUNDS
        special = {"chute": "wedged", "pin": "pin", "post_on_floor": "drop"}.get(family)
        if special:
            choices += [special] * len(choices)  # half of the draws
        issue_drop = not composite and family == "post_on_floor" and draw.polygons[1] == ISSUE_POST
    placement = str(rng.choice(choices))
    if family == "chute":
        if placement != "wedged":
            placement = "wedged" if rng.uniform() < 0.5 else placement
    shape = PartShape.of(read_part(part) if composite else _peg(part))
    size = part_extent(shape.part)
    toward = np.array([0.0, -1.0])
    pose = None
    if family == "chute":  # narrower than the part is long: it cannot turn round in it
        if composite:
            narrow, _, wide, _ = span_range(shape)
            width = narrow + rng.uniform(0.05, 0.95) * (wide - narrow)
        else:
            peg = _peg(part)
            width = peg.width + rng.uniform(0.05, 0.95) * (peg.length - peg.width)
        draw = scale_chute(draw, width)
        if placement == "wedged":
            if composite:
                found = _wedged_any(rng, draw, width, shape, level)
                if found is not None:
                    pose, toward = found
            else:
                pose, toward = _wedged(rng, draw, width, _peg(part), level)
    if family != "feeder":
        solid = Solid.of_union(union_of(draw.polygons, draw.circles))
    if placement == "entry":
        pose = doc_scene_start(scene, rng)
    elif placement == "drop":
        if issue_drop and rng.uniform() < 0.5:
            # the issue's drop exactly: it fell through the floor
            part.update(length=1.0, width=0.5, mass=1.0, heavy_fraction=0.5)
            shape = PartShape.of(_peg(part))
            pose, h, duration = (3.0, 1.0, 0.0), 1e-3, 1.5
            placement = "issue_drop"
        else:
            pose = free_pose(rng, solid, shape, (-4.5, 4.5, 0.6, 3.5), 0.05)
            if pose is not None and rng.uniform() < 0.5:
                pose = (
                    (pose[0], pose[1], 0.0)
                    if signed_distance(solid, shape, (pose[0], pose[1], 0.0)) > 0.05
                    else pose
                )
    elif placement in ("near", "flush", "corner", "overlap", "pin"):
        found = _contact_pose(rng, solid, draw, shape, placement, bounds)
        if found is not None:
            pose, toward = found
            toward = -toward
    if pose is None:
        placement = "free"
        pose = free_pose(rng, solid, shape, bounds, 0.05)
        if pose is None:
            raise RuntimeError(f"case {index} of seed {seed}: no free pose in {family}")
    # plain floats (YAML-ready), the yaw within the scene reader's range
    pose = (float(pose[0]), float(pose[1]), wrap_angle(float(pose[2])))
    velocity, control, inputs = _velocity(rng, level, toward, shape.part.mass, size, placement)
    env["inputs"] = inputs
    if family == "feeder":
        doc["inputs"] = inputs
    else:
        doc = {
            "name": f"stress {seed}-{index} {family}",
            "obstacles": draw.document(),
            "bounds": list(bounds),
            "starts": {"case": list(pose)},
            "goal": _goal_around(pose, bounds, solid),
            **env,
        }
    inertia = shape.part.inertia if composite else _peg(part).inertia
    if placement != "issue_drop" and rng.uniform() < 0.5:
        inertia *= _log_uniform(rng, 0.1, 10.0)
    state = tuple(pose) if level == "geometric" else (*pose, *velocity)
    return Case(
        seed=seed,
        index=index,
        level=level,
        family=f"{family}+{kind}" if composite else family,
        placement=placement,
        scene=doc,
        state=tuple(float(v) for v in state),
        control=(float(control[0]), float(control[1]), float(control[2])),
        h=float(h),
        duration=float(duration),
        mass=float(part["mass"]) if not composite else float(mass),
        inertia=float(inertia),
        friction=float(env["friction"]),
    )


def doc_scene_start(scene, rng: np.random.Generator) -> tuple[float, float, float]:
    """One of a feeder's entry poses."""
    return tuple(scene.starts[ORIENTATIONS[int(rng.integers(len(ORIENTATIONS)))]])


def _goal_around(pose, bounds, solid: Solid | None = None) -> dict[str, Any]:
    """A small goal box around the start, inside the bounds (the stress runs ignore goals);
    the whole bounds when that box lies inside the ``solid`` (a cup hooked on a pin wider
    than the box has its centre of mass over the pin: the scene reader refuses a goal no part
    can reach, seed 42's composite case 106)."""
    x0 = min(max(pose[0] - 0.1, bounds[0]), bounds[1] - 0.2)
    y0 = min(max(pose[1] - 0.1, bounds[2]), bounds[3] - 0.2)
    box = shapely.box(x0, y0, x0 + 0.2, y0 + 0.2)
    if solid is not None and box.difference(solid.union).area <= 1e-12:
        x0, y0 = bounds[0], bounds[2]
        return {"x": [x0, bounds[1]], "y": [y0, bounds[3]], "yaw": 0.0, "yaw_tol": math.pi}
    return {"x": [x0, x0 + 0.2], "y": [y0, y0 + 0.2], "yaw": 0.0, "yaw_tol": math.pi}


def ramp_foot_case(seed: int, j: int, levels: tuple[str, ...], step: float | None = None) -> Case:
    """Ramp-foot case ``j`` of ``seed`` (issue 35), at level ``j mod L``: a peg's corner on a
    40-75 degree ramp standing on the floor (placement ``ramp``: touching it or up to 1e-3
    above it, sliding down at 2-20 length/s) or on an upright wall it is already 1e-7 to 1e-6
    inside (``wall``: 14-17 length/s), 0.002-0.05 above the foot, where the face meets the
    floor in a concave corner; the part's other corners are at least half as high, so the
    corner reaches the foot, and the floor, in the run, first or nearly (on a wall the part
    stands along it, tilted by up to 1e-2 rad). The placements alternate every L cases.
    Gravity is the only input; h is drawn as the other cases' (or ``step``) and the run lasts
    three times the time to the foot (at least 50 steps, at most :data:`RAMP_FOOT_STEPS`)."""
    rng = np.random.default_rng([seed, RAMP_FOOT_BASE + j])
    level = levels[j % len(levels)]
    placement = RAMP_FOOT_PLACEMENTS[(j // len(levels)) % len(RAMP_FOOT_PLACEMENTS)]
    wall = placement == "wall"
    part = _part(rng, "ramp_foot")
    shape = PartShape.of(_peg(part))
    friction = 0.0 if rng.uniform() < 0.2 else float(rng.uniform(0.0, 1.0))
    restitution = float(rng.uniform(0.0, 1.0))
    h = _log_uniform(rng, 1e-5, 1e-1)
    h = h if step is None else float(step)  # drawn either way: the later draws stay the same
    for _ in range(_TRIES):
        draw = ramp_foot(rng, wall)
        height = _log_uniform(rng, *FOOT_HEIGHT)
        along = height / -draw.down[1]  # from the foot up the face
        point = np.array([draw.foot, 0.0]) - along * draw.down
        target = -_log_uniform(rng, *WALL_INSIDE) if wall else _target(rng, "flush")
        pose = _leading_corner_pose(rng, draw, shape, point, height, target)
        if pose is not None:
            break
    else:
        raise RuntimeError(f"ramp-foot case {j} of seed {seed}: no pose with a leading corner")
    speed = float(rng.uniform(*(WALL_SPEED if wall else RAMP_SPEED)))
    velocity = speed * draw.down
    reach = along / speed
    duration = h * min(max(math.ceil(3.0 * reach / h), 50), RAMP_FOOT_STEPS)
    mass = part["mass"]
    if level == "dynamic":
        inputs = {"max_force": min(1e3, 2.0 * mass * 9.81), "max_torque": min(1e3, mass * 9.81)}
        control = (0.0, 0.0, 0.0)
    else:
        inputs = {"max_speed": speed, "max_turn": 1.0}
        control = (float(velocity[0]), float(velocity[1]), 0.0)
    doc = {
        "name": f"stress {seed}-{RAMP_FOOT_BASE + j} ramp_foot",
        "obstacles": draw.obstacles.document(),
        "bounds": list(BOUNDS),
        "starts": {"case": list(pose)},
        "goal": _goal_around(pose, BOUNDS),
        "part": part,
        "friction": friction,
        "restitution": restitution,
        "inputs": inputs,
    }
    inertia = _peg(part).inertia
    if rng.uniform() < 0.5:
        inertia *= _log_uniform(rng, 0.1, 10.0)
    state = pose if level == "geometric" else (*pose, float(velocity[0]), float(velocity[1]), 0.0)
    return Case(
        seed=seed,
        index=RAMP_FOOT_BASE + j,
        level=level,
        family="ramp_foot",
        placement=placement,
        scene=doc,
        state=tuple(float(v) for v in state),
        control=control,
        h=float(h),
        duration=float(duration),
        mass=float(mass),
        inertia=float(inertia),
        friction=friction,
    )


def _leading_corner_pose(rng, draw, shape: PartShape, point, height: float, target: float):
    """A pose (x, y, yaw) whose corner nearest the face is at ``point`` (``height`` above the
    floor), ``target`` from the face's piece along its normal (a gap > 0 or an overlap < 0),
    clear of the floor, every other corner at least half as high: any yaw on a ramp; on a
    wall a side along it, tilted by 1e-6 to 1e-2 rad (a rectangle's corner is the nearest to
    an upright wall only so); None after a few failed yaws."""
    floor = shapely.Polygon(draw.obstacles.polygons[0])
    solid = Solid.of_union(union_of([draw.obstacles.polygons[1]], []))  # the face's piece
    wall = abs(draw.normal[1]) < 1e-9
    for _ in range(_TRIES):
        if wall:
            tilt = _log_uniform(rng, 1e-6, 1e-2) * (1.0 if rng.uniform() < 0.5 else -1.0)
            yaw = flush_yaw(draw.normal, int(rng.integers(4))) + tilt
        else:
            yaw = float(rng.uniform(-math.pi, math.pi))
        start = touching_pose(shape, point, draw.normal, yaw)
        corners = placed_points(shape.outline, np.array([start]))[0]
        nearest = int(np.argmin(corners @ draw.normal))
        if np.delete(corners[:, 1], nearest).min() < 0.5 * height:
            continue
        pose = slide_to(solid, shape, start, draw.normal, target)
        if pose is None or not in_bounds(pose, BOUNDS):
            continue
        if shape.placed(np.array([pose]))[0].distance(floor) > 0.0:
            return (float(pose[0]), float(pose[1]), wrap_angle(float(pose[2])))
    return None
