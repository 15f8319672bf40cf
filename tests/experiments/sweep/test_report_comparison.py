"""A sweep's report says why its best design: the top designs that work judged again beside
table3 on fresh draws and drawn over it, or a sentence saying why there is no comparison."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
from sweep_fixtures import TINY

from experiments.sweep.config import config_from_dict
from experiments.sweep.ladder import run_sweep
from experiments.sweep.report import write_report
from experiments.sweep.summary import summarise
from feeders.design import PRESETS

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def passive_sweep(tmp_path: Path, target: float, **options) -> tuple[Path, str]:
    """A four-design sweep with only a passive rung of two trials, and its report (without
    the recommended design's margins unless ``margins=True``: they are tested in
    test_report_recommendation.py)."""
    data = {
        **copy.deepcopy(TINY),
        "designs": {"count": 4, "seed": 0},  # design 3 works (the default sweep)
        "feeder": {"friction": 0.05},
        "ladder": [
            {
                "level": "passive",
                "verdict": {"target": target, "min_drops": 2, "batch": 2, "max_drops": 2},
            }
        ],
        "holdout": {"fraction": 0.0, "seed": 7},
    }
    path = run_sweep(config_from_dict(data), tmp_path / "sweep")
    page = write_report(tmp_path / "sweep", summarise(path), path, **{"margins": False, **options})
    return page, page.read_text(encoding="utf-8")


def test_a_sweep_with_a_design_that_works_shows_why_this_design(tmp_path: Path) -> None:
    page, text = passive_sweep(tmp_path, target=0.0)  # any success from each entry works
    summary = summarise(tmp_path / "sweep" / "results.sqlite")
    assert summary["best"], "the fixture needs a design that works"
    top = summary["best"][0]["design_id"]
    assert "Why this design: compared with table3 on the same fresh draws" in text
    assert f"design {top} against table3" in text
    assert "40 fresh perturbed trials" in text and "drops in" in text
    assert "confirmed" in text and "of Table 2&#x27;s range" in text
    overlay = page.parent / "figures" / f"overlay_design_{top}.png"
    assert f'src="figures/{overlay.name}"' in text
    assert overlay.read_bytes()[:8] == PNG_MAGIC


@pytest.mark.parametrize("target", [1.0])
def test_a_sweep_where_nothing_works_says_why_there_is_no_comparison(
    tmp_path: Path, target: float
) -> None:
    page, text = passive_sweep(tmp_path, target=target)  # no lower bound exceeds 1
    assert "No comparison with table3 on fresh draws: no design works" in text
    assert not list((page.parent / "figures").glob("overlay_*.png"))


@pytest.mark.slow  # ~8 s
def test_the_comparison_is_with_the_baseline_given(tmp_path: Path) -> None:
    baseline = ("fig7a", [float(v) for v in PRESETS["fig7a"].to_vector()])
    _, text = passive_sweep(tmp_path, target=0.0, baseline=baseline)
    assert "Why this design: compared with fig7a on the same fresh draws" in text
    assert "against table3" not in text
    assert "40 fresh draws shared with fig7a" in text
