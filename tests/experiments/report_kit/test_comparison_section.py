"""The "Why this design" section says, from the numbers, whether the fresh draws confirm the
ranking, and shows both designs' numbers and the parameter differences."""

from __future__ import annotations

from experiments.proportions import wilson_interval
from experiments.report_kit.comparison_section import (
    comparison_html,
    confirmation,
    fresh_ranking,
    overlay_name,
)


def verdict(k_leading: int, k_trailing: int, n: int) -> dict:
    def per(k: int) -> dict:
        return {
            "successes": k,
            "p": k / n,
            "interval": list(wilson_interval(k, n)),
            "mean_exit_time_s": 2.25,
        }

    both = min(k_leading, k_trailing)
    return {
        "decision": "n/a",
        "drops": n,
        "orientations": {"heavy_leading": per(k_leading), "heavy_trailing": per(k_trailing)},
        "both": {"successes": both, "p": both / n, "interval": list(wilson_interval(both, n))},
        "transitions": {
            "heavy_leading": {"heavy end down": k_leading, "heavy end up": n - k_leading},
            "heavy_trailing": {"heavy end down": k_trailing, "caught on the pin": n - k_trailing},
        },
    }


def entry(k_leading: int, k_trailing: int, n: int = 40) -> dict:
    return {"label": "design 5", "values": [], "verdict": verdict(k_leading, k_trailing, n)}


def test_all_successes_on_40_draws_confirm_a_target_of_0_9() -> None:
    ok, sentence = confirmation(entry(40, 40), 40, 0.9)
    assert ok and sentence.startswith("confirmed:") and "0.912" in sentence


def test_one_failure_in_40_leaves_it_undecided_and_says_what_would_confirm() -> None:
    ok, sentence = confirmation(entry(40, 39), 40, 0.9)
    assert not ok and sentence.startswith("not confirmed: undecided")
    assert "0.871" in sentence and "40 of 40 would give 0.912" in sentence


def test_a_clear_failure_on_fresh_draws_is_said_to_fail() -> None:
    ok, sentence = confirmation(entry(40, 20), 40, 0.9)
    assert not ok and "fails" in sentence and "heavy trailing" in sentence


def test_a_design_that_cannot_be_built_is_not_confirmed() -> None:
    ok, sentence = confirmation({"label": "x", "verdict": None, "reason": "walls cross"}, 40, 0.9)
    assert not ok and "walls cross" in sentence


def test_the_section_shows_both_designs_numbers_and_the_differences() -> None:
    comparison = {
        "seed": 77,
        "drops": 40,
        "target": 0.9,
        "wall_time_s": 1.5,
        "baseline": {"label": "table3", "values": [], "verdict": verdict(38, 37, 40)},
        "designs": [
            {
                **entry(40, 40),
                "differences": [
                    {
                        "name": "a",
                        "design": 1.2,
                        "baseline": 1.1,
                        "difference": 0.1,
                        "fraction": 1.0,
                    }
                ],
                "paired": {"draws": 40, "design_only": 2, "baseline_only": 0},
            }
        ],
    }
    text = "\n".join(comparison_html(comparison, {}))
    assert "Why this design" in text and "seed 77" in text and "160 drops in 1.5 s" in text
    assert "confirmed</b>" in text and "not confirmed" not in text
    assert "38 / 40" in text and "40 / 40" in text and "2.250" in text
    assert "heavy end up" in text and "caught on the pin" in text  # the baseline's matrix
    assert "+100%" in text and "width of input chute" in text
    assert "on 2, table3 where design 5 did not on 0" in text
    assert "No drawing" in text  # no overlay figure given


def test_overlay_names_are_file_safe() -> None:
    assert overlay_name("design 31") == "overlay_design_31"


def test_fresh_ranking_puts_confirmed_designs_first_then_the_faster_on_a_tie() -> None:
    slow = entry(40, 40)
    slow["label"] = "slow"
    fast = entry(40, 40)
    fast["label"] = "fast"
    fast["verdict"]["orientations"]["heavy_trailing"]["mean_exit_time_s"] = 2.0
    slow["verdict"]["orientations"]["heavy_trailing"]["mean_exit_time_s"] = 3.0
    lucky = entry(40, 30)  # ranked first on its own draws, refuted on the fresh ones
    lucky["label"] = "lucky"
    comparison = {"drops": 40, "target": 0.9, "designs": [lucky, slow, fast]}
    ranked = fresh_ranking(comparison)
    assert [r["label"] for r in ranked] == ["fast", "slow", "lucky"]
    assert [r["confirmed"] for r in ranked] == [True, True, False]
    assert ranked[0]["exit_time_s"] == 2.25  # the slower entry's time limits the rate
