"""A sweep recommends by reliability, then by robustness (issue 34): among the designs the
fresh draws confirm, and the baseline on the same draws, a design is built only when it is
more reliable than the baseline by the paired exact test, or as reliable and more robust
beyond the margins' resolution; otherwise the report says to keep the baseline, with both
designs' margins side by side."""

from __future__ import annotations

import dataclasses
import html
import re
from pathlib import Path

from test_report_recommendation import WORKS, _comparison, _entry, _summary

from experiments.drop.perturbations import Perturbations
from experiments.report_kit.recommendation import KEEP
from experiments.sweep.report_html import html_page
from experiments.sweep.report_recommendation import BUILD, recommendation_of


def _margins(design: str, room_above: float, works: bool = True) -> dict:
    """One design's margins with fy the limiting axis: nominal 1.0 in Table 2's [0.5, 2.5],
    allowed up to 1.0 + 2 * room_above (the last value inside) with the first value outside
    one resolution step (2/128) further; mu's low side at the box's edge."""
    limit = 1.0 + 2.0 * room_above
    side = {
        "limit": limit,
        "at_box_edge": False,
        "first_outside": {"value": limit + 2.0 / 128},
    }
    return {
        "design": design,
        "works": works,
        "target": 0.9,
        "drops_per_value": 20,
        "seed": 3,
        "meaning": "values where P(both) stays above the target",
        "cost": {"drops": 900, "wall_time_s": 9.0, "workers": 2},
        "margins": [
            {
                "parameter": "fy",
                "meaning": "y of the protuberance tip",
                "kind": "design",
                "unit": "length",
                "nominal": 1.0,
                "box": [0.5, 2.5],
                "box_source": "Table 2",
                "interval": [0.5 + 1e-9, limit],
                "low": {"limit": 0.5, "at_box_edge": True, "first_outside": None},
                "high": side,
            },
            {
                "parameter": "mu",
                "meaning": "walls' friction",
                "kind": "friction",
                "unit": "-",
                "nominal": 0.05,
                "box": [0.0, 0.3],
                "box_source": "stated range",
                "interval": [0.0, 0.25],
                "low": {"limit": 0.0, "at_box_edge": True, "first_outside": None},
                "high": {"limit": 0.25, "at_box_edge": False, "first_outside": {"value": 0.26}},
            },
        ],
    }


def _paired(entry: dict, design_only: int, baseline_only: int) -> dict:
    paired = {"draws": 40, "design_only": design_only, "baseline_only": baseline_only}
    return {**entry, "paired": paired}


def _text(page: str) -> str:
    return html.unescape(re.sub(r"<[^>]+>", " ", page.split("<body>", 1)[1]))


def test_a_design_as_reliable_and_less_robust_than_the_baseline_is_not_built() -> None:
    # issue 34's default run: design 31, 40/40 against table3's 40/40, fy room 0.8% of its
    # box against table3's 4.7%: keep table3
    comparison = _comparison(_entry("design 31", WORKS))
    margins = {"design 31": _margins("design 31", 0.008), "table3": _margins("table3", 0.047)}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == KEEP and rec["label"] == "table3" and rec["confirmed"]
    assert rec["contender"] == "design 31"
    assert abs(rec["robustness"]["table3"]["value"] - 0.047) < 1e-12
    assert "no more reliable" in rec["why"] and "0.8%" in rec["why"] and "4.7%" in rec["why"]


def test_a_design_more_robust_beyond_the_resolution_is_built() -> None:
    comparison = _comparison(_entry("design 9", WORKS))
    margins = {"design 9": _margins("design 9", 0.12), "table3": _margins("table3", 0.047)}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == BUILD and rec["label"] == "design 9"
    assert "more robust" in rec["why"]


def test_a_robustness_gain_within_the_resolution_keeps_the_baseline() -> None:
    # 0.05 against 0.047: the brackets (one resolution step, 1/128 of the box) overlap
    comparison = _comparison(_entry("design 9", WORKS))
    margins = {"design 9": _margins("design 9", 0.05), "table3": _margins("table3", 0.047)}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == KEEP


def test_a_design_more_reliable_by_the_paired_test_is_built_even_when_less_robust() -> None:
    # it succeeded alone on 6 draws, the baseline on none: one-sided p = 1/64 < 0.05
    comparison = _comparison(_paired(_entry("design 9", WORKS), 6, 0))
    margins = {"design 9": _margins("design 9", 0.01), "table3": _margins("table3", 0.047)}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == BUILD and rec["label"] == "design 9"
    assert rec["reliability"]["design 9"]["better"]
    assert "more reliable" in rec["why"]


def test_a_few_more_successes_are_not_called_more_reliable() -> None:
    # 4 to 0 discordant draws: p = 1/16, not below 0.05
    comparison = _comparison(_paired(_entry("design 9", WORKS), 4, 0))
    margins = {"design 9": _margins("design 9", 0.01), "table3": _margins("table3", 0.047)}
    assert recommendation_of(_summary(comparison), comparison, margins)["decision"] == KEEP


