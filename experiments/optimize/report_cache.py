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
from pathlib import Path
from typing import Any

from experiments.report_kit.cache import (
    code_digest,
    read_json,
    report_intact,
    report_state,
    save_json,
)

CACHE = "report-cache.json"
CACHE_FORMAT = "partfeeder optimize report cache 1"
# results that change with every run of the command, not with what the report shows
VOLATILE = ("wall_time_s", "new_evaluations", "files")


def report_key(results: dict[str, Any], config: dict[str, Any]) -> str:
    """SHA-256 of ``results`` (but :data:`VOLATILE`), ``config`` and the code that draws
    the report (:func:`experiments.report_kit.cache.code_digest`)."""
    digest = hashlib.sha256(CACHE_FORMAT.encode())
    shown = {k: v for k, v in results.items() if k not in VOLATILE}
    digest.update(json.dumps([shown, config], sort_keys=True, default=str).encode())
    return code_digest(digest).hexdigest()


def report_current(out: Path, key: str) -> bool:
    """Whether ``out``'s report was written under ``key`` and its files are as written: none
    removed, replaced, edited or added."""
    cache = read_json(out / CACHE)
    if not isinstance(cache, dict) or cache.get("key") != key:
        return False
    return report_intact(out, cache.get("state"))


def save_cache(out: Path, key: str) -> None:
    """Record the report just written under ``key`` (written whole or not at all)."""
    save_json(out / CACHE, {"key": key, "state": report_state(out)})
