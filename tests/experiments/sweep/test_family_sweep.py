"""The Halton sweep on a device family (issue 24): the packaged Fig. 1 family's designs drawn
from its box, screened and judged by the family's own screen and verdict, stored under its
parameter names, summarised and reported; the same on Dask; a database of another family or
of the feeder refused on resume; the feeder-only ``necessary`` rung refused with a family."""

from __future__ import annotations

import copy
import json
import sqlite3
from html.parser import HTMLParser
from pathlib import Path

import pytest
import yaml
from cli_process import run_cli

from experiments.drop.family_verdict import family_screen, family_verdict
from experiments.drop.perturbations import Perturbations
from experiments.drop.screen_settings import ScreenSettings
from experiments.drop.verdict_settings import VerdictSettings
from experiments.sweep import results_db
from experiments.sweep.config import ConfigError, config_from_dict, load_config
from experiments.sweep.job import screen_seed, verdict_seed
from experiments.sweep.ladder import run_sweep
from experiments.sweep.report import write_report
from experiments.sweep.summary import summarise
from feeders.device_family import load_family
from feeders.feeder import DegenerateDesign
from feeders.halton import halton_points

FIG1 = Path(__file__).resolve().parents[3] / "feeders" / "families" / "fig1.yaml"
SCREEN = {"max_drops": 20}
VERDICT = {"target": 0.5, "min_drops": 4, "batch": 2, "max_drops": 6, "t_max": 4.0}
TINY_FAMILY = {
    "name": "tiny-fig1",
    "family": "fig1",
    "designs": {"count": 12, "seed": 1},  # design 11 works
    "ladder": [
        {"level": "screen", "screen": SCREEN},
        {"level": "passive", "verdict": VERDICT},
    ],
    "holdout": {"fraction": 0.0, "seed": 7},
    "audit": {"fraction": 1.0, "seed": 11},
    "workers": 2,
}


@pytest.fixture(scope="module")
def swept(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The tiny fig1 sweep, run once for the module's tests (a few seconds)."""
    out = tmp_path_factory.mktemp("family-sweep")
    run_sweep(config_from_dict(TINY_FAMILY), out)
    return out


def _rows(path: Path, query: str) -> list[tuple]:
    db = sqlite3.connect(path)
    try:
        return db.execute(query).fetchall()
    finally:
        db.close()


def test_a_family_config_reads_the_packaged_family_and_round_trips() -> None:
    config = config_from_dict(TINY_FAMILY)
    family = config.device_family()
    assert family is not None and family.vector_names == load_family(FIG1).vector_names
    assert config.family == str(FIG1.resolve())
    again = config_from_dict(config.to_dict())
    assert again == config and again.results_key() == config.results_key()


def test_a_family_file_is_found_relative_to_the_config_file(tmp_path: Path) -> None:
    (tmp_path / "devices").mkdir()
    (tmp_path / "devices" / "mine.yaml").write_text(FIG1.read_text())
    data = {**TINY_FAMILY, "family": "devices/mine.yaml"}
    (tmp_path / "sweep.yaml").write_text(yaml.safe_dump(data))
    config = load_config(tmp_path / "sweep.yaml")
    assert config.family == str((tmp_path / "devices" / "mine.yaml").resolve())
    # the same text is the same family, wherever its file lies: the results key agrees
    assert config.results_key() == config_from_dict(TINY_FAMILY).results_key()


def test_a_config_without_family_is_the_feeder_and_its_key_is_unchanged() -> None:
    feeder = {k: v for k, v in TINY_FAMILY.items() if k != "family"}
    config = config_from_dict(feeder)
    assert config.family is None and config.device_family() is None
    assert "family" not in config.to_dict()


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (
            {"ladder": [{"level": "necessary"}, {"level": "passive"}]},
            r"^ladder\[0\]\.level = necessary: .*12-parameter feeder's; allowed with family: ",
        ),
        ({"family": "nosuch"}, r"^family = 'nosuch' is neither a file .* packaged families: fig1"),
        ({"family": 3}, r"^family = 3; allowed: "),
        ({"feeder": {"friction": 0.1}}, r"^feeder: \['friction'\] given with family"),
    ],
)
def test_a_bad_family_config_is_refused_in_one_line_naming_the_field(
    change: dict, message: str
) -> None:
    with pytest.raises(ConfigError, match=message) as caught:
        config_from_dict({**TINY_FAMILY, **change})
    assert "\n" not in str(caught.value)


def test_a_family_config_with_the_necessary_rung_exits_2_at_the_cli(tmp_path: Path) -> None:
    data = {**TINY_FAMILY, "ladder": [{"level": "necessary"}, {"level": "passive"}]}
    (tmp_path / "necessary.yaml").write_text(yaml.safe_dump(data))
    done = run_cli("run", str(tmp_path / "necessary.yaml"), "--out", str(tmp_path / "out"))
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "ladder[0].level = necessary" in done.stderr
    assert not (tmp_path / "out").exists()


