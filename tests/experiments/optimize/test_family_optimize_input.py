"""A family's optimisation config and its ``--from`` sweep (issue 24): ``feeder:`` with a
family is refused in one line naming the field (exit 2 at the command line), as the sweep
refuses it; ``start.presets`` with a family is ``default`` only; ``--from`` takes a sweep of the
same family (its designs that work first, then the failing ones nearest to working) and
refuses one of another device, naming ``--from``."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from cli_process import run_cli

from experiments.cli.optimize import sweep_best_designs
from experiments.cli.usage import UsageError
from experiments.optimize.config import OptimizeConfigError, config_from_dict, load_config
from experiments.optimize.run import start_designs
from experiments.sweep.config import config_from_dict as sweep_config
from experiments.sweep.ladder import run_sweep

METHODS = [{"method": "differential-evolution", "budget": 4, "population": 5}]
FIG1_SWEEP = {
    "name": "tiny-fig1",
    "family": "fig1",
    "designs": {"count": 12, "seed": 1},  # design 11 works (tests/experiments/sweep)
    "ladder": [
        {"level": "screen", "screen": {"max_drops": 20}},
        {
            "level": "passive",
            "verdict": {"target": 0.5, "min_drops": 4, "batch": 2, "max_drops": 6, "t_max": 4.0},
        },
    ],
    "holdout": {"fraction": 0.0, "seed": 7},
    "audit": {"fraction": 1.0, "seed": 11},
    "workers": 2,
}


def test_feeder_with_a_family_is_refused_in_one_line_naming_the_field() -> None:
    with pytest.raises(OptimizeConfigError) as caught:
        config_from_dict({"family": "fig1-cup", "feeder": {"friction": 0.1}, "methods": METHODS})
    message = str(caught.value)
    assert message.startswith("feeder: ['friction'] given with family") and "\n" not in message


def test_a_familys_start_is_its_default_and_a_paper_preset_is_refused() -> None:
    config = config_from_dict({"family": "fig1-cup", "methods": METHODS})
    family = config.device_family()
    assert config.presets == ("default",)
    assert start_designs(config, []) == {"default": [float(v) for v in family.default()]}
    with pytest.raises(OptimizeConfigError, match=r"start\.presets\[0\] = 'table3'; allowed"):
        config_from_dict(
            {"family": "fig1-cup", "start": {"presets": ["table3"]}, "methods": METHODS}
        )


def test_the_family_file_is_found_beside_the_config_and_its_text_keys_the_objective(
    tmp_path: Path,
) -> None:
    packaged = load_config("fig1-cup-optimize")
    (tmp_path / "mine.yaml").write_text(packaged.family_yaml)
    (tmp_path / "opt.yaml").write_text(yaml.safe_dump({"family": "mine.yaml", "methods": METHODS}))
    mine = load_config(tmp_path / "opt.yaml")
    assert mine.family == str((tmp_path / "mine.yaml").resolve())
    same = config_from_dict({"family": "fig1-cup", "methods": METHODS})
    assert mine.objective_key() == same.objective_key()  # the text, not where the file lies
    (tmp_path / "mine.yaml").write_text(packaged.family_yaml + "\n# another text\n")
    assert load_config(tmp_path / "opt.yaml").objective_key() != same.objective_key()


def test_the_shipped_fig1_cup_config_loads() -> None:
    config = load_config("fig1-cup-optimize")
    assert config.device_family().name == "fig1-cup" and config.presets == ("default",)
    assert not config.feeder and config.sweep_best >= 1


def test_feeder_with_a_family_exits_2_at_the_command_line(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(
        yaml.safe_dump({"family": "fig1-cup", "feeder": {"friction": 0.1}, "methods": METHODS})
    )
    done = run_cli("optimize", str(path), "--out", str(tmp_path / "out"), "--quiet")
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "feeder: ['friction'] given with family" in lines[0]
    assert not (tmp_path / "out" / "evaluations.sqlite").exists()


@pytest.mark.parametrize("baseline", ["table3", "1,2,3"])
def test_a_feeder_baseline_with_a_family_exits_2_at_the_command_line(
    tmp_path: Path, baseline: str
) -> None:
    """``--baseline table3`` (the feeder's preset, also the option's value when not given to
    the feeder) is no design of the family: it is refused, not read as the family's default."""
    path = tmp_path / "cup.yaml"
    path.write_text(yaml.safe_dump({"family": "fig1-cup", "methods": METHODS}))
    done = run_cli(
        "optimize", str(path), "--out", str(tmp_path / "out"), "--quiet", "--baseline", baseline
    )
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and f"--baseline = '{baseline}'" in lines[0] and "default" in lines[0]
    assert not (tmp_path / "out" / "evaluations.sqlite").exists()


@pytest.fixture(scope="module")
def fig1_sweep(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A 12-design sweep of the fig1 family (a few seconds)."""
    out = tmp_path_factory.mktemp("fig1-sweep")
    run_sweep(sweep_config(FIG1_SWEEP), out)
    return out


def test_from_a_sweep_of_the_family_its_working_designs_then_the_nearest_failing(
    fig1_sweep: Path,
) -> None:
    config = config_from_dict({"family": "fig1", "start": {"sweep_best": 3}, "methods": METHODS})
    best = sweep_best_designs(fig1_sweep, config)
    assert best[0]["design_id"] == 11 and best[0]["verdict"]["works"]
    assert len(best) == 3 and not any(b["verdict"]["works"] for b in best[1:])
    both = [b["verdict"]["both"]["p"] for b in best[1:]]
    assert both == sorted(both, reverse=True)
    starts = start_designs(config, best)
    assert list(starts) == ["default", "sweep:11", *(f"sweep:{b['design_id']}" for b in best[1:])]
    assert all(len(v) == len(config.device_family().vector_names) for v in starts.values())


@pytest.mark.parametrize(
    "data, words",
    [
        ({"family": "fig1-cup"}, "device family 'fig1'"),
        ({"feeder": {"friction": 0.05}}, "the 12-parameter feeder (no family:)"),
    ],
)
def test_from_a_sweep_of_another_device_is_refused_naming_from(
    fig1_sweep: Path, data: dict, words: str
) -> None:
    config = config_from_dict({**data, "methods": METHODS})
    with pytest.raises(UsageError) as caught:
        sweep_best_designs(fig1_sweep, config)
    message = str(caught.value)
    assert message.startswith(f"--from '{fig1_sweep}'") and words in message
