"""The stress suite on composite parts (issue 24): the measures against shapely on hand-made
poses of the cup (no convex-hull shortcut: an obstacle in its mouth is no overlap), composite
cases generated beside the peg's without changing them, case files holding a composite part,
and a run of them that keeps every hard bound."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import pytest
import shapely

from experiments.stress import add_arguments, run
from experiments.stress.case import LEVEL_NAMES, Case, CaseError
from experiments.stress.command import MAX_CASES
from experiments.stress.generate import (
    COMPOSITE_BASE,
    FAMILIES,
    composite_index,
    generate_case,
)
from experiments.stress.measures import PartShape, Solid, penetration_depths, union_of
from experiments.stress.parts import KINDS, read_part
from experiments.stress.placement import hull_sides, signed_distance, span_range, wedge_angle
from experiments.stress.pool import run_cases
from experiments.stress.report import read_case, summary, table, write_case
from experiments.stress.runner import record_of, scene_of
from experiments.stress.scenes import BOUNDS, FLOOR
from feeders.composite_part import CompositePart, part_from_dict
from feeders.cup import cup_part
from feeders.part_shape import part_geometry
from validity import make_level

CASES = Path(__file__).parent / "cases"
CUP = cup_part()  # 1.0 wide, 0.9 high, walls 0.15: the base's outer face 0.345 from the com
POST = [[0.0, 0.0], [1.0, 0.0], [1.0, 3.0], [0.0, 3.0]]
BASE_DOWN = -math.pi / 2  # open end up: body +x (toward the base) points down


def _solid(polygons, circles=()) -> Solid:
    return Solid.of_union(union_of(polygons, list(circles)))


def _depth(solid: Solid, part, pose) -> float:
    return float(penetration_depths(solid, part, np.array([pose], dtype=float))[0])


def _overlap_area(solid: Solid, part, pose) -> float:
    return float(part_geometry(part, pose).intersection(solid.union).area)


def test_cup_resting_on_a_floor_reads_no_depth():
    """Base down, its outer face on the floor's top (y = 0): shapely sees no overlap, the
    measure reads none, and the gap is 0; lifted 0.01 the gap is 0.01."""
    floor = _solid([FLOOR])
    pose = (1.0, 0.345, BASE_DOWN)
    assert _overlap_area(floor, CUP, pose) < 1e-12
    assert _depth(floor, CUP, pose) < 1e-12
    assert abs(signed_distance(floor, CUP, pose)) < 1e-12
    assert signed_distance(floor, CUP, (1.0, 0.355, BASE_DOWN)) == pytest.approx(0.01, abs=1e-12)


def test_cup_pushed_into_a_post_reads_the_push():
    """Base toward +x, its outer face 0.05 inside the post's left face: depth 0.05, and it is
    shapely's: moved back 0.05 the cup overlaps nothing, moved back 0.049 it still does."""
    post = _solid([POST])
    pose = (0.05 - 0.345, 1.5, 0.0)
    assert _depth(post, CUP, pose) == pytest.approx(0.05, abs=1e-9)
    assert signed_distance(post, CUP, pose) == pytest.approx(-0.05, abs=1e-9)
    assert _overlap_area(post, CUP, (pose[0] - 0.05, 1.5, 0.0)) < 1e-12
    assert _overlap_area(post, CUP, (pose[0] - 0.049, 1.5, 0.0)) > 1e-4


def test_pin_in_the_cups_mouth_is_no_overlap():
    """A disc of radius 0.2 in the mouth of the cup (open end up), 0.15 from either wall: inside
    the cup's convex hull but not in the cup. Depth 0, gap 0.15 (shapely's distance)."""
    pin = _solid([], [(0.0, 2.2, 0.2)])
    pose = (0.0, 2.0, BASE_DOWN)  # the mouth: x in [-0.35, 0.35], y from 1.805 up
    c, s = math.cos(pose[2]), math.sin(pose[2])
    hull = shapely.Polygon(CUP.convex_hull() @ np.array([[c, s], [-s, c]]) + pose[:2])
    assert hull.intersection(pin.union).area > 0.1  # what a hull shortcut would overlap
    assert _depth(pin, CUP, pose) == 0.0
    reference = part_geometry(CUP, pose).distance(pin.union)
    assert signed_distance(pin, CUP, pose) == pytest.approx(reference, abs=1e-9)
    assert reference == pytest.approx(0.15, abs=1e-5)


