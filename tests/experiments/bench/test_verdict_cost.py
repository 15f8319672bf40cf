"""``partfeeder bench --verdict``: the full verdict alone against the screened one on the same
designs, in one run (issue 21). Numbers are measured, not asserted: these check what is
reported and that the decisions are the procedures' own."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from experiments.bench.verdict_cost import PROCEDURES, format_verdict_cost, verdict_cost


def test_every_procedure_is_timed_on_the_same_buildable_designs():
    results = verdict_cost(designs=6, seed=0)
    assert results["buildable"] <= 6 and set(results["procedures"]) == set(PROCEDURES)
    for v in results["procedures"].values():
        assert v["total_s"] > 0.0
        assert math.isclose(v["mean_s"] * results["buildable"], v["total_s"])
    # the screen only fails designs: the screened pipeline calls no design working that the
    # SPRT verdict alone does not
    procedures = results["procedures"]
    assert procedures["screen + sprt"]["works"] <= procedures["sprt"]["works"]
    for name, ratio in results["ratios"].items():
        low, high = ratio["ci"]
        assert low <= ratio["value"] <= high, name
    text = format_verdict_cost(results)
    assert "wilson / screen + sprt" in text and "sprt / screen + sprt" in text


@pytest.mark.slow  # ~5 s
def test_a_disagreement_is_listed_with_both_decisions():
    results = verdict_cost(designs=6, seed=0)
    for row in results["disagreements"]:
        assert row["wilson"] != row["screen + sprt"]


def test_a_bad_count_is_one_line_and_exit_2():
    done = subprocess.run(
        [sys.executable, "-m", "experiments.cli", "bench", "--verdict", "0"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 2
    assert "--verdict" in done.stderr and len(done.stderr.strip().splitlines()) == 1
