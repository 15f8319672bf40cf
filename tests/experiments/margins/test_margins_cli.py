"""``partfeeder margins``: the JSON a script reads (every axis, its interval inside its box
around the nominal, the cost), the chart and the JSON file with ``--out``, and the verdict
alone for a design that does not work."""

from __future__ import annotations

import json

import pytest
from cli_process import noise, run_cli

from experiments.margins.axes import AXIS_NAMES

ROW_KEYS = {
    "parameter", "kind", "meaning", "unit", "nominal", "box", "box_source", "interval",
    "nominal_estimate", "low", "high", "trials", "wall_time_s",
}  # fmt: skip
SIDE_KEYS = {
    "limit", "at_box_edge", "edge", "last_inside", "first_outside", "evaluations", "drops",
    "resolution",
}  # fmt: skip


@pytest.mark.slow  # ~25 s
def test_margins_json_schema_and_files(tmp_path):
    done = run_cli(
        "margins", "--design", "table3", "--drops", "1", "--workers", "1", "--json",
        "--out", str(tmp_path / "m"),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert noise(done.stderr) == ""
    data = json.loads(done.stdout)
    assert data["works"] is True and data["design"] == "table3"
    assert [row["parameter"] for row in data["margins"]] == list(AXIS_NAMES)
    for row in data["margins"]:
        assert set(row) == ROW_KEYS
        low, high = row["interval"]
        box_low, box_high = row["box"]
        assert box_low <= low <= row["nominal"] <= high <= box_high
        for side in ("low", "high"):
            assert set(row[side]) == SIDE_KEYS
            assert row[side]["at_box_edge"] == (row[side]["first_outside"] is None)
    assert [r["box_source"] for r in data["margins"]].count("Table 2") == 12
    cost = data["cost"]
    assert cost["drops"] == 2 * cost["trials"] > 0 and cost["wall_time_s"] > 0
    assert sorted(p.rsplit(".", 1)[1] for p in data["files"]) == ["json", "png"]
    written = json.loads((tmp_path / "m" / "margins_table3.json").read_text())
    assert written["margins"] == data["margins"]


def test_a_design_that_does_not_work_prints_its_verdict_and_no_margins():
    done = run_cli("margins", "--design", "fig7a", "--drops", "2", "--workers", "1")
    assert done.returncode == 0, done.stderr
    assert "FAILS" in done.stdout and "no margins" in done.stdout


def test_the_text_of_a_design_with_no_margins_says_what_its_verdict_decided():
    """Issue 39: "does not work" was said of an undecided design too."""
    from experiments.cli.margins import text_table

    def data(decision: str) -> dict:
        verdict = {"drops": 3, "decision": decision, "both": {"p": 1.0, "interval": [0.3, 1]}}
        return {"design": "table3", "seed": 0, "target": 0.9, "verdict": verdict, "works": False}

    assert text_table(data("undecided")).splitlines()[-1] == (
        "the design is undecided (too few trials to tell whether it works at the target) at "
        "nominal: no margins"
    )
    assert text_table(data("fails")).splitlines()[-1] == (
        "the design does not work at nominal: no margins"
    )
