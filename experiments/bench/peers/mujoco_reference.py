"""MuJoCo reference: the sliding-box incline benchmark simulated in MuJoCo.

What and why
------------
Our dynamic level steps a planar rigid body with a Stewart-Trinkle LCP time stepper (hard
contact, exact Coulomb cone in the plane). MuJoCo is the engine a user might pick instead, so
this module builds the same test problem in MuJoCo, so that accuracy and cost per step of the
two can be compared in one run. MuJoCo is *not* a project dependency: it is the optional extra
``mujoco`` (``pip install 'partfeeder[mujoco]'``), imported lazily inside the functions, so
importing this module without it works; the functions that need it raise an ``ImportError``.

Test problem (closed form)
--------------------------
A uniform ``width x height`` = 2 x 1 box of mass 1 rests with its long side flat on an incline
at ``phi`` = 30 degrees under gravity g = 9.81, Coulomb friction ``mu``, starting at rest. Its
along-slope displacement is ``x(t) = 1/2 g (sin phi - mu cos phi) t^2`` when ``mu < tan phi``,
else 0: x(1 s) = 1.178144 m for mu = 0.3, 0.116203 m for mu = 0.55, and 0 for mu = 0.7.

The MuJoCo model
----------------
* Planar: the box body has exactly three DOF, two slide joints in the x-z plane (the incline's
  cross-section) and a hinge about y, like the planar model. The body frame is tilted by
  ``phi`` about y, and the slide joints come before the hinge, so their axes stay fixed: the
  first is along the slope (positive downhill) and the second along the incline's normal.
* The incline is real geometry: a static box geom in the world body rotated by ``phi`` about y;
  gravity is MuJoCo's usual ``(0, 0, -9.81)``. This exercises the box-box collision at a
  non-axis-aligned orientation as a user's scene would (rotating gravity instead would give the
  same dynamics for this planar system).
* The box's third dimension (depth, along y) is 1; its inertia comes from its ``mass`` and shape,
  so the moment about the hinge is ``m (w^2 + h^2) / 12`` as in the planar model. The incline is
  deeper than the box, so the contact is a full face-face contact (MuJoCo's box-box collider
  puts up to 4 points on the face).
* Friction: both geoms get ``friction="mu 0.005 0.0001"`` (MuJoCo combines two geoms' friction
  by the maximum; setting both makes the result ``mu`` whatever the rule). ``condim`` is the
  default 3 (sliding friction only; torsional and rolling friction are off).
* The box starts touching the incline (signed distance 0, at rest).

Solver settings, and why they are fair
--------------------------------------
Everything is MuJoCo's default except the timestep (``h`` as given, the same as our stepper's)
and, when asked for, the friction cone and the integrator:

* ``cone``: ``"pyramidal"`` (MuJoCo's default) or ``"elliptic"``. For condim 3 the pyramid has
  edges ``n +- mu t_i``, exact along a contact-frame tangent axis; here MuJoCo's contact frame
  has one tangent along the slope (the other along y), so the pyramid's sliding bound is
  exactly ``mu``. The elliptic cone is exact in every direction.
* ``integrator``: ``"euler"`` (default, semi-implicit Euler) or ``"implicitfast"``. With no
  damping or actuators the two give the same result for this problem.
* Contact is soft by default (``solref = (0.02, 1)``, ``solimp = (0.9, 0.95, 0.001, 0.5, 2)``,
  ``impratio = 1``): the box sinks into the incline by up to ~0.1-0.3 mm at h = 1e-3, and,
  the problem being a regularised convex one rather than a complementarity one, friction
  below its limit still lets a small velocity through, so a box that should stick creeps
  downhill (about 2.8 mm/s with the pyramidal cone, 1 mm/s with the elliptic one, at
  mu = 0.7). The sliding box also rocks and hops off the incline by a fraction of a
  millimetre (``airborne_steps``), which makes the sliding results sensitive at the ~0.1-1 mm
  level to tiny perturbations. That is what a user gets from MuJoCo, so it is kept and
  measured (penetration, creep, hops) rather than tuned away.
* Options, off by default, to see how much of the gap tuning closes: ``impratio`` (MuJoCo's
  recommended remedy for slip, stiffening friction relative to normal; meant for elliptic
  cones) and ``noslip_iterations`` (MuJoCo's post-processor against slip; in MuJoCo 4.0.0 it
  made no measurable difference to the creep here).
* Solver (Newton), ``iterations`` = 100 and ``tolerance`` = 1e-8 are MuJoCo's defaults.
"""

