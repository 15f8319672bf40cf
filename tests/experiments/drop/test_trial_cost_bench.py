"""``partfeeder bench --trial``: the cost of one verdict trial and its parts (issue 21), as a
reproducible number. What is checked is the report's shape and that bad input is refused
before any trial runs, never a time."""

from __future__ import annotations

import json

import pytest

from experiments.bench.trial_cost import PARTS, format_trial_cost, trial_cost
from experiments.cli import run


def test_every_part_of_a_trial_is_timed_and_the_shares_of_their_sum_add_up() -> None:
    """Issue 39: medians of parts as shares of the whole's median printed "drops 59.9 ms
    114.0%" of a 52.5 ms trial. The parts' means add up: each share is of their sum."""
    results = trial_cost("table3", trials=3, seed=1)
    assert results["trials"] == 3 and results["trial_ms"] > 0.0
    assert results["trial_mean_ms"] > 0.0
    assert tuple(results["parts"]) == PARTS
    parts = results["parts"].values()
    assert results["parts_ms"] == pytest.approx(sum(p["ms"] for p in parts))
    for part in parts:
        assert part["ms"] > 0.0 and part["median_ms"] > 0.0
        assert part["share"] == pytest.approx(part["ms"] / results["parts_ms"])
        assert 0.0 < part["share"] < 1.0
    assert sum(p["share"] for p in parts) == pytest.approx(1.0)
    text = format_trial_cost(results)
    assert "table3" in text and all(p in text for p in PARTS)
    assert "share of the parts' sum" in text


def test_the_printed_shares_add_up_to_100_percent() -> None:
    # a trial whose parts ran slower than the timed whole (a busy machine): shares stay <= 100%
    results = {
        "design": "table3",
        "trials": 200,
        "seed": 0,
        "trial_ms": 52.5,
        "trial_mean_ms": 53.0,
        "parts_ms": 64.0,
        "parts": {
            "draw": {"ms": 0.5, "median_ms": 0.4, "share": 0.5 / 64},
            "made feeder": {"ms": 1.5, "median_ms": 1.4, "share": 1.5 / 64},
            "level": {"ms": 2.0, "median_ms": 1.9, "share": 2.0 / 64},
            "drops": {"ms": 60.0, "median_ms": 59.9, "share": 60.0 / 64},
        },
    }
    lines = format_trial_cost(results).splitlines()
    shares = [float(line.split("%")[0].split()[-1]) for line in lines[2:]]
    assert sum(shares) == pytest.approx(100.0, abs=0.2)
    assert "drops" in lines[-1] and "93.8%" in lines[-1] and "(median 59.900 ms)" in lines[-1]


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
