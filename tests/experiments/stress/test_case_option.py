"""``partfeeder stress --case N --out DIR`` runs case N of the seed alone and writes its file
whatever its result, so README's replay example has a file to replay on any machine (issue 22:
the example named a file that existed only if case 2606 failed, and it no longer does)."""

from __future__ import annotations

import argparse

from experiments.stress import add_arguments, run
from experiments.stress.case import LEVEL_NAMES
from experiments.stress.generate import generate_case
from experiments.stress.report import read_case
from experiments.stress.runner import record_of


def _args(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    return parser.parse_args(list(argv))


def test_case_writes_the_file_that_replay_reads(tmp_path):
    assert run(_args("--case", "2606", "--out", str(tmp_path))) == 0
    path = tmp_path / "case-0-002606-dynamic.yaml"
    case, stored = read_case(path)
    assert case == generate_case(0, 2606, LEVEL_NAMES)
    assert stored == record_of(case)
    assert run(_args("--replay", str(path))) == 0
