"""``partfeeder run 2>log`` (issue 39: piped to a file, a sweep said nothing until its summary,
18 minutes on a busy machine): with stderr not a terminal the sweep writes plain progress
lines as designs finish, with done/total, before the summary; and the printed wall time
names the report's share (it took longer than the sweep in two of the issue's three runs)."""

from __future__ import annotations

import copy
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from cli_process import ROOT
from sweep_fixtures import TINY

DESIGNS = 10
SMALL = {
    **copy.deepcopy(TINY),
    "name": "small",
    "designs": {"count": DESIGNS, "seed": 1},
    "ladder": [  # budgets in propagations: the same rows on any machine, a few seconds
        {"level": "geometric", "planners": ["rrt"], "budget": {"propagations": 500}},
        {"level": "kinematic", "planners": ["rrt"], "budget": {"propagations": 300}},
    ],
}
PROGRESS = re.compile(r"^partfeeder: designs: (\d+)/(\d+) \((\d+)%\), elapsed \d\d:\d\d, ETA ")


@pytest.mark.slow  # about 11 s at load 5 on 2 cores: a 10-design sweep and its report
def test_run_with_stderr_to_a_file_writes_progress_lines_before_the_summary(tmp_path: Path):
    config = tmp_path / "small.yaml"
    config.write_text(yaml.safe_dump(SMALL))
    log = tmp_path / "log"
    with log.open("w") as handle:  # stdout and stderr into one file, neither a terminal
        done = subprocess.run(
            [sys.executable, "-m", "experiments.cli", "run", str(config), "--out",
             str(tmp_path / "out")],
            cwd=ROOT, stdout=handle, stderr=subprocess.STDOUT, timeout=600,
        )  # fmt: skip
    text = log.read_text()
    assert done.returncode == 0, text
    assert "\r" not in text
    lines = text.splitlines()
    summary_at = next(k for k, line in enumerate(lines) if line.startswith("sweep 'small'"))
    assert lines.index(f"partfeeder: designs: started, {DESIGNS}") < summary_at
    counts = [
        (k, int(m[1]), int(m[2])) for k, line in enumerate(lines) if (m := PROGRESS.match(line))
    ]
    # a line per tenth of the designs: 1/10 .. 9/10 as they finish, then the end line
    assert [(n, total) for _, n, total in counts] == [(n, DESIGNS) for n in range(1, DESIGNS)]
    assert all(k < summary_at for k, _, _ in counts)
    end = f"partfeeder: designs: {DESIGNS}/{DESIGNS} (100%) done in "
    assert any(line.startswith(end) for line in lines[:summary_at])
    report_said = next(line for line in lines if line.startswith("partfeeder: report written"))
    assert lines.index(report_said) < summary_at

    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["wall_time_s"] == pytest.approx(
        summary["sweep_time_s"] + summary["report_time_s"]
    )
    report_s = float(re.search(r"in (\d+\.\d) s", report_said)[1])
    assert summary["report_time_s"] >= report_s - 0.05  # the report's time is in the total
    wall = next(line for line in lines if line.startswith("wall time: "))
    assert re.fullmatch(
        r"wall time: [\d.]+ s \(sweep [\d.]+ s, OMPL database, summary and report [\d.]+ s\)",
        wall,
    )
