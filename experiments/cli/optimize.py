"""``partfeeder optimize``: the paper's design optimisation (Eq. 10-11), made robust
(:mod:`experiments.optimize`): from the best designs of a sweep (``--from``) or the config's
presets, derivative-free methods search Table 2's box (a device family's box, with the
config's ``family:``) for the design that turns both entries heavy end down (the family's goal)
under perturbation, as fast as possible. Resumes when started again in the same directory."""

from __future__ import annotations

import argparse
import json
import sys
import time
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from experiments.cli.baseline import add_baseline_argument, baseline_for
from experiments.cli.kernels import compile_once
from experiments.cli.usage import UsageError, check_count, out_dir
from experiments.config_files import shipped_configs_help
from experiments.names import EXECUTOR_NAMES

if TYPE_CHECKING:
    from experiments.optimize.config import OptimizeConfig

DEFAULT_OUT = Path("optimize")


def add_arguments(opt: argparse.ArgumentParser) -> None:
    opt.add_argument(
        "config",
        nargs="?",
        default="optimize",
        help="optimisation config: a YAML file, or a shipped one by name: "
        f"{shipped_configs_help('optimize')}; optimize takes a few minutes, optimize-compare "
        "runs every method on several seeds, robust maximises the smallest normalised margin "
        "at the verdict's target (design centering)",
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
    opt.add_argument(
        "--evaluations",
        type=int,
        default=None,
        metavar="N",
        help="override the evaluation budget: every method's evaluations per seed "
        "(methods[].budget; with goal robustness, centering.budget)",
    )
    opt.add_argument(
        "--trials",
        type=int,
        default=None,
        metavar="N",
        help="override final.trials: the trials of each verdict on fresh draws (the "
        "candidates', the optimum's, the baseline's); objective.trials, which defines the "
        "objective, stays",
    )
    add_baseline_argument(opt)
    opt.add_argument("--no-report", action="store_true", help="skip the HTML report")
    opt.add_argument("--json", action="store_true", help="print the results as JSON")
    opt.add_argument("--quiet", action="store_true", help="no progress bar")


class OptimizeProgress:
    """Bars with totals fixed when they start: the evaluations
    (:func:`experiments.optimize.run.evaluations_total`: starts, every run's budget, the
    baseline's; a run that converges early jumps to its budget), with the best value and
    P(both) so far, then the verdicts on fresh draws (the candidates', the optimum's and the
    baseline's), then the optimum's margins (16 axes, a family's its parameters and mu; its
    verdict at nominal comes first).
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


def sweep_best_designs(sweep: Path | None, config: OptimizeConfig | None = None) -> list[dict]:
    """The best designs of a sweep directory, by their passive verdict (its summary). The
    sweep must design what ``config`` designs (the 12-parameter feeder, or the same device
    family: the same file's text); else one line naming ``--from`` and ``family``. A
    family's sweep may have no design that works (fig1-cup's 1,000 Halton designs: none), so
    for a family the designs that work are followed, up to ``start.sweep_best``, by the
    failing ones nearest to working (the largest fraction of trials succeeding from both
    entries, then from the worse entry): starts for the optimiser to improve on."""
    if sweep is None:
        return []
    database = sweep / "results.sqlite"
    if not database.is_file():
        raise UsageError(f"--from '{sweep}': no results.sqlite there (is it a sweep directory?)")
    from experiments.sweep import results_db
    from experiments.sweep.results_db import ResultsDamaged
    from experiments.sweep.summary import summarise

    try:
        with closing(results_db.connect(database, readonly=True)) as db:
            record = results_db.stored_family(db)
            _check_same_design(sweep, record, config)
            near = _nearest_failing(db) if record is not None else []
        best = summarise(database).get("best") or []
    except ResultsDamaged as exc:
        raise UsageError(f"--from: {exc}") from None
    ranked = [b for b in best if b.get("verdict")]
    if config is not None and config.family is not None:
        taken = {b["design_id"] for b in ranked}
        ranked += [b for b in near if b["design_id"] not in taken]
        ranked = ranked[: max(len(best), config.sweep_best)]
    if not ranked:
        raise UsageError(
            f"--from '{sweep}': no design of that sweep works by its passive verdict "
            "(a sweep with a passive rung gives them)"
        )
    return ranked


def _check_same_design(
    sweep: Path, record: dict[str, Any] | None, config: OptimizeConfig | None
) -> None:
    """Refuse a sweep of another device: the feeder's for a family, a family's for the
    feeder, or a family of another name or other parameters (the sweep's designs are vectors
    of its parameters). A sweep of the same family whose file has changed since (a comment,
    a wall moved) is accepted: its designs are only starts, each evaluated again under this
    config's family; its verdicts only order them."""
    family = None if config is None else config.device_family()
    if record is None and family is None:
        return
    if (
        record is not None
        and family is not None
        and (record["name"], list(record["parameters"])) == (family.name, list(family.vector_names))
    ):
        return
    theirs = (
        "the 12-parameter feeder"
        if record is None
        else f"device family '{record['name']}' ({', '.join(record['parameters'])})"
    )
    mine = (
        "the 12-parameter feeder (no family:)"
        if family is None
        else f"family '{family.name}' ({', '.join(family.vector_names)})"
    )
    raise UsageError(
        f"--from '{sweep}' is a sweep of {theirs}; this config's family: designs {mine}; "
        "allowed: a sweep of the same device"
    )


def _nearest_failing(db: Any) -> list[dict]:
    """The sweep's designs with a passive verdict that does not work, nearest to working
    first: the fraction of trials succeeding from both entries, then the worse entry's."""
    from experiments.sweep import results_db

    names = results_db.parameter_names(db)
    columns = ", ".join(f'"{n}"' for n in names)
    values = {
        int(r[0]): [float(v) for v in r[1:]]
        for r in db.execute(f"SELECT design_id, {columns} FROM designs")
    }
    rows = []
    for d, verdict in results_db.verdicts(db).items():
        if verdict.get("works") or d not in values:
            continue
        worse = min(per["p"] for per in verdict["orientations"].values())
        rows.append(
            (
                (-verdict["both"]["p"], -worse, d),
                {"design_id": d, "values": values[d], "verdict": verdict},
            )
        )
    return [row for _, row in sorted(rows, key=lambda r: r[0])]


def _budget_options(args: argparse.Namespace, config: OptimizeConfig) -> OptimizeConfig:
    """``config`` with ``--evaluations`` and ``--trials`` applied, each checked against the
    range of the config field it overrides (one line naming the option otherwise)."""
    from experiments.optimize.config import (
        MAX_BUDGET,
        MAX_CENTERING_BUDGET,
        MAX_TRIALS,
        ROBUSTNESS,
        with_budget,
    )

    if args.evaluations is not None:
        high = MAX_CENTERING_BUDGET if config.goal == ROBUSTNESS else MAX_BUDGET
        check_count(args.evaluations, "--evaluations", high)
    if args.trials is not None:
        check_count(args.trials, "--trials", MAX_TRIALS)
    return with_budget(config, args.evaluations, args.trials)


def run(args: argparse.Namespace) -> int:
    from experiments.optimize.config import OptimizeConfigError, config_from_dict, load_config
    from experiments.optimize.store import StoreDamaged, StoreMismatch

    try:
        config = load_config(args.config)
        if args.workers is not None:
            config = config_from_dict({**config.to_dict(), "workers": args.workers}, config.name)
    except OptimizeConfigError as exc:
        raise UsageError(str(exc)) from None
    config = _budget_options(args, config)
    if args.executor != "dask" and args.scheduler is not None:
        raise UsageError("--scheduler is only for --executor dask")
    if args.executor == "dask":
        if not args.scheduler:
            raise UsageError("--executor dask needs --scheduler ADDRESS (tcp://host:port)")
        from experiments.executors.cluster import check_scheduler

        check_scheduler(args.scheduler)
    baseline = baseline_for(args.baseline, config.device_family())
    best = sweep_best_designs(args.sweep, config)
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
