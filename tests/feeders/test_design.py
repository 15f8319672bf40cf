"""Specification of feeders.design: the twelve parameters (paper Table 1), the Table 2 box and
every design printed in the paper.

References are typed in from the paper (/work/shared/seed/hierarchical-design-paper.txt,
Section 3: Tables 1-3 and the captions of Figs. 4-9), never read from the code under test.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from feeders.design import (
    DESIGN_SPACE,
    PARAMETER_NAMES,
    PHYSICAL_BOUNDS,
    PRESETS,
    TABLE2_BOUNDS,
    DesignError,
    DesignParameters,
    preset,
)

# Paper Table 1, in the order a, b, c, d, e, f = (fx, fy), g = (gx, gy), r, theta, alpha.
NAMES = ("a", "b", "c", "d", "e", "fx", "fy", "gx", "gy", "r", "theta", "alpha")

# Paper Table 2. The paper prints e as [-1.0, -2.0]; as an interval that is [-2, -1].
TABLE2 = {
    "a": (1.1, 1.2),
    "b": (1.1, 1.3),
    "c": (0.75, 0.8),
    "d": (2.5, 5.0),
    "e": (-2.0, -1.0),
    "fx": (-1.0, -0.6),
    "fy": (0.5, 2.5),
    "gx": (0.2, 2.0),
    "gy": (1.5, 3.0),
    "r": (0.1, 0.3),
    "theta": (0.3, 0.9),
    "alpha": (0.9, 1.1),
}


def _paper(a, b, c, d, e, f, g, r, theta, alpha):
    return dict(
        a=a, b=b, c=c, d=d, e=e, fx=f[0], fy=f[1], gx=g[0], gy=g[1], r=r, theta=theta,
        alpha=alpha,
    )  # fmt: skip


# Every design printed in the paper, typed from its figure captions and Table 3.
PAPER_DESIGNS = {
    # Fig. 4: a sample RRT with a geometrically feasible path.
    "fig4": _paper(1.113, 1.134, 0.7727, 3.462, -1.161, (-0.616, 1.929), (1.325, 2.666), 0.144,
                   0.4764, 0.9526),
    # Fig. 5: the same device for theta = 0.235 (left) and theta = 0.529 (right).
    "fig5a": _paper(1.1, 1.1086, 0.798, 3.008, -1.9, (-0.985, 1.01), (0.733, 2.039), 0.101,
                    0.235, 1.047),
    "fig5b": _paper(1.1, 1.1086, 0.798, 3.008, -1.9, (-0.985, 1.01), (0.733, 2.039), 0.101,
                    0.529, 1.047),
    # Fig. 6: two geometrically feasible samples of the Table 2 box.
    "fig6a": _paper(1.178, 1.1, 0.782, 3.106, -1.935, (-0.923, 0.949), (1.493, 2.518), 0.152,
                    0.725, 1.005),
    "fig6b": _paper(1.181, 1.107, 0.787, 3.298, -1.967, (-0.619, 1.234), (1.043, 1.685), 0.161,
                    0.761, 1.016),
    # Fig. 7: two samples for which no successful trajectory was found.
    "fig7a": _paper(1.1, 1.1, 0.75, 2.5, -1.0, (-0.6, 0.5), (0.2, 1.5), 0.1, 0.3, 0.9),
    "fig7b": _paper(1.127, 1.168, 0.795, 4.423, -1.322, (-0.632, 1.397), (0.762, 2.055), 0.186,
                    0.65, 1.005),
    # Fig. 8: two kinematically feasible designs.
    "fig8a": _paper(1.14, 1.2, 0.769, 2.899, -1.483, (-0.65, 0.87), (1.88, 1.88), 0.23, 0.829,
                    1.06),
    "fig8b": _paper(1.159, 1.25, 0.751, 4.245, -1.709, (-0.824, 0.908), (0.931, 2.277), 0.291,
                    0.478, 0.932),
    # Fig. 9: the initial guess of the dynamic optimisation.
    "fig9": _paper(1.2, 1.3, 0.8, 5.0, -1.0, (-0.7, 2.5), (1.5, 3.0), 0.3, 0.7854, 1.0472),
    # Table 3: the optimum found with the dynamic model.
    "table3": _paper(1.1, 1.1086, 0.7979, 3.0078, -1.9, (-0.9849, 1.0098), (0.733, 2.0388),
                     0.101, 0.4673, 1.0472),
}  # fmt: skip


def _in_table2(values: dict[str, float]) -> list[str]:
    return [n for n, (lo, hi) in TABLE2.items() if not lo <= values[n] <= hi]


# --- names and box -------------------------------------------------------------------------


def test_twelve_parameter_names_in_table1_order():
    """Reference: paper Table 1 (f and g are points, so two values each: 12 in all)."""
    assert PARAMETER_NAMES == NAMES
    assert len(PARAMETER_NAMES) == 12


def test_table2_bounds_with_e_as_an_interval():
    """Reference: paper Table 2, with e's printed [-1.0, -2.0] read as the interval [-2, -1]."""
    assert TABLE2_BOUNDS == TABLE2
    assert TABLE2_BOUNDS["e"] == (-2.0, -1.0)
    assert all(lo < hi for lo, hi in TABLE2_BOUNDS.values())


