"""The passive verdict in a sweep's report: the numbers of the summary's ``passive``,
``pipelines`` and ``best`` entries on the page, the transition matrices, the strips of the
best designs' nominal drops, and what a design that cannot be built gets instead."""

from __future__ import annotations

import copy
import re
from pathlib import Path

import pytest

from experiments.sweep import results_db
from experiments.sweep.report import write_report
from feeders.design import PRESETS

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
TABLE3 = [float(v) for v in PRESETS["table3"].to_vector()]


def _verdict(k_leading: int, k_trailing: int, n: int) -> dict:
    def per(k: int) -> dict:
        return {"successes": k, "p": k / n, "interval": [k / n - 0.1, 1.0], "mean_exit_time_s": 2.5}

    return {
        "decision": "works",
        "works": True,
        "target": 0.9,
        "drops": n,
        "orientations": {"heavy_leading": per(k_leading), "heavy_trailing": per(k_trailing)},
        "both": {"successes": min(k_leading, k_trailing), "p": 0.95, "interval": [0.86, 0.99]},
        "transitions": {
            "heavy_leading": {"heavy end down": k_leading, "wedged at the lip": n - k_leading},
            "heavy_trailing": {"heavy end down": k_trailing, "caught on the pin": n - k_trailing},
        },
        "wall_time_s": 1.0,
    }


SUMMARY = {
    "name": "verdicts <b>",
    "results_key": "k",
    "designs": 4,
    "holdout": 4,
    "ladder": ["passive", "geometric"],
    "feeder": {"friction": 0.05},
    "levels": [],
    "planners": [],
    "truth": "passive",
    "pruning": [],
    "ladder_pruning": [],
    "speedup": None,
    "quarantined": [],
    "passive": {
        "evaluated": 4,
        "works": 2,
        "fails": 1,
        "undecided": 1,
        "degenerate": 0,
        "works_fraction": 0.5,
        "works_ci": [0.15, 0.85],
        "works_basis": "every design",
        "works_n": 4,
        "drops": 320,
        "mean_trials": 40.0,
        "drops_per_s": 50.0,
        "target": 0.9,
    },
    "pipelines": [
        {
            "rungs": ["passive"],
            "cost_s": 0.5,
            "cost_ci": [0.4, 0.6],
            "recall": 1.0,
            "recall_ci": [0.5, 1.0],
            "speedup": 1.0,
            "n": 4,
        },
        {
            "rungs": ["geometric", "passive"],
            "cost_s": 0.8,
            "cost_ci": [0.7, 0.9],
            "recall": 0.5,
            "recall_ci": [0.1, 0.9],
            "speedup": 0.625,
            "n": 4,
        },
    ],
    "best": [
        {"design_id": 7, "values": TABLE3, "exit_time_s": 2.5, "verdict": _verdict(38, 38, 40)},
    ],
}


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    root = tmp_path_factory.mktemp("verdicts")
    db = results_db.connect(root / "results.sqlite")
    db.close()
    page = write_report(root / "report", copy.deepcopy(SUMMARY), root / "results.sqlite")
    return page, page.read_text(encoding="utf-8")


def test_the_passive_numbers_and_the_pipelines_are_on_the_page(report) -> None:
    _, text = report
    assert "Passive verdict" in text and "[0.15, 0.85]" in text and "every design" in text
    assert ("geometric → passive" in text and "0.625" in text) or "0.62" in text
    assert "verdicts &lt;b&gt;" in text and "verdicts <b>" not in text


def test_a_design_that_works_shows_its_probabilities_and_transition_matrix(report) -> None:
    _, text = report
    assert "Design 7: works" in text
    assert "38 / 40" in text and "[0.86, 0.99]" in text
    for outcome in ("heavy end down", "wedged at the lip", "caught on the pin"):
        assert outcome in text
    assert "Selector efficiency" in text and "0.950" in text  # 76 of 80 drops out right


def test_the_strip_and_the_transition_figure_are_written_and_referenced(report) -> None:
    page, text = report
    sources = set(re.findall(r'<img src="([^"]+)"', text))
    for name in ("figures/strip_design000007.png", "figures/transitions.png"):
        assert name in sources
        assert (page.parent / name).read_bytes()[:8] == PNG_MAGIC


def test_a_design_that_cannot_be_built_gets_a_sentence_and_stale_strips_go(
    report, tmp_path: Path
) -> None:
    page, _ = report
    out = tmp_path / "again"
    out.mkdir()
    (out / "figures").mkdir()
    (out / "figures" / "strip_design000007.png").write_bytes(PNG_MAGIC)
    summary = copy.deepcopy(SUMMARY)
    summary["best"][0]["design_id"] = 8
    summary["best"][0]["values"] = [float(v) for v in TABLE3]
    summary["best"][0]["values"][1] = 0.01  # b: an exit chute far narrower than any part
    again = write_report(out, summary, page.parent.parent / "results.sqlite")
    text = again.read_text(encoding="utf-8")
    assert "cannot be built" in text
    assert not (out / "figures" / "strip_design000007.png").exists()
    assert not (out / "figures" / "strip_design000008.png").exists()


def test_without_a_passive_rung_the_page_has_no_verdict_section(tmp_path: Path) -> None:
    summary = {k: v for k, v in SUMMARY.items() if k not in ("passive", "pipelines", "truth")}
    summary["best"] = []
    db = results_db.connect(tmp_path / "results.sqlite")
    db.close()
    text = write_report(tmp_path / "r", summary, tmp_path / "results.sqlite").read_text()
    assert "Passive verdict" not in text
    assert not (tmp_path / "r" / "figures" / "transitions.png").exists()
