"""The agreement suite (``partfeeder bench --agreement``) as a specification.

The peers must model what partfeeder models, or their disagreement measures adapters, not
physics: pymunk's walls are one chain along the solid's outline with no internal seam (the
mitre faces between convex pieces gave it ghost normals), each peer slides the part down a
plain incline at the Coulomb closed form sqrt(2 g s (sin phi - mu cos phi)) and down the
feeder's input chute to the lip at it; every engine gets the same made feeder and the same
start state from the verdict's draws; the end rule found in a peer's states is the compiled
loop's; and a tiny run produces every table. Skipped without MuJoCo or pymunk (optional
extras: ``pip install ".[bench]"``).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString, Polygon

pytest.importorskip("mujoco")
pytest.importorskip("pymunk")

from experiments.bench.agreement.designs import named_design
from experiments.bench.agreement.drops import peer_drop
from experiments.bench.agreement.ending import EndRule
from experiments.bench.agreement.lip import SLOW, closed_form_speed
from experiments.bench.agreement.report import markdown, write_outputs
from experiments.bench.agreement.suite import (
    AgreementSettings,
    agreement_data,
    run_trial,
    trial_starts,
)
from experiments.bench.peers.mujoco_engine import MujocoFeederSimulator
from experiments.bench.peers.outline import chain_segments, outline_chains
from experiments.bench.peers.pymunk_engine import PymunkFeederSimulator
from experiments.drop.perturbations import Perturbations, draw
from experiments.drop.verdict import entry_state, made_feeders
from feeders.design import PRESETS
from feeders.feeder import ORIENTATIONS, build_feeder
from feeders.part import DEFAULT_PEG
from feeders.scene import Goal, Scene
from feeders.shapes import Obstacles
from validity.dynamic import DynamicLevel

PEERS = {"mujoco": MujocoFeederSimulator, "pymunk": PymunkFeederSimulator}


@pytest.mark.parametrize("name", ["table3", "halton:0:31"])
def test_outline_chain_is_the_union_boundary_without_internal_seams(name):
    scene = build_feeder(named_design(name).design)
    chains = outline_chains(scene)
    assert len(chains) == 1  # the cavity: one closed chain
    pieces = [Polygon(p) for p in scene.obstacles.polygons]
    boundary = shapely.unary_union(pieces).boundary
    segments = [LineString([a, b]) for _, a, b, _ in chain_segments(chains[0])]
    for seg in segments:
        assert boundary.buffer(1e-9).contains(seg)  # every segment is a face of the solid
        # solid on one side of its middle, free space on the other: not an internal face
        mid = np.asarray(seg.interpolate(0.5, normalized=True).coords[0])
        d = np.diff(np.asarray(seg.coords), axis=0)[0]
        n = np.array([-d[1], d[0]]) / np.hypot(*d) * 1e-6
        inside = [any(p.contains(shapely.Point(*(mid + s * n))) for p in pieces) for s in (1, -1)]
        assert sorted(inside) == [False, True]
    # no collinear seam: every vertex turns
    c = chains[0]
    e1, e2 = np.roll(c, -1, axis=0) - c, c - np.roll(c, 1, axis=0)
    cross = e2[:, 0] * e1[:, 1] - e2[:, 1] * e1[:, 0]
    assert np.all(np.abs(cross) > 1e-9)
    # and the mitred internal faces at the lip are not in it: the chain is the cavity's
    # outline (the free interior) except where the protuberance juts in
    lip = (scene.design.gx, scene.design.gy)
    ends = [tuple(np.round(v, 9)) for v in c]
    assert tuple(np.round(lip, 9)) in ends
    at_lip = [s for s in segments if s.distance(shapely.Point(lip)) < 1e-9]
    assert len(at_lip) == 2  # the chute floor and the wall below: nothing else meets the lip


def _incline_scene(phi: float, mu: float) -> tuple[Scene, tuple[float, ...]]:
    """A slab whose top face rises at ``phi`` through the origin, the peg resting on it."""
    u, n = np.array([math.cos(phi), math.sin(phi)]), np.array([-math.sin(phi), math.cos(phi)])
    slab = np.array([-20 * u - n, 20 * u - n, 20 * u, -20 * u])
    goal = Goal(-1.0, 1.0, -60.0, -59.0, -math.pi / 2, 0.3)
    com = 5.0 * u + (DEFAULT_PEG.width / 2) * n
    scene = Scene(
        "incline", Obstacles((slab,), np.zeros((0, 3))), DEFAULT_PEG, (-30, 30, -30, 30),
        {"rest": (float(com[0]), float(com[1]), phi)}, goal, friction=mu, restitution=0.0,
    )  # fmt: skip
    return scene, (float(com[0]), float(com[1]), phi, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("engine", ["mujoco", "pymunk"])
def test_peer_slides_down_a_plain_incline_at_the_coulomb_closed_form(engine):
    phi, mu, h, t = 0.5, 0.1, 1e-4, 0.6
    scene, start = _incline_scene(phi, mu)
    sim = PEERS[engine](scene, h)
    sim.reset(start)
    out = np.empty((round(t / h), 6))
    sim.run(out)
    u = np.array([math.cos(phi), math.sin(phi)])
    s = float((np.asarray(start[:2]) - out[-1, :2]) @ u)  # slid down the incline
    accel = 9.81 * (math.sin(phi) - mu * math.cos(phi))
    assert s == pytest.approx(0.5 * accel * t * t, rel=0.02)
    assert math.hypot(out[-1, 3], out[-1, 4]) == pytest.approx(math.sqrt(2 * accel * s), rel=0.01)
    assert abs(out[-1, 2] - phi) < 1e-3  # flat on the face, no rocking


@pytest.mark.parametrize("engine", ["mujoco", "pymunk"])
@pytest.mark.parametrize("trial", [None, 3, 27])
def test_peer_reaches_the_lip_at_the_sliding_speed(engine, trial):
    """Nominal starts and two perturbed trials where pymunk, with segments of radius 0, lost
    a fifth and more of the speed as the part's leading corner passed the lip."""
    if trial is None:
        scene = build_feeder(PRESETS["table3"], restitution=0.0)
        starts = {o: (*scene.start(o), 0.0, 0.0, 0.0) for o in ORIENTATIONS}
    else:
        d = draw(Perturbations(), 0, trial, 2)
        scene = made_feeders(PRESETS["table3"])(d)
        starts = trial_starts(scene, DynamicLevel(scene), d)
    for start in starts.values():
        drop = peer_drop(scene, start, PEERS[engine](scene, 1e-4), t_max=4.0)
        assert drop.lip is not None
        assert drop.lip.ratio == pytest.approx(1.0, abs=0.03)
        assert drop.lip.ratio > SLOW
        assert drop.lip.reference == pytest.approx(
            closed_form_speed(scene, start, drop.lip.distance)
        )
        assert drop.ending.success  # table3 works


