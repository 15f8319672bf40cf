"""MuJoCo on a partfeeder scene: the planar box among box obstacles, stepped with ``mj_step``.

The model (built from the :class:`feeders.scene.Scene`, so MuJoCo sees the project's own scene
files): the scene's plane is MuJoCo's x-z plane; the part is a body with three joints, slide x,
slide z and a hinge about -y (so the joint values are the scene's x, y and counter-clockwise
yaw, and their velocities vx, vy, omega), its inertia given explicitly (mass and the scene's
moment about the centre of mass), its geometry a box of the part's length and width (depth 1)
centred where the part's rectangle is. Every obstacle polygon must be a rectangle
(:mod:`experiments.bench.peers.rectangles`): it becomes a static box geom, depth 2 (deeper than
the part, so face contacts are whole). Gravity is the scene's, in x-z. Friction: both geoms get
``mu`` (MuJoCo combines by the maximum), condim 3 (sliding friction only).

Settings (:data:`SETTINGS`): ``default`` is MuJoCo's defaults except the timestep (pyramidal
cone, Euler integrator, Newton solver, 100 iterations, tolerance 1e-8, impratio 1, soft
contact solref (0.02, 1) and solimp (0.9, 0.95, 0.001, 0.5, 2)); ``accurate`` is its most
accurate friction: an elliptic cone, impratio 10 (friction stiffened against slip, as its
documentation recommends with elliptic cones), 10 noslip iterations (its post-processor
against slip), the implicitfast integrator and tolerance 1e-10. Contact softness (solref,
solimp) is left at its default in both: it is what a MuJoCo user gets, and the diagrams show
what it costs in penetration and in the drop's time to rest.

Feeders (:class:`MujocoFeederSimulator`, for the agreement suite): every convex polygon piece
is a static mesh, the exact prism of the piece extruded in y (MuJoCo collides a mesh as its
convex hull, which for a convex prism is the prism itself), with ``multiccd`` on so a face
resting on a face gets several contact points; every disc (the protuberance's tip) is a sphere
centred in the part's plane: its section there is the disc exactly, and sphere contacts are
MuJoCo's exact special case (a cylinder against the box goes through the general convex
collider, which returned a wrong normal). Options of :data:`FEEDER_OPTIONS`: the elliptic cone
(the planar friction cone exact), impratio 10, noslip 10, implicitfast, tolerance 1e-10;
contacts critically damped (MuJoCo's default solref), so no restitution, as the dynamic level.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from experiments.bench.peers.rectangles import rectangle_of
from feeders.scene import Scene

ENGINE = "mujoco"
SETTINGS = {
    "default": "MuJoCo defaults (pyramidal cone, Euler, soft contact)",
    "accurate": "elliptic cone, impratio 10, noslip 10, implicitfast, tolerance 1e-10",
}
_OPTIONS = {
    "default": "",
    "accurate": 'cone="elliptic" impratio="10" noslip_iterations="10" '
    'integrator="implicitfast" tolerance="1e-10"',
}
PART_DEPTH = 1.0
OBSTACLE_DEPTH = 2.0


def available() -> bool:
    """True when the optional ``mujoco`` package can be imported."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        return False
    return True


def _vec(values: Sequence[float]) -> str:
    return " ".join(f"{float(v):.17g}" for v in values)


def _quat_about_minus_y(angle: float) -> str:
    """Quaternion of a counter-clockwise turn by ``angle`` in the x-z plane (about -y)."""
    return _vec((math.cos(angle / 2), 0.0, -math.sin(angle / 2), 0.0))


def _part_body(scene: Scene, mu: str) -> str:
    """The part as an MJCF body: slide x, slide z and a hinge about -y (the joint values are
    the scene's x, y and counter-clockwise yaw), the scene's mass and moment about the centre
    of mass, a box of the part's length and width (depth ``PART_DEPTH``)."""
    part = scene.part
    half = (part.length / 2, PART_DEPTH / 2, part.width / 2)
    return f"""    <body name="part">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="y" type="slide" axis="0 0 1"/>
      <joint name="yaw" type="hinge" axis="0 -1 0"/>
      <inertial pos="0 0 0" mass="{part.mass:.17g}" diaginertia="{_vec((part.inertia,) * 3)}"/>
      <geom name="part" type="box" size="{_vec(half)}" pos="{_vec((-part.com_offset, 0, 0))}"
            friction="{mu}" mass="0"/>
    </body>"""


def model_xml(scene: Scene, h: float, setting: str = "default") -> str:
    """MJCF of ``scene`` with timestep ``h`` and the options of ``setting``."""
    if setting not in _OPTIONS:
        raise ValueError(f"MuJoCo setting {setting!r}; settings: {', '.join(_OPTIONS)}")
    mu = f"{scene.friction:.17g} 0.005 0.0001"
    gx, gy = scene.gravity
    geoms = []
    for k, polygon in enumerate(scene.obstacles.polygons):
        r = rectangle_of(polygon)
        geoms.append(
            f'    <geom name="obstacle{k}" type="box" friction="{mu}" '
            f'size="{_vec((r.half_length, OBSTACLE_DEPTH, r.half_width))}" '
            f'pos="{_vec((r.centre[0], 0.0, r.centre[1]))}" quat="{_quat_about_minus_y(r.angle)}"/>'
        )
    if len(scene.obstacles.circles):
        raise ValueError("the MuJoCo model takes rectangular obstacles only, not circles")
    return f"""<mujoco model="{scene.name}">
  <option timestep="{h:.17g}" gravity="{_vec((gx, 0.0, gy))}" {_OPTIONS[setting]}/>
  <worldbody>
{chr(10).join(geoms)}
{_part_body(scene, mu)}
  </worldbody>
</mujoco>
"""


