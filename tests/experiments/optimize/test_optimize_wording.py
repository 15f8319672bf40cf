"""What the optimiser's summary and report say of an optimum that is not a clear winner
(issue 39): an undecided optimum is called undecided, not one that "does not work"; an
optimum that is the baseline itself is said to be, and the report does not draw its outline
over itself."""

from __future__ import annotations

import pytest

from experiments.optimize.config import config_from_dict
from experiments.optimize.report import report_figures, same_design_sentence, summary_text
from experiments.optimize.run import _margins, designed, optimise, same_design
from experiments.report_kit.comparison_section import OVERLAY_PREFIX
from feeders.design import preset

# one evaluation: powell's first point is its start, table3 (through the unit cube and
# back), so the optimum is the baseline table3 itself; 2 fresh trials decide nothing
ONE = {
    "name": "one",
    "feeder": {"friction": 0.05, "restitution": 0.3},
    "objective": {"trials": 2, "seed": 0},
    "start": {"presets": ["table3"]},
    "methods": [{"method": "powell", "budget": 1, "seeds": [0]}],
    "final": {"trials": 2, "seed": 1000, "candidates": 1},
    "workers": 2,
}


@pytest.fixture(scope="module")
def one(tmp_path_factory):
    out = tmp_path_factory.mktemp("one")
    config = config_from_dict(ONE)
    return out, config, optimise(config, out)


@pytest.mark.slow  # a real run: about 15 s on 2 cores
def test_an_undecided_optimum_is_called_undecided(one) -> None:
    _, _, results = one
    assert results["optimum"]["verdict"]["decision"] == "undecided"
    assert results["margins"] is None
    assert results["margins_absent"] == (
        "the optimum is undecided (too few trials to tell whether it works at the target) on "
        "its 2 fresh trials, so it has no margins"
    )
    assert "does not work" not in summary_text(results)


@pytest.mark.parametrize(
    ("decision", "said"),
    [
        ("fails", "does not work"),
        ("undecided", "is undecided (too few trials to tell whether it works at the target)"),
    ],
)
def test_an_optimum_with_no_margins_is_said_to_be_what_its_verdict_decided(
    decision: str, said: str
) -> None:
    config = config_from_dict(ONE)
    optimum = {"verdict": {"works": False, "decision": decision, "drops": 40}}
    margins, why = _margins(None, config, optimum, designed(config))
    assert margins is None
    assert why == f"the optimum {said} on its 40 fresh trials, so it has no margins"


@pytest.mark.slow  # a real run: about 15 s on 2 cores
def test_an_optimum_that_is_the_baseline_says_so_and_is_not_drawn_over_itself(one) -> None:
    out, config, results = one
    assert results["optimum_is_baseline"] is True
    assert results["compared_with"] == "table3"
    sentence = "the optimum is the baseline, table3, itself: the search found no better design"
    assert same_design_sentence(results).startswith(sentence)
    assert sentence in summary_text(results)
    figures = report_figures(config, results, out / "figures")
    assert results["comparison"] is not None
    assert not [name for name in figures if name.startswith(OVERLAY_PREFIX)]


@pytest.mark.slow  # a real run: about 15 s on 2 cores
def test_a_different_optimum_is_drawn_over_the_baseline_and_not_called_the_same(
    one, tmp_path
) -> None:
    _, config, results = one
    other = {**results, "optimum_is_baseline": False}
    assert same_design_sentence(other) is None
    figures = report_figures(config, other, tmp_path)
    assert [name for name in figures if name.startswith(OVERLAY_PREFIX)]


def test_the_same_design_is_within_a_billionth_of_each_box_width() -> None:
    space = designed(config_from_dict(ONE))
    table3 = preset("table3").to_vector().tolist()
    moved = list(table3)
    moved[7] = 0.7329999999999999  # gx, as the unit cube gave table3's 0.733 back
    assert same_design(moved, table3, space)
    moved[7] = 0.733 + 1e-6  # a micrometre in a 1.8-wide box: another design
    assert not same_design(moved, table3, space)
