"""What a long job shows while it works: on a terminal, bars whose total is fixed when they
start and a phase's line with its time; anywhere else (``partfeeder run 2>log``), plain lines
with done/total and an estimate, a line per tenth of the work, never a carriage return."""

from __future__ import annotations

import io
import re

from experiments.eta import Eta
from experiments.progress import LogBar, PhaseBars, bar, phase, say


class Terminal(io.StringIO):
    """A stream that says it is a terminal: what one would be drawn."""

    def isatty(self) -> bool:
        return True


class Clock:
    """A clock stepped by hand (s)."""

    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def last_frame(text: str) -> str:
    """What a terminal shows last: tqdm redraws a line with carriage returns."""
    return re.split(r"[\r\n]+", text.strip())[-1]


def test_a_bar_counts_against_its_fixed_total_on_a_terminal() -> None:
    out = Terminal()
    with bar(8, "designs", "design", stream=out) as b:
        b.update(2)
        b.refresh()
        assert "2/8" in last_frame(out.getvalue()) and "25%" in last_frame(out.getvalue())


def test_a_terminal_bar_shows_the_callers_estimate_marked_when_a_lower_bound() -> None:
    out = Terminal()
    with bar(8, "designs", "design", stream=out, estimate=lambda _s: Eta(202, True)) as b:
        b.update(2)
        b.refresh()
        assert "ETA >= 03:22" in last_frame(out.getvalue())


def test_in_a_log_a_bar_is_lines_one_per_tenth_of_its_items_with_done_total_and_eta() -> None:
    out, clock = io.StringIO(), Clock()
    with bar(20, "designs", "design", stream=out, clock=clock) as b:
        for _ in range(20):
            clock.now += 3.0
            b.update()
    text = out.getvalue()
    assert "\r" not in text
    lines = text.splitlines()
    assert lines[0] == "partfeeder: designs: started, 20"
    progress = lines[1:-1]
    assert [line.split()[2] for line in progress] == [f"{k}/20" for k in range(2, 20, 2)]
    # the rate rule over equal items: 3 s each, so 4/20 done after 12 s leaves 48 s
    assert "4/20 (20%), elapsed 00:12, ETA 00:48" in progress[1]
    assert lines[-1] == "partfeeder: designs: 20/20 (100%) done in 01:00"


def test_in_a_log_a_long_bar_writes_at_least_every_fifty_items_and_every_interval() -> None:
    out, clock = io.StringIO(), Clock()
    b = bar(1000, "cases", "case", stream=out, clock=clock)
    for _ in range(120):
        b.update()  # a tenth is 100 items: lines at 50 (every 50) and 100 (the tenth)
    clock.now += LogBar.INTERVAL_S
    b.update()  # the interval since the last line: one more
    b.update()
    counted = [line.split()[2] for line in out.getvalue().splitlines()[1:]]
    assert counted == ["50/1000", "100/1000", "121/1000"]


def test_in_a_log_work_that_moves_no_item_gets_a_line_per_interval_not_per_refresh() -> None:
    """A sweep's evaluations below the top refresh the counts beside the bar: a log hears of
    them once per interval, not once each."""
    out, clock = io.StringIO(), Clock()
    b = bar(10, "designs", "design", stream=out, clock=clock)
    for _ in range(5):
        clock.now += LogBar.INTERVAL_S / 4
        b.set_postfix_str(f"evaluated {clock.now:.1f}")
        b.refresh()
    lines = out.getvalue().splitlines()
    assert len(lines) == 2  # the start, and one after the interval
    assert lines[1].startswith("partfeeder: designs: 0/10 (0%), elapsed 00:30, ETA ?")
    assert lines[1].endswith(f"evaluated {LogBar.INTERVAL_S:.1f}")


def test_a_log_bar_closed_early_says_where_it_stopped_with_the_callers_counts() -> None:
    out, clock = io.StringIO(), Clock()
    b = bar(10, "designs", "design", initial=4, stream=out, clock=clock)
    b.set_postfix_str("feasible/evaluated geometric 3/5")
    clock.now = 65.0
    b.update()
    b.close()
    b.close()  # once only
    lines = out.getvalue().splitlines()
    assert lines[0] == "partfeeder: designs: started, 10, 4 done before"
    assert lines[-1] == (
        "partfeeder: designs: stopped at 5/10 (50%) after 01:05 | feasible/evaluated geometric 3/5"
    )
    assert len(lines) == 3


def test_a_log_bar_with_nothing_measured_yet_says_its_eta_is_unknown() -> None:
    out = io.StringIO()
    b = bar(10, "designs", "design", stream=out, clock=Clock(), estimate=lambda _s: None)
    b.update()
    assert out.getvalue().splitlines()[-1].endswith("ETA ?")


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


def test_a_phase_line_says_what_and_how_long_on_a_terminal() -> None:
    out = Terminal()
    with phase("writing the report", stream=out):
        pass
    assert re.fullmatch(r"partfeeder: writing the report \.\.\. \d+\.\d s\n", out.getvalue())


def test_in_a_log_a_phase_is_a_line_when_it_starts_and_one_with_its_time_when_it_ends() -> None:
    out = io.StringIO()
    with phase("writing the report", stream=out):
        print("partfeeder: margins: started, 16", file=out)  # a bar inside the phase
    assert re.fullmatch(
        r"partfeeder: writing the report \.\.\.\n"
        r"partfeeder: margins: started, 16\n"
        r"partfeeder: writing the report: done in \d+\.\d s\n",
        out.getvalue(),
    )


def test_stderr_that_is_not_a_terminal_gets_lines_and_quiet_gets_nothing(capsys) -> None:
    with phase("writing the report"):
        pass
    say("report written")
    with PhaseBars("x") as bars:
        bars.note("a", 1)
        bars.note("a", 0)
    err = capsys.readouterr().err
    assert "\r" not in err
    assert err.splitlines()[0] == "partfeeder: writing the report ..."
    assert "partfeeder: report written" in err and "partfeeder: x: a: 1/1 (100%)" in err
    with phase("writing the report", quiet=True):
        pass
    say("report written", quiet=True)
    assert capsys.readouterr().err == ""
