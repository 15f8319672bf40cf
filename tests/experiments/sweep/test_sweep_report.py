"""The HTML report of a sweep: figures written and referenced, data escaped, partial sweeps."""

from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

import matplotlib.pyplot as plt
import pytest

from experiments.sweep import results_db
from experiments.sweep.report import FIGURES, write_report
from experiments.sweep.report_figures import highest_passed
from feeders.halton import halton_points

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
LADDER = ["geometric", "kinematic", "dynamic"]
N_DESIGNS = 10
HOLDOUT = (0, 1, 2)
EVIL = "<script>alert('x')</script> & worker died"

# design -> verdict per level (missing: not evaluated). Design 3 is degenerate; holdout design
# 1 fails the geometric level but climbs on (and is feasible at kinematic: not a survivor).
VERDICTS = {
    0: {"geometric": "feasible", "kinematic": "feasible", "dynamic": "feasible"},
    1: {"geometric": "infeasible", "kinematic": "feasible", "dynamic": "infeasible"},
    2: {"geometric": "feasible", "kinematic": "infeasible", "dynamic": "infeasible"},
    3: {"geometric": "degenerate"},
    4: {"geometric": "feasible", "kinematic": "feasible", "dynamic": "feasible"},
    5: {"geometric": "feasible", "kinematic": "feasible"},
    6: {"geometric": "infeasible"},
    7: {"geometric": "feasible", "kinematic": "infeasible"},
    8: {"geometric": "feasible"},
    9: {"geometric": "feasible"},
}
PLANNERS = {"geometric": ["rrt"], "kinematic": ["rrt"], "dynamic": ["rrt", "kpiece"]}


def _run(orientation: str, planner: str, solved: bool, seed: int) -> dict:
    return {
        "orientation": orientation,
        "planner": planner,
        "run": 0,
        "seed": seed,
        "solved": solved,
        "approximate": not solved,
        "time_s": 0.1 + 0.05 * seed if solved else 1.0,
        "tree_size": 40 + 13 * seed,
        "tree_edges": 39 + 13 * seed,
        "propagations": 100 * seed,
        "validity_checks": 300 * seed,
        "exit_time_s": 1.5 + 0.1 * seed if solved else float("nan"),
    }


def _result(design_id: int, level: str, status: str) -> dict:
    """A hand-made evaluation as a worker returns it (leading entry first; the trailing one
    is skipped once the leading one fails)."""
    if status == "degenerate":
        return {
            "design_id": design_id,
            "level": level,
            "status": status,
            "reason": "the walls do not enclose a cavity",
            "orientations": {"heavy_leading": None, "heavy_trailing": None},
            "runs": [],
            "logs": {},
            "wall_time_s": 0.01,
            "worker": "w0",
        }
    feasible = status == "feasible"
    runs, logs = [], {}
    orientations = {"heavy_leading": feasible, "heavy_trailing": True if feasible else None}
    for orientation, solved in orientations.items():
        if solved is None:
            continue
        for planner in PLANNERS[level]:
            runs.append(_run(orientation, planner, solved, design_id + len(runs)))
        logs[orientation] = f"OMPL log of design {design_id} at {level}"
    return {
        "design_id": design_id,
        "level": level,
        "status": status,
        "reason": None,
        "orientations": orientations,
        "runs": runs,
        "logs": logs,
        "wall_time_s": 0.2 + 0.01 * design_id,
        "worker": "w1",
    }


def _make_db(path: Path, levels: tuple[str, ...] = tuple(LADDER), quarantine: bool = True) -> Path:
    db = results_db.connect(path)
    points = halton_points(N_DESIGNS, 1)
    results_db.add_designs(db, [(i, i in HOLDOUT, list(points[i])) for i in range(N_DESIGNS)])
    for design_id, verdicts in VERDICTS.items():
        for level, status in verdicts.items():
            if level in levels:
                result = _result(design_id, level, status)
                assert results_db.record(db, result, LADDER.index(level), attempts=1)
    if quarantine:
        results_db.quarantine(db, 9, "kinematic", 2, EVIL)
    db.close()
    return path