def test_design_space_is_the_table2_box_in_parameter_order():
    """Reference: paper Table 2; low/high follow the Table 1 order."""
    np.testing.assert_array_equal(DESIGN_SPACE.low, [TABLE2[n][0] for n in NAMES])
    np.testing.assert_array_equal(DESIGN_SPACE.high, [TABLE2[n][1] for n in NAMES])


def test_design_space_scale_maps_unit_cube_corners_to_box_corners():
    """Reference: the typed Table 2 corners and the box centre."""
    unit = np.array([np.zeros(12), np.ones(12), np.full(12, 0.5)])
    low = np.array([TABLE2[n][0] for n in NAMES])
    high = np.array([TABLE2[n][1] for n in NAMES])
    np.testing.assert_allclose(DESIGN_SPACE.scale(unit), [low, high, (low + high) / 2])


def test_table2_lies_inside_the_physical_bounds():
    """Every design of the paper's box must be constructible: Table 2 within PHYSICAL_BOUNDS."""
    for name, (lo, hi) in TABLE2.items():
        plo, phi = PHYSICAL_BOUNDS[name]
        assert plo <= lo and hi <= phi, name


# --- presets --------------------------------------------------------------------------------


def test_presets_are_exactly_the_designs_printed_in_the_paper():
    """Reference: the figure and table names of the paper that print a design."""
    assert set(PRESETS) == set(PAPER_DESIGNS)


@pytest.mark.parametrize("name", sorted(PAPER_DESIGNS))
def test_preset_equals_the_paper_values(name):
    """Reference: the values printed in the paper (Fig. 4-9 captions, Table 3), typed in."""
    design = PRESETS[name]
    for field, value in PAPER_DESIGNS[name].items():
        assert getattr(design, field) == pytest.approx(value, abs=1e-12), (name, field)
    assert preset(name) == design


def test_fig5_differs_only_in_theta():
    """Reference: Fig. 5 caption, one device at theta = 0.235 and theta = 0.529."""
    a, b = PRESETS["fig5a"].to_dict(), PRESETS["fig5b"].to_dict()
    assert {k for k in a if a[k] != b[k]} == {"theta"}
    assert (a["theta"], b["theta"]) == (0.235, 0.529)


def test_only_fig5a_is_outside_the_box_and_only_in_theta():
    """Reference: typed Table 2 (theta in [0.3, 0.9]) against the typed paper designs."""
    outside = {name: _in_table2(values) for name, values in PAPER_DESIGNS.items()}
    assert {k: v for k, v in outside.items() if v} == {"fig5a": ["theta"]}
    for name, design in PRESETS.items():
        assert DESIGN_SPACE.outside(design) == outside[name], name
        assert DESIGN_SPACE.contains(design) == (not outside[name]), name


# --- immutability and variants -------------------------------------------------------------


