"""What a sweep's report finds beyond its summary (issue 25): the comparison with the baseline
on fresh draws, the recommendation, and the recommended design's tolerance margins, on the
page, in ``summary.json`` and in the printed JSON, kept by the report's cache; and the
margins, most of a report's time, shown as a bar with a fixed total while they run."""

from __future__ import annotations

import argparse
import copy
import io
import json
from pathlib import Path

import pytest
from sweep_fixtures import TINY

from experiments.cli import report as report_cli
from experiments.margins.axes import axes
from experiments.sweep.config import config_from_dict
from experiments.sweep.ladder import run_sweep

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
FIG1_CONFIG = "family: fig1\ndesigns: {count: 2, seed: 1}\nladder: [{level: passive}]\n"


class Terminal(io.StringIO):
    """What a terminal would show: the bar is drawn, not written as log lines."""

    def isatty(self) -> bool:
        return True


def test_the_margins_bar_has_one_step_per_axis_from_the_start() -> None:
    assert report_cli.MARGINS_AXES == len(axes())
    stream = Terminal()
    progress = report_cli.MarginsProgress(quiet=False, stream=stream)
    progress("margins", {"design": "design 3", "axes": report_cli.MARGINS_AXES})
    assert "margins of design 3:   0%|" in stream.getvalue()
    assert f"0/{report_cli.MARGINS_AXES}" in stream.getvalue()
    for axis in axes():
        progress("axis", {"parameter": axis.name})
    progress.close()
    drawn = stream.getvalue()
    assert f"{report_cli.MARGINS_AXES}/{report_cli.MARGINS_AXES}" in drawn
    assert "100%" in drawn and drawn.count("100%") == 1  # only once every axis is done


@pytest.mark.parametrize("stream", [Terminal, io.StringIO], ids=["terminal", "log"])
def test_axes_not_needed_shrink_the_margins_bar_so_it_ends_done_not_stopped(stream) -> None:
    """A design outranked after 2 of its 4 axes, or one that does not work, has axes that are
    never measured: the bar's total drops by them and it ends at 100 %, not "stopped at"
    (issue 39: a log read "stopped at 17/39" of a report that finished)."""
    out = stream()
    progress = report_cli.MarginsProgress(quiet=False, stream=out)
    progress("margins", {"design": "table3, design 3", "axes": 8})
    for name in ("a", "b", "c", "d", "a", "b"):
        progress("axis", {"parameter": name})
    progress("skipped", {"design": "design 3", "axes": 2})
    progress.close()
    drawn = out.getvalue()
    assert "6/6" in drawn and "100%" in drawn and "stopped" not in drawn
    assert "design 3: 2 axes not needed" in drawn


def test_a_quiet_report_draws_no_margins_bar() -> None:
    stream = io.StringIO()
    progress = report_cli.MarginsProgress(quiet=True, stream=stream)
    progress("margins", {"design": "design 3", "axes": 16})
    progress("axis", {"parameter": "a"})
    progress.close()
    assert stream.getvalue() == ""


