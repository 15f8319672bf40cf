"""The shared local pool every job runs on (issue 23: the sweep, the optimiser, stress and
feasibility had pools of their own). References: the same calls made in one process."""

from __future__ import annotations

import signal

import pytest
from pool_jobs import die_on_three, fail_on_three, sigint_disposition, square
from process_table import sigint_as_from_a_terminal

from experiments.executors.local import JobFailed, LocalPool, map_jobs

JOBS = list(range(12))


@pytest.fixture
def ctrl_c_raises():
    """This process turns Ctrl-C into KeyboardInterrupt, as from a terminal, even when the
    test run was started in the background with SIGINT ignored."""
    with sigint_as_from_a_terminal():
        yield


@pytest.mark.parametrize("workers", [1, 2])
def test_map_jobs_gives_the_results_in_job_order_and_reports_each_once(workers: int) -> None:
    seen: list[tuple[int, int]] = []
    got = map_jobs(square, JOBS, workers, on_result=lambda i, r: seen.append((i, r)))
    assert got == [square(x) for x in JOBS]
    assert sorted(seen) == list(enumerate(got))


def test_a_pool_lives_across_maps() -> None:
    with LocalPool(2) as pool:
        assert pool.map(square, JOBS) == [x * x for x in JOBS]
        assert pool.map(square, [5]) == [25]


def test_a_job_that_raises_fails_the_map_naming_the_job_and_its_error() -> None:
    with pytest.raises(JobFailed) as failed:
        map_jobs(fail_on_three, JOBS, 2)
    assert failed.value.index == 3
    assert "ValueError: three is refused" in str(failed.value)


def test_a_job_that_kills_its_worker_is_named_with_the_signal_after_its_attempts() -> None:
    with pytest.raises(JobFailed) as failed:
        map_jobs(die_on_three, JOBS, 2, max_attempts=2)
    assert failed.value.index == 3
    assert "died 2 times" in failed.value.reason and "SIGKILL" in failed.value.reason


def test_pool_workers_ignore_sigint_and_the_calling_process_does_not(ctrl_c_raises) -> None:
    """Ctrl-C is the parent's: workers ignore it, and running jobs here (one worker) must
    not make the calling process ignore it."""
    assert map_jobs(sigint_disposition, [0, 1], 2) == [True, True]
    assert map_jobs(sigint_disposition, [0], 1, warm_up=lambda: None) == [False]
    assert signal.getsignal(signal.SIGINT) != signal.SIG_IGN


def test_a_stop_request_ends_the_pool_without_waiting_for_long_jobs(
    ctrl_c_raises, tmp_path
) -> None:
    """Issue 37, item 6: Ctrl-C and SIGTERM waited for the jobs in flight (30 s for
    ``margins``): the pool's exit shut down with ``wait=True``. Now its workers are
    terminated; what was handed on before the stop is kept. A long job leaves a file when
    it finishes (after a minute): the pool has ended before any did (an event, not a time
    bound: issue 39, a loaded machine)."""
    import functools
    import os
    import threading

    from pool_jobs import sleep_then_square

    done: list[int] = []

    def on_done(job: int, result: int, _attempts: int) -> list[int]:
        done.append(result)
        if job == 3:  # the quick jobs are in; the long ones run: stop now
            # a real signal (interrupt_main sets the flag only: a blocked wait never sees it)
            threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
        return []

    job = functools.partial(sleep_then_square, finished_in=str(tmp_path))
    pool = LocalPool(2)
    with pytest.raises(KeyboardInterrupt):
        with pool:
            pool.run(job, [1, 2, 3, 100, 101], on_done, lambda *a: None)
    assert sorted(done) == [1, 4, 9]
    assert not list(tmp_path.iterdir()), "the pool waited for a long job to finish"
