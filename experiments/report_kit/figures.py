"""What every report's figures share: a panel that says why it is empty, and tick labels a
reader can read (plain numbers, not ``4.04842 x 10^-1``).

The figures are matplotlib (Agg) PNGs shown in a page at most 1200 px wide, so they are drawn
at most about 10 inches wide at 100 dpi with type of 9 pt or more.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter

PLAIN_TICKS = FuncFormatter(lambda value, _: f"{value:.3g}")


def empty_plot(message: str, size: tuple[float, float] = (6.0, 2.5)) -> Figure:
    """A figure that says why there is nothing to draw (the page keeps its layout)."""
    fig, ax = plt.subplots(figsize=size)
    ax.text(0.5, 0.5, message, ha="center", va="center", fontsize=11, color="#555555")
    ax.axis("off")
    return fig
