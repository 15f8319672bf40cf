"""The cup family's sweep (issue 24: "the cup family's sweep the same on the local and Dask
executors"): the second worked example's designs, screened and judged with the cup, give the
same database rows with one worker, with two, and on a Dask cluster. The reference is the
one-worker local run: a design's results depend only on the design and the sweep's seeds."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pytest

from experiments.sweep.config import config_from_dict
from experiments.sweep.ladder import run_sweep

CUP_SWEEP = {
    "name": "tiny-cup",
    "family": "fig1-cup",
    "designs": {"count": 10, "seed": 0},
    "ladder": [
        {"level": "screen", "screen": {"max_drops": 12}},
        {
            "level": "passive",
            "verdict": {"target": 0.5, "min_drops": 3, "batch": 3, "max_drops": 6, "t_max": 6.0},
        },
    ],
    "holdout": {"fraction": 0.0, "seed": 7},
    "audit": {"fraction": 1.0, "seed": 11},
}
QUERIES = (
    "SELECT * FROM designs ORDER BY design_id",
    "SELECT design_id, level, rung, status, reason, heavy_leading, heavy_trailing "
    "FROM evaluations ORDER BY design_id, rung",
    "SELECT design_id, decision, trials, heavy_leading, heavy_trailing, both_entries, "
    "exit_heavy_leading_s, exit_heavy_trailing_s, seed, verdict FROM verdicts ORDER BY design_id",
)


def _rows(path: Path) -> list[list[tuple]]:
    """The rows of ``QUERIES``; a verdict's JSON without its wall time (the one thing that
    depends on the machine)."""
    db = sqlite3.connect(path)
    try:
        designs, evaluations, verdicts = (db.execute(q).fetchall() for q in QUERIES)
    finally:
        db.close()
    timeless = []
    for row in verdicts:
        verdict = json.loads(row[-1])
        verdict.pop("wall_time_s", None)
        timeless.append((*row[:-1], verdict))
    return [designs, evaluations, timeless]


@pytest.fixture(scope="module")
def one_worker(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("cup-one")
    return run_sweep(config_from_dict({**CUP_SWEEP, "workers": 1}), out)


def test_the_cup_sweep_judges_its_designs_with_the_cups_classes(one_worker: Path) -> None:
    designs, evaluations, verdicts = _rows(one_worker)
    assert len(designs) == 10
    assert {e[3] for e in evaluations} >= {"degenerate"} and len(verdicts) > 0
    for verdict in (v[-1] for v in verdicts):  # the transition matrix names the cup's classes
        assert all("open end up" in row for row in verdict["transitions"].values())


@pytest.mark.slow  # ~5 s
def test_the_same_with_two_local_workers(one_worker: Path, tmp_path: Path) -> None:
    two = run_sweep(config_from_dict({**CUP_SWEEP, "workers": 2}), tmp_path)
    assert _rows(two) == _rows(one_worker)


@pytest.mark.slow  # end to end on a Dask cluster, run by CI's longer job (issue 22)
def test_the_same_on_the_dask_executor(one_worker: Path, tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        remote = run_sweep(
            config_from_dict(CUP_SWEEP),
            tmp_path,
            executor="dask",
            scheduler=cluster.scheduler_address,
        )
    assert _rows(remote) == _rows(one_worker)
