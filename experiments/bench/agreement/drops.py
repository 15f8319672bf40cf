"""One passive drop of a made feeder from one start in one engine, ended and judged alike.

partfeeder runs :func:`experiments.drop.passive.passive_drop` (its compiled loop applies the
end rule itself, at its own step); a peer (:class:`Peer`: MuJoCo or pymunk on the same scene)
is stepped in chunks of ``CHUNK`` steps and :class:`.ending.EndRule` finds the end in each
chunk's states. Either way the outcome is classified from q(T) by the project's own classifier,
and the speed just past the lip is read from the recorded states (:mod:`.lip`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from experiments.bench.agreement.ending import Ending, EndRule, ending_of
from experiments.bench.agreement.lip import LipSpeed, lip_speed
from experiments.drop.passive import passive_drop
from feeders.scene import Scene
from validity.dynamic import DynamicLevel

CHUNK = 2000  # peer steps between looks at the end rule (0.2 s at h = 1e-4)


class Peer(Protocol):
    """A peer engine's model of one scene at one step: ``reset`` puts the part at a start
    (x, y, yaw, vx, vy, omega), ``run`` fills each row of ``out`` with the state after a step."""

    h: float

    def reset(self, start: Sequence[float]) -> None: ...

    def run(self, out: np.ndarray) -> None: ...


@dataclass(frozen=True)
class Drop:
    """One drop in one engine: its ending, the lip speed (None if never reached), the steps
    taken, the engine's step h (s) and the wall time (s)."""

    ending: Ending
    lip: LipSpeed | None
    steps: int
    h: float
    wall_time: float


def partfeeder_drop(
    scene: Scene, orientation: str, start: Sequence[float], level: DynamicLevel, t_max: float
) -> Drop:
    """The dynamic level's drop (its step is ``level.step``); its wall time is the drop's own,
    measured after the compiled kernel is loaded (a first run's compile is no drop's cost)."""
    result = passive_drop(scene, orientation, t_max=t_max, level=level, start=start)
    wall = result.wall_time
    run = result.trajectory
    ending = ending_of(scene, result.end, run.states[run.settle_index], result.T, result.success)
    return Drop(ending, lip_speed(scene, start, run.states), result.steps, level.step, wall)


def peer_drop(scene: Scene, start: Sequence[float], peer: Peer, t_max: float) -> Drop:
    """A peer's drop from ``start``, at most ``t_max`` s, ended by :class:`EndRule`."""
    h = peer.h
    n_max = max(1, math.ceil(t_max / h - 1e-9))
    rule = EndRule.of(scene, h)
    states = np.empty((n_max + 1, 6))
    states[0] = np.asarray(start, dtype=float)[:6]
    t0 = time.perf_counter()
    peer.reset(start)
    done, end, last = 0, "duration", n_max
    while done < n_max:
        n = min(CHUNK, n_max - done)
        chunk = states[done + 1 : done + 1 + n]
        peer.run(chunk)
        found = rule.first_end(chunk)
        if found is not None:
            k, end = found
            last = done + 1 + k
            break
        done += n
    wall = time.perf_counter() - t0
    if end == "left_bounds":
        last -= 1  # the step out is not taken: the drop ends at the last state inside
    settle = last - rule.rest if end == "at_rest" else last
    kept = states[: last + 1]
    ending = ending_of(scene, end, states[settle], settle * h)
    return Drop(ending, lip_speed(scene, start, kept), last, h, wall)
