"""Rod-rod anchor friction (elasto-plastic, mu_s >= mu_k): kernel values, Jacobian, commit.

Standalone like tests/rod/test_contact.py (its minimal system stand-in is reused).
"""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.rod._kernels.contact_rodrod import SLIP_GAP
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import FLOOR_RULES, AnchorFriction
from tests.rod.test_contact import assemble_dense, crossing_rods, fd_jacobian

K_C = 1e4


def contact(mu_s=0.4, mu_k=None, kt=1e4):
    fr = AnchorFriction(mu_static=mu_s, mu_kinetic=mu_k, tangential_stiffness=kt)
    return RodContact(stiffness=K_C, sharpness=2000.0, friction=fr)


def moved(sysm, q, dx, rod=0):
    """q with every node of ``rod`` (6 nodes each) moved by ``dx`` along x."""
    q1 = q.copy()
    nodes = np.arange(6) + 6 * rod
    q1[sysm.node_dofs[nodes, 0]] += dx
    return q1


def friction_part(c, sysm, q, q_old):
    c0 = RodContact(stiffness=K_C, sharpness=2000.0)
    c0.begin_step(sysm, q_old, None, 1e-3)
    f, J = assemble_dense(c, sysm, q, q_old, 1e-3)
    f0, _ = assemble_dense(c0, sysm, q, q_old, 1e-3)
    return f - f0, f, J


@pytest.mark.parametrize("dx", [2e-5, 5e-4, 5e-3])
def test_stick_then_slide_force_and_jacobian(dx):
    """Rod 0 slid by dx along x against rod 1: the smoothed anchor spring gives
    mu_s N dx / sqrt(dx^2 + a^2) (a = mu_s N / k_t) against the slide, -k_t dx for a
    small dx, mu_s N for a long one (which then counts as sliding); rod 1 gets the
    opposite. The Jacobian matches central differences (the plane turning included)."""
    sysm, q = crossing_rods(gap=0.0195)
    c = contact()
    c.begin_step(sysm, q, None, 1e-3)
    q1 = moved(sysm, q, dx)
    ffr, f, J = friction_part(c, sysm, q1, q)
    rod0 = ffr[sysm.node_dofs[:6].ravel()].reshape(-1, 3).sum(0)
    rod1 = ffr[sysm.node_dofs[6:].ravel()].reshape(-1, 3).sum(0)
    fn = float(np.sum(c.last_normal_force))
    np.testing.assert_allclose(rod0 + rod1, 0.0, atol=1e-12 * fn)
    # the pairs that carry the contact (their neighbours are within the penalty's reach
    # with a force ~1e-9 |F_n|: those slide)
    main = c.last_normal_force > 1e-6 * fn
    assert main.sum() == 1
    # the smoothed anchor spring: mu N u / sqrt(u^2 + a^2), a = mu N / k_t
    limit = 0.4 * fn
    a = limit / 1e4
    assert np.linalg.norm(rod0) == pytest.approx(limit * dx / np.hypot(dx, a), rel=1e-6)
    assert rod0[0] < 0
    assert c.sliding[main].all() == (dx > SLIP_GAP * a)
    if dx < 0.1 * a:  # stick: the spring k_t u
        assert rod0[0] == pytest.approx(-1e4 * dx, rel=2e-3)
    J_fd = fd_jacobian(c, sysm, q1, q, 1e-3, h=1e-9)
    np.testing.assert_allclose(J, J_fd, atol=2e-3 * np.abs(J).max())


