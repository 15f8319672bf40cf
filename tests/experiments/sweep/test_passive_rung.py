"""The passive rung of the sweep: a design's verdict (success probability over perturbed
passive drops, issue 13) as a rung of the ladder, stored, summarised and replayed as
pipelines."""

from __future__ import annotations

import copy
import json
import sqlite3
from pathlib import Path

import pytest
from sweep_fixtures import TINY, fake_result, fake_verdict

from experiments.drop.perturbations import Perturbations
from experiments.drop.verdict import VerdictSettings, design_verdict
from experiments.sweep import results_db
from experiments.sweep.config import ConfigError, config_from_dict
from experiments.sweep.job import evaluate_design, sweep_job, verdict_seed
from experiments.sweep.ladder import run_sweep
from experiments.sweep.summary import summarise, summary_table
from feeders.design import PRESETS, DesignParameters
from feeders.halton import halton_points
from feeders.part import DEFAULT_PEG

SMALL_VERDICT = {"target": 0.5, "min_drops": 4, "batch": 2, "max_drops": 6, "t_max": 4.0}
PASSIVE_ONLY = {
    **TINY,
    "designs": {"count": 3, "seed": 1},
    "feeder": {"friction": 0.05},
    "ladder": [{"level": "passive", "verdict": SMALL_VERDICT}],
    "holdout": {"fraction": 0.0, "seed": 7},
}
TABLE3 = [float(v) for v in PRESETS["table3"].to_vector()]


def test_a_passive_rung_is_read_with_every_setting_filled_in() -> None:
    config = config_from_dict(PASSIVE_ONLY)
    rung = config.ladder[0]
    assert rung.level == "passive" and rung.planners == ()
    defaults = VerdictSettings()
    assert rung.verdict == {**SMALL_VERDICT, "step": defaults.step}
    assert rung.perturbations == Perturbations().to_dict()
    again = config_from_dict(config.to_dict())
    assert again == config and again.results_key() == config.results_key()


@pytest.mark.parametrize(
    ("rung", "message"),
    [
        ({"verdict": {"target": 1.5}}, r"ladder\[0\]\.verdict\.target = 1\.5 .*\[0, 1\]"),
        ({"verdict": {"min_drops": 2.5}}, r"ladder\[0\]\.verdict\.min_drops .*whole number"),
        ({"verdict": {"min_drops": 9, "max_drops": 3}}, r"min_drops = 9 is more than"),
        ({"verdict": {"nosuch": 1}}, r"ladder\[0\]\.verdict.*nosuch"),
        ({"perturbations": {"yaw": 2.0}}, r"ladder\[0\]\.perturbations\.yaw = 2\.0 .*0\.5"),
        ({"planners": ["rrt"]}, r"ladder\[0\].*planners"),
    ],
)
def test_a_bad_passive_rung_is_refused_naming_the_field(rung: dict, message: str) -> None:
    data = copy.deepcopy(PASSIVE_ONLY)
    data["ladder"] = [{"level": "passive", **rung}]
    with pytest.raises(ConfigError, match=message):
        config_from_dict(data)


def test_the_passive_rung_may_stand_anywhere_but_the_planning_levels_keep_their_order() -> None:
    passive = {"level": "passive"}
    geometric, kinematic = TINY["ladder"][0], TINY["ladder"][1]
    for ladder in ([passive, geometric, kinematic], [geometric, passive, kinematic]):
        config_from_dict({**TINY, "ladder": ladder})
    with pytest.raises(ConfigError, match="planning levels in order"):
        config_from_dict({**TINY, "ladder": [passive, kinematic, geometric]})
    with pytest.raises(ConfigError, match="level twice"):
        config_from_dict({**TINY, "ladder": [passive, geometric, passive]})


def test_the_passive_evaluation_is_the_designs_verdict_with_the_sweeps_seed() -> None:
    """Reference: design_verdict called directly with the same part, friction, settings and
    the seed derived from the sweep's seed and the design id alone (not the rung)."""
    config = config_from_dict(PASSIVE_ONLY)
    job = sweep_job(config, 5, TABLE3, 0)
    result = evaluate_design(job)
    seed = verdict_seed(config.seed, 5)
    settings = VerdictSettings(**SMALL_VERDICT)
    direct = design_verdict(PRESETS["table3"], DEFAULT_PEG, 0.05, settings, seed=seed)
    stored = result["verdict"]
    assert result["verdict_seed"] == seed
    assert stored["decision"] == direct.decision and stored["drops"] == direct.drops
    assert stored["transitions"] == direct.transitions()
    assert result["status"] == ("feasible" if direct.works else "infeasible")
    # table3 is the paper's optimum: with the calibrated part it works at this small target
    assert direct.works and result["orientations"] == {
        "heavy_leading": True,
        "heavy_trailing": True,
    }


