"""A corpus of malformed input to ``partfeeder``, and a runner that says how each case ended.

Issue 16: every input path (run configs, scenes, ``--design``, command lines, output
directories, the scheduler address, the results database, a sweep directory in use) must answer
bad input with one line on stderr and exit status 2, within seconds. The corpus builds each
family's cases from valid documents by construction (a field outside its stated range, of the
wrong type, missing or extra, a file that is not what it claims, a damaged database), plus a few
valid controls; the runner runs the command line of each in its own directory and classifies:

- ``clean``: exit 2, exactly one line on stderr, no traceback (and protected files unchanged);
- ``traceback``: a Python traceback on stderr;
- ``hang``: still running after ``TIMEOUT_S`` (killed with its process group);
- ``accepted``: exit 0 (for a control: the expected outcome);
- ``written``: an error, but a file that must be left alone was changed;
- ``unclean``: any other ending (several lines, another exit status, a signal).

Usage (from anywhere; ``--code DIR`` runs another checkout, e.g. the code before the fixes)::

    python tests/experiments/cli/bad_input_corpus.py --out corpus.json
    PYTHONPATH=/tmp/old python tests/experiments/cli/bad_input_corpus.py --code /tmp/old

It imports nothing of partfeeder at module level, so the same runner judges old and new code.
Cases run in forked children of a process that has imported the CLI already (``--mode fork``,
fast) or as fresh ``python`` processes (``--mode subprocess``, as a user runs them).
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import os
import random
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

TIMEOUT_S = 10.0
# The optimize control starts a worker process, loads the dynamic level there and in the main
# process and runs 10 verdict trials: about 8 s on a quiet machine, more in CI's fresh cache.
OPTIMIZE_CONTROL_S = 120.0
OUTCOMES = ("clean", "traceback", "hang", "accepted", "written", "unclean")
CLI = "from experiments.cli import main; main()"

# A valid run config that finishes in seconds: one design, the geometric rung, a small
# budget in propagations, one worker.
BASE_CONFIG: dict[str, Any] = {
    "name": "corpus",
    "designs": {"count": 1, "seed": 1},
    "feeder": {
        "friction": 0.3,
        "restitution": 0.3,
        "gravity": [0.0, -9.81],
        "part": {"length": 1.6, "width": 1.0, "mass": 1.0, "heavy_fraction": 0.75},
        "inputs": {"max_speed": 1.0, "max_turn": 1.0, "max_force": 10.0, "max_torque": 2.0},
    },
    "planner": {"step": 0.05, "min_steps": 1, "max_steps": 20},
    "ladder": [
        {
            "level": "geometric",
            "planners": ["rrt"],
            "runs": 1,
            "budget": {"propagations": 2000, "time": 5.0},
        }
    ],
    "holdout": {"fraction": 0.0, "seed": 7},
    "workers": 1,
    "max_attempts": 1,
}

# A valid free-form scene: a box with a floor and a roof, a start between them.
BASE_SCENE: dict[str, Any] = {
    "name": "box",
    "obstacles": [
        {"polygon": [[-6, -4], [6, -4], [6, -3], [-6, -3]]},
        {"polygon": [[-6, 3], [6, 3], [6, 4], [-6, 4]]},
        {"circle": {"centre": [4.0, 0.0], "radius": 0.5}},
    ],
    "part": {"length": 1.0, "width": 0.5, "mass": 1.0, "heavy_fraction": 0.5},
    "friction": 0.3,
    "restitution": 0.3,
    "gravity": [0.0, -9.81],
    "inputs": {"max_speed": 1.0, "max_turn": 1.0, "max_force": 5.0, "max_torque": 1.0},
    "bounds": [-5, 5, -2.5, 2.5],
    "starts": {"drop": [0.0, 2.0, 0.0]},
    "goal": {"x": [-1, 1], "y": [-2.5, -2], "yaw": 0.0, "yaw_tol": 0.5},
}

BASE_FEEDER_SCENE: dict[str, Any] = {
    "feeder": {"preset": "table3"},
    "part": {"length": 1.6, "width": 1.0, "mass": 1.0, "heavy_fraction": 0.75},
    "friction": 0.3,
}

# Values no bounded numeric field accepts: non-finite, beyond any range, of another type.
BAD_NUMBERS: tuple[tuple[str, Any], ...] = (
    ("nan", math.nan),
    ("inf", math.inf),
    ("-inf", -math.inf),
    ("1e308", 1e308),
    ("-1e308", -1e308),
    ("10^400", 10**400),
    ("text", "twelve"),
    ("list", [1, 2]),
    ("mapping", {"value": 1}),
    ("null", None),
    ("bool", True),
)

# (path, low, high, integer): the numeric leaves of a run config and their stated ranges.
CONFIG_LEAVES: tuple[tuple[str, float, float, bool], ...] = (
    ("designs.count", 1, 1_000_000, True),
    ("designs.seed", 0, 2**31 - 1, True),
    ("feeder.friction", 0.0, 10.0, False),
    ("feeder.restitution", 0.0, 1.0, False),
    ("feeder.gravity.1", -1e3, 1e3, False),
    ("feeder.part.length", 1.0, 100.0, False),  # >= the part's width
    ("feeder.part.mass", 1e-9, 1e9, False),
    ("feeder.part.heavy_fraction", 0.5, 1.0, False),
    ("feeder.inputs.max_speed", 1e-9, 1e3, False),
    ("feeder.inputs.max_turn", 1e-9, 1e3, False),
    ("feeder.inputs.max_force", 0.0, 1e3, False),
    ("feeder.inputs.max_torque", 0.0, 1e3, False),
    ("planner.step", 1e-4, 10.0, False),
    ("planner.min_steps", 1, 20, True),
    ("planner.max_steps", 1, 10_000, True),
    ("ladder.0.runs", 1, 1000, True),
    ("ladder.0.budget.time", 1e-3, 86400.0, False),
    ("ladder.0.budget.propagations", 1, 10**9, True),
    ("holdout.fraction", 0.0, 1.0, False),
    ("holdout.seed", 0, 2**31 - 1, True),
    ("workers", 1, 1024, True),
    ("max_attempts", 1, 100, True),
)

# The numeric leaves of the free-form scene: (path, low, high, exact). Every value in
# [low, high] is valid (the rest of BASE_SCENE as it is: the start clear of every wall, the goal
# inside the bounds); with ``exact`` the values just outside are not (no value of BAD_NUMBERS
# is valid for any leaf: coordinates must be finite and within +-1e6, and so on).
SCENE_LEAVES: tuple[tuple[str, float, float, bool], ...] = (
    ("bounds.0", -1e6, -1.0, True),  # x_min <= the goal's x_min
    ("bounds.1", 1.0, 1e6, True),
    ("bounds.2", -1e6, -2.5, True),
    ("bounds.3", 2.0, 1e6, True),  # y_max >= the start's y
    ("starts.drop.0", -5.0, 5.0, True),
    ("starts.drop.1", -2.5, 2.5, True),
    ("starts.drop.2", -2 * math.pi, 2 * math.pi, True),
    ("goal.x.0", -5.0, 0.999, False),
    ("goal.x.1", -0.999, 5.0, False),
    ("goal.y.1", -2.499, 2.5, False),
    ("goal.yaw", -math.pi, math.pi, True),
    ("goal.yaw_tol", 1e-6, math.pi, True),
    ("part.length", 0.5, math.hypot(10.0, 5.0), True),  # >= width, <= the bounds' diagonal
    ("part.mass", 1e-9, 1e9, True),
    ("part.heavy_fraction", 0.5, 1.0, True),
    ("friction", 0.0, 10.0, True),
    ("restitution", 0.0, 1.0, True),
    ("gravity.1", -1e3, 1e3, True),
    ("inputs.max_speed", 1e-9, 1e3, True),
    ("inputs.max_force", 0.0, 1e3, True),
    ("obstacles.0.polygon.0.0", -1e6, 5.0, False),
    ("obstacles.2.circle.radius", 1e-9, 3.9, False),  # 3.91 from the start's part
)


@dataclass(frozen=True)
class Case:
    """One command line and the files it reads. ``{dir}`` in ``argv`` is the case's own
    directory. ``setup`` names a preparation the runner does (a FIFO, a damaged database, a
    run holding the directory, a server that is not a scheduler); ``keep`` lists files that
    must be unchanged afterwards; ``valid`` marks a control that must run (exit 0)."""

    family: str
    name: str
    argv: tuple[str, ...]
    files: tuple[tuple[str, str | bytes], ...] = ()
    setup: str = ""
    keep: tuple[str, ...] = ()
    valid: bool = False
    timeout: float | None = None  # a control that does real work (seconds), if over the runner's


@dataclass
class Outcome:
    case: Case
    outcome: str
    returncode: int | None
    seconds: float
    stderr: str = field(repr=False, default="")


def with_value(doc: Any, path: str, value: Any) -> Any:
    """A deep copy of ``doc`` with the leaf at ``path`` (dots; list indices as numbers)
    replaced by ``value``; ``value`` is ``DELETE`` to remove the key."""
    doc = copy.deepcopy(doc)
    *head, last = path.split(".")
    node = doc
    for key in head:
        node = node[int(key)] if isinstance(node, list) else node[key]
    if isinstance(node, list):
        node[int(last)] = value
    elif value is DELETE:
        del node[last]
    else:
        node[last] = value
    return doc


DELETE = object()


def dump(doc: Any) -> str:
    return yaml.safe_dump(doc, sort_keys=False, width=1000)


def _out_of_range(low: float, high: float, integer: bool) -> list[tuple[str, Any]]:
    """Values just outside [low, high] (and a float where an integer is wanted)."""
    if integer:
        values = [("below", int(low) - 1), ("above", int(high) + 1), ("float", 2.5)]
    else:
        step = max(abs(high - low) * 1e-3, 1e-12)
        values = [("below", low - step), ("above", high + step)]
    return values


def _run_argv(config: str = "cfg.yaml", *extra: str) -> tuple[str, ...]:
    return ("run", config, "--out", "{dir}/sweep", "--no-report", "--quiet", *extra)


def _plan_argv(scene: str = "scene.yaml") -> tuple[str, ...]:
    return ("plan", "--scene", scene, "--time", "0.2", "--orientation", "both")


# -- families ------------------------------------------------------------------------------


def document_cases() -> Iterator[Case]:
    """Files that are not sound YAML documents, as a run config and as a scene."""
    bomb = "a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"{k}: &{k} [{', '.join([f'*{p}'] * 9)}]\n"
        for p, k in zip("abcdefgh", "bcdefghi", strict=True)
    )
    anchors = "[&a [x, x, x, x, x, x, x, x, x], " + ", ".join(
        f"&{k} [{', '.join([f'*{p}'] * 9)}]" for p, k in zip("abcdefgh", "bcdefghi", strict=True)
    )
    in_name = "name: " + anchors + ", *i]\n"  # the value a reader turns into text
    bodies: list[tuple[str, str | bytes]] = [
        ("alias-bomb", bomb),
        (
            "alias-bomb-in-name",
            in_name + dump({k: v for k, v in BASE_CONFIG.items() if k != "name"}),
        ),
        ("one-alias", "a: &x 1\nb: *x\n"),
        ("nested-1000", "[" * 1000 + "]" * 1000),
        ("nested-40-mappings", "a: " + "{b: " * 40 + "1" + "}" * 40 + "\n"),
        ("latin-1", b"name: caf\xe9\n"),
        ("utf-16", "name: box\n".encode("utf-16")),
        ("lone-continuation-byte", b"name: \x80\n"),
        ("nul-byte", "name: a\x00b\n"),
        ("empty", ""),
        ("only-comment", "# nothing\n"),
        ("null-document", "null\n"),
        ("top-level-list", "- 1\n- 2\n"),
        ("top-level-scalar", "42\n"),
        ("unclosed-bracket", "bounds: [1, 2\n"),
        ("bad-indent", "a:\n  b: 1\n c: 2\n"),
        ("tab-indent", "a:\n\tb: 1\n"),
        ("python-tag", "!!python/object/apply:os.system ['true']\n"),
        ("binary-tag", "name: !!binary 'AAAA'\n"),
        ("bad-base64", "name: !!binary '%%%'\n"),
        ("set-tag", "name: !!set {a, b}\n"),
        ("two-documents", "a: 1\n---\nb: 2\n"),
        ("long-int", "workers: " + "9" * 5000 + "\n"),
        ("dense-list", "[" + ",".join(["1"] * 400_000) + "]"),
        ("over-1-mib", "# " + "x" * (1 << 20) + "\n"),
        ("unhashable-key", "? [a, b]\n: 1\n"),
        ("mixed-keys", "1: a\nb: 2\n"),
        # YAML that reads as something else than it says (issue 23)
        ("duplicate-designs", dump(BASE_CONFIG) + "designs: {count: 1000000, seed: 1}\n"),
        ("duplicate-nested-key", "designs: {count: 1, count: 2}\n"),
        ("sexagesimal-count", "designs: {count: 1:30, seed: 1}\n"),
        ("octal-count", "designs: {count: 017, seed: 1}\n"),
        ("float-tag-name", "name: !!float 1000\n"),
        ("str-tag", "name: !!str box\n"),
    ]
    for name, body in bodies:
        yield Case("documents", f"config-{name}", _run_argv(), (("cfg.yaml", body),))
        if name == "alias-bomb-in-name":
            scene = {k: v for k, v in BASE_SCENE.items() if k != "name"}
            body = in_name + dump(scene)
        yield Case("documents", f"scene-{name}", _plan_argv(), (("scene.yaml", body),))
    for kind, argv_of in (("config", _run_argv), ("scene", _plan_argv)):
        yield Case("documents", f"{kind}-fifo", argv_of("pipe.yaml"), setup="fifo:pipe.yaml")
        yield Case("documents", f"{kind}-dev-zero", argv_of("/dev/zero"))
        yield Case("documents", f"{kind}-directory", argv_of("/tmp"))
        yield Case("documents", f"{kind}-missing", argv_of("missing.yaml"))
        yield Case("documents", f"{kind}-name-5000", argv_of("x" * 5000 + ".yaml"))
        yield Case("documents", f"{kind}-proc-file", argv_of("/proc/self/status"))


def config_cases() -> Iterator[Case]:
    """Run configs with one field wrong: each numeric leaf out of range or of another type,
    keys missing or unknown, the ladder malformed, the name unusable."""
    for path, low, high, integer in CONFIG_LEAVES:
        for label, value in (*BAD_NUMBERS, *_out_of_range(low, high, integer)):
            doc = with_value(BASE_CONFIG, path, value)
            yield Case("configs", f"{path}={label}", _run_argv(), (("cfg.yaml", dump(doc)),))
    structural: list[tuple[str, Any]] = [
        ("no-designs", with_value(BASE_CONFIG, "designs", DELETE)),
        ("no-count", with_value(BASE_CONFIG, "designs.count", DELETE)),
        ("no-ladder", with_value(BASE_CONFIG, "ladder", DELETE)),
        ("ladder-empty", with_value(BASE_CONFIG, "ladder", [])),
        ("ladder-mapping", with_value(BASE_CONFIG, "ladder", {"level": "geometric"})),
        ("ladder-string", with_value(BASE_CONFIG, "ladder", "geometric")),
        ("level-unknown", with_value(BASE_CONFIG, "ladder.0.level", "physics")),
        ("level-number", with_value(BASE_CONFIG, "ladder.0.level", 3)),
        ("level-missing", with_value(BASE_CONFIG, "ladder.0.level", DELETE)),
        ("planners-empty", with_value(BASE_CONFIG, "ladder.0.planners", [])),
        ("planners-twice", with_value(BASE_CONFIG, "ladder.0.planners", ["rrt", "rrt"])),
        ("planners-twice-case", with_value(BASE_CONFIG, "ladder.0.planners", ["rrt", "RRT"])),
        ("planners-unknown", with_value(BASE_CONFIG, "ladder.0.planners", ["prm"])),
        ("planners-string", with_value(BASE_CONFIG, "ladder.0.planners", "rrt")),
        ("planners-nested", with_value(BASE_CONFIG, "ladder.0.planners", [["rrt"]])),
        ("budget-empty", with_value(BASE_CONFIG, "ladder.0.budget", {})),
        ("budget-number", with_value(BASE_CONFIG, "ladder.0.budget", 5)),
        ("budget-unknown-key", with_value(BASE_CONFIG, "ladder.0.budget", {"seconds": 5})),
        ("rung-unknown-key", with_value(BASE_CONFIG, "ladder.0.speed", 1)),
        ("top-unknown-key", with_value(BASE_CONFIG, "gravity", [0, -9.81])),
        ("feeder-unknown-key", with_value(BASE_CONFIG, "feeder.colour", "red")),
        ("part-unknown-key", with_value(BASE_CONFIG, "feeder.part.density", 1)),
        ("designs-list", with_value(BASE_CONFIG, "designs", [1, 1])),
        ("feeder-list", with_value(BASE_CONFIG, "feeder", [1])),
        ("gravity-short", with_value(BASE_CONFIG, "feeder.gravity", [0.0])),
        ("gravity-string", with_value(BASE_CONFIG, "feeder.gravity", "down")),
        ("gravity-huge-norm", with_value(BASE_CONFIG, "feeder.gravity", [900.0, -900.0])),
        ("min-over-max", with_value(BASE_CONFIG, "planner", {"min_steps": 30, "max_steps": 20})),
        ("width-over-length", with_value(BASE_CONFIG, "feeder.part.width", 2.0)),
        (
            "same-level-twice",
            with_value(BASE_CONFIG, "ladder", [BASE_CONFIG["ladder"][0]] * 2),
        ),
        (
            "ladder-out-of-order",
            with_value(
                BASE_CONFIG,
                "ladder",
                [{**BASE_CONFIG["ladder"][0], "level": "kinematic"}, BASE_CONFIG["ladder"][0]],
            ),
        ),
        ("name-5000", with_value(BASE_CONFIG, "name", "n" * 5000)),
        ("name-slash", with_value(BASE_CONFIG, "name", "../../escape")),
        ("name-dotdot", with_value(BASE_CONFIG, "name", "..")),
        ("name-empty", with_value(BASE_CONFIG, "name", "")),
        ("name-newline", with_value(BASE_CONFIG, "name", "two\nlines")),
        ("name-list", with_value(BASE_CONFIG, "name", ["a"])),
        ("name-mapping", with_value(BASE_CONFIG, "name", {"a": 1})),
        ("deep-in-feeder", with_value(BASE_CONFIG, "feeder.part", _deep(40))),
    ]
    for name, doc in structural:
        yield Case("configs", name, _run_argv(), (("cfg.yaml", dump(doc)),))
    for flags in (("--workers", "0"), ("--workers", "-3"), ("--designs", "0"), ("--designs", "-1")):
        yield Case(
            "configs",
            f"override{'='.join(flags)}",
            _run_argv("cfg.yaml", *flags),
            (("cfg.yaml", dump(BASE_CONFIG)),),
        )
    yield Case(
        "configs",
        "override--designs=10^7",
        _run_argv("cfg.yaml", "--designs", "10000000"),
        (("cfg.yaml", dump(BASE_CONFIG)),),
    )


def _deep(depth: int) -> Any:
    node: Any = 1
    for _ in range(depth):
        node = {"a": node}
    return node


def _star(n: int, cx: float = 0.0, cy: float = -3.5) -> list[list[float]]:
    points = []
    for k in range(n):
        angle = 2 * math.pi * k / n
        radius = 1.0 if k % 2 == 0 else 0.5
        points.append(
            [round(cx + radius * math.cos(angle), 9), round(cy + radius * math.sin(angle) * 0.4, 9)]
        )
    return points


def scene_cases() -> Iterator[Case]:
    """Scenes with one field wrong, and scenes that are well-typed but physically nonsense."""
    for path, low, high, exact in SCENE_LEAVES:
        near = _out_of_range(low, high, False) if exact else []
        for label, value in (*BAD_NUMBERS, *near):
            doc = with_value(BASE_SCENE, path, value)
            yield Case("scenes", f"{path}={label}", _plan_argv(), (("scene.yaml", dump(doc)),))
    walls = BASE_SCENE["obstacles"]
    nonsense: list[tuple[str, Any]] = [
        ("start-in-roof", with_value(BASE_SCENE, "starts.drop", [0.0, 3.5, 0.0])),
        ("start-in-circle", with_value(BASE_SCENE, "starts.drop", [4.0, 0.0, 0.0])),
        ("start-outside-bounds", with_value(BASE_SCENE, "starts.drop", [9.0, 0.0, 0.0])),
        ("start-yaw-1e308", with_value(BASE_SCENE, "starts.drop", [0.0, 0.0, 1e308])),
        ("goal-outside-bounds", with_value(BASE_SCENE, "goal.x", [20, 30])),
        (
            "goal-in-obstacle",
            with_value(
                with_value(BASE_SCENE, "bounds", [-5, 5, -2.5, 3.9]),
                "goal",
                {"x": [-1, 1], "y": [3.2, 3.8], "yaw": 0.0, "yaw_tol": 0.5},
            ),
        ),
        ("part-100x50", with_value(BASE_SCENE, "part", {"length": 100, "width": 50})),
        ("bounds-1e308", with_value(BASE_SCENE, "bounds", [-1e308, 1e308, -1e308, 1e308])),
        ("bounds-inverted", with_value(BASE_SCENE, "bounds", [5, -5, -2.5, 2.5])),
        ("gravity-1e308", with_value(BASE_SCENE, "gravity", [0.0, -1e308])),
        (
            "circle-1e6-over-start",
            with_value(
                BASE_SCENE, "obstacles", [*walls, {"circle": {"centre": [0, 2], "radius": 1e6}}]
            ),
        ),
        (
            "circle-1e5-over-start",
            with_value(
                BASE_SCENE, "obstacles", [*walls, {"circle": {"centre": [0, 2], "radius": 1e5}}]
            ),
        ),
        (
            "polygon-1e5-convex",
            with_value(BASE_SCENE, "obstacles", [*walls, {"polygon": _regular(100_000)}]),
        ),
        (
            "polygon-1e5-star",
            with_value(BASE_SCENE, "obstacles", [*walls, {"polygon": _star(100_000)}]),
        ),
        (
            "polygon-1000-star",
            with_value(BASE_SCENE, "obstacles", [*walls, {"polygon": _star(1000)}]),
        ),
        (
            "polygons-20-stars-of-200",
            with_value(
                BASE_SCENE,
                "obstacles",
                [*walls, *({"polygon": _star(200, 3.0 * k - 30, -3.5)} for k in range(20))],
            ),
        ),
        (
            "starts-10000",
            with_value(BASE_SCENE, "starts", {f"s{i}": [0, 0, 0] for i in range(10_000)}),
        ),
        ("starts-empty", with_value(BASE_SCENE, "starts", {})),
        ("starts-list", with_value(BASE_SCENE, "starts", [[0, 0, 0]])),
        ("start-short", with_value(BASE_SCENE, "starts.drop", [0, 0])),
        (
            "obstacles-2000-circles",
            with_value(
                BASE_SCENE, "obstacles", [{"circle": {"centre": [0, -9], "radius": 1}}] * 2000
            ),
        ),
        ("obstacles-empty", with_value(BASE_SCENE, "obstacles", [])),
        (
            "polygon-self-crossing",
            with_value(BASE_SCENE, "obstacles.0.polygon", [[-6, -4], [6, -3], [6, -4], [-6, -3]]),
        ),
        (
            "polygon-zero-area",
            with_value(BASE_SCENE, "obstacles.0.polygon", [[0, -4], [1, -4], [2, -4]]),
        ),
        ("polygon-two-points", with_value(BASE_SCENE, "obstacles.0.polygon", [[0, -4], [1, -4]])),
        ("polygon-point-nan", with_value(BASE_SCENE, "obstacles.0.polygon.0", [math.nan, -4])),
        ("polygon-point-triple", with_value(BASE_SCENE, "obstacles.0.polygon.0", [-6, -4, 0])),
        ("circle-no-radius", with_value(BASE_SCENE, "obstacles.2.circle", {"centre": [4, 0]})),
        (
            "obstacle-both-kinds",
            with_value(BASE_SCENE, "obstacles.2.polygon", [[0, 0], [1, 0], [0, 1]]),
        ),
        ("goal-inverted", with_value(BASE_SCENE, "goal.x", [1, -1])),
        ("goal-missing-yaw", with_value(BASE_SCENE, "goal.yaw", DELETE)),
        ("no-goal", with_value(BASE_SCENE, "goal", DELETE)),
        ("no-bounds", with_value(BASE_SCENE, "bounds", DELETE)),
        ("unknown-key", with_value(BASE_SCENE, "colour", "red")),
        ("name-5000", with_value(BASE_SCENE, "name", "n" * 5000)),
        ("name-slash", with_value(BASE_SCENE, "name", "../../../tmp/escape")),
        ("label-5000", with_value(BASE_SCENE, "obstacles.0.label", "l" * 5000)),
        ("width-over-length", with_value(BASE_SCENE, "part.width", 2.0)),
        ("feeder-and-obstacles", {**BASE_SCENE, "feeder": {"preset": "table3"}}),
        ("feeder-unknown-preset", with_value(BASE_FEEDER_SCENE, "feeder.preset", "fig99")),
        ("feeder-preset-5000", with_value(BASE_FEEDER_SCENE, "feeder.preset", "p" * 5000)),
        ("feeder-design-partial", with_value(BASE_FEEDER_SCENE, "feeder", {"design": {"a": 1.1}})),
        ("feeder-with-bounds", with_value(BASE_FEEDER_SCENE, "bounds", [-5, 5, -5, 5])),
        ("feeder-part-100x50", with_value(BASE_FEEDER_SCENE, "part", {"length": 100, "width": 50})),
        ("feeder-part-mass-0", with_value(BASE_FEEDER_SCENE, "part.mass", 0)),
        ("feeder-part-length-1e308", with_value(BASE_FEEDER_SCENE, "part.length", 1e308)),
        ("feeder-gravity-1e308", with_value(BASE_FEEDER_SCENE, "gravity", [0, 1e308])),
    ]
    for name, doc in nonsense:
        body = (("scene.yaml", dump(doc)),)
        yield Case("scenes", name, _plan_argv(), body)
        if name.startswith(("start-", "goal-", "part-", "bounds-", "gravity-", "circle-")):
            yield Case(
                "scenes",
                f"draw:{name}",
                ("draw", "--scene", "scene.yaml", "--out", "{dir}/p.png"),
                body,
            )
            yield Case(
                "scenes",
                f"simulate:{name}",
                ("simulate", "--scene", "scene.yaml", "--time", "0.1"),
                body,
            )


def _regular(n: int) -> list[list[float]]:
    return [
        [round(math.cos(2 * math.pi * k / n), 9), round(math.sin(2 * math.pi * k / n) - 10, 9)]
        for k in range(n)
    ]


def design_cases() -> Iterator[Case]:
    """``--design``: empty, unknown, too long, not 12 numbers, non-finite, out of range."""
    good = [
        1.1,
        1.1086,
        0.7979,
        3.0078,
        -1.9,
        -0.9849,
        1.0098,
        0.733,
        2.0388,
        0.101,
        0.4673,
        1.0472,
    ]

    def values(index: int, value: str) -> str:
        parts = [str(v) for v in good]
        parts[index] = value
        return ",".join(parts)

    specs = [
        ("empty", ""),
        ("blank", "   "),
        ("unknown", "fig99"),
        ("upper-case", "TABLE3"),
        ("name-5000", "d" * 5000),
        ("three-values", "1,2,3"),
        ("thirteen-values", ",".join(str(v) for v in [*good, 1.0])),
        ("commas-only", ",,,,,,,,,,,"),
        ("text-value", values(3, "abc")),
        ("nan", values(0, "nan")),
        ("inf", values(1, "inf")),
        ("1e308", values(2, "1e308")),
        ("-1e308", values(4, "-1e308")),
        ("1e999", values(5, "1e999")),
        ("negative-radius", values(9, "-0.1")),
        ("huge-angle", values(10, "100")),
        ("all-zero", ",".join(["0"] * 12)),
    ]
    for name, spec in specs:
        yield Case("designs", f"plan:{name}", ("plan", "--design", spec, "--time", "0.2"))
        yield Case("designs", f"draw:{name}", ("draw", "--design", spec, "--out", "{dir}/d.png"))
        yield Case("designs", f"simulate:{name}", ("simulate", "--design", spec, "--time", "0.1"))


def command_line_cases() -> Iterator[Case]:
    """Flags out of range or of the wrong type, unknown flags and commands."""
    cfg = (("cfg.yaml", dump(BASE_CONFIG)),)
    lines: list[tuple[str, tuple[str, ...], tuple[tuple[str, str | bytes], ...]]] = [
        ("no-command", (), ()),
        ("unknown-command", ("optimise",), ()),
        ("unknown-flag", ("plan", "--speed", "3"), ()),
        ("plan-time-negative", ("plan", "--time", "-1"), ()),
        ("plan-time-zero", ("plan", "--time", "0"), ()),
        ("plan-time-nan", ("plan", "--time", "nan"), ()),
        ("plan-time-inf", ("plan", "--time", "inf"), ()),
        ("plan-time-1e9", ("plan", "--time", "1e9"), ()),
        ("plan-time-text", ("plan", "--time", "soon"), ()),
        ("plan-seed-negative", ("plan", "--seed", "-1", "--time", "0.2"), ()),
        ("plan-seed-2^40", ("plan", "--seed", str(2**40), "--time", "0.2"), ()),
        ("plan-level-unknown", ("plan", "--level", "quantum"), ()),
        ("plan-planner-unknown", ("plan", "--planner", "prm"), ()),
        ("plan-orientation-unknown", ("plan", "--orientation", "sideways", "--time", "0.2"), ()),
        ("plan-design-and-scene", ("plan", "--design", "table3", "--scene", "s.yaml"), ()),
        ("simulate-step-zero", ("simulate", "--step", "0"), ()),
        ("simulate-step-nan", ("simulate", "--step", "nan"), ()),
        ("simulate-step-1", ("simulate", "--step", "1"), ()),
        ("simulate-time-negative", ("simulate", "--time", "-5"), ()),
        ("simulate-samples-negative", ("simulate", "--samples", "-1"), ()),
        ("simulate-samples-10^9", ("simulate", "--samples", str(10**9)), ()),
        ("simulate-target-2", ("simulate", "--samples", "5", "--target", "2"), ()),
        ("simulate-target-nan", ("simulate", "--samples", "5", "--target", "nan"), ()),
        ("simulate-seed-negative", ("simulate", "--samples", "5", "--seed", "-1"), ()),
        ("run-workers-0", _run_argv("cfg.yaml", "--workers", "0"), cfg),
        ("run-workers-10^6", _run_argv("cfg.yaml", "--workers", "1000000"), cfg),
        ("run-designs-text", _run_argv("cfg.yaml", "--designs", "many"), cfg),
        ("run-executor-unknown", _run_argv("cfg.yaml", "--executor", "slurm"), cfg),
        ("run-unknown-shipped-name", ("run", "nosuchconfig", "--out", "{dir}/sweep"), ()),
        ("run-two-configs", ("run", "cfg.yaml", "cfg.yaml"), cfg),
        ("report-missing-dir", ("report", "{dir}/nothing-here"), ()),
        ("report-a-file", ("report", "cfg.yaml"), cfg),
        ("report-name-5000", ("report", "r" * 5000), ()),
        ("feasibility-levels-one", ("feasibility", "--levels", "geometric"), ()),
        ("feasibility-levels-unknown", ("feasibility", "--levels", "a,b"), ()),
        ("feasibility-designs-0", ("feasibility", "--designs", "0"), ()),
        (
            "feasibility-designs-10^12",
            ("feasibility", "--designs", str(10**12), "--time", "0.1"),
            (),
        ),
        ("feasibility-workers-0", ("feasibility", "--workers", "0"), ()),
        ("feasibility-planner-unknown", ("feasibility", "--planner", "prm"), ()),
        ("feasibility-seed-0", ("feasibility", "--seed", "0"), ()),
        ("calibrate-runs-0", ("calibrate", "--runs", "0"), ()),
        ("calibrate-quick-alone", ("calibrate", "--quick"), ()),
        ("calibrate-part-no-out", ("calibrate", "--part"), ()),
        (
            "calibrate-part-workers-0",
            ("calibrate", "--part", "--out", "{dir}/c", "--workers", "0"),
            (),
        ),
        ("draw-no-out", ("draw", "--design", "table3"), ()),
    ]
    for name, argv, files in lines:
        yield Case("command-lines", name, argv, files)


def out_dir_cases() -> Iterator[Case]:
    """``--out`` that cannot be a directory to write in."""
    cfg = (
        ("cfg.yaml", dump(BASE_CONFIG)),
        ("file.txt", "a file\n"),
        ("scene.yaml", dump(BASE_SCENE)),
    )
    targets = [
        ("existing-file", "{dir}/file.txt"),
        ("under-a-file", "{dir}/file.txt/sub"),
        ("proc", "/proc"),
        ("under-proc", "/proc/partfeeder-out"),
        ("under-sys", "/sys/partfeeder-out"),
        ("dev-null", "/dev/null"),
        ("name-5000", "{dir}/" + "o" * 5000),
        ("component-300", "{dir}/" + "c" * 300 + "/x"),
    ]
    commands: list[tuple[str, Callable[[str], tuple[str, ...]]]] = [
        ("run", lambda out: ("run", "cfg.yaml", "--out", out, "--no-report", "--quiet")),
        ("plan", lambda out: ("plan", "--design", "table3", "--time", "0.2", "--out", out)),
        ("simulate", lambda out: ("simulate", "--design", "table3", "--time", "0.1", "--out", out)),
        (
            "feasibility",
            lambda out: (
                "feasibility",
                "--designs",
                "1",
                "--time",
                "0.1",
                "--workers",
                "1",
                "--out",
                out,
            ),
        ),
    ]
    for command, argv_of in commands:
        for name, target in targets:
            yield Case(
                "out-dirs", f"{command}:{name}", argv_of(target), cfg, keep=("cfg.yaml", "file.txt")
            )
    yield Case(
        "out-dirs",
        "run:the-config-itself",
        ("run", "cfg.yaml", "--out", "cfg.yaml", "--quiet"),
        cfg,
        keep=("cfg.yaml",),
    )
    yield Case(
        "out-dirs",
        "run:default-out-under-a-file",
        ("run", "{dir}/cfg.yaml", "--quiet"),
        (*cfg, ("sweep", "a file named like the default sweep directory\n")),
        keep=("sweep", "cfg.yaml"),
    )
    yield Case(
        "out-dirs",
        "plan:scene-itself",
        ("plan", "--scene", "scene.yaml", "--time", "0.2", "--out", "scene.yaml"),
        cfg,
        keep=("scene.yaml",),
    )
    draws = [
        ("draw:scene-itself", "scene.yaml"),
        ("draw:a-directory", "{dir}"),
        ("draw:bad-suffix", "{dir}/picture.yaml"),
        ("draw:no-suffix", "{dir}/picture"),
        ("draw:under-proc", "/proc/partfeeder.png"),
        ("draw:under-a-file", "{dir}/file.txt/p.png"),
        ("draw:name-5000", "{dir}/" + "p" * 5000 + ".png"),
    ]
    for name, target in draws:
        yield Case(
            "out-dirs",
            name,
            ("draw", "--scene", "scene.yaml", "--out", target),
            cfg,
            keep=("scene.yaml", "file.txt"),
        )


def scheduler_cases() -> Iterator[Case]:
    """``--executor dask`` with a scheduler address nothing answers at, or that is not one."""
    cfg = (("cfg.yaml", dump(BASE_CONFIG)),)
    addresses = [
        ("refused-port", "tcp://127.0.0.1:1"),
        ("refused-port-ipv6", "tcp://[::1]:1"),
        ("unknown-host", "tcp://no-such-host.invalid:8786"),
        ("no-scheme-refused", "127.0.0.1:1"),
        ("not-a-scheduler", "tcp://127.0.0.1:{garbage_port}"),
        ("port-99999", "tcp://127.0.0.1:99999"),
        ("port-text", "tcp://127.0.0.1:port"),
        ("http-scheme", "http://127.0.0.1:8786"),
        ("empty", ""),
        ("no-host", "tcp://:8786"),
        ("nonsense", "nonsense::://"),
    ]
    for name, address in addresses:
        setup = "garbage-server" if "garbage_port" in address else ""
        argv = _run_argv("cfg.yaml", "--executor", "dask", "--scheduler", address)
        yield Case("scheduler", name, argv, cfg, setup=setup)
    yield Case(
        "scheduler", "dask-without-address", _run_argv("cfg.yaml", "--executor", "dask"), cfg
    )
    yield Case(
        "scheduler",
        "address-without-dask",
        _run_argv("cfg.yaml", "--scheduler", "tcp://127.0.0.1:1"),
        cfg,
    )


DB_DAMAGE = (
    "truncate-100",
    "truncate-one-page",
    "truncate-half",
    "truncate-last-page",
    "truncate-minus-100",
    "garbage-header-16",
    "garbage-header-100",
    "zero-header",
    "garbage-page-2",
    "garbage-page-3",
    "garbage-last-page",
    "garbage-all-pages",
    *(
        f"data-page-{table}@{seed}"
        for table in ("runs", "designs", "evaluations", "meta")
        for seed in range(5)
    ),
    "schema-page-damage",
    "wrong-schema-other-tables",
    "wrong-schema-missing-column",
    "wrong-schema-extra-table",
    "text-file",
    "directory",
    "fifo",
    "empty-file",  # for report only: an empty file is where a new run starts
)


# A valid optimisation config that finishes in seconds: one Powell evaluation of one trial.
BASE_OPTIMIZE: dict[str, Any] = {
    "name": "corpus-optimize",
    "feeder": {"friction": 0.05, "restitution": 0.3},
    "objective": {"trials": 1, "seed": 0, "weight": 5.0, "step": 0.001, "t_max": 10.0},
    "perturbations": {
        "position": 0.05,
        "yaw": 0.05,
        "speed": 0.05,
        "friction": 0.2,
        "tolerance": 0.01,
    },
    "start": {"presets": ["table3"], "sweep_best": 6},
    "methods": [{"method": "powell", "budget": 1, "seeds": [0]}],
    "final": {"trials": 1, "seed": 1000, "target": 0.9},
    "workers": 1,
    "max_attempts": 1,
}

# (path, low, high, integer): the numeric leaves of an optimisation config and their ranges.
OPTIMIZE_LEAVES: tuple[tuple[str, float, float, bool], ...] = (
    ("objective.trials", 1, 10_000, True),
    ("objective.seed", 0, 2**31 - 1, True),
    ("objective.weight", 0.0, 1e6, False),
    ("objective.step", 1e-6, 0.1, False),
    ("objective.t_max", 1e-3, 3600.0, False),
    ("perturbations.position", 0.0, 0.5, False),
    ("perturbations.yaw", 0.0, 0.5, False),
    ("perturbations.speed", 0.0, 1.0, False),
    ("perturbations.friction", 0.0, 0.9, False),
    ("perturbations.tolerance", 0.0, 0.1, False),
    ("start.sweep_best", 0, 1000, True),
    ("methods.0.budget", 1, 1_000_000, True),
    ("methods.0.seeds.0", 0, 2**31 - 1, True),
    ("final.trials", 1, 10_000, True),
    ("final.seed", 0, 2**31 - 1, True),
    ("final.target", 0.0, 1.0, False),
    ("workers", 1, 1024, True),
    ("max_attempts", 1, 100, True),
)


def _optimize_argv(config: str = "opt.yaml", *extra: str) -> tuple[str, ...]:
    return ("optimize", config, "--out", "{dir}/opt", "--no-report", "--quiet", *extra)


def optimize_cases() -> Iterator[Case]:
    """Optimisation configs with one field wrong (each numeric leaf out of range or of another
    type, the methods and starts malformed, keys unknown), and bad ``--from`` directories."""
    for path, low, high, integer in OPTIMIZE_LEAVES:
        for label, value in (*BAD_NUMBERS, *_out_of_range(low, high, integer)):
            doc = with_value(BASE_OPTIMIZE, path, value)
            yield Case("optimize", f"{path}={label}", _optimize_argv(), (("opt.yaml", dump(doc)),))
    structural: list[tuple[str, Any]] = [
        ("no-methods", with_value(BASE_OPTIMIZE, "methods", DELETE)),
        ("methods-empty", with_value(BASE_OPTIMIZE, "methods", [])),
        ("methods-mapping", with_value(BASE_OPTIMIZE, "methods", {"method": "powell"})),
        ("method-unknown", with_value(BASE_OPTIMIZE, "methods.0.method", "fmincon")),
        ("method-number", with_value(BASE_OPTIMIZE, "methods.0.method", 3)),
        ("method-missing", with_value(BASE_OPTIMIZE, "methods.0.method", DELETE)),
        ("budget-missing", with_value(BASE_OPTIMIZE, "methods.0.budget", DELETE)),
        ("population-small", with_value(BASE_OPTIMIZE, "methods.0.population", 4)),
        ("population-text", with_value(BASE_OPTIMIZE, "methods.0.population", "big")),
        ("seeds-empty", with_value(BASE_OPTIMIZE, "methods.0.seeds", [])),
        ("seeds-string", with_value(BASE_OPTIMIZE, "methods.0.seeds", "0")),
        ("seeds-twice", with_value(BASE_OPTIMIZE, "methods.0.seeds", [1, 1])),
        ("method-twice", with_value(BASE_OPTIMIZE, "methods", BASE_OPTIMIZE["methods"] * 2)),
        ("presets-unknown", with_value(BASE_OPTIMIZE, "start.presets", ["fig99"])),
        ("presets-string", with_value(BASE_OPTIMIZE, "start.presets", "table3")),
        ("presets-none", with_value(BASE_OPTIMIZE, "start.presets", [])),
        ("method-unknown-key", with_value(BASE_OPTIMIZE, "methods.0.speed", 1)),
        ("objective-unknown-key", with_value(BASE_OPTIMIZE, "objective.mu", 0.1)),
        ("final-unknown-key", with_value(BASE_OPTIMIZE, "final.drops", 10)),
        ("top-unknown-key", with_value(BASE_OPTIMIZE, "ladder", [])),
        ("feeder-unknown-key", with_value(BASE_OPTIMIZE, "feeder.colour", "red")),
        ("feeder-friction", with_value(BASE_OPTIMIZE, "feeder.friction", -1)),
        ("name-slash", with_value(BASE_OPTIMIZE, "name", "../../escape")),
        ("not-a-mapping", [1, 2, 3]),
    ]
    for name, doc in structural:
        yield Case("optimize", name, _optimize_argv(), (("opt.yaml", dump(doc)),))
    cfg = (("opt.yaml", dump(BASE_OPTIMIZE)),)
    for name, extra in (
        ("from-missing", ("--from", "{dir}/nowhere")),
        ("from-file", ("--from", "opt.yaml")),
        ("from-empty-dir", ("--from", "{dir}")),
        ("workers-0", ("--workers", "0")),
        ("scheduler-without-dask", ("--scheduler", "tcp://127.0.0.1:1")),
        ("dask-without-scheduler", ("--executor", "dask")),
    ):
        yield Case("optimize", name, _optimize_argv("opt.yaml", *extra), cfg)


def database_cases() -> Iterator[Case]:
    """A results database (a real sweep's) damaged in one way, read by ``report`` and by a
    ``run`` that would resume it. The database must be left as it was."""
    cfg = (("cfg.yaml", dump(BASE_CONFIG)),)
    for kind in DB_DAMAGE:
        for command, argv in (
            ("report", ("report", "{dir}/sweep", "--json")),
            ("run", _run_argv()),
        ):
            if command == "run" and kind == "empty-file":
                continue
            keep = () if kind in ("directory", "fifo") else ("sweep/results.sqlite",)
            yield Case("database", f"{command}:{kind}", argv, cfg, setup=f"db:{kind}", keep=keep)


def lock_cases() -> Iterator[Case]:
    """A second ``partfeeder run`` on a directory another run is working in."""
    cfg = (("cfg.yaml", dump(BASE_CONFIG)),)
    for name in ("second-run", "second-run-json"):
        extra = ("--json",) if name.endswith("json") else ()
        yield Case("lock", name, _run_argv("cfg.yaml", *extra), cfg, setup="held")


def control_cases() -> Iterator[Case]:
    """Valid inputs: each must run (exit 0), so the runner can tell acceptance from errors."""
    cfg = (("cfg.yaml", dump(BASE_CONFIG)),)
    yield Case("controls", "run", _run_argv(), cfg, valid=True)
    yield Case(
        "controls", "plan-scene", _plan_argv(), (("scene.yaml", dump(BASE_SCENE)),), valid=True
    )
    yield Case(
        "controls",
        "plan-feeder-scene",
        ("plan", "--scene", "scene.yaml", "--time", "0.2"),
        (("scene.yaml", dump(BASE_FEEDER_SCENE)),),
        valid=True,
    )
    yield Case(
        "controls",
        "draw-design",
        ("draw", "--design", "table3", "--out", "{dir}/t.png"),
        valid=True,
    )
    yield Case(
        "controls", "report", ("report", "{dir}/sweep", "--json"), setup="db:none", valid=True
    )
    yield Case("controls", "run-after-killed-run", _run_argv(), cfg, setup="stale-lock", valid=True)
    yield Case(
        "controls", "run-on-empty-database", _run_argv(), cfg, setup="db:empty-file", valid=True
    )
    yield Case(
        "controls",
        "optimize",
        _optimize_argv(),
        (("opt.yaml", dump(BASE_OPTIMIZE)),),
        valid=True,
        timeout=OPTIMIZE_CONTROL_S,
    )


# -- issue 23, the small input findings (a block of its own: other additions go elsewhere) ----

# /etc/shadow's form: the tab and ': ' on the second line break YAML; the file's text must
# never be in the error (test_bad_input.py checks that; here: one clean line).
SHADOW_TEXT = (
    "root:$6$SECRETsalt$SECREThashhash:19000:0:99999:7:::\n"
    "operator:\t$6$SECRET2salt: 19000:0:99999:7:::\n"
)


def small_input_cases() -> Iterator[Case]:
    """Issue 23's small findings: non-YAML text as every kind of YAML file, seeds beyond
    2^64 and empty level names on every command that takes them, bench's arguments that it
    refused only after starting work, names with white space at an end."""
    for label, text in (("shadow", SHADOW_TEXT), ("repeated-secret-key", "k: 1\nk: 2\n")):
        files = (("f.yaml", text),)
        yield Case("issue-23", f"config-{label}", _run_argv("f.yaml"), files)
        yield Case("issue-23", f"scene-{label}", _plan_argv("f.yaml"), files)
        yield Case("issue-23", f"optimize-{label}", _optimize_argv("f.yaml"), files)
        yield Case("issue-23", f"stress-case-{label}", ("stress", "--replay", "f.yaml"), files)
    big = str(2**64)
    lines: list[tuple[str, tuple[str, ...]]] = [
        ("stress-seed-2^64", ("stress", "--seed", big, "--cases", "1")),
        ("stress-seed-negative", ("stress", "--seed", "-1", "--cases", "1")),
        ("simulate-seed-2^64", ("simulate", "--samples", "5", "--seed", big)),
        ("plan-seed-2^64", ("plan", "--seed", big, "--time", "0.2")),
        (
            "stress-levels-empty-name",
            ("stress", "--levels", "geometric,,geometric", "--cases", "1"),
        ),
        ("stress-levels-twice", ("stress", "--levels", "geometric,geometric", "--cases", "1")),
        ("feasibility-levels-empty-name", ("feasibility", "--levels", "geometric,,geometric")),
        ("bench-out-a-file", ("bench", "--quick", "--out", "{dir}/file.txt")),
        ("bench-out-under-a-file", ("bench", "--quick", "--out", "{dir}/file.txt/sub")),
        ("bench-out-proc", ("bench", "--quick", "--out", "/proc/partfeeder-bench")),
        ("bench-seed-negative", ("bench", "--quick", "--seed", "-1")),
        ("bench-seed-2^64", ("bench", "--quick", "--seed", big, "--out", "{dir}/b")),
        ("bench-level-seed-negative", ("bench", "--level", "geometric", "--seed", "-1")),
    ]
    for name, argv in lines:
        yield Case("issue-23", name, argv, (("file.txt", "a file\n"),))
    for name in (" corpus", "corpus ", "\u00a0corpus", "corpus\u3000"):
        shown = name.replace("\u00a0", "<nbsp>").replace("\u3000", "<ideographic space>")
        cfg = (("cfg.yaml", dump({**BASE_CONFIG, "name": name})),)
        yield Case("issue-23", f"config-name-{shown!r}", _run_argv(), cfg)
        opt = (("opt.yaml", dump({**BASE_OPTIMIZE, "name": name})),)
        yield Case("issue-23", f"optimize-name-{shown!r}", _optimize_argv(), opt)
        scene = (("scene.yaml", dump({**BASE_SCENE, "name": name})),)
        yield Case("issue-23", f"scene-name-{shown!r}", _plan_argv(), scene)


# -- end of issue 23's small findings ---------------------------------------------------------


FAMILIES: dict[str, Callable[[], Iterator[Case]]] = {
    "documents": document_cases,
    "configs": config_cases,
    "scenes": scene_cases,
    "designs": design_cases,
    "command-lines": command_line_cases,
    "out-dirs": out_dir_cases,
    "scheduler": scheduler_cases,
    "database": database_cases,
    "lock": lock_cases,
    "optimize": optimize_cases,
    "issue-23": small_input_cases,  # issue 23's small findings
    "controls": control_cases,
}


def corpus(families: tuple[str, ...] = tuple(FAMILIES)) -> list[Case]:
    """Every case of ``families``, in a fixed order."""
    return [case for family in families for case in FAMILIES[family]()]


def sample(cases: list[Case], per_family: int, seed: int) -> list[Case]:
    """At most ``per_family`` cases of each family, drawn with ``seed``."""
    rng = random.Random(seed)
    chosen: list[Case] = []
    for family in dict.fromkeys(c.family for c in cases):
        mine = [c for c in cases if c.family == family]
        chosen += rng.sample(mine, min(per_family, len(mine)))
    return chosen


# -- preparing a case ----------------------------------------------------------------------


def damage_database(path: Path, kind: str, seed: int = 0) -> None:
    """Damage the SQLite file at ``path`` in the way ``kind`` names (see ``DB_DAMAGE``)."""
    kind, _, given = kind.partition("@")
    seed = int(given) if given else seed
    rng = random.Random(f"{kind}-{seed}")
    data = bytearray(path.read_bytes())
    page = int.from_bytes(data[16:18], "big") or 65536
    pages = len(data) // page

    def garbage(n: int) -> bytes:
        return bytes(rng.randrange(256) for _ in range(n))

    def table_page(table: str) -> int:
        db = sqlite3.connect(path)
        try:
            root = db.execute(
                "SELECT rootpage FROM sqlite_master WHERE name = ?", (table,)
            ).fetchone()
        finally:
            db.close()
        return int(root[0])

    if kind.startswith("truncate-"):
        size = {
            "truncate-100": 100,
            "truncate-one-page": page,
            "truncate-half": (pages // 2) * page,
            "truncate-last-page": (pages - 1) * page,
            "truncate-minus-100": len(data) - 100,
        }[kind]
        data = data[:size]
    elif kind == "garbage-header-16":
        data[:16] = garbage(16)
    elif kind == "garbage-header-100":
        data[:100] = garbage(100)
    elif kind == "zero-header":
        data[:100] = bytes(100)
    elif kind.startswith("garbage-page-") or kind == "garbage-last-page":
        number = pages if kind == "garbage-last-page" else int(kind.rsplit("-", 1)[1])
        start = (number - 1) * page
        data[start : start + page] = garbage(page)
    elif kind == "garbage-all-pages":
        data[page:] = garbage(len(data) - page)
    elif kind.startswith("data-page-") or kind == "schema-page-damage":
        table = kind.removeprefix("data-page-") if kind.startswith("data-") else "sqlite_master"
        number = 1 if table == "sqlite_master" else table_page(table)
        start = (number - 1) * page
        header = 100 if number == 1 else 0
        cells = int.from_bytes(data[start + header + 5 : start + header + 7], "big") or page
        # the cell content area (the records themselves): 16 bytes of garbage at a seeded place
        where = start + rng.randrange(cells, page - 16)
        data[where : where + 16] = garbage(16)
    elif kind.startswith("wrong-schema-"):
        if kind == "wrong-schema-other-tables":
            path.unlink()
        script = {
            "wrong-schema-other-tables": "CREATE TABLE photos (id INTEGER, name TEXT);",
            "wrong-schema-missing-column": "ALTER TABLE runs DROP COLUMN exit_time_s;",
            "wrong-schema-extra-table": "CREATE TABLE extra (x INTEGER);",
        }[kind]
        db = sqlite3.connect(path)
        try:
            db.executescript(script)
        finally:
            db.close()
        return
    elif kind == "text-file":
        data = bytearray(b"these are not the results you are looking for\n" * 50)
    elif kind == "empty-file":
        data = bytearray()
    elif kind == "directory":
        path.unlink()
        path.mkdir()
        return
    elif kind == "fifo":
        path.unlink()
        os.mkfifo(path)
        return
    elif kind == "none":
        return
    else:
        raise ValueError(f"unknown damage {kind!r}")
    path.write_bytes(bytes(data))


def make_template_database(workdir: Path, env: dict[str, str]) -> Path:
    """A real sweep's results database (BASE_CONFIG, run by the code under test)."""
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "cfg.yaml").write_text(dump(BASE_CONFIG))
    argv = [sys.executable, "-c", CLI, *_run_argv()]
    argv = [a.replace("{dir}", str(workdir)) for a in argv]
    done = subprocess.run(argv, cwd=workdir, env=env, capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise RuntimeError(f"the template sweep failed: {done.stderr[-2000:]}")
    db = sqlite3.connect(workdir / "sweep" / "results.sqlite")
    db.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    db.close()
    return workdir / "sweep" / "results.sqlite"


GARBAGE_SERVER = """
import socket, sys
server = socket.socket()
server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
server.bind(("127.0.0.1", 0))
server.listen(16)
print(server.getsockname()[1], flush=True)
while True:
    conn, _ = server.accept()
    try:
        conn.sendall(b"HTTP/1.0 200 OK\\r\\n\\r\\nthis is not a dask scheduler\\n" * 4)
    except OSError:
        pass
    conn.close()
"""

HOLDER_CONFIG = {**BASE_CONFIG, "designs": {"count": 400, "seed": 1}}


@dataclass
class Environment:
    """What the cases share: the environment of the code under test, a template database,
    helper processes (a garbage server)."""

    env: dict[str, str]
    scratch: Path
    template: Path | None = None
    garbage_port: int | None = None
    helpers: list[subprocess.Popen] = field(default_factory=list)

    def close(self) -> None:
        for process in self.helpers:
            _kill_group(process.pid)
            process.wait()


def _kill_group(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def prepare(
    case: Case, directory: Path, shared: Environment
) -> tuple[list[str], list[subprocess.Popen]]:
    """Write the case's files, do its setup; returns its argv and processes to stop after."""
    directory.mkdir(parents=True, exist_ok=True)
    for name, body in case.files:
        target = directory / name
        if isinstance(body, bytes):
            target.write_bytes(body)
        else:
            target.write_text(body)
    after: list[subprocess.Popen] = []
    kind, _, arg = case.setup.partition(":")
    if kind == "fifo":
        os.mkfifo(directory / arg)
    elif kind == "db":
        assert shared.template is not None
        (directory / "sweep").mkdir(exist_ok=True)
        target = directory / "sweep" / "results.sqlite"
        shutil.copyfile(shared.template, target)
        damage_database(target, arg)
    elif kind == "garbage-server":
        if shared.garbage_port is None:
            server = subprocess.Popen(
                [sys.executable, "-c", GARBAGE_SERVER],
                stdout=subprocess.PIPE,
                text=True,
                start_new_session=True,
            )
            assert server.stdout is not None
            shared.garbage_port = int(server.stdout.readline())
            shared.helpers.append(server)
    elif kind in ("held", "stale-lock"):
        # held: a long run (400 designs) holds the directory; stale-lock: a run of the case's
        # own config killed with SIGKILL as soon as its database exists leaves the directory
        # (and, with the fix, its lock file naming a dead pid) behind
        config = HOLDER_CONFIG if kind == "held" else BASE_CONFIG
        (directory / "holder.yaml").write_text(dump(config))
        (directory / "cfg.yaml").write_text(dump(config))  # so only the lock can refuse it
        holder = subprocess.Popen(
            [
                sys.executable,
                "-c",
                CLI,
                *(a.replace("{dir}", str(directory)) for a in _run_argv("holder.yaml")),
            ],
            cwd=directory,
            env=shared.env,
            start_new_session=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        deadline = time.monotonic() + 120
        while not (directory / "sweep" / "results.sqlite").exists() and time.monotonic() < deadline:
            time.sleep(0.05)
        if kind == "held":
            time.sleep(1.0)
            after.append(holder)
        else:
            _kill_group(holder.pid)
            holder.wait()
    argv = [a.replace("{dir}", str(directory)) for a in case.argv]
    if shared.garbage_port is not None:
        argv = [a.replace("{garbage_port}", str(shared.garbage_port)) for a in argv]
    return argv, after


def classify(case: Case, returncode: int | None, stderr: str, changed: bool) -> str:
    """The outcome of a finished (or killed: ``returncode`` None) case."""
    if returncode is None:
        return "hang"
    if "Traceback (most recent call last)" in stderr:
        return "traceback"
    if returncode == 0:
        return "accepted"
    lines = [line for line in stderr.splitlines() if line.strip()]
    if returncode == 2 and len(lines) == 1:
        return "written" if changed else "clean"
    return "unclean"


# -- running -------------------------------------------------------------------------------


def _run_forked(argv: list[str], directory: Path, timeout: float) -> tuple[int | None, str]:
    """The CLI's ``main(argv)`` in a forked child (its own process group) in ``directory``."""
    err_path = directory / ".stderr"
    out_path = directory / ".stdout"
    pid = os.fork()
    if pid == 0:  # the child: never returns
        try:
            os.setpgrp()
            os.chdir(directory)
            null = os.open(os.devnull, os.O_RDONLY)
            os.dup2(null, 0)
            out = os.open(out_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
            err = os.open(err_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
            os.dup2(out, 1)
            os.dup2(err, 2)
            sys.stdout = open(1, "w", closefd=False)
            sys.stderr = open(2, "w", closefd=False)
            from experiments.cli import main

            main(argv)
            os._exit(0)
        except BaseException:
            import traceback

            traceback.print_exc()
            sys.stderr.flush()
            os._exit(1)
    deadline = time.monotonic() + timeout
    status = None
    while time.monotonic() < deadline:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        time.sleep(0.01)
    else:
        _kill_group(pid)
        os.waitpid(pid, 0)
        _kill_group(pid)
        return None, err_path.read_text(errors="replace")
    _kill_group(pid)  # workers it left behind
    code = os.waitstatus_to_exitcode(status) if status is not None else None
    return code, err_path.read_text(errors="replace")


def _run_subprocess(
    argv: list[str], directory: Path, timeout: float, env: dict[str, str]
) -> tuple[int | None, str]:
    process = subprocess.Popen(
        [sys.executable, "-c", CLI, *argv],
        cwd=directory,
        env=env,
        start_new_session=True,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        errors="replace",
    )
    try:
        _, stderr = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        _kill_group(process.pid)
        _, stderr = process.communicate()
        return None, stderr
    _kill_group(process.pid)
    return process.returncode, stderr


def _digest(path: Path) -> bytes | None:
    try:
        return path.read_bytes() if path.is_file() else None
    except OSError:
        return None


def run_case(
    case: Case, directory: Path, shared: Environment, mode: str = "fork", timeout: float = TIMEOUT_S
) -> Outcome:
    """Prepare, run and classify one case."""
    argv, after = prepare(case, directory, shared)
    before = {name: _digest(directory / name) for name in case.keep}
    start = time.monotonic()
    try:
        if mode == "fork":
            code, stderr = _run_forked(argv, directory, max(case.timeout or 0.0, timeout))
        else:
            limit = max(case.timeout or 0.0, timeout)
            code, stderr = _run_subprocess(argv, directory, limit, shared.env)
    finally:
        for process in after:
            _kill_group(process.pid)
            process.wait()
    seconds = time.monotonic() - start
    changed = any(_digest(directory / name) != digest for name, digest in before.items())
    return Outcome(case, classify(case, code, stderr, changed), code, seconds, stderr)


def environment(code: Path | None, scratch: Path, need_template: bool) -> Environment:
    """The shared environment for the code at ``code`` (None: the installed one)."""
    env = dict(os.environ)
    if code is not None:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(code), env.get("PYTHONPATH", "")]))
    env.setdefault("NUMBA_CACHE_DIR", str(scratch / "numba-cache"))
    shared = Environment(env, scratch)
    if need_template:
        shared.template = make_template_database(scratch / "template", env)
    return shared


def preload() -> None:
    """Import what the subcommands import when they run, so forked children start at once."""
    import importlib

    for name in (
        "experiments.cli",
        "experiments.cli.entry",
        "experiments.sweep_config",  # the layout before the fixes
        "experiments.sweep",
        "ompl.util",
        "numpy",
        "shapely",
        "matplotlib",
        "feeders.scene_yaml",
        "experiments.sweep.config",
        "experiments.sweep.ladder",
        "experiments.sweep.summary",
        "experiments.sweep.report",
        "planners.plan",
        "experiments.pictures.scenes",
        "experiments.drop.passive",
    ):
        try:
            importlib.import_module(name)
        except Exception:  # an older checkout may not have it
            pass


def run_corpus(
    cases: list[Case],
    scratch: Path,
    code: Path | None = None,
    mode: str = "fork",
    timeout: float = TIMEOUT_S,
    progress: Callable[[Outcome], None] | None = None,
) -> list[Outcome]:
    """Run every case in its own directory under ``scratch``."""
    if code is not None:
        sys.path.insert(0, str(code))
    os.environ.setdefault("MPLBACKEND", "Agg")
    need_template = any(c.setup.startswith("db:") for c in cases)
    shared = environment(code, scratch, need_template)
    os.environ["NUMBA_CACHE_DIR"] = shared.env["NUMBA_CACHE_DIR"]
    if mode == "fork":
        preload()
    outcomes = []
    try:
        for index, case in enumerate(cases):
            directory = scratch / f"{index:04d}"
            outcome = run_case(case, directory, shared, mode, timeout)
            outcomes.append(outcome)
            if progress is not None:
                progress(outcome)
            shutil.rmtree(directory, ignore_errors=True)
    finally:
        shared.close()
    return outcomes


def counts(outcomes: list[Outcome]) -> dict[str, Any]:
    """Outcome counts over the malformed cases (all and per family), and over the controls."""
    bad = [o for o in outcomes if not o.case.valid]
    per_family: dict[str, Counter[str]] = {}
    for o in bad:
        per_family.setdefault(o.case.family, Counter())[o.outcome] += 1
    return {
        "malformed_cases": len(bad),
        "outcomes": {k: Counter(o.outcome for o in bad).get(k, 0) for k in OUTCOMES},
        "per_family": {f: dict(c) for f, c in per_family.items()},
        "controls": {o.case.name: o.outcome for o in outcomes if o.case.valid},
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--code", type=Path, default=None, help="checkout to run (default: installed)"
    )
    parser.add_argument("--mode", choices=("fork", "subprocess"), default="fork")
    parser.add_argument("--families", default=",".join(FAMILIES))
    parser.add_argument(
        "--per-family", type=int, default=None, help="a seeded sample of each family"
    )
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--timeout", type=float, default=TIMEOUT_S)
    parser.add_argument(
        "--out", type=Path, default=None, help="JSON of every outcome and the counts"
    )
    parser.add_argument("--list", action="store_true", help="list the cases and stop")
    args = parser.parse_args(argv)
    cases = corpus(tuple(args.families.split(",")))
    if args.per_family:
        cases = sample(cases, args.per_family, args.seed)
    if args.list:
        for c in cases:
            print(f"{c.family:14} {c.name}")
        print(f"{len(cases)} cases")
        return 0
    scratch = Path(tempfile.mkdtemp(prefix="partfeeder-corpus-"))

    def show(o: Outcome) -> None:
        mark = (
            "" if o.outcome in ("clean",) or (o.case.valid and o.outcome == "accepted") else "  <--"
        )
        last = o.stderr.strip().splitlines()[-1][:150] if o.stderr.strip() else ""
        print(
            f"{o.outcome:9} {o.seconds:5.1f}s {o.case.family:13} {o.case.name[:60]:60} "
            f"{last}{mark}",
            flush=True,
        )

    try:
        outcomes = run_corpus(cases, scratch, args.code, args.mode, args.timeout, show)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    summary = counts(outcomes)
    print(json.dumps(summary, indent=1))
    if args.out is not None:
        rows = [
            {
                "family": o.case.family,
                "name": o.case.name,
                "outcome": o.outcome,
                "returncode": o.returncode,
                "seconds": round(o.seconds, 2),
                "stderr": o.stderr[-3000:],
            }
            for o in outcomes
        ]
        args.out.write_text(json.dumps({"summary": summary, "cases": rows}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
