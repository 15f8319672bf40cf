"""``partfeeder family new NAME --part FILE|NAME``: a device family made for a part (issue 39).

The family is the paper's Fig. 1 device of the shipped ``fig1-cup`` family with the part's
entries, chute widths and orientation classes written from its mass properties
(:func:`feeders.family_template.family_template`), checked to build at its defaults. Printed,
or written to ``--out`` (an existing file only with ``--force``: a family is edited by hand
after it is made).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from experiments.cli.usage import UsageError, out_dir

FAMILY_SUFFIXES = (".yaml", ".yml")


def add_arguments(family: argparse.ArgumentParser) -> None:
    actions = family.add_subparsers(dest="action", required=True, metavar="ACTION")
    new = actions.add_parser(
        "new",
        help="write a family for a part: the Fig. 1 device with the part's entries, chute "
        "widths and orientation classes (docs/families.md)",
    )
    new.add_argument("name", help="the family's name (its sweeps' folder and OMPL experiment)")
    new.add_argument(
        "--part",
        required=True,
        help="a part YAML file (docs/parts.md) or a shipped part (cup); `partfeeder part` "
        "shows what the family is written from",
    )
    new.add_argument(
        "--out", type=Path, default=None, help="the family file to write (default: print it)"
    )
    new.add_argument("--force", action="store_true", help="replace an existing --out file")


def _check_out(out: Path, force: bool, part: str) -> None:
    """``--out``: a .yaml name, not a directory, not the part file, new unless ``force``."""
    from feeders.fields import shown

    where = f"--out '{shown(out)}'"
    if out.suffix.lower() not in FAMILY_SUFFIXES:
        raise UsageError(f"{where}: a family file's name ends in .yaml or .yml")
    if out.is_dir():
        raise UsageError(f"{where} is a directory; give a file name")
    if out.exists() and Path(part).exists() and out.resolve() == Path(part).resolve():
        raise UsageError(f"{where} is the part file itself")
    if out.exists() and not force:
        raise UsageError(f"{where} exists; give --force to replace it")
    out_dir(out.parent)


def run(args: argparse.Namespace) -> int:
    from feeders.family_template import family_template
    from feeders.fields import name_field
    from feeders.part_file import part_source

    name = name_field(args.name, "NAME")
    text = family_template(name, part_source(args.part))
    if args.out is None:
        print(text, end="")
        return 0
    _check_out(args.out, args.force, args.part)
    args.out.write_text(text, encoding="utf-8")
    print(args.out)
    print(
        f"next: partfeeder draw --family {args.out} --out {args.out.stem}.png; a sweep config "
        f"with family: {args.out.name} (docs/families.md)",
        file=sys.stderr,
    )
    return 0
