"""A device family's sweep gets the feeder's recommendation (issue 24, "any parametric
device"): the report judges its top designs that work again beside the family's default on
the same fresh draws (the family verdict's own trials on a seed none was ranked with), opens
with the design to build when those draws confirm it, shows the family's parameters and
devices, and measures the recommended design's margins over the family's parameters and mu.

The sweep is a small one of the packaged fig1 family (peg) with budgets in counts; its design
11 works by its own verdict."""

from __future__ import annotations

import argparse
import html
import re
from pathlib import Path

import pytest

from experiments.cli.baseline import family_baseline_of
from experiments.drop.compare import fixed_settings, fresh_seed
from experiments.drop.family_verdict import family_verdict
from experiments.margins.measure import FamilySubject
from experiments.margins.run import axes_of
from experiments.sweep.config import config_from_dict
from experiments.sweep.job import verdict_seed
from experiments.sweep.ladder import run_sweep
from experiments.sweep.report import report_with_findings
from experiments.sweep.report_recommendation import margin_subject
from experiments.sweep.report_verdicts import comparison_of, passive_settings, sweep_config
from experiments.sweep.summary import summarise
from feeders.device_family import load_family, packaged_family

FIG1 = load_family(packaged_family("fig1"))
SWEEP_SEED = 1
FAMILY_SWEEP = {
    "name": "fig1-recommends",
    "family": "fig1",
    "designs": {"count": 12, "seed": SWEEP_SEED},  # design 11 works
    "ladder": [
        {"level": "screen", "screen": {"max_drops": 20}},
        {
            "level": "passive",
            "verdict": {"target": 0.5, "min_drops": 4, "batch": 2, "max_drops": 6, "t_max": 4.0},
        },
    ],
    "holdout": {"fraction": 0.0, "seed": 7},
    "audit": {"fraction": 1.0, "seed": 11},
    "workers": 1,
}
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def reported(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict, dict]:
    """The sweep, its summary and what its report found (without the margins: measured in
    the slow test below), run once for the module."""
    out = tmp_path_factory.mktemp("fig1-recommends")
    db = run_sweep(config_from_dict(FAMILY_SWEEP), out)
    summary = summarise(db)
    _, findings = report_with_findings(out, summary, db, workers=1, margins=False)
    return db, summary, findings


def _timeless(verdict: dict) -> dict:
    return {k: v for k, v in verdict.items() if k != "wall_time_s"}


def test_the_report_recommends_a_design_that_works_on_fresh_draws(reported) -> None:
    _, summary, findings = reported
    recommendation = findings["recommendation"]
    assert summary["passive"]["works"] >= 1
    assert recommendation["confirmed"] and recommendation["label"] == recommendation["ranking"][0]
    entry = next(
        d for d in findings["comparison"]["designs"] if d["label"] == recommendation["label"]
    )
    assert entry["verdict"]["works"] and entry["verdict"]["decision"] == "works"
    assert "shared with default" in recommendation["chosen"]


def test_the_baseline_is_the_familys_default_on_the_same_draws(reported) -> None:
    _, _, findings = reported
    comparison = findings["comparison"]
    assert comparison["family"] == "fig1"
    assert comparison["parameters"] == list(FIG1.vector_names)
    assert comparison["entries"] == ["open_leading", "open_trailing"]
    baseline = comparison["baseline"]
    assert baseline["label"] == "default" and baseline["values"] == FIG1.default().tolist()
    for entry in comparison["designs"]:
        assert entry["paired"]["draws"] == comparison["drops"] == baseline["verdict"]["drops"]
        assert [d["name"] for d in entry["differences"]] == list(FIG1.vector_names)


