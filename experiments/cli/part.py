"""``partfeeder part FILE|NAME``: a part's mass, centre of mass, inertia, area and the stable
poses it rests in on a floor (issue 39), what a device family's entries and orientation
classes are written from; ``--out`` draws them, ``--family`` adds a family's classes.

The numbers are :mod:`feeders.composite_part`'s closed forms and stable-pose test, through
:func:`feeders.part_properties.mass_properties`; a part is a shipped name or a YAML file
(:func:`feeders.part_file.part_source`).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from experiments.cli.usage import UsageError, out_file

if TYPE_CHECKING:
    from feeders.part_properties import MassProperties
    from feeders.scene import OrientationClass

SHIPPED_NAMES = ("peg", "cup")  # feeders.part_file.SHIPPED_PARTS, named in --help


def add_arguments(part: argparse.ArgumentParser) -> None:
    part.add_argument(
        "part",
        help=f"a part YAML file (part: as in a device family, or outline/pieces and density; "
        f"docs/parts.md), or a part shipped with partfeeder: {', '.join(SHIPPED_NAMES)}",
    )
    part.add_argument(
        "--family",
        type=Path,
        default=None,
        help="a device family (file, or shipped by name: fig1-cup): name each stable pose by "
        "the family's orientation classes and draw the classes on the part",
    )
    part.add_argument("--json", action="store_true", help="print the same as JSON")
    part.add_argument(
        "--out", type=Path, default=None, help="picture file to write (.png, .pdf or .svg)"
    )


def _classes(family_file: Path | None) -> tuple[OrientationClass, ...]:
    if family_file is None:
        return ()
    from experiments.cli.scenes import family_path
    from feeders.device_family import FamilyError, load_family

    try:
        return load_family(family_path(family_file)).orientations
    except FamilyError as exc:
        raise UsageError(str(exc)) from None


def _report(props: MassProperties, classes: tuple[OrientationClass, ...]) -> dict[str, Any]:
    from feeders.scene import orientation_of

    out = props.as_dict()
    if classes:
        for pose in out["stable_poses"]:
            pose["orientation"] = orientation_of(classes, pose["yaw"])
        out["orientations"] = [
            {"name": c.name, "centres": list(c.centres), "tolerance": c.tolerance} for c in classes
        ]
    return out


def _text(name: str, report: dict[str, Any]) -> str:
    e = report["extent"]
    size = max(e["x_max"] - e["x_min"], e["y_max"] - e["y_min"])
    x, y = (0.0 if abs(v) < 1e-12 * size else v for v in report["centre_of_mass"])  # 1e-17
    lines = [
        f"part {name}",
        f"  mass                {report['mass']:.6g}",
        f"  area                {report['area']:.6g}",
        f"  centre of mass      ({x:.6g}, {y:.6g}) in the part's frame",
        f"  inertia             {report['inertia']:.6g} about the centre of mass (mass x length^2)",
        f"  extent about it     x {e['x_min']:.6g} to {e['x_max']:.6g}, "
        f"y {e['y_min']:.6g} to {e['y_max']:.6g}",
        f"  stable poses        {len(report['stable_poses'])} on a floor (gravity -y): the centre "
        "of mass above a face of the convex hull",
    ]
    for pose in report["stable_poses"]:
        (ax, ay), (bx, by) = pose["face"]
        where = "" if pose["on_outline"] else " (a hull edge across a hollow)"
        named = f"  [{pose['orientation']}]" if "orientation" in pose else ""
        lines.append(
            f"    {pose['face_number']}  yaw {pose['yaw_degrees']:7.4g} deg "
            f"({pose['yaw']:+.4f} rad)  face ({ax:.4g}, {ay:.4g}) to ({bx:.4g}, {by:.4g})"
            f"{where}{named}"
        )
    for c in report.get("orientations", []):
        centres = ", ".join(f"{math.degrees(v):.4g}" for v in c["centres"])
        lines.append(
            f"  class {c['name']!r}: yaw {centres} deg +- {math.degrees(c['tolerance']):.4g}"
        )
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    """The part and ``--family`` are read, and ``--out`` checked, before matplotlib loads."""
    from feeders.part_file import part_source
    from feeders.part_properties import mass_properties

    source = part_source(args.part)
    classes = _classes(args.family)
    inputs = [Path(args.part)] + ([] if args.family is None else [args.family])
    out = None if args.out is None else out_file(args.out, inputs=inputs)
    props = mass_properties(source.part)
    report = _report(props, classes)
    if args.json:
        print(json.dumps({"part": source.name, **report}, indent=2))
    else:
        print(_text(source.name, report))
    if out is not None:
        from experiments.pictures.part_sheet import part_sheet

        written = part_sheet(source.part, props, f"part {source.name}", out, classes)
        if args.json:
            import sys

            print(f"wrote {written}", file=sys.stderr)
        else:
            print(f"picture: {written}")
    return 0
