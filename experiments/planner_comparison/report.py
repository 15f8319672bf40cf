"""The comparison's report: the headline table (text and markdown), an HTML page with the
figures (:mod:`experiments.report_kit.page`) and the JSON, from the report's data
(:mod:`.summary`)."""

from __future__ import annotations

import html
import json
import statistics
from pathlib import Path
from typing import Any

from experiments.report_kit.cells import cell
from experiments.report_kit.page import STYLE, figure_html, html_table

HEADERS = [
    "planner",
    "runs solved",
    "95% Wilson",
    "problems solved",
    "median propagations (solved runs)",
    "profile area [95% bootstrap]",
    "best in resamples",
]


def headline_rows(level: dict[str, Any], labels: list[str]) -> list[list[str]]:
    """One row per planner of a level: the headline table's cells."""
    rows = []
    best = level["best"]
    for label in labels:
        p = level["planners"][label]
        solved = level["ecdf"][label]["x"]
        median = statistics.median(solved) if solved else None
        area = best["area"][label] if best else None
        spread = "-"
        if area is not None:
            low, high = area["interval95"]
            spread = f"{area['area']:.2f} [{low:.2f}, {high:.2f}]"
        rows.append(
            [
                label,
                f"{p['solved_runs']}/{p['runs']}",
                f"[{p['wilson95'][0]:.2f}, {p['wilson95'][1]:.2f}]",
                f"{p['problems_solved']}/{level['counted']}",
                cell(median, ".0f"),
                spread,
                "-" if area is None else f"{100 * area['best_share']:.0f}%",
            ]
        )
    return rows


def best_sentence(level_name: str, level: dict[str, Any]) -> str:
    """Which planner is best at a level by the performance profile's area, with its interval."""
    best = level["best"]
    if best is None:
        return f"{level_name}: no counted problem was solved by any planner; no ranking."
    name = best["planner"]
    a = best["area"][name]
    runner = best["ranking"][1] if len(best["ranking"]) > 1 else None
    text = (
        f"{level_name}: best by the performance profile is {name} (area {a['area']:.2f}, 95% "
        f"bootstrap interval [{a['interval95'][0]:.2f}, {a['interval95'][1]:.2f}] over "
        f"{best['resamples']} resamples of its {len(level['profile']['problems'])} problems; "
        f"best in {100 * a['best_share']:.0f}% of them)"
    )
    if runner is not None:
        r = best["area"][runner]
        text += (
            f"; next {runner} ({r['area']:.2f} [{r['interval95'][0]:.2f}, "
            f"{r['interval95'][1]:.2f}])"
        )
    return text + "."


