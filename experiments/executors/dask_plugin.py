"""What every Dask worker of a partfeeder run needs before its first job, as a worker plugin
(it reaches the workers there are and those that join later). Imported only with Dask."""

from __future__ import annotations

from typing import Any

from distributed import WorkerPlugin

from experiments.executors.worker import quiet_ompl

PROFILER_CALLBACKS = ("profile", "profile-cycle")


class PlanningWorker(WorkerPlugin):
    """OMPL's log off, and Dask's statistical profiler stopped. The profiler samples the
    stacks of the worker's task threads every few milliseconds while OMPL calls back into
    Python from threads of its own (its Benchmark solves in a thread it starts): with two
    threads per worker this crashed the worker with SIGSEGV in about half the runs of the
    tiny sweep, and in none of them with the profiler off (issue 23)."""

    name = "partfeeder-planning-worker"

    def setup(self, worker: Any) -> None:
        quiet_ompl()
        for name in PROFILER_CALLBACKS:
            callback = worker.periodic_callbacks.pop(name, None)
            if callback is not None:
                callback.stop()
