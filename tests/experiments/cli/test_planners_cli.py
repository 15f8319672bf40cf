"""``partfeeder planners``: bad input is one line naming the option or the config's field,
exit status 2, before any planning."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.cli import run


@pytest.mark.parametrize(
    ("args", "error"),
    [
        (["--runs", "0"], "--runs = 0 is outside the allowed range [1, 1000]"),
        (["--workers", "0"], "--workers = 0 is outside the allowed range [1, 1024]"),
        (["--seed", "0"], "--seed = 0 is outside the allowed range"),
        (["planners", "--quick"], "give a config or --quick, not both"),
        (["/nonexistent/suite.yaml"], "cannot read planner comparison config file"),
        (["--quick", "--out", "/proc/partfeeder-test"], "--out"),
    ],
)
def test_bad_option_is_one_line_and_exit_2(args, error, capsys) -> None:
    assert run(["planners", *args]) == 2
    err = capsys.readouterr().err
    assert error in err and len(err.strip().splitlines()) == 1, err


def test_a_bad_field_of_the_config_is_one_line_naming_it(tmp_path: Path, capsys) -> None:
    config = tmp_path / "suite.yaml"
    config.write_text(
        "name: x\ndesigns: [{preset: table3}]\nplanners: [rrt, sst]\nruns: 1\n"
        "budgets: {geometric: 10, kinematic: 10, dynamic: 10}\n"
    )
    assert run(["planners", str(config)]) == 2
    err = capsys.readouterr().err
    assert "planners[1] = 'sst' cannot run: oc.SST has no constructor" in err
    assert len(err.strip().splitlines()) == 1


def test_a_tiny_comparison_prints_its_table_and_writes_nothing_without_out(
    tmp_path: Path, capsys, monkeypatch
) -> None:
    config = tmp_path / "suite.yaml"
    config.write_text(
        "name: tiny\ndesigns: [{preset: table3}]\nlevels: [dynamic]\n"
        "planners: [rrt, kpiece]\nruns: 1\nbudgets: {dynamic: 100}\nbootstrap: 20\n"
    )
    monkeypatch.chdir(tmp_path)
    assert run(["planners", str(config), "--workers", "1"]) == 0
    out = capsys.readouterr().out
    assert "dynamic: best by the performance profile is" in out or "no ranking" in out
    assert "KPIECE1" in out and "cost: 2 problems planned, 4 runs" in out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["suite.yaml"]