def _markdown_table(headers: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def markdown(report: dict[str, Any]) -> str:
    """The report as markdown: per level the headline table, the best planner, the
    problems no planner solved and those left out as unsolvable."""
    labels = [p["label"] for p in report["planners"]]
    s = report["suite"]
    out = [
        f"# Planner comparison: {s['name']}",
        "",
        f"{len(report['problems'])} problems (design x level x entry), planners "
        f"{', '.join(labels)}; {s['runs']} runs each, run r seeded with {s['seed']} + r; "
        "budgets in propagations per run: "
        + ", ".join(f"{k} {v}" for k, v in s["budgets"].items())
        + ". Solved fractions count runs on the problems not known to be unsolvable; the "
        "performance profile's cost is "
        + "the expected propagations to the first success with restarts.",
        "",
    ]
    for name, level in report["levels"].items():
        out += [f"## {name}", "", best_sentence(name, level), ""]
        out += [_markdown_table(HEADERS, headline_rows(level, labels)), ""]
        if level["unsolved_by_all"]:
            out += ["No planner solved: " + ", ".join(level["unsolved_by_all"]) + ".", ""]
        if level["excluded"]:
            out += [
                "Not counted: "
                + "; ".join(
                    f"{e['problem']} ({e['status']}: {e['reason']})" for e in level["excluded"]
                )
                + ".",
                "",
            ]
        out += [f"![{name}](figures/{name}.png)", ""]
    if report["contradictions"]:
        out += [
            "A planner solved problems marked unsolvable: " + ", ".join(report["contradictions"]),
            "",
        ]
    if report.get("unavailable"):
        out += ["Not compared (cannot run from Python): "]
        out += [f"- {k}: {v}" for k, v in report["unavailable"].items()]
        out += [""]
    return "\n".join(out)


def html_page(report: dict[str, Any], figures: dict[str, Path]) -> str:
    """The report as one HTML page, the figures beside it in ``figures/``."""
    labels = [p["label"] for p in report["planners"]]
    s = report["suite"]
    body = [
        f"<h1>Planner comparison: {html.escape(s['name'])}</h1>",
        f"<p>{len(report['problems'])} problems (design x level x entry; "
        f"{sum(1 for p in report['problems'] if p['planned'])} planned), "
        f"{s['runs']} runs per planner and problem, run r seeded with {s['seed']} + r, "
        "budgets in propagations: "
        + html.escape(", ".join(f"{k} {v}" for k, v in s["budgets"].items()))
        + ".</p>",
    ]
    body.append(
        html_table(
            ["planner", "configuration"],
            [[p["label"], p["about"]] for p in report["planners"]],
            text_columns=(0, 1),
        )
    )
    for name, level in report["levels"].items():
        body.append(f"<h2>{html.escape(name)}</h2>")
        body.append(f"<p><b>{html.escape(best_sentence(name, level))}</b></p>")
        body.append(html_table(HEADERS, headline_rows(level, labels), text_columns=(0,)))
        body.append(figure_html(figures, name, f"{name}: solved fraction, ECDF, profile"))
        if level["unsolved_by_all"]:
            body.append(
                "<p>No planner solved: " + html.escape(", ".join(level["unsolved_by_all"])) + "</p>"
            )
        if level["excluded"]:
            rows = [
                [e["problem"], e["status"], e["reason"], str(e["planned"])]
                for e in level["excluded"]
            ]
            body.append("<p class='note'>Not counted against any planner:</p>")
            body.append(html_table(["problem", "status", "why", "planned"], rows, (0, 1, 2)))
    if report.get("unavailable"):
        rows = [[k, v] for k, v in report["unavailable"].items()]
        body.append("<h2>Not compared</h2>")
        body.append(html_table(["planner", "why"], rows, (0, 1)))
    return (
        f"<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>Planner comparison</title>"
        f"<style>{STYLE}</style></head><body>\n" + "\n".join(body) + "\n</body></html>\n"
    )


def text_table(report: dict[str, Any]) -> str:
    """The headline tables as plain text, for the terminal."""
    labels = [p["label"] for p in report["planners"]]
    lines = []
    for name, level in report["levels"].items():
        rows = headline_rows(level, labels)
        widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(HEADERS)]
        lines.append(best_sentence(name, level))
        lines.append("  ".join(h.ljust(w) for h, w in zip(HEADERS, widths, strict=True)))
        lines += ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) for r in rows]
        if level["unsolved_by_all"]:
            lines.append("no planner solved: " + ", ".join(level["unsolved_by_all"]))
        if level["excluded"]:
            lines.append(
                "not counted (known unsolvable): "
                + ", ".join(e["problem"] for e in level["excluded"])
            )
        lines.append("")
    return "\n".join(line.rstrip() for line in lines).rstrip()


def write_report(report: dict[str, Any], out: Path) -> list[Path]:
    """``report.md``, ``report.html``, ``report.json`` and ``figures/`` in ``out``."""
    from experiments.planner_comparison.figures import figures

    out.mkdir(parents=True, exist_ok=True)
    drawn = figures(report, out / "figures")
    (out / "report.md").write_text(markdown(report))
    (out / "report.html").write_text(html_page(report, drawn))
    write_json(report, out / "report.json")
    return [out / "report.md", out / "report.html", out / "report.json", *drawn.values()]


def write_json(report: dict[str, Any], path: Path) -> None:
    """The report's data as JSON (no NaN: unknown numbers are null)."""
    path.write_text(json.dumps(report, indent=1, allow_nan=False))
