"""The peer engines' models of the project's scenes: the rectangle conversion (always), and
when MuJoCo or pymunk is installed, that their free flight matches the closed form up to the
first-order error of Euler time stepping, g h T / 2 (a mis-mapped axis or sign would not)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from experiments.bench.analytic import case, steps_for
from experiments.bench.closed_forms import ballistic_state
from experiments.bench.engines import engine_settings
from experiments.bench.peers import mujoco_engine, pymunk_engine
from experiments.bench.peers.rectangles import rectangle_of


def test_rectangle_of_a_turned_rectangle():
    c, s = math.cos(0.3), math.sin(0.3)
    corners = np.array([[0, 0], [4 * c, 4 * s], [4 * c - s, 4 * s + c], [-s, c]])
    r = rectangle_of(corners)
    assert (r.half_length, r.half_width) == pytest.approx((2.0, 0.5))
    assert r.angle == pytest.approx(0.3)
    assert r.centre == pytest.approx(tuple(corners.mean(axis=0)))
    with pytest.raises(ValueError, match="not a rectangle"):
        rectangle_of(np.array([[0, 0], [2, 0], [3, 1], [0, 1]]))
    with pytest.raises(ValueError, match="corners"):
        rectangle_of(np.array([[0, 0], [1, 0], [0, 1]]))


def test_peer_settings_listed_whether_installed_or_not():
    labels = {s.label: s.available for s in engine_settings()}
    assert labels["partfeeder (default)"] is True
    assert labels["mujoco (default)"] == mujoco_engine.available()
    assert labels["pymunk (accurate)"] == pymunk_engine.available()


@pytest.mark.parametrize("engine", ["mujoco", "pymunk"])
@pytest.mark.parametrize("setting", ["default", "accurate"])
def test_peer_free_flight_is_first_order_euler(engine, setting):
    module = {"mujoco": mujoco_engine, "pymunk": pymunk_engine}[engine]
    if not module.available():
        pytest.skip(f"{engine} not installed")
    flight = case("flight")
    h = 1e-3
    sim = module.builder(setting)(flight.scene, h)
    states = sim.record(flight.start, steps_for(1.0, h))
    exact = ballistic_state(flight.start, flight.scene.gravity, 1.0)
    # Euler: y_n = exact -+ g h t / 2 (MuJoCo updates the velocity first: below the
    # parabola; Chipmunk moves the position first: above it); x and yaw exact
    assert states[-1, 0] == pytest.approx(exact[0], abs=1e-9)
    sign = {"mujoco": -1.0, "pymunk": 1.0}[engine]
    assert states[-1, 1] == pytest.approx(exact[1] + sign * 9.81 * h * 1.0 / 2.0, abs=1e-9)
    assert states[-1, 2] == pytest.approx(exact[2], abs=1e-9)


def test_mujoco_model_keeps_the_box_resting_on_the_incline():
    if not mujoco_engine.available():
        pytest.skip("mujoco not installed")
    stick = case("stick")
    sim = mujoco_engine.builder("accurate")(stick.scene, 1e-3)
    states = sim.record(stick.start, 200)
    # soft contact: it sinks and creeps a little, but stays on the face (no fall, no jump)
    assert stick.errors(states, 1e-3)["penetration"] < 1e-2
    assert abs(states[-1, 2] - stick.start[2]) < 1e-2


def test_without_peers_their_columns_say_not_installed(monkeypatch):
    from experiments.bench.summary import markdown
    from experiments.bench.work_precision import run_work_precision

    monkeypatch.setattr(mujoco_engine, "available", lambda: False)
    monkeypatch.setattr(pymunk_engine, "available", lambda: False)
    wp = run_work_precision((1e-2,), repeats=1, cases=[case("flight")], creep_duration=0.1)
    assert {p["engine"] for p in wp["cases"]["flight"]["points"]} == {"partfeeder (default)"}
    assert wp["creep"]["by_engine"]["mujoco (default)"] == "not installed"
    data = {
        "machine": {"platform": "p", "machine": "m", "cores": 2, "usable_cores": 2, "python": "3"},
        "versions": {},
        "settings": {},
        "work_precision": wp,
    }
    text = markdown(data)
    assert "mujoco (accurate) | - | not installed" in text
    assert (
        "pymunk (default): pymunk defaults (10 iterations, collision slop 0.1) — **not installed**"
        in text
    )