def _summary(full: bool = True) -> dict:
    """A hand-made summary (its numbers need not match the database: the report shows them)."""
    nan = float("nan")
    points = halton_points(N_DESIGNS, 1)
    levels = [
        {
            "level": level,
            "rung": rung,
            "evaluated": 10 if rung == 0 else (6 if full else 0),
            "feasible": 7 if rung == 0 else (3 if full else 0),
            "infeasible": 2 if rung == 0 else (3 if full else 0),
            "degenerate": 1 if rung == 0 else 0,
            "quarantined": 1 if (full and rung == 1) else 0,
            "survivors": [7, 3, 2][rung] if full else (7 if rung == 0 else 0),
            "wall_time_s": 2.5 if (full or rung == 0) else 0.0,
            "median_wall_time_s": 0.25 if (full or rung == 0) else nan,
            "designs_per_s": 4.0 if (full or rung == 0) else None,
        }
        for rung, level in enumerate(LADDER)
    ]
    planners = [
        {
            "level": level,
            "planner": planner,
            "runs": 12,
            "solved": 8,
            "solved_fraction": 8 / 12,
            "median_time_s": 0.3,
            "median_tree_size": 90.0,
        }
        for level in (LADDER if full else LADDER[:1])
        for planner in PLANNERS[level]
    ]
    summary = {
        "name": "test <sweep> & co",
        "results_key": "abc123",
        "designs": N_DESIGNS,
        "holdout": len(HOLDOUT),
        "ladder": list(LADDER),
        "feeder": {"friction": 0.3, "inputs": {"max_force": 10.0, "max_torque": 2.0}},
        "levels": levels,
        "planners": planners,
        "pruning": [],
        "speedup": None,
        "best": [],
        "quarantined": [],
    }
    if full:
        summary["pruning"] = [
            {
                "level": "geometric",
                "n": 3,
                "tp": 1,
                "fp": 1,
                "fn": 0,
                "tn": 1,
                "precision": 0.5,
                "precision_ci": [0.09, 0.91],
                "recall": 1.0,
                "recall_ci": [0.21, 1.0],
            },
            {
                "level": "kinematic",
                "n": 3,
                "tp": 1,
                "fp": 1,
                "fn": 0,
                "tn": 1,
                "precision": nan,
                "precision_ci": [nan, nan],
                "recall": None,
                "recall_ci": [0.0, 1.0],
            },
        ]
        summary["ladder_pruning"] = [dict(summary["pruning"][0], level="<geometric>")]
        summary["speedup"] = {
            "ladder_cost_s": 3.1,
            "dynamic_cost_s": 9.6,
            "dynamic_cost_ci": [7.0, 12.5],
            "speedup": 3.1,
            "speedup_ci": [2.2, 4.0],
            "holdout_n": 3,
            "top_level": "dynamic",
        }
        summary["best"] = [
            {"design_id": i, "values": [float(v) for v in points[i]], "exit_time_s": t}
            for i, t in ((0, 1.6), (4, 1.9), (1, None))
        ]
        summary["quarantined"] = [
            {"design_id": 9, "level": "kinematic", "attempts": 2, "reason": EVIL}
        ]
    return summary


def _image_sources(page: str) -> list[str]:
    return re.findall(r'<img src="([^"]+)"', page)


