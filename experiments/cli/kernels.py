"""The numba kernels a command needs, compiled once per machine before its work starts
(:mod:`validity.kernel_cache`), saying so on stderr when numba's cache was cold (a bar over
the levels on a terminal, one line elsewhere): a first run compiles for 15-60 s and should say
why it waits. Nothing is printed when the kernels load
from the cache, and nothing on stdout (``--json`` stays clean)."""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import Any

from experiments.names import DROP_RUNGS, LEVEL_NAMES, NECESSARY

COMPILING = "partfeeder: compiling the numba kernels once for this machine (later runs load them)"
COMPILING_BAR = "compiling the numba kernels once for this machine"


def kernel_levels(rungs: Iterable[str]) -> list[str]:
    """The levels whose kernels ``rungs`` (level names or ``passive``) run: the passive rung
    drops the part with the dynamic level."""
    levels = {"dynamic" if rung in DROP_RUNGS else rung for rung in rungs}
    return [name for name in (*LEVEL_NAMES, NECESSARY) if name in levels]


def compile_once(rungs: Iterable[str]) -> None:
    """Compile (or load) the kernels of ``rungs`` in this process before any worker starts,
    so workers only load them. On a cold cache say so on stderr: on a terminal as a bar over
    the levels whose kernels are made (a fixed total, with tqdm's time estimate), elsewhere as
    one line with the time it took."""
    from experiments.progress import bar
    from validity.kernel_cache import compile_kernels

    levels = kernel_levels(rungs)
    terminal = bool(getattr(sys.stderr, "isatty", lambda: False)())
    done: list[str] = []
    shown: list[Any] = []  # the bar, once the first kernel compiles

    def announce() -> None:
        if terminal:
            shown.append(bar(len(levels), COMPILING_BAR, "level", initial=len(done)))
        else:
            print(f"{COMPILING} ...", end="", file=sys.stderr, flush=True)

    def level_done(name: str) -> None:
        done.append(name)
        for b in shown:
            b.update()

    load = compile_kernels(levels, on_first_compile=announce, on_level=level_done)
    for b in shown:
        b.close()
    if load.cold and not terminal:
        print(f" {load.seconds:.0f} s", file=sys.stderr, flush=True)
