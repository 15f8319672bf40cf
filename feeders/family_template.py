"""A device family made for a part (issue 39: ``partfeeder family new NAME --part FILE``).

A family's entries are poses of the part's centre of mass, so a new part in a shipped family
means new entries worked out by hand (``fig1-cup.yaml`` writes the cup's 0.345 and 0.555).
The expression language names only a family's parameters, not its part, so the template
writes the numbers, computed from the part's mass properties
(:func:`feeders.part_properties.mass_properties`) and said where they came from.

The device is the paper's Fig. 1 device of the shipped ``fig1-cup`` family (its pieces, rules,
goal box and bounds, read from the shipped file), fitted to the part:

* **entries:** the part in the top of input chute A, centred across it, its upper end
  :data:`CAP_GAP` below the chute's cap (A is :data:`CHUTE_LENGTH` long from the lip): with
  its x axis up the chute (yaw ``theta``, ``x_axis_up_chute``) and down it (``theta - pi``);
* **chute widths** (A and exit chute C): the part's width across them (its y extent) plus
  :data:`PLAY`, as fig1-cup gives the cup 0.1-0.3;
* **orientation classes:** one per stable resting pose, ``on face k`` (k as ``partfeeder part``
  numbers them), each the hull face down within ``pi/4``; the goal accepts the class nearest
  yaw ``-pi/2`` (the x axis pointing down, as the cup's "open end up").

For the cup this gives fig1-cup's entries, widths and goal. Everything else is the cup's
device: the template is a start, checked to build at its defaults, not a design.
"""

from __future__ import annotations

import math
from typing import Any

import yaml

from feeders.device_family import FamilyError, family_from_dict, packaged_family
from feeders.fields import parse_document, read_yaml
from feeders.part_file import PartSource
from feeders.part_properties import MassProperties, mass_properties

TEMPLATE_DEVICE = "fig1-cup"  # the shipped family whose device the template writes
CHUTE_LENGTH = 4.0  # length of input chute A from the lip to its cap (fig1-cup.yaml)
CAP_GAP = 0.05  # the part's upper end below the cap at the start (fig1-cup.yaml)
PLAY = (0.1, 0.2, 0.3)  # chute width minus the part's width: low, default, high
CLASS_TOLERANCE = "pi/4"  # of each orientation class (as fig1-cup's)
ENTRY_UP, ENTRY_DOWN = "x_axis_up_chute", "x_axis_down_chute"
DECIMALS = 12  # of a written number: the properties' float noise (~1e-16) goes, no more


def _number(value: float) -> float:
    """``value`` to :data:`DECIMALS` decimals, ``-0`` as ``0``."""
    return round(float(value), DECIMALS) + 0.0


def _text(value: float) -> str:
    """``value`` as written in the file (``3.605``, ``4``, ``0``)."""
    return f"{_number(value):.15g}"


def _term(value: float) -> str:
    """`` + value`` or `` - |value|`` for an expression, empty when ``value`` is 0."""
    value = _number(value)
    if value == 0.0:
        return ""
    return f" + {_text(value)}" if value > 0 else f" - {_text(-value)}"


def _entry(along: float, across: float, yaw: str) -> list[str]:
    """The pose at ``along`` from the lip up chute A's floor and ``chute_width/2 + across``
    above it (A rises at ``theta`` from its lip at ``(exit_width/2, lip_height)``)."""
    a = _text(along)
    c = f"(chute_width/2{_term(across)})" if _term(across) else "chute_width/2"
    return [
        f"exit_width/2 + {a}*cos(theta) - {c}*sin(theta)",
        f"lip_height + {a}*sin(theta) + {c}*cos(theta)",
        yaw,
    ]


def template_entries(props: MassProperties) -> dict[str, list[str]]:
    """The two entries of chute A for a part of these mass properties (see the module).

    Yaw ``theta`` turns the body x axis up the chute and its y axis away from the floor, so
    the upper end is ``x_max`` beyond the centre of mass and the part spans ``y_min..y_max``
    across; yaw ``theta - pi`` turns both axes round (``-x_min`` and ``-y_max..-y_min``)."""
    x_min, x_max, y_min, y_max = props.extent
    top = CHUTE_LENGTH - CAP_GAP
    middle = 0.5 * (y_min + y_max)
    return {
        ENTRY_UP: _entry(top - x_max, -middle, "theta"),
        ENTRY_DOWN: _entry(top + x_min, middle, "theta - pi"),
    }


def class_name(number: int) -> str:
    """The orientation class of the part resting on its face ``number`` (from 1)."""
    return f"on face {number}"


def template_orientations(props: MassProperties) -> dict[str, dict[str, Any]]:
    """One class per stable resting pose: its face down (part frame, as ``partfeeder part``
    prints it), or its yaw for a disc's arc (a point has no face)."""
    out: dict[str, dict[str, Any]] = {}
    for k, pose in enumerate(props.resting):
        face = [[_number(v) for v in point] for point in pose.face]
        spec: dict[str, Any] = (
            {"yaw": _number(pose.yaw)} if face[0] == face[1] else {"face_down": face}
        )
        out[class_name(k + 1)] = {**spec, "tolerance": CLASS_TOLERANCE}
    return out


