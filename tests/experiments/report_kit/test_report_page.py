"""The page's pieces: escaped tables, figures by relative path, one design's verdict."""

from __future__ import annotations

from pathlib import Path

from experiments.report_kit.page import figure_html, html_table
from experiments.report_kit.verdict_section import design_verdict_html, strip_name

VERDICT = {
    "decision": "works",
    "drops": 20,
    "orientations": {
        "heavy_leading": {"successes": 20, "p": 1.0, "interval": [0.84, 1.0]},
        "heavy_trailing": {"successes": 19, "p": 0.95, "interval": [0.76, 0.99]},
    },
    "both": {"successes": 19, "p": 0.95, "interval": [0.76, 0.99]},
    "transitions": {
        "heavy_leading": {"heavy end down": 20},
        "heavy_trailing": {"heavy end down": 19, "heavy end up": 1},
    },
}


def test_a_table_escapes_every_cell_and_aligns_text_columns_left():
    table = html_table(["a<b", "n"], [["<script>", "3"]], text_columns=(0,))
    assert "<script>" not in table
    assert '<td class="text">&lt;script&gt;</td><td>3</td>' in table


def test_a_figure_is_referenced_relative_to_the_page_and_a_missing_one_is_nothing():
    figures = {"x": Path("/anywhere/figures/x.png")}
    assert 'src="figures/x.png"' in figure_html(figures, "x", "alt")
    assert figure_html(figures, "y", "alt") == ""


def test_a_verdict_shows_both_entries_the_transitions_and_the_strip():
    label = "optimum"
    parts = design_verdict_html(
        {"design_id": label, "verdict": VERDICT},
        {strip_name(label): Path(f"f/{strip_name(label)}.png")},
    )
    page = "\n".join(parts)
    assert "<h4>Design optimum: works</h4>" in page
    assert "19 / 20" in page and "[0.76, 0.99]" in page
    assert "<th>heavy end up</th>" in page
    assert "0.975" in page  # selector efficiency: 39 heavy end down of 40
    assert f"figures/{strip_name(label)}.png" in page


def test_a_verdict_without_its_strip_says_why():
    page = "\n".join(design_verdict_html({"design_id": 7, "verdict": VERDICT}, {}))
    assert "No strip" in page
    assert strip_name(7) == "strip_design000007"
