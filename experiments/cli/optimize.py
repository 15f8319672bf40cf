"""``partfeeder optimize``: the paper's design optimisation (Eq. 10-11), made robust
(:mod:`experiments.optimize`): from the best designs of a sweep (``--from``) or the config's
presets, derivative-free methods search Table 2's box for the design that turns both entries
heavy end down under perturbation, as fast as possible. Resumes when started again in the
same directory."""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any, TextIO

from experiments.cli.baseline import add_baseline_argument, baseline_of
from experiments.cli.kernels import compile_once
from experiments.cli.usage import UsageError, out_dir
from experiments.names import EXECUTOR_NAMES

DEFAULT_OUT = Path("optimize")


def add_arguments(opt: argparse.ArgumentParser) -> None:
    opt.add_argument(
        "config",
        nargs="?",
        default="optimize",
        help="optimisation config: a YAML file, or a shipped one by name: optimize (a few "
        "minutes), optimize-compare (every method, several seeds)",
    )
    opt.add_argument(
        "--from",
        dest="sweep",
        type=Path,
        default=None,
        help="start from the best designs of this sweep directory (by their passive verdict)",
    )
    opt.add_argument(
        "--out", type=Path, default=None, help="output directory (default: optimize/<config>)"
    )
    opt.add_argument("--executor", default="local", choices=EXECUTOR_NAMES)
    opt.add_argument(
        "--scheduler", default=None, help="Dask scheduler address (tcp://host:port) for dask"
    )
    opt.add_argument("--workers", type=int, default=None, help="local worker processes")
    add_baseline_argument(opt)
    opt.add_argument("--no-report", action="store_true", help="skip the HTML report")
    opt.add_argument("--json", action="store_true", help="print the results as JSON")
    opt.add_argument("--quiet", action="store_true", help="no progress bar")


class OptimizeProgress:
    """Bars with totals fixed when they start: the evaluations
    (:func:`experiments.optimize.run.evaluations_total`: starts, every run's budget, the
    baseline's; a run that converges early jumps to its budget), with the best value and
    P(both) so far, then the verdicts on fresh draws (the candidates', the optimum's and the
    baseline's), then the optimum's margins (16 axes; its verdict at nominal comes first).
    ``stream`` None draws on stderr when it is a terminal (tests give a ``StringIO``)."""

    def __init__(self, quiet: bool, stream: TextIO | None = None):
        self.quiet = quiet
        self.stream = stream
        self.bar: Any = None

    def __call__(self, event: str, info: dict[str, Any]) -> None:
        if self.quiet:
            return
        from experiments.progress import bar

        if event == "start":
            self.bar = bar(info["evaluations"], "optimize", "eval", stream=self.stream)
        elif event == "verdicts":
            self.close()
            desc = f"verdicts ({info['trials']} trials each)"
            self.bar = bar(info["verdicts"], desc, "verdict", stream=self.stream)
        elif event == "margins":
            self.close()
            self.bar = bar(info["axes"], "margins of the optimum", "axis", stream=self.stream)
            self.bar.set_postfix_str("its verdict at nominal first", refresh=False)
        elif self.bar is None:
            return
        elif event == "run":
            self.bar.set_description(info["run"])
        elif event == "run end":
            self.bar.update(info["unspent"])
        elif event == "evaluation":
            best = info["best"]
            self.bar.set_postfix(best=f"{best['value']:.4f}", both=best["both"], refresh=False)
            self.bar.update()
        elif event in ("verdict", "axis"):
            self.bar.set_postfix_str(info.get("label") or info.get("axis") or "", refresh=False)
            self.bar.update()

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


def sweep_best_designs(sweep: Path | None) -> list[dict]:
    """The best designs of a sweep directory, by their passive verdict (its summary)."""
    if sweep is None:
        return []
    database = sweep / "results.sqlite"
    if not database.is_file():
        raise UsageError(f"--from '{sweep}': no results.sqlite there (is it a sweep directory?)")
    from experiments.sweep.results_db import ResultsDamaged
    from experiments.sweep.summary import summarise

    try:
        best = summarise(database).get("best") or []
    except ResultsDamaged as exc:
        raise UsageError(f"--from: {exc}") from None
    ranked = [b for b in best if b.get("verdict")]
    if not ranked:
        raise UsageError(
            f"--from '{sweep}': no design of that sweep works by its passive verdict "
            "(a sweep with a passive rung gives them)"
        )
    return ranked


def run(args: argparse.Namespace) -> int:
    from experiments.optimize.config import OptimizeConfigError, config_from_dict, load_config
    from experiments.optimize.store import StoreDamaged, StoreMismatch

    try:
        config = load_config(args.config)
        if args.workers is not None:
            config = config_from_dict({**config.to_dict(), "workers": args.workers}, config.name)
    except OptimizeConfigError as exc:
        raise UsageError(str(exc)) from None
    if args.executor != "dask" and args.scheduler is not None:
        raise UsageError("--scheduler is only for --executor dask")
    if args.executor == "dask":
        if not args.scheduler:
            raise UsageError("--executor dask needs --scheduler ADDRESS (tcp://host:port)")
        from experiments.executors.cluster import check_scheduler

        check_scheduler(args.scheduler)
    baseline = baseline_of(args.baseline)
    best = sweep_best_designs(args.sweep)
    if not config.presets and not best:
        raise UsageError(
            f"{args.config}: start.presets is empty and no --from SWEEP_DIR was given: "
            "nothing to start from"
        )
    out = out_dir(args.out or DEFAULT_OUT / config.name, inputs=[Path(args.config)])
    assert out is not None
    from experiments.optimize.report import summary_text, write_report
    from experiments.optimize.run import optimise
    from experiments.progress import phase
    from experiments.sweep.lock import sweep_lock

    bar = OptimizeProgress(args.quiet or args.json)
    with sweep_lock(out, job="optimize"):
        if args.executor == "local":
            compile_once(["passive"])  # before the workers start: they then only load them
        t0 = time.perf_counter()
        try:
            results = optimise(
                config, out, best, args.executor, args.scheduler, progress=bar, baseline=baseline
            )
        except (StoreMismatch, StoreDamaged) as exc:
            raise UsageError(f"{out}: {exc}") from None
        except KeyboardInterrupt:
            bar.close()
            print(
                f"partfeeder optimize: interrupted; evaluations so far are in {out}; "
                "run the same command again to resume",
                file=sys.stderr,
            )
            return 130
        finally:
            bar.close()
        results["wall_time_s"] = time.perf_counter() - t0
        files = {"evaluations": str(out / "evaluations.sqlite")}
        if not args.no_report:
            with phase("writing the report", args.quiet):
                files["report"] = str(write_report(out, config, results))
        results["files"] = files
        (out / "summary.json").write_text(json.dumps(results, indent=2))
    if args.json:
        print(json.dumps(results, indent=2))
    else:
        print(summary_text(results))
        for name, path in files.items():
            print(f"{name}: {path}")
    return 0
