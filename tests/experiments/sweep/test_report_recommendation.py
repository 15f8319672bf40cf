"""A sweep's report opens with the design to build: the first of its top designs ranked again
on fresh draws beside the baseline, only when those draws confirm it works; the top designs'
table says per design what the fresh draws said; a design they did not confirm is never
called best or told to be built (issue 25: a design that works 40/40 by its own verdict can
be a lucky draw)."""

from __future__ import annotations

import html
import re
from pathlib import Path

from experiments.report_kit.comparison_section import fresh_ranking
from experiments.sweep.report_html import html_page
from experiments.sweep.report_recommendation import (
    fresh_status,
    margins_seed,
    recommendation_of,
)
from feeders.design import PARAMETER_NAMES, PRESETS

TABLE3 = [float(v) for v in PRESETS["table3"].to_vector()]
DROPS = 40


def _verdict(decision: str, successes: int, low: float, high: float, exit_time: float) -> dict:
    """A ``Verdict.to_dict`` on the fresh draws: both entries alike."""
    per = {
        "successes": successes,
        "p": successes / DROPS,
        "interval": [low, high],
        "mean_exit_time_s": exit_time,
    }
    return {
        "decision": decision,
        "works": decision == "works",
        "target": 0.9,
        "drops": DROPS,
        "orientations": {"heavy_leading": per, "heavy_trailing": per},
        "both": {"successes": successes, "p": successes / DROPS, "interval": [low, high]},
        "transitions": {"heavy_leading": {"heavy end down": successes}},
        "wall_time_s": 1.0,
    }


WORKS = _verdict("works", 40, 0.912, 1.0, 2.6)
FAILS = _verdict("fails", 20, 0.35, 0.65, 2.4)
UNDECIDED = _verdict("undecided", 37, 0.80, 0.97, 2.5)


def _entry(label: str, verdict: dict | None) -> dict:
    return {
        "label": label,
        "values": TABLE3,
        "verdict": verdict,
        "reason": None if verdict else "the exit chute is narrower than the part",
        "differences": [
            {"name": n, "design": 1.0, "baseline": 1.0, "difference": 0.0, "fraction": 0.0}
            for n in PARAMETER_NAMES
        ],
        "paired": {"draws": DROPS, "design_only": 0, "baseline_only": 0},
    }


def _comparison(*entries: dict) -> dict:
    return {
        "seed": 5,
        "drops": DROPS,
        "target": 0.9,
        "baseline": _entry("table3", WORKS),
        "designs": list(entries),
        "wall_time_s": 2.0,
        "ranked_with": [1, 2, 3],
    }


def _best(design_id: int, exit_time: float) -> dict:
    both = {"successes": 40, "p": 1.0, "interval": [0.912, 1.0]}
    return {
        "design_id": design_id,
        "values": TABLE3,
        "exit_time_s": exit_time,
        "verdict": {**WORKS, "both": both},
    }


def _summary(comparison: dict) -> dict:
    """A sweep whose top designs by its own verdict are 7, 9 and 11 (all 40/40), 12 below."""
    summary = {
        "name": "recommend",
        "ladder": ["passive"],
        "feeder": {"friction": 0.05},
        "passive": {"evaluated": 20, "works": 4, "target": 0.9},
        "best": [_best(7, 2.4), _best(9, 2.5), _best(11, 2.6), _best(12, 2.7)],
        "comparison": comparison,
    }
    summary["recommendation"] = recommendation_of(summary, comparison)
    summary["margins"] = None
    return summary


def _page(summary: dict) -> str:
    return html_page(summary, ["passive"], {}, Path("results.sqlite"))


def _text(page: str) -> str:
    """What a reader sees: the page without its tags, unescaped."""
    body = page.split("<body>", 1)[1]
    return html.unescape(re.sub(r"<[^>]+>", " ", body))


