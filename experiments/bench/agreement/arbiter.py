"""Box2D as the arbiter of a family agreement run (issue 35): the drops where the engines
disagree on success, and a control set where they agree, dropped again in Box2D
(:mod:`experiments.bench.peers.box2d_engine`) from the same made device and the same start, at
one or more scales (its model choice: the scale sets the corners' rounding, 0.01 / S).

For every disputed drop Box2D's success is set beside each engine's; the report counts, per
engine, the disputed drops on which Box2D sides with it, and the control drops on which Box2D
agrees with all (a check that Box2D models the same scenes: without it, siding says little).
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Callable, Sequence

from experiments.bench.agreement.drops import peer_drop
from experiments.bench.agreement.family import FamilyDesign, settings_of, trial_scene
from feeders.device_family import load_family


def _drops_by_key(data: dict) -> dict[tuple[str, int, str], dict[str, dict]]:
    out: dict = defaultdict(dict)
    for r in data["drops"]:
        if r["start"]:
            out[(r["design"], r["trial"], r["entry"])][r["engine"]] = r
    return out


def chosen_drops(data: dict, control: int) -> tuple[list[tuple], list[tuple]]:
    """(disputed, control): the drops whose engines differ on success, and those of each
    design's first ``control`` trials on which every engine agrees."""
    disputed, agreed = [], []
    for key, by in _drops_by_key(data).items():
        if len({r["success"] for r in by.values()}) > 1:
            disputed.append(key)
        elif key[1] < control:
            agreed.append(key)
    return disputed, agreed


def arbitrate(
    data: dict,
    scales: Sequence[float],
    h: float = 1e-4,
    control: int = 3,
    progress: Callable[[str], None] | None = None,
) -> dict:
    """Box2D at each of ``scales`` on the disputed and control drops of a family agreement
    run (``data`` as :func:`.family.family_agreement_data` returns or agreement.json holds)."""
    from experiments.bench.peers.box2d_engine import Box2DCompoundSimulator

    family = load_family(data["family"]["file"])
    settings = settings_of(data)
    disputed, agreed = chosen_drops(data, control)
    by_key = _drops_by_key(data)
    engines = list(data["engines"])
    results: dict = {}
    for scale in scales:
        drops = []
        for kind, keys in (("disputed", disputed), ("control", agreed)):
            for design, trial, entry in keys:
                values = tuple(data["designs"][design])
                made = trial_scene(family, FamilyDesign(design, values), trial, settings)
                if made is None:
                    continue
                scene, _, starts = made
                sim = Box2DCompoundSimulator(scene, h, scale)
                d = peer_drop(scene, starts[entry], sim, settings.t_max)
                others = {e: by_key[(design, trial, entry)][e]["success"] for e in engines}
                drops.append(
                    {
                        "kind": kind,
                        "design": design,
                        "trial": trial,
                        "entry": entry,
                        "box2d": d.ending.success,
                        "box2d_outcome": d.ending.outcome,
                        "engines": others,
                        "wall_time": d.wall_time,
                    }
                )
        if progress:
            progress(f"box2d at scale {scale:g}: {len(drops)} drops")
        results[f"{scale:g}"] = {"drops": drops, "summary": _summary(drops, engines)}
    return {"h": h, "control_trials": control, "engines": engines, "scales": results}


def _summary(drops: list[dict], engines: list[str]) -> dict:
    disputed = [d for d in drops if d["kind"] == "disputed"]
    control = [d for d in drops if d["kind"] == "control"]
    sides = {e: sum(d["box2d"] == d["engines"][e] for d in disputed) for e in engines}
    per_design: dict = defaultdict(lambda: dict.fromkeys(engines, 0) | {"drops": 0})
    for d in disputed:
        cell = per_design[d["design"]]
        cell["drops"] += 1
        for e in engines:
            cell[e] += d["box2d"] == d["engines"][e]
    return {
        "disputed": len(disputed),
        "sides_with": sides,
        "per_design": dict(per_design),
        "control": len(control),
        "control_agrees": sum(all(d["box2d"] == v for v in d["engines"].values()) for d in control),
        "wall_s": math.fsum(d["wall_time"] for d in drops),
    }


def arbiter_markdown(arbiter: dict) -> str:
    """The arbiter's tables: per scale, the disputed drops Box2D sides with each engine on,
    per design, and the control drops it agrees on."""
    engines = arbiter["engines"]
    lines = [
        "## Box2D as the arbiter (the drops where the engines disagree on success)",
        "",
        f"Box2D at h = {arbiter['h']:g} s; control: the first {arbiter['control_trials']} trials "
        "of each design where every engine agrees.",
        "",
        "| scale | disputed drops | Box2D sides with "
        + " | ".join(engines)
        + " | control agrees |",
        "|---|---|" + "---|" * len(engines) + "---|",
    ]
    for scale, r in arbiter["scales"].items():
        s = r["summary"]
        sides = " | ".join(str(s["sides_with"][e]) for e in engines)
        lines.append(
            f"| {scale} | {s['disputed']} | {sides} | {s['control_agrees']}/{s['control']} |"
        )
    for scale, r in arbiter["scales"].items():
        lines += ["", f"Per design at scale {scale} (disputed drops; Box2D sides with):", ""]
        lines += ["| design | drops | " + " | ".join(engines) + " |"]
        lines += ["|---|---|" + "---|" * len(engines)]
        for design, cell in r["summary"]["per_design"].items():
            lines.append(
                f"| {design} | {cell['drops']} | "
                + " | ".join(str(cell[e]) for e in engines)
                + " |"
            )
    return "\n".join(lines) + "\n"
