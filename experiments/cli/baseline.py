"""``--baseline``: the design a report compares its recommendation with (the paper's table3
unless given), named as ``--design`` names one: a preset or 12 comma-separated values. Checked
when the command starts, so a bad value is one line before any work is done."""

from __future__ import annotations

import argparse

from experiments.cli.usage import UsageError

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
    return label, [float(v) for v in design.to_vector()]