from __future__ import annotations

import math
import time

import numpy as np

G = 9.81
PHI = math.radians(30.0)
_IMPORT_MESSAGE = "MuJoCo is not installed: pip install 'partfeeder[mujoco]'"
_INTEGRATORS = {"euler": "Euler", "implicitfast": "implicitfast"}
_CONES = ("pyramidal", "elliptic")


def _mujoco():
    try:
        import mujoco
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(_IMPORT_MESSAGE) from exc
    return mujoco


def mujoco_available() -> bool:
    """True when the optional ``mujoco`` package can be imported."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        return False
    return True


def exact_displacement(mu: float, t: float, phi: float = PHI, g: float = G) -> float:
    """Closed-form along-slope displacement at time ``t`` (0 when ``mu >= tan phi``)."""
    a = g * (math.sin(phi) - mu * math.cos(phi))
    return 0.5 * a * t * t if a > 0.0 else 0.0


def incline_model_xml(
    mu: float,
    phi: float = PHI,
    width: float = 2.0,
    height: float = 1.0,
    mass: float = 1.0,
    timestep: float = 1e-3,
    cone: str = "pyramidal",
    *,
    integrator: str = "euler",
    noslip_iterations: int = 0,
    impratio: float = 1.0,
    depth: float = 1.0,
) -> str:
    """MJCF of the box on the incline: a planar 3-DOF box on a static box geom tilted by ``phi``.

    The body ``box`` has slide joints ``along`` (downhill) and ``normal`` and hinge ``theta``
    (about y); its centre starts at ``height / 2`` above the incline's surface, which passes
    through the origin.
    """
    if cone not in _CONES:
        raise ValueError(f"cone must be one of {_CONES}, not {cone!r}")
    if integrator not in _INTEGRATORS:
        raise ValueError(f"integrator must be one of {tuple(_INTEGRATORS)}, not {integrator!r}")
    s, c = math.sin(phi), math.cos(phi)
    quat = f"{math.cos(phi / 2):.17g} 0 {math.sin(phi / 2):.17g} 0"  # rotation by phi about y
    normal = np.array([s, 0.0, c])
    slab_half = (20.0, depth, 0.25)  # long, deeper than the box, thick enough not to tunnel
    slab_pos = -slab_half[2] * normal
    box_pos = 0.5 * height * normal
    friction = f"{mu:.17g} 0.005 0.0001"

    def vec(v) -> str:
        return " ".join(f"{float(x):.17g}" for x in v)

    return f"""<mujoco model="partfeeder_incline">
  <compiler angle="radian"/>
  <option timestep="{timestep:.17g}" gravity="0 0 {-G:.17g}" cone="{cone}"
          integrator="{_INTEGRATORS[integrator]}" noslip_iterations="{int(noslip_iterations)}"
          impratio="{impratio:.17g}"/>
  <worldbody>
    <geom name="incline" type="box" size="{vec(slab_half)}" pos="{vec(slab_pos)}"
          quat="{quat}" friction="{friction}"/>
    <body name="box" pos="{vec(box_pos)}" quat="{quat}">
      <joint name="along" type="slide" axis="1 0 0"/>
      <joint name="normal" type="slide" axis="0 0 1"/>
      <joint name="theta" type="hinge" axis="0 1 0"/>
      <geom name="box" type="box" size="{vec((width / 2, depth / 2, height / 2))}"
            mass="{mass:.17g}" friction="{friction}"/>
    </body>
  </worldbody>
