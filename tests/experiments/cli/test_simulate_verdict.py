"""``partfeeder simulate --samples N``: the design's passive verdict from the command line."""

from __future__ import annotations

import json

import pytest
from cli_process import run_cli

from experiments.cli import run


def test_samples_prints_the_verdict_as_json(capsys):
    """table3 with the default part: per entry a probability inside its interval, and every
    drop in the transition matrix."""
    scene_args = ["--design", "table3", "--samples", "60", "--json", "--time", "5"]
    assert run(["simulate", *scene_args]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["scene"] == "table3"
    assert set(report["orientations"]) == {"heavy_leading", "heavy_trailing"}
    assert report["drops"] <= 60
    for o, row in report["orientations"].items():
        assert sum(report["transitions"][o].values()) == report["drops"]
        assert 0.0 <= row["interval"][0] <= row["p"] <= row["interval"][1] <= 1.0


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--samples", "-3"], "--samples = -3 is outside the allowed range"),
        (["--samples", "10", "--target", "1.5"], "--target = 1.5 is outside the allowed range"),
        # issue 23: accepted by simulate (and stress), refused by plan; numpy draws from
        # [0, 2**32 - 1], with or without --samples
        (["--seed", str(2**64)], "--seed = 18446744073709551616 is outside the allowed range"),
        (["--samples", "5", "--seed", "-1"], "--seed = -1 is outside the allowed range [0,"),
        # issue 23: a MemoryError traceback after trying to allocate 161 GiB
        (["--step", "1e-6", "--time", "3600"], "3600000000 steps; a recorded drop has at most"),
    ],
)
def test_bad_verdict_options_are_one_line_and_exit_2(extra, message):
    done = run_cli("simulate", "--design", "table3", *extra, timeout=300)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and message in lines[0]
