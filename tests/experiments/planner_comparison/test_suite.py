"""The comparison's config: the shipped suites load, and a bad field is one line naming it
and its allowed range."""

from __future__ import annotations

import pytest

from experiments.planner_comparison.shipped import SUITES
from experiments.planner_comparison.suite import SuiteError, load_suite, suite_from_dict

GOOD = {
    "name": "t",
    "designs": [{"preset": "table3"}],
    "planners": ["rrt", "kpiece"],
    "runs": 2,
    "budgets": {"geometric": 100, "kinematic": 100, "dynamic": 100},
}


@pytest.mark.parametrize("name", ["planners", "planners-quick"])
def test_the_shipped_suites_compare_at_least_five_planners_at_every_level(name) -> None:
    suite = suite_from_dict(SUITES[name])
    assert suite.levels == ("geometric", "kinematic", "dynamic")
    assert len(suite.planners) >= 5
    assert set(suite.budgets) == set(suite.levels)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"runs": 0}, r"runs = 0 is outside the allowed range \[1, 1000\]"),
        ({"planners": ["rrt", "prm"]}, r"planners\[1\] = 'prm': one of rrt"),
        ({"planners": ["sst"]}, r"planners\[0\] = 'sst' cannot run: oc.SST has no constructor"),
        ({"budgets": {"geometric": 100}}, r"budgets: missing the budget of level 'kinematic'"),
        ({"budgets": {"geometric": 0, "kinematic": 1, "dynamic": 1}}, r"budgets.geometric = 0"),
        ({"designs": [{"preset": "fig99"}]}, r"designs\[0\].preset = 'fig99': one of"),
        ({"designs": [{"preset": "fig4", "scene": "x.yaml"}]}, r"designs\[0\]: give exactly one"),
        ({"levels": ["dynamic", "fast"]}, r"levels\[1\] = 'fast': one of geometric"),
        ({"colour": "red"}, r"config: unknown key\(s\) \['colour'\]"),
    ],
)
def test_a_bad_field_is_one_line_naming_it(change, message) -> None:
    with pytest.raises(SuiteError, match=message) as caught:
        suite_from_dict({**GOOD, **change})
    assert "\n" not in str(caught.value)


def test_only_the_suites_levels_need_a_budget() -> None:
    suite = suite_from_dict({**GOOD, "levels": ["dynamic"], "budgets": {"dynamic": 50}})
    assert suite.budgets == {"dynamic": 50}


def test_a_config_file_reads_as_its_mapping(tmp_path) -> None:
    path = tmp_path / "suite.yaml"
    path.write_text(
        "name: t\ndesigns: [{preset: table3}, {scene: my.yaml}]\nplanners: [rrt, kpiece]\n"
        "runs: 2\nbudgets: {geometric: 100, kinematic: 100, dynamic: 100}\n"
    )
    suite = load_suite(path)
    assert suite == suite_from_dict(
        {**GOOD, "designs": [{"preset": "table3"}, {"scene": "my.yaml"}]}, base=tmp_path
    )
    assert suite.base == str(tmp_path)
