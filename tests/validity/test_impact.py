"""The impact law of the kinematic level (Algorithm 2's Imp) as a specification.

References: hand-worked impacts of a body struck at its centre of mass (K = I / m, so slip and
stick have closed forms); a plain-Python integration of Routh's impact equations in 10^5
small increments of the normal impulse (no phases, no closed forms), for impacts that stop,
stick or reverse slip; and the conservation laws of an impulse at one point: the momentum
changes by the impulse, the angular momentum about the contact point does not change, the
kinetic energy does not rise, and the impulse lies in the friction cone.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from validity.contact_lcp import assemble_lcp, contact_jacobians, lcp_columns
from validity.impact import (
    IMPACT_DONE,
    IMPACT_NONE,
    STATS_FIELDS,
    collide,
    contact_inverse_inertia,
    contact_velocity,
    impact_workspace,
    planar_impact,
    resolve_impacts,
)
from validity.lcp import LCP_SOLVED, solve_lcp

M, INERTIA = 1.0, 77.0 / 300.0  # the default peg's mass and moment of inertia


def _energy(vel: np.ndarray, mass: float = M, inertia: float = INERTIA) -> float:
    return 0.5 * mass * (vel[0] ** 2 + vel[1] ** 2) + 0.5 * inertia * vel[2] ** 2


# --------------------------------------------------------------------------- hand-worked


@pytest.mark.parametrize("e", [0.0, 0.3, 0.5, 1.0])
def test_frictionless_head_on_impact_reverses_the_normal_velocity_scaled_by_e(e: float) -> None:
    """Struck along the line through its centre of mass (r parallel to n): u_n+ = -e u_n-,
    the tangential velocity and the spin unchanged."""
    vel = np.array([0.4, -2.0, 0.0])
    status = collide(vel, 0.0, -0.7, 0.0, 1.0, M, INERTIA, 0.0, e)  # floor below the centre
    assert status == IMPACT_DONE
    assert vel[1] == pytest.approx(2.0 * e, abs=1e-12)
    assert vel[0] == pytest.approx(0.4, abs=1e-12) and vel[2] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_frictionless_off_centre_impact_obeys_newtons_law_at_the_contact(e: float) -> None:
    """Without friction every restitution law agrees: the contact point's normal velocity is
    reversed and scaled by e, however the body spins up."""
    vel = np.array([0.0, -1.5, 0.8])
    rx, ry = 0.7, -0.5
    before = contact_velocity(vel, rx, ry, 0.0, 1.0)
    collide(vel, rx, ry, 0.0, 1.0, M, INERTIA, 0.0, e)
    assert contact_velocity(vel, rx, ry, 0.0, 1.0) == pytest.approx(-e * before, abs=1e-12)


def test_oblique_impact_that_slips_throughout_loses_mu_1_plus_e_u_n() -> None:
    """Struck at the centre of mass, u_t = 2 > mu (1 + e) |u_n| = 0.45: slip never stops and
    u_t+ = u_t - mu (1 + e) |u_n| = 1.55, u_n+ = -e u_n (the slip branch)."""
    pn, pt, status = planar_impact(-1.0, 2.0, 1 / M, 0.0, 1 / M, 0.3, 0.5)
    assert status == IMPACT_DONE
    assert pn == pytest.approx(1.5 * M, abs=1e-12)
    assert pt == pytest.approx(-0.3 * 1.5 * M, abs=1e-12)
    assert 2.0 + pt / M == pytest.approx(1.55, abs=1e-12)


def test_oblique_impact_that_sticks_ends_with_no_slip() -> None:
    """u_t = 0.2 < mu (1 + e) |u_n|: slip stops at p_n = u_t / mu = 0.667 m, before the impact
    ends at 1.5 m, and the contact then sticks (the stick branch): u_t+ = 0, u_n+ = -e u_n."""
    pn, pt, _ = planar_impact(-1.0, 0.2, 1 / M, 0.0, 1 / M, 0.3, 0.5)
    assert pn == pytest.approx(1.5 * M, abs=1e-12)
    assert pt == pytest.approx(-0.2 * M, abs=1e-12)


def test_a_separating_contact_gets_no_impulse() -> None:
    assert planar_impact(0.3, 1.0, 1.0, 0.2, 1.0, 0.5, 0.5) == (0.0, 0.0, IMPACT_NONE)


# --------------------------------------------------------------------------- reference


def _routh_reference(un, ut, knn, knt, ktt, mu, e, n=100_000):
    """Routh's equations du = K dp, dp_t = -mu sign(u_t) dp_n (or the stick impulse when
    the slip would change sign within an increment and stick is possible), integrated in
    equal increments of p_n; restitution ends when the normal work done in it reaches
    -e^2 times the work in compression. The total normal impulse is found first by a coarse
    pass, then the increment is set to 1/n of it."""

    def run(dp: float, limit: int):
        pn = pt = w = wc = 0.0
        u_n, u_t = un, ut
        compressing = True
        for _ in range(limit):
            if abs(u_t) > 1e-15:
                s = math.copysign(1.0, u_t)
                dpt = -mu * s * dp
                new_t = u_t + knt * dp + ktt * dpt
                if new_t * s < 0.0 and mu * ktt >= abs(knt):  # slip stops inside: stick
                    dpt = -(u_t + knt * dp) / ktt
            elif mu * ktt >= abs(knt):
                dpt = -knt / ktt * dp
            else:
                dpt = -mu * math.copysign(1.0, knt) * dp
            new_n = u_n + knn * dp + knt * dpt
            w += 0.5 * (u_n + new_n) * dp
            u_t += knt * dp + ktt * dpt
            u_n = new_n
            pn += dp
            pt += dpt
            if compressing and u_n >= 0.0:
                compressing, wc = False, w
                if e == 0.0:
                    break
            if not compressing and w - wc >= -e * e * wc:
                break
        return pn, pt

    coarse, _ = run(1e-3, 10**7)
    return run(coarse / n, 10 * n)


IMPACTS = [  # (u_n, u_t, r_x, r_y, mu, e): a peg corner striking a floor (n = (0, 1))
    (-1.0, 0.5, 0.8, -0.5, 0.3, 0.5),  # slip stops, then sticks
    (-1.0, 0.2, 0.8, -0.5, 0.1, 0.8),  # slip stops; stick impossible: slip reverses
    (-1.0, -0.3, -0.8, -0.5, 0.6, 0.0),  # plastic
    (-2.0, 1.0, 0.3, -0.5, 1.0, 1.0),  # elastic, sticky
    (-0.5, 3.0, 0.8, -0.1, 0.2, 0.7),  # slips throughout
]


@pytest.mark.parametrize("un,ut,rx,ry,mu,e", IMPACTS)
def test_phases_match_a_fine_integration_of_routh_equations(un, ut, rx, ry, mu, e) -> None:
    """Exact phase-by-phase integration agrees with 10^5 small increments to 1e-4 (the
    reference's own first-order error at this increment)."""
    knn, knt, ktt = contact_inverse_inertia(rx, ry, 0.0, 1.0, M, INERTIA)
    pn, pt, status = planar_impact(un, ut, knn, knt, ktt, mu, e)
    ref_n, ref_t = _routh_reference(un, ut, knn, knt, ktt, mu, e)
    assert status == IMPACT_DONE
    assert pn == pytest.approx(ref_n, abs=1e-4)
    assert pt == pytest.approx(ref_t, abs=1e-4)


def test_the_reference_cases_cover_slip_reversal() -> None:
    """Case 2 has |K_nt| > mu K_tt (stick impossible) and an impulse that drives u_t through
    0 (u_t K_nt < 0): the contact ends the impact slipping the other way."""
    un, ut, rx, ry, mu, e = IMPACTS[1]
    knn, knt, ktt = contact_inverse_inertia(rx, ry, 0.0, 1.0, M, INERTIA)
    assert abs(knt) > mu * ktt and ut * knt < 0.0
    pn, pt, _ = planar_impact(un, ut, knn, knt, ktt, mu, e)
    assert (ut + knt * pn + ktt * pt) * ut < 0.0


# --------------------------------------------------------------------------- laws


unit = st.floats(-1.0, 1.0)
impacts = st.tuples(
    st.floats(-3.0, 3.0),  # vx
    st.floats(-3.0, 3.0),  # vy
    st.floats(-5.0, 5.0),  # omega
    st.floats(-1.0, 1.0),  # rx
    st.floats(-1.0, 1.0),  # ry
    st.floats(0.0, 2 * math.pi),  # normal angle
    st.floats(0.0, 2.0),  # mu
    st.floats(0.0, 1.0),  # e
    st.floats(0.05, 5.0),  # inertia
)


@settings(max_examples=400, deadline=None)
@given(impacts)
def test_an_impact_conserves_what_it_must_and_never_gains_energy(case) -> None:
    """For any body state, contact point, normal, mu in [0, 2] and e in [0, 1]: momentum
    changes by exactly the impulse (so only along it), angular momentum about the contact
    point is unchanged, the impulse is in the friction cone with p_n >= 0, the contact does
    not approach afterwards, and the kinetic energy does not rise."""
    vx, vy, w, rx, ry, angle, mu, e, inertia = case
    nx, ny = math.cos(angle), math.sin(angle)
    vel = np.array([vx, vy, w])
    before = vel.copy()
    collide(vel, rx, ry, nx, ny, M, inertia, mu, e)
    px, py = M * (vel[0] - before[0]), M * (vel[1] - before[1])  # the impulse applied

    # angular momentum about the contact point: I omega + m (c - p) x v, c - p = -r
    def ang(v):
        return inertia * v[2] - M * (rx * v[1] - ry * v[0])

    assert ang(vel) == pytest.approx(ang(before), abs=1e-9)
    pn, pt = px * nx + py * ny, -px * ny + py * nx
    assert pn >= -1e-12
    assert abs(pt) <= mu * pn + 1e-9
    assert contact_velocity(vel, rx, ry, nx, ny) >= -1e-9
    assert _energy(vel, M, inertia) <= _energy(before, M, inertia) + 1e-9


def test_a_flat_landing_leaves_no_corner_approaching() -> None:
    """The peg landing flat on a floor touches at two corners at once. The impact leaves
    neither corner approaching, adds no energy, and (frictionless, plastic) removes all
    downward momentum without changing the horizontal velocity."""
    body = np.array([[-1.0, -0.5], [1.0, -0.5]])  # the two lower corners, centre at origin
    contacts = np.zeros((12, 5))
    for i, (bx, by) in enumerate(body):
        contacts[i] = (0.0, 0.0, 1.0, bx, by)
    for mu, e in [(0.0, 0.0), (0.3, 0.0), (0.3, 0.5), (1.0, 1.0)]:
        vel = np.array([0.2, -1.0, 0.0])
        before = _energy(vel)
        stats = np.zeros(len(STATS_FIELDS))
        count = resolve_impacts(
            vel,
            0.0,
            0.0,
            contacts,
            2,
            1e-4,
            M,
            INERTIA,
            mu,
            e,
            1e-12,
            64,
            impact_workspace(12),
            stats,
        )
        assert count >= 1
        for bx, by in body:
            assert contact_velocity(vel, bx, by, 0.0, 1.0) >= -1e-12
        assert _energy(vel) <= before + 1e-12
        if e == 0.0 and mu == 0.0:
            assert vel[1] == pytest.approx(0.0, abs=1e-9)
            assert vel[0] == pytest.approx(0.2, abs=1e-12)


# --------------------------------------------------------------------------- simultaneous
# A uniform 2 x 1 box, mass 1, I = m (2^2 + 1^2) / 12 = 5/12, centre of mass at the origin.
BOX_M, BOX_I = 1.0, 5.0 / 12.0
BAND = 1e-4


def _resolve(vel, rows, mu, e, mass=BOX_M, inertia=BOX_I, slack=1e-12, max_impacts=32):
    """resolve_impacts on contact rows (gap, n_x, n_y, p_x, p_y), centre of mass at 0."""
    contacts = np.zeros((12, 5))
    contacts[: len(rows)] = rows
    stats = np.zeros(len(STATS_FIELDS))
    count = resolve_impacts(
        vel,
        0.0,
        0.0,
        contacts,
        len(rows),
        BAND,
        mass,
        inertia,
        mu,
        e,
        slack,
        max_impacts,
        impact_workspace(12),
        stats,
    )
    assert stats[1] == 0 and stats[2] == 0  # no LCP fallback in these cases
    return count


def _face_on_wall(hx: float, hy: float) -> list:
    """The box's face x = hx flush against a wall on its right (normal (-1, 0) into the box):
    its two corners (hx, +-hy) touch."""
    return [(0.0, -1.0, 0.0, hx, hy), (0.0, -1.0, 0.0, hx, -hy)]


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("half", [(1.0, 0.5), (0.5, 1.0)], ids=["short_face", "long_face"])
def test_a_face_hitting_a_wall_flat_rebounds_at_minus_e_without_spin(e, half) -> None:
    """Issue 11, fault 2. The box moving at (1, 0, 0) meets a frictionless wall with a whole
    face at once (two corners, symmetric about the line of motion through the centre of mass).
    By symmetry no torque acts: the impact is that of a point mass, v+ = (-e, 0, 0), no spin.
    (Sequential single-point impacts gave vx = -0.094, spin 0.19 at e = 0 for the short face.)"""
    vel = np.array([1.0, 0.0, 0.0])
    count = _resolve(vel, _face_on_wall(*half), 0.0, e)
    assert count >= 1
    assert vel == pytest.approx([-e, 0.0, 0.0], abs=1e-12)


def test_the_impact_lcp_of_the_flat_box_is_the_hand_worked_one() -> None:
    """The frictionless compression LCP of the short face on the wall, assembled by the shared
    contact-LCP module: W_n columns (n, r x n) = (-1, 0, +-0.5), so
    A = W_n' M^-1 W_n = 1 + (+-0.5)(+-0.5) / I = [[1.6, 0.4], [0.4, 1.6]] (I = 5/12), and
    b = W_n' v- = (-1, -1) for v- = (1, 0, 0); its solution p_c = A^-1 (1, 1) = (0.5, 0.5)."""
    rows = np.array(_face_on_wall(1.0, 0.5))
    wn, wt, cols = np.zeros((3, 2)), np.zeros((3, 2)), np.zeros((3, 6))
    B, b, z = np.zeros((8, 8)), np.zeros(8), np.zeros(8)
    minv = np.array([1.0, 1.0, 12.0 / 5.0])
    contact_jacobians(rows, 2, 0.0, 0.0, wn, wt)
    m = lcp_columns(wn, wt, 2, False, cols)
    size = assemble_lcp(cols, m, 2, False, 0.0, minv, np.zeros(2), np.array([1.0, 0, 0]), B, b)
    assert (m, size) == (2, 2)
    assert B[:2, :2] == pytest.approx(np.array([[1.6, 0.4], [0.4, 1.6]]), abs=1e-15)
    assert b[:2] == pytest.approx([-1.0, -1.0], abs=0.0)
    status, _, _, _ = solve_lcp(B[:2, :2], b[:2], z[:2])
    assert status == LCP_SOLVED and z[:2] == pytest.approx([0.5, 0.5], abs=1e-12)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_flat_face_arriving_obliquely_sticks_when_mu_is_large(e: float) -> None:
    """Short face on the wall, v- = (1, 0.3, 0), mu = 1. Compression can stop both corners
    entirely: the tangential impulse needed, 0.3 m, is within mu times the normal one, 1 m,
    and the torque balance 0.5 (p_1 - p_2) = 1 * 0.3 keeps both normal impulses positive
    (0.8 and 0.2). So v_c = 0 and Poisson's law returns v+ = -e v- = (-e, -0.3 e, 0): no spin;
    at e = 0 the box stops dead (no tangential velocity)."""
    vel = np.array([1.0, 0.3, 0.0])
    _resolve(vel, _face_on_wall(1.0, 0.5), 1.0, e)
    assert vel == pytest.approx([-e, -0.3 * e, 0.0], abs=1e-12)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_flat_face_arriving_obliquely_slips_when_mu_is_small(e: float) -> None:
    """Short face on the wall, v- = (1, 0.3, 0), mu = 0.1: friction cannot stop the slip
    (mu (1 + e) * 1 <= 0.2 < 0.3), both corners slip up the wall and stay pressed (torque
    balance 0.5 (p_1 - p_2) = 0.1 (1 + e) keeps both positive). Hand-worked: v_x+ = -e, the
    tangential change is mu (1 + e) times the normal change (1 + e): v_y+ = 0.3 - 0.1 (1 + e);
    no spin."""
    vel = np.array([1.0, 0.3, 0.0])
    _resolve(vel, _face_on_wall(1.0, 0.5), 0.1, e)
    assert vel == pytest.approx([-e, 0.3 - 0.1 * (1.0 + e), 0.0], abs=1e-12)


FLOOR_ROWS = [(0.0, 0.0, 1.0, -1.0, -0.5), (0.0, 0.0, 1.0, 1.0, -0.5)]  # long face on a floor


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize(
    "mu,expected_vx",
    [(0.0, lambda e: 0.4), (0.2, lambda e: 0.4 - 0.2 * (1 + e)), (1.0, lambda e: -0.4 * e)],
    ids=["frictionless", "slips", "sticks"],
)
def test_a_box_landing_flat_on_a_floor(e, mu, expected_vx) -> None:
    """The box lands on its long face at v- = (0.4, -1, 0): both lower corners touch. Hand-
    worked (both corners stay pressed: the friction torque, arm 0.5, is balanced by normal
    impulses with arms +-1): v_y+ = e, no spin; v_x+ = 0.4 frictionless, 0.4 - mu (1 + e)
    when it slips (mu = 0.2), -e 0.4 when friction (mu = 1 >= 0.4) stops the slip in
    compression (Poisson's law then reverses the tangential velocity too)."""
    vel = np.array([0.4, -1.0, 0.0])
    _resolve(vel, FLOOR_ROWS, mu, e)
    assert vel == pytest.approx([expected_vx(e), e, 0.0], abs=1e-12)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_three_contacts_a_corner_in_a_wedge_and_a_corner_on_the_floor(e, mu) -> None:
    """The box lying on its long face with its lower right corner (1, -0.5) in the right-angled
    wedge of the floor and a wall on its right: three contacts (the floor at both lower
    corners, the wall at one), v- = (1, -1, 0) into the wedge. Compression stops all three
    (v_y + omega r_x = 0 at r_x = +-1 and v_x - omega r_y = 0), with normal impulses
    wall 1, floor 0.25 and 0.75 (torque balance -0.5 * 1 - p_1 + p_2 = 0), all positive, so no
    friction is needed: v+ = -e v- = (-e, e, 0) with or without friction."""
    rows = [*FLOOR_ROWS, (0.0, -1.0, 0.0, 1.0, -0.5)]
    vel = np.array([1.0, -1.0, 0.0])
    _resolve(vel, rows, mu, e)
    assert vel == pytest.approx([-e, e, 0.0], abs=1e-12)


def test_a_contact_that_approaches_after_restitution_is_resolved_again() -> None:
    """Rows: the two lower corners on the floor and a wall touching the left upper corner
    (normal (1, 0)), box moving down and spinning: after the first round (the wall contact
    separating, no impulse there) the restitution may drive a contact in; whatever the rounds,
    at the end no touching contact approaches and the energy has not risen."""
    rows = [*FLOOR_ROWS, (0.0, 1.0, 0.0, -1.0, 0.5)]
    for mu, e in [(0.0, 1.0), (0.5, 1.0), (0.3, 0.5)]:
        vel = np.array([0.2, -1.0, 2.0])
        before = _energy(vel, BOX_M, BOX_I)
        count = _resolve(vel, rows, mu, e)
        assert count >= 1
        for _, nx, ny, px, py in rows:
            assert contact_velocity(vel, px, py, nx, ny) >= -1e-9
        assert _energy(vel, BOX_M, BOX_I) <= before + 1e-12


def test_one_touching_contact_keeps_the_single_point_law() -> None:
    """With one contact touching (the other row 0.1 away) resolve_impacts applies exactly
    :func:`collide` (Routh's method, Stronge's e), not the impact LCP."""
    rows = [FLOOR_ROWS[0], (0.1, 0.0, 1.0, 1.0, -0.5)]
    vel = np.array([0.4, -1.0, 0.7])
    ref = vel.copy()
    collide(ref, -1.0, -0.5, 0.0, 1.0, BOX_M, BOX_I, 0.3, 0.6)
    contacts = np.zeros((12, 5))
    contacts[:2] = rows
    stats = np.zeros(len(STATS_FIELDS))
    n = resolve_impacts(
        vel, 0.0, 0.0, contacts, 2, BAND, BOX_M, BOX_I, 0.3, 0.6, 1e-12, 32,
        impact_workspace(12), stats,
    )  # fmt: skip
    assert n == 1 and stats[0] == 0
    assert vel == pytest.approx(ref, abs=0.0)


contact_sets = st.tuples(
    st.floats(0.1, 2.0),  # half length
    st.floats(0.05, 1.0),  # half width
    st.floats(0.1, 10.0),  # mass
    st.floats(0.2, 5.0),  # inertia factor (times a uniform box's)
    st.lists(  # contacts: normal angle, point as fractions of the half sizes
        st.tuples(st.floats(0.0, 2 * math.pi), st.floats(-1, 1), st.floats(-1, 1)),
        min_size=2,
        max_size=5,
    ),
    st.tuples(st.floats(-3, 3), st.floats(-3, 3), st.floats(-5, 5)),  # v-
    st.floats(0.0, 2.0),  # mu
    st.floats(0.0, 1.0),  # e
)


@settings(max_examples=400, deadline=None)
@given(contact_sets)
def test_simultaneous_impacts_never_gain_energy(case) -> None:
    """For random boxes (mass, inertia), 2 to 5 touching contacts with random normals and
    points, random velocities, mu in [0, 2], e in [0, 1]: the kinetic energy never rises (the
    energy bound of the module docstring, -(1 + e) D + (1 + e)(e - 1) / 2 P'AP <= 0 per
    round), and unless the jam limit stopped it, no contact approaches afterwards."""
    hx, hy, mass, factor, contacts, v, mu, e = case
    inertia = factor * mass * (hx * hx + hy * hy) / 3.0
    rows = [(0.0, math.cos(a), math.sin(a), fx * hx, fy * hy) for a, fx, fy in contacts]
    vel = np.array(v)
    before = _energy(vel, mass, inertia)
    count = _resolve(vel, rows, mu, e, mass=mass, inertia=inertia, max_impacts=64)
    assert np.all(np.isfinite(vel))
    assert _energy(vel, mass, inertia) <= before * (1.0 + 1e-9) + 1e-12
    if count >= 0:
        for _, nx, ny, px, py in rows:
            assert contact_velocity(vel, px, py, nx, ny) >= -1e-9 * (1.0 + np.abs(v).sum())
