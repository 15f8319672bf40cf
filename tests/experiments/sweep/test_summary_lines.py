"""The sweep summary's lines name the denominator of every count they give (issue 39: "4 of
30 designs judged work (4 % [2 %, 10 %] of every design, n = 103)" put three in one line)
and never print a unit after an unknown value."""

from __future__ import annotations

import re

from experiments.sweep.summary import passive_counts, pipeline_line, summary_table


def passive(**changed) -> dict:
    """A passive summary as ``_passive_summary`` writes it: 30 designs judged, 4 work, 2
    undecided; the fraction over every design, 103 (73 proven to fail by sound rungs)."""
    return {
        "evaluated": 30,
        "works": 4,
        "fails": 24,
        "undecided": 2,
        "works_fraction": 4 / 103,
        "works_ci": [0.015, 0.096],
        "works_basis": "every design",
        "works_n": 103,
        "works_in_basis": 4,
        "mean_trials": 41.5,
        "drops_per_s": 120.0,
        **changed,
    }


def test_every_count_in_the_passive_line_names_what_it_counts_among() -> None:
    assert passive_counts(passive()) == (
        "4 of 30 designs judged work, 2 undecided; 4 of 103 in every design (30 judged, 73 "
        "proven to fail below) work: 4% [2%, 10%]"
    )


def test_over_the_holdout_the_fraction_is_of_the_holdouts_designs() -> None:
    # the audit or holdout is judged whatever the rungs below said: 3 of its 20 work
    line = passive_counts(
        passive(works_basis="the holdout", works_n=20, works_in_basis=3, works_fraction=0.15)
    )
    assert line.endswith("3 of 20 in the holdout work: 15% [2%, 10%]")


def test_a_summary_written_before_works_in_basis_gives_the_count_from_the_fraction() -> None:
    old = passive()
    del old["works_in_basis"]
    assert "4 of 103 in every design" in passive_counts(old)


def summary_of(passive_line: dict) -> dict:
    """A sweep's summary of 8 designs with no levels, pruning or best: only ``passive``."""
    return {
        "name": "s",
        "designs": 8,
        "holdout": 0,
        "levels": [],
        "pruning": [],
        "speedup": None,
        "passive": passive_line,
        "best": [],
        "quarantined": [],
    }


def test_a_pipeline_with_no_cost_reads_n_a_and_a_top_design_with_no_exit_time_too() -> None:
    summary = {
        **summary_of(passive()),
        "pipelines": [
            {
                "rungs": ["screen", "passive"],
                "cost_s": None,
                "speedup": None,
                "n": 0,
                "recall": None,
                "recall_ci": [None, None],
            }
        ],
        "best": [{"design_id": 3, "exit_time_s": None}],
    }
    text = summary_table(summary)
    assert "work: 4% [2%, 10%]; 41.5 trials per verdict, 120 drops/s" in text
    assert "pipeline screen -> passive: n/a (holdout n=0), speed-up - at recall" in text
    assert "top: design 3, exit time n/a" in text
    assert "- s" not in text


def test_a_passive_line_with_no_trials_counted_reads_n_a() -> None:
    # every design of the basis proven to fail below: none judged, no trials, no drops/s
    summary = summary_of(
        passive(evaluated=0, works=0, undecided=0, mean_trials=None, drops_per_s=None)
    )
    assert "n/a trials per verdict, n/a drops/s" in summary_table(summary)


def pipeline(**changed) -> dict:
    """A pipeline row as ``_pipelines`` writes it: screen -> passive on the audit's 64
    designs, 4 of which reached the verdict, all 4 that work kept."""
    return {
        "rungs": ["screen", "passive"],
        "cost_s": 0.04,
        "cost_ci": [0.03, 0.05],
        "n": 64,
        "reached": [64, 4],
        "unreached": [],
        "basis": "the audit",
        "recall": 1.0,
        "recall_ci": [0.51, 1.0],
        "recall_n": 4,
        "recall_basis": "the audit",
        "thrown_away": [],
        "speedup": 1.97,
        "speedup_ci": [1.49, 3.18],
        **changed,
    }


def test_a_pipeline_says_how_many_designs_reached_each_rung_and_its_recall_beside_its_speed_up():
    assert pipeline_line(pipeline()) == (
        "pipeline screen -> passive: 0.04 s/design (audit n=64; reached screen 64, passive 4), "
        "speed-up 1.97x [1.49, 3.18] at recall 100% [51%, 100%] (4 of 4 that work, the audit)"
    )


def test_a_pipeline_whose_later_rungs_saw_no_design_prints_no_speed_up() -> None:
    # issue 36: no holdout design passed the screen, so every pipeline starting with it
    # printed the screen's cost as "14.73x"
    row = pipeline(
        rungs=["screen", "geometric", "passive"],
        n=8,
        basis="the holdout",
        reached=[8, 0, 0],
        unreached=["geometric", "passive"],
        cost_s=None,
        speedup=None,
        speedup_ci=[None, None],
    )
    line = pipeline_line(row)
    assert line == (
        "pipeline screen -> geometric -> passive: holdout n=8; reached screen 8, geometric 0, "
        "passive 0: no holdout design reached geometric, so its cost would be the rungs below "
        "alone; no cost or speed-up is given"
    )
    assert "x [" not in line


def test_a_speed_up_bought_with_every_working_design_says_recall_0_of_2_beside_it() -> None:
    # paper.yaml's cut-down run printed "4.26x [2.63, 6.55]" for a ladder whose recall was 0
    # of 2: the old line had no recall at all
    row = {
        "top_level": "passive",
        "speedup": 4.26,
        "speedup_ci": [2.63, 6.55],
        "ladder_cost_s": 10.0,
        "dynamic_cost_s": 42.6,
        "recall": 0.0,
        "recall_ci": [0.0, 0.66],
        "recall_n": 2,
        "recall_basis": "the holdout",
        "thrown_away": [5, 9],
    }
    text = summary_table({**summary_of(passive()), "speedup": row})
    assert (
        "speed-up of the ladder up to passive over passive only: 4.26x [2.63, 6.55] at recall "
        "0% [0%, 66%] (0 of 2 that work, the holdout) (10 s of worker time vs ~43 s)"
    ) in text


def test_every_printed_speed_up_has_a_recall_beside_it() -> None:
    rows = [
        pipeline(),
        pipeline(recall_n=0, recall=None, recall_ci=[None, None], basis="the holdout"),
        pipeline(rungs=["passive"], reached=[4], speedup=1.0, speedup_ci=[1.0, 1.0]),
    ]
    summary = {
        **summary_of(passive()),
        "speedup": {
            "top_level": "passive",
            "speedup": 2.0,
            "speedup_ci": [1.5, 2.5],
            "ladder_cost_s": 1.0,
            "dynamic_cost_s": 2.0,
        },
        "pipelines": rows,
    }
    speed_lines = [line for line in summary_table(summary).splitlines() if "x [" in line]
    assert len(speed_lines) == 4
    for line in speed_lines:
        assert re.search(r"\d\.\d\dx \[[\d.]+, [\d.]+\] (at recall|\(its recall)", line), line
    assert "at recall unmeasured (no design that works in the audit)" in speed_lines[2]
    assert "(its recall not recorded)" in speed_lines[0]
