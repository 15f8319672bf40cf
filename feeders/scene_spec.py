"""The scene a user means by a design specification, whichever way it is given.

A specification is one of:

- a paper preset's name (``"table3"``, ``"fig7a"``, ...: :data:`feeders.design.PRESETS`);
- the 12 design values ``a, b, c, d, e, fx, fy, gx, gy, r, theta, alpha``, as a sequence of
  numbers or as text separated by commas (``"1.1,1.1086,..."``, as ``--design`` takes them);
- a :class:`~feeders.design.DesignParameters`;
- a :class:`~feeders.scene.Scene` (returned as it is, once checked);
- a path to a scene YAML file (:mod:`feeders.scene_yaml`), as a :class:`~pathlib.Path` or as
  text that names a file (``"my_scene.yaml"``).

A design becomes the parametric feeder of :func:`feeders.feeder.build_feeder` with its default
part, friction, restitution, gravity and input set; a scene file may set those itself.
Every scene returned is physically sane (:func:`feeders.scene_yaml.checked_scene`: the same
checks as a scene file), so the command line (``--design``, ``--scene``) and the Python API
(``planners.problem``) accept and refuse the same things with the same words. Pure data: no
OMPL, no numba.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TypeAlias

import numpy as np

from feeders.design import PARAMETER_NAMES, PRESETS, DesignError, DesignParameters, preset
from feeders.feeder import DegenerateDesign, build_feeder
from feeders.fields import shown
from feeders.scene import Scene
from feeders.scene_yaml import SceneError, checked_scene, load_scene

# What :func:`scene_of` accepts (see the module docstring).
DesignSpec: TypeAlias = str | Path | Sequence[float] | np.ndarray | DesignParameters | Scene

CUSTOM_DESIGN = "custom design"  # the name of a scene built from 12 given values


def design_of_text(text: str) -> DesignParameters:
    """The design named by ``text``: a preset's name or 12 values separated by commas;
    :class:`~feeders.design.DesignError` naming what is wrong (an unknown preset lists them)."""
    spec = text.strip()
    if not spec:
        raise DesignError(
            f"design is empty; give a preset ({', '.join(sorted(PRESETS))}) or "
            f"{len(PARAMETER_NAMES)} comma-separated values"
        )
    if "," not in spec:
        return preset(spec)
    try:
        values = [float(v) for v in spec.split(",")]
    except ValueError:
        raise DesignError(
            f"design '{shown(spec)}' is not {len(PARAMETER_NAMES)} comma-separated numbers"
        ) from None
    return DesignParameters.from_vector(values)


def _looks_like_path(text: str) -> bool:
    """A file name rather than a preset: a directory part or a YAML suffix."""
    return "/" in text or "\\" in text or text.lower().endswith((".yaml", ".yml"))


def _feeder(design: DesignParameters, name: str) -> Scene:
    try:
        return build_feeder(design, name=name)
    except DegenerateDesign as exc:
        raise SceneError(f"degenerate design: {exc}") from None


def design_scene(text: str) -> Scene:
    """The checked feeder of a design given as text, a preset's name or 12 comma-separated
    values (never a file: what ``--design`` takes), named after the preset or
    ``"custom design"``."""
    design = design_of_text(text)
    name = text.strip() if text.strip() in PRESETS else CUSTOM_DESIGN
    return checked_scene(_feeder(design, name))


def scene_of(spec: DesignSpec) -> Scene:
    """The checked scene of ``spec`` (see the module docstring).

    Text is a file when it names one that exists or looks like a path (a ``/`` or a ``.yaml``
    suffix), otherwise a preset or 12 comma-separated values. A preset's scene is named after
    it, a file's after its stem (or its ``name`` field), 12 values' ``"custom design"``.
    Raises :class:`~feeders.design.DesignError` (a design value or preset) or
    :class:`~feeders.scene_yaml.SceneError` (a file, a degenerate design, a scene that is not
    physically sane), both ValueErrors whose one-line message names the field and its range.
    """
    if isinstance(spec, Scene):
        return checked_scene(spec)
    if isinstance(spec, DesignParameters):
        return checked_scene(_feeder(spec, CUSTOM_DESIGN))
    if isinstance(spec, Path):
        return load_scene(spec)
    if isinstance(spec, str):
        text = spec.strip()
        if text and "," not in text and (_looks_like_path(text) or Path(text).is_file()):
            return load_scene(Path(text))
        return design_scene(text)
    if isinstance(spec, (Sequence, np.ndarray)):
        try:
            values = [float(v) for v in np.asarray(spec, dtype=object).ravel()]
        except (TypeError, ValueError):
            raise DesignError(
                f"a design's values must be {len(PARAMETER_NAMES)} numbers "
                f"({', '.join(PARAMETER_NAMES)})"
            ) from None
        return checked_scene(_feeder(DesignParameters.from_vector(values), CUSTOM_DESIGN))
    raise TypeError(
        "a design is a preset name, 12 values, DesignParameters, a Scene or a scene file's "
        f"path; got {type(spec).__name__}"
    )
