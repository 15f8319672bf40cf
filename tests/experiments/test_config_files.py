"""A config by name or by path (:mod:`experiments.config_files`). Issue 39: README's
``partfeeder optimize --from sweep/default``, interrupted, said "run the same command again to
resume"; run again, it exited 2 with "config file 'optimize' is not a regular file", since its
own output folder ``./optimize/`` shadowed the shipped config ``optimize``. A directory is never
a config file, so a bare name that is one here is the shipped config of that name."""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

import pytest

from experiments.cli import entry
from experiments.config_files import CONFIG_DIR, resolve_config, shipped_configs
from experiments.optimize.config import OptimizeConfig, load_config
from experiments.sweep.config import load_config as load_sweep_config


class Captured(Exception):
    """Raised by the stand-in optimiser: the command got as far as optimising."""


def test_a_shipped_name_is_the_shipped_config(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    assert resolve_config("optimize") == CONFIG_DIR / "optimize.yaml"


def test_a_file_of_that_name_here_is_taken_over_the_shipped_one(tmp_path: Path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "optimize").write_text("name: mine\n")
    assert resolve_config("optimize") == Path("optimize")


def test_a_directory_of_a_shipped_configs_name_is_not_taken_for_the_config(
    tmp_path: Path, monkeypatch
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "optimize" / "optimize").mkdir(parents=True)  # optimize's default --out
    (tmp_path / "default").mkdir()  # a sweep's --out default
    assert load_config("optimize") == load_config(CONFIG_DIR / "optimize.yaml")
    assert load_sweep_config("default") == load_sweep_config(CONFIG_DIR / "default.yaml")


def test_a_path_with_a_folder_or_a_suffix_is_never_redirected(tmp_path: Path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "optimize.yaml").mkdir()
    (tmp_path / "optimize").mkdir()
    assert resolve_config("optimize.yaml") == Path("optimize.yaml")
    assert resolve_config(tmp_path / "optimize") == tmp_path / "optimize"


def test_the_readme_optimize_command_run_again_in_the_same_folder_resumes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The same command twice from one folder: the second finds its config (and its output
    folder, optimize/optimize, where the first left its evaluations)."""
    monkeypatch.chdir(tmp_path)
    outs: list[tuple[OptimizeConfig, Path]] = []

    def optimise(config: OptimizeConfig, out: Path, *args: object, **kwargs: object) -> dict:
        outs.append((config, out))
        (out / "evaluations.sqlite").touch()
        raise KeyboardInterrupt  # stopped as by Ctrl-C, after it made its output folder

    monkeypatch.setattr("experiments.optimize.run.optimise", optimise)
    monkeypatch.setattr("experiments.cli.optimize.compile_once", lambda levels: None)
    for _ in range(2):
        assert entry.run(["optimize", "--quiet"]) == 130
        assert "run the same command again to resume" in capsys.readouterr().err
    assert [out for _, out in outs] == [Path("optimize/optimize")] * 2
    assert outs[0][0] == outs[1][0] == load_config(CONFIG_DIR / "optimize.yaml")


def _help(command: str) -> str:
    """``partfeeder COMMAND --help`` as printed, its lines joined (argparse wraps words and
    breaks a name at its hyphen: "ladder-" / "order")."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        entry.run([command, "--help"])
    return " ".join(out.getvalue().split()).replace("- ", "-")


def test_every_shipped_config_is_filed_under_the_command_that_reads_it() -> None:
    configs = shipped_configs()
    listing = sorted(p.stem for p in CONFIG_DIR.glob("*.yaml"))
    assert sorted(configs) == ["optimize", "run"]  # none under "" (no command named)
    assert sorted(configs["run"] + configs["optimize"]) == listing
    for name in configs["run"]:  # each reads as the config of its command
        assert load_sweep_config(name).name
    for name in configs["optimize"]:
        assert load_config(name).name


@pytest.mark.parametrize("command", ["run", "optimize"])
def test_help_names_every_shipped_config(command: str) -> None:
    """Issue 39: ``run --help`` named 2 of the 8 shipped configs (default and paper)."""
    text = _help(command)
    listing = sorted(p.stem for p in CONFIG_DIR.glob("*.yaml"))
    assert len(listing) >= 9 and all(f" {name}" in text for name in listing)
    named = shipped_configs()
    mine = ", ".join(named[command])
    other = "optimize" if command == "run" else "run"
    assert f"shipped one by name: {mine} (for {other}: {', '.join(named[other])})" in text
