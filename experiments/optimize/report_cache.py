"""A finished optimisation's report is drawn again only when what it shows may have changed.

``report-cache.json`` in the output directory holds a key (the results as the report shows
them, the config, and the source of the code that draws them) and the state of the files
written under it (``report.html`` and ``figures/``, by size and modification time). A run
started again in a finished directory gets the same results; when the key and the files
are unchanged the report is kept (issue 25: drawing it again, nominal drops and every
figure, cost about 2 s of a 3 s re-run before the margins and the overlay were added).
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

CACHE = "report-cache.json"
CACHE_FORMAT = "partfeeder optimize report cache 1"
# packages whose code decides what the report shows: a change in any draws it again
REPORT_CODE = ("experiments", "feeders", "validity")
# results that change with every run of the command, not with what the report shows
VOLATILE = ("wall_time_s", "new_evaluations", "files")


def report_key(results: dict[str, Any], config: dict[str, Any]) -> str:
    """SHA-256 of ``results`` (but :data:`VOLATILE`), ``config`` and the source of
    :data:`REPORT_CODE` with the matplotlib and numpy versions."""
    from importlib import metadata, util

    digest = hashlib.sha256(CACHE_FORMAT.encode())
    shown = {k: v for k, v in results.items() if k not in VOLATILE}
    digest.update(json.dumps([shown, config], sort_keys=True, default=str).encode())
    for package in REPORT_CODE:
        spec = util.find_spec(package)
        for root in (spec.submodule_search_locations or []) if spec else []:
            for source in sorted(Path(root).rglob("*.py")):
                digest.update(str(source.relative_to(root)).encode())
                digest.update(source.read_bytes())
    for dist in ("matplotlib", "numpy"):
        digest.update(f"{dist} {metadata.version(dist)}".encode())
    return digest.hexdigest()


def report_state(out: Path) -> dict[str, list[int]]:
    """``report.html`` and each picture in ``figures/`` by size and modification time (ns)."""
    paths = [out / "report.html", *sorted((out / "figures").glob("*"))]
    return {
        str(p.relative_to(out)): [p.stat().st_size, p.stat().st_mtime_ns]
        for p in paths
        if p.is_file()
    }


def report_current(out: Path, key: str) -> bool:
    """Whether ``out``'s report was written under ``key`` and its files are as written: none
    removed, replaced, edited or added."""
    try:
        cache = json.loads((out / CACHE).read_text())
    except (OSError, ValueError):
        return False
    if not isinstance(cache, dict) or cache.get("key") != key:
        return False
    state = cache.get("state")
    return isinstance(state, dict) and bool(state) and report_state(out) == state


def save_cache(out: Path, key: str) -> None:
    """Record the report just written under ``key`` (written beside and renamed: a reader
    never sees half of it)."""
    partial = out / f"{CACHE}.partial"
    partial.write_text(json.dumps({"key": key, "state": report_state(out)}, indent=1))
    os.replace(partial, out / CACHE)
