"""The contact LCP of Eq. 7 assembled from contact rows, and solved with its fallbacks.

Shared by the dynamic level's time step (:mod:`validity.stewart_trinkle`, v* the velocity
after the free forces, bias the stabilisation psi_n / h) and the kinematic level's
simultaneous impacts (:mod:`validity.impact`, v* the velocity before the impact, bias 0).

A body with velocity v = (vx, vy, omega) and mass matrix M = diag(m, m, I) (``minv`` holds its
inverse diagonal) touches at contacts with normal n (into the body), tangent t = (-n_y, n_x)
and lever r = p - c (c the centre of mass): Jacobian columns W_n = (n, r x n) and
W_f = (+t, r x t), (-t, -(r x t)) (two friction directions per contact: the planar friction
cone is exact). The LCP(B, b) in z = (p_n, p_f, s) is
``B = [[W_n' M^-1 W_n, W_n' M^-1 W_f, 0], [W_f' M^-1 W_n, W_f' M^-1 W_f, E], [U, -E', 0]]``,
``b = (W_n' v* + bias, W_f' v*, 0)``, and the new velocity is v* + M^-1 (W_n p_n + W_f p_f).
Without friction it shrinks to the n_c normal rows. Arrays in, arrays out; compiled with numba,
writing into buffers the caller allocates once.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from validity.lcp import LCP_REGULARISED, LCP_SOLVED, solve_lcp
from validity.leaf_kernel import leaf_kernel

FALLBACK_FRICTIONLESS = 10  # status: the friction LCP failed, the frictionless one held
FAILED = 11  # status: no LCP could be solved; no contact impulse


@leaf_kernel
def contact_jacobians(
    contacts: np.ndarray, nc: int, x: float, y: float, wn: np.ndarray, wt: np.ndarray
) -> None:
    """Columns W_n (3, nc) and the tangent columns W_t (3, nc) of the contact rows
    ``(gap, n_x, n_y, p_x, p_y)`` of a body with centre of mass (x, y); W_f is (+W_t, -W_t)."""
    for i in range(nc):
        nx, ny = contacts[i, 1], contacts[i, 2]
        rx, ry = contacts[i, 3] - x, contacts[i, 4] - y
        tx, ty = -ny, nx
        wn[0, i], wn[1, i], wn[2, i] = nx, ny, rx * ny - ry * nx
        wt[0, i], wt[1, i], wt[2, i] = tx, ty, rx * ty - ry * tx


@leaf_kernel
def lcp_columns(wn: np.ndarray, wt: np.ndarray, nc: int, frictional: bool, cols: np.ndarray) -> int:
    """[W_n | W_f] into ``cols (3, >= 3 nc)``, W_f = (+t_i, -t_i) per contact; W_n alone when
    frictionless. Returns the number of columns m."""
    for i in range(nc):
        for k in range(3):
            cols[k, i] = wn[k, i]
            if frictional:
                cols[k, nc + 2 * i] = wt[k, i]
                cols[k, nc + 2 * i + 1] = -wt[k, i]
    return 3 * nc if frictional else nc


@leaf_kernel
def assemble_lcp(
    cols: np.ndarray,
    m: int,
    nc: int,
    frictional: bool,
    mu: float,
    minv: np.ndarray,
    bias: np.ndarray,
    vstar: np.ndarray,
    B: np.ndarray,
    b: np.ndarray,
) -> int:
    """B and b of Eq. 7 (size 4 n_c, unknowns p_n, p_f, s), or of the frictionless problem
    (size n_c, unknowns p_n) when ``frictional`` is False. Returns the size."""
    n = 4 * nc if frictional else nc
    for i in range(n):
        b[i] = 0.0
        for j in range(n):
            B[i, j] = 0.0
    for i in range(m):
        b[i] = cols[0, i] * vstar[0] + cols[1, i] * vstar[1] + cols[2, i] * vstar[2]
        for j in range(m):
            B[i, j] = (
                cols[0, i] * minv[0] * cols[0, j]
                + cols[1, i] * minv[1] * cols[1, j]
                + cols[2, i] * minv[2] * cols[2, j]
            )
    for i in range(nc):
        b[i] += bias[i]
        if frictional:
            for s in range(2):
                B[nc + 2 * i + s, m + i] = 1.0  # E
                B[m + i, nc + 2 * i + s] = -1.0  # -E'
            B[m + i, i] = mu  # U
    return n


@leaf_kernel
def apply_lcp_impulse(
    cols: np.ndarray, m: int, z: np.ndarray, minv: np.ndarray, v: np.ndarray
) -> None:
    """v += M^-1 [W_n | W_f] (p_n, p_f)."""
    for i in range(m):
        v[0] += minv[0] * cols[0, i] * z[i]
        v[1] += minv[1] * cols[1, i] * z[i]
        v[2] += minv[2] * cols[2, i] * z[i]


@njit(cache=True)
def solve_with_fallback(
    wn: np.ndarray,
    wt: np.ndarray,
    nc: int,
    frictional: bool,
    mu: float,
    minv: np.ndarray,
    bias: np.ndarray,
    vstar: np.ndarray,
    cols: np.ndarray,
    m: int,
    size: int,
    B: np.ndarray,
    b: np.ndarray,
    z: np.ndarray,
) -> tuple[int, int, int, int, float, float]:
    """Solve the assembled LCP (``cols``, ``B``, ``b`` of ``m`` columns and ``size`` rows) by
    :func:`validity.lcp.solve_lcp`; when that fails with friction, assemble and solve the
    frictionless LCP of the same contacts instead. Returns ``(status, m, size, pivots,
    regularisation, residual)``: status LCP_SOLVED, LCP_REGULARISED, FALLBACK_FRICTIONLESS or
    FAILED, and the m and size of the problem z solves (apply it with ``cols[:, :m]``)."""
    status, pivots, reg, residual = solve_lcp(B[:size, :size], b[:size], z[:size])
    solved = status == LCP_SOLVED or status == LCP_REGULARISED
    if not solved and frictional:
        m = lcp_columns(wn, wt, nc, False, cols)
        size = assemble_lcp(cols, m, nc, False, mu, minv, bias, vstar, B, b)
        st2, pv2, reg, residual = solve_lcp(B[:size, :size], b[:size], z[:size])
        pivots += pv2
        status = FALLBACK_FRICTIONLESS if st2 <= LCP_REGULARISED else FAILED
    elif not solved:
        status = FAILED
    return status, m, size, pivots, reg, residual
