"""``partfeeder bench --part``: a step's cost for the cup (three pieces) against the peg (issue
24). What is checked is that the numbers are the drops' own (steps counted from the runs, the
contact share a share, the ratio the ratio of the medians) and that bad input is refused before
any drop, never a time."""

from __future__ import annotations

import json

import pytest

from experiments.bench.part_cost import format_part_cost, part_cost
from experiments.cli import run


def test_both_parts_are_dropped_and_the_ratio_is_of_their_medians() -> None:
    results = part_cost(trials=2, seed=1)
    assert results["cup"]["device"] == "fig1-cup default"
    assert results["peg"]["device"] == "table3"
    for name in ("cup", "peg"):
        r = results[name]
        assert r["us_per_step"] > 0.0 and r["steps"] > 1000  # two trials of two drops
        assert 0.0 < r["contact_share"] < 1.0
    assert results["ratio"] == pytest.approx(
        results["cup"]["us_per_step"] / results["peg"]["us_per_step"]
    )
    assert "cup / peg" in format_part_cost(results)


def test_the_cli_prints_the_numbers_as_json(capsys) -> None:
    assert run(["bench", "--part", "1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["trials"] == 1 and set(data) >= {"cup", "peg", "ratio"}


@pytest.mark.parametrize(
    ("argv", "says"),
    [(["--part", "0"], "--part = 0"), (["--part", "3", "--seed", "0"], "--seed = 0")],
)
def test_bad_input_is_one_line_and_exit_2(argv, says, capsys, monkeypatch) -> None:
    def stand_in(*args, **kwargs):
        raise AssertionError("a drop ran before the arguments were checked")

    monkeypatch.setattr("experiments.bench.part_cost.part_cost", stand_in)
    assert run(["bench", *argv]) == 2
    out, err = capsys.readouterr()
    assert out == "" and says in err and len(err.strip().splitlines()) == 1
