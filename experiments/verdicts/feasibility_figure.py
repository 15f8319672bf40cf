"""Where two levels agree in design space, and how often each says feasible: the picture of
:func:`experiments.verdicts.feasibility.compare_levels`'s rows (PNG, matplotlib)."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import matplotlib.pyplot as plt

from experiments.pictures.scenes import save_figure
from experiments.verdicts.feasibility import AGREEMENT_CLASSES, agreement, classify, paired_rows
from feeders.design import PARAMETER_NAMES


def feasibility_figure(
    rows: Iterable[dict],
    a: str,
    b: str,
    path: str | Path,
    x: str = "theta",
    y: str = "d",
) -> Path:
    """Where the two levels agree in the design space, and how often each says feasible.

    Left: each design at (``x``, ``y``), two of ``PARAMETER_NAMES`` (default the input chute's
    angle theta in rad and length d), coloured by its cell of the 2x2 table; designs feasible
    at ``a`` but not ``b`` (exceptions to the subset) are drawn large and labelled with their
    index; degenerate designs are crosses. Right: the fraction feasible at each level with its
    Wilson 95% interval. Saved as PNG at ``path``; returns the path.
    """
    for name in (x, y):
        if name not in PARAMETER_NAMES:
            raise ValueError(f"unknown design parameter '{name}'; known: {PARAMETER_NAMES}")
    ix, iy = PARAMETER_NAMES.index(x), PARAMETER_NAMES.index(y)
    pairs, _ = paired_rows(list(rows), a, b)
    summary = agreement([r for pair in pairs for r in pair], a, b)
    label_b = f"{b} (run 2)" if a == b else b
    style = {
        "both": ("#2ca02c", "feasible at both"),
        "a_only": ("#d62728", f"{a} only (exception)"),
        "b_only": ("#1f77b4", f"{label_b} only"),
        "neither": ("#7f7f7f", "neither"),
    }
    fig, (ax, bar) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [3, 1.3]})
    cells = [classify(bool(ra["feasible"]), bool(rb["feasible"])) for ra, rb in pairs]
    for cell in AGREEMENT_CLASSES:
        colour, label = style[cell]
        chosen = [ra for (ra, _), c in zip(pairs, cells, strict=True) if c == cell]
        for built, marker in ((True, "o"), (False, "x")):
            pts = [ra["values"] for ra in chosen if bool(ra["built"]) == built]
            if not pts:
                continue
            # an edge for filled markers only (crosses have none); exceptions stand out
            edge = {"edgecolors": "k" if cell == "a_only" else "none"} if built else {}
            ax.scatter(
                [p[ix] for p in pts],
                [p[iy] for p in pts],
                c=colour,
                marker=marker,
                s=60 if cell == "a_only" else 22,
                linewidths=0.6,
                label=f"{label} ({len(pts)})" if built else f"{label}, not built ({len(pts)})",
                zorder=4 if cell == "a_only" else 3,
                **edge,
            )
    for e in summary["exceptions"]:
        ax.annotate(
            str(e["index"]),
            (e["values"][ix], e["values"][iy]),
            fontsize=7,
            xytext=(3, 3),
            textcoords="offset points",
        )
    angles = ("theta", "alpha")  # the other parameters are lengths (part length 2)
    ax.set_xlabel(f"{x} (rad)" if x in angles else x)
    ax.set_ylabel(f"{y} (rad)" if y in angles else y)
    ax.set_title(
        f"{summary['designs']} Halton designs: {a} vs {label_b} "
        f"({summary['counts']['a_only']} exceptions)",
        fontsize=10,
    )
    ax.legend(fontsize=7, loc="best")

    names = [a, label_b]
    fractions = [summary["fraction_a"], summary["fraction_b"]]
    heights = [f["fraction"] or 0.0 for f in fractions]
    errors = [
        [h - f["ci95"][0] for h, f in zip(heights, fractions, strict=True)],
        [f["ci95"][1] - h for h, f in zip(heights, fractions, strict=True)],
    ]
    bar.bar(names, heights, yerr=errors, capsize=6, color=["#9467bd", "#8c564b"])
    for k, (h, f) in enumerate(zip(heights, fractions, strict=True)):
        bar.text(k, h / 2, f"{f['feasible']}/{f['designs']}", ha="center", fontsize=8, color="w")
    bar.set_ylim(0, 1)
    bar.set_ylabel("fraction feasible (Wilson 95% CI)")
    bar.set_title("feasible fraction", fontsize=10)
    return save_figure(fig, path)
