"""The verdict and the screen run on any device family (issue 24): a family's n parameters
are made to tolerance one factor each, its entries are the verdict's orientations, and a made
device its rules refuse is a failed trial; the 12-parameter feeder's draws are what they were."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from experiments.drop.family_verdict import (
    entry_names,
    family_screen,
    family_verdict,
    made_devices,
)
from experiments.drop.perturbations import Perturbations, draw, toleranced, toleranced_values
from experiments.drop.verdict import UNBUILDABLE, run_trial
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import PARAMETER_NAMES, PHYSICAL_BOUNDS, preset
from feeders.device_family import DeviceFamily, family_from_dict
from feeders.feeder import ORIENTATIONS, DegenerateDesign
from feeders.part import Peg
from feeders.scene import Scene

FIG1 = Path(__file__).resolve().parents[3] / "feeders" / "families" / "fig1.yaml"
QUICK = VerdictSettings(min_drops=2, batch=2, max_drops=4)

# draw(Perturbations(), seed=21, index=3) as the code drew it before ``parameters`` existed
RECORDED_DRAW = (
    (
        "0x1.fe0f3eed7d3aap-1",
        "0x1.0212bf60397ccp+0",
        "0x1.014161a831221p+0",
        "0x1.ffd137febef05p-1",
        "0x1.fd2eb36ddf864p-1",
        "0x1.fb77086f49cf6p-1",
        "0x1.fd38a125e4938p-1",
        "0x1.003f767199c8bp+0",
        "0x1.00d1174240093p+0",
        "0x1.010ab716792e7p+0",
        "0x1.fd54a80b9e438p-1",
        "0x1.0144bf80c4027p+0",
    ),
    "0x1.2a6355276d003p+0",
    (
        ("0x1.4d4cf998dc8fap-5", "0x1.0336d81ded70dp-5", "-0x1.d0ef787872107p-6"),
        ("0x1.6123252c08e8dp-7", "0x1.2d01dd91bcf75p-5", "0x1.8b9dc9608ceb4p-5"),
    ),
    (
        ("-0x1.e7091a8fec9b4p-6", "-0x1.5dbc91c4e6b74p-8"),
        ("0x1.d4a0416b02887p-7", "0x1.8c5d7437a5ed2p-5"),
    ),
)


def fig1_data() -> dict[str, Any]:
    return yaml.safe_load(FIG1.read_text())


@pytest.fixture(scope="module")
def fig1() -> DeviceFamily:
    return family_from_dict(fig1_data(), name="fig1")


def made_parameters(scene: Scene) -> dict[str, float]:
    """fig1's six parameters read back from a built scene's geometry."""
    theta = scene.starts["open_leading"][2]
    pin_x, pin_y, pin_r = scene.obstacles.circles[0]
    y_top = scene.bounds[3]  # 2.2 + 4 sin(theta) + chute_width cos(theta)
    return {
        "theta": theta,
        "chute_width": (y_top - 2.2 - 4.0 * math.sin(theta)) / math.cos(theta),
        "exit_width": 2.0 * scene.goal.x_max,
        "pin_x": float(pin_x),
        "pin_y": float(pin_y),
        "pin_r": float(pin_r),
    }


def test_the_feeders_draw_is_the_recorded_one_bit_for_bit() -> None:
    for d in (
        draw(Perturbations(), 21, 3),
        draw(Perturbations(), 21, 3, entries=2, parameters=len(PARAMETER_NAMES)),
    ):
        assert tuple(f.hex() for f in d.design_factors) == RECORDED_DRAW[0]
        assert d.friction_factor.hex() == RECORDED_DRAW[1]
        assert tuple(tuple(x.hex() for x in o) for o in d.entry_offsets) == RECORDED_DRAW[2]
        assert tuple(tuple(x.hex() for x in v) for v in d.entry_velocities) == RECORDED_DRAW[3]


def test_a_draw_has_one_factor_per_parameter_and_its_first_factors_do_not_depend_on_n() -> None:
    twelve = draw(Perturbations(), 5, 7)
    for n in (0, 1, 6, 20):
        d = draw(Perturbations(), 5, 7, parameters=n)
        assert len(d.design_factors) == n
        k = min(n, 12)
        assert d.design_factors[:k] == twelve.design_factors[:k]
    with pytest.raises(ValueError, match="parameters"):
        draw(Perturbations(), 5, 7, parameters=-1)


def test_toleranced_values_with_the_physical_bounds_is_the_feeders_toleranced() -> None:
    design = preset("table3")
    low = [PHYSICAL_BOUNDS[n][0] for n in PARAMETER_NAMES]
    high = [PHYSICAL_BOUNDS[n][1] for n in PARAMETER_NAMES]
    for index in range(5):
        factors = draw(Perturbations(tolerance=0.1), 2, index).design_factors
        made = toleranced_values(list(design.to_vector()), factors, low, high)
        assert made == tuple(toleranced(design, factors).to_vector())
    assert toleranced_values([2.0, -1.0, 0.0], [1.01, 0.99, 1.05]) == (2.02, -0.99, 0.0)
    assert toleranced_values([2.0], [1.5], high=[2.5]) == (2.5,)
    with pytest.raises(ValueError, match="2 factors for 3 values"):
        toleranced_values([1.0, 2.0, 3.0], [1.0, 1.0])


def test_made_devices_perturb_each_parameter_by_its_own_factor_within_tolerance(
    fig1: DeviceFamily,
) -> None:
    tolerance = 0.03
    perturbations = Perturbations(tolerance=tolerance)
    nominal = fig1.values(fig1.default())
    make_scene = made_devices(fig1, fig1.default())
    moved = dict.fromkeys(nominal, 0.0)
    for index in range(8):
        d = draw(perturbations, 4, index, entries=2, parameters=len(nominal))
        scene = make_scene(d)
        made = made_parameters(scene)
        for (name, value), factor in zip(nominal.items(), d.design_factors, strict=True):
            assert made[name] == pytest.approx(value * factor, rel=1e-9, abs=1e-12), name
            assert abs(made[name] / value - 1.0) <= tolerance + 1e-12, name
            moved[name] = max(moved[name], abs(made[name] / value - 1.0))
        assert scene.friction == pytest.approx(fig1.friction * d.friction_factor)
    assert all(m > 0.1 * tolerance for m in moved.values()), moved


def test_friction_and_part_given_replace_the_familys(fig1: DeviceFamily) -> None:
    part = Peg(length=2.0, width=0.6)
    make_scene = made_devices(fig1, fig1.default(), part=part, friction=0.2)
    d = draw(Perturbations(), 0, 0, parameters=6)
    scene = make_scene(d)
    assert scene.part == part
    assert scene.friction == pytest.approx(0.2 * d.friction_factor)


def test_fig1_default_gets_a_verdict_over_its_entries_reproducible_by_seed(
    fig1: DeviceFamily,
) -> None:
    first = family_verdict(fig1, fig1.default(), QUICK, seed=3)
    again = family_verdict(fig1, fig1.values(fig1.default()), QUICK, seed=3)
    assert first.orientations == entry_names(fig1) == ("open_leading", "open_trailing")
    assert first.orientations != ORIENTATIONS
    assert 2 <= len(first.trials) <= 4
    assert first.decision in ("works", "fails", "undecided")
    assert [t.success for t in again.trials] == [t.success for t in first.trials]
    assert [t.outcome for t in again.trials] == [t.outcome for t in first.trials]
    assert set(first.transitions()) == set(entry_names(fig1))
    other = family_verdict(fig1, fig1.default(), QUICK, seed=4)
    assert [t.T for t in other.trials] != [t.T for t in first.trials]


def test_fig1_default_gets_a_screen_over_its_entries_reproducible_by_seed(
    fig1: DeviceFamily,
) -> None:
    screen = family_screen(fig1, fig1.default(), seed=3)
    assert screen.orientations == entry_names(fig1)
    assert screen.total_drops >= 1
    again = family_screen(fig1, fig1.default(), seed=3)
    assert (again.drops, again.successes, again.decision) == (
        screen.drops,
        screen.successes,
        screen.decision,
    )


def test_a_vector_a_rule_refuses_raises_degenerate_design_at_once(fig1: DeviceFamily) -> None:
    values = fig1.values(fig1.default())
    values["pin_x"] = 0.9  # pin_x + pin_r > 1.0: touches the wall below the lip
    with pytest.raises(DegenerateDesign, match="wall below the lip"):
        made_devices(fig1, values)
    with pytest.raises(DegenerateDesign, match="wall below the lip"):
        family_verdict(fig1, values, QUICK)
    with pytest.raises(DegenerateDesign, match="wall below the lip"):
        family_screen(fig1, values)


def test_a_made_device_a_rule_refuses_is_an_unbuildable_trial() -> None:
    data = fig1_data()
    data["rules"].append({"require": "pin_r <= 0.25", "reason": "pin B is stock of 0.25 at most"})
    family = family_from_dict(data, name="stock pin")  # default pin_r = 0.25: on the edge
    make_scene = made_devices(family, family.default())
    orientations = entry_names(family)
    unbuildable = []
    for index in range(8):
        trial = run_trial(make_scene, orientations, QUICK, 9, index)
        factor = draw(QUICK.perturbations, 9, index, len(orientations)).design_factors[5]
        refused = 0.25 * factor > 0.25
        assert (trial.outcome == (UNBUILDABLE, UNBUILDABLE)) == refused, index
        if refused:
            assert trial.success == (False, False)
            assert all(math.isnan(t) for t in trial.T)
        unbuildable.append(refused)
    assert any(unbuildable) and not all(unbuildable)


def test_a_family_of_more_parameters_than_the_feeders_gets_a_factor_for_each() -> None:
    """A family's draw has one design factor per parameter, however many (13 here, one more
    than the feeder's 12), and its verdict runs on them."""
    data = fig1_data()
    for k in range(7):  # 6 + 7 = 13 parameters
        data["parameters"][f"spare{k}"] = {"low": 0.0, "high": 1.0, "default": 0.5}
    family = family_from_dict(data, name="thirteen")
    assert len(draw(Perturbations(), 1, 0, 2, parameters=13).design_factors) == 13
    verdict = family_verdict(family, np.asarray(family.default()), QUICK, seed=1)
    assert verdict.orientations == entry_names(family) and 2 <= len(verdict.trials) <= 4


def test_the_pages_verdict_example_runs_as_written(capsys: pytest.CaptureFixture[str]) -> None:
    """docs/families.md, "The verdict of a family": its python block runs from the repository
    root and prints what the page says it prints."""
    page = FIG1.parents[2] / "docs" / "families.md"
    section = page.read_text().split("## The verdict of a family", 1)[1]
    block = re.search(r"^```python\n(.*?)^```", section, re.MULTILINE | re.DOTALL)
    assert block is not None
    code = block.group(1).replace('"feeders/families/fig1.yaml"', repr(str(FIG1)))
    exec(compile(code, str(page), "exec"), {"__name__": "families_page"})
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "fails ('open_leading', 'open_trailing')"
    assert lines[1].startswith("open_leading 0 of 10")
    assert lines[2].startswith("open_trailing 10 of 10")
    assert lines[3] == "fails"
