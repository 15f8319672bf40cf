"""The benchmark's pictures (matplotlib, Agg), drawn from the data dictionary alone.

* ``perf-work-precision.png``: per analytic case (and measure of the flat drop), error against
  wall time per simulated second, log-log, one curve per engine setting, marker shape by h;
  an error of exactly 0 is drawn at :data:`ZERO_FLOOR` with an open marker;
* ``perf-feeder.png``: the feeder's success fraction (Wilson 95%) against h with the
  reference's, the KS distance of T's distribution against work with its noise floor, and the
  paired exit-time difference of single drops, which does not converge (chaos);
* ``perf-ladder.png``: each level's cost per design against the disagreement of its verdict
  with the top verdict, and its precision and recall, with Wilson intervals;
* ``perf-speed.png``: microseconds per LCP solve by size, and per step of every engine at
  h = 1e-3 on each analytic case.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

ZERO_FLOOR = 1e-16
COLOURS = {
    "partfeeder (default)": "tab:blue",
    "mujoco (default)": "tab:red",
    "mujoco (accurate)": "tab:orange",
    "pymunk (default)": "tab:green",
    "pymunk (accurate)": "tab:olive",
}
MARKERS = ("o", "s", "^", "D", "v", "P", "X")
MEASURE_TITLES = {
    "error": "error (length)",
    "time_to_rest": "|T_rest - t*| (s)",
    "penetration": "deepest penetration (length)",
    "energy": "|E(T) - E_rest|",
}


def _marker(h_values: list[float], h: float) -> str:
    index = min(range(len(h_values)), key=lambda i: abs(h_values[i] - h))
    return MARKERS[index % len(MARKERS)]


def work_precision_figure(wp: dict, path: Path) -> Path:
    panels = []
    for name, data in wp["cases"].items():
        measures = data["measures"] if name == "drop" else data["measures"][:1]
        panels += [(name, data, m) for m in measures]
    cols = 4
    rows = -(-(len(panels) + 1) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.6 * rows), squeeze=False)
    h_values = wp["h"]
    for ax, (name, data, measure) in zip(axes.flat, panels, strict=False):
        for engine in COLOURS:
            pts = sorted(
                (p for p in data["points"] if p["engine"] == engine), key=lambda p: -p["h"]
            )
            if not pts:
                continue
            xs = [p["wall_per_sim_s"] for p in pts]
            ys = [max(p["errors"][measure], ZERO_FLOOR) for p in pts]
            ax.plot(xs, ys, "-", color=COLOURS[engine], lw=1, alpha=0.7)
            for p, x, y in zip(pts, xs, ys, strict=True):
                zero = p["errors"][measure] <= 0.0
                ax.plot(
                    x,
                    y,
                    _marker(h_values, p["h"]),
                    color=COLOURS[engine],
                    mfc="none" if zero else COLOURS[engine],
                    ms=6,
                )
                if engine.startswith("partfeeder"):
                    ax.annotate(
                        f"{p['h']:.0e}",
                        (x, y),
                        fontsize=6,
                        xytext=(3, 3),
                        textcoords="offset points",
                    )
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{data['title']}" + ("" if name != "drop" else f": {measure}"), fontsize=9)
        ax.set_xlabel("wall time per simulated second (s)", fontsize=8)
        ax.set_ylabel(MEASURE_TITLES[measure], fontsize=8)
        ax.grid(True, which="both", alpha=0.2)
        ax.tick_params(labelsize=7)
    legend_ax = axes.flat[len(panels)]
    legend_ax.axis("off")
    handles = [
        plt.Line2D(
            [], [], color=c, lw=2, label=e + ("" if _available(wp, e) else ": not installed")
        )
        for e, c in COLOURS.items()
    ]
    handles += [
        plt.Line2D([], [], color="k", ls="none", marker=_marker(h_values, h), label=f"h = {h:g}")
        for h in h_values
    ]
    legend_ax.legend(handles=handles, loc="center", fontsize=8, frameon=False)
    legend_ax.text(
        0.5,
        0.02,
        f"open marker: error exactly 0 (drawn at {ZERO_FLOOR:g})",
        ha="center",
        fontsize=7,
        transform=legend_ax.transAxes,
    )
    for ax in list(axes.flat)[len(panels) + 1 :]:
        ax.axis("off")
    fig.suptitle("Work-precision: error against the closed form vs wall time (medians, one run)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _available(wp: dict, label: str) -> bool:
    return any(e["label"] == label and e["available"] for e in wp["engines"])


def feeder_figure(fc: dict, path: Path) -> Path:
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for k, (name, data) in enumerate(fc["designs"].items()):
        colour = f"C{k}"
        rows = sorted(data["by_h"], key=lambda r: r["h"])
        hs = [r["h"] for r in rows]
        ps = [r["p"] for r in rows]
        lows = [max(0.0, r["p"] - r["interval"][0]) for r in rows]
        highs = [max(0.0, r["interval"][1] - r["p"]) for r in rows]
        axes[0].errorbar(hs, ps, yerr=[lows, highs], fmt="o-", color=colour, capsize=3, label=name)
        ref = data["reference"]
        axes[0].axhline(ref["p"], color=colour, ls="--", lw=0.8)
        xs = [r["wall_per_sim_s"] for r in rows]
        axes[1].plot(xs, [r["ks"] for r in rows], "o-", color=colour, label=name)
        for r, x in zip(rows, xs, strict=True):
            axes[1].annotate(
                f"{r['h']:.0e}", (x, r["ks"]), fontsize=6, xytext=(3, 3), textcoords="offset points"
            )
        axes[2].plot(
            hs, [max(r["paired_T_error"], ZERO_FLOOR) for r in rows], "o-", color=colour, label=name
        )
    first = next(iter(fc["designs"].values()))["by_h"][0]
    axes[1].axhline(first["ks_critical"], color="k", ls=":", lw=1, label="95% KS noise floor")
    axes[0].set_xscale("log")
    axes[0].set_xlabel("h (s)")
    axes[0].set_ylabel("success fraction (Wilson 95%); dashed: reference")
    axes[0].set_title(f"success fraction, {2 * fc['drops_per_orientation']} drops per point")
    axes[1].set_xscale("log")
    axes[1].set_xlabel("wall time per simulated second (s)")
    axes[1].set_ylabel("KS distance of T to the reference's")
    axes[1].set_title("T's distribution: KS distance to the reference's")
    axes[1].set_ylim(bottom=0.0)
    axes[2].set_xscale("log")
    axes[2].set_yscale("log")
    axes[2].set_xlabel("h (s)")
    axes[2].set_ylabel("median |T(h) - T(ref)|, same drop (s)")
    axes[2].set_title("a single drop does not converge (chaos)")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.2)
        ax.legend(fontsize=7)
    fig.suptitle(
        "Feeder drops: a single drop's exit does not converge with h (contact through the feeder"
        " is chaotic), so what is measured is what does: the success fraction and T's "
        f"distribution, against h_ref = {fc['h_reference']:.3g}",
        fontsize=9,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _bars(rate: dict) -> list[list[float]]:
    """Error bars of a rate from its interval (never negative: a Wilson bound may round past
    the value)."""
    lo, hi = rate["interval"]
    return [[max(0.0, rate["value"] - lo)], [max(0.0, hi - rate["value"])]]


def ladder_figure(ladder: dict, path: Path) -> Path:
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4))
    levels = ladder["levels"]
    for k, (level, d) in enumerate(levels.items()):
        dis = d["vs_passive"]["disagreement"]
        axes[0].errorbar(
            d["median_s"],
            dis["value"],
            yerr=_bars(dis),
            fmt="o",
            color=f"C{k}",
            capsize=3,
            label=level,
        )
        axes[0].annotate(
            level,
            (d["median_s"], dis["value"]),
            fontsize=8,
            xytext=(4, 4),
            textcoords="offset points",
        )
        for j, measure in enumerate(("precision", "recall")):
            r = d["vs_passive"][measure]
            if r["value"] is None:
                axes[1].plot(k + 0.15 * (2 * j - 1), 0.5, "x", color=f"C{j}")
                continue
            axes[1].errorbar(
                k + 0.15 * (2 * j - 1),
                r["value"],
                yerr=_bars(r),
                fmt="o",
                color=f"C{j}",
                capsize=3,
            )
    axes[0].set_xscale("log")
    axes[0].set_xlabel("wall time per design (s, median)")
    axes[0].set_ylabel("fraction disagreeing with the passive verdict")
    axes[0].set_title(f"cost vs verdict error, {len(ladder['rows'])} designs (Wilson 95%)")
    axes[1].set_xticks(range(len(levels)), list(levels))
    axes[1].set_ylim(-0.05, 1.05)
    axes[1].set_ylabel("fraction (x: undefined, no positives)")
    axes[1].set_title("precision and recall against the passive verdict, Wilson 95%")
    axes[1].legend(
        handles=[
            plt.Line2D([], [], color=f"C{j}", marker="o", ls="none", label=m)
            for j, m in enumerate(("precision", "recall"))
        ],
        fontsize=8,
    )
    for ax in axes:
        ax.grid(True, alpha=0.2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def speed_figure(speed: dict, wp: dict | None, path: Path) -> Path:
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    sizes = sorted(speed["lcp"], key=int)
    axes[0].plot([int(s) for s in sizes], [speed["lcp"][s]["median"] for s in sizes], "o-")
    axes[0].set_xscale("log", base=2)
    axes[0].set_yscale("log")
    axes[0].set_xlabel("LCP size 4 n_c")
    axes[0].set_ylabel("us per solve (median)")
    axes[0].set_title("Lemke (validity.lcp.solve_lcp), contact LCPs of Eq. 7")
    if wp is not None:
        cases = list(wp["cases"])
        engines = [e for e in COLOURS if _available(wp, e)]
        width = 0.8 / max(len(engines), 1)
        for j, engine in enumerate(engines):
            values = []
            for name in cases:
                p = next(
                    (
                        p
                        for p in wp["cases"][name]["points"]
                        if p["engine"] == engine and abs(p["h"] - 1e-3) < 1e-12
                    ),
                    None,
                )
                values.append(p["us_per_step"] if p else 0.0)
            axes[1].bar(
                [i + j * width for i in range(len(cases))],
                values,
                width,
                color=COLOURS[engine],
                label=engine,
            )
        axes[1].set_xticks([i + 0.4 - width / 2 for i in range(len(cases))], cases)
        axes[1].set_ylabel("us per step at h = 1e-3 (median)")
        axes[1].set_title("per step, same run (peers stepped from Python)")
        axes[1].legend(fontsize=7)
    for ax in axes:
        ax.grid(True, which="both", alpha=0.2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def draw_all(data: dict, out: Path) -> list[Path]:
    """Every figure whose section is in ``data``, into ``out``."""
    paths = []
    if "work_precision" in data:
        paths.append(work_precision_figure(data["work_precision"], out / "perf-work-precision.png"))
    if "feeder" in data:
        paths.append(feeder_figure(data["feeder"], out / "perf-feeder.png"))
    if "ladder" in data:
        paths.append(ladder_figure(data["ladder"], out / "perf-ladder.png"))
    if "speed" in data:
        paths.append(
            speed_figure(data["speed"], data.get("work_precision"), out / "perf-speed.png")
        )
    return paths
