"""``partfeeder report``: the summary and HTML report of a sweep directory (also how
``partfeeder run`` ends)."""

from __future__ import annotations

import argparse
import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any, TextIO

from experiments.cli.baseline import add_baseline_argument, baseline_for, check_baseline_form
from experiments.cli.usage import UsageError

MARGINS_AXES = 16  # the margins' axes (experiments.margins.axes): 12 parameters, mu, the part


def add_arguments(report: argparse.ArgumentParser) -> None:
    report.add_argument("dir", type=Path, help="a sweep directory (holds results.sqlite)")
    report.add_argument("--json", action="store_true", help="print the summary as JSON")
    add_baseline_argument(report)
    report.add_argument(
        "--workers",
        type=int,
        default=None,
        help="worker processes for the recommended design's margins (default: the sweep's)",
    )


# what ``finish`` writes in a sweep directory, beside the figures in ``figures/``
WRITTEN = (
    "summary.json",
    "report.html",
    "report.html.partial",
    "figures",
    "report-cache.json",
    "report-cache.json.partial",
)


def run(args: argparse.Namespace) -> int:
    check_baseline_form(args.baseline)  # a bad --baseline is one line before any work
    if args.workers is not None:
        from experiments.cli.usage import check_count

        check_count(args.workers, "--workers", 1024)
    if not (args.dir / "results.sqlite").exists():
        raise UsageError(f"{args.dir}: no results.sqlite here (is it a sweep directory?)")
    unwritable = not_writable(args.dir)
    if unwritable is not None:
        raise UsageError(
            f"'{unwritable}' is not writable, and the report is written into the sweep "
            "directory (report.html, figures/, summary.json); make it writable, or copy "
            "the directory"
        )
    return finish(args.dir, args, {})


def not_writable(out: Path) -> Path | None:
    """The first of the sweep directory ``out`` and what the report writes there (existing
    files it replaces or rewrites, ``figures/`` and its pictures) that this process may not
    write, else None. Checked before the database is read, so a directory that is read-only
    (permissions, an immutable attribute, a read-only mount) is one line, not a traceback
    halfway through the figures; the database itself is only read
    (:func:`experiments.sweep.results_db.connect` with ``readonly``), so reading a sweep
    needs no write access."""
    figures = out / "figures"
    pictures = sorted(figures.iterdir()) if figures.is_dir() else []
    for path in (out, *(out / name for name in WRITTEN), *pictures):
        if not path.exists():
            continue
        mode = os.W_OK | (os.X_OK if path.is_dir() else 0)
        if not os.access(path, mode):
            return path
    return None


class MarginsProgress:
    """A bar over the recommended design's margins, one axis at a time, with a fixed total
    (the axes, :data:`MARGINS_AXES`) and tqdm's time estimate: the margins are most of a
    report's time (about 30 s on 2 workers), which was a silent wait. The report's
    ``progress`` (:mod:`experiments.sweep.report_recommendation`); ``stream`` None draws on
    stderr when it is a terminal (tests give a ``StringIO``)."""

    def __init__(self, quiet: bool, stream: TextIO | None = None):
        self.quiet = quiet
        self.stream = stream
        self.bar: Any = None

    def __call__(self, event: str, info: dict[str, Any]) -> None:
        if self.quiet:
            return
        if event == "margins":
            from experiments.progress import bar

            self.close()
            self.bar = bar(
                int(info.get("axes", MARGINS_AXES)),
                f"margins of {info.get('design', 'the design')}",
                "axis",
                stream=self.stream,
            )
        elif event == "axis" and self.bar is not None:
            self.bar.set_postfix_str(str(info.get("parameter", "")), refresh=False)
            self.bar.update(1)
        elif event == "skipped" and self.bar is not None:  # not needed: the total shrinks
            self.bar.total = max(self.bar.n, self.bar.total - int(info["axes"]))
            self.bar.set_postfix_str(f"{info['design']}: {info['axes']} axes not needed")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


