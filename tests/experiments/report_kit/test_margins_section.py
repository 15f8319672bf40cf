"""The margins section names the axes with the least room, in fractions of each axis's box,
and marks an end that reached the box's edge as a lower bound."""

from __future__ import annotations

from pathlib import Path

from experiments.report_kit.margins_section import (
    margins_html,
    margins_sentence,
    room,
    tightest,
)


def row(name: str, nominal: float, interval: list[float] | None, box=(0.0, 1.0), edge=False):
    return {
        "parameter": name,
        "meaning": f"meaning of {name}",
        "kind": "design",
        "unit": "length",
        "nominal": nominal,
        "box": list(box),
        "box_source": "Table 2",
        "interval": interval,
        "low": None if interval is None else {"at_box_edge": edge},
        "high": None if interval is None else {"at_box_edge": False},
    }


def margins(*rows: dict, works: bool = True) -> dict:
    return {
        "design": "design 7",
        "works": works,
        "target": 0.9,
        "drops_per_value": 20,
        "seed": 0,
        "meaning": "values where P(both) stays above the target",
        "margins": list(rows),
        "cost": {"drops": 1000, "wall_time_s": 20.0, "workers": 2},
    }


def test_room_is_a_fraction_of_the_box_on_each_side() -> None:
    # nominal 1.5 in a box [1, 3] allowed from 1.4 to 1.9: 0.05 and 0.2 of the width 2
    below, above = room(row("d", 1.5, [1.4, 1.9], box=(1.0, 3.0)))
    assert abs(below - 0.05) < 1e-12 and abs(above - 0.2) < 1e-12
    assert room(row("r", 0.1, None)) is None


def test_the_tightest_axes_come_first_and_an_axis_without_margin_before_all() -> None:
    data = margins(
        row("a", 0.5, [0.1, 0.9]),  # 0.4 either side
        row("b", 0.5, [0.48, 0.9]),  # 0.02 below
        row("c", 0.5, None),  # no margin at all
        row("d", 0.5, [0.2, 0.55]),  # 0.05 above
    )
    assert [t["parameter"] for t in tightest(data)] == ["c", "b", "d"]
    sentence = margins_sentence(data)
    assert "c none" in sentence and "b 2.0% / 40.0%" in sentence


def test_a_design_that_does_not_work_has_no_margins_and_the_page_says_so(tmp_path: Path) -> None:
    data = margins(works=False)
    assert "no margins" in margins_sentence(data)
    page = "\n".join(margins_html(data, {}))
    assert "no margins" in page and "<img" not in page


def test_the_table_marks_an_end_at_the_box_edge_as_at_least() -> None:
    data = margins(row("a", 0.3, [0.0, 0.9], edge=True))
    page = "\n".join(margins_html(data, {}))
    assert "≥ 30.0%" in page and "60.0%" in page


def test_without_margins_the_reason_is_given() -> None:
    page = "\n".join(margins_html(None, {}, absent="no design works"))
    assert "No margins: no design works." in page


def test_a_side_that_reached_the_box_edge_does_not_make_an_axis_the_tightest() -> None:
    """r's low side stopped at the box's edge 1% below the nominal: the box limits it, not
    the design, so b (3% of room found inside the box) is the tightest."""
    data = margins(row("r", 0.01, [0.0, 0.9], edge=True), row("b", 0.5, [0.47, 0.9]))
    assert tightest(data)[0]["parameter"] == "b"
    assert "r ≥ 1.0% / 89.0%" in margins_sentence(data)


def test_a_design_with_no_margins_is_undecided_or_does_not_work_as_its_verdict_says() -> None:
    """Issue 39: "does not work" was said of an undecided design."""
    from experiments.report_kit.margins_section import margins_sentence, robustness_sentence

    undecided = {**margins(works=False), "verdict": {"decision": "undecided"}}
    failing = {**margins(works=False), "verdict": {"decision": "fails"}}
    assert margins_sentence(undecided).startswith(
        "design 7 is undecided (too few trials to tell whether it works at the target) at "
        "nominal on the margins' draws"
    )
    assert "does not work" not in robustness_sentence(undecided)
    assert "is undecided" in robustness_sentence(undecided)
    assert margins_sentence(failing).startswith("design 7 does not work at nominal")
    assert "none (it does not work on these draws)" in robustness_sentence(failing)
