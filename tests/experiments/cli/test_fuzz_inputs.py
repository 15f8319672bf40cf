"""Hypothesis over the run-config and scene schemas (issue 16), through the CLI's entry point.

Each example mutates a valid document (``BASE_CONFIG``, ``BASE_SCENE`` of the corpus) in one
place and knows by construction whether the result is valid: a numeric leaf set to a value
drawn inside its stated range (valid) or outside it, non-finite, of another type, deeply
nested (invalid); a required key removed or an unknown key added (invalid). An invalid input
must end in exit status 2 with exactly one line on stderr, without reaching the job; a valid
one must reach it. The job itself is replaced by a stand-in that records it was reached (the
sweep and the planner are tested elsewhere), and every example has a deadline: a reader that
hangs or crawls fails the test. Derandomized, so a failure is reproducible.
"""

from __future__ import annotations

import copy
import math
import tempfile
from pathlib import Path
from typing import Any

import pytest
import yaml
from bad_input_corpus import (
    BASE_CONFIG,
    BASE_SCENE,
    CONFIG_LEAVES,
    DELETE,
    SCENE_LEAVES,
    with_value,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import experiments.pictures.scenes  # (imported before the deadlines apply)
import experiments.sweep.ladder  # noqa: F401
import planners.plan  # noqa: F401
from experiments.cli import run

SETTINGS = settings(
    max_examples=150,
    deadline=3000,  # ms per example: a reader that hangs or crawls fails here
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


class Reached(Exception):
    """The stand-in job: the CLI accepted the input and started the work."""


def _reach(*args: Any, **kwargs: Any) -> None:
    raise Reached


def _nested(depth: int, leaf: Any) -> Any:
    for i in range(depth):
        leaf = {"k": leaf} if i % 2 else [leaf]
    return leaf


def _wrong_values(low: float, high: float, integer: bool) -> st.SearchStrategy[Any]:
    """Values outside [low, high] or not a number of the right kind."""
    outside = st.one_of(
        st.floats(max_value=low, exclude_max=True, allow_nan=False),
        st.floats(min_value=high, exclude_min=True, allow_nan=False),
        st.sampled_from([math.nan, math.inf, -math.inf]),
    )
    if integer:
        outside = st.one_of(
            st.integers(max_value=int(low) - 1),
            st.integers(min_value=int(high) + 1),
            st.floats(allow_nan=True).filter(lambda v: not float(v).is_integer()),
            st.floats(low, high).map(float),  # a float where an integer is wanted
        )
    wrong_type = st.one_of(
        st.text(max_size=20),
        st.lists(st.integers(), max_size=3),
        st.dictionaries(st.text(max_size=5), st.integers(), max_size=2),
        st.none(),
        st.booleans(),
        st.integers(min_value=2, max_value=60).map(lambda d: _nested(d, 1)),
    )
    return st.one_of(outside, wrong_type)


def _valid_values(low: float, high: float, integer: bool) -> st.SearchStrategy[Any]:
    if integer:
        return st.integers(int(low), int(high))
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


def _mutations(
    base: dict[str, Any], leaves: list[tuple[str, float, float, bool]], required: list[str]
) -> st.SearchStrategy[tuple[Any, bool]]:
    """(document, valid) pairs: one leaf changed, a required key removed, a key added."""
    leaf = st.sampled_from(leaves)
    valid = leaf.flatmap(
        lambda f: _valid_values(f[1], f[2], f[3]).map(lambda v: (with_value(base, f[0], v), True))
    )
    invalid = leaf.flatmap(
        lambda f: _wrong_values(f[1], f[2], f[3]).map(lambda v: (with_value(base, f[0], v), False))
    )
    removed = st.sampled_from(required).map(lambda p: (with_value(base, p, DELETE), False))
    mappings = sorted({p.rsplit(".", 1)[0] for p, *_ in leaves if "." in p} | {""})
    added = st.tuples(st.sampled_from(mappings), st.text(min_size=1, max_size=12)).map(
        lambda t: (_with_key(base, t[0], "zz_" + t[1]), False)
    )
    return st.one_of(valid, invalid, removed, added)


def _with_key(base: dict[str, Any], mapping: str, key: str) -> Any:
    """``base`` with ``key: 1`` added to the mapping at ``mapping`` (the top level when it
    names a list)."""
    doc = copy.deepcopy(base)
    node: Any = doc
    for part in mapping.split(".") if mapping else []:
        node = node[int(part)] if isinstance(node, list) else node[part]
    (node if isinstance(node, dict) else doc)[key] = 1
    return doc


def _check(capsys, argv: list[str], valid: bool) -> None:
    try:
        code = run(argv)
    except Reached:
        assert valid, "invalid input reached the job"
        return
    err = capsys.readouterr().err
    assert not valid, f"valid input refused: {err}"
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err


CONFIG_INTEGER = [(p, lo, hi, integer) for p, lo, hi, integer in CONFIG_LEAVES]
SCENE_FLOAT = [(p, lo, hi, False) for p, lo, hi, _ in SCENE_LEAVES]


@SETTINGS
@given(mutation=_mutations(BASE_CONFIG, CONFIG_INTEGER, ["designs", "designs.count", "ladder"]))
def test_run_configs(capsys, mutation: tuple[Any, bool]) -> None:
    doc, valid = mutation
    with tempfile.TemporaryDirectory() as tmp, pytest.MonkeyPatch.context() as patch:
        patch.setattr("experiments.sweep.ladder.run_sweep", _reach)
        config = Path(tmp) / "cfg.yaml"
        config.write_text(yaml.safe_dump(doc))
        _check(capsys, ["run", str(config), "--out", f"{tmp}/sweep", "--quiet"], valid)


@SETTINGS
@given(mutation=_mutations(BASE_SCENE, SCENE_FLOAT, ["bounds", "starts", "goal", "goal.yaw"]))
@pytest.mark.slow  # ~8 s; the run configs' stays
def test_scenes(capsys, mutation: tuple[Any, bool]) -> None:
    doc, valid = mutation
    with tempfile.TemporaryDirectory() as tmp, pytest.MonkeyPatch.context() as patch:
        patch.setattr("planners.plan.plan", _reach)
        scene = Path(tmp) / "scene.yaml"
        scene.write_text(yaml.safe_dump(doc))
        _check(capsys, ["plan", "--scene", str(scene), "--time", "0.2"], valid)
