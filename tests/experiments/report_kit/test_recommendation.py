"""The report's first box names the design to build only when the fresh draws confirm it,
with its numbers beside the baseline's on the same draws and its tightest margins."""

from __future__ import annotations

from test_comparison_section import entry
from test_margins_section import margins, row

from experiments.report_kit.recommendation import recommendation_html


def comparison(design: dict) -> dict:
    base = entry(40, 38)
    base["label"] = "table3"
    return {"drops": 40, "target": 0.9, "seed": 1, "baseline": base, "designs": [design]}


def test_a_confirmed_design_is_named_to_build_with_the_baseline_and_its_margins() -> None:
    design = entry(40, 40)
    design["paired"] = {"draws": 40, "design_only": 2, "baseline_only": 0}
    box = recommendation_html(
        "design 5", comparison(design), margins(row("b", 0.5, [0.48, 0.9])), "the best"
    )
    assert "Build design 5" in box and "confirmed:" in box
    assert "40/40 against 38/40" in box and "failed on 2, the reverse on 0" in box
    assert "b 2.0% / 40.0%" in box and 'href="#margins"' in box


def test_an_unconfirmed_design_is_not_called_one_to_build() -> None:
    box = recommendation_html("design 5", comparison(entry(40, 39)), None, "the best")
    assert "Build" not in box and "not confirmed" in box


def test_no_design_says_why() -> None:
    box = recommendation_html(None, None, None, "", absent="no design works")
    assert "No design to build yet" in box and "no design works" in box


def test_a_missing_mean_exit_time_reads_n_a_not_a_dash_and_a_unit() -> None:
    """Issue 39: an entry with no mean exit time printed a dangling "– s"."""
    design = entry(40, 40)
    design["verdict"]["orientations"]["heavy_trailing"]["mean_exit_time_s"] = None
    design["verdict"]["orientations"]["heavy_leading"]["mean_exit_time_s"] = 1.234
    box = recommendation_html("design 5", comparison(design), None, "the best")
    assert "mean exit time heavy leading 1.23 s, heavy trailing n/a against" in box
    assert "– s" not in box and "- s" not in box
