"""The analytic scenes and their closed forms: the numbers the benchmark measures errors
against, checked by hand arithmetic and by shapely (independent of the simulators)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from experiments.bench.analytic import CASES, case
from experiments.bench.closed_forms import ballistic_state, incline_displacement, landing_time


def test_near_threshold_displacement_is_the_issues_number():
    # 1/2 g (sin 30 - mu cos 30) t^2 with g = 9.81, mu = 0.55, t = 1, by hand:
    # 4.905 * (0.5 - 0.55 * 0.8660254038) = 4.905 * 0.0236860279 = 0.116180
    s = incline_displacement(0.55, math.radians(30.0), 9.81, 1.0)
    assert s == pytest.approx(0.116180, abs=5e-7)


def test_sliding_and_sticking_displacements():
    phi = math.radians(30.0)
    assert incline_displacement(0.3, phi, 9.81, 1.0) == pytest.approx(1.178144, abs=5e-7)
    assert incline_displacement(0.7, phi, 9.81, 10.0) == 0.0  # mu > tan 30: sticks
    assert incline_displacement(math.tan(phi) + 1e-9, phi, 9.81, 1.0) == 0.0


def test_ballistic_and_landing():
    end = ballistic_state((0.0, 0.0, 0.0, 2.0, 5.0, 3.0), (0.0, -9.81), 1.0)
    np.testing.assert_allclose(end, [2.0, 5.0 - 4.905, 3.0, 2.0, 5.0 - 9.81, 3.0])
    assert landing_time(1.0, 9.81) == pytest.approx(0.451524, abs=5e-7)
    with pytest.raises(ValueError, match="gap"):
        landing_time(-1.0, 9.81)


@pytest.mark.parametrize("name", ["slide", "threshold", "stick"])
def test_incline_scenes_are_30_degrees_with_the_box_resting_on_the_face(name):
    c = case(name)
    scene = c.scene
    assert scene.friction == {"slide": 0.3, "threshold": 0.55, "stick": 0.7}[name]
    slab = shapely.Polygon(scene.obstacles.polygons[0])
    if len(scene.obstacles.polygons) > 1:  # convex pieces of one rectangle
        slab = shapely.union_all([shapely.Polygon(p) for p in scene.obstacles.polygons])
    x, y, yaw = c.start[:3]
    assert yaw == pytest.approx(-math.radians(30.0), abs=1e-15)
    corners = scene.part.body_vertices() @ np.array(
        [[math.cos(yaw), math.sin(yaw)], [-math.sin(yaw), math.cos(yaw)]]
    ) + np.array([x, y])
    box = shapely.Polygon(corners)
    assert box.distance(slab) == pytest.approx(0.0, abs=1e-12)
    assert box.intersection(slab).area == pytest.approx(0.0, abs=1e-12)
    # the long bottom face of the box lies on the slab's top face (both corners touch)
    bottom = corners[:2]
    assert max(shapely.Point(p).distance(slab.exterior) for p in bottom) < 1e-12


def test_a_track_that_follows_the_closed_form_has_zero_error():
    # states built from the closed forms, not from any simulator
    h = 1e-2
    t = np.arange(101) * h
    slide = case("slide")
    phi = math.radians(30.0)
    s = 0.5 * 9.81 * (math.sin(phi) - 0.3 * math.cos(phi)) * t**2
    states = np.zeros((len(t), 6))
    states[:, 0] = slide.start[0] + s * math.cos(phi)
    states[:, 1] = slide.start[1] - s * math.sin(phi)
    states[:, 2] = slide.start[2]
    errors = slide.errors(states, h)
    assert errors["error"] < 1e-12
    assert errors["penetration"] < 1e-9
    flight = case("flight")
    track = np.array([ballistic_state(flight.start, (0.0, -9.81), tk) for tk in t])
    assert flight.errors(track, h)["error"] < 1e-12


def test_the_drop_measures_against_a_hand_built_track():
    drop = case("drop")
    h = 1e-3
    t = np.arange(1001) * h
    t_star = math.sqrt(2.0 / 9.81)
    y = np.where(t < t_star, 1.5 - 0.5 * 9.81 * t**2, 0.5)
    vy = np.where(t < t_star, -9.81 * t, 0.0)
    states = np.zeros((len(t), 6))
    states[:, 1], states[:, 4] = y, vy
    e = drop.errors(states, h)
    assert e["time_to_rest"] <= h  # the grid's first rest sample is within one step of t*
    assert e["energy"] < 1e-12
    assert e["penetration"] < 1e-9
    sunk = states.copy()
    sunk[-1, 1] = 0.5 - 0.01  # 0.01 into the floor at the end
    assert drop.errors(sunk, h)["penetration"] == pytest.approx(0.01, abs=1e-9)


def test_every_case_has_a_scene_and_measures():
    assert {c.name for c in CASES} == {"slide", "threshold", "stick", "flight", "drop"}
    with pytest.raises(ValueError, match="unknown case"):
        case("nope")
