"""Names that become columns through OMPL's log reader (issue 37, item 2): the rule of
:mod:`planners.sql_names`, checked against SQLite's own keyword list and OMPL's own reader."""

from __future__ import annotations

import contextlib
import ctypes
import io
import sqlite3
from pathlib import Path

import pytest
from ompl import _benchmark_statistics as obs

from planners.sql_names import OMPL_EXPERIMENT_COLUMNS, SQL_KEYWORDS, column_name_problem


def _library_keywords() -> set[str]:
    import _sqlite3

    try:
        lib = ctypes.CDLL(_sqlite3.__file__)
        count = lib.sqlite3_keyword_count()
    except (OSError, AttributeError):
        pytest.skip("the linked SQLite's keyword list is not reachable through ctypes")
    lib.sqlite3_keyword_name.argtypes = [
        ctypes.c_int,
        ctypes.POINTER(ctypes.c_char_p),
        ctypes.POINTER(ctypes.c_int),
    ]
    name, size = ctypes.c_char_p(), ctypes.c_int()
    words = set()
    for i in range(count):
        lib.sqlite3_keyword_name(i, ctypes.byref(name), ctypes.byref(size))
        assert name.value is not None
        words.add(name.value[: size.value].decode())
    return words


def test_the_keyword_list_holds_every_keyword_of_the_linked_sqlite() -> None:
    assert _library_keywords() <= SQL_KEYWORDS


def test_keywords_columns_and_other_text_are_refused_and_identifiers_pass() -> None:
    for word in SQL_KEYWORDS:
        assert column_name_problem(word.lower()) is not None
    for column in OMPL_EXPERIMENT_COLUMNS:
        assert column_name_problem(column.upper()) is not None
    for bad in ["", "1x", "a b", "a-b", "a;b", 'a"', "é", None, 3]:
        assert column_name_problem(bad) == "not a plain identifier"
    for good in ["theta", "pin_x", "chute_width", "depth", "_a1", "indexes"]:
        assert column_name_problem(good) is None


def _log(properties: list[str]) -> str:
    """A minimal OMPL benchmark log (one experiment, no planner) with ``properties`` as its
    experiment properties, as planners.benchmark writes them."""
    lines = [
        "OMPL version 2.0.0",
        "Experiment test",
        f"{len(properties)} experiment properties",
        *(f"{p} REAL = 1.5" for p in properties),
        "Running on host",
        "Starting at 2024-01-01 00:00:00",
        "<<<|",
        "setup",
        "|>>>",
        "<<<|",
        "cpu",
        "|>>>",
        "3 is the random seed",
        "1 seconds per run",
        "100 MB per run",
        "1 runs per planner",
        "1 seconds spent to collect the data",
        "0 enum types",
        "0 planners",
    ]
    return "\n".join(lines) + "\n"


def _read(tmp_path: Path, properties: list[str]) -> list[str]:
    log = tmp_path / "run.log"
    log.write_text(_log(properties))
    db = tmp_path / "bench.db"
    db.unlink(missing_ok=True)
    with contextlib.redirect_stdout(io.StringIO()):
        obs.readBenchmarkLog(str(db), [str(log)], False)
    with contextlib.closing(sqlite3.connect(db)) as con:
        return [c[1] for c in con.execute("PRAGMA table_info(experiments)")]


def test_ompls_reader_takes_every_name_the_rule_allows_and_fails_on_keywords(
    tmp_path: Path,
) -> None:
    allowed = ["theta", "pin_x", "depth", "indexes", "design_id", "level"]
    assert all(column_name_problem(n) is None for n in allowed)
    assert set(allowed) <= set(_read(tmp_path, allowed))
    for refused in ["index", "order", "select"]:  # what the rule is for
        assert column_name_problem(refused) == "an SQL keyword"
        with pytest.raises(sqlite3.OperationalError):
            _read(tmp_path, [refused])


def test_benchmark_refuses_a_parameter_ompls_reader_cannot_take() -> None:
    from feeders.design import PRESETS
    from feeders.feeder import build_feeder
    from planners.benchmark import Budget, benchmark_problem

    scene = build_feeder(PRESETS["table3"], name="table3")
    with pytest.raises(ValueError, match=r"parameter 'order': an SQL keyword; a parameter"):
        benchmark_problem(
            scene,
            "geometric",
            "heavy_leading",
            ["rrt"],
            1,
            Budget(5.0, 10),
            1,
            experiment="t",
            parameters={"order": 1.0},
        )