def test_commit_keeps_a_stuck_anchor_moves_a_sliding_one_and_uses_mu_k():
    sysm, q = crossing_rods(gap=0.0195)
    c = contact(mu_s=0.5, mu_k=0.3)
    c.begin_step(sysm, q, None, 1e-3)
    q1 = moved(sysm, q, 5e-3)
    ffr, _, _ = friction_part(c, sysm, q1, q)
    main = c.last_normal_force > 1e-6 * c.last_normal_force.max()
    c.end_step(sysm, q1, q, 1e-3)
    keys, anc, slip = c._store
    n_edges = sysm.edge_nodes.shape[0]
    main_keys = c.pairs[main, 0] * n_edges + c.pairs[main, 1]
    assert main_keys.size == 1 and slip[np.searchsorted(keys, main_keys)].all()
    # after the slide the anchor sits at the yield length of mu_s: the same place again
    # gives the kinetic force mu_k |F_n|
    c.begin_step(sysm, q1, None, 1e-3)
    q2 = moved(sysm, q1, 1e-12)
    ffr, _, _ = friction_part(c, sysm, q2, q1)
    rod0 = ffr[sysm.node_dofs[:6].ravel()].reshape(-1, 3).sum(0)
    fn = c.last_normal_force
    # the anchor sits SLIP_GAP a_s behind: the kinetic force with gap ratio
    # SLIP_GAP mu_s/mu_k
    g = SLIP_GAP * 0.5 / 0.3
    assert np.linalg.norm(rod0) == pytest.approx(0.3 * fn.max() * g / np.hypot(g, 1), rel=1e-4)
    # moving back by the kinetic slide gap SLIP_GAP mu_k N / k_t unloads the spring: it sticks
    c.end_step(sysm, q2, q1, 1e-3)
    main = fn > 1e-6 * fn.max()
    assert main.sum() == 1
    q3 = moved(sysm, q2, -SLIP_GAP * 0.3 * fn.max() / 1e4)
    c.begin_step(sysm, q2, None, 1e-3)
    ffr, _, _ = friction_part(c, sysm, q3, q2)
    assert not c.sliding[main].any()
    rod0 = ffr[sysm.node_dofs[:6].ravel()].reshape(-1, 3).sum(0)
    assert np.linalg.norm(rod0) < 1e-3 * 0.3 * fn.max()


def test_state_arrays_round_trip_and_rigid_motion_keeps_the_anchor():
    """The anchors are material points: translating both rods together keeps them stuck
    with no force; a fresh contact restored from state_arrays gives the same force."""
    sysm, q = crossing_rods(gap=0.0195)
    c = contact()
    c.begin_step(sysm, q, None, 1e-3)
    q1 = moved(sysm, q, 1e-5)
    assemble_dense(c, sysm, q1, q, 1e-3)
    c.end_step(sysm, q1, q, 1e-3)
    both = moved(sysm, moved(sysm, q1, 0.03, rod=0), 0.03, rod=1)
    c.begin_step(sysm, q1, None, 1e-3)
    f_c, _ = assemble_dense(c, sysm, both, q1, 1e-3)
    c2 = contact()
    c2.load_state_arrays({k: v.copy() for k, v in c.state_arrays().items()})
    c2.begin_step(sysm, q1, None, 1e-3)
    f_c2, _ = assemble_dense(c2, sysm, both, q1, 1e-3)
    assert np.array_equal(f_c, f_c2)
    ffr, _, _ = friction_part(c, sysm, both, q1)
    rod0 = ffr[sysm.node_dofs[:6].ravel()].reshape(-1, 3).sum(0)
    main = c.last_normal_force > 1e-6 * c.last_normal_force.max()
    limit = 0.4 * c.last_normal_force.max()
    a = limit / 1e4
    assert main.sum() == 1
    assert rod0[0] == pytest.approx(-limit * 1e-5 / np.hypot(1e-5, a), rel=1e-6)


def test_friction_type_is_checked():
    with pytest.raises(InputError, match="friction"):
        RodContact(stiffness=1.0, sharpness=1.0, friction=0.3)