def test_offset_chain_keeps_the_faces_where_they_are():
    """pymunk's segments have radius r on a chain moved r into the solid: every segment lies
    exactly r from the solid's boundary, so the capsules' surface is the solid's faces."""
    scene = build_feeder(PRESETS["table3"])
    r = 1e-3
    boundary = shapely.unary_union([Polygon(p) for p in scene.obstacles.polygons]).boundary
    chain = outline_chains(scene, offset=r)[0]
    assert len(chain) == len(outline_chains(scene)[0])
    for _, a, b, _ in chain_segments(chain):
        mid = LineString([a, b]).interpolate(0.5, normalized=True)
        assert mid.distance(boundary) == pytest.approx(r, abs=1e-12)


def test_the_same_draw_gives_every_engine_the_same_feeder_and_start():
    named = named_design("table3")
    settings = AgreementSettings(trials=1, t_max=0.05)
    rows = run_trial(named, 3, settings)
    assert {r.engine for r in rows} == {"partfeeder", "mujoco", "pymunk"}
    d = draw(Perturbations(), 0, 3, 2)
    scene = made_feeders(named.design)(d)
    level = DynamicLevel(scene)
    for k, o in enumerate(ORIENTATIONS):
        expected = entry_state(level, scene.start(o), d.entry_offsets[k], d.entry_velocities[k])
        mine = [r for r in rows if r.entry == o]
        assert len(mine) == 3
        for r in mine:
            assert r.start == pytest.approx(expected, abs=0, rel=0)
            assert r.friction == scene.friction
    # another trial index is another draw
    assert run_trial(named, 4, settings)[0].start != rows[0].start


