"""A level as OMPL's state validity checker and state propagator.

OMPL 2's ``oc.StatePropagator`` cannot be subclassed from Python, so both are callables that
OMPL calls with its own states; they read the state into a tuple, call the level (one compiled
kernel call), and write the result back.
"""

from __future__ import annotations

from collections.abc import Callable

from planners.spaces import state_codec


def validity_checker(level, counts: list[int] | None = None) -> Callable:
    """``isValid(state) -> bool`` for OMPL; with ``counts``, each call adds 1 to ``counts[0]``
    (the work done, for budgets and benchmarks that do not depend on the machine)."""
    read, _ = state_codec(level.state_dim)
    is_valid = level.is_valid

    def check(state) -> bool:
        return is_valid(read(state))

    if counts is None:
        return check

    def counted_check(state) -> bool:
        counts[0] += 1
        return is_valid(read(state))

    return counted_check


def state_propagator(level, counts: list[int] | None = None) -> Callable:
    """``propagate(start, control, duration, result)`` for OMPL; with ``counts``, each call
    adds 1 to ``counts[1]``."""
    read, write = state_codec(level.state_dim)
    propagate = level.propagate
    dim = level.control_dim

    def prop(start, control, duration, result) -> None:
        write(result, propagate(read(start), [control[i] for i in range(dim)], duration))

    if counts is None:
        return prop

    def counted_prop(start, control, duration, result) -> None:
        counts[1] += 1
        write(result, propagate(read(start), [control[i] for i in range(dim)], duration))

    return counted_prop