def test_its_trials_are_the_family_verdicts_on_a_fresh_seed(reported) -> None:
    """Reference: family_verdict, called directly on the comparison's seed with the passive
    rung's settings as a fixed sample, for every compared design and the default: the same
    made devices and drops give the same verdicts."""
    db, summary, findings = reported
    comparison = findings["comparison"]
    judged = [b for b in summary["best"] if "verdict" in b][:3]  # the top 3 with a verdict
    ranked_with = [verdict_seed(SWEEP_SEED, b["design_id"]) for b in judged]
    assert comparison["ranked_with"] == ranked_with
    assert comparison["seed"] == fresh_seed(SWEEP_SEED, ranked_with)
    assert comparison["seed"] not in ranked_with
    settings = fixed_settings(passive_settings(sweep_config(db)), comparison["drops"])
    for entry in (comparison["baseline"], *comparison["designs"]):
        reference = family_verdict(FIG1, entry["values"], settings, comparison["seed"])
        assert _timeless(entry["verdict"]) == _timeless(reference.to_dict()), entry["label"]


def test_the_page_opens_with_the_design_to_build_and_shows_the_familys_devices(
    reported,
) -> None:
    db, _, findings = reported
    label = findings["recommendation"]["label"]
    page = (db.parent / "report.html").read_text(encoding="utf-8")
    opening = page.split("</h1>", 1)[1].split("<h2>Levels</h2>", 1)[0]
    assert f"Build {label}" in opening
    text = html.unescape(re.sub(r"<[^>]+>", " ", page))
    assert "Why this design: compared with default on the same fresh draws" in text
    assert f"{label} against default" in text and "of the family's box" in text
    assert "Table 2" not in text and "heavy leading" not in text
    overlay = db.parent / "figures" / f"overlay_{label.replace(' ', '_')}.png"
    assert f'src="figures/{overlay.name}"' in page
    assert overlay.read_bytes()[:8] == PNG_MAGIC


def test_the_margins_vary_the_familys_parameters_and_mu(reported) -> None:
    db, summary, findings = reported
    label = findings["recommendation"]["label"]
    entry = next(d for d in findings["comparison"]["designs"] if d["label"] == label)
    subject = margin_subject(summary, db, entry["values"], label)
    assert isinstance(subject, FamilySubject) and subject.family() == FIG1
    assert subject.vector == tuple(entry["values"]) and subject.name == label
    assert subject.friction == FIG1.friction
    axes = axes_of(subject)
    assert [a.name for a in axes] == [*FIG1.vector_names, "mu"]
    low, high = FIG1.bounds()
    assert [(a.low, a.high) for a in axes[:-1]] == list(zip(low, high, strict=True))


@pytest.mark.slow  # ~6 s
def test_another_baseline_given_as_the_familys_values(reported) -> None:
    db, summary, _ = reported
    text = "0.5,1.2,1.2,-0.6,1.6,0.2"
    baseline = family_baseline_of(text, FIG1)
    assert baseline == ("baseline", [0.5, 1.2, 1.2, -0.6, 1.6, 0.2])
    comparison = comparison_of(summary, db, baseline=baseline)
    assert comparison["baseline"]["label"] == "baseline"
    assert comparison["baseline"]["values"] == baseline[1]


@pytest.mark.slow  # about 45 s on one busy core: the margins of the recommended design
def test_the_recommended_designs_margins_are_measured_over_the_familys_axes(
    reported, tmp_path: Path
) -> None:
    db, summary, _ = reported
    _, findings = report_with_findings(tmp_path, summary, db, workers=1)
    margins = findings["margins"]
    label = findings["recommendation"]["label"]
    assert margins["design"] == label and margins["works"]
    assert [row["parameter"] for row in margins["margins"]] == [*FIG1.vector_names, "mu"]
    assert margins["family"]["name"] == "fig1" and margins["part"] is None
    page = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert f"How much tolerance it has: the margins of {label}" in page


def test_the_report_command_reads_baseline_as_the_sweeps_family(reported) -> None:
    """``partfeeder report`` on a family sweep: a feeder's baseline is refused in one line
    before the report is touched (the family's own are taken: the tests above)."""
    from experiments.cli import report as report_cli
    from experiments.cli.usage import UsageError

    db, _, _ = reported
    page = db.parent / "report.html"
    before = page.stat().st_mtime_ns
    args = argparse.Namespace(json=True, no_report=False, quiet=True, baseline="table3")
    args.workers = 1
    with pytest.raises(UsageError, match="allowed with family fig1: default, or 6") as refused:
        report_cli.finish(db.parent, args, {})
    assert "\n" not in str(refused.value)
    assert page.stat().st_mtime_ns == before
