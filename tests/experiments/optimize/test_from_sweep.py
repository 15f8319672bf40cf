"""``partfeeder optimize --from SWEEP_DIR``: the starts are the sweep's designs that work, in
the order of its summary (lower bound of P(both), then exit time); a sweep without any is a
usage error. The sweep database is made by hand (its verdicts need not be computed here)."""

from __future__ import annotations

from pathlib import Path

import pytest
from sweep_fixtures import TINY, fake_result, fake_verdict

from experiments.cli.optimize import sweep_best_designs
from experiments.cli.usage import UsageError
from experiments.optimize.config import config_from_dict as optimize_config
from experiments.optimize.run import start_designs
from experiments.sweep import results_db
from experiments.sweep.config import config_from_dict
from feeders.design import preset
from feeders.halton import halton_points


def _sweep(directory: Path, plan: list[tuple[int, str, dict]]) -> Path:
    config = config_from_dict(
        {
            **TINY,
            "designs": {"count": len(plan), "seed": 1},
            "ladder": [{"level": "passive"}],
            "holdout": {"fraction": 0.0, "seed": 7},
        }
    )
    directory.mkdir()
    db = results_db.connect(directory / "results.sqlite")
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(len(plan), 1)
        results_db.add_designs(db, ((i, False, list(points[i])) for i in range(len(plan))))
        for d, status, verdict in plan:
            results_db.record(db, fake_result(d, "passive", status, 0.1, verdict), 0, 1)
    finally:
        db.close()
    return directory


def test_the_starts_are_the_sweeps_working_designs_best_first(tmp_path):
    sweep = _sweep(
        tmp_path / "sweep",
        [
            (0, "infeasible", fake_verdict("fails", 0, 10, None)),
            (1, "feasible", fake_verdict("works", 38, 40, 2.0)),
            (2, "feasible", fake_verdict("works", 40, 40, 2.5)),
        ],
    )
    best = sweep_best_designs(sweep)
    config = optimize_config(
        {"methods": [{"method": "powell", "budget": 1}], "start": {"sweep_best": 6}}
    )
    starts = start_designs(config, best)
    assert list(starts) == ["table3", "sweep:2", "sweep:1"]
    assert starts["sweep:2"] == pytest.approx(list(halton_points(3, 1)[2]))


def test_a_sweep_where_nothing_works_is_a_usage_error(tmp_path):
    sweep = _sweep(tmp_path / "sweep", [(0, "infeasible", fake_verdict("fails", 0, 10, None))])
    with pytest.raises(UsageError, match="no design of that sweep works"):
        sweep_best_designs(sweep)


def test_a_directory_that_is_not_a_sweep_is_a_usage_error(tmp_path):
    with pytest.raises(UsageError, match=r"no results\.sqlite"):
        sweep_best_designs(tmp_path)


def test_a_start_inside_the_box_is_kept_to_the_last_bit():
    # contact is chaotic: a start rounded through the unit cube (gx 0.733 -> 0.7329999999999999)
    # was another design, whose mean G differed from table3's by 0.05 s
    config = optimize_config({"methods": [{"method": "powell", "budget": 1}]})
    assert start_designs(config, [])["table3"] == preset("table3").to_vector().tolist()