def _best_table_status(page: str) -> dict[str, str]:
    """Per design id, the "fresh draws" cell of the top designs' table."""
    table = page.split("Top designs by the sweep", 1)[1].split("</table>", 1)[0]
    header = re.findall(r"<th[^>]*>(.*?)</th>", table)
    column = header.index("fresh draws")
    out = {}
    for row in re.findall(r"<tr>(.*?)</tr>", table, re.S)[1:]:
        cells = [html.unescape(c) for c in re.findall(r"<td[^>]*>(.*?)</td>", row)]
        out[cells[0]] = cells[column]
    return out


def test_the_recommendation_is_the_first_confirmed_on_fresh_draws_not_the_sweeps_top() -> None:
    comparison = _comparison(
        _entry("design 7", FAILS), _entry("design 9", WORKS), _entry("design 11", UNDECIDED)
    )
    summary = _summary(comparison)
    recommendation = summary["recommendation"]
    assert recommendation["label"] == "design 9" and recommendation["confirmed"]
    assert recommendation["ranking"] == [r["label"] for r in fresh_ranking(comparison)]
    assert recommendation["ranking"] == ["design 9", "design 11", "design 7"]
    assert "the sweep's 4 designs that work" in recommendation["chosen"]
    assert "40 fresh draws shared with table3" in recommendation["chosen"]
    page = _page(summary)
    opening = page.split("</h1>", 1)[1].split("<h2>Levels</h2>", 1)[0]
    assert '<div class="recommendation">' in opening and "Build design 9" in opening
    assert "Build design 7" not in page


def test_the_top_designs_table_says_what_the_fresh_draws_said_per_design() -> None:
    comparison = _comparison(
        _entry("design 7", FAILS), _entry("design 9", WORKS), _entry("design 11", UNDECIDED)
    )
    status = _best_table_status(_page(_summary(comparison)))
    assert status == {
        "7": "not confirmed (fails)",
        "9": "confirmed",
        "11": "not confirmed (undecided)",
        "12": "not re-judged",
    }


def test_a_design_that_cannot_be_built_on_fresh_draws_is_not_confirmed() -> None:
    comparison = _comparison(_entry("design 7", None))
    assert fresh_status(comparison) == {"design 7": "not confirmed (cannot be built)"}
    assert recommendation_of(_summary(comparison), comparison)["label"] is None


def test_an_unconfirmed_top_design_is_not_called_best_or_to_be_built() -> None:
    comparison = _comparison(
        _entry("design 7", UNDECIDED), _entry("design 9", FAILS), _entry("design 11", FAILS)
    )
    summary = _summary(comparison)
    recommendation = summary["recommendation"]
    assert recommendation["label"] is None and not recommendation["confirmed"]
    assert "design 7 (undecided)" in recommendation["sentence"]
    assert "design 9 (fails)" in recommendation["sentence"]
    page = _page(summary)
    text = _text(page)
    assert '<div class="recommendation none"><h2>No design to build yet</h2>' in page
    assert "none of the top 3" in text
    assert re.search(r"\bbest\b", text, re.I) is None
    assert "Build " not in text
    assert "recommended design" not in text
    assert "No margins: no design is recommended" in text


def test_without_a_design_that_works_the_box_says_so() -> None:
    comparison = {"absent": "no design works, so none is recommended", "baseline": {"label": "x"}}
    summary = {**_summary(comparison), "best": []}
    assert summary["recommendation"]["label"] is None
    text = _text(_page(summary))
    assert "No design to build yet" in text and "no design works" in text
    assert "No comparison with x on fresh draws" in text


def test_without_a_passive_rung_the_box_says_why_and_there_is_no_margins_section() -> None:
    summary = {"name": "geometric only", "ladder": ["geometric"], "best": []}
    summary["recommendation"] = recommendation_of(summary, None)
    text = _text(html_page(summary, ["geometric"], {}, Path("results.sqlite")))
    assert "No design to build yet" in text and "no passive rung" in text
    assert "How much tolerance" not in text


def test_the_margins_seed_follows_the_sweeps_seed_and_avoids_the_seeds_used() -> None:
    seed = margins_seed(0)
    assert margins_seed(0) == seed and margins_seed(1) != seed
    assert margins_seed(0, avoid=(seed,)) != seed
    assert 0 <= seed < 2**31 - 1
