"""The agreement suite's outputs: ``agreement.json`` (settings, every drop, every table),
``agreement.md`` (the tables) and ``agreement.png`` (success fractions with intervals per
design and entry in each engine; the lip-speed ratios per engine)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from experiments.bench.agreement.lip import PAST_LIP, SLOW

SHORT = {"heavy_leading": "leading", "heavy_trailing": "trailing"}


def _f(cell: dict) -> str:
    lo, hi = cell["interval"]
    return f"{cell['k']}/{cell['n']} [{lo:.2f}, {hi:.2f}]"


def markdown(data: dict) -> str:
    """The tables as Markdown (``data`` as :func:`write_outputs` stores it)."""
    t, s = data["tables"], data["settings"]
    engines = data["engines"]
    first: dict = next(iter(t["success"].values()), {}).get(engines[0], {})
    entries = max(1, len(first) - 1)  # the entries and "both"
    family = (
        [f"Device family {data['family']['name']}: {data['family']['model']}"]
        if (data.get("family"))
        else []
    )
    lines = [
        "# Agreement: the same perturbed drops in partfeeder, MuJoCo and pymunk",
        "",
        *family,
        f"{len(t['success'])} designs x {entries} entries x {s['trials']} trials "
        f"(draw seed {s['seed']}); "
        f"partfeeder at h = {s['partfeeder_step']:g} s, peers at h = {s['peer_step']:g} s; "
        f"t_max {s['t_max']:g} s; wall time {data['wall_time_s']:.0f} s"
        f"{' on ' + str(data['workers']) + ' workers' if data['workers'] > 1 else ''}.",
        f"Versions: {', '.join(f'{k} {v}' for k, v in data['versions'].items())}. "
        f"Contact kernel: {data['kernel']}.",
        "",
        "## Success per design and entry (in the goal; Wilson 95%)",
        "",
        "| design | entry | " + " | ".join(engines) + " |",
        "|---|---|" + "---|" * len(engines),
    ]
    for design, by in t["success"].items():
        for entry in by[engines[0]]:  # the entries, then "both"
            cells = [_f(by[e][entry]) for e in engines]
            lines.append(f"| {design} | {SHORT.get(entry, entry)} | " + " | ".join(cells) + " |")
    lines += ["", "## Per-drop agreement, every pair of engines (same drops)", ""]
    lines += [
        "| pair | success agrees | outcome class agrees "
        "| 2 x 2 (both / first only / second only / neither) |",
        "|---|---|---|---|",
    ]
    for pair, p in t["pairs"].items():
        tab = " / ".join(str(v) for v in p["table"].values())
        sp, op = p["success"], p["outcome"]
        lines.append(f"| {pair} | {sp['p']:.3f} ({_f(sp)}) | {op['p']:.3f} ({_f(op)}) | {tab} |")
    lines += ["", "Per design, success agreement:", ""]
    pairs = list(t["pairs"])
    lines += ["| design | " + " | ".join(pairs) + " |", "|---|" + "---|" * len(pairs)]
    for design in t["success"]:
        cells = []
        for pair in pairs:
            c = t["pairs"][pair]["per_design"].get(design)
            cells.append(f"{c['k']}/{c['n']}" if c else "-")
        lines.append(f"| {design} | " + " | ".join(cells) + " |")
    v = t["verdicts"]
    lines += [
        "",
        f"## Verdicts on these trials (works: every entry's lower bound > {v['target']:g}; "
        "fails: some upper bound below it)",
        "",
        "| design | " + " | ".join(engines) + " |",
        "|---|" + "---|" * len(engines),
    ]
    for design, by in v["decisions"].items():
        lines.append(f"| {design} | " + " | ".join(by[e] for e in engines) + " |")
    lines += [""]
    for pair, p in v["pairs"].items():
        lines.append(f"- {pair}: same verdict on {p['agree']} of {p['designs']} designs")
    odd = v["partfeeder_odd"]
    lines.append(
        "- designs whose partfeeder verdict differs from both peers (which agree): "
        + (", ".join(odd) if odd else "none")
    )
    if any(t["lip"][e]["measured"] for e in engines):
        lines += _lip_lines(t, engines)
    else:
        lines += ["", "No lip speed: no drop reached a named lip (a device family names none)."]
    order = " / ".join(engines)
    lines += ["", f"## Outcome classes side by side (drops per engine: {order})", ""]
    lines += ["| design | entry | class | drops |", "|---|---|---|---|"]
    for design, by_entry in t["outcomes"].items():
        for entry, classes in by_entry.items():
            for c, counts in classes.items():
                lines.append(
                    f"| {design} | {SHORT.get(entry, entry)} | {c} | "
                    + " / ".join(str(counts[e]) for e in engines)
                    + " |"
                )
    lines += [
        "",
        "## Cost",
        "",
        "| engine | h (s) | drops | wall (s) | per drop (s) | mean T (s) |",
    ]
    lines += ["|---|---|---|---|---|---|"]
    for engine, c in t["timing"].items():
        lines.append(
            f"| {engine} | {c['h']:g} | {c['drops']} | {c['wall_s']:.1f} | "
            f"{c['mean_wall_s']:.3f} | {c['mean_T_s']:.2f} |"
        )
    if data.get("arbiter"):
        from experiments.bench.agreement.arbiter import arbiter_markdown

        lines += ["", arbiter_markdown(data["arbiter"]).rstrip("\n")]
    return "\n".join(lines) + "\n"


def _lip_lines(t: dict, engines: list[str]) -> list[str]:
    """The lip-speed tables (the peg feeder's lip, :mod:`.lip`)."""
    lines = [
        "",
        f"## Speed just past the lip (centre of mass {PAST_LIP:g} before it) / sliding closed form",
        "",
        "| engine | drops measured | below " + f"{SLOW:g}" + " | min | 5% | median | 95% | max |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for engine in engines:
        lt = t["lip"][engine]
        q = lt["quantiles"]
        vals = [q.get(k, math.nan) for k in ("min", "q05", "median", "q95", "max")]
        lines.append(
            f"| {engine} | {lt['measured']} of {lt['drops']} | {lt['slow']} | "
            + " | ".join(f"{x:.3f}" for x in vals)
            + " |"
        )
    lines += ["", "Drops below the threshold per design and entry:", ""]
    lines += ["| design, entry | " + " | ".join(engines) + " |", "|---|" + "---|" * len(engines)]
    for key in t["lip"][engines[0]]["per_design_entry"]:
        cells = []
        for engine in engines:
            c = t["lip"][engine]["per_design_entry"][key]
            low = f", min {c['min']:.2f}" if c["measured"] else ""
            cells.append(f"{c['slow']}/{c['measured']}{low}")
        lines.append(f"| {key} | " + " | ".join(cells) + " |")
    return lines


def figure(data: dict, path: Path) -> None:
    """Success fractions with intervals per design and entry (one marker per engine), and the
    lip-speed ratio per engine (strip plot, threshold marked)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t, engines = data["tables"], data["engines"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5), gridspec_kw={"width_ratios": [2, 1]})
    entries = [e for e in next(iter(t["success"].values()))[engines[0]] if e != "both"]
    labels = [f"{d}\n{SHORT.get(e, e)}" for d in t["success"] for e in entries]
    for j, engine in enumerate(engines):
        xs, ps, lo, hi = [], [], [], []
        cells = [by[engine][e] for by in t["success"].values() for e in entries]
        for i, c in enumerate(cells):
            xs.append(i + (j - 1) * 0.2)
            ps.append(c["p"])
            lo.append(c["p"] - c["interval"][0])
            hi.append(c["interval"][1] - c["p"])
        ax1.errorbar(xs, ps, yerr=[lo, hi], fmt="o", capsize=2, label=engine)
    ax1.axhline(data["settings"]["target"], color="grey", lw=0.8, ls="--")
    ax1.set_xticks(range(len(labels)), labels, rotation=60, fontsize=7)
    ax1.set_ylabel("P(in the goal), Wilson 95%")
    ax1.legend()
    ratios = {e: [r["lip_ratio"] for r in data["drops"] if r["engine"] == e] for e in engines}
    for j, engine in enumerate(engines):
        vals = [v for v in ratios[engine] if v is not None and math.isfinite(v)]
        ax2.plot([j + 0.15 * ((k % 7) - 3) / 3 for k in range(len(vals))], vals, ".", alpha=0.5)
    ax2.axhline(SLOW, color="red", lw=0.8, ls="--")
    ax2.set_xticks(range(len(engines)), engines)
    ax2.set_ylabel("speed past the lip / sliding closed form")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _clean(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    return value


def written_data(data: dict) -> dict:
    """``data`` as agreement.json holds it (a NaN or an infinity as null), for printing it
    when no file is written."""
    return _clean(data)


def write_outputs(data: dict, out: Path, picture: bool = True) -> list[Path]:
    """agreement.json, agreement.md and (``picture``) agreement.png in ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    data = written_data(data)
    paths = [out / "agreement.json", out / "agreement.md"]
    paths[0].write_text(json.dumps(data, indent=1))
    paths[1].write_text(markdown(data))
    if picture:
        paths.append(out / "agreement.png")
        figure(data, paths[-1])
    return paths
