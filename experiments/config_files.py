"""Where a job's config file is: a path, or the name of a config shipped with partfeeder
(``experiments/configs/NAME.yaml``, package data), so ``partfeeder run paper`` and
``partfeeder optimize optimize`` work from any directory. Shared by every job that reads one."""

from __future__ import annotations

from pathlib import Path

CONFIG_DIR = Path(__file__).resolve().parent / "configs"  # experiments/configs/*.yaml


def resolve_config(path: str | Path) -> Path:
    """``path``, or the shipped config of that name (``experiments/configs/NAME.yaml``) when
    ``path`` is a bare name with no suffix and no such file here."""
    path = Path(path)
    shipped = CONFIG_DIR / f"{path.name}.yaml"
    if len(path.parts) == 1 and path.suffix == "" and not _exists(path) and _exists(shipped):
        return shipped
    return path


def _exists(path: Path) -> bool:
    """Whether ``path`` exists (a name too long for the file system does not)."""
    try:
        return path.exists()
    except OSError:
        return False
