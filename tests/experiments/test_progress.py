"""What a long job shows while it works: bars whose total is fixed when they start, a phase's
line with its time, and nothing on a stream that is not a terminal."""

from __future__ import annotations

import io
import re

from experiments.progress import PhaseBars, bar, phase


def last_frame(text: str) -> str:
    """What a terminal shows last: tqdm redraws a line with carriage returns."""
    return re.split(r"[\r\n]+", text.strip())[-1]


def test_a_bar_counts_against_its_fixed_total() -> None:
    out = io.StringIO()
    with bar(8, "designs", "design", stream=out) as b:
        b.update(2)
        b.refresh()
        assert "2/8" in last_frame(out.getvalue()) and "25%" in last_frame(out.getvalue())


def test_each_phase_gets_its_own_bar_with_the_total_queued_for_it() -> None:
    out = io.StringIO()
    with PhaseBars("part calibration", stream=out) as bars:
        bars.note("passive", 4)
        for _ in range(4):
            bars.note("passive", 0)
        bars.note("geometric", 2)  # sized by the passive phase's results
        bars.note("geometric", 0)
        assert (bars.current.n, bars.current.total) == (1, 2)
        assert bars.current.desc == "part calibration: geometric"
    text = out.getvalue()
    assert "4/4" in text and "100%" in text  # the finished phase read 100% only when done
    assert "5/" not in text  # never one bar whose total grew


def test_a_phase_line_says_what_and_how_long() -> None:
    out = io.StringIO()
    with phase("writing the report", stream=out):
        pass
    assert re.fullmatch(r"partfeeder: writing the report \.\.\. \d+\.\d s\n", out.getvalue())


def test_nothing_is_drawn_when_stderr_is_not_a_terminal(capsys) -> None:
    with phase("writing the report"):
        pass
    with PhaseBars("x") as bars:
        bars.note("a", 1)
        bars.note("a", 0)
    assert capsys.readouterr().err == ""
