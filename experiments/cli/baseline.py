"""``--baseline``: the design a report compares its recommendation with, named as ``--design``
names one: the paper's feeder's a preset or 12 comma-separated values (table3 unless given);
a device family's ``default`` (its default design, also when not given) or its values in its
parameters' order. Checked when the command starts, so a bad value is one line before any
work is done: its form at once, against what is designed (the feeder or a family) as soon as
the config or the sweep's database says which."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING

from experiments.cli.usage import UsageError

if TYPE_CHECKING:
    from feeders.device_family import DeviceFamily

DEFAULT_BASELINE = "table3"


def add_baseline_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--baseline",
        default=None,
        metavar="DESIGN",
        help="the design the report compares the recommendation with, on the same fresh "
        "draws: a preset (table3, fig7a, ...) or 12 comma-separated values "
        f"(default {DEFAULT_BASELINE}; with a device family: 'default', its default design, "
        "or its values)",
    )


def baseline_of(text: str | None) -> tuple[str, list[float]]:
    """``(label, 12 values)`` of a ``--baseline`` value (None: not given, table3): a preset
    keeps its name, 12 values are labelled ``baseline``; :class:`UsageError` naming the option
    and what is allowed."""
    from feeders.design import DesignError
    from feeders.scene_spec import design_of_text

    text = DEFAULT_BASELINE if text is None else text
    try:
        design = design_of_text(text)
    except DesignError as exc:
        raise UsageError(f"--baseline: {exc}") from None
    label = text.strip() if "," not in text else "baseline"
    from experiments.cli.scenes import warn_outside_box

    warn_outside_box(text, "--baseline")
    return label, [float(v) for v in design.to_vector()]


def family_baseline_of(text: str | None, family: DeviceFamily) -> tuple[str, list[float]]:
    """``(label, values)`` of a ``--baseline`` value for a device family: its default design
    (``default``, or None: not given) labelled ``default``, or one number per parameter in
    the family's order labelled ``baseline``; :class:`UsageError` naming the option and what
    is allowed, or why those values cannot be built."""
    from experiments.family_config import FAMILY_DEFAULT, family_default
    from feeders.feeder import DegenerateDesign
    from feeders.fields import shown

    if text in (None, FAMILY_DEFAULT):
        return family_default(family)
    names = family.vector_names
    values = _numbers(str(text), finite=False)
    if values is not None and len(values) == len(names):
        for name, value in zip(names, values, strict=True):
            if not math.isfinite(value):
                raise UsageError(
                    f"--baseline: {name} = {value} is not a finite number; every value must "
                    "be finite"
                )
    if values is None or len(values) != len(names):
        raise UsageError(
            f"--baseline = '{shown(str(text))}'; allowed with family {family.name}: "
            f"{FAMILY_DEFAULT}, or "
            f"{len(names)} comma-separated numbers ({', '.join(names)})"
        )
    try:
        family.build(values)
    except DegenerateDesign as exc:
        raise UsageError(
            f"--baseline = '{shown(str(text))}' cannot be built: {exc.reason}"
        ) from None
    return "baseline", values


def baseline_for(text: str | None, family: DeviceFamily | None) -> tuple[str, list[float]]:
    """``--baseline`` for what is designed: the paper's feeder (``family`` None,
    :func:`baseline_of`) or a device family (:func:`family_baseline_of`)."""
    return baseline_of(text) if family is None else family_baseline_of(text, family)


def check_baseline_form(text: str | None) -> None:
    """Refuse at once a ``--baseline`` that no design could be: anything but a preset,
    ``default`` or comma-separated finite numbers (how many, and whether ``default`` or a
    preset is allowed, is checked by :func:`baseline_for` once the family is known)."""
    from experiments.family_config import FAMILY_DEFAULT

    if text in (None, FAMILY_DEFAULT) or ("," in str(text) and _numbers(str(text))):
        return
    numbers = _numbers(str(text), finite=False) if "," in str(text) else None
    for k, value in enumerate(numbers or [], start=1):
        if not math.isfinite(value):  # said so, not as a wrong count of values (issue 37)
            raise UsageError(
                f"--baseline: value {k} = {value} is not a finite number; every value must "
                "be finite"
            )
    baseline_of(text)


def _numbers(text: str, finite: bool = True) -> list[float] | None:
    """The comma-separated (finite, unless not ``finite``) numbers of ``text``, or None when
    it is not such a list."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        return None
    return values if not finite or all(math.isfinite(v) for v in values) else None
