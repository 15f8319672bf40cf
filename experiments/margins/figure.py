"""The margins chart a designer reads at a glance: one row per axis, its box (Table 2's for
the 12 design parameters, a device family's own box for its parameters, the stated range for
friction and the part) as a grey bar scaled to
the same width, the allowed interval in colour over it, the nominal as a black mark, the
interval's ends in units at the right. A row whose interval reaches an end of its box has that
end drawn square (the margin may go further: the search stops at the box)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from experiments.margins.robustness import in_words, robustness

INSIDE = "#2b8cbe"  # the allowed interval
NONE = "#d95f02"  # an axis with no margin (the nominal itself below the target)
BASELINE = "#fdae6b"  # the baseline's allowed interval, beside the design's
LABELS = {
    "a": "a  input chute width",
    "b": "b  exit chute width",
    "c": "c  chamfer depth",
    "d": "d  input chute length",
    "e": "e  left cavity wall x",
    "fx": "fx  protuberance tip x",
    "fy": "fy  protuberance tip y",
    "gx": "gx  lip x",
    "gy": "gy  lip y",
    "r": "r  protuberance radius",
    "theta": "θ  input chute angle",
    "alpha": "α  chamfer angle",
    "mu": "μ  wall friction",
    "length": "part length",
    "width": "part width",
    "heavy_fraction": "heavy half's mass share",
}


def _num(value: float) -> str:
    return f"{value:.3g}"


def _smallest(data: dict) -> str:
    """A design's robustness in a few words (:mod:`experiments.margins.robustness`)."""
    return f"{data['design']} {in_words(robustness(data), bool(data.get('stopped')))}"


def _bar(ax, row: dict, y: float, height: float, color: str, end_color: str) -> str:
    """One design's allowed interval on an axis's row (box fractions), its ends found inside
    the box marked, its nominal a diamond; returns the interval's text."""
    lo, hi = row["box"]
    span = hi - lo or 1.0
    nominal = (row["nominal"] - lo) / span
    unit = "" if row["unit"] in ("-", "share") else f" {row['unit']}"
    if row["interval"] is None:
        ax.text(0.5, y, "no margin: below target at nominal", ha="center", va="center",
                color=NONE, fontsize=8)  # fmt: skip
        note = "none"
    else:
        a, b = ((v - lo) / span for v in row["interval"])
        ax.barh(y, max(b - a, 0.004), left=a, height=height, color=color)
        note = f"[{_num(row['interval'][0])}, {_num(row['interval'][1])}]{unit}"
        for side, x in (("low", a), ("high", b)):
            if not row[side]["at_box_edge"]:
                ax.plot([x, x], [y - 0.58 * height, y + 0.58 * height], color=end_color, lw=1.6)
    ax.plot([nominal], [y], marker="D", color="black", markersize=4.5, zorder=3)
    return note


def margins_chart(data: dict, path: Path, baseline: dict | None = None) -> Path:
    """Draw the margins of :meth:`experiments.margins.run.MarginsReport.to_dict` into
    ``path`` (PNG, 900 px wide); with ``baseline`` (another design's margins), each axis
    shows both designs' intervals, the design's above the baseline's."""
    rows = data["margins"]
    n = len(rows)
    theirs = {r["parameter"]: r for r in (baseline or {}).get("margins") or []}
    per_row = 0.62 if baseline else 0.42
    fig, ax = plt.subplots(figsize=(9.0, per_row * n + 2.1), dpi=100)
    for i, row in enumerate(rows):
        y = n - 1 - i
        lo, hi = row["box"]
        ax.barh(y, 1.0, left=0.0, height=0.8, color="#e6e6e6", edgecolor="#bdbdbd")
        if baseline is None:
            note = _bar(ax, row, y, 0.62, INSIDE, "#08306b")
            ax.text(1.03, y, note, va="center", fontsize=9)
        else:
            note = _bar(ax, row, y + 0.19, 0.34, INSIDE, "#08306b")
            ax.text(1.03, y + 0.19, note, va="center", fontsize=8.5, color="#08306b")
            other = theirs.get(row["parameter"])
            if other is not None:
                note = _bar(ax, other, y - 0.19, 0.34, BASELINE, "#7f2704")
                ax.text(1.03, y - 0.19, note, va="center", fontsize=8.5, color="#7f2704")
        ax.text(1.36, y, f"[{_num(lo)}, {_num(hi)}]", va="center", fontsize=9, color="#636363")
    design_rows = sum(1 for r in rows if r["kind"] == "design")
    if 0 < design_rows < n:
        ax.axhline(n - design_rows - 0.5, color="#636363", lw=0.8, ls="--")
    ax.set_yticks(range(n))
    labels = {} if data.get("family") else LABELS  # a family's names are its own
    ax.set_yticklabels([labels.get(r["parameter"], r["parameter"]) for r in reversed(rows)],
                       fontsize=10)  # fmt: skip
    ax.text(1.03, n - 0.45, "allowed", fontsize=9, fontweight="bold", va="bottom")
    ax.text(1.36, n - 0.45, "box", fontsize=9, fontweight="bold", va="bottom", color="#636363")
    ax.set_xlim(-0.02, 1.6)
    ax.set_ylim(-0.6, n + 0.1)
    ax.set_xticks([0.0, 0.25, 0.5, 0.75, 1.0])
    ax.spines["bottom"].set_bounds(0.0, 1.0)
    ax.set_xticklabels(["low end", "1/4", "1/2", "3/4", "high end"], fontsize=9)
    family = data.get("family")
    boxes = (
        f"{family['name']}'s box for its parameters, a stated range for μ"
        if family
        else "Table 2's range for a ... α, a stated range for μ and the part"
    )
    colours = (
        f"blue: {data['design']}'s allowed interval, orange: {baseline['design']}'s"
        if baseline
        else "blue: allowed interval"
    )
    ax.set_xlabel(
        f"position in the box (grey bar): {boxes}\n{colours};  ◆ nominal\n"
        "| an end found inside the box (a full bar reaches the box's edges)",
        fontsize=9,
    )
    classes = (data.get("verdict") or {}).get("success_classes") or ["heavy end down"]
    success = " or ".join(classes)
    smallest = f"\nsmallest margin: {_smallest(data)}, {_smallest(baseline)}" if baseline else ""
    ax.set_title(
        f"{data['design']}{' beside ' + baseline['design'] if baseline else ''}: tolerance "
        "margins, one parameter at a time (others nominal)\n"
        f"where P(both entries {success}) ≥ {data['target']:g} over "
        f"{data['drops_per_value']} perturbed drops per entry{smallest}",
        fontsize=11,
    )
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return path
