"""``partfeeder report``: the summary and HTML report of a sweep directory (also how
``partfeeder run`` ends)."""

from __future__ import annotations

import argparse
import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

from experiments.cli.usage import UsageError


def add_arguments(report: argparse.ArgumentParser) -> None:
    report.add_argument("dir", type=Path, help="a sweep directory (holds results.sqlite)")
    report.add_argument("--json", action="store_true", help="print the summary as JSON")


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


def finish(
    out: Path,
    args: argparse.Namespace,
    extra: dict[str, Any],
    export: Callable[[], object] | None = None,
) -> int:
    """Summarise the sweep in ``out``, write its report (unless ``--no-report``) and
    ``summary.json``, and print the summary (a table, or JSON with ``--json``); ``export``
    (``run``: OMPL's database from the stored logs) is called first, unless the results have
    not changed since it last was and ``ompl/benchmark.db`` is there.

    A report is drawn again only when what it shows may have changed: the summary and the
    report's state are kept in ``report-cache.json`` under a key of the results database's
    rows and of the code that draws it (:func:`report_key`); with the key unchanged and the
    report's files as they were written, the stored summary is printed and nothing is
    redrawn (a finished sweep's ``report`` took 5.0 s on 64 designs, up to 68 s in the
    issue, all of it figures and nominal drops drawn again)."""
    from experiments.progress import phase, say
    from experiments.sweep import results_db
    from experiments.sweep.report_cache import (
        OMPL_DATABASE,
        load_cache,
        report_intact,
        report_key,
        report_state,
        save_cache,
    )
    from experiments.sweep.summary import summary_table

    quiet = bool(getattr(args, "quiet", False))
    results = out / "results.sqlite"
    results_db.check_database(results)  # refused as the summary would refuse it
    key = report_key(results)  # before the summary: a key never newer than what it keys
    cache = load_cache(out, key)
    if cache is None:
        from experiments.sweep.summary import summarise

        cache = {"key": key, "summary": summarise(results), "report": None}
    if export is not None:
        if key is None or cache.get("ompl") != key or not (out / OMPL_DATABASE).exists():
            export()
        cache["ompl"] = key
    summary = {**cache["summary"], **extra}
    files = {"results": str(results)}
    if (out / OMPL_DATABASE).exists():
        files["ompl_database"] = str(out / OMPL_DATABASE)
    if not getattr(args, "no_report", False):
        page = out / "report.html"
        if report_intact(out, cache["report"]):
            say(f"{page} is up to date (the results have not changed)", quiet)
        else:
            from experiments.sweep.report import write_report

            with phase("writing the report", quiet):
                page = write_report(out, summary, results)
            cache["report"] = report_state(out)
        files["report"] = str(page)
    if key is not None:
        save_cache(out, cache)
    summary["files"] = files
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(summary_table(summary))
        if "wall_time_s" in summary:
            print(f"wall time: {summary['wall_time_s']:.1f} s")
        for name, path in files.items():
            print(f"{name}: {path}")
    return 0
