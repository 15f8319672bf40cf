"""``partfeeder report``: the summary and HTML report of a sweep directory (also how
``partfeeder run`` ends)."""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
from typing import Any

from experiments.cli.usage import UsageError


def add_arguments(report: argparse.ArgumentParser) -> None:
    report.add_argument("dir", type=Path, help="a sweep directory (holds results.sqlite)")
    report.add_argument("--json", action="store_true", help="print the summary as JSON")


# what ``finish`` writes in a sweep directory, beside the figures in ``figures/``
WRITTEN = ("summary.json", "report.html", "report.html.partial", "figures")


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


def finish(out: Path, args: argparse.Namespace, extra: dict[str, Any]) -> int:
    """Summarise the sweep in ``out``, write its report (unless ``--no-report``) and
    ``summary.json``, and print the summary (a table, or JSON with ``--json``)."""
    from experiments.sweep.report import write_report
    from experiments.sweep.summary import summarise, summary_table

    results = out / "results.sqlite"
    summary = summarise(results)
    summary.update(extra)
    files = {"results": str(results)}
    if (out / "ompl" / "benchmark.db").exists():
        files["ompl_database"] = str(out / "ompl" / "benchmark.db")
    if not getattr(args, "no_report", False):
        files["report"] = str(write_report(out, summary, results))
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
