"""Specification of feeders.part: the two-density rectangular peg.

References: numerical integration (midpoint rule) on a fine grid over the two-density
rectangle for the centre of mass and the moment of inertia, closed forms for the uniform and
one-sided limits, shapely for polygon orientation and extents, and the Table 2 chute widths
typed from the paper.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from shapely import affinity
from shapely.geometry import Polygon, box

from feeders.part import DEFAULT_PEG, PartError, Peg

# Paper Table 2: input chute width a in [1.1, 1.2], exit chute width b in [1.1, 1.3].
A_RANGE = (1.1, 1.2)
B_RANGE = (1.1, 1.3)

CASES = [
    # (length, width, mass, heavy_fraction)
    (2.2, 0.7, 1.0, 0.9),  # the defaults (docs/calibration.md)
    (1.6, 1.0, 1.0, 0.75),  # the defaults before the calibration
    (2.0, 1.0, 1.0, 0.75),
    (2.0, 1.0, 1.0, 0.5),  # uniform
    (2.0, 1.0, 1.0, 1.0),  # all the mass in one half
    (3.0, 0.5, 2.5, 0.6),
    (1.5, 1.2, 0.3, 0.9),
]


def _grid_moments(length, width, mass, heavy_fraction, nx=2000, ny=800):
    """Mass, centre of mass (x, y) and polar moment about it, by the midpoint rule on an
    nx x ny grid over [-L/2, L/2] x [-w/2, w/2]; the half x > 0 has density
    heavy_fraction * mass / (L/2 * w), the other half the rest. nx is even, so the density
    jump at x = 0 falls on a cell edge."""
    hx, hy = length / nx, width / ny
    x = -length / 2 + hx * (np.arange(nx) + 0.5)
    y = -width / 2 + hy * (np.arange(ny) + 0.5)
    half_area = length / 2 * width
    rho_x = np.where(x > 0, heavy_fraction, 1 - heavy_fraction) * mass / half_area
    xx, yy = np.meshgrid(x, y, indexing="ij")
    dm = np.broadcast_to(rho_x[:, None], xx.shape) * hx * hy
    total = dm.sum()
    cx, cy = (dm * xx).sum() / total, (dm * yy).sum() / total
    inertia = (dm * ((xx - cx) ** 2 + (yy - cy) ** 2)).sum()
    return total, cx, cy, inertia


@pytest.mark.parametrize(("length", "width", "mass", "heavy"), CASES)
def test_two_density_matches_grid_integration(length, width, mass, heavy):
    """Reference: midpoint-rule integration on a 2000 x 800 grid of the two-density plate."""
    peg = Peg.two_density(length=length, width=width, mass=mass, heavy_fraction=heavy)
    total, cx, cy, inertia = _grid_moments(length, width, mass, heavy)
    assert total == pytest.approx(mass, rel=1e-12)
    assert abs(cy) < 1e-12
    assert peg.com_offset == pytest.approx(cx, rel=1e-9, abs=1e-12)
    assert peg.inertia == pytest.approx(inertia, rel=1e-5)
    assert (peg.length, peg.width, peg.mass) == (length, width, mass)


def test_uniform_and_one_sided_limits_match_closed_forms():
    """Reference: a uniform plate, I = m (L^2 + w^2) / 12 at the centre; all mass in one half,
    the plate (L/2 x w) with I = m ((L/2)^2 + w^2) / 12 about its centre at L/4."""
    uniform = Peg.two_density(2.0, 1.0, 3.0, 0.5)
    assert uniform.com_offset == pytest.approx(0.0, abs=1e-15)
    assert uniform.inertia == pytest.approx(3.0 * (4.0 + 1.0) / 12.0, rel=1e-12)
    one_sided = Peg.two_density(2.0, 1.0, 3.0, 1.0)
    assert one_sided.com_offset == pytest.approx(0.5, rel=1e-12)
    assert one_sided.inertia == pytest.approx(3.0 * (1.0 + 1.0) / 12.0, rel=1e-12)


def test_default_peg_is_the_default_two_density_peg():
    """The calibrated defaults (docs/calibration.md) L = 2.2, w = 0.7, m = 1, heavy half 0.9.
    Reference: grid integration (offset (0.9 - 0.1) * 2.2 / 4 = 0.44)."""
    _, cx, _, inertia = _grid_moments(2.2, 0.7, 1.0, 0.9)
    assert cx == pytest.approx(0.44, rel=1e-9)
    for peg in (Peg(), DEFAULT_PEG, Peg.two_density()):
        assert (peg.length, peg.width, peg.mass) == (2.2, 0.7, 1.0)
        assert peg.com_offset == pytest.approx(cx, rel=1e-9)
        assert peg.inertia == pytest.approx(inertia, rel=1e-5)


@pytest.mark.parametrize(("length", "width", "mass", "heavy"), CASES)
def test_body_vertices_are_a_ccw_rectangle_with_the_centre_of_mass_at_the_origin(
    length, width, mass, heavy
):
    """Reference: shapely (orientation, area, halves) and the mass-weighted centroid of the two
    halves, heavy half = the half of larger x."""
    peg = Peg.two_density(length=length, width=width, mass=mass, heavy_fraction=heavy)
    vertices = peg.body_vertices()
    assert vertices.shape == (4, 2)
    polygon = Polygon(vertices)
    assert polygon.is_valid and polygon.exterior.is_ccw
    assert polygon.area == pytest.approx(length * width, rel=1e-12)
    xmin, ymin, xmax, ymax = polygon.bounds
    assert (xmax - xmin, ymax - ymin) == pytest.approx((length, width), rel=1e-12)
    assert polygon.equals(box(xmin, ymin, xmax, ymax))  # axis-aligned: x along the peg
    middle = (xmin + xmax) / 2
    heavy_half = box(middle, ymin, xmax, ymax)
    light_half = box(xmin, ymin, middle, ymax)
    com = (
        heavy * mass * np.array(heavy_half.centroid.coords[0])
        + (1 - heavy) * mass * np.array(light_half.centroid.coords[0])
    ) / mass
    np.testing.assert_allclose(com, [0.0, 0.0], atol=1e-12)


def test_heavy_end_points_along_plus_x():
    """The heavy end is the end of larger x: it is the nearer end to the centre of mass."""
    vertices = DEFAULT_PEG.body_vertices()
    heavy_end, light_end = vertices[:, 0].max(), -vertices[:, 0].min()
    # L = 2.2, offset 0.44: heavy end 1.1 - 0.44 from the centre of mass, light end 1.1 + 0.44.
    assert heavy_end == pytest.approx(0.66) and light_end == pytest.approx(1.54)


def test_bounding_radius_is_the_farthest_corner():
    """Reference: the light-end corners, at (L/2 + offset, w/2) from the centre of mass."""
    assert DEFAULT_PEG.bounding_radius() == pytest.approx(math.hypot(1.54, 0.35), rel=1e-12)


# --- the default peg makes the paper's designs physical -------------------------------------


def _extent_across(peg: Peg, yaw: float) -> float:
    """Extent of the peg along y when it is turned by yaw (the width of strip it needs)."""
    polygon = affinity.rotate(Polygon(peg.body_vertices()), yaw, origin=(0, 0), use_radians=True)
    _, ymin, _, ymax = polygon.bounds
    return ymax - ymin


def test_default_peg_slides_in_both_chutes():
    """Reference: Table 2, a >= 1.1 and b >= 1.1: lying along a chute the peg needs a strip as
    wide as it is (extent across at yaw 0 is w = 0.7), which is narrower than either chute."""
    assert DEFAULT_PEG.width < min(A_RANGE[0], B_RANGE[0])
    assert _extent_across(DEFAULT_PEG, 0.0) == pytest.approx(DEFAULT_PEG.width)
    assert _extent_across(DEFAULT_PEG, 0.0) < A_RANGE[0]


def test_default_peg_cannot_turn_end_for_end_in_either_chute():
    """Turning end for end in a strip, the peg's yaw passes pi/2 (continuity), where its extent
    across the strip equals its length; the widest Table 2 chute is 1.3 < 2.2. Reference: shapely
    extents of the rotated body against the analytic L |sin| + w |cos|."""
    peg = DEFAULT_PEG
    yaws = np.linspace(0.0, math.pi, 181)
    extents = np.array([_extent_across(peg, yaw) for yaw in yaws])
    analytic = peg.length * np.abs(np.sin(yaws)) + peg.width * np.abs(np.cos(yaws))
    np.testing.assert_allclose(extents, analytic, atol=1e-12)
    assert _extent_across(peg, math.pi / 2) == pytest.approx(peg.length)
    assert extents.max() > max(A_RANGE[1], B_RANGE[1])
    assert peg.length > max(A_RANGE[1], B_RANGE[1])


def test_peg_is_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT_PEG.length = 3.0  # type: ignore[misc]


# --- errors ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "field", "shown_range"),
    [
        ({"length": 0.0}, "length", "[0.001, 100]"),
        ({"length": math.nan}, "length", "[0.001, 100]"),
        ({"width": 2.5}, "width", "[0.001, 2.2]"),  # wider than the default length
        ({"mass": -1.0}, "mass", "[1e-09, 1e+09]"),
        ({"com_offset": 1.5}, "com_offset", "[0, 1.1]"),  # outside the peg (L/2 = 1.1)
        ({"inertia": 0.0}, "inertia", "[1e-12, 1e+12]"),
    ],
)
def test_peg_error_names_the_field_and_range(kwargs, field, shown_range):
    with pytest.raises(PartError) as info:
        Peg(**kwargs)
    message = str(info.value)
    assert f"'{field}'" in message and shown_range in message
    assert "\n" not in message


@pytest.mark.parametrize("fraction", [0.4, 1.01, math.inf])
def test_two_density_rejects_a_heavy_fraction_outside_half_to_one(fraction):
    with pytest.raises(PartError) as info:
        Peg.two_density(heavy_fraction=fraction)
    assert "'heavy_fraction'" in str(info.value) and "[0.5, 1]" in str(info.value)


def test_part_error_is_a_value_error():
    assert issubclass(PartError, ValueError)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"mass": 0.0}, "mass"),  # was ZeroDivisionError
        ({"length": 1e308}, "length"),  # was OverflowError
        ({"width": -1.0}, "width"),
        ({"mass": math.nan}, "mass"),
    ],
)
def test_two_density_checks_its_values_before_computing_with_them(kwargs, field):
    with pytest.raises(PartError) as info:
        Peg.two_density(**kwargs)
    assert f"'{field}'" in str(info.value)
