"""The numba kernels a command needs, compiled once per machine before its work starts
(:mod:`validity.kernel_cache`), with one line on stderr when numba's cache was cold: a first
run compiles for 15-60 s and should say why it waits. Nothing is printed when the kernels load
from the cache, and nothing on stdout (``--json`` stays clean)."""

from __future__ import annotations

import sys
from collections.abc import Iterable

from experiments.names import LEVEL_NAMES, PASSIVE

COMPILING = "partfeeder: compiling the numba kernels once for this machine (later runs load them)"


def kernel_levels(rungs: Iterable[str]) -> list[str]:
    """The levels whose kernels ``rungs`` (level names or ``passive``) run: the passive rung
    drops the part with the dynamic level."""
    levels = {"dynamic" if rung == PASSIVE else rung for rung in rungs}
    return [name for name in LEVEL_NAMES if name in levels]


def compile_once(rungs: Iterable[str]) -> None:
    """Compile (or load) the kernels of ``rungs`` in this process before any worker starts,
    so workers only load them; on a cold cache say so, and how long it took, on stderr."""
    from validity.kernel_cache import compile_kernels

    def announce() -> None:
        print(f"{COMPILING} ...", end="", file=sys.stderr, flush=True)

    load = compile_kernels(kernel_levels(rungs), on_first_compile=announce)
    if load.cold:
        print(f" {load.seconds:.0f} s", file=sys.stderr, flush=True)
