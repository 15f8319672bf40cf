"""The agreement suite on a device family (``partfeeder bench --agreement --family``, issue 35)
as a specification.

Its drops must be the family verdict's own: trial i of a design is the verdict's trial i (the
same draw, the same made device, the same starts), so partfeeder's rows are the verdict's
outcomes drop for drop. Designs are named as the family's sweep numbers them. Bad input (a
family that is neither a file nor a packaged one, a design the family cannot take, a rounding
out of range) is one line and exit status 2 before any work. A tiny run in every engine makes
every table with the family's own entries. Skipped without MuJoCo or pymunk.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")
pytest.importorskip("pymunk")

from experiments.bench.agreement.arbiter import chosen_drops
from experiments.bench.agreement.family import (
    FamilySuite,
    family_agreement_data,
    family_design,
    run_family_trial,
)
from experiments.bench.agreement.report import markdown
from experiments.bench.agreement.suite import AgreementSettings
from experiments.cli import run
from experiments.cli.scenes import family_path
from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.verdict import run_trial
from experiments.drop.verdict_settings import VerdictSettings
from feeders.device_family import load_family
from feeders.halton import halton_points

CUP = str(family_path(Path("fig1-cup")))
OPTIMUM = "0.6907,1.2855,1.2213,1.8129,1.1795,0.5437,0.1447,0.4392"  # docs/cup-example.md


def test_designs_are_named_as_the_familys_sweep_numbers_them():
    family = load_family(CUP)
    assert family_design(family, "default").values == tuple(family.default())
    point = halton_points(341, 0, family.space())[340]
    assert family_design(family, "halton:0:340").values == tuple(point)
    assert family_design(family, OPTIMUM).values[0] == 0.6907
    for bad in ("halton:0", "halton:x:1", "1,2,3", "nan,1,1,1,1,1,1,1", "optimum"):
        with pytest.raises(ValueError, match="design"):
            family_design(family, bad)


@pytest.mark.parametrize("index", [0, 1, 5])
@pytest.mark.parametrize("token", ["default", OPTIMUM])
def test_partfeeders_rows_are_the_family_verdicts_trial(token, index):
    family = load_family(CUP)
    design = family_design(family, token)
    settings = AgreementSettings(trials=1, engines=("partfeeder",))
    rows = run_family_trial(family, design, index, FamilySuite(CUP, settings, 1e-3))
    entries = entry_names(family)
    verdict = run_trial(
        made_devices(family, design.values),
        entries,
        VerdictSettings(),
        0,
        index,
        len(family.vector_names),
    )
    assert [r.entry for r in rows] == list(entries)
    assert tuple(r.success for r in rows) == verdict.success
    assert tuple(r.outcome for r in rows) == verdict.outcome
    assert tuple(r.T for r in rows) == pytest.approx(verdict.T)


@pytest.mark.slow  # about 8 s on a loaded machine: 6 drops, 4 of them in the peers
def test_a_tiny_run_makes_every_table_with_the_familys_entries():
    family = load_family(CUP)
    suite = FamilySuite(CUP, AgreementSettings(trials=1), 1e-3)
    data = family_agreement_data(suite, [family_design(family, OPTIMUM)])
    assert data["family"]["name"] == "fig1-cup"
    rows = data["drops"]
    assert len(rows) == 3 * 2  # three engines, two entries
    starts = {r["entry"]: set() for r in rows}
    for r in rows:
        starts[r["entry"]].add(tuple(np.round(r["start"], 12)))
    assert all(len(s) == 1 for s in starts.values())  # every engine the same start
    text = markdown(data)
    for entry in entry_names(family):
        assert f"| {entry} |" in text
    assert "mujoco vs pymunk" in text and "No lip speed" in text


@pytest.fixture
def no_work(monkeypatch) -> list[str]:
    reached: list[str] = []

    def stand_in(*args, **kwargs):
        reached.append("family_agreement_data")
        raise AssertionError("the suite ran before the arguments were checked")

    monkeypatch.setattr("experiments.bench.agreement.family.family_agreement_data", stand_in)
    return reached


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["--family", "no-such-family"], "--family: 'no-such-family' is neither a file"),
        (["--family", "fig1-cup", "--design", "1,2"], "--design 1,2"),
        (["--family", "fig1-cup", "--design", "halton:0"], "--design halton:0"),
        (["--family", "fig1-cup", "--pymunk-radius", "0.5"], "--pymunk-radius = 0.5"),
        (["--pymunk-radius", "0.002"], "--pymunk-radius needs --family"),
        (["--family", "fig1-cup", "--arbiter", "0"], "--arbiter = '0'"),
        (["--family", "fig1-cup", "--arbiter", "4,x"], "--arbiter = '4,x'"),
        (["--arbiter", "4"], "--arbiter needs --family"),
    ],
)
def test_bad_family_arguments_are_one_line_and_exit_2(capsys, no_work, argv, says):
    assert run(["bench", "--agreement", "--quick", *argv]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("partfeeder bench: error: "), err
    assert says in lines[0]
    assert not no_work


def test_good_family_arguments_reach_the_suite(capsys, no_work):
    with pytest.raises(AssertionError, match="ran before"):
        run(["bench", "--agreement", "--quick", "--family", "fig1-cup", "--design", OPTIMUM])
    assert no_work == ["family_agreement_data"]


def test_the_arbiter_takes_the_disputed_drops_and_a_control_set_where_all_agree():
    def row(design, trial, entry, engine, success):
        return {"design": design, "trial": trial, "entry": entry, "engine": engine,
                "success": success, "start": (0.0,) * 6}  # fmt: skip

    engines = ("partfeeder", "mujoco", "pymunk")
    drops = [row("a", t, "e", e, True) for t in range(5) for e in engines]
    drops[3 * 2 + 1]["success"] = False  # trial 2: MuJoCo alone
    drops[3 * 4 + 0]["success"] = False  # trial 4: partfeeder alone
    unbuilt = [{**row("a", 9, "e", e, False), "start": []} for e in engines]  # not run
    disputed, control = chosen_drops({"drops": drops + unbuilt}, control=3)
    assert disputed == [("a", 2, "e"), ("a", 4, "e")]
    assert control == [("a", 0, "e"), ("a", 1, "e")]