def test_pin_pressed_into_the_cups_inner_base_reads_its_depth():
    """The disc pressed 0.03 into the inner face of the base (from inside the mouth): depth
    0.03 (its discretisation on the solid's side: < 5e-6 r)."""
    pin = _solid([], [(0.0, 1.805 + 0.2 - 0.03, 0.2)])
    pose = (0.0, 2.0, BASE_DOWN)
    assert _depth(pin, CUP, pose) == pytest.approx(0.03, abs=1e-5)


def test_gap_of_a_disc_piece_is_exact():
    """A plate with a disc touching its end, above a floor: the gap is the disc's lowest point
    (centre less radius), to round-off, not its inscribed polygon's."""
    part = part_from_dict(
        {
            "pieces": [
                {"polygon": [[0, -0.1], [1, -0.1], [1, 0.1], [0, 0.1]], "density": 1.0},
                {"circle": {"centre": [1.3, 0.0], "radius": 0.3}, "density": 2.0},
            ]
        }
    )
    floor = _solid([FLOOR])
    lowest = part.body_discs()[0, 1] - 0.3
    for y in (0.5, 0.4 + 1e-9):
        assert signed_distance(floor, part, (0.0, y, 0.0)) == pytest.approx(y + lowest, abs=1e-12)


def test_a_composite_parts_shapes_for_the_placements():
    """The cup rests flush on four sides (base, walls, rims); its width across a chute runs
    from 0.9 (its height) to its diagonal, and a chute between them is spanned exactly."""
    assert len(hull_sides(CUP)) == 4
    narrow, _, wide, _ = span_range(CUP)
    assert narrow == pytest.approx(0.9, abs=1e-6)
    assert wide == pytest.approx(math.hypot(0.9, 1.0), abs=1e-3)
    angle = wedge_angle(CUP, 1.1)
    assert angle is not None
    outline = PartShape.of(CUP).outline @ np.array([math.cos(angle), math.sin(angle)])
    assert outline.max() - outline.min() == pytest.approx(1.1, abs=1e-12)
    assert wedge_angle(CUP, 0.8) is None


@pytest.mark.slow  # ~9 s; the run over them stays
def test_composite_cases_cover_every_kind_family_and_level():
    """81 consecutive composite cases hold every (kind, family, level); each is plain data that
    round-trips, its scene's part a composite part weighing the case's mass."""
    cases = [generate_case(3, composite_index(j), LEVEL_NAMES) for j in range(81)]
    combos = {(c.family, c.level) for c in cases}
    assert combos == {(f"{f}+{k}", lv) for f in FAMILIES for k in KINDS for lv in LEVEL_NAMES}
    assert "wedged" in {c.placement for c in cases}
    assert not {"entry", "issue_drop"} & {c.placement for c in cases}
    for case in cases[:12]:
        assert Case.from_dict(case.to_dict()) == case
        part = read_part(case.scene["part"])
        assert isinstance(part, CompositePart)
        assert part.mass == pytest.approx(case.mass, rel=1e-9)
        scene = scene_of(case)
        assert scene.part.mass == case.mass and scene.part.inertia == case.inertia


@pytest.mark.parametrize(
    "name", ["case-0-001034-dynamic", "case-7-004193-dynamic", "case-0-009401-dynamic"]
)
def test_peg_cases_keep_their_index_and_draws(name):
    """The composite cases have indices of their own (from 10,000,000), so every peg case is
    the one the files of earlier runs hold."""
    stored, _ = read_case(next(CASES.rglob(f"{name}.yaml")))
    assert generate_case(stored.seed, stored.index, LEVEL_NAMES) == stored
    assert COMPOSITE_BASE == MAX_CASES  # the CLI's limit is where they begin


def _cup_on_floor(level: str) -> Case:
    """The cup (``part: cup``), base down 1e-4 above a floor, released at rest."""
    scene = {
        "obstacles": [{"polygon": FLOOR}],
        "bounds": list(BOUNDS),
        "starts": {"case": [1.0, 0.3451, BASE_DOWN]},
        "goal": {"x": [0.9, 1.1], "y": [0.2, 0.4], "yaw": 0.0, "yaw_tol": 3.0},
        "part": "cup",
    }
    state = (1.0, 0.3451, BASE_DOWN) + (() if level == "geometric" else (0.0, -0.5, 0.0))
    control = (0.0, 0.0, 0.0) if level == "dynamic" else (0.0, -0.5, 0.0)
    return Case(0, 0, level, "post_on_floor+cup", "drop", scene, state, control, 1e-3, 1.0, 1.0,
                CUP.inertia, 0.3)  # fmt: skip


