"""A finished sweep's report is not drawn again while nothing it shows has changed (issue 25:
``report DIR`` on a finished sweep took 68 s and ``run --json`` 81 s, drawing every figure and
nominal drop again): the second ``report`` of an unchanged sweep writes no report, and prints
the same summary; a changed sweep, a changed or removed report file, gets a new report."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pytest
from cli_process import noise, run_cli
from sweep_fixtures import TINY, fake_result

from experiments.cli import report as report_cli
from experiments.cli.baseline import baseline_of
from experiments.sweep import report_cache, results_db
from experiments.sweep.config import config_from_dict
from feeders.halton import halton_points

CONFIG = {
    **TINY,
    "designs": {"count": 3, "seed": 1},
    "ladder": [{"level": "geometric", "planners": ["rrt"], "budget": {"propagations": 100}}],
    "holdout": {"fraction": 0.0, "seed": 7},
}


def finished_sweep(directory: Path) -> Path:
    """A finished one-rung sweep of three designs (hand-made evaluations), design 2 pending."""
    config = config_from_dict(CONFIG)
    directory.mkdir()
    db = results_db.connect(directory / "results.sqlite")
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(3, 1)
        results_db.add_designs(db, ((i, False, list(points[i])) for i in range(3)))
        results_db.record(db, fake_result(0, "geometric", "infeasible", 0.1), 0, 1)
        results_db.record(db, fake_result(1, "geometric", "feasible", 0.2), 0, 1)
    finally:
        db.close()
    return directory


@pytest.fixture
def drawn(monkeypatch) -> list[Path]:
    """The sweep directories the report was drawn for; it writes a page and a figure and
    finds a recommendation naming the baseline it was given (the real one's figures,
    comparison and margins cost seconds and are specified elsewhere)."""
    calls: list[Path] = []

    def report_with_findings(out, summary, db_path, baseline=None, **_options):
        calls.append(Path(out))
        (Path(out) / "figures").mkdir(exist_ok=True)
        (Path(out) / "figures" / "survivors.png").write_bytes(b"png")
        page = Path(out) / "report.html"
        page.write_text(f"<p>{summary['levels'][0]['evaluated']} evaluated</p>")
        findings = {
            "comparison": {"absent": "no design works", "baseline": {"label": baseline[0]}},
            "recommendation": {"label": None, "confirmed": False, "sentence": "none works"},
            "margins": None,
        }
        return page, findings

    monkeypatch.setattr("experiments.sweep.report.report_with_findings", report_with_findings)
    return calls


def _report(sweep: Path, capsys, baseline: str = "table3") -> dict:
    args = argparse.Namespace(json=True, no_report=False, quiet=True, baseline=baseline)
    assert report_cli.finish(sweep, args, {}) == 0
    return json.loads(capsys.readouterr().out)


def test_a_second_report_of_an_unchanged_sweep_writes_no_report(tmp_path, drawn, capsys):
    sweep = finished_sweep(tmp_path / "sweep")
    first = _report(sweep, capsys)
    page = sweep / "report.html"
    written = page.stat().st_mtime_ns
    second = _report(sweep, capsys)
    assert drawn == [sweep]
    assert page.stat().st_mtime_ns == written
    assert second == first  # the stored summary is the summary
    assert first["levels"][0]["evaluated"] == 2


def test_what_the_report_found_is_in_the_summary_printed_written_and_cached(
    tmp_path, drawn, capsys
):
    sweep = finished_sweep(tmp_path / "sweep")
    first = _report(sweep, capsys)
    second = _report(sweep, capsys)
    written = json.loads((sweep / "summary.json").read_text())
    assert drawn == [sweep]
    for summary in (first, second, written):
        assert summary["recommendation"]["sentence"] == "none works"
        assert summary["comparison"]["baseline"]["label"] == "table3"
        assert "margins" in summary


def test_another_baseline_is_another_report_and_then_cached(tmp_path, drawn, capsys):
    sweep = finished_sweep(tmp_path / "sweep")
    _report(sweep, capsys)
    against_fig7a = _report(sweep, capsys, baseline="fig7a")
    again = _report(sweep, capsys, baseline="fig7a")
    assert drawn == [sweep, sweep]
    assert against_fig7a["comparison"]["baseline"]["label"] == "fig7a"
    assert again == against_fig7a


def test_the_key_follows_the_baseline_by_its_values_not_only_its_name(tmp_path):
    sweep = finished_sweep(tmp_path / "sweep")
    rows = report_cache.report_key(sweep / "results.sqlite")
    table3 = baseline_of("table3")
    keys = {
        report_cache.with_baseline(rows, table3),
        report_cache.with_baseline(rows, baseline_of("fig7a")),
        report_cache.with_baseline(rows, ("table3", [v + 1e-9 for v in table3[1]])),
    }
    assert len(keys) == 3 and rows not in keys
    assert report_cache.with_baseline(rows, table3) == report_cache.with_baseline(rows, table3)
    assert report_cache.with_baseline(None, table3) is None


def test_a_changed_sweep_gets_a_new_report(tmp_path, drawn, capsys):
    sweep = finished_sweep(tmp_path / "sweep")
    _report(sweep, capsys)
    db = results_db.connect(sweep / "results.sqlite")
    try:
        results_db.record(db, fake_result(2, "geometric", "feasible", 0.3), 0, 1)
    finally:
        db.close()
    summary = _report(sweep, capsys)
    assert drawn == [sweep, sweep]
    assert summary["levels"][0]["evaluated"] == 3
    assert "3 evaluated" in (sweep / "report.html").read_text()


@pytest.mark.parametrize("damage", ["remove the page", "edit the page", "remove a figure"])
def test_a_report_changed_on_disk_is_written_again(tmp_path, drawn, capsys, damage):
    sweep = finished_sweep(tmp_path / "sweep")
    _report(sweep, capsys)
    if damage == "remove the page":
        (sweep / "report.html").unlink()
    elif damage == "edit the page":
        (sweep / "report.html").write_text("<p>edited by hand</p>")
    else:
        (sweep / "figures" / "survivors.png").unlink()
    _report(sweep, capsys)
    assert drawn == [sweep, sweep]
    assert (sweep / "report.html").read_text() == "<p>2 evaluated</p>"


def test_a_cache_of_another_sweep_or_unreadable_is_not_used(tmp_path, drawn, capsys):
    sweep = finished_sweep(tmp_path / "sweep")
    _report(sweep, capsys)
    cache = sweep / report_cache.CACHE
    stored = json.loads(cache.read_text())
    cache.write_text(json.dumps({**stored, "key": "0" * 64}))
    _report(sweep, capsys)
    cache.write_text("{not json")
    _report(sweep, capsys)
    assert drawn == [sweep, sweep, sweep]


def test_the_key_follows_the_rows_not_the_files_bytes(tmp_path):
    sweep = finished_sweep(tmp_path / "sweep")
    results = sweep / "results.sqlite"
    key = report_cache.report_key(results)
    db = results_db.connect(results)  # a run that finds nothing to do: claims, adds nothing
    try:
        config = config_from_dict(CONFIG)
        results_db.claim(db, config.to_dict(), config.results_key())
    finally:
        db.close()
    assert report_cache.report_key(results) == key
    db = results_db.connect(results)
    try:
        results_db.record(db, fake_result(2, "geometric", "infeasible", 0.3), 0, 1)
    finally:
        db.close()
    assert report_cache.report_key(results) not in (key, None)


@pytest.mark.slow  # ~15 s
def test_report_twice_on_the_command_line_draws_once_and_prints_json(tmp_path):
    sweep = finished_sweep(tmp_path / "sweep")
    first = run_cli("report", str(sweep), "--json")
    assert first.returncode == 0, first.stderr
    pictures = {p: p.stat().st_mtime_ns for p in [sweep / "report.html", *sweep.glob("figures/*")]}
    second = run_cli("report", str(sweep), "--json")
    assert second.returncode == 0, second.stderr
    assert noise(second.stderr) == ""  # off a terminal: no progress lines
    assert json.loads(second.stdout) == json.loads(first.stdout)
    assert {p: p.stat().st_mtime_ns for p in pictures} == pictures
