"""Every script in examples/ runs as a user runs it (a separate process, from a directory
outside the repository) with a small budget, and prints what its docstring promises.

Budgets are counts of propagations, so each run's numbers are the same on any machine: the
assertions about who solved what hold under any load."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _run(tmp_path: Path, script: str, *args: str) -> str:
    proc = subprocess.run(
        [sys.executable, str(EXAMPLES / script), *args],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert "Traceback" not in proc.stderr and "leaked" not in proc.stderr
    return proc.stdout


def test_every_example_has_a_test() -> None:
    scripts = {p.name for p in EXAMPLES.glob("*.py")}
    assert scripts == {"compare_planners.py", "custom_scene.py", "custom_planner.py"}


def test_compare_planners_tabulates_each_planner_and_writes_planner_arenas_database(
    tmp_path: Path,
) -> None:
    import sqlite3

    out = _run(
        tmp_path,
        "compare_planners.py",
        "--designs", "table3,fig7a",
        "--orientations", "heavy_leading",
        "--runs", "2",
        "--propagations", "400",
        "--out", "cmp",
    )  # fmt: skip
    rows = [line.split() for line in out.splitlines() if line.startswith(("table3", "fig7a"))]
    assert [(r[0], r[2]) for r in rows] == [
        (design, planner) for design in ("table3", "fig7a") for planner in ("RRT", "KPIECE1", "EST")
    ]
    for row in rows:
        solved, runs = row[3].split("/")
        assert runs == "2" and 0 <= int(solved) <= 2
        assert 0 < float(row[4]) <= 400 + 50  # a run stops within an iteration of its budget
    # table3 at the dynamic level falls heavy end down by itself: every planner reaches the goal
    assert all(r[3] == "2/2" for r in rows if r[0] == "table3")
    database = tmp_path / "cmp" / "benchmark.db"
    with sqlite3.connect(database) as db:
        names = [n for (n,) in db.execute("SELECT name FROM experiments ORDER BY id")]
        runs = db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
    assert names == ["table3/dynamic/heavy_leading", "fig7a/dynamic/heavy_leading"]
    assert runs == 2 * 3 * 2


def test_custom_scene_plans_through_the_funnel_next_to_it(tmp_path: Path) -> None:
    out = _run(tmp_path, "custom_scene.py", "--level", "dynamic", "--propagations", "2000")
    assert "scene funnel" in out
    assert "dynamic level, KPIECE1: solved" in out
    end = next(line for line in out.splitlines() if line.startswith("end pose"))
    y, yaw = float(end.split()[5].rstrip(",")), float(end.split()[7])
    assert -3.0 <= y <= -2.2 and abs(yaw + 1.5708) <= 0.5  # inside funnel.yaml's goal


def test_custom_scene_takes_a_scene_file_and_a_change_of_friction(tmp_path: Path) -> None:
    scene = tmp_path / "ramp.yaml"
    scene.write_text(
        "obstacles:\n  - polygon: [[-5, -1], [5, -1], [5, 0], [-5, 0]]\n"
        "bounds: [-5, 5, 0, 6]\nstarts: {top: [0, 4, 0]}\n"
        "goal: {x: [-5, 5], y: [0, 1], yaw: 0.0, yaw_tol: 3.14}\n"
    )
    out = _run(
        tmp_path, "custom_scene.py", "--scene", str(scene), "--level", "geometric",
        "--planner", "RRT-greedy", "--friction", "0.7", "--propagations", "3000",
    )  # fmt: skip
    assert "scene ramp, friction 0.7" in out
    assert "geometric level, RRT-greedy: solved" in out


def test_custom_planner_is_benchmarked_beside_rrt(tmp_path: Path) -> None:
    out = _run(
        tmp_path, "custom_planner.py", "--level", "dynamic", "--runs", "2",
        "--propagations", "1000",
    )  # fmt: skip
    rows = {line.split()[0]: line.split() for line in out.splitlines()[2:]}
    assert set(rows) == {"RandomShooting", "RRT"}
    # On table3 the part falls heavy end down by itself: random wrenches get there too.
    assert rows["RandomShooting"][1] == "2/2" and rows["RRT"][1] == "2/2"
