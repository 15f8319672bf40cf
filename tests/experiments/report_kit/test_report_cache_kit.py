"""A report's cache keys on the code that draws it and keeps a report only while its files
are exactly as written."""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

from experiments.report_kit.cache import (
    code_digest,
    read_json,
    report_intact,
    report_state,
    save_json,
)


def test_the_code_digest_changes_with_any_source_file_of_the_packages(tmp_path, monkeypatch):
    package = tmp_path / "drawpkg"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "draw.py").write_text("COLOUR = 'red'\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    sys.modules.pop("drawpkg", None)

    def key() -> str:
        return code_digest(hashlib.sha256(), ("drawpkg",)).hexdigest()

    before = key()
    assert key() == before
    (package / "draw.py").write_text("COLOUR = 'blue'\n")
    assert key() != before


def report(out: Path) -> None:
    (out / "figures").mkdir(parents=True, exist_ok=True)
    (out / "report.html").write_text("<html></html>")
    (out / "figures" / "a.png").write_bytes(b"png")


def test_a_report_is_intact_until_a_file_is_edited_removed_or_added(tmp_path):
    report(tmp_path)
    state = report_state(tmp_path)
    assert report_intact(tmp_path, state)
    (tmp_path / "figures" / "b.png").write_bytes(b"new")
    assert not report_intact(tmp_path, state)
    (tmp_path / "figures" / "b.png").unlink()
    assert report_intact(tmp_path, state)
    (tmp_path / "report.html").write_text("<html>edited</html>")
    assert not report_intact(tmp_path, state)
    assert not report_intact(tmp_path, {}) and not report_intact(tmp_path, None)


def test_json_is_written_whole_and_a_bad_file_reads_as_none(tmp_path):
    path = tmp_path / "cache.json"
    save_json(path, {"key": "k"})
    assert read_json(path) == {"key": "k"}
    assert list(tmp_path.iterdir()) == [path]  # no partial file left beside it
    path.write_text("{not json")
    assert read_json(path) is None and read_json(tmp_path / "missing.json") is None
