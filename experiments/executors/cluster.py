"""A Dask cluster as the executor: the same plain-data jobs and callbacks as
:class:`experiments.executors.local.LocalPool`, so a run gives the same results on either for
the same seed (with budgets in propagations; a time budget depends on the machine), whatever
the workers' processes and threads (planning takes turns within a process:
:mod:`planners.exclusive`; each worker is prepared by :mod:`.dask_plugin`). Results come
back to the calling process."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from experiments.executors.local import Evaluate, Job, OnDone, OnQuarantine, error_text

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

            from experiments.executors.dask_plugin import PlanningWorker
        except ImportError:
            raise RuntimeError(
                "the dask executor needs Dask's distributed scheduler: "
                "pip install 'partfeeder[dask]' (or: pip install distributed)"
            ) from None
        check_scheduler(self.scheduler)
        self._client = Client(self.scheduler, set_as_default=False, timeout=10)
        self._client.register_plugin(PlanningWorker())
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
                on_quarantine(job, 1, error_text(exc))
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
