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


def shipped_configs() -> dict[str, list[str]]:
    """The shipped configs' names (sorted) by the command that reads them, from the package's
    configs directory: each file's first line names its command (``# partfeeder run ...``,
    ``# partfeeder optimize ...``), so ``--help`` lists every one without a hard-coded list
    and without parsing YAML. A file whose first line names no command is under ``""``."""
    found: dict[str, list[str]] = {}
    for path in sorted(CONFIG_DIR.glob("*.yaml"), key=lambda p: p.stem):
        with path.open(encoding="utf-8") as f:
            words = f.readline().replace(":", " ").split()
        command = words[2] if words[:2] == ["#", "partfeeder"] and len(words) > 2 else ""
        found.setdefault(command, []).append(path.stem)
    return found


def shipped_configs_help(command: str) -> str:
    """The shipped configs for ``--help``: ``command``'s by name, then the others' with their
    command (every shipped config named, each where it belongs)."""
    configs = shipped_configs()
    others = "; ".join(
        f"for {other or 'no command'}: {', '.join(names)}"
        for other, names in sorted(configs.items())
        if other != command
    )
    return ", ".join(configs.get(command, [])) + (f" ({others})" if others else "")
