"""``partfeeder bench --trial``: the cost of one verdict trial and its parts (issue 21), as a
reproducible number. What is checked is the report's shape and that bad input is refused
before any trial runs, never a time."""

from __future__ import annotations

import json

import pytest

from experiments.bench.trial_cost import PARTS, format_trial_cost, trial_cost
from experiments.cli import run


def test_every_part_of_a_trial_is_timed_and_its_share_is_of_the_whole_trial() -> None:
    results = trial_cost("table3", trials=3, seed=1)
    assert results["trials"] == 3 and results["trial_ms"] > 0.0
    assert tuple(results["parts"]) == PARTS
    for part in results["parts"].values():
        assert part["ms"] > 0.0
        assert part["share"] == pytest.approx(part["ms"] / results["trial_ms"])
    text = format_trial_cost(results)
    assert "table3" in text and all(p in text for p in PARTS)


def test_the_cli_prints_the_numbers_as_json(capsys) -> None:
    assert run(["bench", "--trial", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["design"] == "table3" and data["trials"] == 2


@pytest.mark.parametrize(
    ("argv", "says"),
    [(["--trial", "0"], "--trial = 0"), (["--trial", "3", "--seed", "0"], "--seed = 0")],
)
def test_bad_input_is_one_line_and_exit_2(argv, says, capsys, monkeypatch) -> None:
    def stand_in(*args, **kwargs):
        raise AssertionError("a trial ran before the arguments were checked")

    monkeypatch.setattr("experiments.bench.trial_cost.trial_cost", stand_in)
    assert run(["bench", *argv]) == 2
    out, err = capsys.readouterr()
    assert out == "" and says in err and len(err.strip().splitlines()) == 1
