"""``partfeeder --help`` and a bad argument answer without loading the heavy libraries, and a
command loads only what it uses.

Every registered subcommand's module is imported to build the parser, so each must leave
numba, OMPL and matplotlib to the moment it runs; a subcommand checks every value it is
given before it imports them (issue 22: a bad ``--design`` took 0.5 s, a bad ``--designs``
0.8 s, against 0.07 s for ``--help``). Checked in a fresh interpreter (the test process has
them loaded already) by reading ``sys.modules`` after the command: counts of modules, not
seconds, so a busy machine cannot break it.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from cli_process import ROOT

from experiments.cli.registry import SUBCOMMANDS

HEAVY = ("numba", "ompl", "matplotlib")

PROBE = """
import contextlib, io, json, sys
from experiments.cli import run
out, err = io.StringIO(), io.StringIO()
with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
    try:
        code = run(sys.argv[1:])
    except SystemExit as exc:
        code = exc.code
print(json.dumps({
    "modules": sorted({name.split(".")[0] for name in sys.modules}),
    "code": code,
    "stdout": out.getvalue(),
    "stderr": err.getvalue(),
}))
"""


def _probe(*args: str) -> dict:
    """The command run in a fresh interpreter: its exit status, output and the top-level
    packages it left imported."""
    done = subprocess.run(
        [sys.executable, "-c", PROBE, *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
        check=True,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def _loaded(*args: str) -> set[str]:
    return set(_probe(*args)["modules"])


@pytest.mark.parametrize(
    "args",
    [
        ("--help",),
        ("plan", "--level", "nosuch"),
        ("run", "--executor", "nosuch"),
        *((command.name, "--help") for command in SUBCOMMANDS),
    ],
)
def test_parser_loads_no_heavy_library(args):
    assert not _loaded(*args) & set(HEAVY)


# (arguments, a piece of the one-line error): every subcommand's values, each refused with
# exit status 2 before numba, OMPL or matplotlib is imported.
BAD_VALUES = [
    (("plan", "--design", "nope"), "unknown design preset 'nope'"),
    (("plan", "--design", "1,2,3"), "a design has 12 values"),
    (("plan", "--time", "-1"), "--time = -1.0"),
    (("plan", "--seed", "0"), "--seed = 0"),
    (("plan", "--orientation", "sideways"), "--orientation 'sideways'"),
    (("plan", "--out", "/proc/partfeeder-test"), "--out"),
    (("simulate", "--samples", "-1"), "--samples = -1"),
    (("simulate", "--step", "5"), "--step = 5.0"),
    (("simulate", "--time", "0"), "--time = 0.0"),
    (("simulate", "--time", "3600", "--step", "1e-6"), "steps"),
    (("simulate", "--samples", "3", "--target", "3"), "--target = 3.0"),
    (("simulate", "--seed", "-1"), "--seed = -1"),
    (("simulate", "--design", "nope"), "unknown design preset 'nope'"),
    (("draw", "--design", "nope", "--out", "x.png"), "unknown design preset 'nope'"),
    (("draw", "--out", "x.txt"), "--out 'x.txt'"),
    (("calibrate", "--runs", "0"), "--runs = 0"),
    (("calibrate", "--time", "-1"), "--time = -1.0"),
    (("calibrate", "--quick"), "--quick needs --part"),
    (("calibrate", "--part"), "--part needs --out"),
    (("calibrate", "--part", "--out", "o", "--workers", "0"), "--workers = 0"),
    (("bench", "--repeats", "0"), "--repeats = 0"),
    (("bench", "--seed", "0"), "--seed = 0"),
    (("bench", "--level", "geometric", "--seed", "0"), "--seed = 0"),
    (("bench", "--sections", "nosuch"), "--sections"),
    (("bench", "--agreement", "--trials", "0"), "--trials = 0"),
    (("bench", "--agreement", "--engines", "nosuch"), "--engines"),
    (("report", "/nonexistent-sweep"), "no results.sqlite"),
    (("run", "nosuch.yaml"), "cannot read config file 'nosuch.yaml'"),
    (("run", "--executor", "dask"), "--executor dask needs --scheduler"),
    (("run", "--scheduler", "tcp://h:1"), "--scheduler is only for --executor dask"),
    pytest.param(("run", "--designs", "-3"), "designs.count = -3"),
    pytest.param(("run", "--workers", "0"), "workers = 0"),
    (("optimize", "nosuch.yaml"), "cannot read config file 'nosuch.yaml'"),
    (("optimize", "--workers", "0"), "workers = 0"),
    (("optimize", "--executor", "dask"), "--executor dask needs --scheduler"),
    (("optimize", "--from", "/nonexistent-sweep"), "no results.sqlite"),
    (("stress", "--cases", "-1"), "--cases = -1"),
    pytest.param(("feasibility", "--designs", "-1"), "--designs = -1"),
    (("margins", "--drops", "0"), "--drops = 0"),
    (("margins", "--target", "1.5"), "--target = 1.5"),
    (("margins", "--seed", "-1"), "--seed = -1"),
    (("margins", "--workers", "0"), "--workers = 0"),
    (("margins", "--design", "nope"), "unknown design preset 'nope'"),
    (("margins", "--design", "1,2,3"), "a design has 12 values"),
    (("margins", "--out", "/proc/partfeeder-test"), "--out"),
    (("part", "bowl"), "part 'bowl' is neither a file nor a shipped part"),
    (("part", "cup", "--out", "x.txt"), "--out 'x.txt'"),
    (("family", "new", "x", "--part", "bowl"), "part 'bowl' is neither a file nor"),
    (("planners", "--runs", "0"), "--runs = 0"),
]


@pytest.mark.parametrize(("args", "error"), BAD_VALUES)
def test_bad_value_is_refused_before_heavy_imports(args, error):
    """As fast as ``--help``: the value's one-line error, exit 2, and none of numba, OMPL,
    matplotlib imported (importing them is what took 0.25-0.8 s)."""
    seen = _probe(*args)
    assert seen["code"] == 2, seen
    assert error in seen["stderr"] and len(seen["stderr"].strip().splitlines()) == 1, seen
    assert not set(seen["modules"]) & set(HEAVY), seen["stderr"]


def test_every_subcommand_has_a_bad_value_case():
    tried = {getattr(case, "values", case)[0][0] for case in BAD_VALUES}
    assert tried == {command.name for command in SUBCOMMANDS}


def test_plan_without_out_draws_nothing():
    """``plan`` imports matplotlib only to draw, with ``--out``; its JSON is on stdout."""
    seen = _probe(
        "plan", "--level", "geometric", "--orientation", "heavy_leading", "--time", "0.05",
        "--json",
    )  # fmt: skip
    assert seen["code"] == 0, seen
    assert json.loads(seen["stdout"])["figure"] is None
    assert "matplotlib" not in seen["modules"]
    assert {"numba", "ompl"} <= set(seen["modules"])  # it did plan


def test_simulate_without_out_draws_nothing():
    seen = _probe("simulate", "--orientation", "heavy_leading", "--time", "0.05", "--json")
    assert seen["code"] == 0, seen
    assert json.loads(seen["stdout"])["files"] == []
    assert "matplotlib" not in seen["modules"] and "ompl" not in seen["modules"]


@pytest.mark.parametrize(
    "args", [("part", "cup", "--json"), ("family", "new", "x", "--part", "cup")]
)
def test_part_and_family_new_compute_without_heavy_libraries(args):
    """Mass properties and a family's text are geometry: no numba, OMPL or matplotlib (only
    ``part --out`` draws)."""
    seen = _probe(*args)
    assert seen["code"] == 0, seen
    assert not set(seen["modules"]) & set(HEAVY)


def test_simulate_checks_the_recording_bound_of_the_dynamic_level():
    """``simulate`` refuses a drop too long to record without importing the level: its bound
    is the level's own."""
    from experiments.cli import simulate
    from validity.moving_part import MAX_RECORDED_STEPS

    assert simulate.MAX_RECORDED_STEPS == MAX_RECORDED_STEPS


OMPL_LOG = """
import json, sys
from experiments.cli.console import set_ompl_logging
set_ompl_logging(sys.argv[1] == "verbose")
before = "ompl" in sys.modules
from ompl import util as ou
print(json.dumps([before, ou.getLogLevel().name]))
"""


@pytest.mark.parametrize(("mode", "level"), [("quiet", "LOG_NONE"), ("verbose", "LOG_INFO")])
def test_ompl_log_level_is_set_when_ompl_is_first_imported(mode, level):
    """The CLI sets OMPL's log level without importing OMPL; it takes effect on import."""
    done = subprocess.run(
        [sys.executable, "-c", OMPL_LOG, mode],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    )
    assert json.loads(done.stdout) == [False, level]


def test_every_subcommand_declares_arguments_and_runs():
    for command in SUBCOMMANDS:
        module = command.load()
        assert callable(module.add_arguments) and callable(module.run), command.module
