"""``partfeeder run``: the main job, Halton designs up the ladder of levels through OMPL's
Benchmark (see :mod:`experiments.sweep`), with a progress bar over the designs; resumes when started
again in the same directory."""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path
from time import monotonic
from typing import Any, TextIO

from experiments.cli.baseline import add_baseline_argument, baseline_for, check_baseline_form
from experiments.cli.kernels import compile_once
from experiments.cli.report import finish
from experiments.cli.usage import UsageError, out_dir
from experiments.config_files import shipped_configs_help
from experiments.names import EXECUTOR_NAMES

DEFAULT_OUT = Path("sweep")


def add_arguments(run: argparse.ArgumentParser) -> None:
    run.add_argument(
        "config",
        nargs="?",
        default="default",
        help="experiment config: a YAML file, or a shipped one by name: "
        f"{shipped_configs_help('run')}; default takes a few minutes, paper is the paper's "
        "scale (hours)",
    )
    run.add_argument(
        "--out", type=Path, default=None, help="sweep directory (default: sweep/<config name>)"
    )
    run.add_argument("--executor", default="local", choices=EXECUTOR_NAMES)
    run.add_argument(
        "--scheduler", default=None, help="Dask scheduler address (tcp://host:port) for dask"
    )
    run.add_argument("--workers", type=int, default=None, help="local worker processes")
    run.add_argument("--designs", type=int, default=None, help="override designs.count")
    run.add_argument("--no-report", action="store_true", help="skip the HTML report")
    add_baseline_argument(run)
    run.add_argument("--json", action="store_true", help="print the summary as JSON")
    run.add_argument("--quiet", action="store_true", help="no progress bars")


class SweepProgress:
    """One bar over the designs, with a fixed total: a design is done when it stops climbing
    (:func:`experiments.sweep.ladder.run_sweep`'s ``finished``), so the bar's total is the
    config's number of designs from the start and tqdm's time estimate means something;
    the number of evaluations is not known in advance (the ladder is adaptive), so each
    level's feasible and evaluated counts so far are shown beside it. The time left is
    :class:`experiments.eta.LadderEta`'s, from each level's cost and pass rate measured so
    far (the designs stopped at the cheap first level finish first: a rate over designs
    finished read "00:02" with minutes left). ``stream`` None writes on stderr, redrawn on a
    terminal, as lines elsewhere (:mod:`experiments.progress`; tests give a ``StringIO``);
    ``clock`` (s) is the estimate's."""

    def __init__(
        self, quiet: bool, stream: TextIO | None = None, clock: Callable[[], float] = monotonic
    ):
        self.quiet = quiet
        self.stream = stream
        self.clock = clock
        self.bar: Any = None
        self.eta: Any = None
        self.levels: list[str] = []
        self.evaluated: list[int] = []
        self.feasible: list[int] = []

    def __call__(self, event: str, info: dict[str, Any]) -> None:
        if self.quiet:
            return
        if event == "start":
            from experiments.eta import LadderEta
            from experiments.progress import bar

            self.levels = list(info["levels"])
            self.eta = LadderEta(len(self.levels), info.get("waiting", ()))
            done = info["done"]
            self.evaluated = [sum(1 for (_, lv) in done if lv == level) for level in self.levels]
            self.feasible = [
                sum(1 for (_, lv), s in done.items() if lv == level and s == "feasible")
                for level in self.levels
            ]
            self.bar = bar(
                info["designs"],
                "designs",
                "design",
                initial=info["finished"],
                stream=self.stream,
                estimate=self.eta.eta,
                clock=self.clock,
            )
            self.bar.set_postfix_str(self.counts(), refresh=False)
            return
        if self.bar is None:
            return
        rung = info["rung"]
        self.eta.result(rung, info.get("wall_time_s"), not info["finished"])
        self.evaluated[rung] += 1
        if event == "result" and info["status"] == "feasible":
            self.feasible[rung] += 1
        self.bar.set_postfix_str(self.counts(), refresh=False)
        if info["finished"]:
            self.bar.update(1)
        else:
            self.bar.refresh()

    def counts(self) -> str:
        """Each level's feasible / evaluated designs so far, and the levels the time estimate
        has no cost of yet (while there are any it is a lower bound, shown as ``>=``)."""
        per_level = zip(self.levels, self.feasible, self.evaluated, strict=True)
        text = "feasible/evaluated " + ", ".join(f"{lv} {k}/{n}" for lv, k, n in per_level)
        untimed = [] if self.eta is None else [self.levels[r] for r in self.eta.untimed()]
        return text + (f"; not yet timed: {', '.join(untimed)}" if untimed else "")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


def _executor_flags(args: argparse.Namespace) -> None:
    """``--executor`` and ``--scheduler`` agree."""
    if args.executor != "dask" and args.scheduler is not None:
        raise UsageError("--scheduler is only for --executor dask")
    if args.executor == "dask" and not args.scheduler:
        raise UsageError("--executor dask needs --scheduler ADDRESS (tcp://host:port)")


def _check_scheduler(args: argparse.Namespace) -> None:
    """A Dask scheduler answers (within about 2 s:
    :func:`experiments.executors.cluster.check_scheduler`), before anything is written."""
    if args.executor == "dask":
        from experiments.executors.cluster import check_scheduler

        check_scheduler(args.scheduler)


def run(args: argparse.Namespace) -> int:
    """The config and every flag are checked before numba, OMPL or the job is imported
    (issue 22: a bad ``--designs`` took 0.8 s, as long as importing them). On the local
    executor the kernels are compiled here once, before the workers start, which then only
    load them (on a cold cache each worker compiled them itself)."""
    _executor_flags(args)
    check_baseline_form(args.baseline)
    from experiments.sweep.config import ConfigError, config_from_dict, load_config

    try:
        config = load_config(args.config)
        overrides: dict[str, Any] = {}
        if args.workers is not None:
            overrides["workers"] = args.workers
        if args.designs is not None:
            overrides["designs"] = {"count": args.designs, "seed": config.seed}
        if overrides:
            config = config_from_dict({**config.to_dict(), **overrides})
    except ConfigError as exc:
        raise UsageError(str(exc)) from None
    baseline_for(args.baseline, config.device_family())  # the feeder's, or the family's
    _check_scheduler(args)
    out = out_dir(args.out or DEFAULT_OUT / config.name, inputs=[Path(args.config)])
    assert out is not None
    from experiments.sweep.ladder import export_ompl, run_sweep
    from experiments.sweep.lock import sweep_lock
    from experiments.sweep.results_db import ResultsMismatch

    bars = SweepProgress(args.quiet or args.json)
    with sweep_lock(out, job="run"):
        if args.executor == "local":
            compile_once(rung.level for rung in config.ladder)
        t0 = time.perf_counter()
        try:
            results = run_sweep(config, out, args.executor, args.scheduler, progress=bars)
        except ResultsMismatch as exc:
            raise UsageError(f"{out}: {exc}") from None
        except KeyboardInterrupt:
            bars.close()
            print(
                f"partfeeder run: interrupted; results so far are in {out}; "
                "run the same command again to resume",
                file=sys.stderr,
            )
            return 130
        finally:
            bars.close()
        wall = time.perf_counter() - t0
        return finish(
            out,
            args,
            {"wall_time_s": wall, "sweep_time_s": wall},  # finish adds the report's time
            export=lambda: export_ompl(results, out / "ompl"),
        )
