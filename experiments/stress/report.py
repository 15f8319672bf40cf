"""The stress run's summary (counts per level and kind, worst cases, speed), as plain data and
as text, and the replayable files of failing cases."""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from pathlib import Path
from typing import Any

import yaml

from experiments.stress.bounds import HARD, SOFT, TRUSTED_STEP, VACUOUS_FRACTION, vacuous
from experiments.stress.case import Case, CaseError
from feeders.fields import read_yaml

WORST = 5  # worst cases shown per measure
LISTED = 10  # vacuous allowances listed per band of h in the text summary


def _ratio(record: dict, value: str, allowed: str) -> float:
    return record[value] / record[allowed] if record[allowed] > 0 else record[value]


def summary(results: list[tuple[dict[str, Any], float]], seed: int) -> dict[str, Any]:
    """Counts of cases and of each broken bound per level, hard failures per level and decade
    of h, the worst cases by penetration and energy gain, and cases per second per level (one
    core: the wall time of the cases themselves)."""
    counts: dict[str, Counter] = defaultdict(Counter)
    by_h: dict[str, Counter] = defaultdict(Counter)
    seconds: dict[str, float] = defaultdict(float)
    for record, elapsed in results:
        level = record["level"]
        counts[level]["cases"] += 1
        seconds[level] += elapsed
        for kind in record["hard"] + record["soft"]:
            counts[level][kind] += 1
        if record["hard"]:
            by_h[level][f"1e{math.floor(math.log10(record['h']))}"] += 1
    records = [r for r, _ in results]
    worst = {
        "penetration": sorted(records, key=lambda r: -r["max_depth"])[:WORST],
        "energy": sorted(records, key=lambda r: -_ratio(r, "energy_gain", "energy_allowed"))[
            :WORST
        ],
    }
    data = {
        "seed": seed,
        "cases": len(records),
        "hard_failures": sum(1 for r in records if r["hard"]),
        "counts": {level: dict(c) for level, c in counts.items()},
        "hard_by_h": {level: dict(sorted(c.items())) for level, c in by_h.items()},
        "cases_per_second": {
            level: counts[level]["cases"] / seconds[level] for level in seconds if seconds[level]
        },
        "worst": {k: [_brief(r) for r in v] for k, v in worst.items()},
        "failing": [_brief(r) for r in records if r["hard"]],
        "families": dict(sorted(Counter(r["family"].split("+")[0] for r in records).items())),
    }
    data["bands"] = _bands(records)
    if any("+" in r["family"] for r in records):
        data["parts"] = _by_part(records)
    return data


def _band(record: dict[str, Any]) -> str:
    return f"h<={TRUSTED_STEP:g}" if record["h"] <= TRUSTED_STEP else f"h>{TRUSTED_STEP:g}"


def _bands(records: list[dict[str, Any]]) -> dict[str, Any]:
    """Per band of h (up to :data:`TRUSTED_STEP` and above), the dynamic cases, their hard
    failures, and the cases whose linearisation allowance is vacuous (above
    :data:`VACUOUS_FRACTION` of the part's size, :func:`experiments.stress.bounds.vacuous`):
    how many, how many of those went deeper than the fixed tolerance (their pass rests on the
    allowance), and each one's index, h, allowance, part size and depth."""
    bands: dict[str, Any] = {}
    for r in records:
        if r["level"] != "dynamic":
            continue
        row = bands.setdefault(
            _band(r), {"cases": 0, "hard": 0, "vacuous": 0, "vacuous_deeper": 0, "list": []}
        )
        row["cases"] += 1
        row["hard"] += bool(r["hard"])
        if vacuous(r):
            row["vacuous"] += 1
            row["vacuous_deeper"] += r["max_depth"] > r["depth_allowed"] - r["step_error"]
            row["list"].append(
                {k: r[k] for k in ("index", "h", "step_error", "part_size", "max_depth", "hard")}
            )
    return {"fraction": VACUOUS_FRACTION, **dict(sorted(bands.items()))}


