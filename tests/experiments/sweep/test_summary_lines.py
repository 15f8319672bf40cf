"""The sweep summary's lines name the denominator of every count they give (issue 39: "4 of
30 designs judged work (4 % [2 %, 10 %] of every design, n = 103)" put three in one line)
and never print a unit after an unknown value."""

from __future__ import annotations

from experiments.sweep.summary import passive_counts, summary_table


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
    assert "pipeline screen -> passive: n/a (holdout n=0)" in text
    assert "top: design 3, exit time n/a" in text
    assert "- s" not in text


def test_a_passive_line_with_no_trials_counted_reads_n_a() -> None:
    # every design of the basis proven to fail below: none judged, no trials, no drops/s
    summary = summary_of(
        passive(evaluated=0, works=0, undecided=0, mean_trials=None, drops_per_s=None)
    )
    assert "n/a trials per verdict, n/a drops/s" in summary_table(summary)
