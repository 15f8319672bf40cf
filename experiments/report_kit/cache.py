"""What a report's cache is made of, once for every job's report: a digest of the code that
draws it, the state of the files it wrote, and a JSON file written whole or not at all.

A job's cache (:mod:`experiments.sweep.report_cache`, :mod:`experiments.optimize.
report_cache`) keys its report on what the report shows (its own results) and on
:func:`code_digest`; it keeps the report when the key is unchanged and
:func:`report_intact` says its files are as written (issue 25: a finished sweep's report
was drawn again in 68 s, its figures and nominal drops, on every ``report``)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

# packages whose code decides what a report shows: a change in any draws it again
REPORT_CODE = ("experiments", "feeders", "validity", "planners")
LIBRARIES = ("matplotlib", "numpy")  # whose versions change the pictures


def code_digest(digest: Any, packages: tuple[str, ...] = REPORT_CODE) -> Any:
    """``digest`` (a :mod:`hashlib` object) updated with every ``.py`` file of
    ``packages`` (path and bytes, in sorted order) and the versions of :data:`LIBRARIES`."""
    from importlib import metadata, util

    for package in packages:
        spec = util.find_spec(package)
        for root in (spec.submodule_search_locations or []) if spec else []:
            for source in sorted(Path(root).rglob("*.py")):
                digest.update(str(source.relative_to(root)).encode())
                digest.update(source.read_bytes())
    for dist in LIBRARIES:
        digest.update(f"{dist} {metadata.version(dist)}".encode())
    return digest


def report_state(out: Path) -> dict[str, list[int]]:
    """``report.html`` and each picture in ``figures/`` by size and modification time (ns),
    as just written."""
    paths = [out / "report.html", *sorted((out / "figures").glob("*"))]
    return {
        str(p.relative_to(out)): [p.stat().st_size, p.stat().st_mtime_ns]
        for p in paths
        if p.is_file()
    }


def report_intact(out: Path, state: Any) -> bool:
    """The report's files are those recorded in ``state``: none removed, replaced, edited
    or added."""
    return isinstance(state, dict) and bool(state) and report_state(out) == state


def read_json(path: Path) -> Any:
    """The JSON document at ``path``, or None when it is missing or not JSON."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def save_json(path: Path, data: Any) -> None:
    """``data`` as JSON at ``path``, written beside it and renamed: a reader never sees
    half of it."""
    partial = path.with_name(f"{path.name}.partial")
    partial.write_text(json.dumps(data, indent=1))
    os.replace(partial, path)
