"""``partfeeder bench --quick`` in every mode (issue 39): quick budgets for ``--trial``,
``--verdict`` and ``--part`` when no N is given, and no ``bench-out/`` left behind by a smoke
test unless ``--out`` asks for it. The jobs are stand-ins that record what they were given."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.cli import run
from experiments.cli.bench import COUNTS, DEFAULT_OUT


@pytest.fixture
def written(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> list[Path]:
    """The suite and the agreement suite as stand-ins, run in an empty folder; the folders
    their outputs were written to."""
    monkeypatch.chdir(tmp_path)
    folders: list[Path] = []

    def write_outputs(data: dict, out: Path, *args: object) -> list[Path]:
        folders.append(out)
        return [out / "bench.json"]

    monkeypatch.setattr("experiments.bench.suite.run_suite", lambda settings, progress: {})
    monkeypatch.setattr("experiments.bench.suite.write_outputs", write_outputs)
    monkeypatch.setattr("experiments.bench.summary.goal_lines", lambda data: ["goals"])
    monkeypatch.setattr(
        "experiments.bench.agreement.suite.agreement_data", lambda *a, **k: {"tables": {}}
    )
    monkeypatch.setattr("experiments.bench.agreement.report.write_outputs", write_outputs)
    monkeypatch.setattr("experiments.bench.agreement.report.markdown", lambda data: "tables")
    monkeypatch.setattr("experiments.cli.bench.compile_once", lambda levels: None)
    return folders


@pytest.mark.parametrize(
    "mode", [[], ["--agreement", "--engines", "partfeeder,pymunk", "--workers", "1"]]
)
def test_quick_without_out_writes_no_file_and_says_so(
    written: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str], mode: list[str]
) -> None:
    if mode:
        pytest.importorskip("pymunk")
    assert run(["bench", *mode, "--quick"]) == 0
    out, err = capsys.readouterr()
    assert written == [] and list(tmp_path.iterdir()) == []
    assert "bench: no files written (--quick without --out)" in err
    assert "wrote" not in out


@pytest.mark.parametrize(
    ("argv", "folder"),
    [
        (["--quick", "--out", "mine"], Path("mine")),
        ([], Path(DEFAULT_OUT)),  # the full bench: bench-out, as before
        (["--sections", "speed", "--out", "mine"], Path("mine")),
    ],
)
def test_the_files_go_to_out_and_the_full_bench_to_bench_out(
    written: list[Path], argv: list[str], folder: Path
) -> None:
    assert run(["bench", *argv]) == 0
    assert written == [folder]


@pytest.mark.parametrize("option", ["trial", "verdict", "part"])
@pytest.mark.parametrize(
    ("given", "quick", "expected"),
    [([], False, "full"), ([], True, "quick"), (["7"], True, 7), (["7"], False, 7)],
)
def test_quick_gives_each_counted_mode_its_quick_n_unless_n_is_given(
    monkeypatch: pytest.MonkeyPatch,
    option: str,
    given: list[str],
    quick: bool,
    expected: int | str,
) -> None:
    job = {
        "trial": ("experiments.bench.trial_cost.trial_cost", "format_trial_cost"),
        "verdict": ("experiments.bench.verdict_cost.verdict_cost", "format_verdict_cost"),
        "part": ("experiments.bench.part_cost.part_cost", "format_part_cost"),
    }[option]
    counts: list[int] = []

    def stand_in(*args: object) -> dict:
        counts.append(next(a for a in args if isinstance(a, int)))
        return {}

    monkeypatch.setattr(job[0], stand_in)
    monkeypatch.setattr(f"{job[0].rsplit('.', 1)[0]}.{job[1]}", lambda results: "")
    argv = ["bench", f"--{option}", *given, *(["--quick"] if quick else [])]
    assert run(argv) == 0
    full, short = COUNTS[option]
    assert counts == [{"full": full, "quick": short}.get(expected, expected)]
    assert short < full


def test_a_quick_count_of_zero_is_still_refused(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(["bench", "--trial", "0", "--quick"]) == 2
    assert "--trial = 0 is outside the allowed range [1, 100000]" in capsys.readouterr().err
