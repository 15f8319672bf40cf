"""Specification of feeders.part_properties: a part's mass properties and resting poses in its
own frame (issue 39: ``partfeeder part``).

References independent of the code under test: shapely's Polygon.area and Polygon.centroid of
the part's outline as the user wrote it; closed forms for a rectangle's inertia m (w^2 + h^2)/12
and a disc's m r^2 / 2; statics by hand for the cup's and the L's resting faces.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import shapely
import yaml

from feeders.cup import CUP_HEIGHT, CUP_WALL, CUP_WIDTH, cup_part
from feeders.part import DEFAULT_PEG
from feeders.part_file import part_of_spec, part_source, read_part_file
from feeders.part_properties import mass_properties

ROOT = Path(__file__).resolve().parents[2]
L_FILE = ROOT / "examples" / "l-part.yaml"


def _cup_outline() -> list[tuple[float, float]]:
    """The cup's U in its part frame (rim at x = 0, base's outer face at x = height), from
    feeders.cup's dimensions, not its pieces."""
    h, half, inner = CUP_HEIGHT, CUP_WIDTH / 2, CUP_WIDTH / 2 - CUP_WALL
    base = h - CUP_WALL
    return [
        (0, -half), (h, -half), (h, half), (0, half), (0, inner), (base, inner),
        (base, -inner), (0, -inner),
    ]  # fmt: skip


def test_cup_mass_centre_and_area_agree_with_feeders_cup_and_shapely():
    props = mass_properties(cup_part())
    outline = shapely.Polygon(_cup_outline())
    assert props.area == pytest.approx(outline.area, rel=1e-12)
    assert props.mass == pytest.approx(cup_part().mass, rel=1e-12)
    np.testing.assert_allclose(props.com, [outline.centroid.x, outline.centroid.y], atol=1e-12)
    np.testing.assert_allclose(props.com, cup_part().com, atol=1e-15)
    assert props.inertia == pytest.approx(cup_part().inertia, rel=1e-15)


def test_cup_rests_on_four_faces_numbered_by_yaw():
    """The hull is the 0.9 x 1.0 rectangle, the centre of mass inside it: four stable faces.
    The face across the opening (open end down, on the rims) is a hull edge, not the cup's."""
    props = mass_properties(cup_part())
    yaws = [pose.yaw for pose in props.resting]
    assert yaws == pytest.approx([-math.pi, -math.pi / 2, 0.0, math.pi / 2], abs=1e-12)
    faces = {round(p.yaw, 9): p for p in props.resting}
    base = faces[round(-math.pi / 2, 9)]
    np.testing.assert_allclose(base.face, [[0.9, -0.5], [0.9, 0.5]], atol=1e-12)  # part frame
    rims = faces[round(math.pi / 2, 9)]
    np.testing.assert_allclose(rims.face, [[0.0, 0.5], [0.0, -0.5]], atol=1e-12)
    assert base.on_outline and not rims.on_outline
    assert props.extent == pytest.approx((-0.555, 0.345, -0.5, 0.5), abs=1e-12)


def test_l_part_file_agrees_with_shapely_and_rests_on_three_faces():
    """examples/l-part.yaml: the outline's area and centroid by shapely; statics by hand: the
    foot (y = 0) and the upright's outer side (x = 0.9) hold the centre of mass (0.58125,
    0.36875) above them, and so does the diagonal from the upright's top (0.6, 1) to the foot's
    end (0, 0.3); the top (x from 0.6 to 0.9) and the foot's end (y to 0.3) do not."""
    spec = yaml.safe_load(L_FILE.read_text())["part"]
    outline = shapely.Polygon(spec["outline"])
    props = mass_properties(read_part_file(L_FILE).part)
    assert props.area == pytest.approx(outline.area, rel=1e-12)
    assert props.mass == pytest.approx(spec["density"] * outline.area, rel=1e-12)
    np.testing.assert_allclose(props.com, [outline.centroid.x, outline.centroid.y], atol=1e-12)
    faces = [sorted(map(tuple, np.round(p.face, 12))) for p in props.resting]
    assert faces == [
        [(0.9, 0.0), (0.9, 1.0)],
        [(0.0, 0.0), (0.9, 0.0)],
        [(0.0, 0.3), (0.6, 1.0)],
    ]
    assert [p.on_outline for p in props.resting] == [True, True, False]


@pytest.mark.parametrize(("w", "h", "density"), [(2.0, 0.3, 1.0), (1.0, 1.0, 3.5), (0.2, 5, 0.1)])
def test_rectangle_inertia_is_the_closed_form(w, h, density):
    part = part_of_spec({"outline": [[0, 0], [w, 0], [w, h], [0, h]], "density": density})
    props = mass_properties(part)
    m = density * w * h
    assert props.mass == pytest.approx(m, rel=1e-12)
    assert props.inertia == pytest.approx(m * (w * w + h * h) / 12.0, rel=1e-12)
    np.testing.assert_allclose(props.com, [w / 2, h / 2], atol=1e-12)
    assert len(props.resting) == 4  # every side of a rectangle holds its centre


def test_disc_inertia_is_the_closed_form_and_it_has_no_resting_pose():
    part = part_of_spec({"pieces": [{"circle": {"centre": [1, 2], "radius": 0.5}, "density": 2}]})
    props = mass_properties(part)
    m = 2 * math.pi * 0.25
    assert props.mass == pytest.approx(m, rel=1e-12)
    assert props.inertia == pytest.approx(m * 0.25 / 2, rel=1e-12)
    np.testing.assert_allclose(props.com, [1, 2], atol=1e-12)
    assert props.resting == ()  # neutral: it rolls
    assert props.extent == pytest.approx((-0.5, 0.5, -0.5, 0.5), abs=1e-15)  # not the hull's


def test_peg_is_taken_as_its_two_halves():
    """The shipped peg: its own mass, centre-of-mass offset (from its geometric centre) and
    inertia (feeders.part.two_density_moments)."""
    props = mass_properties(part_source("peg").part)
    assert props.mass == pytest.approx(DEFAULT_PEG.mass, rel=1e-12)
    assert props.inertia == pytest.approx(DEFAULT_PEG.inertia, rel=1e-12)
    np.testing.assert_allclose(props.com, [DEFAULT_PEG.com_offset, 0.0], atol=1e-12)
    assert props.area == pytest.approx(DEFAULT_PEG.length * DEFAULT_PEG.width, rel=1e-12)


def test_as_dict_is_plain_data():
    data = mass_properties(cup_part()).as_dict()
    assert yaml.safe_load(yaml.safe_dump(data)) == data  # no NumPy in it
    assert [p["face_number"] for p in data["stable_poses"]] == [1, 2, 3, 4]
