"""The comparison's figures, one row per level: the solved fraction of runs with its Wilson
interval, the ECDF of propagations to solve (log axis) and the performance profiles (log2
tau), from the report's data (:mod:`.summary`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from experiments.report_kit.figures import PLAIN_TICKS, empty_plot, plt

COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2")
COUNT_TICKS = FuncFormatter(lambda value, _: f"{value:,.0f}")  # 5,000 not 5e+03
STYLES = ("-", "--", "-.", ":", (0, (5, 1)), (0, (3, 1, 1, 1)), (0, (1, 1)))


def level_figure(level: str, data: dict[str, Any], labels: list[str], path: Path) -> Path:
    """The three panels of ``level`` (its entry of the report's ``levels``) as a PNG."""
    if not data["counted"]:
        fig = empty_plot(f"{level}: no problem counted (all known unsolvable or not planned)")
        fig.savefig(path, dpi=100)
        plt.close(fig)
        return path
    fig, (bars, ecdf, prof) = plt.subplots(1, 3, figsize=(12.0, 3.8))
    for j, label in enumerate(labels):
        p = data["planners"][label]
        colour = COLOURS[j % len(COLOURS)]
        lo, hi = p["wilson95"]
        frac = p["fraction"] or 0.0
        bars.barh(j, frac, color=colour, alpha=0.75)
        bars.errorbar(frac, j, xerr=[[frac - lo], [hi - frac]], color="k", capsize=3, lw=1)
        bars.text(1.02, j, f"{p['solved_runs']}/{p['runs']}", va="center", fontsize=9)
        curve = data["ecdf"][label]
        if curve["x"]:
            xs = [curve["x"][0], *curve["x"]]
            ys = [0.0, *curve["y"]]
            ecdf.step(xs, ys, where="post", color=colour, ls=STYLES[j % len(STYLES)], label=label)
        if data["profile"] is not None:
            taus = data["profile"]["taus"]
            prof.step(
                taus,
                data["profile"]["rho"][label],
                where="post",
                color=colour,
                ls=STYLES[j % len(STYLES)],
                label=label,
            )
    bars.set_yticks(range(len(labels)), labels)
    bars.invert_yaxis()
    bars.set_xlim(0, 1.18)
    bars.set_xlabel("runs solved (95% Wilson)")
    bars.set_title(f"{level}: solved fraction", fontsize=10)
    ecdf.set_xscale("log")
    ecdf.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ecdf.xaxis.set_major_formatter(COUNT_TICKS)
    ecdf.xaxis.set_minor_formatter(NullFormatter())  # 3x10^3, 4x10^3 ... would overlap
    ecdf.set_ylim(0, 1.02)
    ecdf.set_xlabel("propagations to solve (log)")
    ecdf.set_ylabel("fraction of runs solved")
    ecdf.set_title(f"{level}: ECDF of propagations", fontsize=10)
    ecdf.grid(alpha=0.3)
    if data["profile"] is not None:
        prof.set_xscale("log", base=2)
        prof.xaxis.set_major_formatter(PLAIN_TICKS)
        prof.set_ylim(0, 1.02)
        prof.set_xlabel("tau: within this factor of the best (log2)")
        prof.set_ylabel("fraction of problems")
        n = len(data["profile"]["problems"])
        prof.set_title(f"{level}: profile, {n} problems", fontsize=10)
        prof.grid(alpha=0.3)
        prof.legend(fontsize=8, loc="lower right")
    else:
        prof.text(0.5, 0.5, "no problem solved\nby any planner", ha="center", va="center")
        prof.axis("off")
    if any(data["ecdf"][label]["x"] for label in labels):
        ecdf.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def figures(report: dict[str, Any], directory: Path) -> dict[str, Path]:
    """Every level's figure in ``directory`` (made), by name ``LEVEL``."""
    directory.mkdir(parents=True, exist_ok=True)
    labels = [p["label"] for p in report["planners"]]
    return {
        level: level_figure(level, data, labels, directory / f"{level}.png")
        for level, data in report["levels"].items()
    }
