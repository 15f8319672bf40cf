"""``partfeeder optimize`` on a device family (issue 24), end to end with tiny budgets: the
design vector is the family's (its parameters, its box), the objective's trials are the
family's verdict trials (made to tolerance by ``made_devices``), the store keeps the family's
parameter names, the baseline is the family's default, and the report draws both designs'
nominal drops from the family's entries. The same on a Dask cluster (slow)."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import numpy as np
import pytest

from experiments.drop.family_verdict import entry_names, made_devices
from experiments.drop.perturbations import Perturbations
from experiments.drop.verdict import run_trial
from experiments.drop.verdict_settings import VerdictSettings
from experiments.optimize import store
from experiments.optimize.config import config_from_dict
from experiments.optimize.objective import trial_to_dict
from experiments.optimize.report import write_report
from experiments.optimize.run import DATABASE, optimise

CUP = {
    "name": "tiny-cup",
    "family": "fig1-cup",
    "objective": {"trials": 3, "seed": 0},
    "start": {"presets": ["default"]},
    "methods": [{"method": "differential-evolution", "budget": 6, "seeds": [0], "population": 5}],
    "final": {"trials": 4, "seed": 1000, "candidates": 2},
    "workers": 2,
}


@pytest.fixture(scope="module")
def cup_run(tmp_path_factory: pytest.TempPathFactory):
    """The tiny fig1-cup optimisation, run once for the module (a few seconds)."""
    out = tmp_path_factory.mktemp("cup-optimise")
    config = config_from_dict(CUP)
    return out, config, optimise(config, out)


def test_the_design_vector_is_the_familys_within_its_box(cup_run) -> None:
    _, config, results = cup_run
    family = config.device_family()
    assert family is not None
    names = list(family.vector_names)
    low, high = family.bounds()
    assert results["parameters"] == names and results["family"]["parameters"] == names
    assert results["entries"] == ["open_leading", "open_trailing"]
    for label in ("optimum", "default"):
        values = results[label]["values"]
        assert list(values) == names
        assert np.all(np.array(list(values.values())) >= low)
        assert np.all(np.array(list(values.values())) <= high)
    assert results["compared_with"] == "default"
    assert list(results["default"]["values"].values()) == list(family.default())
    assert list(results["optimum"]["verdict"]["orientations"]) == names_of_entries(family)
    assert results["evaluations"] >= 2


def names_of_entries(family) -> list[str]:
    return list(entry_names(family))


def test_the_store_holds_the_familys_vectors_and_record(cup_run) -> None:
    out, config, _ = cup_run
    family = config.device_family()
    db = store.connect(out / DATABASE, readonly=True)
    try:
        keys = list(store.evaluations(db))
        meta = json.loads(db.execute("SELECT value FROM meta WHERE key = 'config'").fetchone()[0])
    finally:
        db.close()
    assert keys and all(len(store.design_of_key(k)) == len(family.vector_names) for k in keys)
    assert meta["family_record"]["parameters"] == list(family.vector_names)
    assert meta["family_record"]["yaml"] == config.family_yaml


def test_a_start_is_evaluated_by_the_familys_verdict_trials(cup_run) -> None:
    out, config, _ = cup_run
    family = config.device_family()
    default = [float(v) for v in family.default()]
    db = store.connect(out / DATABASE, readonly=True)
    try:
        stored = store.evaluations(db)[store.design_key(default)]["trial_data"]
    finally:
        db.close()
    settings = VerdictSettings(
        step=config.step, t_max=config.t_max, perturbations=Perturbations(**config.perturbations)
    )
    make = made_devices(family, default)
    n = len(family.vector_names)
    expected = [
        trial_to_dict(run_trial(make, entry_names(family), settings, config.seed, i, n))
        for i in range(config.trials)
    ]
    assert stored == expected


@pytest.mark.slow  # ~8 s
def test_the_report_builds_with_both_designs_strips_and_says_what_is_left_out(cup_run) -> None:
    out, config, results = cup_run
    page = write_report(out, config, results)
    text = page.read_text()
    for label in ("optimum", "default"):
        assert (out / "figures" / f"strip_design_{label}.png").stat().st_size > 10_000
        assert f"strip_design_{label}.png" in text
    assert "theta = " in text and "Device family fig1-cup" in text
    assert "The design: the family's parameters" in text and "chute_width" in text
    assert "The comparison is not shown" in text and "12-parameter feeder" in text
    assert results["margins"] is None  # measured for an optimum that works (margins tests)
    # undecided on 4 trials (issue 39: it was said not to work)
    assert (
        "is undecided (too few trials to tell whether it works at the target) on its 4 "
        "fresh trials" in results["margins_absent"]
    )


def test_a_second_run_evaluates_nothing_again(cup_run) -> None:
    out, config, results = cup_run
    again = optimise(config, out)
    assert again["new_evaluations"] == 0
    assert again["optimum"]["values"] == results["optimum"]["values"]


def test_a_directory_of_the_feeders_optimisation_is_refused(tmp_path: Path) -> None:
    feeder = config_from_dict(
        {k: v for k, v in CUP.items() if k not in ("family", "start")}, "feeder"
    )
    db = store.connect(tmp_path / DATABASE)
    try:
        store.claim(db, feeder.to_dict(), feeder.objective_key())
    finally:
        db.close()
    with pytest.raises(store.StoreMismatch, match="another objective"):
        optimise(config_from_dict(CUP), tmp_path)
    assert sqlite3.connect(tmp_path / DATABASE).execute(
        "SELECT COUNT(*) FROM evaluations"
    ).fetchone() == (0,)


@pytest.mark.slow  # end to end on a Dask cluster, run by CI's longer job
def test_same_result_on_a_dask_cluster(cup_run, tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    _, config, local = cup_run
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        remote = optimise(
            config, tmp_path / "dask", executor="dask", scheduler=cluster.scheduler_address
        )
    assert remote["runs"] == local["runs"]
    assert remote["optimum"]["values"] == local["optimum"]["values"]
    assert remote["optimum"]["verdict"]["transitions"] == local["optimum"]["verdict"]["transitions"]