def test_design_is_frozen():
    design = PRESETS["table3"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        design.theta = 0.5  # type: ignore[misc]
    assert design.theta == 0.4673


def test_replace_makes_a_variant_and_leaves_the_original():
    design = PRESETS["table3"]
    variant = dataclasses.replace(design, theta=0.6, d=4.0)
    assert (variant.theta, variant.d) == (0.6, 4.0)
    assert design.theta == 0.4673 and design.d == 3.0078
    same = {n for n in NAMES if getattr(variant, n) == getattr(design, n)}
    assert same == set(NAMES) - {"theta", "d"}


def test_replace_is_validated():
    """A variant goes through the same checks as a new design."""
    with pytest.raises(DesignError, match="'theta'"):
        dataclasses.replace(PRESETS["table3"], theta=math.nan)


def test_values_are_stored_as_floats():
    design = DesignParameters(**{**PAPER_DESIGNS["fig9"], "d": 5, "e": -1})
    assert type(design.d) is float and type(design.e) is float


def test_designs_are_hashable_values():
    assert len({PRESETS["fig5a"], preset("fig5a"), PRESETS["fig5b"]}) == 2


# --- vectors and mappings -------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(PAPER_DESIGNS))
def test_to_vector_is_in_table1_order_and_round_trips(name):
    """Reference: the typed paper values in the Table 1 order."""
    design = PRESETS[name]
    vector = design.to_vector()
    assert vector.shape == (12,) and vector.dtype == np.float64
    np.testing.assert_allclose(vector, [PAPER_DESIGNS[name][n] for n in NAMES], atol=1e-12)
    assert DesignParameters.from_vector(vector) == design
    assert DesignParameters.from_vector(list(vector)) == design
    assert DesignParameters.from_vector(vector.reshape(3, 4)) == design


def test_to_dict_has_the_twelve_names():
    assert PRESETS["fig4"].to_dict() == PAPER_DESIGNS["fig4"]


def test_from_mapping_accepts_f_and_g_as_pairs():
    """Reference: the Fig. 4 caption, written the way the paper writes it (f and g as points)."""
    mapping = {
        "a": 1.113, "b": 1.134, "c": 0.7727, "d": 3.462, "e": -1.161, "f": [-0.616, 1.929],
        "g": (1.325, 2.666), "r": 0.144, "theta": 0.4764, "alpha": 0.9526,
    }  # fmt: skip
    assert DesignParameters.from_mapping(mapping) == PRESETS["fig4"]
    assert "f" in mapping and "fx" not in mapping  # the caller's mapping is not modified


def test_from_mapping_accepts_flat_names():
    assert DesignParameters.from_mapping(PAPER_DESIGNS["fig8b"]) == PRESETS["fig8b"]


def test_from_mapping_rejects_unknown_and_missing_names():
    values = dict(PAPER_DESIGNS["fig4"])
    with pytest.raises(DesignError, match="unknown") as info:
        DesignParameters.from_mapping({**values, "beta": 1.0})
    assert "beta" in str(info.value)
    del values["alpha"]
    with pytest.raises(DesignError, match="missing") as info:
        DesignParameters.from_mapping(values)
    assert "alpha" in str(info.value)


@pytest.mark.parametrize("bad", [1.0, [1.0], [1.0, 2.0, 3.0], "xy"])
def test_from_mapping_rejects_f_that_is_not_a_pair(bad):
    values = {k: v for k, v in PAPER_DESIGNS["fig4"].items() if k not in ("fx", "fy")}
    with pytest.raises(DesignError, match="'f'"):
        DesignParameters.from_mapping({**values, "f": bad})


# --- errors ---------------------------------------------------------------------------------


def test_unknown_preset_lists_the_presets():
    with pytest.raises(DesignError) as info:
        preset("fig10")
    message = str(info.value)
    assert "fig10" in message
    for name in PAPER_DESIGNS:
        assert name in message


@pytest.mark.parametrize("field", NAMES)
def test_nan_names_the_field_and_its_range(field):
    values = {**PAPER_DESIGNS["table3"], field: math.nan}
    with pytest.raises(DesignError) as info:
        DesignParameters(**values)
    low, high = PHYSICAL_BOUNDS[field]
    message = str(info.value)
    assert f"'{field}'" in message
    assert f"[{low:g}, {high:g}]" in message
    assert "\n" not in message


@pytest.mark.parametrize(
    ("field", "value", "shown_range"),
    [
        ("a", 0.0, "[0.05, 10]"),  # a chute of zero width
        ("b", -1.1, "[0.05, 10]"),
        ("d", 60.0, "[0.1, 50]"),
        ("e", 0.5, "[-20, -0.05]"),  # the left cavity wall right of the exit chute's axis
        ("gy", -1.0, "[0, 20]"),
        ("r", 0.0, "[0.01, 5]"),
        ("theta", math.pi / 2, "[0, 1.5608]"),  # a vertical input chute
        ("alpha", 0.0, "[0.05, 1.5708]"),  # a flat chamfer
        ("c", math.inf, "[0, 10]"),
    ],
)
def test_out_of_physical_range_names_the_field_and_range(field, value, shown_range):
    """Reference: the physical ranges stated in feeders/design.py, typed as printed."""
    assert not PHYSICAL_BOUNDS[field][0] <= value <= PHYSICAL_BOUNDS[field][1]
    with pytest.raises(DesignError) as info:
        dataclasses.replace(PRESETS["table3"], **{field: value})
    assert f"'{field}'" in str(info.value)
    assert shown_range in str(info.value)


def test_non_number_names_the_field():
    with pytest.raises(DesignError, match="'d'"):
        DesignParameters(**{**PAPER_DESIGNS["fig9"], "d": "five"})
    with pytest.raises(DesignError, match="'r'"):
        DesignParameters(**{**PAPER_DESIGNS["fig9"], "r": None})


def test_design_error_is_a_value_error():
    assert issubclass(DesignError, ValueError)


@pytest.mark.parametrize("length", [0, 11, 13, 24])
def test_from_vector_rejects_the_wrong_length(length):
    with pytest.raises(DesignError) as info:
        DesignParameters.from_vector(np.ones(length))
    assert "12" in str(info.value)
    assert f"got {length}" in str(info.value)
