"""The room every feeder made to tolerance can give the part: a sound outer bound (issue 21).

The verdict judges feeders *as made*: each of the 12 design parameters times a factor in
``[1 - t, 1 + t]`` (``experiments.drop.perturbations.toleranced``, clamped to
``feeders.design.PHYSICAL_BOUNDS``), the part entering up to ``position`` off the made start
and ``yaw`` off its yaw. A necessary condition that is to hold for every made feeder is tested
against a region that contains the free space of all of them; this module builds it.

The free interior (``feeders.feeder.interior_edges``) is written here as one fixed list of 14
vertices whose positions are continuous functions of the design (the branches of the chamfer,
lip and left wall become ``min``/``max``: repeated vertices where a branch has fewer), so the
nominal and any made outline are the same closed curve moved vertex by vertex. Interval
arithmetic over the tolerance box bounds each vertex's displacement ``delta_i``. Moving a
closed curve along straight lines never sweeps a point farther than ``max(delta_i,
delta_{i+1})`` from segment ``i`` (a point's winding number changes only when the curve
crosses it), so every made interior lies inside the nominal interior united with capsules of
those radii round its segments. The protuberance only shrinks: every made finger contains the
intersection box of all made fingers, every made tip disc the nominal disc shrunk by the
largest move of its centre and radius. A further ``slack`` (the overlap the dynamic model
allows between part and wall) widens capsules and shrinks the pin alike.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from feeders.design import PARAMETER_NAMES, PHYSICAL_BOUNDS, DesignParameters
from feeders.feeder import START_CLEARANCE, WALL_THICKNESS
from feeders.part import Peg

Interval = tuple[float, float]
VERTICES = 14  # the fixed outline: see :func:`outline_intervals`


@dataclass(frozen=True)
class MadeEnvelope:
    """An outer bound of the free space of every feeder made to ``tolerance``, as arrays.

    ``outline (14, 2)``: the nominal free interior (CCW, with repeated vertices);
    ``capsules (14,)``: the radius round segment ``i`` (vertex ``i`` to ``i + 1``) that every
    made wall stays within, ``slack`` included; ``finger (4,)``: (xmin, ymin, xmax, ymax) of a
    box inside every made finger (empty when xmin >= xmax or ymin >= ymax); ``tip (3,)``: a
    disc (x, y, r) inside every made tip (r <= 0: none); ``entry (3,)``: (x, y, radius) of a disc
    holding the part's geometric centre at every perturbed entry; ``entry_yaw (2,)``: the
    heavy-trailing entry's yaw range (rad; heavy leading: plus pi).
    """

    outline: np.ndarray
    capsules: np.ndarray
    finger: np.ndarray
    tip: np.ndarray
    entry: np.ndarray
    entry_yaw: np.ndarray


def parameter_intervals(design: DesignParameters, tolerance: float) -> dict[str, Interval]:
    """Each parameter's range over the made feeders: value times ``[1 - t, 1 + t]``, clamped
    to its physical bounds as the verdict's made feeders are."""
    out = {}
    for name in PARAMETER_NAMES:
        value = getattr(design, name)
        low, high = sorted((value * (1.0 - tolerance), value * (1.0 + tolerance)))
        lo_bound, hi_bound = PHYSICAL_BOUNDS[name]
        out[name] = (min(hi_bound, max(lo_bound, low)), min(hi_bound, max(lo_bound, high)))
    return out


def _add(p: Interval, q: Interval) -> Interval:
    return (p[0] + q[0], p[1] + q[1])


def _neg(p: Interval) -> Interval:
    return (-p[1], -p[0])


def _mul(p: Interval, q: Interval) -> Interval:
    products = (p[0] * q[0], p[0] * q[1], p[1] * q[0], p[1] * q[1])
    return (min(products), max(products))


def _scale(k: float, p: Interval) -> Interval:
    return _mul((k, k), p)


def _min(p: Interval, q: Interval) -> Interval:
    return (min(p[0], q[0]), min(p[1], q[1]))


def _max(p: Interval, q: Interval) -> Interval:
    return (max(p[0], q[0]), max(p[1], q[1]))


def _const(x: float) -> Interval:
    return (x, x)


