"""The "Why this design" section of a device family's comparison (issue 24): the verdicts'
own entries (the family's, not the feeder's two), the differences over the family's box, the
family's devices drawn over each other by their pieces; the recommendation box names the
family's entries too."""

from __future__ import annotations

import html
import re
from pathlib import Path

from experiments.proportions import wilson_interval
from experiments.report_kit.comparison_section import (
    comparison_figures,
    comparison_html,
    confirmation,
    fresh_ranking,
    overlay_name,
)
from experiments.report_kit.recommendation import recommendation_html
from feeders.device_family import load_family, packaged_family

ENTRIES = ("open_leading", "open_trailing")
FIG1 = load_family(packaged_family("fig1"))
OTHER = [0.31, 1.07, 1.39, -1.5, 0.45, 0.35]  # a fig1 design that builds
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _verdict(k_leading: int, k_trailing: int, n: int = 40) -> dict:
    def per(k: int, exit_time: float) -> dict:
        return {
            "successes": k,
            "p": k / n,
            "interval": list(wilson_interval(k, n)),
            "mean_exit_time_s": exit_time if k else None,
        }

    both = min(k_leading, k_trailing)
    return {
        "decision": "works" if both == n else "fails",
        "drops": n,
        "orientations": {ENTRIES[0]: per(k_leading, 3.1), ENTRIES[1]: per(k_trailing, 2.4)},
        "both": {"successes": both, "p": both / n, "interval": list(wilson_interval(both, n))},
        "transitions": {
            ENTRIES[0]: {"heavy end down": k_leading, "stopped in the cavity": n - k_leading},
            ENTRIES[1]: {"heavy end down": k_trailing},
        },
        "success_classes": ["heavy end down"],
    }


def _comparison() -> dict:
    low, high = FIG1.bounds()
    default = FIG1.default().tolist()
    differences = [
        {
            "name": name,
            "design": x,
            "baseline": y,
            "difference": x - y,
            "fraction": (x - y) / (hi - lo),
            "low": float(lo),
            "high": float(hi),
        }
        for name, x, y, lo, hi in zip(FIG1.vector_names, OTHER, default, low, high, strict=True)
    ]
    return {
        "seed": 9,
        "drops": 40,
        "target": 0.9,
        "family": "fig1",
        "parameters": list(FIG1.vector_names),
        "entries": list(ENTRIES),
        "baseline": {"label": "default", "values": default, "verdict": _verdict(0, 40)},
        "designs": [
            {
                "label": "design 11",
                "values": OTHER,
                "verdict": _verdict(40, 40),
                "reason": None,
                "differences": differences,
                "paired": {"draws": 40, "design_only": 40, "baseline_only": 0},
            }
        ],
        "wall_time_s": 2.5,
    }


def _text(parts: list[str] | str) -> str:
    page = "\n".join(parts) if isinstance(parts, list) else parts
    return html.unescape(re.sub(r"<[^>]+>", " ", page))


def test_the_confirmation_and_ranking_read_the_familys_entries() -> None:
    comparison = _comparison()
    confirmed, sentence = confirmation(comparison["designs"][0], 40, 0.9)
    assert confirmed and "open leading 0.912, open trailing 0.912" in sentence
    ranked = fresh_ranking(comparison)
    assert ranked[0]["label"] == "design 11" and ranked[0]["exit_time_s"] == 3.1


def test_the_section_shows_the_familys_entries_box_and_parameters() -> None:
    text = _text(comparison_html(_comparison(), {}))
    assert "compared with default on the same fresh draws" in text
    assert "device family fig1's (theta, chute_width" in text
    assert "Cost: 160 drops" in text  # 40 trials x 2 entries x (1 design + the baseline)
    assert "open leading" in text and "open trailing" in text
    assert "heavy leading" not in text and "Table 2" not in text
    assert "of the family's box" in text and "family's box" in text
    assert "[0.3, 0.9]" in text  # theta's box
    for name in FIG1.vector_names:
        assert f" {name} " in text


def test_the_recommendation_box_gives_the_familys_exit_times() -> None:
    comparison = _comparison()
    box = _text(recommendation_html("design 11", comparison, None, "the first confirmed"))
    assert "Build design 11" in box
    # the baseline's leading entry has no mean exit time: n/a, never a dash and a unit
    assert "open leading 3.10 s, open trailing 2.40 s against open leading n/a" in box


def test_the_familys_devices_are_drawn_over_each_other(tmp_path: Path) -> None:
    figures = comparison_figures(_comparison(), tmp_path, family=FIG1)
    name = overlay_name("design 11")
    assert list(figures) == [name]
    assert figures[name].read_bytes()[:8] == PNG_MAGIC
