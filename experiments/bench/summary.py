"""The benchmark's Markdown summary, written from the data dictionary alone."""

from __future__ import annotations

from experiments.bench.comparisons import goals, peer_ratios


def _g(value: float | None, digits: int = 3) -> str:
    if value is None:
        return "n/a"
    if value == 0.0:
        return "0"
    return f"{value:.{digits}g}"


def _interval(rate: dict) -> str:
    if rate["value"] is None:
        return f"n/a (0 of 0) [{rate['interval'][0]:.2f}, {rate['interval'][1]:.2f}]"
    lo, hi = rate["interval"]
    return f"{rate['value']:.2f} ({rate['k']}/{rate['n']}) [{lo:.2f}, {hi:.2f}]"


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    return [
        "| " + " | ".join(header) + " |",
        "|" + "|".join("---" for _ in header) + "|",
        *("| " + " | ".join(r) + " |" for r in rows),
    ]


def _machine(data: dict) -> list[str]:
    m, v = data["machine"], data["versions"]
    versions = ", ".join(f"{k} {val}" for k, val in v.items())
    return [
        f"Machine: {m['platform']}, {m['machine']}, CPU {m.get('cpu', 'unknown')}, "
        f"{m['cores']} cores ({m['usable_cores']} usable); Python {m['python']}.",
        f"Engines: {versions}.",
        f"Settings: {data['settings']}.",
        "",
    ]


def _goals(data: dict) -> list[str]:
    rows = []
    for g in goals(data):
        met = {True: "met", False: "not met", None: "not measured"}[g["met"]]
        rows.append([g["goal"], _g(g["value"]), met])
    return ["## Goals", "", *_table(["goal", "measured", ""], rows), ""]


def _work_precision(wp: dict) -> list[str]:
    out = [
        "## Work-precision, analytic scenes",
        "",
        f"Errors against closed forms; wall time is the median of {wp['repeats']} runs, "
        "interleaved over every case, engine and h.",
        "",
    ]
    for e in wp["engines"]:
        state = "" if e["available"] else " — **not installed**"
        out.append(f"- {e['label']}: {e['description']}{state}")
    out.append("")
    for data in wp["cases"].values():
        measures = data["measures"]
        out += [f"### {data['title']} (`{data['scene']}`, {data['duration_s']:g} s)", ""]
        header = ["engine", "h", "us/step", "wall s per sim s", *measures]
        rows = []
        for p in data["points"]:
            rows.append(
                [
                    p["engine"],
                    f"{p['h']:g}",
                    _g(p["us_per_step"]),
                    _g(p["wall_per_sim_s"]),
                    *(_g(p["errors"][m]) for m in measures),
                ]
            )
        for e in wp["engines"]:
            if not e["available"]:
                rows.append([e["label"], "-", "not installed", "-", *("-" for _ in measures)])
        out += [*_table(header, rows), ""]
    creep = wp["creep"]
    out += [
        f"### Creep of the sticking box after {creep['duration_s']:g} s at h = {creep['h']:g}",
        "",
        *_table(
            ["engine", "creep (length)"],
            [[k, v if isinstance(v, str) else _g(v)] for k, v in creep["by_engine"].items()],
        ),
        "",
        "### Ratios against the peers (same run)",
        "",
        "per step: partfeeder's us/step over the peer's at h = 1e-3; at equal error: "
        "partfeeder's wall time per simulated second at the peer's h = 1e-3 error "
        "(interpolated on its curve) over the peer's.",
        "",
    ]
    rows = []
    for r in peer_ratios(wp):
        if not r["measured"]:
            rows.append([r["case"], r["peer"], "not installed", "", "", ""])
            continue
        rows.append(
            [
                r["case"],
                r["peer"],
                _g(r["step_ratio"]),
                _g(r["equal_error_ratio"]),
                _g(r["ours_error"]),
                _g(r["peer_error"]),
            ]
        )
    out += [
        *_table(["case", "peer", "per step", "at equal error", "our error", "peer error"], rows),
        "",
    ]
    return out