def test_a_family_with_a_parameter_that_cannot_name_a_column_is_refused(tmp_path: Path) -> None:
    data = yaml.safe_load(FIG1.read_text())
    data["parameters"] = {
        "holdout" if k == "pin_r" else k: v for k, v in data["parameters"].items()
    }
    text = yaml.safe_dump(data, sort_keys=False).replace("pin_r", "holdout")
    (tmp_path / "bad.yaml").write_text(text)
    with pytest.raises(
        ConfigError, match=r"^family: .*parameters.holdout: a column the sweep writes itself"
    ):
        config_from_dict({**TINY_FAMILY, "family": "bad.yaml"}, base=tmp_path)


def test_the_designs_are_the_halton_points_of_the_familys_box_under_its_names(
    swept: Path,
) -> None:
    family = load_family(FIG1)
    path = swept / "results.sqlite"
    db = results_db.connect(path, readonly=True)
    try:
        assert results_db.parameter_names(db) == family.vector_names
        stored = results_db.stored_family(db)
    finally:
        db.close()
    assert stored is not None and stored["name"] == "fig1"
    assert stored["entries"] == ["open_leading", "open_trailing"]
    assert stored["yaml"] == FIG1.read_text()
    names = ", ".join(family.vector_names)
    values = _rows(path, f"SELECT {names} FROM designs ORDER BY design_id")
    assert values == [tuple(p) for p in halton_points(12, 1, family.space()).tolist()]


def test_the_screen_and_the_verdict_are_the_familys_with_the_sweeps_seeds(swept: Path) -> None:
    """Reference: family_screen and family_verdict called directly with the rung's settings
    and the seeds derived from the sweep's seed and the design id, as the feeder's are."""
    family = load_family(FIG1)
    path = swept / "results.sqlite"
    evaluations = {
        (d, level): (status, reason)
        for d, level, status, reason in _rows(
            path, "SELECT design_id, level, status, reason FROM evaluations"
        )
    }
    stored = {d: json.loads(v) for d, v in _rows(path, "SELECT design_id, verdict FROM verdicts")}
    designs = _rows(path, f"SELECT design_id, {', '.join(family.vector_names)} FROM designs")
    built = refused = 0
    for design_id, *values in designs:
        try:
            family.build(values)
        except DegenerateDesign as exc:
            refused += 1
            assert evaluations[(design_id, "screen")] == ("degenerate", exc.reason)
            assert evaluations[(design_id, "passive")] == ("degenerate", exc.reason)
            continue
        built += 1
        screen = family_screen(
            family,
            values,
            ScreenSettings(**SCREEN, perturbations=Perturbations()),
            screen_seed(1, design_id),
        )
        expected = {"passes": "feasible", "fails": "infeasible"}.get(screen.decision, "unknown")
        assert evaluations[(design_id, "screen")][0] == expected
        verdict = family_verdict(
            family,
            values,
            VerdictSettings(**VERDICT, perturbations=Perturbations()),
            verdict_seed(1, design_id),
        ).to_dict()
        assert {**stored[design_id], "wall_time_s": None} == {**verdict, "wall_time_s": None}
    assert built >= 3 and refused >= 1  # both kinds of design are exercised


@pytest.mark.slow  # ~6 s
def test_the_summary_and_the_report_use_the_familys_parameters(swept: Path) -> None:
    summary = summarise(swept / "results.sqlite")
    assert summary["parameters"] == list(load_family(FIG1).vector_names)
    assert summary["family"]["name"] == "fig1" and "yaml" not in summary["family"]
    assert [lv["evaluated"] for lv in summary["levels"]] == [12, 12]
    assert summary["passive"]["works"] >= 1 and "verdict" in summary["best"][0]
    page = write_report(swept, summary, swept / "results.sqlite", margins=False)
    text = page.read_text(encoding="utf-8")
    parser = HTMLParser()
    parser.feed(text)  # it parses
    parser.close()
    assert "device family fig1" in text
    headers = set(_header_cells(text))
    assert set(load_family(FIG1).vector_names) <= headers
    assert not {"alpha", "gx", "gy", "fx", "fy"} & headers  # the feeder's names are not shown
    best = summary["best"][0]["design_id"]
    for figure in ("feasible_set", "best_designs", f"strip_design{best:06d}"):
        assert (swept / "figures" / f"{figure}.png").stat().st_size > 0
        assert f"figures/{figure}.png" in text


def _header_cells(text: str) -> list[str]:
    return [cell.split("</th>")[0] for cell in text.split("<th>")[1:]]