def outline_intervals(
    box: dict[str, Interval], part: Peg, roof_rise: float
) -> list[tuple[Interval, Interval]]:
    """The 14 outline vertices (x and y ranges) over the design box ``box``.

    Order (CCW): exit chute bottom left, bottom right, top right; right chamfer end; foot of
    the wall below the lip; lip g; input chute top floor, top ceiling, lip ceiling; roof's
    right end; left wall top; left wall foot; left chamfer end; exit chute top left. With a
    degenerate box (every interval one point) this is the nominal outline.
    """
    half_b = _scale(0.5, box["b"])
    c, e, gx, gy, a, d = (box[k] for k in ("c", "e", "gx", "gy", "a", "d"))
    theta, alpha = box["theta"], box["alpha"]
    # theta in [0, pi/2 - 0.01], alpha in [0.05, pi/2]: sin, tan rise and cos falls there
    sin_t, cos_t = (
        (math.sin(theta[0]), math.sin(theta[1])),
        (math.cos(theta[1]), math.cos(theta[0])),
    )
    tan_a = (math.tan(alpha[0]), math.tan(alpha[1]))
    cot_a = (1.0 / tan_a[1], 1.0 / tan_a[0])
    mouth = _add(half_b, _mul(c, cot_a))
    depth = _const(-2.0 * part.length)
    zero = _const(0.0)
    right = _max(gx, half_b)  # x of the wall below the lip (b/2 when the lip overhangs)
    right_y = _min(_mul(tan_a, _max(_add(gx, _neg(half_b)), zero)), c)
    left_y = _min(_mul(tan_a, _max(_add(_neg(e), _neg(half_b)), zero)), c)
    u = (cos_t, sin_t)
    n = (_neg(sin_t), cos_t)
    top_floor = (_add(gx, _mul(d, u[0])), _add(gy, _mul(d, u[1])))
    top_ceiling = (_add(top_floor[0], _mul(a, n[0])), _add(top_floor[1], _mul(a, n[1])))
    lip_ceiling = (_add(gx, _mul(a, n[0])), _add(gy, _mul(a, n[1])))
    roof_y = _add(lip_ceiling[1], _const(roof_rise))
    return [
        (_neg(half_b), depth),
        (half_b, depth),
        (half_b, zero),
        (_min(right, mouth), right_y),
        (right, right_y),
        (gx, gy),
        top_floor,
        top_ceiling,
        lip_ceiling,
        (lip_ceiling[0], roof_y),
        (e, roof_y),
        (e, left_y),
        (_max(e, _neg(mouth)), left_y),
        (_neg(half_b), zero),
    ]


def start_interval(box: dict[str, Interval], part: Peg) -> tuple[Interval, Interval]:
    """The geometric centre of the part at the (unperturbed) start, over the design box:
    ``g + (d - L/2 - START_CLEARANCE) u + (a/2) n`` as in ``feeders.feeder.build_feeder``."""
    theta = box["theta"]
    sin_t, cos_t = (
        (math.sin(theta[0]), math.sin(theta[1])),
        (math.cos(theta[1]), math.cos(theta[0])),
    )
    along = _add(box["d"], _const(-part.length / 2 - START_CLEARANCE))
    across = _scale(0.5, box["a"])
    x = _add(_add(box["gx"], _mul(along, cos_t)), _mul(across, _neg(sin_t)))
    y = _add(_add(box["gy"], _mul(along, sin_t)), _mul(across, cos_t))
    return x, y


def _farthest(nominal: tuple[float, float], xs: Interval, ys: Interval) -> float:
    """The largest distance from ``nominal`` to a point of the box ``xs x ys``."""
    dx = max(abs(xs[0] - nominal[0]), abs(xs[1] - nominal[0]))
    dy = max(abs(ys[0] - nominal[1]), abs(ys[1] - nominal[1]))
    return math.hypot(dx, dy)


def roof_rise_of(design: DesignParameters, outline: np.ndarray) -> float:
    """The roof's rise above the input chute's upper wall in a built feeder's ``outline``
    (``build_feeder``'s ``roof_rise``): the top of the left cavity wall, ``x = e``."""
    on_left = np.abs(outline[:, 0] - design.e) < 1e-9
    if not np.any(on_left):
        raise ValueError("scene.outline has no vertex on the left cavity wall (x = e)")
    roof_y = float(outline[on_left, 1].max())
    lip_ceiling_y = design.gy + design.a * math.cos(design.theta)
    return max(0.0, roof_y - lip_ceiling_y)


def made_envelope(
    design: DesignParameters,
    part: Peg,
    tolerance: float,
    position: float,
    yaw: float,
    slack: float,
    roof_rise: float = 0.0,
) -> MadeEnvelope:
    """The outer bound of every made feeder's free space (see the module) and the entry
    region: the start's geometric centre over the box, plus an entry offset of up to
    ``position`` in x and y and a yaw offset of up to ``yaw`` (moving the geometric centre by
    at most ``com_offset * yaw``, the centre of mass being the pose's origin)."""
    box = parameter_intervals(design, tolerance)
    point = {k: _const(getattr(design, k)) for k in PARAMETER_NAMES}
    nominal = [(x[0], y[0]) for x, y in outline_intervals(point, part, roof_rise)]
    ranges = outline_intervals(box, part, roof_rise)
    moves = np.array([_farthest(v, xs, ys) for v, (xs, ys) in zip(nominal, ranges, strict=True)])
    capsules = np.maximum(moves, np.roll(moves, -1)) + slack
    root = _add(box["e"], _const(-WALL_THICKNESS))
    low_edge = _add(box["fy"], _neg(box["r"]))
    high_edge = _add(box["fy"], box["r"])
    finger = np.array(
        [root[1] + slack, low_edge[1] + slack, box["fx"][0] - slack, high_edge[0] - slack]
    )
    centre_move = _farthest((design.fx, design.fy), box["fx"], box["fy"])
    tip = np.array([design.fx, design.fy, box["r"][0] - centre_move - slack])
    start_nominal = start_interval(point, part)
    start_box = start_interval(box, part)
    centre = (start_nominal[0][0], start_nominal[1][0])
    spread = _farthest(centre, *start_box) + math.sqrt(2.0) * position + part.com_offset * yaw
    theta = box["theta"]
    return MadeEnvelope(
        outline=np.array(nominal, dtype=np.float64),
        capsules=capsules.astype(np.float64),
        finger=finger,
        tip=tip,
        entry=np.array([centre[0], centre[1], spread]),
        entry_yaw=np.array([theta[0] - yaw, theta[1] + yaw]),
    )