def _feeder(fc: dict) -> list[str]:
    out = [
        "## Feeder: convergence of what converges",
        "",
        "A single drop's exit does not converge with h: contact through the feeder is chaotic "
        "(the paired column shows it). Measured instead: the success fraction over "
        f"{fc['drops_per_orientation']} seeded drops per entry orientation (entry pose "
        "perturbed by +-0.05 and +-0.05 rad) with its Wilson 95% interval, and T's "
        "distribution (KS distance and difference of medians), against the same drops at "
        f"h_ref = {fc['h_reference']:.3g} s.",
        "",
    ]
    rows = []
    for name, data in fc["designs"].items():
        ref = data["reference"]
        lo, hi = ref["interval"]
        rows.append(
            [
                name,
                f"{ref['h']:.3g} (ref)",
                f"{ref['p']:.2f} [{lo:.2f}, {hi:.2f}]",
                "",
                "",
                "",
                "",
                _g(ref["wall_per_drop_s"] * 1e3),
            ]
        )
        for r in data["by_h"]:
            lo, hi = r["interval"]
            rows.append(
                [
                    name,
                    f"{r['h']:g}",
                    f"{r['p']:.2f} [{lo:.2f}, {hi:.2f}]",
                    _g(r["p_error"]),
                    f"{r['ks']:.2f} (floor {r['ks_critical']:.2f})",
                    _g(r["median_T_error"]),
                    _g(r["paired_T_error"]),
                    _g(r["wall_per_drop_s"] * 1e3),
                ]
            )
    header = [
        "design",
        "h",
        "success [95%]",
        "abs dp",
        "KS of T",
        "dmedian T (s)",
        "paired dT (s)",
        "ms/drop",
    ]
    return [*out, *_table(header, rows), ""]


def _ladder(ladder: dict) -> list[str]:
    out = [
        "## The ladder: what each rung buys",
        "",
        f"{len(ladder['rows'])} designs at every level (RRT, budgets per orientation "
        f"{ladder['budgets_s_per_orientation']} s; passive verdict "
        f"{ladder['passive_settings']}). Precision and recall against the passive verdict "
        "(the top), Wilson 95%.",
        "",
    ]
    rows = []
    for level, d in ladder["levels"].items():
        vs = d["vs_passive"]
        rows.append(
            [
                level,
                _g(d["median_s"]),
                _g(d["designs_per_s"]),
                str(d["feasible"]),
                _interval(vs["precision"]),
                _interval(vs["recall"]),
                _interval(vs["disagreement"]),
            ]
        )
    header = [
        "level",
        "s/design (median)",
        "designs/s",
        "passed",
        "precision",
        "recall",
        "disagreement",
    ]
    skip = ladder["skip_levels_not_climbed"]
    against_dynamic = [
        [
            level,
            _interval(d["vs_dynamic"]["precision"]),
            _interval(d["vs_dynamic"]["recall"]),
            _interval(d["vs_dynamic"]["disagreement"]),
        ]
        for level, d in ladder["levels"].items()
        if level in ("geometric", "kinematic")
    ]
    return [
        *out,
        *_table(header, rows),
        "",
        "Against the dynamic level (the top of `partfeeder run`'s ladder):",
        "",
        *_table(["level", "precision", "recall", "disagreement"], against_dynamic),
        "",
        f"Levels not climbed (skip on): the ladder took {skip['ladder_s']:.1f} s; every "
        f"design at every level (skip off) {skip['every_level_s']:.1f} s: "
        f"{skip['speed_up']:.2f}x.",
        "",
    ]


def _speed(speed: dict) -> list[str]:
    rows = [
        [name, _g(d["check_us"]["median"]), _g(d["step_us"]["median"]), f"{d['step_h']:g}"]
        for name, d in speed["levels"].items()
    ]
    out = [
        "## Speed tables",
        "",
        "### Per validity check and per propagation step (table3, medians)",
        "",
        *_table(["level", "us/check", "us/step", "h"], rows),
        "",
        "### Per LCP solve by size (compiled loop)",
        "",
        *_table(
            ["size", "contacts", "us/solve", "solved"],
            [
                [s, str(d["contacts"]), _g(d["median"]), f"{d['solved']}/{d['count']}"]
                for s, d in sorted(speed["lcp"].items(), key=lambda kv: int(kv[0]))
            ],
        ),
        "",
        "### The dynamic level's skips, on and off (interleaved)",
        "",
    ]
    rows = []
    for label, d in speed["dynamic_skips"].items():
        rows.append(
            [
                label,
                _g(d["median_ms"]),
                _g(d["us_per_step"]),
                str(d["steps"]),
                str(d["contact_searches"]),
                str(d["lcp_solves"]),
            ]
        )
    return [
        *out,
        *_table(["run", "ms", "us/step", "steps", "contact searches", "LCPs"], rows),
        "",
    ]


def markdown(data: dict) -> str:
    """The whole summary."""
    lines = ["# partfeeder bench", "", *_machine(data), *_goals(data)]
    if "work_precision" in data:
        lines += _work_precision(data["work_precision"])
    if "feeder" in data:
        lines += _feeder(data["feeder"])
    if "ladder" in data:
        lines += _ladder(data["ladder"])
    if "speed" in data:
        lines += _speed(data["speed"])
    return "\n".join(lines) + "\n"


def goal_lines(data: dict) -> list[str]:
    """One line per goal, for the terminal."""
    lines = []
    for g in goals(data):
        met = {True: "met", False: "NOT met", None: "not measured"}[g["met"]]
        lines.append(f"goal: {g['goal']}: {_g(g['value'])} ({met})")
    return lines