@pytest.mark.parametrize("level", LEVEL_NAMES)
def test_cup_case_file_round_trips_and_replays(tmp_path, level):
    """A case file with ``part: cup`` is written, read back equal and run again to the same
    record; the cup settles on the floor without sinking or crossing it."""
    case = _cup_on_floor(level)
    record = record_of(case)
    assert record["hard"] == [] and record["error"] is None, record
    path = write_case(tmp_path, case, record)
    assert "part: cup" in path.read_text()
    again, stored = read_case(path)
    assert again == case and stored == record
    assert record_of(again) == record
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    assert run(parser.parse_args(["--replay", str(path)])) == 0


def test_generated_composite_case_file_replays(tmp_path):
    """``--case`` of a composite index writes its file (the part's pieces in it); the replay
    gives the same record."""
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    index = composite_index(5)
    run(parser.parse_args(["--case", str(index), "--out", str(tmp_path)]))
    path = tmp_path / f"case-0-{index:06d}-dynamic.yaml"
    case, stored = read_case(path)
    assert case == generate_case(0, index, LEVEL_NAMES)
    assert "pieces" in case.scene["part"] or "outline" in case.scene["part"]
    assert record_of(case) == stored


def test_a_case_file_with_a_bad_composite_part_is_refused_naming_the_field():
    data = _cup_on_floor("dynamic").to_dict()
    data["scene"] = {**data["scene"], "part": {"outline": [[0, 0], [1, 1], [1, 0], [0, 1]]}}
    with pytest.raises(CaseError, match=r"case\.scene\.part\.outline"):
        Case.from_dict({**data, "scene": {**data["scene"], "part": {"outline": [], "density": 1}}})
    with pytest.raises(CaseError, match=r"case\.scene\.part"):
        Case.from_dict(data)


@pytest.mark.parametrize("seed", [0, pytest.param(3, marks=pytest.mark.slow)])  # ~12 s each
def test_composite_run_keeps_every_hard_bound(seed):
    """81 composite cases (every kind x family x level) at their drawn steps: no exception,
    NaN, penetration, energy gain or wall crossing beyond the bounds; the summary counts them
    by kind of part."""
    results = run_cases(seed, 0, LEVEL_NAMES, workers=1, n_composite=81)
    data = summary(results, seed)
    assert data["cases"] == 81
    assert data["hard_failures"] == 0, table(data)
    assert set(data["parts"]) == set(KINDS)
    assert sum(row["cases"] for rows in data["parts"].values() for row in rows.values()) == 81


def test_bad_composite_count_is_one_line(capsys):
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    assert run(parser.parse_args(["--composite", "-1"])) == 2
    err = capsys.readouterr().err
    assert err.startswith("partfeeder stress: error: --composite") and err.count("\n") == 1


def test_a_pin_entering_the_cups_mouth_is_no_wall_crossing():
    """The cup, open end down, lowered onto a pin until the pin meets the inside of its base:
    its centre of mass (in the mouth) ends inside the pin, yet no material went through it. The
    crossing measure follows a point of the material (3 of 2,000 composite cases of seed 0 were
    read as crossings with no overlap when it followed the centre of mass)."""
    shape = PartShape.of(CUP)
    assert shapely.contains_xy(shape.body, *shape.anchor)
    assert not shapely.contains_xy(shape.body, 0.0, 0.0)
    scene = {
        "obstacles": [{"polygon": FLOOR}, {"circle": {"centre": [0.0, 1.0], "radius": 0.2}}],
        "bounds": list(BOUNDS),
        "starts": {"case": [0.0, 1.805, math.pi / 2]},
        "goal": {"x": [-2.0, -1.8], "y": [2.0, 2.2], "yaw": 0.0, "yaw_tol": 3.0},
        "part": "cup",
    }
    case = Case(0, 0, "kinematic", "pin+cup", "drop", scene, (0.0, 1.805, math.pi / 2, 0, -1, 0),
                (0.0, -1.0, 0.0), 1e-3, 1.0, 1.0, CUP.inertia, 0.3)  # fmt: skip
    record = record_of(case)
    assert record["hard"] == [], record
    assert record["max_depth"] <= 1e-9
    level = make_level("kinematic", scene_of(case), step=1e-3)
    end = level.run(case.state, case.control, 1.0, record=True).states[-1]
    assert math.hypot(end[0], end[1] - 1.0) < 0.2  # the centre of mass is inside the pin
