"""Where jobs run, for every job (sweep, optimiser, stress, feasibility, calibration, the
agreement suite): local worker processes (:mod:`.local`) or a Dask cluster (:mod:`.cluster`),
each worker started the same way (:mod:`.worker`). A shared piece below the jobs: no job owns
it, and it knows nothing of any job's data."""

from __future__ import annotations

from experiments.executors.cluster import DaskPool
from experiments.executors.local import LocalPool


def open_pool(
    executor: str, workers: int, max_attempts: int, scheduler: str | None
) -> LocalPool | DaskPool:
    """The pool of ``executor`` (``local`` or ``dask``), not yet entered."""
    if executor == "dask":
        if not scheduler:
            raise ValueError("the dask executor needs a scheduler address")
        return DaskPool(scheduler)
    return LocalPool(workers, max_attempts)
