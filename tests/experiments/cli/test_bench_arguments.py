"""``partfeeder bench``'s arguments are all checked before any work or output (issue 23:
``bench`` printed its progress, ran a section and only then refused an ``--out`` it could not
write in; a negative ``--seed`` ended in NumPy's traceback after the progress line).

The jobs are replaced by stand-ins that fail the test if reached: bad input must be refused
before them, with exactly one line on stderr and nothing on stdout.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.cli import run

JOBS = (
    "experiments.bench.suite.run_suite",
    "experiments.bench.agreement.suite.agreement_data",
    "experiments.bench.geometric.run_benchmarks",
    "experiments.bench.kinematic.run_kinematic_benchmarks",
)


@pytest.fixture
def no_work(monkeypatch) -> list[str]:
    """The bench jobs replaced by stand-ins that record that they were reached."""
    reached: list[str] = []
    for job in JOBS:

        def stand_in(*args, _job=job, **kwargs):
            reached.append(_job)
            raise AssertionError(f"{_job} ran before the arguments were checked")

        monkeypatch.setattr(job, stand_in)
    return reached


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["--quick", "--out", "{tmp}/file.txt"], "--out"),
        (["--quick", "--out", "{tmp}/file.txt/sub"], "--out"),
        (["--quick", "--out", "/proc/partfeeder-bench"], "--out"),
        (["--quick", "--out", "{tmp}/" + "o" * 300], "--out"),
        (["--quick", "--seed", "-1"], "--seed = -1"),
        (["--quick", "--seed", "0"], "--seed = 0"),
        (["--quick", "--seed", str(2**64)], "--seed"),
        (["--level", "geometric", "--seed", "-1"], "--seed = -1"),
        (["--level", "kinematic", "--seed", str(2**31)], "--seed"),
        (
            ["--agreement", "--quick", "--engines", "partfeeder,pymunk", "--out", "{tmp}/file.txt"],
            "--out",
        ),
    ],
)
def test_bad_bench_arguments_are_one_line_before_any_work(
    tmp_path: Path, capsys, no_work: list[str], argv: list[str], says: str
) -> None:
    (tmp_path / "file.txt").write_text("a file\n")
    before = sorted(p.name for p in tmp_path.iterdir())
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert run(["bench", *argv]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("partfeeder bench: error: "), err
    assert says in lines[0]
    assert not no_work
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing made


def test_good_bench_arguments_reach_the_job(tmp_path: Path, capsys, no_work: list[str]) -> None:
    """The control: the same stand-in is reached when the arguments are good."""
    with pytest.raises(AssertionError, match="ran before"):
        run(["bench", "--quick", "--seed", "7", "--out", str(tmp_path / "new")])
    assert no_work == ["experiments.bench.suite.run_suite"]
