"""Linear complementarity problems of contact dynamics, solved by Lemke's method.

LCP(M, q): find ``z >= 0`` with ``w = M z + q >= 0`` and ``z^T w = 0``. The contact levels
pose one per time step (Stewart & Trinkle 1996, planar Coulomb friction): M is neither
symmetric nor positive semidefinite, and resting contacts make it degenerate (a box lying
flat on collinear contacts, duplicate or nearly coincident contacts). Lemke's complementary
pivoting (covering vector 1) processes these LCPs whenever ``q^T z >= 0`` for every solution z
of LCP(M, 0), which holds unless the contacts are wedged (a self-balanced load through a
penetrating contact, psi < 0); wedged problems often have no solution and may end on a ray.
Four measures make it dependable in floating point:

* Lexicographic ratio test (Cottle, Pang & Stone, *The Linear Complementarity Problem*,
  1992, Sec. 4.4 and 4.9): ties in the minimum ratio are broken on the rows of
  ``[B^-1 q, B^-1]`` divided by the pivot column entry, which rules out cycling on degenerate
  problems; ratios within a relative ``_TIE_TOL`` count as tied, since rounding splits exact
  ties. A tie that includes the artificial variable ``z0`` goes to ``z0``, which then leaves.
* ``z0`` at zero (to ``_Z0_TOL * max|q|``) ends the run: the basis is then a solution. Rounded
  data (a friction row of q at -1e-19 instead of 0) otherwise walks into a ray.
* One step of iterative refinement on the final basis (on contacts 1e-6 apart the largest
  residual fell from 8e-10 to 1e-11 of ``1 + max|q|``).
* Regularisation retry: near-coincident contacts (1e-7 to 1e-9 apart; condition numbers past
  1e16) can end a run on a secondary ray. The retry solves LCP(M + alpha I, q) with
  ``alpha = 1e-12 * max|M|``, multiplied by 100 per retry, at most ``MAX_RETRIES`` retries.

Every attempt is judged by its residual against the original (M, q), whatever ended it:
``max_i |min(z_i, w_i)|`` together with ``max(0, -min z)`` and ``max(0, -min w)``. A run on the
original problem is accepted at ``TOL * (1 + max|q|)``. A regularised solution violates the
original problem by ``alpha * z`` in w (its complementary rows have ``w = -alpha z``), which
dominates its residual; it is accepted at the looser ``TOL_REGULARISED * (1 + max|q|)``: q is a
velocity, so that is a normal or sliding velocity error of at most 1e-6 (1 + max|q|) in one
step. In the tests regularised residuals reach 4e-7 (median 5e-10) of ``1 + max|q|``.

Tableau conventions: the basis equations are ``w - M z - d z0 = q`` with ``d = 1``, columns
ordered ``w_0..w_{n-1}, z_0..z_{n-1}, z0``; the basis inverse ``B^-1`` is kept explicitly,
starting from ``B = I`` (w basic). Lexicographic feasibility starts with the entry of ``z0``:
the leaving row is the lexicographic minimum of the rows ``[q_i, e_i]``, which among tied
minimal ``q_i`` is the one with the largest index.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from validity.leaf_kernel import leaf_kernel

LCP_SOLVED = 0  # solved by Lemke on the original problem
LCP_REGULARISED = 1  # solved after one or more regularisation retries
LCP_RAY = 2  # secondary ray termination (unrecovered)
LCP_MAX_PIVOTS = 3  # pivot limit reached (unrecovered)
LCP_RESIDUAL = 4  # finished but the residual check failed, or M, q not finite (unrecovered)

TOL = 1e-9  # residual acceptance, original problem, relative to 1 + max|q|
TOL_REGULARISED = 1e-6  # residual acceptance after regularisation, relative to 1 + max|q|
REG_START = 1e-12  # first alpha, relative to max|M|
REG_GROWTH = 100.0  # alpha factor per retry
MAX_RETRIES = 5
PIVOTS_PER_ROW = 50  # solve_lcp's pivot limit per attempt: PIVOTS_PER_ROW * n + PIVOT_BASE
PIVOT_BASE = 50

_PIVOT_TOL = 1e-9  # pivot column entries below this times the column's max |entry| are zero
_TIE_TOL = 1e-9  # ratios within this (relative) of the minimum are ties
_Z0_TOL = 1e-12  # z0 below this times max|q| is zero: the basis is then complementary


@leaf_kernel
def _column(M: np.ndarray, alpha: float, binv: np.ndarray, var: int, col: np.ndarray) -> None:
    """``B^-1`` times the tableau column of ``w_var`` (var < n) or ``z_{var-n}``."""
    n = M.shape[0]
    if var < n:
        for i in range(n):
            col[i] = binv[i, var]
        return
    j = var - n
    for i in range(n):
        acc = alpha * binv[i, j]
        for k in range(n):
            acc += binv[i, k] * M[k, j]
        col[i] = -acc


@leaf_kernel
def _leaving_row(
    x: np.ndarray,
    binv: np.ndarray,
    col: np.ndarray,
    basis: np.ndarray,
    art: int,
    cand: np.ndarray,
) -> int:
    """The lexicographic minimum-ratio row for pivot column ``col``; -1 if unbounded (a ray)."""
    n = x.shape[0]
    cmax = 0.0
    xmax = 0.0
    for i in range(n):
        cmax = max(cmax, abs(col[i]))
        xmax = max(xmax, abs(x[i]))
    ptol = _PIVOT_TOL * cmax
    best = np.inf
    for i in range(n):
        if col[i] > ptol:
            best = min(best, max(x[i], 0.0) / col[i])
    if best == np.inf:
        return -1
    bound = best + _TIE_TOL * (xmax / cmax + best)
    m = 0
    for i in range(n):
        if col[i] > ptol and max(x[i], 0.0) / col[i] <= bound:
            if basis[i] == art:
                return i
            cand[m] = i
            m += 1
    for k in range(n):
        if m == 1:
            break
        lo = np.inf
        hi = 0.0
        for c in range(m):
            v = binv[cand[c], k] / col[cand[c]]
            lo = min(lo, v)
            hi = max(hi, abs(v))
        bound = lo + _TIE_TOL * hi
        kept = 0
        for c in range(m):
            if binv[cand[c], k] / col[cand[c]] <= bound:
                cand[kept] = cand[c]
                kept += 1
        m = kept
    return cand[0]


@leaf_kernel
def _pivot(x: np.ndarray, binv: np.ndarray, col: np.ndarray, r: int) -> None:
    n = x.shape[0]
    p = col[r]
    x[r] /= p
    for k in range(n):
        binv[r, k] /= p
    for i in range(n):
        if i != r and col[i] != 0.0:
            f = col[i]
            x[i] -= f * x[r]
            for k in range(n):
                binv[i, k] -= f * binv[r, k]


@leaf_kernel
def _refine(
    M: np.ndarray,
    q: np.ndarray,
    alpha: float,
    binv: np.ndarray,
    basis: np.ndarray,
    x: np.ndarray,
    r: np.ndarray,
) -> None:
    """One step of iterative refinement of the basic solution: ``x += B^-1 (q - B x)``."""
    n = M.shape[0]
    for i in range(n):
        r[i] = q[i]
    for j in range(n):
        var = basis[j]
        if var < n:
            r[var] -= x[j]
        elif var < 2 * n:
            c = var - n
            r[c] += alpha * x[j]
            for i in range(n):
                r[i] += M[i, c] * x[j]
        else:
            for i in range(n):
                r[i] += x[j]
    for i in range(n):
        acc = 0.0
        for k in range(n):
            acc += binv[i, k] * r[k]
        x[i] += acc


@njit(cache=True)
def _lemke(
    M: np.ndarray, q: np.ndarray, alpha: float, z: np.ndarray, max_pivots: int
) -> tuple[int, int]:
    """Lemke on LCP(M + alpha I, q); see :func:`lemke`."""
    n = M.shape[0]
    for i in range(n):
        z[i] = 0.0
    if n == 0:
        return LCP_SOLVED, 0
    qmin = q[0]
    qmax = abs(q[0])
    for i in range(1, n):
        qmin = min(qmin, q[i])
        qmax = max(qmax, abs(q[i]))
    if qmin >= 0.0:
        return LCP_SOLVED, 0

    art = 2 * n
    binv = np.eye(n)
    x = q.copy()
    col = np.empty(n)
    cand = np.empty(n, dtype=np.int64)
    basis = np.arange(n)
    r = 0
    bound = qmin + _TIE_TOL * qmax
    for i in range(n):
        if q[i] <= bound:
            r = i
    for i in range(n):
        col[i] = -1.0
    _pivot(x, binv, col, r)
    leaving = basis[r]
    basis[r] = art
    pivots = 1
    status = LCP_MAX_PIVOTS
    z0_zero = _Z0_TOL * qmax
    z0_row = r  # z0 keeps its row until it leaves
    while pivots < max_pivots:
        if x[z0_row] <= z0_zero:
            status = LCP_SOLVED
            break
        entering = leaving + n if leaving < n else leaving - n
        _column(M, alpha, binv, entering, col)
        r = _leaving_row(x, binv, col, basis, art, cand)
        if r < 0:
            status = LCP_RAY
            break
        _pivot(x, binv, col, r)
        leaving = basis[r]
        basis[r] = entering
        pivots += 1
        if leaving == art:
            status = LCP_SOLVED
            break

    if status == LCP_SOLVED:
        _refine(M, q, alpha, binv, basis, x, col)
    for i in range(n):
        if n <= basis[i] < art:
            z[basis[i] - n] = max(x[i], 0.0)
    return status, pivots


@njit(cache=True)
def lemke(M: np.ndarray, q: np.ndarray, z: np.ndarray, max_pivots: int) -> tuple[int, int]:
    """One run of Lemke's complementary pivoting (covering vector 1, lexicographic ratio test).

    Writes z (n,) in place: the basic z-values, clipped at 0 (rounding), zeros elsewhere.
    Returns (status in {LCP_SOLVED, LCP_RAY, LCP_MAX_PIVOTS}, pivots). If q >= 0: z = 0 with 0
    pivots (with 1 pivot if min q is negative only by rounding, above -1e-12 max|q|). On
    a ray or the pivot limit z holds the last basis' z-values (an almost-complementary point).
    """
    return _lemke(M, q, 0.0, z, max_pivots)


@leaf_kernel
def lcp_residual(M: np.ndarray, q: np.ndarray, z: np.ndarray) -> float:
    """``max(max_i |min(z_i, w_i)|, -min z, -min w, 0)`` with ``w = M z + q``."""
    n = M.shape[0]
    res = 0.0
    for i in range(n):
        w = q[i]
        for k in range(n):
            w += M[i, k] * z[k]
        res = max(res, abs(min(z[i], w)), -z[i], -w)
        if math.isnan(w) or math.isnan(z[i]):
            return np.inf
    return res


@leaf_kernel
def _finite(a: np.ndarray) -> bool:
    for v in a.flat:
        if not math.isfinite(v):
            return False
    return True


@njit(cache=True)
def solve_lcp(M: np.ndarray, q: np.ndarray, z: np.ndarray) -> tuple[int, int, float, float]:
    """Lemke with the regularisation retry and the residual check (see the module docstring).

    Writes z. Returns (status, total pivots over all attempts, alpha used (0.0 when none; the
    last one tried on a failure), residual of z against the original problem). Pivot limit per
    attempt: ``PIVOTS_PER_ROW * n + PIVOT_BASE``. Never raises and never writes NaN into z: on
    an unrecovered failure z holds the attempt with the smallest residual if finite, else zeros,
    and the status is the first attempt's ending (LCP_RESIDUAL if it finished). M or q with NaN
    or inf: LCP_RESIDUAL, z = 0, residual inf.
    """
    n = M.shape[0]
    for i in range(n):
        z[i] = 0.0
    if not (_finite(M) and _finite(q)):
        return LCP_RESIDUAL, 0, 0.0, np.inf
    max_pivots = PIVOTS_PER_ROW * n + PIVOT_BASE
    scale = 1.0
    mmax = 0.0
    for i in range(n):
        scale = max(scale, 1.0 + abs(q[i]))
        for k in range(n):
            mmax = max(mmax, abs(M[i, k]))

    trial = np.empty(n)
    best_res = np.inf
    first_status = LCP_SOLVED
    total = 0
    alpha = 0.0
    for attempt in range(MAX_RETRIES + 1):
        if attempt == 1:
            alpha = REG_START * mmax if mmax > 0.0 else REG_START
        elif attempt > 1:
            alpha *= REG_GROWTH
        status, pivots = _lemke(M, q, alpha, trial, max_pivots)
        total += pivots
        res = lcp_residual(M, q, trial)
        if attempt == 0:
            first_status = status if status != LCP_SOLVED else LCP_RESIDUAL
        if res < best_res:
            best_res = res
            for i in range(n):
                z[i] = trial[i]
        tol = TOL if attempt == 0 else TOL_REGULARISED
        if res <= tol * scale:
            for i in range(n):
                z[i] = trial[i]
            return (LCP_SOLVED if attempt == 0 else LCP_REGULARISED), total, alpha, res
    if best_res == np.inf:
        for i in range(n):
            z[i] = 0.0
        best_res = lcp_residual(M, q, z)
    return first_status, total, alpha, best_res


@leaf_kernel
def guess_basis(
    M: np.ndarray, q: np.ndarray, z: np.ndarray, basic: np.ndarray, degenerate: np.ndarray
) -> None:
    """The basis to guess next step from this step's solution z of LCP(M, q): ``basic``, every
    z_i > 0; ``degenerate``, every pair with z_i = 0 and w_i = (Mz + q)_i = 0 to the solver's
    tolerance, which a pivoting solver may have held basic at zero."""
    n = M.shape[0]
    scale = 1.0
    for i in range(n):
        scale = max(scale, 1.0 + abs(q[i]))
    for i in range(n):
        basic[i] = z[i] > 0.0
        degenerate[i] = False
        if not basic[i]:
            w = q[i]
            for k in range(n):
                w += M[i, k] * z[k]
            degenerate[i] = abs(w) <= TOL * scale


@leaf_kernel
def _solve_guess(
    M: np.ndarray,
    q: np.ndarray,
    guess: np.ndarray,
    trial: np.ndarray,
    idx: np.ndarray,
    a: np.ndarray,
    pivot_col: np.ndarray,
) -> bool:
    """Solve ``M_SS z_S = -q_S`` for S = {i: guess[i]} into ``trial`` (zero off S), Gaussian
    elimination with partial pivoting in one pass. A column without a pivot (M_SS singular)
    leaves S (``guess[i]`` is cleared): its z_i is 0 and the rows left over are not solved for
    (the caller verifies the result). Returns whether a column left. ``idx``, ``a`` (at least
    n x (n + 1)) and ``pivot_col`` are scratch."""
    n = M.shape[0]
    m = 0
    for i in range(n):
        trial[i] = 0.0
        if guess[i]:
            idx[m] = i
            m += 1
    for r in range(m):
        for c in range(m):
            a[r, c] = M[idx[r], idx[c]]
        a[r, m] = -q[idx[r]]
    rows = 0
    for c in range(m):
        p = rows
        for r in range(rows + 1, m):
            if abs(a[r, c]) > abs(a[p, c]):
                p = r
        if rows >= m or not abs(a[p, c]) > 1e-13:
            guess[idx[c]] = False  # no pivot: z of this column stays 0
            continue
        if p != rows:
            for k in range(c, m + 1):
                a[rows, k], a[p, k] = a[p, k], a[rows, k]
        for r in range(rows + 1, m):
            f = a[r, c] / a[rows, c]
            if f != 0.0:
                for k in range(c, m + 1):
                    a[r, k] -= f * a[rows, k]
        pivot_col[rows] = c
        rows += 1
    for r in range(rows - 1, -1, -1):
        c = pivot_col[r]
        s = a[r, m]
        for k in range(c + 1, m):
            s -= a[r, k] * trial[idx[k]]
        trial[idx[c]] = s / a[r, c]
    return rows < m


@njit(cache=True)
def solve_from_basis(
    M: np.ndarray, q: np.ndarray, basic: np.ndarray, degenerate: np.ndarray, z: np.ndarray
) -> float:
    """Try a guessed complementary basis: z_i basic where ``basic[i]``, w_i basic elsewhere.

    Solves ``M_SS z_S = -q_S`` (Gaussian elimination, partial pivoting) and accepts the result
    only if it is a solution of LCP(M, q) to the same tolerance as :func:`solve_lcp`
    (residual <= ``TOL * (1 + max|q|)``). A time stepper passes the basis of its previous step
    (:func:`guess_basis`): in sustained contact (resting, sliding, rolling) the contact mode
    rarely changes, and a verified guess replaces Lemke's pivots by one small solve.

    A variable whose column has no pivot (``M_SS`` singular) leaves the guess (z_i = 0); if
    that does not verify, the guess is retried with the ``degenerate`` pairs added. This is
    the sticking case: two contacts that stick share the friction in a way the LCP leaves
    open, Lemke's basis held one of its variables at zero, and the guess read from z > 0 left
    that one out but kept both frictions. Whatever the guess, only a verified solution is
    accepted. Returns the residual when accepted (and writes z), inf otherwise (z untouched).
    """
    n = M.shape[0]
    return solve_from_basis_in(
        M,
        q,
        basic,
        degenerate,
        z,
        np.empty(n),
        np.empty(n, dtype=np.bool_),
        np.empty(n, dtype=np.int64),
        np.empty((n, n + 1)),
        np.empty(n, dtype=np.int64),
    )


@leaf_kernel
def solve_from_basis_in(
    M: np.ndarray,
    q: np.ndarray,
    basic: np.ndarray,
    degenerate: np.ndarray,
    z: np.ndarray,
    trial: np.ndarray,
    guess: np.ndarray,
    idx: np.ndarray,
    a: np.ndarray,
    pivot_col: np.ndarray,
) -> float:
    """:func:`solve_from_basis` in the caller's scratch (``trial``, ``guess``, ``idx`` and
    ``pivot_col`` of at least n, ``a`` of at least n x (n + 1)): a time stepper's warm start,
    which runs on most contact steps of a drop, allocates nothing."""
    n = M.shape[0]
    scale = 1.0
    for i in range(n):
        scale = max(scale, 1.0 + abs(q[i]))
        guess[i] = basic[i]
    singular = _solve_guess(M, q, guess, trial, idx, a, pivot_col)
    res = lcp_residual(M, q, trial)
    if not res <= TOL * scale and singular:
        for i in range(n):
            guess[i] = basic[i] or degenerate[i]
        _solve_guess(M, q, guess, trial, idx, a, pivot_col)
        res = lcp_residual(M, q, trial)
    if not res <= TOL * scale:
        return np.inf
    for i in range(n):
        z[i] = max(trial[i], 0.0)
        basic[i] = guess[i]
    return res
