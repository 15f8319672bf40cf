"""Where a job's config file is: a path, or the name of a config shipped with partfeeder
(``experiments/configs/NAME.yaml``, package data), so ``partfeeder run paper`` and
``partfeeder optimize optimize`` work from any directory. Shared by every job that reads one."""

from __future__ import annotations

from pathlib import Path

CONFIG_DIR = Path(__file__).resolve().parent / "configs"  # experiments/configs/*.yaml


def resolve_config(path: str | Path) -> Path:
    """``path``, or the shipped config of that name (``experiments/configs/NAME.yaml``) when
    ``path`` is a bare name with no suffix and no such file here. A directory of that name
    is not such a file: a job's default output folder is named after its config
    (``optimize/optimize`` for ``partfeeder optimize``), and the command run again to resume
    must find its config, not its output (issue 39)."""
    path = Path(path)
    shipped = CONFIG_DIR / f"{path.name}.yaml"
    here = _exists(path) and not path.is_dir()
    if len(path.parts) == 1 and path.suffix == "" and not here and _exists(shipped):
        return shipped
    return path


def _exists(path: Path) -> bool:
    """Whether ``path`` exists (a name too long for the file system does not)."""
    try:
        return path.exists()
    except OSError:
        return False
