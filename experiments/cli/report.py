"""``partfeeder report``: the summary and HTML report of a sweep directory (also how
``partfeeder run`` ends)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from experiments.cli.usage import UsageError


def add_arguments(report: argparse.ArgumentParser) -> None:
    report.add_argument("dir", type=Path, help="a sweep directory (holds results.sqlite)")
    report.add_argument("--json", action="store_true", help="print the summary as JSON")


def run(args: argparse.Namespace) -> int:
    if not (args.dir / "results.sqlite").exists():
        raise UsageError(f"{args.dir}: no results.sqlite here (is it a sweep directory?)")
    return finish(args.dir, args, {})


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
