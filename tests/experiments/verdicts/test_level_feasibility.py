"""Feasibility of Halton designs at two levels: verdicts, agreement, Wilson intervals, the CLI.

Budgets that decide a verdict are counts of propagations, never seconds: a loaded machine
must not flip a verdict (issue 22: a 0.5 s budget failed on a busy 2-core machine). The
seconds given beside them are caps that only a hang reaches."""

from __future__ import annotations

import csv
import dataclasses
import json
from types import SimpleNamespace

import pytest

import experiments.verdicts.feasibility as lf
from experiments.cli import run
from experiments.verdicts.feasibility_figure import feasibility_figure
from feeders.design import PARAMETER_NAMES, preset

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
CAP_S = 600.0  # a cap against a hang; the budgets are the propagations
# table3 at the geometric level, rrt, seed 1, needs about 4,000 propagations per entry;
# Halton design 0's heavy-trailing entry about 62,000 (so it is infeasible within this).
PROPAGATIONS = 20_000


def _verdicts(rows: list[dict]) -> list[tuple]:
    """What must not depend on how jobs were run: position, level and every verdict."""
    return [
        (
            r["index"],
            r["slot"],
            r["level"],
            r["values"],
            r["built"],
            r["feasible"],
            tuple((o["ran"], o["solved"], o["propagations"]) for o in r["orientations"].values()),
        )
        for r in rows
    ]


def _row(index: int, level: str, feasible: bool, slot: int = 0, built: bool = True) -> dict:
    return {
        "index": index,
        "slot": slot,
        "level": level,
        "feasible": feasible,
        "built": built,
        "values": [float(index)] * len(PARAMETER_NAMES),
    }


# --- design_verdict --------------------------------------------------------------------------


def test_table3_is_feasible_at_the_geometric_level():
    values = [float(v) for v in preset("table3").to_vector()]
    row = lf.design_verdict(values, "geometric", "rrt", CAP_S, 1, propagations=PROPAGATIONS)
    assert row["built"] and row["reason"] is None and row["feasible"] is True
    assert row["values"] == values and row["level"] == "geometric" and row["seed"] == 1
    assert row["propagations"] == PROPAGATIONS and row["time_limit_s"] == CAP_S
    for o in lf.ORIENTATIONS:
        entry = row["orientations"][o]
        assert entry["ran"] and entry["solved"] and entry["tree_size"] > 1
        assert 0 < entry["propagations"] <= PROPAGATIONS and entry["time_s"] > 0.0
    assert row["wall_time_s"] > 0.0
    json.dumps(row)  # plain data


def test_degenerate_design_is_not_built_and_infeasible():
    bad = dataclasses.replace(preset("table3"), gy=0.5)  # lip below the cavity floor
    row = lf.design_verdict(list(bad.to_vector()), "dynamic", "rrt", 1.0, 1)
    assert row["built"] is False and row["feasible"] is False
    assert "lip" in row["reason"]
    assert not any(o["ran"] for o in row["orientations"].values())


def test_first_orientation_failing_skips_the_second(monkeypatch):
    import planners.plan

    calls = []

    def unsolved(scene, level, planner, orientation, time_limit, seed, propagations=None):
        calls.append((orientation, propagations))
        return SimpleNamespace(solved=False, time=0.1, tree_size=7, propagations=101)

    monkeypatch.setattr(planners.plan, "plan", unsolved)
    values = list(preset("table3").to_vector())
    row = lf.design_verdict(values, "geometric", "rrt", 1.0, 1, propagations=100)
    assert calls == [("heavy_leading", 100)]
    assert row["feasible"] is False and row["built"] is True
    assert row["orientations"]["heavy_leading"] == {
        "ran": True,
        "solved": False,
        "time_s": 0.1,
        "tree_size": 7,
        "propagations": 101,
    }
    assert row["orientations"]["heavy_trailing"]["ran"] is False


def test_unknown_level_is_refused_even_for_a_degenerate_design():
    bad = dataclasses.replace(preset("table3"), gy=0.5)
    with pytest.raises(ValueError, match=r"levels: .*geometric"):
        lf.design_verdict(list(bad.to_vector()), "nosuch", "rrt", 1.0, 1)


# --- agreement and Wilson intervals ----------------------------------------------------------


