"""docs/api.md runs as written: every fenced ``python`` block, in order, in one namespace (as
a reader types them into one session), in a fresh directory (the page writes OMPL logs).

A block that no longer runs (a renamed function, a changed signature, a result that is not
there) fails here, so the page cannot drift from the code. The blocks' budgets are counts of
propagations, so what they print does not depend on the machine."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

PAGE = Path(__file__).resolve().parents[2] / "docs" / "api.md"
BLOCK = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def _blocks() -> list[str]:
    return BLOCK.findall(PAGE.read_text())


def test_the_page_has_the_examples_a_researcher_needs() -> None:
    text = "\n".join(_blocks())
    assert len(_blocks()) >= 7
    for needed in (
        "from planners import problem",
        "oc.KPIECE1(p.si)",
        "validity_checker(level)",
        "state_propagator(level)",
        "ot.Benchmark(",
        "benchmark_control_problem(",
        "one_at_a_time",
    ):
        assert needed in text, needed


def test_every_python_block_of_the_page_runs_in_order(tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "api_page"}
    for number, block in enumerate(_blocks(), start=1):
        try:
            exec(compile(block, f"docs/api.md block {number}", "exec"), namespace)
        except Exception as exc:  # pragma: no cover - the failure message is the point
            pytest.fail(f"docs/api.md block {number} fails: {type(exc).__name__}: {exc}")
    out = capsys.readouterr().out
    # The first block's answer: KPIECE1 reaches the goal of table3 at the dynamic level.
    assert out.splitlines()[0].startswith("True ")
    # The benchmark block printed a row per run and wrote OMPL's log.
    assert "RRT-greedy" in out
    log = (tmp_path / "table3.log").read_text()
    assert "table3/dynamic/heavy_leading" in log and "propagations INTEGER" in log
    assert (tmp_path / "table3-dynamic.log").exists()  # OMPL's own Benchmark's log


def test_the_readme_python_block_runs(tmp_path, monkeypatch, capsys) -> None:
    """README's example is the one a researcher tries first: it runs and reaches the goal."""
    readme = Path(__file__).resolve().parents[2] / "README.md"
    (block,) = BLOCK.findall(readme.read_text())
    monkeypatch.chdir(tmp_path)
    exec(compile(block, "README.md python block", "exec"), {"__name__": "readme"})
    assert capsys.readouterr().out.splitlines()[0].startswith("True ")