@pytest.fixture(scope="module")
def full_report(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    root = tmp_path_factory.mktemp("sweep")
    db = _make_db(root / "results.sqlite")
    page = write_report(root / "report", _summary(), db)
    return page, page.read_text(encoding="utf-8")


def test_report_writes_every_figure_as_png(full_report):
    page, _ = full_report
    assert page.name == "report.html" and page.exists()
    for name in FIGURES:
        png = page.parent / "figures" / f"{name}.png"
        assert png.exists(), name
        assert png.read_bytes()[:8] == PNG_MAGIC


def test_report_references_exactly_the_figures_that_exist(full_report):
    page, text = full_report
    written = {f"figures/{p.name}" for p in (page.parent / "figures").glob("*.png")}
    assert set(_image_sources(text)) == written
    assert len(written) == len(FIGURES)


def test_report_is_self_contained(full_report):
    _, text = full_report
    assert "://" not in text  # no network resources, not even a CDN
    assert "<script" not in text.lower()


def test_report_escapes_text_from_data(full_report):
    _, text = full_report
    assert "&lt;script&gt;alert(&#x27;x&#x27;)&lt;/script&gt; &amp; worker died" in text
    assert "test &lt;sweep&gt; &amp; co" in text
    assert '<td class="text">&lt;geometric&gt;</td>' in text  # the cumulative pruning
    assert "<sweep>" not in text and "<geometric>" not in text


def test_report_shows_the_summary_numbers(full_report):
    _, text = full_report
    assert "geometric" in text and "kinematic" in text and "dynamic" in text
    assert "[0.09, 0.91]" in text  # precision interval of the geometric level
    assert "3.1x" in text and "[2.2, 4]" in text  # the speed-up and its interval
    assert "nan" not in text.lower()  # unknown numbers are dashes, not NaN
    assert "kpiece" in text


def test_report_of_a_sweep_with_only_geometric_evaluations(tmp_path):
    """A sweep just started: no pruning, no speed-up, its best design not even buildable."""
    db = _make_db(tmp_path / "results.sqlite", levels=("geometric",), quarantine=False)
    summary = _summary(full=False)
    values = [float(v) for v in halton_points(1, 1)[0]]
    values[1] = 0.5  # exit chute narrower than the part: a degenerate design
    summary["best"] = [{"design_id": 0, "values": values, "exit_time_s": math.nan}]
    before = set(plt.get_fignums())
    page = write_report(tmp_path / "report", summary, db)
    assert set(plt.get_fignums()) == before  # every figure closed
    text = page.read_text(encoding="utf-8")
    figures = page.parent / "figures"
    for name in FIGURES:
        assert (figures / f"{name}.png").read_bytes()[:8] == PNG_MAGIC
    assert set(_image_sources(text)) == {f"figures/{name}.png" for name in FIGURES}
    assert "Not measured" in text and "not measured" in text  # no speed-up, no pruning


def test_report_rewritten_drops_figures_it_no_longer_draws(full_report, tmp_path):
    out = tmp_path / "report"
    shutil.copytree(full_report[0].parent, out)
    assert (out / "figures" / "best_designs.png").exists()
    summary = _summary(full=False)
    summary["levels"] = []
    db = results_db.connect(tmp_path / "empty.sqlite")  # a database without designs yet
    db.close()
    page = write_report(out, summary, tmp_path / "empty.sqlite")
    assert not (out / "figures" / "best_designs.png").exists()
    text = page.read_text(encoding="utf-8")
    sources = _image_sources(text)
    assert "figures/best_designs.png" not in sources
    assert {f"figures/{p.name}" for p in (out / "figures").glob("*.png")} == set(sources)
    for src in sources:
        assert (out / src).read_bytes()[:8] == PNG_MAGIC


def test_highest_passed_counts_rungs_from_the_bottom_without_a_miss():
    status = {
        (0, "geometric"): "feasible",
        (0, "kinematic"): "feasible",
        (1, "geometric"): "infeasible",
        (1, "kinematic"): "feasible",  # a holdout design: feasible above a miss
        (2, "geometric"): "degenerate",
    }
    assert highest_passed(0, LADDER, status) == 2
    assert highest_passed(1, LADDER, status) == 0
    assert highest_passed(2, LADDER, status) == 0
    assert highest_passed(3, LADDER, status) == 0  # not evaluated at all
    assert highest_passed(0, LADDER[:2], status) == 2
