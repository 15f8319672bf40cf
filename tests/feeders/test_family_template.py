"""Specification of feeders.family_template: a device family written for a part from its mass
properties (issue 39: ``partfeeder family new``).

References: the shipped fig1-cup.yaml, whose entries were worked out by hand for the cup (its
0.345 and 0.555), for the cup's template; for an L, shapely: the L's outline as written, turned
and slid into chute A as the module's docstring says (its upper end 0.05 below the cap, its
extent across the chute centred), whose centroid must be the entry pose's position.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.affinity
import yaml

from feeders.device_family import FamilyError, family_from_dict, load_family, packaged_family
from feeders.family_template import (
    CAP_GAP,
    CHUTE_LENGTH,
    ENTRY_DOWN,
    ENTRY_UP,
    class_name,
    family_template,
)
from feeders.fields import parse_yaml
from feeders.halton import halton_points
from feeders.part_file import part_source
from feeders.part_properties import mass_properties

ROOT = Path(__file__).resolve().parents[2]
L_FILE = ROOT / "examples" / "l-part.yaml"


def _family(name: str, given: str | Path):
    text = family_template(name, part_source(given))
    return family_from_dict(parse_yaml(text), name=name), text


def test_the_cups_template_has_fig1_cups_entries_pieces_and_goal():
    """fig1-cup's open_leading is the template's x axis up the chute, open_trailing down it:
    the same poses at the defaults and at 32 Halton points of the box (every one that builds),
    from the same pieces, into the same goal."""
    shipped = load_family(packaged_family("fig1-cup"))
    made, _ = _family("cup-template", "cup")
    assert made.part == shipped.part
    assert made.vector_names == shipped.vector_names
    np.testing.assert_array_equal(made.bounds()[0], shipped.bounds()[0])
    np.testing.assert_array_equal(made.bounds()[1], shipped.bounds()[1])
    np.testing.assert_array_equal(made.default(), shipped.default())
    vectors = [shipped.default(), *halton_points(32, seed=3, space=shipped.space())]
    built = 0
    for vector in vectors:
        try:
            a = shipped.build(vector)
        except Exception:  # a rule refuses it: the template must refuse it too
            with pytest.raises(Exception):  # noqa: B017 - the same DegenerateDesign
                made.build(vector)
            continue
        b = made.build(vector)
        built += 1
        np.testing.assert_allclose(b.starts[ENTRY_UP], a.starts["open_leading"], atol=1e-12)
        np.testing.assert_allclose(b.starts[ENTRY_DOWN], a.starts["open_trailing"], atol=1e-12)
        for p, q in zip(a.obstacles.polygons, b.obstacles.polygons, strict=True):
            np.testing.assert_array_equal(p, q)
        np.testing.assert_array_equal(a.obstacles.circles, b.obstacles.circles)
        assert (b.goal.x_min, b.goal.x_max, b.goal.y_min, b.goal.y_max) == (
            a.goal.x_min, a.goal.x_max, a.goal.y_min, a.goal.y_max,
        )  # fmt: skip
        assert (b.goal.yaw, b.goal.yaw_tol) == pytest.approx(
            (a.goal.yaw, a.goal.yaw_tol), abs=1e-12
        )
        assert b.goal.more_yaws == a.goal.more_yaws == ()
    assert built >= 20


def test_the_cups_template_writes_the_numbers_fig1_cup_worked_by_hand():
    _, text = _family("cup-template", "cup")
    entries = yaml.safe_load(text)["entries"]
    assert "3.605*cos(theta)" in entries[ENTRY_UP][0]
    assert "3.395*cos(theta)" in entries[ENTRY_DOWN][0]


def _placed_l(theta: float, lip: tuple[float, float], width: float, up: bool) -> shapely.Polygon:
    """The L as written, turned by theta (x axis up chute A) or theta - pi, then slid so its
    extent along the chute ends CAP_GAP below the cap and its extent across is centred."""
    outline = shapely.Polygon(yaml.safe_load(L_FILE.read_text())["part"]["outline"])
    yaw = theta if up else theta - math.pi
    turned = shapely.affinity.rotate(outline, yaw, origin=(0, 0), use_radians=True)
    along = np.array([math.cos(theta), math.sin(theta)])
    across = np.array([-math.sin(theta), math.cos(theta)])
    corners = np.asarray(turned.exterior.coords)
    top = max(corners @ along)
    low, high = min(corners @ across), max(corners @ across)
    shift = (
        np.array(lip)
        + (CHUTE_LENGTH - CAP_GAP - top) * along
        + (width / 2 - (low + high) / 2) * across
    )
    return shapely.affinity.translate(turned, *shift)


def test_the_l_templates_entries_sit_at_the_ls_centre_of_mass():
    family, _ = _family("l-template", L_FILE)
    vectors = [family.default(), *halton_points(16, seed=5, space=family.space())]
    checked = 0
    for vector in vectors:
        values = family.values(vector)
        try:
            scene = family.build(vector)
        except Exception:
            continue
        lip = (values["exit_width"] / 2, values["lip_height"])
        for entry, up in ((ENTRY_UP, True), (ENTRY_DOWN, False)):
            placed = _placed_l(values["theta"], lip, values["chute_width"], up)
            x, y, yaw = scene.starts[entry]
            assert (x, y) == pytest.approx((placed.centroid.x, placed.centroid.y), abs=1e-9)
            assert yaw == pytest.approx(values["theta"] - (0 if up else math.pi), abs=1e-12)
        checked += 1
    assert checked >= 8


def test_the_l_templates_widths_fit_the_l_and_its_classes_are_its_resting_poses():
    family, _ = _family("l-template", L_FILE)
    props = mass_properties(part_source(L_FILE).part)
    width = props.extent[3] - props.extent[2]
    names = family.vector_names
    low, high = family.bounds()
    for key in ("chute_width", "exit_width"):
        k = names.index(key)
        assert (low[k], family.default()[k], high[k]) == pytest.approx(
            (width + 0.1, width + 0.2, width + 0.3), abs=1e-12
        )
    assert [c.name for c in family.orientations] == [class_name(k) for k in (1, 2, 3)]
    centres = [c.centres[0] for c in family.orientations]
    assert centres == pytest.approx([p.yaw for p in props.resting], abs=1e-9)
    scene = family.build(family.default())
    assert scene.goal.orientations == (class_name(1),)  # yaw -pi/2: the x axis down
    assert scene.goal.yaw == pytest.approx(-math.pi / 2, abs=1e-9)


def test_a_part_too_long_for_the_device_is_one_line_saying_why():
    """A bar 6 long does not fit chute A (4 long): its start pose reaches into the walls."""
    big = {"outline": [[0, 0], [6, 0], [6, 1], [0, 1]], "density": 1.0}
    from feeders.part_file import PartSource, part_of_spec

    with pytest.raises(FamilyError) as caught:
        family_template("big", PartSource("big", part_of_spec(big), big))
    message = str(caught.value)
    assert "cannot be built" in message and "edit it for this part" in message
    assert "\n" not in message


def test_a_part_with_no_resting_pose_is_refused():
    disc = {"pieces": [{"circle": {"centre": [0, 0], "radius": 0.4}, "density": 1}]}
    from feeders.part_file import PartSource, part_of_spec

    with pytest.raises(FamilyError, match="no stable resting pose"):
        family_template("disc", PartSource("disc", part_of_spec(disc), disc))