def test_a_design_that_cannot_be_built_is_degenerate_at_the_passive_rung() -> None:
    config = config_from_dict(PASSIVE_ONLY)
    values = list(TABLE3)
    names = list(DesignParameters.__dataclass_fields__)
    values[names.index("b")] = 0.05  # an exit chute far narrower than the part
    result = evaluate_design(sweep_job(config, 0, values, 0))
    assert result["status"] in ("degenerate", "infeasible")
    if result["status"] == "infeasible":  # buildable, but the part cannot pass
        assert result["verdict"]["both"]["successes"] == 0


def test_a_passive_sweep_stores_each_verdict_beside_its_evaluation(tmp_path: Path) -> None:
    """Run in worker processes; each stored verdict equals the verdict computed again here
    (the same seed gives the same verdict whatever process runs it)."""
    config = config_from_dict(PASSIVE_ONLY)
    path = run_sweep(config, tmp_path / "sweep")
    db = results_db.connect(path, readonly=True)
    try:
        verdicts = results_db.verdicts(db)
        status = {
            r["design_id"]: r["status"]
            for r in db.execute("SELECT design_id, status FROM evaluations")
        }
    finally:
        db.close()
    assert set(status) == {0, 1, 2}
    for design_id, verdict in verdicts.items():
        assert status[design_id] == ("feasible" if verdict["decision"] == "works" else "infeasible")
        again = evaluate_design(sweep_job(config, design_id, _values(path, design_id), 0))
        assert again["verdict"]["transitions"] == verdict["transitions"]
        assert again["verdict"]["drops"] == verdict["drops"]
    summary = summarise(path)
    assert summary["truth"] == "passive"
    passive = summary["passive"]
    assert passive["evaluated"] == 3 and passive["works_basis"] == "every design"
    assert passive["works"] + passive["fails"] + passive["undecided"] == len(verdicts)
    assert passive["drops"] == 2 * sum(v["drops"] for v in verdicts.values())


def _values(path: Path, design_id: int) -> list[float]:
    db = sqlite3.connect(path)
    try:
        row = db.execute("SELECT * FROM designs WHERE design_id = ?", (design_id,)).fetchone()
    finally:
        db.close()
    return [float(v) for v in row[2:]]


def test_pipelines_replay_the_holdout_by_hand(tmp_path: Path) -> None:
    """Four holdout designs, stored by hand (geometric then passive; times in s):
    design 0: geometric feasible 1.0, passive works 0.5 (k=40 of 40, exit 2.0 s)
    design 1: geometric infeasible 1.0, passive works 0.5 (k=38 of 40, exit 1.0 s)
    design 2: geometric infeasible 1.0, passive fails 0.1
    design 3: geometric feasible 1.0, passive fails 0.1
    passive alone costs (0.5 + 0.5 + 0.1 + 0.1) / 4 = 0.3 s per design and keeps both that
    work; geometric first costs (1.5 + 1 + 1 + 1.1) / 4 = 1.15 s and keeps 1 of 2 (recall
    0.5). Ranking: design 0 first (lower bound of P(both) 0.9 vs 0.85)."""
    config = config_from_dict(
        {
            **PASSIVE_ONLY,
            "designs": {"count": 4, "seed": 1},
            "ladder": [TINY["ladder"][0], {"level": "passive"}],
            "holdout": {"fraction": 1.0, "seed": 7},
        }
    )
    path = tmp_path / "results.sqlite"
    db = results_db.connect(path)
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(4, 1)
        results_db.add_designs(db, ((i, True, list(points[i])) for i in range(4)))
        plan = [
            (0, "feasible", "feasible", fake_verdict("works", 40, 40, 2.0), 0.5),
            (1, "infeasible", "feasible", fake_verdict("works", 38, 40, 1.0), 0.5),
            (2, "infeasible", "infeasible", fake_verdict("fails", 0, 10, None), 0.1),
            (3, "feasible", "infeasible", fake_verdict("fails", 1, 10, None), 0.1),
        ]
        for d, geometric, passive, verdict, wall in plan:
            results_db.record(db, fake_result(d, "geometric", geometric, 1.0), 0, 1)
            results_db.record(db, fake_result(d, "passive", passive, wall, verdict), 1, 1)
    finally:
        db.close()
    summary = summarise(path)
    pipes = {tuple(p["rungs"]): p for p in summary["pipelines"]}
    assert pipes[("passive",)]["cost_s"] == pytest.approx(0.3)
    assert pipes[("passive",)]["recall"] == 1.0
    assert pipes[("geometric", "passive")]["cost_s"] == pytest.approx(1.15)
    assert pipes[("geometric", "passive")]["recall"] == 0.5
    assert pipes[("geometric", "passive")]["speedup"] == pytest.approx(0.3 / 1.15)
    # all 4 reach geometric; designs 0 and 3 pass it and reach the verdict
    assert pipes[("geometric", "passive")]["reached"] == [4, 2]
    # the ladder's own geometric rung does not prune (a planner's miss is "unknown" and
    # climbs on): up to the verdict it keeps both designs that work, a census
    ladder = summary["speedup"]
    assert (ladder["recall_n"], ladder["thrown_away"]) == (2, [])
    assert ladder["recall_basis"] == "every design"
    assert [b["design_id"] for b in summary["best"]] == [0, 1]
    assert summary["best"][0]["exit_time_s"] == 2.0
    pruning = summary["pruning"][0]
    assert (pruning["tp"], pruning["fp"], pruning["fn"], pruning["tn"]) == (1, 1, 1, 1)
    assert summary["passive"]["works_basis"] == "the holdout"
    assert summary["passive"]["works_fraction"] == 0.5