def _other_family(tmp_path: Path, name: str, rename: str | None = None) -> Path:
    """fig1's file under another family ``name``, with ``pin_r`` called ``rename``."""
    text = FIG1.read_text().replace("name: fig1", f"name: {name}")
    if rename:
        text = text.replace("pin_r", rename)
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("family", "message"),
    [
        ("other", r"^family: this directory holds a sweep of family 'fig1', this config's is "),
        ("feeder", r"^family: .* family 'fig1', this config's is the 12-parameter feeder"),
        ("renamed", r"^parameters: this directory holds a sweep of parameters \[.*'pin_r'\]"),
    ],
)
def test_resuming_with_another_family_is_refused_naming_the_field(
    swept: Path, tmp_path: Path, family: str, message: str
) -> None:
    data = copy.deepcopy(TINY_FAMILY)
    if family == "feeder":
        del data["family"]
    elif family == "other":
        data["family"] = str(_other_family(tmp_path, "fig1b"))
    else:
        data["family"] = str(_other_family(tmp_path, "fig1", rename="pin_radius"))
    before = (swept / "results.sqlite").read_bytes()
    with pytest.raises(results_db.ResultsMismatch, match=message) as caught:
        run_sweep(config_from_dict(data), swept)
    assert "\n" not in str(caught.value)
    assert (swept / "results.sqlite").read_bytes() == before


def test_a_feeder_database_is_not_resumed_as_a_family_sweep(tmp_path: Path) -> None:
    feeder = {**{k: v for k, v in TINY_FAMILY.items() if k != "family"}, "designs": {"count": 1}}
    feeder["ladder"] = [{"level": "screen", "screen": SCREEN}]
    run_sweep(config_from_dict(feeder), tmp_path)
    with pytest.raises(results_db.ResultsMismatch, match=r"^family: .*12-parameter feeder, "):
        run_sweep(config_from_dict(TINY_FAMILY), tmp_path)


def test_a_family_sweep_plans_from_the_familys_entries(tmp_path: Path) -> None:
    """A planning rung on a family: each entry of the family planned on its device (the
    first design that can be built), runs named by the family's entries."""
    data = {
        **TINY_FAMILY,
        "designs": {"count": 4, "seed": 1},
        "ladder": [{"level": "dynamic", "planners": ["rrt"], "budget": {"propagations": 300}}],
    }
    path = run_sweep(config_from_dict(data), tmp_path)
    orientations = {o for (o,) in _rows(path, "SELECT DISTINCT orientation FROM runs")}
    assert orientations and orientations <= {"open_leading", "open_trailing"}
    statuses = {s for (s,) in _rows(path, "SELECT status FROM evaluations")}
    assert statuses <= {"feasible", "unknown", "degenerate"} and statuses - {"degenerate"}


@pytest.mark.slow  # end to end on a Dask cluster, run by CI's longer job (issue 22)
def test_a_family_sweep_is_the_same_on_the_dask_executor(swept: Path, tmp_path: Path) -> None:
    """Reference: the module's sweep on the local executor (worker processes)."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        remote = run_sweep(
            config_from_dict(TINY_FAMILY),
            tmp_path,
            executor="dask",
            scheduler=cluster.scheduler_address,
        )
    queries = (
        "SELECT * FROM designs ORDER BY design_id",
        "SELECT design_id, level, rung, status, reason, heavy_leading, heavy_trailing "
        "FROM evaluations ORDER BY design_id, rung",
        "SELECT design_id, decision, trials, heavy_leading, heavy_trailing, both_entries, "
        "exit_heavy_leading_s, exit_heavy_trailing_s, seed FROM verdicts ORDER BY design_id",
        "SELECT value FROM meta WHERE key = 'family'",
    )
    for query in queries:
        assert _rows(swept / "results.sqlite", query) == _rows(remote, query), query


@pytest.mark.parametrize("name", ["index", "order", "select", "Seed", "level", "name", "KEY"])
def test_a_family_parameter_that_ompls_reader_cannot_take_is_refused_at_load(
    tmp_path: Path, name: str
) -> None:
    """Issue 37, item 2: OMPL's log reader adds the experiment's properties as columns without
    quoting; ``index`` broke the export after the whole sweep, with a message calling the
    database damaged. Refused at the config's load, naming the file, the field and the rule."""
    text = FIG1.read_text().replace("pin_r", name)
    (tmp_path / "bad.yaml").write_text(text)
    with pytest.raises(ConfigError) as caught:
        config_from_dict({**TINY_FAMILY, "family": "bad.yaml"}, base=tmp_path)
    message = str(caught.value)
    assert message.startswith("family: ") and "bad.yaml" in message and "\n" not in message
    assert f"parameters.{name}" in message and "SQL keyword" in message