@pytest.mark.slow  # about 70 s on 2 busy cores: a sweep, 160 fresh trials, 16 axes' margins
def test_a_sweep_report_recommends_a_confirmed_design_with_its_margins(tmp_path, capsys):
    data = {
        **copy.deepcopy(TINY),
        "designs": {"count": 4, "seed": 0},  # design 3 works (the default sweep)
        "feeder": {"friction": 0.05},
        "ladder": [
            {
                "level": "passive",
                "verdict": {"target": 0.0, "min_drops": 2, "batch": 2, "max_drops": 2},
            }
        ],
        "holdout": {"fraction": 0.0, "seed": 7},
    }
    out = tmp_path / "sweep"
    run_sweep(config_from_dict(data), out)
    args = argparse.Namespace(json=True, no_report=False, quiet=True, baseline="table3", workers=2)
    assert report_cli.finish(out, args, {}) == 0
    printed = json.loads(capsys.readouterr().out)
    written = json.loads((out / "summary.json").read_text())
    recommendation = written["recommendation"]
    # issue 34: a confirmed design is built only when more reliable than table3 or more robust
    # beyond the margins' resolution; otherwise table3 is kept, the design contending beside it
    assert recommendation["confirmed"]
    kept = recommendation["decision"] == "keep the baseline"
    if kept:
        assert recommendation["label"] == "table3"
        other = recommendation["contender"]
    else:
        assert recommendation["decision"] == "build"
        assert recommendation["label"].startswith("design ")
        other = "table3"
    assert recommendation["contender"] == recommendation["ranking"][0]
    margins = written["margins"]
    assert margins["design"] == recommendation["label"] and margins["works"]
    device_axes = [a for a in axes() if a.kind in ("design", "friction")]
    assert len(margins["margins"]) == len(device_axes) and margins["target"] == 0.0
    assert written["baseline_margins"]["design"] == other
    assert written["comparison"]["baseline"]["label"] == "table3"
    shown = ("comparison", "recommendation", "margins", "baseline_margins")
    assert {k: printed[k] for k in shown} == {k: written[k] for k in shown}
    page = (out / "report.html").read_text(encoding="utf-8")
    title = "Keep the baseline, table3" if kept else f"Build {recommendation['label']}"
    assert title in page
    assert (
        f"How much tolerance it has: the margins of {recommendation['label']} beside {other}'s"
        in page
    )
    assert 'src="figures/margins.png"' in page
    assert (out / "figures" / "margins.png").read_bytes()[:8] == PNG_MAGIC
    drawn = (out / "report.html").stat().st_mtime_ns
    assert report_cli.finish(out, args, {}) == 0  # cached: nothing computed or drawn again
    assert json.loads(capsys.readouterr().out)["margins"] == margins
    assert (out / "report.html").stat().st_mtime_ns == drawn


def test_report_refuses_a_bad_baseline_in_one_line(tmp_path: Path) -> None:
    from experiments.cli.usage import UsageError

    args = argparse.Namespace(dir=tmp_path, json=False, baseline="table4", workers=None)
    with pytest.raises(UsageError, match="--baseline"):
        report_cli.run(args)


def test_run_refuses_a_bad_baseline_before_any_work() -> None:
    """Three numbers could be a device family's baseline: the config says what is designed
    (here the feeder, which takes 12), and the refusal comes before the sweep."""
    from experiments.cli import run_sweep
    from experiments.cli.usage import UsageError

    args = argparse.Namespace(
        executor="local", scheduler=None, baseline="1,2,3", config="default", workers=None
    )
    args.designs = None
    with pytest.raises(UsageError, match="--baseline"):
        run_sweep.run(args)


@pytest.mark.parametrize(
    ("config", "baseline", "allowed"),
    [
        ("default", "default", "--baseline: "),  # the feeder has no 'default' design
        ("fig1-family", "table3", "allowed with family fig1: default, or 6 comma-separated"),
        ("fig1-family", "1,2,3", "allowed with family fig1: default, or 6 comma-separated"),
    ],
)
def test_run_reads_the_baseline_as_the_config_designs_it(
    tmp_path: Path, config: str, baseline: str, allowed: str
) -> None:
    """``--baseline`` of a family sweep is ``default`` or the family's values (as the
    optimiser reads it); the feeder's presets and 12 values are not a family's, nor is
    ``default`` the feeder's. Refused in one line before the sweep writes anything."""
    from experiments.cli import run_sweep
    from experiments.cli.usage import UsageError

    if config == "fig1-family":
        (tmp_path / "fig1.yaml").write_text(FIG1_CONFIG)
        config = str(tmp_path / "fig1.yaml")
    args = argparse.Namespace(
        executor="local", scheduler=None, baseline=baseline, config=config, workers=None
    )
    args.designs, args.out = None, tmp_path / "out"
    with pytest.raises(UsageError, match=allowed) as refused:
        run_sweep.run(args)
    assert "\n" not in str(refused.value)
    assert not (tmp_path / "out").exists()
