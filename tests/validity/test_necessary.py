"""Necessary conditions (issue 21): a design that fails one cannot work, so a sweep may prune on
it; every design that works passes, and each test fails where its geometry says it must."""

from __future__ import annotations

import csv
import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from scipy import ndimage
from shapely.geometry import Point, Polygon, box

from experiments.drop.perturbations import Perturbations, draw, toleranced
from feeders.design import PAPER_GEOMETRIC_VERDICT, PARAMETER_NAMES, DesignParameters, preset
from feeders.feeder import DegenerateDesign, build_feeder, protuberance
from validity.made_envelope import made_envelope, roof_rise_of
from validity.necessary import necessary_conditions
from validity.necessary_kernel import corridor_flood, distance_grid, free_mask

DATA = Path(__file__).parent / "data" / "necessary_working_designs.csv"

# Halton designs (seed 0) whose verdict fails with no success from either entry
TURN_PRUNED = (
    1.132441233568603,
    1.2522521480589448,
    0.7931322181533016,
    2.648895996642878,
    -1.1304635935302867,
    -0.6668791918086148,
    1.8303843541069293,
    0.4753249236760085,
    2.160134120323746,
    0.21885308112143237,
    0.8822140549964679,
    1.0028238168563746,
)
SLICED_PRUNED = (
    1.195722483568603,
    1.1271492674005086,
    0.7635322181533015,
    3.6984586788586213,
    -1.023025577001361,
    -0.7875892509802125,
    2.4947442156986246,
    0.22601744445163183,
    2.8349923433861277,
    0.1149291810025263,
    0.40645963251988093,
    1.0698800622909985,
)


def working_designs() -> list[DesignParameters]:
    lines = [line for line in DATA.read_text().splitlines() if not line.startswith("#")]
    rows = list(csv.DictReader(lines))
    return [
        DesignParameters.from_mapping({k: float(row[k]) for k in PARAMETER_NAMES}) for row in rows
    ]


def blocked_design() -> DesignParameters:
    """table3 with a pin of radius 0.45 over the funnel's mouth: the gaps either side of it
    (about 0.33) are narrower than the peg (0.7)."""
    return dataclasses.replace(preset("table3"), fx=0.0, fy=0.6, r=0.45)


def outer_free_space(scene, tolerance: float, slack: float) -> shapely.Geometry:
    """The envelope's free space drawn with shapely: interior and capsules, minus the pin."""
    d = scene.design
    env = made_envelope(d, scene.part, tolerance, 0.05, 0.05, slack, roof_rise_of(d, scene.outline))
    ring = np.vstack([env.outline, env.outline[:1]])
    pieces = [Polygon(env.outline)] + [
        shapely.LineString(ring[k : k + 2]).buffer(env.capsules[k], quad_segs=32)
        for k in range(len(env.outline))
    ]
    outer = shapely.unary_union(pieces)
    finger = box(*env.finger) if env.finger[0] < env.finger[2] else Polygon()
    tip = Point(env.tip[:2]).buffer(max(env.tip[2], 0.0), quad_segs=32)
    return outer.difference(finger).difference(tip), outer, env


def test_working_designs_pass():
    """Soundness on 40 of the 43 working designs of the first 1000 Halton designs."""
    designs = working_designs()
    assert len(designs) == 40
    failed = [i for i, d in enumerate(designs) if not necessary_conditions(build_feeder(d)).passes]
    assert failed == []


@pytest.mark.parametrize("name", [n for n, ok in PAPER_GEOMETRIC_VERDICT.items() if ok])
def test_presets_the_paper_finds_feasible_pass(name):
    verdict = necessary_conditions(build_feeder(preset(name)))
    assert verdict.passes, verdict
    assert verdict.details["corridor"] and verdict.details["turn"] and verdict.details["sliced"]


def test_a_pin_wider_than_the_gap_blocks_the_corridor():
    scene = build_feeder(blocked_design())
    verdict = necessary_conditions(scene)
    assert (verdict.passes, verdict.failed) == (False, "corridor")
    assert verdict.details["turn"] is None  # stops at the first failure
    # a thinner pin leaves the gaps open to the disc (the peg still cannot turn round it)
    thin = build_feeder(dataclasses.replace(blocked_design(), r=0.1))
    assert necessary_conditions(thin, tests=("corridor",)).passes


def test_turn_and_sliced_fail_where_the_peg_cannot_turn():
    turn = necessary_conditions(build_feeder(DesignParameters.from_vector(TURN_PRUNED)))
    assert (turn.failed, turn.details["corridor"]) == ("turn", True)
    sliced = necessary_conditions(build_feeder(DesignParameters.from_vector(SLICED_PRUNED)))
    assert (sliced.failed, sliced.details["turn"]) == ("sliced", True)
    assert necessary_conditions(build_feeder(preset("fig7a"))).failed == "sliced"