def test_a_design_less_reliable_than_the_baseline_is_not_built_however_robust() -> None:
    comparison = _comparison(_paired(_entry("design 9", WORKS), 0, 6))
    margins = {"design 9": _margins("design 9", 0.3), "table3": _margins("table3", 0.047)}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == KEEP and "less reliable" in rec["why"]


def test_the_most_robust_confirmed_design_contends_not_the_first_on_fresh_draws() -> None:
    comparison = _comparison(
        _entry("design 7", WORKS), _entry("design 9", WORKS), _entry("design 11", WORKS)
    )
    margins = {
        "design 7": _margins("design 7", 0.01),
        "design 9": _margins("design 9", 0.2),
        "design 11": _margins("design 11", 0.1),
        "table3": _margins("table3", 0.047),
    }
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["label"] == "design 9" and rec["decision"] == BUILD


def test_a_baseline_the_fresh_draws_do_not_confirm_is_not_kept() -> None:
    from test_report_recommendation import FAILS

    comparison = _comparison(_entry("design 9", WORKS))
    comparison["baseline"] = _entry("table3", FAILS)
    margins = {"design 9": _margins("design 9", 0.01), "table3": _margins("table3", 0.0, False)}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == BUILD and rec["label"] == "design 9"


def test_the_page_says_keep_the_baseline_and_shows_both_margins() -> None:
    comparison = _comparison(_entry("design 31", WORKS))
    margins = {"design 31": _margins("design 31", 0.008), "table3": _margins("table3", 0.047)}
    summary = _summary(comparison)
    summary["recommendation"] = recommendation_of(summary, comparison, margins)
    summary["margins"], summary["baseline_margins"] = margins["table3"], margins["design 31"]
    page = html_page(summary, ["passive"], {}, Path("results.sqlite"))
    text = _text(page)
    opening = page.split("</h1>", 1)[1].split("<h2>Levels</h2>", 1)[0]
    assert "Keep the baseline, table3" in opening and "Build design 31" not in page
    assert "partfeeder optimize robust" in text
    assert "the margins of table3 beside design 31's" in text
    assert "design 31: room above" in text  # the other design's room in the table
    assert "table3: 4.7% of its box (fy high" in text


def test_without_margins_the_choice_says_robustness_was_not_measured() -> None:
    comparison = _comparison(_entry("design 9", WORKS))
    rec = recommendation_of(_summary(comparison), comparison, None)
    assert rec["decision"] == BUILD and "robustness not measured" in rec["chosen"]


def test_a_design_stopped_while_measured_is_said_at_most_and_never_contends_first() -> None:
    # design 7 was stopped after fy (outranked): its partial robustness is only an upper
    # bound, and a tie with the design that outranked it goes to the one measured whole
    comparison = _comparison(_entry("design 7", WORKS), _entry("design 9", WORKS))
    stopped = {**_margins("design 7", 0.2), "stopped": "not above design 9's 20.0%"}
    margins = {
        "design 7": stopped,
        "design 9": _margins("design 9", 0.2),
        "table3": _margins("table3", 0.047),
    }
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["contender"] == "design 9" and rec["label"] == "design 9"
    comparison = _comparison(_entry("design 7", WORKS))
    margins = {
        "design 7": {**_margins("design 7", 0.01), "stopped": "x"},
        "table3": margins["table3"],
    }
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == KEEP and "at most 1.8%" in rec["why"]


def test_a_baseline_that_cannot_be_built_gets_no_margins_and_the_design_is_built(
    monkeypatch,
) -> None:
    """A ``--baseline`` whose device cannot be built has no verdict on the fresh draws: its
    margins are not measured (its verdict would raise), the confirmed designs' are."""
    from experiments.sweep import report_recommendation as rr
    from experiments.sweep import report_verdicts

    comparison = _comparison(_entry("design 9", WORKS))
    comparison["baseline"] = _entry("table3", None)  # cannot be built
    measured: list[str] = []

    def each(subjects, *args, **kwargs):
        measured.extend(subjects)
        return {label: _Report(_margins(label, 0.05)) for label in subjects}

    monkeypatch.setattr("experiments.margins.run.margins_of_each", each)
    monkeypatch.setattr(report_verdicts, "sweep_config", lambda _db: _CONFIG)
    monkeypatch.setattr(rr, "margin_subject", lambda summary, db, values, label: label)
    margins = rr.margins_of_contenders(_summary(comparison), Path("x"), comparison)
    assert measured == ["design 9"] and set(margins) == {"design 9"}
    rec = recommendation_of(_summary(comparison), comparison, margins)
    assert rec["decision"] == BUILD and rec["label"] == "design 9"


class _Report:
    def __init__(self, data: dict):
        self.data = data

    def to_dict(self) -> dict:
        return self.data


_CONFIG = {
    "designs": {"seed": 0},
    "workers": 1,
    "ladder": [
        {
            "level": "passive",
            "verdict": {
                "rule": "sprt",
                "works_p": 0.95,
                "fails_p": 0.8,
                "error": 0.01,
                "min_drops": 1,
                "batch": 1,
                "max_drops": 200,
                "target": 0.9,
            },
            "perturbations": dataclasses.asdict(Perturbations()),
        }
    ],
}
