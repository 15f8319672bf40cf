"""Stewart-Trinkle time stepping of a rigid planar part among static obstacles (paper Eq. 7).

Generalised coordinates q = (x, y, theta) of the centre of mass, velocity v = (vx, vy, omega),
mass matrix M = diag(m, m, I). Each step of length h:

1. find the contacts within a margin (:func:`validity.contact_kernel.find_contacts`): gaps
   psi_n, normals n, tangents t and points p, giving the Jacobian columns
   W_n = (n, r x n) and W_f = (+t, r x t), (-t, -(r x t)) with r = p - q_xy (two friction
   directions per contact: the planar friction cone is exact);
2. when a contact penetrates deeper than ``CORRECTION_SLOP``, correct the pose, not the
   velocity (post-stabilisation, Cline & Pai 2003; Bullet's split impulse): the smallest
   displacement in the metric M, dq = M^-1 W_n l, with W_n' dq + psi_n >= 0 (a frictionless
   LCP in l), scaled so no point of the part moves more than c h (c the push-out cap, a
   speed); q <- q + dq and psi_n <- psi_n + W_n' dq;
3. solve LCP(B, b) of Eq. 7 for z = (p_n, p_f, s):
   B = [[W_n' M^-1 W_n, W_n' M^-1 W_f, 0], [W_f' M^-1 W_n, W_f' M^-1 W_f, E], [U, -E', 0]],
   b = (W_n' v* + max(psi_n, 0) / h, W_f' v*, 0) with v* = v + h M^-1 (m g + u);
4. v <- v* + M^-1 (W_n p_n + W_f p_f), q <- q + h v (no restitution, as in the paper).

Step 2 replaces the paper's psi_n / h for psi_n < 0, which pushes an overlap out through the
velocity: that adds kinetic energy, and a part wedged between two walls whose contacts cannot
both separate by translation was spun up to hundreds of rad/s by it (stress case 0/2606). A
pose correction adds none (only the potential energy of the lift, at most m |g| depth), and the
velocity LCP then asks of an overlapping contact only that it does not approach.

What a step does not need it skips: no contact within the margin means no LCP (a free step of
the same update), and then as many following steps as provably cannot bring a contact within
the margin skip the contact search too (the bound: the clearance against the farthest any
point of the part can move); an LCP in the same contact mode as the step before is solved by
the previous step's complementary basis, accepted only when it verifies as a solution, before
any pivoting; mu = 0 drops the friction unknowns (an LCP of size n_c instead
of 4 n_c); the broad phase of the contact search bounds far obstacles by their boxes.

A step whose LCP fails even after the solver's regularisation retry falls back to the
frictionless LCP of the same contacts, and if that fails too, to no contact impulse; either
is recorded in the telemetry, never raised. The whole loop is one compiled call.
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
from validity.contact_lcp import (
    FAILED,
    FALLBACK_FRICTIONLESS,
    apply_lcp_impulse,
    assemble_lcp,
    contact_jacobians,
    lcp_columns,
    solve_with_fallback,
)
from validity.geometry_kernel import part_radius, place_part, pose_vertices
from validity.lcp import (
    LCP_REGULARISED,
    LCP_SOLVED,
    guess_basis,
    solve_from_basis_in,
    solve_lcp,
)

# Per-step telemetry columns.
T_CONTACTS, T_STATUS, T_PIVOTS, T_ALPHA, T_RESIDUAL, T_PENETRATION, T_SIZE = range(7)
TELEMETRY_COLUMNS = (
    "contacts",
    "lcp_status",
    "pivots",
    "regularisation",
    "residual",
    "penetration",
    "lcp_size",
)
NO_LCP = -1  # T_STATUS of a step without contacts
CORRECTION_SLOP = (
    1e-7  # deepest overlap (length) left to the velocity LCP without a pose correction
)
WARM = 9  # T_STATUS: the previous step's basis, verified, solved the LCP without pivoting
# T_STATUS also takes validity.contact_lcp's FALLBACK_FRICTIONLESS (the friction LCP failed,
# the frictionless one held) and FAILED (no LCP could be solved; no contact impulse).

# Summary entries.
(
    S_STEPS,
    S_SEARCHES,
    S_LCPS,
    S_REGULARISED,
    S_FALLBACKS,
    S_FAILURES,
    S_MAX_PIVOTS,
    S_MAX_ALPHA,
    S_MAX_RESIDUAL,
    S_MAX_PENETRATION,
    S_CONTACT_STEPS,
    S_WARM,
    S_CORRECTIONS,
    S_MAX_CORRECTION,
) = range(14)
SUMMARY_FIELDS = (
    "steps",
    "contact_searches",
    "lcp_solves",
    "regularised",
    "frictionless_fallbacks",
    "failures",
    "max_pivots",
    "max_regularisation",
    "max_residual",
    "max_penetration",
    "contact_steps",
    "warm_starts",
    "pose_corrections",
    "max_correction",
)

# Why a run ended.
RAN_FULL, CROSSED, AT_REST, LEFT_BOUNDS = range(4)
END_REASONS = ("duration", "crossed", "at_rest", "left_bounds")


@njit(cache=True)
def _free_steps_bound(clear, margin0, h, speed, accel, radius, remaining):
    """How many free steps cannot bring any contact within the margin (at least 0).

    After j free steps no point of the part has moved more than
    j h (|v| + R|w|) + h^2 (|a| + R|alpha|) j (j + 1) / 2, and the margin then is at most
    margin0 + 2 h (speed + j h accel); both grow with j, so the first j that fails ends it.
    """
    j = 0
    while j < remaining:
        k = j + 1
        moved = k * h * speed + h * h * accel * k * (k + 1) / 2.0
        margin = margin0 + 2.0 * h * (speed + (k + 1) * h * accel)
        if moved + margin >= clear:
            break
        j = k
    return j


@njit(cache=True)
def pose_correction(
    contacts: np.ndarray,
    nc: int,
    wn: np.ndarray,
    wt: np.ndarray,
    minv: np.ndarray,
    radius: float,
    max_move: float,
    gap: np.ndarray,
    cols: np.ndarray,
    B: np.ndarray,
    b: np.ndarray,
    z: np.ndarray,
    dq: np.ndarray,
) -> bool:
    """The pose correction dq (step 2 of the module docstring) of the contacts' gaps
    ``contacts[:nc, 0]`` with Jacobian columns ``wn``: dq = M^-1 W_n l for the frictionless
    LCP W_n' M^-1 W_n l + psi_n >= 0, scaled so that no point of the part (radius ``radius``
    about the centre of mass) moves more than ``max_move``. False (dq = 0) when the LCP has no
    solution."""
    dq[0], dq[1], dq[2] = 0.0, 0.0, 0.0
    for i in range(nc):
        gap[i] = contacts[i, 0]
    m = lcp_columns(wn, wt, nc, False, cols)
    size = assemble_lcp(cols, m, nc, False, 0.0, minv, gap, dq, B, b)  # v* = dq = 0
    status, _, _, _ = solve_lcp(B[:size, :size], b[:size], z[:size])
    if status != LCP_SOLVED and status != LCP_REGULARISED:
        return False
    apply_lcp_impulse(cols, m, z, minv, dq)
    move = math.hypot(dq[0], dq[1]) + radius * abs(dq[2])
    if move > max_move:
        scale = max_move / move
        dq[0], dq[1], dq[2] = dq[0] * scale, dq[1] * scale, dq[2] * scale
    return True


@njit(cache=True)
def simulate_kernel(
    state0: np.ndarray,
    wrench: np.ndarray,
    n_steps: int,
    h: float,
    mass: float,
    inertia: float,
    gravity: np.ndarray,
    mu: float,
    margin0: float,
    push_cap: float,
    skip_free: bool,
    warm_start: bool,
    y_stop: float,
    rest_speed: float,
    rest_steps: int,
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
    """Step Eq. 7 up to ``n_steps`` times from ``state0 = (x, y, theta, vx, vy, omega)``.

    ``wrench = (fx, fy, tau)`` is held constant. The run ends early when the centre of mass
    drops below ``y_stop``, when the speed of every point of the part (|v| + R|omega|) stays
    below ``rest_speed`` for ``rest_steps`` steps (0 disables), or when the centre of mass
    would leave ``bounds`` (that step is not taken). Writes the final state to
    ``out_state``, every state to ``traj`` (rows 0..steps) and per-step telemetry to ``tele``
    when they have rows, and totals to ``summary``. Returns ``(steps taken, end reason)``.
    """
    record = traj.shape[0] > 0
    telemetry = tele.shape[0] > 0
    for i in range(summary.shape[0]):
        summary[i] = 0.0
    x, y, th = state0[0], state0[1], state0[2]
    vx, vy, om = state0[3], state0[4], state0[5]
    minv = np.array([1.0 / mass, 1.0 / mass, 1.0 / inertia])
    ax, ay = gravity[0] + wrench[0] / mass, gravity[1] + wrench[1] / mass
    alpha = wrench[2] / inertia
    radius = part_radius(body, body_counts, body_discs)
    accel = math.hypot(ax, ay) + radius * abs(alpha)

    plain = plain_part(body_counts, body_surface, body_corners, body_discs)
    polygon = np.ascontiguousarray(body[0, : body_counts[0]])  # a plain part's only piece
    placed = np.empty_like(polygon)
    world = np.empty_like(body)
    wdiscs = np.empty_like(body_discs)
    contacts = np.empty((MAX_CONTACTS, 5))
    wn = np.empty((3, MAX_CONTACTS))
    wt = np.empty((3, MAX_CONTACTS))
    cols = np.empty((3, 3 * MAX_CONTACTS))
    nmax = 4 * MAX_CONTACTS
    B = np.zeros((nmax, nmax))
    b = np.zeros(nmax)
    z = np.zeros(nmax)
    bias = np.empty(MAX_CONTACTS)
    basic = np.zeros(nmax, dtype=np.bool_)  # the last solved LCP's basis: z_i > 0
    degen = np.zeros(nmax, dtype=np.bool_)  # and its degenerate pairs: z_i = w_i = 0
    basic_size = -1
    trial = np.empty(nmax)  # the warm start's scratch
    guess = np.empty(nmax, dtype=np.bool_)
    idx = np.empty(nmax, dtype=np.int64)
    elim = np.empty((nmax, nmax + 1))
    pivot_col = np.empty(nmax, dtype=np.int64)
    vstar = np.empty(3)
    v = np.empty(3)
    dq = np.empty(3)

    if record:
        traj[0, 0], traj[0, 1], traj[0, 2] = x, y, th
        traj[0, 3], traj[0, 4], traj[0, 5] = vx, vy, om
    free_left = 0
    still = 0
    reason = RAN_FULL
    steps = 0
    for step in range(n_steps):
        last = (x, y, th, vx, vy, om)
        vstar[0], vstar[1], vstar[2] = vx + h * ax, vy + h * ay, om + h * alpha
        status, pivots, reg, residual, depth, nc, size = NO_LCP, 0, 0.0, 0.0, 0.0, 0, 0
        if free_left > 0:
            free_left -= 1
            vx, vy, om = vstar[0], vstar[1], vstar[2]
        else:
            speed = math.hypot(vx, vy) + radius * abs(om)
            margin = margin0 + 2.0 * h * (speed + h * accel)
            if plain:
                pose_vertices(polygon, x, y, th, placed)
                nc, clear = find_contacts(
                    placed, verts, counts, aabbs, circles, surface, corners, margin, contacts
                )
            else:
                place_part(body, body_counts, body_discs, x, y, th, world, wdiscs)
                nc, clear = find_part_contacts(
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
            summary[S_SEARCHES] += 1
            if nc == 0:
                vx, vy, om = vstar[0], vstar[1], vstar[2]
                if skip_free:
                    free_left = _free_steps_bound(
                        clear, margin0, h, speed, accel, radius, n_steps - step - 1
                    )
            else:
                summary[S_CONTACT_STEPS] += 1
                contact_jacobians(contacts, nc, x, y, wn, wt)
                for i in range(nc):
                    depth = max(depth, -contacts[i, 0])
                if depth > CORRECTION_SLOP and pose_correction(
                    contacts, nc, wn, wt, minv, radius, push_cap * h, bias, cols, B, b, z, dq
                ):
                    x, y, th = x + dq[0], y + dq[1], th + dq[2]
                    for i in range(nc):
                        contacts[i, 0] += wn[0, i] * dq[0] + wn[1, i] * dq[1] + wn[2, i] * dq[2]
                    summary[S_CORRECTIONS] += 1
                    moved = math.hypot(dq[0], dq[1]) + radius * abs(dq[2])
                    summary[S_MAX_CORRECTION] = max(summary[S_MAX_CORRECTION], moved)
                for i in range(nc):
                    bias[i] = max(contacts[i, 0], 0.0) / h
                v[0], v[1], v[2] = vstar[0], vstar[1], vstar[2]
                frictional = mu > 0.0
                m = lcp_columns(wn, wt, nc, frictional, cols)
                size = assemble_lcp(cols, m, nc, frictional, mu, minv, bias, vstar, B, b)
                summary[S_LCPS] += 1
                warm = False
                if warm_start and size == basic_size:
                    residual = solve_from_basis_in(
                        B[:size, :size],
                        b[:size],
                        basic[:size],
                        degen[:size],
                        z[:size],
                        trial,
                        guess,
                        idx,
                        elim,
                        pivot_col,
                    )
                    warm = residual < np.inf
                if warm:
                    status = WARM
                    summary[S_WARM] += 1
                else:
                    status, m, size, pivots, reg, residual = solve_with_fallback(
                        wn, wt, nc, frictional, mu, minv, bias, vstar, cols, m, size, B, b, z
                    )
                if status == FAILED:
                    summary[S_FAILURES] += 1
                    basic_size = -1
                else:
                    basic_size = size
                    if not warm:  # a verified guess has already left its basis in basic
                        guess_basis(B[:size, :size], b[:size], z[:size], basic[:size], degen[:size])
                    if status == FALLBACK_FRICTIONLESS:
                        summary[S_FALLBACKS] += 1
                    elif status == LCP_REGULARISED:
                        summary[S_REGULARISED] += 1
                    apply_lcp_impulse(cols, m, z, minv, v)
                vx, vy, om = v[0], v[1], v[2]
                summary[S_MAX_PIVOTS] = max(summary[S_MAX_PIVOTS], pivots)
                summary[S_MAX_ALPHA] = max(summary[S_MAX_ALPHA], reg)
                summary[S_MAX_RESIDUAL] = max(summary[S_MAX_RESIDUAL], residual)
                summary[S_MAX_PENETRATION] = max(summary[S_MAX_PENETRATION], depth)
        x, y, th = x + h * vx, y + h * vy, th + h * om
        steps = step + 1
        if record:
            traj[steps, 0], traj[steps, 1], traj[steps, 2] = x, y, th
            traj[steps, 3], traj[steps, 4], traj[steps, 5] = vx, vy, om
        if telemetry:
            row = tele[step]
            row[T_CONTACTS], row[T_STATUS], row[T_PIVOTS] = nc, status, pivots
            row[T_ALPHA], row[T_RESIDUAL], row[T_PENETRATION], row[T_SIZE] = (
                reg,
                residual,
                depth,
                size,
            )
        if y < y_stop:
            reason = CROSSED
            break
        if not (bounds[0] <= x <= bounds[1] and bounds[2] <= y <= bounds[3]):
            x, y, th, vx, vy, om = last  # the step out is not taken: end at the last state in
            steps = step
            reason = LEFT_BOUNDS
            break
        if rest_steps > 0:
            still = still + 1 if math.hypot(vx, vy) + radius * abs(om) < rest_speed else 0
            if still >= rest_steps:
                reason = AT_REST
                break
    summary[S_STEPS] = steps
    out_state[0], out_state[1], out_state[2] = x, y, th
    out_state[3], out_state[4], out_state[5] = vx, vy, om
    return steps, reason