def goal_class(props: MassProperties) -> str:
    """The class nearest yaw ``-pi/2`` (the part's x axis down): the template's goal."""
    gaps = [abs(math.remainder(pose.yaw + 0.5 * math.pi, 2.0 * math.pi)) for pose in props.resting]
    return class_name(gaps.index(min(gaps)) + 1)


def _dump(data: dict[str, Any], flow: bool | None = None) -> str:
    """YAML of ``data``, its innermost lists and mappings on one line each (``flow=None``)
    or every item on a line of its own (``flow=False``), never folding a long expression."""
    return "".join(
        yaml.safe_dump(
            {key: value},
            sort_keys=False,
            default_flow_style=flow if isinstance(value, (dict, list)) else False,
            width=1 << 20,
        )
        for key, value in data.items()
    )


def family_template(name: str, source: PartSource) -> str:
    """The text of a family ``name`` for ``source``'s part (see the module), checked to load
    and build at its defaults: else :class:`FamilyError` with the reason (a part too large
    for the device, one with no stable resting pose)."""
    props = mass_properties(source.part)
    if not props.resting:
        raise FamilyError(
            f"part {source.name}: it has no stable resting pose on a floor (a disc rolls), so "
            "the template has no orientation class to give it; write orientations: by hand"
        )
    device = packaged_family(TEMPLATE_DEVICE)
    if device is None:  # the package is damaged: not the user's input
        raise RuntimeError(f"the shipped family {TEMPLATE_DEVICE} is missing")
    base = read_yaml(device, "device family", FamilyError)
    width = props.extent[3] - props.extent[2]
    parameters = dict(base["parameters"])
    for key in ("chute_width", "exit_width"):
        low, default, high = (_number(width + play) for play in PLAY)
        parameters[key] = {"low": low, "high": high, "default": default}
    goal = {k: v for k, v in base["goal"].items() if k not in ("yaw", "orientation")}
    goal["orientation"] = goal_class(props)
    x_min, x_max, y_min, y_max = (_text(v) for v in props.extent)
    com = ", ".join(_text(v) for v in props.com)
    part_name = " ".join(source.name.splitlines())  # a comment is one line
    top = CHUTE_LENGTH - CAP_GAP
    middle = 0.5 * (props.extent[2] + props.extent[3])
    faces = "; ".join(
        f"{k + 1}: yaw {math.degrees(p.yaw):.6g} deg" for k, p in enumerate(props.resting)
    )
    text = "\n".join(
        [
            f"# {name}: the part '{part_name}' in the paper's Fig. 1 device, written by",
            f"# `partfeeder family new {name} --part {part_name}` (docs/families.md).",
            f"# The device (pieces, rules, goal box, bounds) is the shipped {TEMPLATE_DEVICE}'s",
            "# (feeders/families/fig1-cup.yaml says what each piece is); the part's numbers are",
            f"# its mass properties (`partfeeder part {part_name}`): centre of mass ({com}) in",
            f"# the part's frame; about it, x from {x_min} to {x_max}, y from {y_min} to",
            f"# {y_max}. Poses are of the centre of mass, yaw turning the part's x axis.",
            _dump({"name": name, "part": source.spec}).rstrip(),
            f"# chute_width and exit_width: the part's width ({_text(width)}, its y extent)",
            f"# plus {PLAY[0]:g} to {PLAY[2]:g} of play.",
            _dump({"parameters": parameters, "pieces": base["pieces"]}).rstrip(),
            "# Start poses: the part in the top of chute A, its x axis up the chute (yaw theta)",
            "# or down it (theta - pi), its upper end "
            f"{CAP_GAP:g} below the cap ({CHUTE_LENGTH:g} up from the lip):",
            f"# {_text(top)} - {x_max} (x_max) or {_text(top)} - {_text(-props.extent[0])} "
            "(-x_min) up the chute; centred",
            f"# across it: its middle across is {_text(middle)} from the centre of mass (y).",
            _dump({"entries": template_entries(props)}, flow=False).rstrip(),
            "# One class per stable resting pose (the centre of mass above the face), numbered",
            f"# as `partfeeder part` numbers them ({faces}).",
            "# Rename them, merge them (a class may list several yaws), choose the goal's class.",
            _dump({"orientations": template_orientations(props)}).rstrip(),
            f"# The goal accepts '{goal['orientation']}': the class nearest yaw -pi/2 "
            "(the x axis down).",
            _dump({"goal": goal}).rstrip(),
            _dump({k: base[k] for k in ("rules", "bounds") if k in base}).rstrip(),
            "",
        ]
    )
    try:
        family_from_dict(parse_document(text, f"family {name}", FamilyError), name=name)
    except FamilyError as exc:
        raise FamilyError(
            f"part {source.name} in the {TEMPLATE_DEVICE} device: {exc}; the template's device "
            "is the cup's (for a part about 1.0 wide and 0.9 long): edit it for this part"
        ) from None
    return text