@pytest.mark.parametrize("dx, cap_floor", [(2e-5, 0.0), (5e-3, 0.0), (2e-4, 5e-2)])
def test_friction_census_reports_the_force_the_law_applies(dx, cap_floor):
    """``rodrod_friction_census`` (validation/_sticking_census.py) reports for the pair
    that carries the contact the |F_t| that the assembly applies (the net friction force
    on rod 0), mu_s, |u|/a = dx/a with a = max(mu_s N/k_t, cap_floor (r_i + r_j)), and
    whether it slides (|u| > SLIP_GAP a)."""
    from knotmech.rod._kernels.contact_rodrod import (
        CENSUS_COLUMNS,
        Z_CUTOFF,
        rodrod_friction_census,
    )

    col = {k: i for i, k in enumerate(CENSUS_COLUMNS)}
    sysm, q = crossing_rods(gap=0.0195)
    fr = AnchorFriction(mu_static=0.4, tangential_stiffness=1e4, cap_floor=cap_floor)
    c = RodContact(stiffness=K_C, sharpness=2000.0, friction=fr)
    c.begin_step(sysm, q, None, 1e-3)
    q1 = moved(sysm, q, dx)
    ffr, _, _ = friction_part(c, sysm, q1, q)
    rod0 = np.linalg.norm(ffr[sysm.node_dofs[:6].ravel()].reshape(-1, 3).sum(0))
    rad, en, nd = c._arrays(sysm)[:3]
    out = np.zeros((c.pairs.shape[0], len(CENSUS_COLUMNS)))
    _, anc, slip, _, known = c._anc
    rodrod_friction_census(
        q1[nd], q[nd], 1e-3, c.pairs, en, rad, c.sharpness, c.stiffness, Z_CUTOFF,
        0.4, 0.4, 1e4, anc, slip, known, out, cap_floor, FLOOR_RULES.index(fr.floor_rule),
    )  # fmt: skip
    main = int(np.argmax(out[:, col["fnorm"]]))
    fn = out[main, col["fnorm"]]
    assert fn == pytest.approx(c.last_normal_force[main], rel=1e-12)
    a = max(0.4 * fn / 1e4, cap_floor * 2 * rad[0])
    assert out[main, col["a"]] == pytest.approx(a, rel=1e-12)
    assert out[main, col["gap_over_a"]] == pytest.approx(dx / a, rel=1e-3)
    assert out[main, col["ft"]] == pytest.approx(0.4 * fn * dx / np.hypot(dx, a), rel=1e-3)
    assert out[main, col["ft"]] == pytest.approx(rod0, rel=1e-3)
    assert out[main, col["slides"]] == float(dx > SLIP_GAP * a)


@pytest.mark.parametrize("dx", [2e-4, 1e-3, 5e-3])
@pytest.mark.parametrize(
    "floor", [dict(cap_floor=5e-2), dict(cap_floor=2e-2, floor_rule="penalty")],
    ids=["radii", "penalty"],
)  # fmt: skip
def test_floored_cap_force_and_jacobian(dx, floor):
    """cap_floor 5e-2: a = 5e-2 (r_i + r_j) = 1e-3 m (above mu_s N/k_t = 3.8e-4 m); or
    floor_rule "penalty" with cap_floor 2e-2 = 2 penalty widths: a = 2/2000 m = 1e-3 m: the
    force is
    mu_s N dx / sqrt(dx^2 + a^2) and the Jacobian (whose |F_n| term is F c_n grad^T where
    the floor is active) matches central differences."""
    sysm, q = crossing_rods(gap=0.0195)
    fr = AnchorFriction(mu_static=0.4, tangential_stiffness=1e4, **floor)
    c = RodContact(stiffness=K_C, sharpness=2000.0, friction=fr)
    c.begin_step(sysm, q, None, 1e-3)
    q1 = moved(sysm, q, dx)
    ffr, f, J = friction_part(c, sysm, q1, q)
    rod0 = ffr[sysm.node_dofs[:6].ravel()].reshape(-1, 3).sum(0)
    fn = float(np.sum(c.last_normal_force))
    a = 1e-3
    assert 0.4 * fn / 1e4 < a  # the floor is what sets the cap
    assert np.linalg.norm(rod0) == pytest.approx(0.4 * fn * dx / np.hypot(dx, a), rel=1e-6)
    J_fd = fd_jacobian(c, sysm, q1, q, 1e-3, h=1e-9)
    np.testing.assert_allclose(J, J_fd, atol=2e-3 * np.abs(J).max())


@pytest.mark.parametrize(
    "mode, slipped, expected",
    [(0, False, 4e-5), (1, False, 0.0), (1, True, 4e-5), (2, False, 2e-5), (3, False, 2e-5)],
)  # fmt: skip
def test_cap_floor_rules(mode, slipped, expected):
    """a_min of each ``floor_rule`` (kernel ``floor_mode``) for cap_floor 1e-2, r_i + r_j =
    4 mm, sharpness 5e4 /m (a penalty width of 20 um): radii 40 um on every pair (all),
    only on a pair that slid (sliding), 20 um (penalty), the smaller (min)."""
    from knotmech.rod._kernels.contact_rodrod import FLOOR_REF, _cap_min
    from knotmech.rod.friction import CAP_FLOOR, FLOOR_RULES

    assert FLOOR_REF == CAP_FLOOR and FLOOR_RULES == ("all", "sliding", "penalty", "min")
    assert _cap_min(1e-2, mode, 4e-3, 5e4, slipped) == pytest.approx(expected, rel=1e-12)
