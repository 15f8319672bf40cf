"""What a run was measured with: the repository's commit, the contact kernel's last commit and
whether the working tree's kernel differs from it (the kernel changes while this suite is used
to judge it), and the engines' versions."""

from __future__ import annotations

import hashlib
import subprocess
from pathlib import Path

import validity.contact_kernel as contact_kernel
from experiments.bench.engines import engine_versions


def _git(root: Path, *args: str) -> str | None:
    try:
        done = subprocess.run(
            ["git", *args], cwd=root, capture_output=True, text=True, timeout=10, check=False
        )
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def kernel_state() -> str:
    """One line: HEAD, the kernel file's last commit, and "modified" with the file's SHA-1
    prefix when the working tree's kernel is not that commit's."""
    path = Path(contact_kernel.__file__).resolve()
    root = path.parent.parent
    digest = hashlib.sha1(path.read_bytes()).hexdigest()[:10]
    head = _git(root, "rev-parse", "--short", "HEAD")
    last = _git(root, "log", "-1", "--format=%h %cs", "--", str(path))
    if head is None or last is None:
        return f"validity/contact_kernel.py sha1 {digest} (no git)"
    dirty = _git(root, "status", "--porcelain", "--", str(path))
    state = f"working tree modified, file sha1 {digest}" if dirty else "as committed"
    return f"HEAD {head}; validity/contact_kernel.py last commit {last}, {state}"


def versions() -> dict[str, str]:
    """Engine versions (``not installed`` for an absent peer)."""
    return engine_versions()
