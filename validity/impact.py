"""Planar rigid-body impact with Coulomb friction and restitution (the impulse of Algorithm 2).

Model: Routh's method for a single-point planar impact, integrated exactly in the normal
impulse p_n as in Wang and Mason (1992), with Stronge's energetic coefficient of restitution e:
the restitution phase ends when the normal impulse has done work ``-e^2`` times its work in
compression. The contact velocity ``(u_n, u_t)`` changes linearly with the impulse,
``du = K dp`` (K: the inverse inertia at the contact, 2 x 2 symmetric positive definite), and
the friction impulse opposes slip, ``dp_t = -mu sign(u_t) dp_n``, or holds stick when
``|K_nt| <= mu K_tt`` allows; slip may stop, stick or reverse within one impact. With
Stronge's coefficient an impact never gains kinetic energy (Newton's and Poisson's laws can,
when slip stops or reverses), and for a frictionless impact, or one that slips one way
throughout, it equals Poisson's and Newton's: a head-on frictionless impact leaves
``u_n+ = -e u_n-``.

Several contacts touching at once (a face landing flat on a wall) are resolved together, by
Poisson's hypothesis applied to the whole contact set: an impact LCP for compression, then
restitution as e times the compression impulse. The compression impulse P_c = (p_n, p_f)
solves the contact LCP of Eq. 7 (:mod:`validity.contact_lcp`) with v* = v- (the velocity
before the impact), no forces and bias 0, over every touching contact (gap <= band), two
friction directions per contact (the planar friction cone is exact): it leaves no contact
approaching, with Coulomb friction. The impulse applied is (1 + e) P_c. Without friction, or
in a symmetric arrival, this is the point-mass answer: a face striking a wall flat leaves at
-e times its normal speed with no spin (issue 11; impacts one point at a time spin it). When
friction sticks in compression the contacts leave with -e times their arrival velocity,
tangential part included (Poisson's law scales the friction impulse too); when every contact
slips the same way throughout, the tangential velocity changes by mu (1 + e) times the normal
change.

Energy: complementarity of the compression LCP gives P_c' W' v_c = -D, v_c = v- + M^-1 W P_c,
D = sum_i s_i mu p_n,i >= 0 (s_i the sliding speed: frictional dissipation). So
P_c' W' v- = -D - P_c' A P_c with A = W' M^-1 W (positive semidefinite), and the kinetic
energy change of the impulse (1 + e) P_c is
``(1 + e) P_c' W' v- + (1 + e)^2 / 2 P_c' A P_c = -(1 + e) D + (1 + e)(e - 1) / 2 P_c' A P_c``,
never positive for e in [0, 1] and any mu >= 0. A contact that did not take part (it was
separating) may approach after the restitution impulse: the loop then solves again over the
contacts touching, until none approaches, each round dissipative. A single touching contact
keeps Routh's method with Stronge's coefficient above. If the LCP fails even after
regularisation it is solved without friction, and failing that the most approaching contact
alone takes a single-point impact (Mirtich's sequential impulses): both are counted, never
raised. Arrays in, numbers out; compiled with numba, writing into buffers
(:func:`impact_workspace`) the caller allocates once.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from validity.contact_lcp import (
    FAILED,
    FALLBACK_FRICTIONLESS,
    apply_lcp_impulse,
    assemble_lcp,
    contact_jacobians,
    lcp_columns,
    solve_with_fallback,
)

IMPACT_NONE = 0  # the contact does not approach: no impulse
IMPACT_DONE = 1  # Routh's integration ended in restitution (or compression, e = 0)
IMPACT_PLASTIC = 2  # integration did not end within its segments: stopped plastically
# Entries of the ``stats`` array resolve_impacts accumulates into.
S_SIMULTANEOUS, S_FRICTIONLESS, S_SEQUENTIAL = range(3)
STATS_FIELDS = ("simultaneous_impacts", "impact_frictionless_fallbacks", "impact_lcp_failures")
_MAX_SEGMENTS = 16  # slip, stick and reversal phases: at most a handful happen in one impact
_ZERO_SLIP = 1e-12  # |u_t| (length/s) below which the contact is rolling, not slipping


@njit(cache=True)
def contact_inverse_inertia(
    rx: float, ry: float, nx: float, ny: float, mass: float, inertia: float
) -> tuple[float, float, float]:
    """``(K_nn, K_nt, K_tt)``: contact velocity change (normal n, tangent t = (-n_y, n_x)) per
    unit impulse at the point r (relative to the centre of mass) of a body of ``mass`` and
    moment of inertia ``inertia``: K_ab = a.b / m + (r x a)(r x b) / I."""
    rn = rx * ny - ry * nx
    rt = rx * nx + ry * ny  # r x t with t = (-n_y, n_x)
    return (
        1.0 / mass + rn * rn / inertia,
        rn * rt / inertia,
        1.0 / mass + rt * rt / inertia,
    )


@njit(cache=True)
def planar_impact(
    un: float, ut: float, knn: float, knt: float, ktt: float, mu: float, e: float
) -> tuple[float, float, int]:
    """Impulse ``(p_n, p_t, status)`` of one impact with approach speed ``-u_n > 0`` and slip
    ``u_t`` at the contact (Routh's method, Stronge's restitution ``e`` in [0, 1], friction
    ``mu`` >= 0; see the module docstring). ``status`` is ``IMPACT_NONE`` when ``u_n >= 0``."""
    if un >= 0.0:
        return 0.0, 0.0, IMPACT_NONE
    pn, pt = 0.0, 0.0
    work, work_c = 0.0, 0.0  # normal work so far, and in compression (<= 0)
    compressing = True
    stick_ok = mu * ktt >= abs(knt)
    for _ in range(_MAX_SEGMENTS):
        s = 0.0  # slip direction of this segment (0: stick)
        if abs(ut) > _ZERO_SLIP:
            s = 1.0 if ut > 0.0 else -1.0
            dpt = -mu * s
        elif stick_ok:
            ut = 0.0
            dpt = -knt / ktt
        else:  # stick is impossible: slip starts in the direction the impulse drives it
            ut = 0.0
            s = 1.0 if knt > 0.0 else -1.0
            dpt = -mu * s
        dun = knn + knt * dpt
        dut = knt + ktt * dpt
        x = np.inf
        slip_stops = s != 0.0 and dut * s < 0.0
        if slip_stops:
            x = -ut / dut
        ends = 0  # 1: compression ends, 2: the impact ends
        if compressing:
            if dun > 0.0 and -un / dun <= x:
                x, ends = -un / dun, 1
        else:
            left = -e * e * work_c - (work - work_c)  # work restitution still has to do
            if left <= 0.0:
                return pn, pt, IMPACT_DONE
            if dun > 0.0:
                xr = 2.0 * left / (un + math.sqrt(un * un + 2.0 * dun * left))
            else:
                disc = un * un + 2.0 * dun * left
                if disc >= 0.0:
                    xr = 2.0 * left / (un + math.sqrt(disc))
                else:  # u_n returns to 0 before that work is done: the contact stays closed
                    xr = -un / dun
            if xr <= x:
                x, ends = xr, 2
        if not math.isfinite(x):
            break
        work += un * x + 0.5 * dun * x * x
        pn += x
        pt += dpt * x
        un += dun * x
        ut = 0.0 if (slip_stops and ends == 0) else ut + dut * x
        if ends == 1:
            un, work_c, compressing = 0.0, work, False
        elif ends == 2:
            return pn, pt, IMPACT_DONE
    # No end within the segments (not expected for a positive definite K): stop the contact
    # point plastically, the impulse -K^-1 u, which only removes kinetic energy.
    det = knn * ktt - knt * knt
    qn = -(ktt * un - knt * ut) / det
    qt = -(knn * ut - knt * un) / det
    return pn + qn, pt + qt, IMPACT_PLASTIC


@njit(cache=True)
def apply_impulse(
    vel: np.ndarray, rx: float, ry: float, px: float, py: float, mass: float, inertia: float
) -> None:
    """``vel (3,) = (v_x, v_y, omega) += M^-1 Imp``: the impulse ``(p_x, p_y)`` at r (relative
    to the centre of mass) changes the momentum by p and the angular momentum by r x p."""
    vel[0] += px / mass
    vel[1] += py / mass
    vel[2] += (rx * py - ry * px) / inertia


@njit(cache=True)
def contact_velocity(vel: np.ndarray, rx: float, ry: float, nx: float, ny: float) -> float:
    """Velocity along the unit vector n of the body point at r: (v + omega z x r) . n."""
    return (vel[0] - vel[2] * ry) * nx + (vel[1] + vel[2] * rx) * ny


@njit(cache=True)
def collide(
    vel: np.ndarray,
    rx: float,
    ry: float,
    nx: float,
    ny: float,
    mass: float,
    inertia: float,
    mu: float,
    e: float,
) -> int:
    """One impact at the body point r against a static obstacle with normal n (into the body):
    ``vel`` is updated in place by M^-1 Imp; returns the status of :func:`planar_impact`."""
    tx, ty = -ny, nx
    un = contact_velocity(vel, rx, ry, nx, ny)
    ut = contact_velocity(vel, rx, ry, tx, ty)
    knn, knt, ktt = contact_inverse_inertia(rx, ry, nx, ny, mass, inertia)
    pn, pt, status = planar_impact(un, ut, knn, knt, ktt, mu, e)
    if status != IMPACT_NONE:
        apply_impulse(vel, rx, ry, pn * nx + pt * tx, pn * ny + pt * ty, mass, inertia)
    return status


@njit(cache=True)
def impact_workspace(max_contacts: int) -> tuple:
    """Buffers of :func:`simultaneous_impact` for up to ``max_contacts`` touching contacts:
    (rows, W_n, W_t, [W_n | W_f], B, b, z, bias, M^-1 diagonal, v-)."""
    n = max_contacts
    return (
        np.zeros((n, 5)),
        np.zeros((3, n)),
        np.zeros((3, n)),
        np.zeros((3, 3 * n)),
        np.zeros((4 * n, 4 * n)),
        np.zeros(4 * n),
        np.zeros(4 * n),
        np.zeros(n),
        np.zeros(3),
        np.zeros(3),
    )


@njit(cache=True)
def simultaneous_impact(
    vel: np.ndarray,
    cx: float,
    cy: float,
    rows: np.ndarray,
    nt: int,
    mass: float,
    inertia: float,
    mu: float,
    e: float,
    work: tuple,
) -> int:
    """One impact at the ``nt`` contacts ``rows[:nt]`` (``(gap, n_x, n_y, p_x, p_y)``) at once
    (see the module docstring): ``vel`` += (1 + e) M^-1 W P_c, P_c the compression LCP's
    impulse. Returns the LCP's status (LCP_SOLVED, LCP_REGULARISED, FALLBACK_FRICTIONLESS;
    FAILED leaves ``vel`` unchanged)."""
    _, wn, wt, cols, B, b, z, bias, minv, vminus = work
    minv[0], minv[1], minv[2] = 1.0 / mass, 1.0 / mass, 1.0 / inertia
    vminus[0], vminus[1], vminus[2] = vel[0], vel[1], vel[2]
    for i in range(nt):
        bias[i] = 0.0
    contact_jacobians(rows, nt, cx, cy, wn, wt)
    frictional = mu > 0.0
    m = lcp_columns(wn, wt, nt, frictional, cols)
    size = assemble_lcp(cols, m, nt, frictional, mu, minv, bias, vminus, B, b)
    status, m, size, _, _, _ = solve_with_fallback(
        wn, wt, nt, frictional, mu, minv, bias, vminus, cols, m, size, B, b, z
    )
    if status == FAILED:
        return status
    for i in range(m):
        z[i] *= 1.0 + e
    apply_lcp_impulse(cols, m, z, minv, vel)
    return status


@njit(cache=True)
def resolve_impacts(
    vel: np.ndarray,
    cx: float,
    cy: float,
    contacts: np.ndarray,
    nc: int,
    band: float,
    mass: float,
    inertia: float,
    mu: float,
    e: float,
    slack: float,
    max_impacts: int,
    work: tuple,
    stats: np.ndarray,
) -> int:
    """Impacts at the touching contacts (rows ``(gap, n_x, n_y, p_x, p_y)`` of
    :func:`validity.contact_kernel.find_contacts` with gap <= ``band``) of a body with centre
    of mass c, until none approaches faster than ``slack``: one contact touching takes the
    single-point impact of :func:`collide`, several take :func:`simultaneous_impact` together
    (on its failure, the most approaching one alone). ``work``: :func:`impact_workspace` for at
    least ``nc`` contacts. ``stats`` (``STATS_FIELDS``) accumulates the simultaneous impacts
    and their fallbacks. Returns the number of impacts, or -1 when contacts still approach
    after ``max_impacts`` (a jam: the caller stops the body)."""
    touch = work[0]
    for count in range(max_impacts + 1):
        worst, k, nt = -slack, -1, 0
        for i in range(nc):
            if contacts[i, 0] > band:
                continue
            for j in range(5):
                touch[nt, j] = contacts[i, j]
            nt += 1
            un = contact_velocity(
                vel, contacts[i, 3] - cx, contacts[i, 4] - cy, contacts[i, 1], contacts[i, 2]
            )
            if un < worst:
                worst, k = un, i
        if k < 0:
            return count
        if count == max_impacts:
            break
        if nt > 1:
            status = simultaneous_impact(vel, cx, cy, touch, nt, mass, inertia, mu, e, work)
            stats[S_SIMULTANEOUS] += 1
            if status == FALLBACK_FRICTIONLESS:
                stats[S_FRICTIONLESS] += 1
            if status != FAILED:
                continue
            stats[S_SEQUENTIAL] += 1
        collide(
            vel,
            contacts[k, 3] - cx,
            contacts[k, 4] - cy,
            contacts[k, 1],
            contacts[k, 2],
            mass,
            inertia,
            mu,
            e,
        )
    return -1
