"""Case generation: a function of the seed alone, plain data, and covering every family."""

from __future__ import annotations

import pytest

from experiments.stress.case import LEVEL_NAMES, Case, CaseError
from experiments.stress.generate import FAMILIES, PLACEMENTS, generate_case


def test_same_seed_same_cases():
    first = [generate_case(7, i, LEVEL_NAMES).to_dict() for i in range(30)]
    again = [generate_case(7, i, LEVEL_NAMES).to_dict() for i in range(30)]
    other = [generate_case(8, i, LEVEL_NAMES).to_dict() for i in range(30)]
    assert first == again
    assert first != other


def test_case_round_trips_through_a_mapping():
    for i in range(12):
        case = generate_case(1, i, LEVEL_NAMES)
        assert Case.from_dict(case.to_dict()) == case


def test_a_bad_case_field_is_named():
    data = generate_case(1, 2, LEVEL_NAMES).to_dict()
    with pytest.raises(CaseError, match=r"case\.h"):
        Case.from_dict({**data, "h": 5.0})
    with pytest.raises(CaseError, match=r"case\.level"):
        Case.from_dict({**data, "level": "quantum"})


@pytest.mark.slow  # ~20 s
def test_generation_covers_every_family_and_placement():
    """Families are dealt in turn with the levels; placements are drawn: 540 cases hold every
    family at every level and every kind of placement (the issue's post drop included)."""
    cases = [generate_case(0, i, LEVEL_NAMES) for i in range(540)]
    pairs = {(c.family, c.level) for c in cases}
    assert pairs == {(f, lv) for f in FAMILIES for lv in LEVEL_NAMES}
    assert {c.placement for c in cases} == set(PLACEMENTS)
    assert {c.placement for c in cases if c.level != "dynamic"} <= set(PLACEMENTS) - {"overlap"}
    friction = [c.friction for c in cases]
    assert min(friction) == 0.0 and max(friction) > 1.5
    steps = [c.h for c in cases]
    assert min(steps) < 1e-4 and max(steps) > 1e-2
    masses = [c.mass for c in cases]
    assert max(masses) / min(masses) > 1e4
