"""The scene a subcommand works on: ``--design`` (a paper preset or 12 values) or ``--scene``
(a YAML file, or the name of a scene packaged with partfeeder), and the entry orientations to
run from it. What a specification means is :mod:`feeders.scene_spec`'s (shared with the Python
API); here its errors become one-line usage errors."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from experiments.cli.usage import UsageError
from experiments.names import PRESET_NAMES

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily
    from feeders.scene import Scene

PACKAGED_SCENES = "scenes"  # experiments/scenes/<name>.yaml, package data of the wheel
# Named in --scene's help; tests/experiments/cli/test_scene_arguments.py checks they exist.
SCENE_EXAMPLES = ("table3", "incline", "drop")
PACKAGED_FAMILIES = "families"  # feeders/families/<name>.yaml, package data of the wheel
FAMILY_EXAMPLES = ("fig1",)


def add_scene_arguments(p: argparse.ArgumentParser) -> None:
    """``--design`` or ``--scene`` (one of them; default: the table3 preset)."""
    group = p.add_mutually_exclusive_group()
    group.add_argument(
        "--design",
        default=None,
        help=f"a paper preset ({', '.join(sorted(PRESET_NAMES))}) or the 12 values "
        "a,b,c,d,e,fx,fy,gx,gy,r,theta,alpha separated by commas (default: table3)",
    )
    group.add_argument(
        "--scene",
        type=Path,
        help="a scene YAML file, or the name of a scene packaged with partfeeder "
        f"({', '.join(SCENE_EXAMPLES)}, ...; a file of that name comes first)",
    )
    group.add_argument(
        "--family",
        type=Path,
        help="a device family YAML file (docs/families.md), or the name of one packaged "
        f"with partfeeder ({', '.join(FAMILY_EXAMPLES)}): its default design, or --values",
    )
    p.add_argument(
        "--values",
        default=None,
        help="with --family: the design's values, comma-separated in the order of the "
        "family's parameters (default: the family's defaults)",
    )


def packaged_scene_names() -> list[str]:
    """The scenes packaged with partfeeder (``experiments/scenes/*.yaml``), by name."""
    return _packaged_names("experiments", PACKAGED_SCENES)


def _packaged_names(package: str, folder: str) -> list[str]:
    """The ``*.yaml`` files of ``package``'s data ``folder``, by name."""
    from importlib.resources import files

    found = files(package).joinpath(folder).iterdir()
    return sorted(e.name[: -len(".yaml")] for e in found if e.name.endswith(".yaml"))


def _file_or_packaged(
    given: Path, flag: str, kind: tuple[str, str], package: str, folder: str
) -> Path:
    """``given`` if such a file exists (or it is a path with a directory part), else the
    ``kind`` (singular, plural) packaged with partfeeder under that name (``table3`` or
    ``table3.yaml``), read through importlib.resources so that it works from an installed
    wheel in any directory; UsageError naming ``flag`` and listing the packaged names when
    it is neither."""
    from importlib.resources import as_file, files

    text = str(given)
    if given.exists() or given.parent != Path("."):
        return given
    name = text[: -len(".yaml")] if text.endswith(".yaml") else text
    names = _packaged_names(package, folder)
    if name not in names:
        from feeders.fields import shown

        raise UsageError(
            f"{flag}: '{shown(text)}' is neither a file nor a packaged {kind[0]}; "
            f"packaged {kind[1]}: {', '.join(names)}"
        )
    resource = files(package).joinpath(folder, f"{name}.yaml")
    with as_file(resource) as path:  # a real file for an installed package (not zipped)
        return Path(path)


def family_path(given: Path) -> Path:
    """The file ``--family`` names: a file, or a family packaged with partfeeder."""
    return _file_or_packaged(
        given, "--family", ("family", "families"), "feeders", PACKAGED_FAMILIES
    )


def load_family_design(family_file: Path, values: str | None) -> tuple[DeviceFamily, list[float]]:
    """The family ``--family`` names and the design ``--values`` gives (its defaults without
    them), checked: UsageError naming the file and field, or ``--values``."""
    from feeders.device_family import FamilyError, load_family
    from feeders.fields import shown

    try:
        family = load_family(family_path(family_file))
    except FamilyError as exc:
        raise UsageError(str(exc)) from None
    if values is None:
        return family, [float(v) for v in family.default()]
    names = family.vector_names
    try:
        vector = [float(v) for v in values.split(",")]
    except ValueError:
        raise UsageError(
            f"--values = '{shown(values)}': expected {len(names)} comma-separated numbers "
            f"({', '.join(names)})"
        ) from None
    if len(vector) != len(names):
        raise UsageError(
            f"--values: {len(vector)} numbers given; the family {family.name} has "
            f"{len(names)} parameters: {', '.join(names)}"
        )
    for name, value in zip(names, vector, strict=True):
        if not math.isfinite(value):  # nan, inf, 1e999: nothing a simulation can make
            raise UsageError(
                f"--values: {family.name}: parameter {name} = {value} is not finite; every "
                "value must be finite (a value outside the family's box is allowed)"
            )
    return family, vector


def scene_path(given: Path) -> Path:
    """The file ``--scene`` names: a file, or a scene packaged with partfeeder."""
    return _file_or_packaged(given, "--scene", ("scene", "scenes"), "experiments", PACKAGED_SCENES)


def load_scene(
    design: str | None,
    scene_file: Path | None,
    family_file: Path | None = None,
    values: str | None = None,
) -> Scene:
    """The scene of ``--design`` / ``--scene`` / ``--family`` (with ``--values``), physically
    sane (the same checks as a scene file: :func:`feeders.scene_yaml.checked_scene`; a
    family's build checks its rules and pieces); UsageError for bad values or a bad file."""
    from feeders.design import DesignError
    from feeders.feeder import DegenerateDesign
    from feeders.scene_spec import design_scene, scene_of
    from feeders.scene_yaml import SceneError

    if values is not None and family_file is None:
        raise UsageError("--values needs --family (a design's values are --design's)")
    if family_file is not None:
        family, vector = load_family_design(family_file, values)
        try:
            return family.build(vector)
        except DegenerateDesign as exc:
            raise UsageError(f"--values: the family's design cannot be built: {exc}") from None

    if design is not None and not design.strip():
        raise UsageError(
            f"--design is empty; give a preset ({', '.join(sorted(PRESET_NAMES))}) or "
            "12 comma-separated values"
        )
    try:
        if scene_file is not None:
            return scene_of(scene_path(scene_file))
        scene = design_scene("table3" if design is None else design)
    except (DesignError, SceneError) as exc:
        raise UsageError(str(exc)) from None
    warn_outside_box(design)
    return scene


def outside_box(text: str | None, flag: str = "--design") -> str | None:
    """One line when the 12 values ``text`` gives (as ``--design`` or ``--baseline`` take
    them) lie outside Table 2's box, naming each such parameter, its value and its range;
    None inside the box, for a paper preset (the paper's own: fig5a's theta lies below the
    box by the paper's choice) or for text that is no design. A design outside the box is
    used as given, not refused: the paper plans some (fig5a) and margins reach past the box;
    only a value the device cannot be built from (``PHYSICAL_BOUNDS``) is refused, by
    :class:`~feeders.design.DesignParameters`."""
    from feeders.design import DESIGN_SPACE, PARAMETER_NAMES, DesignError
    from feeders.scene_spec import design_of_text

    if text is None or "," not in text:
        return None
    try:
        design = design_of_text(text)
    except DesignError:
        return None
    outside = set(DESIGN_SPACE.outside(design))
    if not outside:
        return None
    values = design.to_vector()
    named = [
        f"{name} = {value:g} is outside Table 2's box [{low:g}, {high:g}]"
        for name, value, (low, high) in zip(
            PARAMETER_NAMES, values, DESIGN_SPACE.bounds, strict=True
        )
        if name in outside
    ]
    return f"{flag}: {', '.join(named)}; used as given"


def warn_outside_box(text: str | None, flag: str = "--design") -> None:
    """:func:`outside_box`'s line on stderr, as ``partfeeder: warning: ...``, if any."""
    line = outside_box(text, flag)
    if line is not None:
        print(f"partfeeder: warning: {line}", file=sys.stderr)


def orientations(scene: Scene, choice: str) -> list[str]:
    """``both`` (the feeder's two entries, or every start of a free-form scene) or one start."""
    return orientations_of(list(scene.starts), choice)


def orientations_of(starts: list[str], choice: str) -> list[str]:
    """:func:`orientations` from the names of the scene's starts."""
    from feeders.feeder import ORIENTATIONS

    if choice == "both":
        return [o for o in ORIENTATIONS if o in starts] or list(starts)
    if choice in starts:
        return [choice]
    raise UsageError(
        f"--orientation '{choice}' is not a start of this scene; "
        f"choose both or one of: {', '.join(starts)}"
    )


def design_starts(scene_file: Path | None) -> list[str] | None:
    """The starts of a ``--design``'s feeder (its two entries: known before it is built, which
    loads the compiled wall kernels), None for a ``--scene`` file (read it to know)."""
    from feeders.feeder import ORIENTATIONS

    return None if scene_file is not None else list(ORIENTATIONS)
