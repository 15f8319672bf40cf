"""What a test compares to say that nothing in a directory was created or changed."""

from __future__ import annotations

import hashlib
from pathlib import Path


def directory_state(directory: Path) -> dict[str, tuple[str, int, int]]:
    """Every file under ``directory``: its SHA-256, size and modification time (ns)."""
    return {
        str(p.relative_to(directory)): (
            hashlib.sha256(p.read_bytes()).hexdigest(),
            p.stat().st_size,
            p.stat().st_mtime_ns,
        )
        for p in sorted(directory.rglob("*"))
        if p.is_file()
    }