def test_end_rule_matches_the_compiled_loop_order_and_carries_stillness():
    rule = EndRule(y_stop=-1.0, bounds=(-5, 5, -5, 5), radius=1.0, rest=3)
    moving = np.array([[0, 0, 0, 1.0, 0, 0]] * 2)
    still = np.zeros((2, 6))
    assert rule.first_end(moving) is None
    assert rule.first_end(still) is None and rule.still == 2  # carried to the next chunk
    assert rule.first_end(still) == (0, "at_rest")
    rule = EndRule(y_stop=-1.0, bounds=(-5, 5, -5, 5), radius=1.0, rest=3)
    # below y_stop and out of bounds in the same state: crossed first, as the kernel
    assert rule.first_end(np.array([[0, 0, 0, 1, 0, 0], [9, -2, 0, 1, 0, 0]])) == (1, "crossed")
    assert rule.first_end(np.array([[9, 0, 0, 1, 0, 0]])) == (0, "left_bounds")
    # a spin counts as motion: |v| + R |omega|
    assert rule.first_end(np.array([[0, 0, 0, 0, 0, 0.01]] * 5)) is None


def test_a_tiny_run_produces_every_table(tmp_path):
    settings = AgreementSettings(trials=2)
    data = agreement_data([named_design("table3")], settings)
    t = data["tables"]
    assert set(t) == {"success", "outcomes", "pairs", "verdicts", "lip", "timing"}
    assert set(t["pairs"]) == {"partfeeder vs mujoco", "partfeeder vs pymunk", "mujoco vs pymunk"}
    for pair in t["pairs"].values():
        assert pair["success"]["n"] == 4 and sum(pair["table"].values()) == 4
    for engine in ("partfeeder", "mujoco", "pymunk"):
        cell = t["success"]["table3"][engine]["heavy_leading"]
        assert cell["n"] == 2 and cell["interval"][0] <= cell["p"] <= cell["interval"][1]
        assert t["lip"][engine]["measured"] == 4
    assert t["verdicts"]["decisions"]["table3"]["mujoco"] in ("works", "fails", "undecided")
    assert len(data["drops"]) == 12
    paths = write_outputs(data, tmp_path)
    assert {p.name for p in paths} == {"agreement.json", "agreement.md", "agreement.png"}
    stored = json.loads((tmp_path / "agreement.json").read_text())
    text = markdown(stored)
    for heading in ("Success per design", "Per-drop agreement", "Verdicts", "Speed just past"):
        assert heading in text


def test_bad_agreement_options_are_one_line(capsys, monkeypatch):
    from experiments.bench.peers import pymunk_engine
    from experiments.cli.entry import run

    assert run(["bench", "--agreement", "--trials", "0"]) == 2
    assert run(["bench", "--agreement", "--engines", "mujoco"]) == 2
    assert run(["bench", "--agreement", "--design", "halton:0"]) == 2
    monkeypatch.setattr(pymunk_engine, "available", lambda: False)
    assert run(["bench", "--agreement", "--quick"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 4
    assert "--trials" in lines[0] and "--engines" in lines[1] and "halton" in lines[2]
    assert "pymunk is not installed" in lines[3]
