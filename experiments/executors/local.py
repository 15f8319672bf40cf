"""Local worker processes for every job (sweep, optimiser, stress, feasibility, calibration,
the agreement suite): one pool, with one start-up (:mod:`experiments.executors.worker`) and one
rule for workers that die.

A worker that dies (a crash in compiled code, the OOM killer, a signal) is replaced and its
job tried again; a job that kills its worker ``max_attempts`` times is quarantined with the
reason, and the run goes on. A job that raises a Python exception is quarantined at once
(the same input raises again). A dead worker breaks the whole pool, taking down the jobs
running beside it, so every job that was in flight is re-run alone in a fresh process:
innocent ones finish, the culprit is caught in the act, with its exit signal.

Processes are started with ``spawn``: forking a parent that runs threads (a progress bar's
monitor, numba's pool) can deadlock the child.
"""

from __future__ import annotations

import functools
import os
import signal
import time
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from experiments.executors.worker import start_worker, worker_context

Job = Any  # plain data: a worker builds everything else (its OMPL objects, its scenes)
Evaluate = Callable[[Job], Any]
OnDone = Callable[[Job, Any, int], Iterable[Job]]
OnQuarantine = Callable[[Job, int, str], None]
WarmUp = Callable[[], object]


def _death(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            return f"killed by signal {signal.Signals(-exitcode).name}"
        except ValueError:
            return f"killed by signal {-exitcode}"
    return f"exited with code {exitcode}"


def error_text(exc: BaseException) -> str:
    """One line for a job's exception: its type and message."""
    return f"{type(exc).__name__}: {exc}"


def _start(parent: int, ompl: bool, warm_up: WarmUp | None) -> None:
    """A pool process's initializer: :func:`start_worker`, then ``warm_up`` (for example,
    load the kernels a job's timing must not count)."""
    start_worker(parent, ompl)
    if warm_up is not None:
        warm_up()


def _alone(evaluate: Evaluate, job: Job, conn, start: Callable[[], None]) -> None:
    start()
    try:
        conn.send(("ok", evaluate(job)))
    except Exception as exc:
        conn.send(("error", error_text(exc)))
    conn.close()


def _run_alone(evaluate: Evaluate, job: Job, start: Callable[[], None]) -> tuple[str, Any]:
    """Run one job in a fresh process: ('ok', result), ('error', message) or ('died', why)."""
    context = worker_context()
    receive, send = context.Pipe(duplex=False)
    process = context.Process(target=_alone, args=(evaluate, job, send, start), daemon=True)
    process.start()
    send.close()
    try:
        outcome = receive.recv()
    except EOFError:
        outcome = None
    except BaseException:  # a stop request: the job is not waited for
        process.terminate()
        process.join(STOP_GRACE_S)
        if process.is_alive():
            process.kill()
        raise
    process.join()
    if outcome is None:
        return "died", _death(process.exitcode)
    return outcome


STOP_GRACE_S = 2.0  # after SIGTERM, how long a worker may take to end before SIGKILL


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """End ``pool`` now: its queued jobs cancelled, its workers terminated (SIGTERM, then
    SIGKILL after ``STOP_GRACE_S``), without waiting for the jobs in flight (a verdict's
    batch can run half a minute; a batch scheduler's grace period is often 30 s). What the
    caller stored of finished jobs is kept; a job cut short is run again on resume."""
    processes = list(getattr(pool, "_processes", {}).values())  # the executor's own table
    manager = getattr(pool, "_executor_manager_thread", None)
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    deadline = time.monotonic() + STOP_GRACE_S
    for process in processes:
        process.join(max(0.0, deadline - time.monotonic()))
        if process.is_alive():
            process.kill()
            process.join(1.0)
    if manager is not None:
        # The executor's thread unlinks the pool's named semaphores as it ends: an exit that
        # cuts it between unlink and unregister leaves the resource tracker to report a leak
        # after the command's last line (CI, under load: 3 of the signal tests in one run).
        manager.join(STOP_GRACE_S)


class LocalPool:
    """A pool of ``workers`` local processes that lives across calls of :meth:`run` (an
    optimiser sends a batch at a time; starting workers costs seconds each). A context
    manager: the processes end with it.

    Each process starts with :func:`~experiments.executors.worker.start_worker` (``ompl``:
    also silence OMPL's log; False for jobs that never import it), then ``warm_up`` if given
    (a picklable callable)."""

    def __init__(
        self,
        workers: int = 2,
        max_attempts: int = 2,
        warm_up: WarmUp | None = None,
        ompl: bool = True,
    ):
        self.workers = workers
        self.max_attempts = max_attempts
        self._start = functools.partial(_start, os.getpid(), ompl, warm_up)
        self._context = worker_context()
        self._pool: ProcessPoolExecutor | None = None

    def __enter__(self) -> LocalPool:
        self._pool = self._new_pool()
        return self

    def __exit__(self, exc_type: type[BaseException] | None, *exc: object) -> None:
        if self._pool is not None:
            if exc_type is None:
                self._pool.shutdown(wait=True, cancel_futures=True)
            else:  # a stop request (Ctrl-C, SIGTERM) or a failure: do not wait for the jobs
                stop_pool(self._pool)
            self._pool = None

    def _new_pool(self) -> ProcessPoolExecutor:
        return ProcessPoolExecutor(self.workers, mp_context=self._context, initializer=self._start)

    def run(
        self, evaluate: Evaluate, jobs: Iterable[Job], on_done: OnDone, on_quarantine: OnQuarantine
    ) -> None:
        """Run ``jobs`` and the jobs that ``on_done`` returns, ``workers`` at a time; returns
        when all are done.

        ``on_done(job, result, attempts)`` is called here as each job finishes (in completion
        order) and returns the jobs that follow from it; ``on_quarantine(job, attempts,
        reason)`` for a job given up. At most ``workers`` jobs are in flight, so a broken pool
        takes down no more than that.
        """
        assert self._pool is not None, "use LocalPool as a context manager"
        queue: deque[Job] = deque(jobs)
        suspects: deque[Job] = deque()
        deaths: dict[int, int] = {}
        inflight: dict[Future, Job] = {}

        def settle(future: Future) -> bool:
            """Hand a finished future's job on; True if its worker (and so the pool) died."""
            job = inflight.pop(future)
            try:
                result = future.result()
            except BrokenProcessPool:
                suspects.append(job)
                return True
            except Exception as exc:
                on_quarantine(job, 1, error_text(exc))
            else:
                queue.extend(on_done(job, result, 1))
            return False

        while queue or inflight or suspects:
            if suspects and not inflight:
                job = suspects.popleft()
                key = id(job)
                status, value = _run_alone(evaluate, job, self._start)
                if status == "ok":
                    queue.extend(on_done(job, value, deaths.get(key, 0) + 1))
                elif status == "error":
                    on_quarantine(job, deaths.get(key, 0) + 1, value)
                else:
                    deaths[key] = deaths.get(key, 0) + 1
                    if deaths[key] >= self.max_attempts:
                        on_quarantine(
                            job,
                            deaths[key],
                            f"its worker died {deaths[key]} times running it alone (last: {value})",
                        )
                    else:
                        suspects.append(job)
                continue
            while queue and len(inflight) < self.workers and not suspects:
                job = queue.popleft()
                inflight[self._pool.submit(evaluate, job)] = job
            done, _ = wait(inflight, return_when=FIRST_COMPLETED)
            broken = [settle(future) for future in done]
            if any(broken):
                wait(inflight)  # the others fail with the pool: they become suspects too
                for future in list(inflight):
                    settle(future)
                self._pool.shutdown(wait=True, cancel_futures=True)
                self._pool = self._new_pool()

    def map(
        self,
        evaluate: Evaluate,
        jobs: Sequence[Job],
        on_result: Callable[[int, Any], object] | None = None,
    ) -> list[Any]:
        """``[evaluate(job) for job in jobs]``, in ``jobs``' order (``evaluate`` and the jobs
        picklable). ``on_result(index, result)`` is called here as each job finishes, in
        completion order: the place for progress and for storing rows as they come. A job
        that raises, or kills its worker ``max_attempts`` times, raises :class:`JobFailed`:
        no job starts after it, and the pool's workers are ended at once (:func:`stop_pool`)."""
        results: dict[int, Any] = {}

        def done(_item: tuple[int, Job], result: tuple[int, Any], _attempts: int) -> list[Job]:
            index, value = result
            results[index] = value
            if on_result is not None:
                on_result(index, value)
            return []

        def failed(item: tuple[int, Job], _attempts: int, reason: str) -> None:
            raise JobFailed(item[0], reason)

        self.run(functools.partial(_indexed, evaluate), list(enumerate(jobs)), done, failed)
        return [results[index] for index in range(len(jobs))]


def run_local(
    evaluate: Evaluate,
    jobs: Iterable[Job],
    on_done: OnDone,
    on_quarantine: OnQuarantine,
    workers: int = 2,
    max_attempts: int = 2,
) -> None:
    """:meth:`LocalPool.run` on a pool of its own: ``jobs``, and the jobs that ``on_done``
    returns, ``workers`` at a time."""
    with LocalPool(workers, max_attempts) as pool:
        pool.run(evaluate, jobs, on_done, on_quarantine)


class JobFailed(RuntimeError):
    """A job of :meth:`LocalPool.map` raised, or killed its worker every time it ran."""

    def __init__(self, index: int, reason: str):
        super().__init__(f"job {index}: {reason}")
        self.index = index
        self.reason = reason


def _indexed(evaluate: Evaluate, item: tuple[int, Job]) -> tuple[int, Any]:
    index, job = item
    return index, evaluate(job)


def map_jobs(
    evaluate: Evaluate,
    jobs: Sequence[Job],
    workers: int = 1,
    on_result: Callable[[int, Any], object] | None = None,
    warm_up: WarmUp | None = None,
    ompl: bool = True,
    max_attempts: int = 1,
) -> list[Any]:
    """``[evaluate(job) for job in jobs]``, in ``jobs``' order: :meth:`LocalPool.map` on a
    pool of ``workers`` processes of its own, or with ``workers`` <= 1 here, one after the
    other (after ``warm_up``; a job's exception then propagates as it is)."""
    if workers <= 1:
        if warm_up is not None:
            warm_up()
        out = []
        for index, job in enumerate(jobs):
            out.append(evaluate(job))
            if on_result is not None:
                on_result(index, out[-1])
        return out
    with LocalPool(min(workers, max(len(jobs), 1)), max_attempts, warm_up, ompl) as pool:
        return pool.map(evaluate, jobs, on_result)
