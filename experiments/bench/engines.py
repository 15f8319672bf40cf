"""The engines on the work-precision diagrams, behind one small interface.

A :class:`Simulator` is one engine with one setting on one scene at one step h: ``prepare``
puts the part in a start state (untimed: resetting or building the engine's world),
``advance`` runs a number of steps (what is timed) and ``record`` returns every state of a run
(rows ``(x, y, yaw, vx, vy, omega)`` from the start), from which errors are measured.

partfeeder's dynamic level runs its whole time loop in one compiled call (``propagate``, no
recording while timed); the peers (:mod:`experiments.bench.peers`) are stepped from Python one
step at a time, as a user of their Python bindings would. Peers are optional: a setting whose
engine is not installed is listed with ``available = False`` and never built.
"""

from __future__ import annotations

import importlib.metadata
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from experiments.bench.peers import mujoco_engine, pymunk_engine
from feeders.scene import Scene
from validity.dynamic import DynamicLevel


class Simulator(Protocol):
    def prepare(self, start: Sequence[float]) -> None: ...

    def advance(self, steps: int) -> None: ...

    def record(self, start: Sequence[float], steps: int) -> np.ndarray: ...


class PartfeederSimulator:
    """The dynamic level (Eq. 7) at step h with its default options (or those given)."""

    def __init__(self, scene: Scene, h: float, **options):
        self.level = DynamicLevel(scene, step=h, **options)
        self.h = h
        self._start: tuple[float, ...] = ()
        self.advance_result: tuple[float, ...] = ()

    def prepare(self, start: Sequence[float]) -> None:
        self._start = tuple(float(v) for v in start)

    def advance(self, steps: int) -> None:
        self.advance_result = self.level.propagate(self._start, (0.0, 0.0, 0.0), steps * self.h)

    def record(self, start: Sequence[float], steps: int) -> np.ndarray:
        return self.level.simulate(start, duration=steps * self.h).states


@dataclass(frozen=True)
class EngineSetting:
    """An engine with one setting: ``build(scene, h)`` makes its simulator."""

    engine: str
    setting: str
    description: str
    build: Callable[[Scene, float], Simulator]
    available: bool

    @property
    def label(self) -> str:
        return f"{self.engine} ({self.setting})"


def _partfeeder(scene: Scene, h: float) -> Simulator:
    return PartfeederSimulator(scene, h)


def engine_settings() -> list[EngineSetting]:
    """Every engine and setting of the diagrams, partfeeder first; peers flagged available or
    not (their settings are described in their modules)."""
    out = [
        EngineSetting(
            "partfeeder",
            "default",
            "dynamic level, Stewart-Trinkle LCP (Eq. 7), default options",
            _partfeeder,
            True,
        )
    ]
    for module in (mujoco_engine, pymunk_engine):
        for name, description in module.SETTINGS.items():
            out.append(
                EngineSetting(
                    module.ENGINE,
                    name,
                    description,
                    module.builder(name),
                    module.available(),
                )
            )
    return out


def engine_versions() -> dict[str, str]:
    """Version of every engine ("not installed" for an absent peer)."""

    def version(dist: str) -> str:
        try:
            return importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            return "not installed"

    return {
        "partfeeder": version("partfeeder"),
        "numba": version("numba"),
        mujoco_engine.ENGINE: version("mujoco"),
        pymunk_engine.ENGINE: version("pymunk"),
    }
