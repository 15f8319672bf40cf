"""The planners the comparison names (planners.registry): each a configured OMPL planner
under its own name with its parameters; those OMPL 2.0.1's bindings cannot build say why."""

from __future__ import annotations

import pytest
from ompl import control as oc

from planners import problem
from planners.benchmark import planner_parameters
from planners.registry import CONFIGURED, UNAVAILABLE, PlannerConfig, make_planner


@pytest.fixture(scope="module")
def si():
    return problem("table3", "geometric").si


@pytest.mark.parametrize(
    ("name", "label", "parameters"),
    [
        ("rrt", "RRT", {"goal_bias": "0.05", "intermediate_states": "0"}),
        ("rrt-greedy", "RRT-greedy", {"goal_bias": "0.2", "intermediate_states": "0"}),
        ("rrt-intermediate", "RRT-intermediate", {"goal_bias": "0.05", "intermediate_states": "1"}),
        ("kpiece", "KPIECE1", {"goal_bias": "0.05", "border_fraction": "0.8"}),
        ("est", "EST", {"goal_bias": "0.05"}),
    ],
)
def test_each_configuration_is_its_planner_with_its_parameters(si, name, label, parameters):
    planner = make_planner(name, si)
    assert planner.getName() == label
    assert parameters.items() <= planner_parameters(planner).items()


def test_the_labels_are_distinct_for_one_benchmark() -> None:
    labels = [c.label for c in CONFIGURED.values()]
    assert len(set(labels)) == len(labels)


@pytest.mark.parametrize("name", sorted(UNAVAILABLE))
def test_a_planner_the_bindings_cannot_build_says_why(si, name) -> None:
    with pytest.raises(ValueError, match=f"planner '{name}' cannot run: "):
        make_planner(name, si)


def test_sst_and_pdst_have_no_constructor_in_these_bindings(si) -> None:
    for cls in (oc.SST, oc.PDST):
        with pytest.raises(TypeError):
            cls(si)


def test_a_factory_makes_the_planner_under_the_configurations_label(si) -> None:
    config = PlannerConfig("rrt", "My-EST", "an EST by factory", factory=oc.EST)
    planner = config.make(si)
    assert isinstance(planner, oc.EST) and planner.getName() == "My-EST"