def test_wilson_interval_matches_a_hand_worked_value():
    low, high = lf.wilson_interval(8, 10)
    assert low == pytest.approx(0.4902, abs=1e-4) and high == pytest.approx(0.9433, abs=1e-4)
    assert lf.wilson_interval(0, 10)[0] == 0.0 and lf.wilson_interval(0, 10)[1] > 0.0
    assert lf.wilson_interval(10, 10)[1] == pytest.approx(1.0)
    assert lf.wilson_interval(0, 0) == (0.0, 1.0)
    lo, hi = lf.wilson_interval(3, 10)  # symmetric: k of n mirrors n - k of n
    assert lo == pytest.approx(1 - lf.wilson_interval(7, 10)[1])
    assert hi == pytest.approx(1 - lf.wilson_interval(7, 10)[0])
    with pytest.raises(ValueError):
        lf.wilson_interval(11, 10)


def test_agreement_counts_exceptions_and_intervals():
    # 10 designs: a feasible on 0-7 (8/10), b feasible on 0-5 and 8 (7/10).
    rows = []
    for i in range(10):
        rows.append(_row(i, "kin", i < 8, slot=0, built=i != 9))
        rows.append(_row(i, "geo", i < 6 or i == 8, slot=1, built=i != 9))
    rows.reverse()  # completion order must not matter
    g = lf.agreement(rows, "kin", "geo")
    assert g["designs"] == 10 and g["unpaired"] == 0 and g["unbuilt"] == 1
    assert g["counts"] == {"both": 6, "a_only": 2, "b_only": 1, "neither": 1}
    assert g["subset_holds"] is False
    assert [e["index"] for e in g["exceptions"]] == [6, 7]
    assert g["exceptions"][0]["values"] == [6.0] * 12 and g["exceptions"][0]["design"]["a"] == 6.0
    assert g["fraction_a"]["feasible"] == 8 and g["fraction_a"]["fraction"] == 0.8
    assert g["fraction_a"]["ci95"] == pytest.approx([0.4902, 0.9433], abs=1e-4)
    assert g["fraction_b"]["fraction"] == 0.7
    assert g["fraction_b"]["ci95"] == pytest.approx(list(lf.wilson_interval(7, 10)))
    # the other way round: b's set within a's fails only at design 8
    back = lf.agreement(rows, "geo", "kin")
    assert back["counts"]["a_only"] == 1 and [e["index"] for e in back["exceptions"]] == [8]


def test_agreement_of_a_level_with_itself_pairs_two_runs_and_skips_unpaired():
    rows = [_row(0, "geo", True, 0), _row(0, "geo", False, 1), _row(1, "geo", True, 0)]
    g = lf.agreement(rows, "geo", "geo")
    assert g["designs"] == 1 and g["unpaired"] == 1
    assert g["counts"] == {"both": 0, "a_only": 1, "b_only": 0, "neither": 0}
    assert lf.agreement([], "a", "b")["fraction_a"] == {
        "feasible": 0,
        "designs": 0,
        "fraction": None,
        "ci95": [0.0, 1.0],
    }


def test_feasibility_figure_from_hand_made_rows(tmp_path):
    rows = [_row(i, "kin", i % 2 == 0, 0, built=i != 3) for i in range(6)]
    rows += [_row(i, "geo", i < 3, 1, built=i != 3) for i in range(6)]
    path = feasibility_figure(rows, "kin", "geo", tmp_path / "f.png", x="gx", y="gy")
    assert path.read_bytes()[:8] == PNG_MAGIC
    with pytest.raises(ValueError, match="unknown design parameter"):
        feasibility_figure(rows, "kin", "geo", tmp_path / "g.png", x="nosuch")


# --- compare_levels --------------------------------------------------------------------------


@pytest.mark.slow  # ~7 s
def test_compare_levels_is_the_same_serial_and_in_worker_processes():
    seen: list[tuple[int, int]] = []
    budget = {"time_limit": CAP_S, "seed": 1, "propagations": PROPAGATIONS}
    serial = lf.compare_levels(
        3, ("geometric",), "rrt", workers=1, progress=lambda r: seen.append(r["index"]), **budget
    )
    pooled = lf.compare_levels(3, ("geometric",), "rrt", workers=2, **budget)
    assert [r["index"] for r in serial] == [0, 1, 2] and sorted(seen) == [0, 1, 2]
    assert _verdicts(serial) == _verdicts(pooled)
    # both verdicts occur, so the comparison could fail: design 0 runs out of propagations
    assert [r["feasible"] for r in serial] == [False, True, True]
    assert serial[0]["values"] == pytest.approx(list(lf.halton_points(3, 1)[0]))


