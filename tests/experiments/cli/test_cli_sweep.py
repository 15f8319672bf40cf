"""``partfeeder run`` and ``partfeeder report`` as a user meets them: a summary table or JSON,
the report and OMPL's database on disk, nothing else on stderr, and one clear line for bad input.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml
from cli_process import noise, run_cli
from sweep_fixtures import TINY

from experiments.sweep.config import load_config

_cli = run_cli


def _config(tmp_path: Path, **changes) -> Path:
    path = tmp_path / "tiny.yaml"
    path.write_text(yaml.safe_dump({**TINY, **changes}))
    return path


@pytest.mark.slow  # ~55 s
def test_run_prints_json_and_writes_report_results_and_ompl_database(tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    proc = _cli("run", str(_config(tmp_path)), "--out", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    assert noise(proc.stderr) == ""  # no progress bars off a terminal, no OMPL log, no leak report
    summary = json.loads(proc.stdout)
    assert [lv["level"] for lv in summary["levels"]] == ["geometric", "kinematic", "dynamic"]
    assert summary["levels"][0]["evaluated"] == 6
    for key in ("results", "ompl_database", "report"):
        assert Path(summary["files"][key]).exists()
    assert json.loads((out / "summary.json").read_text())["levels"] == summary["levels"]
    # the report is made again from the directory alone
    again = _cli("report", str(out), "--json")
    assert again.returncode == 0, again.stderr
    assert json.loads(again.stdout)["levels"] == summary["levels"]


def test_a_bad_config_is_one_line_naming_the_field_and_the_allowed_values(tmp_path: Path) -> None:
    ladder = [dict(TINY["ladder"][0]), {**TINY["ladder"][1], "level": "physics"}]
    proc = _cli("run", str(_config(tmp_path, ladder=ladder)), "--out", str(tmp_path / "s"))
    assert proc.returncode == 2
    assert "ladder[1].level = 'physics'" in proc.stderr
    assert "geometric, kinematic, dynamic" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    count = _config(tmp_path, designs={"count": 0, "seed": 1})
    proc = _cli("run", str(count), "--out", str(tmp_path / "s"))
    assert proc.returncode == 2 and "designs.count = 0" in proc.stderr and "[1, " in proc.stderr


@pytest.mark.slow  # ~20 s
def test_a_directory_of_another_config_is_refused_and_kept(tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    first = _config(tmp_path, designs={"count": 1, "seed": 1})
    assert _cli("run", str(first), "--out", str(out), "--no-report").returncode == 0
    before = (out / "results.sqlite").read_bytes()
    other = _config(tmp_path, designs={"count": 1, "seed": 2})
    proc = _cli("run", str(other), "--out", str(out))
    assert proc.returncode == 2 and "another config" in proc.stderr
    assert (out / "results.sqlite").read_bytes() == before


def test_report_of_a_directory_without_a_sweep_says_so(tmp_path: Path) -> None:
    proc = _cli("report", str(tmp_path))
    assert proc.returncode == 2 and "no results.sqlite" in proc.stderr


def test_the_shipped_configs_load_and_climb_the_whole_ladder() -> None:
    """The default puts the screen and then the passive verdict first (stops only on tests
    with stated errors, docs/verdict.md); the paper's config climbs the paper's order with
    the verdict on top."""
    planning = ["geometric", "kinematic", "dynamic"]
    expected = {"default": ["screen", "passive", *planning], "paper": [*planning, "passive"]}
    for name, ladder in expected.items():
        config = load_config(name)
        assert [r.level for r in config.ladder] == ladder
        assert config.holdout_fraction > 0
