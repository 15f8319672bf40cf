"""The analytic scenes of the work-precision benchmark and their errors against closed forms.

Each case is one of the project's scene files (``experiments/scenes/bench-*.yaml``), a start
state (the scene's start pose, plus a velocity for free flight), a duration and the measures
of error computed from a run's states (rows ``(x, y, yaw, vx, vy, omega)`` at ``t = k h``),
whatever engine produced them: the same code judges every engine.

* ``slide`` (mu 0.3), ``threshold`` (mu 0.55) and ``stick`` (mu 0.7) on the 30 degree incline:
  |s(T) - s_exact(T)| for the displacement s along the slope; for ``stick`` s_exact = 0 and
  the error is the creep;
* ``flight``: distance of the centre of mass at T from the parabola;
* ``drop``: a box dropped flat 1.0 above a floor: |T_rest - t*| (T_rest: the first time after
  which every point of the box stays slower than ``REST_SPEED``), the deepest penetration
  (exact: 0) and |E(T) - m g y_rest| (exact: the energy at rest on the floor).

Penetration is measured the same way for every engine: the signed distance of the box at each
recorded pose to the scene's obstacles (:meth:`validity.scene_arrays.SceneArrays.clearance`,
the geometry kernel checked against shapely in its tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from experiments.bench.closed_forms import ballistic_state, incline_displacement, landing_time
from experiments.bench.timing import REPO_ROOT
from feeders.scene import Scene
from feeders.scene_yaml import load_scene
from validity.scene_arrays import SceneArrays

SCENES = REPO_ROOT / "experiments" / "scenes"
REST_SPEED = 1e-2  # length/s: every point slower than this counts as at rest (drop case)
FLIGHT_VELOCITY = (2.0, 5.0, 3.0)  # vx, vy (length/s), omega (rad/s) of the thrown box


@dataclass(frozen=True)
class AnalyticCase:
    """A scene file, its start, a duration (s) and which measure the diagrams plot."""

    name: str
    title: str
    scene_file: str
    kind: str  # "incline", "flight" or "drop": which closed form
    duration: float = 1.0
    velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @cached_property
    def scene(self) -> Scene:
        return load_scene(SCENES / self.scene_file)

    @cached_property
    def arrays(self) -> SceneArrays:
        return SceneArrays.from_scene(self.scene)

    @property
    def start(self) -> tuple[float, ...]:
        pose = next(iter(self.scene.starts.values()))
        return (*(float(v) for v in pose), *self.velocity)

    @property
    def measures(self) -> tuple[str, ...]:
        """The errors :meth:`errors` returns, the plotted one first."""
        if self.kind == "drop":
            return ("time_to_rest", "penetration", "energy")
        return ("error", "penetration")

    def max_penetration(self, states: np.ndarray) -> float:
        """Deepest overlap (length, >= 0) of the box with the obstacles over ``states``."""
        clear = min(self.arrays.clearance(s[0], s[1], s[2]) for s in states)
        return max(0.0, -clear)

    def errors(self, states: np.ndarray, h: float) -> dict[str, float]:
        """The measures of one run whose rows are the states at t = 0, h, 2h, ...; each an
        absolute error against the closed form (length, s or energy)."""
        scene, end = self.scene, states[-1]
        t_end = (len(states) - 1) * h
        g = math.hypot(*scene.gravity)
        out = {"penetration": self.max_penetration(states)}
        if self.kind == "incline":
            slope = -self.start[2]  # the box rests flat on the incline: its yaw is the slope's
            down = np.array([math.cos(slope), -math.sin(slope)])
            moved = float((end[:2] - np.asarray(self.start[:2])) @ down)
            exact = incline_displacement(scene.friction, slope, g, t_end)
            out.update(error=abs(moved - exact), value=moved, exact=exact)
        elif self.kind == "flight":
            exact_state = ballistic_state(self.start, scene.gravity, t_end)
            out.update(
                error=float(np.hypot(*(end[:2] - exact_state[:2]))),
                yaw_error=abs(float(end[2] - exact_state[2])),
            )
        elif self.kind == "drop":
            out.update(self._drop_errors(states, h, g))
        else:
            raise ValueError(f"case {self.name}: unknown kind {self.kind!r}")
        return out

    def _drop_errors(self, states: np.ndarray, h: float, g: float) -> dict[str, float]:
        scene, part = self.scene, self.scene.part
        floor_top = max(float(p[:, 1].max()) for p in scene.obstacles.polygons)
        gap = self.start[1] - part.width / 2.0 - floor_top
        t_star = landing_time(gap, g)
        radius = part.bounding_radius()
        speed = np.hypot(states[:, 3], states[:, 4]) + radius * np.abs(states[:, 5])
        moving = np.flatnonzero(speed >= REST_SPEED)
        rest_index = 0 if len(moving) == 0 else int(moving[-1]) + 1
        t_rest = rest_index * h  # len(states) * h when it never came to rest
        end = states[-1]
        energy = (
            0.5 * part.mass * (end[3] ** 2 + end[4] ** 2)
            + 0.5 * part.inertia * end[5] ** 2
            + part.mass * g * end[1]
        )
        exact_energy = part.mass * g * (floor_top + part.width / 2.0)
        return {
            "time_to_rest": abs(t_rest - t_star),
            "t_rest": t_rest,
            "t_exact": t_star,
            "energy": abs(float(energy) - exact_energy),
        }


CASES: tuple[AnalyticCase, ...] = (
    AnalyticCase("slide", "sliding, incline 30 deg, mu 0.3", "bench-slide.yaml", "incline"),
    AnalyticCase("threshold", "near stick/slip, mu 0.55", "bench-threshold.yaml", "incline"),
    AnalyticCase("stick", "sticking, mu 0.7: creep", "bench-stick.yaml", "incline"),
    AnalyticCase("flight", "free flight", "bench-flight.yaml", "flight", velocity=FLIGHT_VELOCITY),
    AnalyticCase("drop", "box dropped flat", "bench-drop-flat.yaml", "drop"),
)
CASE_NAMES = tuple(c.name for c in CASES)


def case(name: str) -> AnalyticCase:
    """The case called ``name`` (one of :data:`CASE_NAMES`)."""
    for c in CASES:
        if c.name == name:
            return c
    raise ValueError(f"unknown case {name!r}; cases: {', '.join(CASE_NAMES)}")


def steps_for(duration: float, h: float) -> int:
    """Steps of h that make ``duration`` (rounded: the h of the benchmarks divide it)."""
    return max(1, round(duration / h))
