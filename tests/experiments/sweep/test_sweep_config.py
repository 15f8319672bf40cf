"""Experiment configs: what is accepted, and errors that name the field and the allowed range."""

from __future__ import annotations

import copy

import pytest
from sweep_fixtures import TINY

from experiments.sweep.config import ConfigError, config_from_dict


def _with(path: str, value) -> dict:
    data = copy.deepcopy(TINY)
    *parents, last = path.split(".")
    node = data
    for key in parents:
        node = node[int(key)] if key.isdigit() else node[key]
    if value is KeyError:
        del node[last]
    else:
        node[int(last) if last.isdigit() else last] = value
    return data


@pytest.mark.parametrize(
    ("path", "value", "message"),
    [
        ("designs.count", -3, "designs.count = -3 is outside the allowed range [1, "),
        ("designs.count", 2.5, "designs.count: expected an integer"),
        ("holdout.fraction", 1.5, "holdout.fraction = 1.5 is outside the allowed range [0, 1]"),
        ("ladder.0.planners", ["rrt", "prm"], "ladder[0].planners[1] = 'prm'; allowed: rrt"),
        ("ladder.0.planners", ["rrt", "rrt"], "names a planner twice"),
        ("ladder.1.runs", 0, "ladder[1].runs = 0 is outside the allowed range [1, 1000]"),
        ("ladder.2.budget", {}, "ladder[2].budget: give 'time'"),
        ("ladder.2.budget", {"time": -1}, "ladder[2].budget.time = -1.0 is outside"),
        ("ladder.0.budget", {"minutes": 1}, "ladder[0].budget: unknown key(s) ['minutes']"),
        ("feeder.friction", 20, "feeder.friction = 20.0 is outside the allowed range [0, 10]"),
        ("feeder.inputs", {"max_force": -1}, "inputs.max_force = -1.0 is outside"),
        ("workers", 0, "workers = 0 is outside the allowed range [1, 1024]"),
        ("colour", "red", "config: unknown key(s) ['colour']"),
        ("designs.count", KeyError, "designs.count is required"),
    ],
)
def test_a_bad_field_is_named_with_its_allowed_range(path: str, value, message: str) -> None:
    with pytest.raises(ConfigError) as error:
        config_from_dict(_with(path, value))
    assert message in str(error.value)


def test_the_ladder_climbs_in_order_and_names_each_level_once() -> None:
    data = copy.deepcopy(TINY)
    data["ladder"] = [data["ladder"][1], data["ladder"][0]]
    with pytest.raises(ConfigError, match="must climb the planning levels in order"):
        config_from_dict(data)
    data["ladder"] = [TINY["ladder"][0], TINY["ladder"][0]]
    with pytest.raises(ConfigError, match="has a level twice"):
        config_from_dict(data)


def test_a_ladder_may_skip_levels() -> None:
    data = copy.deepcopy(TINY)
    data["ladder"] = [TINY["ladder"][0], TINY["ladder"][2]]
    assert [r.level for r in config_from_dict(data).ladder] == ["geometric", "dynamic"]


def test_the_results_key_follows_what_decides_results_not_how_fast_they_come() -> None:
    base = config_from_dict(TINY)
    assert config_from_dict({**TINY, "workers": 7}).results_key() == base.results_key()
    assert config_from_dict({**TINY, "name": "x"}).results_key() == base.results_key()
    other = {**TINY, "designs": {"count": 6, "seed": 2}}
    assert config_from_dict(other).results_key() != base.results_key()
    assert config_from_dict(base.to_dict()) == base  # to_dict round-trips
