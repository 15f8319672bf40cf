"""``partfeeder --help`` and a bad argument answer without loading the heavy libraries.

Every registered subcommand's module is imported to build the parser, so each must leave
numba, OMPL and matplotlib to the moment it runs. Checked in a fresh interpreter
(the test process has them loaded already) by reading ``sys.modules`` after the parser exits.
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
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    try:
        run(sys.argv[1:])
    except SystemExit:
        pass
print(json.dumps(sorted({name.split(".")[0] for name in sys.modules})))
"""


def _loaded(*args: str) -> set[str]:
    done = subprocess.run(
        [sys.executable, "-c", PROBE, *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    )
    return set(json.loads(done.stdout.strip().splitlines()[-1]))


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


def test_every_subcommand_declares_arguments_and_runs():
    for command in SUBCOMMANDS:
        module = command.load()
        assert callable(module.add_arguments) and callable(module.run), command.module
