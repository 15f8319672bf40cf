"""The scene a subcommand works on: ``--design`` (a paper preset or 12 values) or ``--scene``
(a YAML file), and the entry orientations to run from it."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from experiments.cli.usage import UsageError
from experiments.names import PRESET_NAMES

if TYPE_CHECKING:
    from feeders.scene import Scene


def add_scene_arguments(p: argparse.ArgumentParser) -> None:
    """``--design`` or ``--scene`` (one of them; default: the table3 preset)."""
    group = p.add_mutually_exclusive_group()
    group.add_argument(
        "--design",
        default=None,
        help=f"a paper preset ({', '.join(sorted(PRESET_NAMES))}) or the 12 values "
        "a,b,c,d,e,fx,fy,gx,gy,r,theta,alpha separated by commas (default: table3)",
    )
    group.add_argument("--scene", type=Path, help="a scene YAML file")


def load_scene(design: str | None, scene_file: Path | None) -> Scene:
    """The scene of ``--design`` / ``--scene``, physically sane (the same checks as a scene
    file: :func:`feeders.scene_yaml.checked_scene`); UsageError for bad values or a bad file."""
    from feeders.design import DesignError, DesignParameters, preset
    from feeders.feeder import DegenerateDesign, build_feeder
    from feeders.fields import shown
    from feeders.scene_yaml import SceneError, checked_scene, load_scene

    try:
        if scene_file is not None:
            return load_scene(scene_file)
        spec = "table3" if design is None else design.strip()
        if not spec:
            raise UsageError(
                f"--design is empty; give a preset ({', '.join(sorted(PRESET_NAMES))}) or "
                "12 comma-separated values"
            )
        if "," in spec:
            try:
                values = [float(v) for v in spec.split(",")]
            except ValueError:
                raise UsageError(
                    f"--design: '{shown(spec)}' is not 12 comma-separated numbers"
                ) from None
            scene = build_feeder(DesignParameters.from_vector(values), name="custom design")
        else:
            scene = build_feeder(preset(spec), name=spec)
        return checked_scene(scene)
    except (DesignError, SceneError) as exc:
        raise UsageError(str(exc)) from None
    except DegenerateDesign as exc:
        raise UsageError(f"degenerate design: {exc}") from None


def orientations(scene: Scene, choice: str) -> list[str]:
    """``both`` (the feeder's two entries, or every start of a free-form scene) or one start."""
    from feeders.feeder import ORIENTATIONS

    if choice == "both":
        return [o for o in ORIENTATIONS if o in scene.starts] or list(scene.starts)
    if choice in scene.starts:
        return [choice]
    raise UsageError(
        f"--orientation '{choice}' is not a start of this scene; "
        f"choose both or one of: {', '.join(scene.starts)}"
    )
