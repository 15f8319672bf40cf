"""Where a sweep's jobs run: a local process pool (the default) or a Dask cluster.

Both take the same plain-data jobs and the same callbacks, so a sweep gives the same results
on either for the same seed (with a budget in propagations; a time budget depends on the
machine). Results come back to the calling process, the database's only writer.

A worker that dies (a crash in compiled code, the OOM killer, a signal) is replaced and its
job tried again; a job that kills its worker ``max_attempts`` times is quarantined with the
reason, and the sweep goes on. A job that raises a Python exception is quarantined at once
(the same input raises again). Locally, a dead worker breaks the whole pool, taking down the
jobs running beside it, so every job that was in flight is re-run alone in a fresh process:
innocent ones finish, the culprit is caught in the act, with its exit signal.
"""

from __future__ import annotations

import multiprocessing
import signal
from collections import deque
from collections.abc import Callable, Iterable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import TYPE_CHECKING, Any

from experiments.worker_process import quiet_ompl, start_worker

if TYPE_CHECKING:
    from experiments.sweep.job import SweepJob as Job

Evaluate = Callable[["Job"], dict[str, Any]]
OnDone = Callable[["Job", dict[str, Any], int], Iterable["Job"]]
OnQuarantine = Callable[["Job", int, str], None]


def _death(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            return f"killed by signal {signal.Signals(-exitcode).name}"
        except ValueError:
            return f"killed by signal {-exitcode}"
    return f"exited with code {exitcode}"


def _error(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {exc}"


def _alone(evaluate: Evaluate, job: Job, conn) -> None:
    start_worker()
    try:
        conn.send(("ok", evaluate(job)))
    except Exception as exc:
        conn.send(("error", _error(exc)))
    conn.close()


def _run_alone(evaluate: Evaluate, job: Job) -> tuple[str, Any]:
    """Run one job in a fresh process: ('ok', result), ('error', message) or ('died', why)."""
    context = multiprocessing.get_context("spawn")
    receive, send = context.Pipe(duplex=False)
    process = context.Process(target=_alone, args=(evaluate, job, send), daemon=True)
    process.start()
    send.close()
    try:
        outcome = receive.recv()
    except EOFError:
        outcome = None
    process.join()
    if outcome is None:
        return "died", _death(process.exitcode)
    return outcome


class LocalPool:
    """A pool of ``workers`` local processes that lives across calls of :meth:`run` (an
    optimiser sends a batch at a time; starting workers costs seconds each). A context
    manager: the processes end with it."""

    def __init__(self, workers: int = 2, max_attempts: int = 2):
        self.workers = workers
        self.max_attempts = max_attempts
        self._context = multiprocessing.get_context("spawn")
        self._pool: ProcessPoolExecutor | None = None

    def __enter__(self) -> LocalPool:
        self._pool = self._new_pool()
        return self

    def __exit__(self, *exc: object) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None

    def _new_pool(self) -> ProcessPoolExecutor:
        return ProcessPoolExecutor(self.workers, mp_context=self._context, initializer=start_worker)

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
                on_quarantine(job, 1, _error(exc))
            else:
                queue.extend(on_done(job, result, 1))
            return False

        while queue or inflight or suspects:
            if suspects and not inflight:
                job = suspects.popleft()
                key = id(job)
                status, value = _run_alone(evaluate, job)
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


SCHEDULER_TIMEOUT_S = 2.0  # to reach the scheduler and hear it answer


class SchedulerUnreachable(ValueError):
    """The Dask scheduler address is malformed, or nothing there answers as a scheduler."""


def scheduler_endpoint(address: str) -> tuple[str, int]:
    """(host, port) of a scheduler address ``tcp://host:port`` (``tls://`` too, or just
    ``host:port``); :class:`SchedulerUnreachable` naming the address if it is not one."""
    text = address.strip()
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    host, colon, port = rest.rpartition(":")
    host = host.strip("[]")  # [::1]:8786
    if scheme not in ("tcp", "tls") or not colon or not host or "/" in rest:
        raise SchedulerUnreachable(
            f"--scheduler '{address}' is not a scheduler address; expected tcp://host:port"
        )
    if not port.isdigit() or not 1 <= int(port) <= 65535:
        raise SchedulerUnreachable(
            f"--scheduler '{address}': the port must be a number in [1, 65535]"
        )
    return host, int(port)


async def _identity(address: str, timeout: float) -> Any:
    from distributed.comm import connect

    comm = await connect(address, timeout=timeout)
    try:
        await comm.write({"op": "identity", "reply": True})
        return await comm.read()
    finally:
        comm.abort()


def check_scheduler(address: str, timeout: float = SCHEDULER_TIMEOUT_S) -> None:
    """Fail fast unless a Dask scheduler answers at ``address`` within about ``timeout``
    seconds: a plain TCP connection first (a refused port or an unknown host fails at once),
    then Dask's ``identity`` call, whose reply must say ``Scheduler``. Without it, Dask's
    ``Client`` waits 30 s and ends in a traceback; something else listening on the port can
    even answer with bytes Dask reads as a 3-exabyte message. Raises
    :class:`SchedulerUnreachable` naming the address."""
    import asyncio
    import socket

    host, port = scheduler_endpoint(address)
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise SchedulerUnreachable(
            "the dask executor needs Dask's distributed scheduler: "
            "pip install 'partfeeder[dask]' (or: pip install distributed)"
        ) from None
    try:
        socket.create_connection((host, port), timeout=timeout).close()
    except OSError as exc:
        reason = exc.strerror or str(exc) or type(exc).__name__
        raise SchedulerUnreachable(
            f"--scheduler '{address}': cannot connect to {host}:{port} ({reason})"
        ) from None
    url = address if "://" in address else f"tcp://{address}"
    try:
        reply = asyncio.run(asyncio.wait_for(_identity(url, timeout), timeout + 1.0))
    except Exception as exc:  # anything the other end says that is not a scheduler's reply
        raise SchedulerUnreachable(
            f"--scheduler '{address}': no Dask scheduler answers there "
            f"({type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else 'no reply'})"
        ) from None
    if not isinstance(reply, dict) or reply.get("type") != "Scheduler":
        raise SchedulerUnreachable(
            f"--scheduler '{address}': what answers there is not a Dask scheduler"
        )


class DaskPool:
    """The Dask cluster whose scheduler is at ``scheduler`` (``tcp://host:port``), connected
    across calls of :meth:`run`; a context manager. Its workers need partfeeder installed.
    Dask replaces a dead worker and reschedules its task; after the scheduler's
    ``distributed.scheduler.allowed-failures`` deaths (Dask's setting, 3 by default, not the
    config's ``max_attempts``) it gives up (``KilledWorker``) and the job is quarantined."""

    def __init__(self, scheduler: str):
        self.scheduler = scheduler
        self._client: Any = None

    def __enter__(self) -> DaskPool:
        try:
            from distributed import Client
        except ImportError:
            raise RuntimeError(
                "the dask executor needs Dask's distributed scheduler: "
                "pip install 'partfeeder[dask]' (or: pip install distributed)"
            ) from None
        check_scheduler(self.scheduler)
        self._client = Client(self.scheduler, set_as_default=False, timeout=10)
        self._client.run(quiet_ompl)
        return self

    def __exit__(self, *exc: object) -> None:
        if self._client is not None:
            self._client.close()
            self._client = None

    def run(
        self, evaluate: Evaluate, jobs: Iterable[Job], on_done: OnDone, on_quarantine: OnQuarantine
    ) -> None:
        """The same as :meth:`LocalPool.run`, on the cluster."""
        from distributed import as_completed

        try:
            from distributed.scheduler import KilledWorker
        except ImportError:  # older releases
            from distributed import KilledWorker  # type: ignore[attr-defined,no-redef]

        import dask

        client = self._client
        assert client is not None, "use DaskPool as a context manager"
        deaths = int(dask.config.get("distributed.scheduler.allowed-failures", 3)) + 1
        futures = {}
        for job in jobs:
            futures[client.submit(evaluate, job, pure=False)] = job
        pending = as_completed(list(futures), loop=client.loop)
        for future in pending:
            job = futures.pop(future)
            try:
                result = future.result()
            except KilledWorker as exc:
                on_quarantine(job, deaths, f"its Dask worker died every time it ran it ({exc})")
            except Exception as exc:
                on_quarantine(job, 1, _error(exc))
            else:
                for follow in on_done(job, result, 1):
                    new = client.submit(evaluate, follow, pure=False)
                    futures[new] = follow
                    pending.add(new)


def run_dask(
    evaluate: Evaluate,
    jobs: Iterable[Job],
    on_done: OnDone,
    on_quarantine: OnQuarantine,
    scheduler: str,
) -> None:
    """:meth:`DaskPool.run` on a connection of its own to the scheduler at ``scheduler``."""
    with DaskPool(scheduler) as pool:
        pool.run(evaluate, jobs, on_done, on_quarantine)


def open_pool(executor: str, workers: int, max_attempts: int, scheduler: str | None):
    """The pool of ``executor`` (``local`` or ``dask``), not yet entered."""
    if executor == "dask":
        if not scheduler:
            raise ValueError("the dask executor needs a scheduler address")
        return DaskPool(scheduler)
    return LocalPool(workers, max_attempts)