def test_compare_levels_refuses_bad_arguments():
    with pytest.raises(ValueError, match="levels: "):
        lf.compare_levels(1, ("geometric", "nosuch"))
    with pytest.raises(ValueError, match="n = 0"):
        lf.compare_levels(0, ("geometric",))
    with pytest.raises(ValueError, match="workers"):
        lf.compare_levels(1, ("geometric",), workers=0)
    with pytest.raises(ValueError, match="planners: "):
        lf.compare_levels(1, ("geometric",), planner="nosuch")
    with pytest.raises(ValueError, match="propagations = 0"):
        lf.compare_levels(1, ("geometric",), propagations=0)


# --- CLI -------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("args", "flag", "detail"),
    [
        (["--levels", "geometric,nosuch"], "--levels", "geometric"),
        (["--levels", "geometric"], "--levels", "two level names"),
        (["--designs", "0"], "--designs", "[1, 1000000]"),
        (["--time", "0"], "--time", "(0, 3600]"),
        (["--time", "4000"], "--time", "(0, 3600]"),
        (["--workers", "0"], "--workers", "[1, 1024]"),
        (["--planner", "nosuch"], "--planner", "rrt"),
        (["--seed", "0"], "--seed", "[1, "),
        (["--propagations", "0"], "--propagations", "[1, 1000000000]"),
        (["--propagations", "20", "--time", "0"], "--time", "(0, 3600]"),
    ],
)
def test_cli_rejects_bad_input_naming_the_flag(args, flag, detail, capsys):
    base = ["feasibility", "--levels", "geometric,dynamic", "--designs", "1", "--workers", "1"]
    assert run([*base, *args]) == 2
    err = capsys.readouterr().err
    assert flag in err and detail in err


def test_cli_tiny_run_writes_rows_figure_and_summary(tmp_path, capsys):
    out = tmp_path / "out"
    args = ["feasibility", "--designs", "2", "--levels", "geometric,geometric"]
    assert run([*args, "--propagations", "5000", "--workers", "1", "--out", str(out)]) == 0
    stdout = capsys.readouterr().out
    assert "95% CI" in stdout and "geometric (run 2)" in stdout
    assert "5000 propagations (cap 600 s) per orientation" in stdout
    lines = (out / "feasibility_rows.jsonl").read_text().splitlines()
    assert len(lines) == 4
    rows = json.loads((out / "feasibility_rows.json").read_text())
    assert [(r["index"], r["slot"]) for r in rows] == [(0, 0), (0, 1), (1, 0), (1, 1)]
    with (out / "feasibility_rows.csv").open() as f:
        table = list(csv.DictReader(f))
    assert len(table) == 4 and table[0]["level"] == "geometric" and "theta" in table[0]
    assert (out / "feasibility.png").read_bytes()[:8] == PNG_MAGIC
    summary = json.loads((out / "feasibility_summary.json").read_text())
    assert summary["agreement"]["designs"] == 2
    assert summary["settings"]["levels"] == ["geometric", "geometric"]
    assert summary["settings"]["propagations"] == 5000 and summary["settings"]["time_s"] == 600
    # a count budget: the level agrees with itself, design by design
    assert summary["agreement"]["counts"]["a_only"] == summary["agreement"]["counts"]["b_only"] == 0
    assert all(r["orientations"]["heavy_leading"]["propagations"] <= 5000 for r in rows)


def test_cli_help_names_the_propagation_budget(capsys):
    with pytest.raises(SystemExit):
        run(["feasibility", "--help"])
    assert "--propagations" in capsys.readouterr().out


def test_cli_keeps_finished_rows_when_a_job_fails(tmp_path, monkeypatch):
    real = lf.design_verdict
    calls = []

    def fails_second(*args):
        calls.append(args)
        if len(calls) == 2:
            raise RuntimeError("boom")
        return real(*args)

    monkeypatch.setattr(lf, "design_verdict", fails_second)
    out = tmp_path / "out"
    args = ["feasibility", "--designs", "2", "--levels", "geometric,dynamic"]
    args += ["--propagations", "2000"]
    with pytest.raises(RuntimeError, match="boom"):
        run([*args, "--workers", "1", "--out", str(out)])
    lines = (out / "feasibility_rows.jsonl").read_text().splitlines()
    assert len(lines) == 1 and json.loads(lines[0])["level"] == "geometric"
