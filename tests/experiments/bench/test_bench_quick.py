"""``partfeeder bench --quick`` as CI's smoke test: it runs (with or without the peer engines)
and writes the JSON, the figures and the summary; every error is a finite number; and the
errors shrink with h where the closed form says they must (first-order time stepping: the
sliding box's displacement error and free flight's position error are proportional to h, so
h = 1e-4 must be more accurate than h = 1e-2 for every engine; partfeeder's flat drop lands
within a step of t*)."""

from __future__ import annotations

import json
import math

import pytest
from cli_process import run_cli

from experiments.bench.peers import mujoco_engine


def _numbers(value):
    if isinstance(value, dict):
        for v in value.values():
            yield from _numbers(v)
    elif isinstance(value, list):
        for v in value:
            yield from _numbers(v)
    elif isinstance(value, float | int) and not isinstance(value, bool):
        yield value


@pytest.mark.slow  # ~30 s
def test_quick_bench_writes_everything_and_errors_converge(tmp_path):
    done = run_cli("bench", "--quick", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    names = {p.name for p in tmp_path.iterdir()}
    assert {
        "bench.json",
        "summary.md",
        "perf-work-precision.png",
        "perf-feeder.png",
        "perf-ladder.png",
        "perf-speed.png",
    } <= names
    data = json.loads((tmp_path / "bench.json").read_text())
    assert data["machine"]["cores"] >= 1 and data["versions"]["partfeeder"]
    assert all(math.isfinite(x) for x in _numbers(data))
    wp = data["work_precision"]
    for name in ("slide", "flight"):
        by_engine: dict[str, dict[float, float]] = {}
        for p in wp["cases"][name]["points"]:
            by_engine.setdefault(p["engine"], {})[p["h"]] = p["errors"]["error"]
        assert "partfeeder (default)" in by_engine
        for engine, errors in by_engine.items():
            assert errors[1e-4] < errors[1e-2] / 10, (name, engine, errors)
    ours = [p for p in wp["cases"]["drop"]["points"] if p["engine"] == "partfeeder (default)"]
    for p in ours:
        assert p["errors"]["time_to_rest"] <= 2 * p["h"]
    assert wp["creep"]["by_engine"]["partfeeder (default)"] < 1e-12
    summary = (tmp_path / "summary.md").read_text()
    assert "## Goals" in summary and "## The ladder" in summary
    if not mujoco_engine.available():
        assert "not installed" in summary
    feeder = data["feeder"]["designs"]["table3"]
    for row in feeder["by_h"]:
        assert 0.0 <= row["interval"][0] <= row["p"] <= row["interval"][1] <= 1.0
        assert 0.0 <= row["ks"] <= 1.0