def finish(
    out: Path,
    args: argparse.Namespace,
    extra: dict[str, Any],
    export: Callable[[], object] | None = None,
) -> int:
    """Summarise the sweep in ``out``, write its report (unless ``--no-report``) and
    ``summary.json``, and print the summary (a table, or JSON with ``--json``); ``export``
    (``run``: OMPL's database from the stored logs) is called first, unless the results have
    not changed since it last was and ``ompl/benchmark.db`` is there. The summary holds what
    the report found (:data:`experiments.sweep.report.FINDINGS`: the comparison with
    ``--baseline`` on fresh draws, the recommendation, the recommended design's margins,
    computed on ``--workers`` processes, default the sweep's).

    A report is drawn again only when what it shows may have changed: the summary, what the
    report found and the report's state are kept in ``report-cache.json`` under a key of the
    results database's rows, of the code that draws it and of the baseline
    (:func:`report_key`, :func:`with_baseline`); with the key unchanged and the report's
    files as they were written, the stored summary is printed and nothing is redrawn (a
    finished sweep's ``report`` took 5.0 s on 64 designs, up to 68 s in the issue, all of it
    figures and nominal drops drawn again).

    ``extra`` with ``sweep_time_s`` (``run``): the summary's ``wall_time_s`` is the whole
    command's, the sweep's and then ``report_time_s``, this function's (the OMPL database,
    the summary and the report: longer than the sweep in two of issue 39's three runs), and
    the printed wall time names both."""
    import time

    started = time.perf_counter()

    from experiments.progress import say
    from experiments.report_kit.cache import report_intact, report_state
    from experiments.sweep import results_db
    from experiments.sweep.family import database_family
    from experiments.sweep.report_cache import (
        OMPL_DATABASE,
        load_cache,
        report_key,
        save_cache,
        with_baseline,
    )
    from experiments.sweep.summary import summary_table

    quiet = bool(getattr(args, "quiet", False) or getattr(args, "json", False))  # as run's bars
    results = out / "results.sqlite"
    results_db.check_database(results)  # refused as the summary would refuse it
    found = database_family(results)  # --baseline's meaning: the feeder's, or a family's
    family = None if found is None else found[0]
    baseline = baseline_for(getattr(args, "baseline", None), family)
    rows = report_key(results)  # before the summary: a key never newer than what it keys
    key = with_baseline(rows, baseline)
    cache = load_cache(out, key)
    if cache is None:
        from experiments.sweep.summary import summarise

        cache = {"key": key, "summary": summarise(results), "report": None}
    if export is not None:
        if rows is None or cache.get("ompl") != rows or not (out / OMPL_DATABASE).exists():
            export()
        cache["ompl"] = rows
    summary = {**cache["summary"], **(cache.get("findings") or {}), **extra}
    files = {"results": str(results)}
    if (out / OMPL_DATABASE).exists():
        files["ompl_database"] = str(out / OMPL_DATABASE)
    if not getattr(args, "no_report", False):
        page = out / "report.html"
        if report_intact(out, cache["report"]):
            say(f"{page} is up to date (the results have not changed)", quiet)
        else:
            from experiments.sweep.report import report_with_findings

            say(
                "writing the report (figures, the top designs judged again on fresh draws, "
                "the margins of those confirmed and of the baseline) ...",
                quiet,
            )
            t0 = time.perf_counter()
            bars = MarginsProgress(quiet)
            try:
                page, findings = report_with_findings(
                    out,
                    {**cache["summary"], **extra},
                    results,
                    baseline=baseline,
                    workers=getattr(args, "workers", None),
                    progress=bars,
                )
            finally:
                bars.close()
            say(f"report written in {time.perf_counter() - t0:.1f} s", quiet)
            cache["findings"] = findings
            cache["report"] = report_state(out)
            summary = {**cache["summary"], **findings, **extra}
        files["report"] = str(page)
    if key is not None:
        save_cache(out, cache)
    summary["files"] = files
    if "sweep_time_s" in extra:
        summary["report_time_s"] = time.perf_counter() - started
        summary["wall_time_s"] = extra["sweep_time_s"] + summary["report_time_s"]
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(summary_table(summary))
        recommended = recommendation_line(summary.get("recommendation"))
        if recommended is not None:
            print(recommended)
        cost = (summary.get("recommendation") or {}).get("margins_cost")
        if cost:
            print(
                f"margins: {cost['designs']} designs (the confirmed ones and the baseline), "
                f"{cost['trials']} trials ({cost['drops']} drops) in "
                f"{cost['wall_time_s']:.1f} s"
            )
        if "wall_time_s" in summary:
            print(wall_time_line(summary, reported="report" in files))
        for name, path in files.items():
            print(f"{name}: {path}")
    return 0


def wall_time_line(summary: dict[str, Any], reported: bool) -> str:
    """``wall time: 95.3 s (sweep 35.7 s, OMPL database, summary and report 59.6 s)``: the
    command's, and its parts when the summary has them."""
    line = f"wall time: {summary['wall_time_s']:.1f} s"
    if "sweep_time_s" not in summary or "report_time_s" not in summary:
        return line
    after = "OMPL database, summary and report" if reported else "OMPL database and summary"
    return (
        f"{line} (sweep {summary['sweep_time_s']:.1f} s, {after} {summary['report_time_s']:.1f} s)"
    )


def recommendation_line(recommendation: dict[str, Any] | None) -> str | None:
    """The recommendation in one line of the printed summary (None without one)."""
    if not recommendation:
        return None
    if recommendation.get("decision") == "keep the baseline":
        return (
            f"recommended: keep the baseline {recommendation['label']}: "
            f"{recommendation.get('why')}; {recommendation['sentence']}"
        )
    if recommendation.get("confirmed"):
        why = f" ({recommendation['why']})" if recommendation.get("why") else ""
        return f"recommended: {recommendation['label']}{why}, {recommendation['sentence']}"
    return f"recommended: none, {recommendation.get('sentence')}"