class MujocoSimulator:
    """One MuJoCo model of a scene at step h; the part's state is (qpos, qvel)."""

    def __init__(self, scene: Scene, h: float, setting: str = "default"):
        import mujoco

        self.mujoco = mujoco
        self.model = mujoco.MjModel.from_xml_string(model_xml(scene, h, setting))
        self.data = mujoco.MjData(self.model)

    def prepare(self, start: Sequence[float]) -> None:
        mujoco, data = self.mujoco, self.data
        mujoco.mj_resetData(self.model, data)
        data.qpos[:] = start[:3]
        data.qvel[:] = start[3:6]
        mujoco.mj_forward(self.model, data)

    def advance(self, steps: int) -> None:
        step, model, data = self.mujoco.mj_step, self.model, self.data
        for _ in range(steps):
            step(model, data)

    def record(self, start: Sequence[float], steps: int) -> np.ndarray:
        self.prepare(start)
        out = np.empty((steps + 1, 6))
        data, step, model = self.data, self.mujoco.mj_step, self.model
        out[0, :3], out[0, 3:] = data.qpos, data.qvel
        for k in range(1, steps + 1):
            step(model, data)
            out[k, :3], out[k, 3:] = data.qpos, data.qvel
        return out


FEEDER_OPTIONS = _OPTIONS["accurate"]


def _prism_mesh(name: str, polygon: np.ndarray, depth: float) -> str:
    """A convex polygon (x, y in the scene's plane) as a MuJoCo mesh asset: the prism from
    y = -depth to +depth in MuJoCo's frame (the scene's y is MuJoCo's z)."""
    vertices = []
    for x, y in np.asarray(polygon, dtype=float):
        vertices += [x, -depth, y, x, depth, y]
    return f'    <mesh name="{name}" vertex="{_vec(vertices)}"/>'


def feeder_model_xml(
    scene: Scene,
    h: float,
    part_body: Callable[[Scene, str], tuple[list[str], str]] | None = None,
) -> str:
    """MJCF of a scene with general convex pieces and discs (a feeder) at timestep ``h``;
    ``part_body(scene, mu)`` gives the part's mesh assets and body (default: the peg's box,
    no assets; :mod:`.compound` gives any part's pieces)."""
    mu = f"{scene.friction:.17g} 0.005 0.0001"
    gx, gy = scene.gravity
    part_assets, body = part_body(scene, mu) if part_body else ([], _part_body(scene, mu))
    meshes, geoms = list(part_assets), []
    for k, polygon in enumerate(scene.obstacles.polygons):
        meshes.append(_prism_mesh(f"piece{k}", polygon, OBSTACLE_DEPTH))
        geoms.append(f'    <geom name="obstacle{k}" type="mesh" mesh="piece{k}" friction="{mu}"/>')
    for k, (cx, cy, radius) in enumerate(scene.obstacles.circles):
        geoms.append(
            f'    <geom name="disc{k}" type="sphere" size="{float(radius):.17g}" '
            f'pos="{_vec((cx, 0.0, cy))}" friction="{mu}"/>'
        )
    return f"""<mujoco model="{scene.name}">
  <option timestep="{h:.17g}" gravity="{_vec((gx, 0.0, gy))}" {FEEDER_OPTIONS}>
    <flag multiccd="enable"/>
  </option>
  <asset>
{chr(10).join(meshes)}
  </asset>
  <worldbody>
{chr(10).join(geoms)}
{body}
  </worldbody>
</mujoco>
"""


class MujocoFeederSimulator:
    """A feeder scene in MuJoCo at step ``h`` (s) (:func:`feeder_model_xml`); the state is
    (qpos, qvel) = (x, y, yaw, vx, vy, omega) of the centre of mass."""

    def __init__(self, scene: Scene, h: float, xml: str | None = None):
        """``xml``: the model (default :func:`feeder_model_xml` of the scene at h)."""
        import mujoco

        self.mujoco = mujoco
        self.h = float(h)
        self.model = mujoco.MjModel.from_xml_string(xml or feeder_model_xml(scene, h))
        self.data = mujoco.MjData(self.model)

    def reset(self, start: Sequence[float]) -> None:
        """The part at ``start`` = (x, y, yaw, vx, vy, omega), every other state reset."""
        mujoco, data = self.mujoco, self.data
        mujoco.mj_resetData(self.model, data)
        data.qpos[:] = start[:3]
        data.qvel[:] = start[3:6]
        mujoco.mj_forward(self.model, data)

    def run(self, out: np.ndarray) -> None:
        """Take ``len(out)`` steps; row k of ``out`` gets the state after step k + 1."""
        step, model, data = self.mujoco.mj_step, self.model, self.data
        qpos, qvel = data.qpos, data.qvel
        for k in range(out.shape[0]):
            step(model, data)
            row = out[k]
            row[:3] = qpos
            row[3:] = qvel


def builder(setting: str) -> Callable[[Scene, float], MujocoSimulator]:
    """``build(scene, h)`` for one setting (checked now, built later)."""
    if setting not in _OPTIONS:
        raise ValueError(f"MuJoCo setting {setting!r}; settings: {', '.join(_OPTIONS)}")
    return lambda scene, h: MujocoSimulator(scene, h, setting)