def test_a_pipeline_whose_verdict_no_holdout_design_reached_has_no_speed_up(
    tmp_path: Path,
) -> None:
    """Geometric, pruning, stops all 4 holdout designs (1.0 s each; their verdicts 0.5 s
    each, 2 work): geometric -> passive reached the verdict with none of them, so its cost
    would be geometric's alone and its speed-up meaningless (issue 36); the row says so, and
    the ladder's speed-up says that it kept 0 of the 2 that work."""
    config = config_from_dict(
        {
            **PASSIVE_ONLY,
            "designs": {"count": 4, "seed": 1},
            "ladder": [{**TINY["ladder"][0], "prunes": True}, {"level": "passive"}],
            "holdout": {"fraction": 1.0, "seed": 7},
        }
    )
    path = tmp_path / "results.sqlite"
    db = results_db.connect(path)
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(4, 1)
        results_db.add_designs(db, ((i, True, list(points[i])) for i in range(4)))
        for d in range(4):
            works = d < 2
            verdict = (
                fake_verdict("works", 40, 40, 2.0) if works else fake_verdict("fails", 0, 10, None)
            )
            results_db.record(db, fake_result(d, "geometric", "infeasible", 1.0), 0, 1)
            passive = "feasible" if works else "infeasible"
            results_db.record(db, fake_result(d, "passive", passive, 0.5, verdict), 1, 1)
    finally:
        db.close()
    summary = summarise(path)
    pipe = next(p for p in summary["pipelines"] if p["rungs"] == ["geometric", "passive"])
    assert pipe["reached"] == [4, 0]
    assert pipe["unreached"] == ["passive"]
    assert pipe["speedup"] is None and pipe["cost_s"] is None
    text = summary_table(summary)
    assert "no holdout design reached passive, so its cost would be the rungs below" in text
    assert "at recall 0% [0%, 66%] (0 of 2 that work, the holdout)" in text


def _claimed(path: Path, statement: str, *values) -> Path:
    """A results database of PASSIVE_ONLY at ``path``, then ``statement`` run in it."""
    config = config_from_dict(PASSIVE_ONLY)
    db = results_db.connect(path)
    results_db.claim(db, config.to_dict(), config.results_key())
    with db:
        db.execute(statement, values)
    db.close()
    return path


def test_a_results_database_made_before_the_verdicts_table_is_resumed(tmp_path: Path) -> None:
    path = _claimed(tmp_path / "results.sqlite", "DROP TABLE verdicts")
    assert results_db.verdicts(results_db.connect(path, readonly=True)) == {}
    db = results_db.connect(path)  # the missing table is made
    try:
        tables = {r[0] for r in db.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    finally:
        db.close()
    assert "verdicts" in tables


def test_a_verdict_row_this_program_cannot_write_is_refused(tmp_path: Path) -> None:
    path = _claimed(
        tmp_path / "results.sqlite",
        "INSERT INTO verdicts VALUES (0, 'maybe', 0.9, 10, 1, 1, 1, NULL, NULL, 1, ?)",
        json.dumps({}),
    )
    with pytest.raises(results_db.ResultsDamaged, match="verdicts"):
        results_db.connect(path)


@pytest.mark.slow  # end to end, run by CI's longer job (issue 22)
def test_the_passive_verdicts_are_the_same_on_the_dask_executor(tmp_path: Path) -> None:
    """Reference: the same sweep on the local executor (worker processes)."""
    distributed = pytest.importorskip("distributed")
    config = config_from_dict(PASSIVE_ONLY)
    local = run_sweep(config, tmp_path / "local")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        remote = run_sweep(
            config, tmp_path / "dask", executor="dask", scheduler=cluster.scheduler_address
        )
    stored = []
    for path in (local, remote):
        db = results_db.connect(path, readonly=True)
        try:
            verdicts = results_db.verdicts(db)
        finally:
            db.close()
        stored.append({d: {**v, "wall_time_s": None} for d, v in verdicts.items()})
    assert stored[0] == stored[1] and len(stored[0]) == 3