</mujoco>
"""


def _build(mu, h, cone, integrator, noslip_iterations, impratio):
    mujoco = _mujoco()
    xml = incline_model_xml(
        mu,
        timestep=h,
        cone=cone,
        integrator=integrator,
        noslip_iterations=noslip_iterations,
        impratio=impratio,
    )
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return mujoco, model, data


def simulate_incline(
    mu: float,
    h: float,
    duration: float = 1.0,
    cone: str = "pyramidal",
    *,
    integrator: str = "euler",
    noslip_iterations: int = 0,
    impratio: float = 1.0,
) -> dict:
    """Simulate the box on the incline for ``duration`` s with timestep ``h``.

    Returns ``x_along`` (final along-slope displacement, m, positive downhill), ``x_exact``
    (closed form), ``error`` (their absolute difference), ``steps``, ``penetration`` (largest
    penetration depth of any contact seen, m, >= 0), ``trajectory`` (``steps + 1`` along-slope
    displacements, from 0), ``v_along`` (final along-slope velocity, m/s), ``airborne_steps``
    (steps after which the box had no contact at all: MuJoCo's sliding box rocks and hops by a
    fraction of a millimetre) and ``max_tilt`` (largest ``|theta|`` seen, rad).
    """
    mujoco, model, data = _build(mu, h, cone, integrator, noslip_iterations, impratio)
    steps = round(duration / h)
    body = model.body("box").id
    downhill = np.array([math.cos(PHI), 0.0, -math.sin(PHI)])
    x0 = data.xpos[body].copy()
    trajectory = np.empty(steps + 1)
    trajectory[0] = 0.0
    penetration = 0.0
    airborne = 0
    tilt = 0.0
    for k in range(1, steps + 1):
        mujoco.mj_step(model, data)
        trajectory[k] = float(downhill @ (data.xpos[body] - x0))
        tilt = max(tilt, abs(float(data.qpos[2])))
        if data.ncon:
            penetration = max(penetration, -float(data.contact.dist[: data.ncon].min()))
        else:
            airborne += 1
    x_exact = exact_displacement(mu, steps * h)
    x_along = float(trajectory[-1])
    return {
        "x_along": x_along,
        "x_exact": x_exact,
        "error": abs(x_along - x_exact),
        "steps": steps,
        "penetration": max(penetration, 0.0),
        "trajectory": trajectory,
        "v_along": float(data.qvel[0]),
        "airborne_steps": airborne,
        "max_tilt": tilt,
    }


def time_incline_steps(
    mu: float,
    h: float,
    steps: int = 1000,
    repeats: int = 5,
    *,
    cone: str = "pyramidal",
    integrator: str = "euler",
    noslip_iterations: int = 0,
    impratio: float = 1.0,
) -> dict:
    """Microseconds per ``mj_step`` called from Python, for the incline problem with ``mu``.

    Use mu = 0.3 for the sliding case and mu = 0.7 for the resting one. Each of ``repeats``
    runs starts from the initial state (reset outside the timing) and times only the loop of
    ``steps`` ``mj_step`` calls with ``perf_counter_ns``. One untimed run warms up first. In the
    sliding case about half of MuJoCo's steps have no contact (the box hops), which makes them
    cheaper than the resting ones.
    Returns ``median_us`` (median of the per-run means), ``min_us``, ``max_us``, ``per_run_us``
    and the settings.
    """
    mujoco, model, data = _build(mu, h, cone, integrator, noslip_iterations, impratio)
    step = mujoco.mj_step
    per_run = []
    for run in range(repeats + 1):
        mujoco.mj_resetData(model, data)
        mujoco.mj_forward(model, data)
        t0 = time.perf_counter_ns()
        for _ in range(steps):
            step(model, data)
        t1 = time.perf_counter_ns()
        if run:  # run 0 is the warm-up
            per_run.append((t1 - t0) / steps / 1e3)
    return {
        "mu": mu,
        "h": h,
        "steps": steps,
        "repeats": repeats,
        "median_us": float(np.median(per_run)),
        "min_us": float(min(per_run)),
        "max_us": float(max(per_run)),
        "per_run_us": per_run,
        "cone": cone,
        "integrator": integrator,
        "mujoco_version": mujoco.__version__,
    }
