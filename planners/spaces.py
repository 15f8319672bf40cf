"""OMPL state and control spaces for a level, and reading/writing OMPL states as tuples.

A 3-dimensional level state is an SE2 pose. A 6-dimensional one is SE2 x R^3 (pose and
velocity), for the kinematic and dynamic levels.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from ompl import base as ob
from ompl import control as oc

from feeders.scene import Scene


def make_state_space(
    scene: Scene, state_dim: int, velocity_limit: float | None = None
) -> ob.StateSpace:
    """SE2 bounded by the scene (dim 3) or SE2 x R^3 (dim 6, velocities within
    +-``velocity_limit``, the level's own limit)."""
    se2 = ob.SE2StateSpace()
    bounds = ob.RealVectorBounds(2)
    x_min, x_max, y_min, y_max = scene.bounds
    bounds.setLow(0, x_min)
    bounds.setHigh(0, x_max)
    bounds.setLow(1, y_min)
    bounds.setHigh(1, y_max)
    se2.setBounds(bounds)
    if state_dim == 3:
        return se2
    if state_dim != 6:
        raise ValueError(f"no OMPL state space for a {state_dim}-dimensional state")
    if velocity_limit is None or not velocity_limit > 0.0:
        raise ValueError("a 6-dimensional state space needs the level's velocity_limit > 0")
    vel = ob.RealVectorStateSpace(3)
    vb = ob.RealVectorBounds(3)
    vb.setLow(-velocity_limit)
    vb.setHigh(velocity_limit)
    vel.setBounds(vb)
    space = ob.CompoundStateSpace()
    space.addSubspace(se2, 1.0)
    space.addSubspace(vel, 0.1)
    return space


def make_control_space(
    space: ob.StateSpace, low: Sequence[float], high: Sequence[float]
) -> oc.RealVectorControlSpace:
    """A box of controls ``low <= u <= high`` (a zero-width range fixes that component)."""
    control_space = oc.RealVectorControlSpace(space, len(low))
    bounds = ob.RealVectorBounds(len(low))
    for i, (lo, hi) in enumerate(zip(low, high, strict=True)):
        bounds.setLow(i, float(lo))
        bounds.setHigh(i, float(hi))
    control_space.setBounds(bounds)
    return control_space


def state_codec(state_dim: int) -> tuple[Callable, Callable]:
    """``(read, write)``: an OMPL state to a tuple of floats, and a tuple into an OMPL state."""
    if state_dim == 3:

        def read(s) -> tuple[float, ...]:
            return (s.getX(), s.getY(), s.getYaw())

        def write(s, v: Sequence[float]) -> None:
            s.setX(v[0])
            s.setY(v[1])
            s.setYaw(v[2])

        return read, write

    def read6(s) -> tuple[float, ...]:
        p, v = s[0], s[1]
        return (p.getX(), p.getY(), p.getYaw(), v[0], v[1], v[2])

    def write6(s, v: Sequence[float]) -> None:
        p, w = s[0], s[1]
        p.setX(v[0])
        p.setY(v[1])
        p.setYaw(v[2])
        w[0], w[1], w[2] = v[3], v[4], v[5]

    return read6, write6


def level_spaces(level) -> tuple[ob.StateSpace, oc.RealVectorControlSpace]:
    """The state space and the control space (the input set U, Eqs. 7-9) of a level
    (:mod:`validity`): what :func:`planners.adapters.validity_checker` and
    :func:`planners.adapters.state_propagator` read and write."""
    space = make_state_space(level.scene, level.state_dim, getattr(level, "velocity_limit", None))
    low, high = level.control_bounds()
    return space, make_control_space(space, low, high)
