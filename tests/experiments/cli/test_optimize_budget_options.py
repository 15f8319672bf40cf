"""``optimize --evaluations N --trials N`` (issue 39): the budget of a run without an edited
copy of the YAML. ``--evaluations`` is every method's budget per seed (with goal robustness,
design centering's), ``--trials`` the trials of each verdict on fresh draws; a value that is
not a positive count in the field's range is one line naming the option, exit status 2."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.cli import entry
from experiments.optimize.config import (
    MAX_BUDGET,
    MAX_TRIALS,
    OptimizeConfig,
    load_config,
    with_budget,
)


class Captured(Exception):
    """Raised by the stand-in optimiser: the config it was given reached it."""


@pytest.fixture
def optimised(monkeypatch: pytest.MonkeyPatch) -> list[OptimizeConfig]:
    """The configs ``optimize`` hands to the optimiser (which then stops: nothing runs)."""
    seen: list[OptimizeConfig] = []

    def optimise(config: OptimizeConfig, *args: object, **kwargs: object) -> dict:
        seen.append(config)
        raise Captured

    monkeypatch.setattr("experiments.optimize.run.optimise", optimise)
    monkeypatch.setattr("experiments.cli.optimize.compile_once", lambda levels: None)
    return seen


def test_evaluations_set_every_methods_budget_and_trials_the_final_verdicts() -> None:
    shipped = load_config("optimize-compare")
    assert len(shipped.methods) > 1
    changed = with_budget(shipped, evaluations=7, trials=9)
    assert [m.budget for m in changed.methods] == [7] * len(shipped.methods)
    assert changed.final_trials == 9
    # the rest of each method and the objective's draws are the config's
    assert [(m.method, m.seeds, m.population) for m in changed.methods] == [
        (m.method, m.seeds, m.population) for m in shipped.methods
    ]
    assert changed.trials == shipped.trials
    assert changed.objective_key() == shipped.objective_key()


def test_evaluations_are_design_centerings_budget_with_goal_robustness() -> None:
    shipped = load_config("robust")
    changed = with_budget(shipped, evaluations=5)
    assert changed.centering.budget == 5 != shipped.centering.budget
    assert changed.final_trials == shipped.final_trials


def test_no_option_keeps_the_configs_budget() -> None:
    shipped = load_config("optimize")
    assert with_budget(shipped) == shipped


def test_the_command_hands_the_optimiser_the_overridden_budget(
    optimised: list[OptimizeConfig], tmp_path: Path
) -> None:
    argv = ["optimize", "--out", str(tmp_path / "o"), "--quiet", "--evaluations", "3"]
    with pytest.raises(Captured):
        entry.run([*argv, "--trials", "4"])
    (config,) = optimised
    assert [m.budget for m in config.methods] == [3]
    assert config.final_trials == 4


@pytest.mark.parametrize(
    ("option", "value", "message"),
    [
        ("--evaluations", "0", f"--evaluations = 0 is outside the allowed range [1, {MAX_BUDGET}]"),
        ("--evaluations", "-5", "--evaluations = -5 is outside the allowed range [1, "),
        ("--trials", "0", f"--trials = 0 is outside the allowed range [1, {MAX_TRIALS}]"),
        ("--trials", str(MAX_TRIALS + 1), f"--trials = {MAX_TRIALS + 1} is outside"),
    ],
)
def test_a_count_out_of_range_is_one_line_naming_the_option(
    optimised: list[OptimizeConfig],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    option: str,
    value: str,
    message: str,
) -> None:
    status = entry.run(["optimize", "--out", str(tmp_path / "o"), option, value])
    err = capsys.readouterr().err
    assert status == 2 and not optimised
    assert err.count("\n") == 1 and message in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(("option", "value"), [("--evaluations", "ten"), ("--trials", "2.5")])
def test_a_value_that_is_not_an_integer_is_one_line_naming_the_option(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str, value: str
) -> None:
    with pytest.raises(SystemExit) as exit_:
        entry.run(["optimize", "--out", str(tmp_path / "o"), option, value])
    err = capsys.readouterr().err
    assert exit_.value.code == 2
    assert err.count("\n") == 1 and f"argument {option}: invalid int value: '{value}'" in err