def test_each_test_can_run_alone():
    scene = build_feeder(DesignParameters.from_vector(SLICED_PRUNED))
    assert necessary_conditions(scene, tests=("corridor",)).passes
    alone = necessary_conditions(scene, tests=("sliced",))
    assert (alone.failed, alone.details["corridor"]) == ("sliced", None)


def test_envelope_outline_is_the_built_outline():
    for name in ("table3", "fig4", "fig8a", "fig9"):
        scene = build_feeder(preset(name))
        env = made_envelope(scene.design, scene.part, 0.01, 0.05, 0.05, 0.0, 0.0)
        assert Polygon(env.outline).symmetric_difference(Polygon(scene.outline)).area < 1e-12


def test_made_feeders_lie_inside_the_envelope():
    """Every made feeder's interior inside the outer free space's walls, its pin over the
    envelope's shrunk pin, its entry inside the entry disc."""
    design = preset("table3")
    scene = build_feeder(design)
    _, outer, env = outer_free_space(scene, 0.01, 0.0)
    settings = Perturbations()
    for index in range(30):
        d = draw(settings, seed=5, index=index)
        made = build_feeder(toleranced(design, d.design_factors))
        assert Polygon(made.outline).difference(outer).area < 1e-6
        finger, tip = protuberance_shapes(made.design)
        shrunk = box(*env.finger).union(Point(env.tip[:2]).buffer(env.tip[2], quad_segs=8))
        assert shrunk.difference(finger.union(tip)).area < 1e-9
        centre = np.mean(made.part.body_vertices(), axis=0)  # geometric centre, body frame
        x, y, yaw = made.start("heavy_trailing")
        cx = x + math.cos(yaw) * centre[0] - math.sin(yaw) * centre[1]
        cy = y + math.sin(yaw) * centre[0] + math.cos(yaw) * centre[1]
        assert math.hypot(cx - env.entry[0], cy - env.entry[1]) <= env.entry[2]
        assert env.entry_yaw[0] <= yaw <= env.entry_yaw[1]


def protuberance_shapes(design: DesignParameters) -> tuple[Polygon, shapely.Geometry]:
    finger, tip = protuberance(design)
    return Polygon(finger), Point(tip[:2]).buffer(tip[2], quad_segs=64)


@pytest.mark.parametrize("name", ["table3", "fig6a", "blocked"])
def test_grid_and_corridor_agree_with_shapely(name):
    """The compiled free grid holds every point shapely's free space does, and the corridor
    flood passes when shapely's eroded free space joins the entry to the goal."""
    design = blocked_design() if name == "blocked" else preset(name)
    scene = build_feeder(design)
    room, _, env = outer_free_space(scene, 0.01, 0.01)
    h = 0.04
    low, high = env.outline.min(axis=0) - 0.5, env.outline.max(axis=0) + 0.5
    nx, ny = (math.ceil(v) + 1 for v in (high - low) / h)
    grid = free_mask(env.outline, env.capsules, env.finger, env.tip, low[0], low[1], h, nx, ny)
    xs, ys = np.meshgrid(low[0] + h * np.arange(nx), low[1] + h * np.arange(ny), indexing="ij")
    inside = shapely.contains_xy(room, xs, ys)
    assert not np.any(inside & ~grid)  # shapely's arcs are inscribed: the grid may hold more
    assert np.mean(grid & ~inside) < 0.01

    radius = scene.part.width / 2
    y_goal = scene.goal.y_max + scene.part.com_offset
    eroded = room.buffer(-radius, quad_segs=32)
    entry = Point(env.entry[:2]).buffer(env.entry[2])
    parts = getattr(eroded, "geoms", [eroded])
    joined = any(p.intersects(entry) and p.bounds[1] <= y_goal for p in parts)
    found, _ = corridor_flood(distance_grid(grid, h), low[0], low[1], h, radius, env.entry, y_goal)
    assert joined == (name != "blocked")
    assert found == joined


def test_distance_grid_is_the_exact_transform():
    rng = np.random.default_rng(3)
    room = rng.random((60, 45)) > 0.02
    room[0, 0] = False
    expected = ndimage.distance_transform_edt(room) * 0.1
    assert np.allclose(distance_grid(room, 0.1), expected, atol=1e-12)


def test_perturbed_made_feeders_of_a_working_design_pass():
    design = working_designs()[0]
    settings = Perturbations()
    for index in range(10):
        factors = draw(settings, seed=11, index=index).design_factors
        try:
            made = build_feeder(toleranced(design, factors))
        except DegenerateDesign:
            continue
        assert necessary_conditions(made, tolerance=0.0).passes


def test_bad_input_names_the_field():
    scene = build_feeder(preset("table3"))
    with pytest.raises(ValueError, match=r"tolerance = 0\.5 is outside the allowed range"):
        necessary_conditions(scene, tolerance=0.5)
    with pytest.raises(ValueError, match="unknown"):
        necessary_conditions(scene, tests=("walls",))
    with pytest.raises(ValueError, match="design"):
        necessary_conditions(dataclasses.replace(scene, design=None))
