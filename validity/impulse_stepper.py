"""Time stepping of the kinematic model (paper Eq. 8, Algorithm 2), compiled as one loop.

Every step of length h starts with the velocity the input commands, ``v = u`` (Eq. 8's
``v^{l+1} = W(q^l) u^{l+1}``, W the identity in free space), and moves the pose by
``q <- q + t v``. When the motion would bring the part into an obstacle, the step advances to
the time of impact, applies the impact law of :mod:`validity.impact`
(``v <- v + M^-1 Imp``: Routh's single-point impact at one touching contact, the impact LCP
over all of them when several touch at once) and continues with the new velocity for the
rest of the step.

Time of impact: conservative advancement (Mirtich). For a convex part moving with velocity
``(v, omega)`` against a convex obstacle, each contact candidate of
:func:`validity.contact_kernel.find_contacts` (gap g, normal n into the part) stays apart for
``t < (g - target) / (max(0, -v.n) + |omega| R)``, R the part's radius about its centre of
mass: the distance of a translating point to a convex set is convex in time, and rotation
moves no point faster than ``|omega| R``. Candidates not listed are at least the search
margin away. The advance is therefore safe at any speed and any wall thickness: nothing
tunnels. Touching contacts (gap <= band) that do not approach are left to slide; a move that
would still overlap (second order in rotation) is halved until it does not.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from validity.contact_kernel import (
    MAX_CONTACTS,
    find_contacts,
    find_part_contacts,
    plain_part,
)
from validity.geometry_kernel import (
    part_penetrates,
    part_radius,
    penetrates,
    place_part,
    pose_vertices,
)
from validity.impact import STATS_FIELDS, impact_workspace, resolve_impacts

TELEMETRY_COLUMNS = ("impacts", "sub_steps", "jammed", "stalled", "halvings")
SUMMARY_FIELDS = (
    "steps",
    "impacts",
    "sub_steps",
    "jams",
    "stalls",
    "halvings",
    "contact_steps",
    *STATS_FIELDS,  # simultaneous impacts, and their LCP's fallbacks (see validity.impact)
)
_S_STATS = SUMMARY_FIELDS.index(STATS_FIELDS[0])
END_REASONS = ("duration", "left_bounds")

_MAX_SUB_STEPS = 64  # advances within one step (time of impact, impacts, slides)
_MAX_HALVINGS = 40  # a slide that overlaps is halved at most this often (2^-40 of it)
_MIN_MARGIN = 0.05  # contact search radius (length) at least this: few searches when slow


@njit(cache=True)
def _safe_time(
    vel: np.ndarray,
    radius: float,
    contacts: np.ndarray,
    nc: int,
    margin: float,
    band: float,
    target: float,
    t_left: float,
) -> float:
    """Longest advance (<= t_left) that brings no candidate closer than ``target``."""
    rot = abs(vel[2]) * radius
    speed = math.hypot(vel[0], vel[1]) + rot
    unlisted = margin  # candidates not found are at least this far away ...
    if nc == contacts.shape[0]:  # ... unless the list overflowed: then past its largest gap
        for i in range(nc):
            unlisted = min(unlisted, max(contacts[i, 0], target))
    t = t_left
    if speed > 0.0:
        t = min(t, (unlisted - target) / speed)
    for i in range(nc):
        gap = contacts[i, 0]
        if gap <= band:
            continue  # touching and not approaching (impacts were resolved first)
        rate = max(0.0, -(vel[0] * contacts[i, 1] + vel[1] * contacts[i, 2])) + rot
        if rate > 0.0:
            t = min(t, (gap - target) / rate)
    return max(t, 0.0)


@njit(cache=True)
def kinematic_kernel(
    state0: np.ndarray,
    u: np.ndarray,
    n_steps: int,
    h: float,
    mass: float,
    inertia: float,
    mu: float,
    e: float,
    band: float,
    max_impacts: int,
    body: np.ndarray,
    body_counts: np.ndarray,
    body_surface: np.ndarray,
    body_corners: np.ndarray,
    body_discs: np.ndarray,
    verts: np.ndarray,
    counts: np.ndarray,
    aabbs: np.ndarray,
    circles: np.ndarray,
    surface: np.ndarray,
    corners: np.ndarray,
    bounds: np.ndarray,
    out_state: np.ndarray,
    traj: np.ndarray,
    tele: np.ndarray,
    summary: np.ndarray,
) -> tuple[int, int]:
    """``n_steps`` steps of Eq. 8 with impacts from ``state0 = (x, y, yaw, vx, vy, omega)``
    under the velocity input ``u``; returns ``(steps, reason)`` (index into END_REASONS).

    A step whose motion would take the centre of mass out of ``bounds`` is not taken: the run
    ends at the last state inside (as Algorithm 1's ``break``). ``traj (n_steps + 1, 6)`` and
    ``tele (n_steps, len(TELEMETRY_COLUMNS))`` are filled when they have rows; ``summary``
    accumulates ``SUMMARY_FIELDS``. ``out_state`` receives the final state.
    """
    radius = part_radius(body, body_counts, body_discs)
    target = 0.5 * band
    record = traj.shape[0] > 0
    x, y, yaw = state0[0], state0[1], state0[2]
    vel_out = state0[3:6].copy()
    plain = plain_part(body_counts, body_surface, body_corners, body_discs)
    polygon = np.ascontiguousarray(body[0, : body_counts[0]])  # a plain part's only piece
    placed = np.empty_like(polygon)
    world = np.empty_like(body)
    probe = np.empty_like(body)
    wdiscs = np.empty_like(body_discs)
    probe_discs = np.empty_like(body_discs)
    contacts = np.zeros((MAX_CONTACTS, 5))
    work = impact_workspace(MAX_CONTACTS)
    stats = np.zeros(len(STATS_FIELDS))
    vel = np.empty(3)
    if record:
        traj[0, :3] = x, y, yaw
        traj[0, 3:] = vel_out
    steps, reason = 0, 0
    for k in range(n_steps):
        vel[:] = u
        t_left = h
        px, py, pyaw = x, y, yaw
        impacts, sub, jammed, stalled, halvings, touched = 0, 0, 0, 0, 0, 0
        while t_left > 0.0:
            if sub == _MAX_SUB_STEPS:
                stalled = 1
                break
            sub += 1
            speed = math.hypot(vel[0], vel[1]) + abs(vel[2]) * radius
            if speed == 0.0:
                break
            margin = max(_MIN_MARGIN, speed * t_left + band)
            if plain:
                pose_vertices(polygon, x, y, yaw, placed)
                nc, _ = find_contacts(
                    placed, verts, counts, aabbs, circles, surface, corners, margin, contacts
                )
            else:
                place_part(body, body_counts, body_discs, x, y, yaw, world, wdiscs)
                nc, _ = find_part_contacts(
                    world,
                    body_counts,
                    body_surface,
                    body_corners,
                    wdiscs,
                    verts,
                    counts,
                    aabbs,
                    circles,
                    surface,
                    corners,
                    margin,
                    contacts,
                )
            for i in range(nc):
                if contacts[i, 0] <= band:
                    touched = 1
            n_imp = resolve_impacts(
                vel, x, y, contacts, nc, band, mass, inertia, mu, e, 1e-12, max_impacts, work, stats
            )
            if n_imp < 0:
                vel[:] = 0.0
                jammed = 1
                break
            impacts += n_imp
            t = _safe_time(vel, radius, contacts, nc, margin, band, target, t_left)
            if t <= 0.0:
                continue
            for _ in range(_MAX_HALVINGS + 1):
                nx, ny, nyaw = x + t * vel[0], y + t * vel[1], yaw + t * vel[2]
                if plain:
                    pose_vertices(polygon, nx, ny, nyaw, placed)
                    inside = penetrates(placed, verts, counts, aabbs, circles)
                else:
                    place_part(body, body_counts, body_discs, nx, ny, nyaw, probe, probe_discs)
                    inside = part_penetrates(
                        probe, body_counts, probe_discs, verts, counts, aabbs, circles
                    )
                if not inside:
                    break
                t *= 0.5
                halvings += 1
            else:
                vel[:] = 0.0
                jammed = 1
                break
            x, y, yaw = nx, ny, nyaw
            t_left -= t
        yaw = (yaw + math.pi) % (2.0 * math.pi) - math.pi
        if not (bounds[0] <= x <= bounds[1] and bounds[2] <= y <= bounds[3]):
            x, y, yaw = px, py, pyaw
            reason = 1
            break
        vel_out[:] = vel
        steps = k + 1
        if record:
            traj[k + 1, 0], traj[k + 1, 1], traj[k + 1, 2] = x, y, yaw
            traj[k + 1, 3:] = vel_out
            tele[k, 0], tele[k, 1], tele[k, 2] = impacts, sub, jammed
            tele[k, 3], tele[k, 4] = stalled, halvings
        summary[1] += impacts
        summary[2] += sub
        summary[3] += jammed
        summary[4] += stalled
        summary[5] += halvings
        summary[6] += touched
    summary[0] += steps
    for i in range(stats.shape[0]):
        summary[_S_STATS + i] += stats[i]
    out_state[0], out_state[1], out_state[2] = x, y, yaw
    out_state[3:] = vel_out
    return steps, reason