def _by_part(records: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Per kind of part (``peg``, or the composite kind after the ``+`` of a family), per
    level: cases, hard failures and the deepest penetration (length)."""
    parts: dict[str, dict[str, Any]] = defaultdict(dict)
    for r in records:
        kind = r["family"].split("+")[1] if "+" in r["family"] else "peg"
        row = parts[kind].setdefault(r["level"], {"cases": 0, "hard": 0, "max_depth": 0.0})
        row["cases"] += 1
        row["hard"] += bool(r["hard"])
        row["max_depth"] = max(row["max_depth"], float(r["max_depth"]))
    return {kind: parts[kind] for kind in sorted(parts)}


def _brief(record: dict) -> dict[str, Any]:
    keys = (
        "index",
        "level",
        "family",
        "placement",
        "h",
        "max_depth",
        "depth_allowed",
        "energy_gain",
        "energy_allowed",
        "crossed_step",
        "error",
        "hard",
    )
    return {k: record[k] for k in keys}


def table(data: dict[str, Any]) -> str:
    """The summary as text: a table of counts per level and kind, then the worst cases."""
    kinds = ("cases", *HARD, *SOFT)
    width = max(len(k) for k in kinds) + 1
    levels = list(data["counts"])
    lines = [
        f"stress seed {data['seed']}: {data['cases']} cases, {data['hard_failures']} broke a"
        " hard bound"
    ]
    lines.append("kind".ljust(width) + "".join(f"{lv:>11}" for lv in levels))
    for kind in kinds:
        mark = " *" if kind in HARD else ""
        row = "".join(f"{data['counts'][lv].get(kind, 0):>11}" for lv in levels)
        lines.append((kind + mark).ljust(width + 2)[: width + 2] + row[2:])
    rates = data["cases_per_second"]
    lines.append("cases/s".ljust(width) + "".join(f"{rates.get(lv, 0):>11.1f}" for lv in levels))
    lines.append("(* hard bound; cases/s on one core)")
    for kind, rows in data.get("parts", {}).items():
        lines.append(
            f"part {kind}: "
            + "; ".join(
                f"{level} {row['cases']} cases, {row['hard']} hard, deepest {row['max_depth']:.3g}"
                for level, row in rows.items()
            )
        )
    lines += _band_lines(data.get("bands", {}))
    for level, decades in data["hard_by_h"].items():
        lines.append(
            f"hard failures of {level} by h: "
            + ", ".join(f"h~{d}: {n}" for d, n in decades.items())
        )
    for measure, rows in data["worst"].items():
        lines.append(f"worst {measure}:")
        for r in rows:
            lines.append(
                f"  #{r['index']} {r['level']} {r['family']}/{r['placement']} h={r['h']:.2g}: "
                f"depth {r['max_depth']:.3g} (allowed {r['depth_allowed']:.3g}), energy gain "
                f"{r['energy_gain']:.3g} (allowed {r['energy_allowed']:.3g})"
                + (
                    f", crossed at step {r['crossed_step']}"
                    if r["crossed_step"] is not None
                    else ""
                )
                + (f", {r['error']}" if r["error"] else "")
            )
    return "\n".join(lines)


def _band_lines(bands: dict[str, Any]) -> list[str]:
    """The dynamic cases per band of h: hard failures and vacuous allowances, the vacuous
    cases listed (index, h, allowance / part size, depth) up to :data:`LISTED` per band."""
    lines = []
    fraction = bands.get("fraction", VACUOUS_FRACTION)
    for band, row in bands.items():
        if band == "fraction":
            continue
        lines.append(
            f"dynamic {band}: {row['cases']} cases, {row['hard']} hard; allowance above "
            f"{fraction:.0%} of the part's size in {row['vacuous']} ({row['vacuous_deeper']} "
            "of them deeper than the tolerance)"
        )
        worst = sorted(row["list"], key=lambda v: -v["step_error"] / max(v["part_size"], 1e-300))
        for v in worst[:LISTED]:
            lines.append(
                f"  #{v['index']} h={v['h']:.2g}: allowance {v['step_error']:.3g} "
                f"(part {v['part_size']:.3g}), depth {v['max_depth']:.3g}"
                + (f", {'/'.join(v['hard'])}" if v["hard"] else "")
            )
        if len(worst) > LISTED:
            lines.append(f"  ... {len(worst) - LISTED} more (--json lists every one)")
    return lines


def write_case(directory: Path, case: Case, record: dict[str, Any]) -> Path:
    """A failing case as a replayable YAML file (``scene`` in the scene schema, the rest of
    the case, and the record it gave) in ``directory``; returns its path."""
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / f"case-{case.seed}-{case.index:06d}-{case.level}.yaml"
    data = case.to_dict()
    document = {"scene": data.pop("scene"), "case": data, "record": record}
    path.write_text(yaml.safe_dump(document, sort_keys=False))
    return path


def read_case(path: Path) -> tuple[Case, dict[str, Any] | None]:
    """The case of a file written by :func:`write_case` and the record stored with it."""
    document = read_yaml(path, "stress case", CaseError)
    if not isinstance(document, dict) or "case" not in document or "scene" not in document:
        raise CaseError(f"{path}: expected a mapping with 'scene' and 'case'")
    case = Case.from_dict({**document["case"], "scene": document["scene"]})
    return case, document.get("record")
