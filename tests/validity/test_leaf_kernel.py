"""A kernel compiled without reference counting (``@leaf_kernel``) must allocate no array,
nor call a compiled function that does: numba compiles such a call without complaint, and
the array it returns is never freed (a leak on every step). Reference: the sources
themselves, read as Python syntax trees; an allocating kernel is one that calls numpy's
constructors or ``.copy()``, or calls another allocating kernel (transitively)."""

from __future__ import annotations

import ast
from pathlib import Path

import validity

ALLOCATORS = {"empty", "zeros", "ones", "array", "empty_like", "zeros_like", "full", "copy"}
SOURCES = sorted(Path(validity.__file__).parent.glob("*.py"))


def _functions(sources: dict[str, str]) -> dict[str, tuple[ast.FunctionDef, bool]]:
    """Every module-level function of the modules ``sources`` (name: text): (node, is a leaf
    kernel)."""
    out = {}
    for module, text in sources.items():
        for node in ast.parse(text).body:
            if isinstance(node, ast.FunctionDef):
                leaf = any(getattr(d, "id", None) == "leaf_kernel" for d in node.decorator_list)
                out[f"{module}.{node.name}"] = (node, leaf)
    return out


def _calls(node: ast.FunctionDef) -> tuple[set[str], bool]:
    """The plain names it calls, and whether it calls an allocator (np.empty, x.copy())."""
    names, allocates = set(), False
    for call in ast.walk(node):
        if not isinstance(call, ast.Call):
            continue
        if isinstance(call.func, ast.Name):
            names.add(call.func.id)
        elif isinstance(call.func, ast.Attribute) and call.func.attr in ALLOCATORS:
            allocates = True
    return names, allocates


def leaking_leaves(sources: dict[str, str]) -> tuple[set[str], set[str]]:
    """(the leaf kernels, those of them that allocate or call a function that does)."""
    functions = _functions(sources)
    calls = {name: _calls(node) for name, (node, _) in functions.items()}
    by_short: dict[str, set[str]] = {}
    for name in functions:
        by_short.setdefault(name.split(".", 1)[1], set()).add(name)
    allocating = {name for name, (_, allocates) in calls.items() if allocates}
    grew = True
    while grew:
        grew = False
        for name, (names, _) in calls.items():
            if name not in allocating and any(
                full in allocating for short in names for full in by_short.get(short, ())
            ):
                allocating.add(name)
                grew = True
    leaves = {name for name, (_, leaf) in functions.items() if leaf}
    return leaves, leaves & allocating


def test_no_leaf_kernel_allocates_or_calls_a_kernel_that_does() -> None:
    leaves, leaking = leaking_leaves({p.stem: p.read_text() for p in SOURCES})
    assert len(leaves) >= 30, "the leaf kernels were not found"
    assert not leaking, sorted(leaking)


def test_the_check_sees_a_leaf_that_calls_an_allocating_kernel() -> None:
    """The rule itself, on two made-up modules: a leaf kernel that calls an allocating kernel
    of another module (through a third function) is caught; one that only writes is not."""
    boxes = "import numpy as np\ndef boxes(a):\n    return np.empty((a.shape[0], 4))\n"
    level = (
        "@leaf_kernel\ndef leaking(a):\n    return wrapped(a)\n"
        "def wrapped(a):\n    return boxes(a)\n"
        "@leaf_kernel\ndef writing(a, out):\n    out[0] = a[0]\n"
    )
    leaves, leaking = leaking_leaves({"boxes": boxes, "level": level})
    assert leaves == {"level.leaking", "level.writing"}
    assert leaking == {"level.leaking"}
