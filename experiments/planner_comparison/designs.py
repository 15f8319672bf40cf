"""A config's design (plain data, :mod:`.suite`) as a scene: built in the worker that plans
it, so that only the plain description crosses processes."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from feeders.scene import Scene


def scene_for(design: dict[str, Any], base: str = ".") -> Scene:
    """The scene of ``design`` (named by :func:`.suite.design_name`); a relative family or
    scene path is read from ``base`` (the config's directory), else as a packaged name."""
    from experiments.planner_comparison.suite import design_name

    name = design_name(design)
    if "preset" in design:
        from feeders.design import PRESETS
        from feeders.feeder import build_feeder

        return build_feeder(PRESETS[design["preset"]], name=name)
    if "halton" in design:
        from feeders.feeder import build_feeder
        from feeders.halton import halton_designs

        h = design["halton"]
        values = halton_designs(int(h["index"]) + 1, int(h["seed"]))[int(h["index"])]
        return build_feeder(values, name=name)
    if "family" in design:
        import dataclasses

        from feeders.device_family import load_family, packaged_family

        given = Path(str(design["family"]))
        path = _local(given, base) or packaged_family(str(given))
        if path is None:
            raise FileNotFoundError(2, "no such family file or packaged family", str(given))
        family = load_family(path)
        vector = design.get("values") or [p.default for p in family.parameters]
        return dataclasses.replace(family.build(list(vector)), name=name)
    from feeders.scene_yaml import load_scene

    given = Path(str(design["scene"]))
    path = _local(given, base)
    if path is None:
        from experiments.config_files import CONFIG_DIR

        path = CONFIG_DIR.parent / "scenes" / f"{given.stem}.yaml"
    return load_scene(path)


def _local(given: Path, base: str) -> Path | None:
    """``given`` as a file (relative to ``base`` when relative), or None when there is none."""
    path = given if given.is_absolute() else Path(base) / given
    return path if path.is_file() else None
