"""A level as OMPL's state validity checker and state propagator.

OMPL 2's ``oc.StatePropagator`` cannot be subclassed from Python, so both are callables that
OMPL calls with its own states; they read the state into a tuple, call the level (one compiled
kernel call), and write the result back.
"""

from __future__ import annotations

from collections.abc import Callable

from planners.spaces import state_codec


def validity_checker(level) -> Callable:
    """``isValid(state) -> bool`` for OMPL."""
    read, _ = state_codec(level.state_dim)
    is_valid = level.is_valid

    def check(state) -> bool:
        return is_valid(read(state))

    return check


def state_propagator(level) -> Callable:
    """``propagate(start, control, duration, result)`` for OMPL."""
    read, write = state_codec(level.state_dim)
    propagate = level.propagate
    dim = level.control_dim

    def prop(start, control, duration, result) -> None:
        write(result, propagate(read(start), [control[i] for i in range(dim)], duration))

    return prop
