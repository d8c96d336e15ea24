"""Rod-rod contact inside the implicit solver: two crossing rods pushed together.

Without contact the pushed rod passes through the other (checked, so the test can fail);
with the implicit contact model it wraps over it: the centreline distance never drops much
below 2r and the crossing keeps its over/under order.
"""

import numpy as np
import pytest

from knotmech.rod._kernels.contact_rodrod import edge_distance_hessian
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import SmoothFriction
from knotmech.rod.solver import SolverOptions, simulate
from knotmech.rod.system import Rod, RodSystem

R = 1e-3


def crossing(push, interactions, t_end=0.5, dt=0.01):
    n = 41
    s = np.linspace(-0.05, 0.05, n)
    a = np.stack([s, 0 * s, 0 * s], 1)
    b = np.stack([0 * s + 0.0013, s, 0 * s + 2.5 * R], 1)
    rods = [Rod(positions=p, radius=R, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    system = RodSystem(rods)
    ends_a = [0, n - 1]
    ends_b = [n, 2 * n - 1]
    cons = (
        Clamp(nodes=ends_a, edges=[0, n - 2]),
        MovingNodes(nodes=ends_b, velocity=(0.0, 0.0, -push / t_end)),
        Clamp(edges=[n - 1, 2 * n - 3]),
    )
    res = simulate(
        system,
        t_end=t_end,
        dt=dt,
        constraints=cons,
        interactions=interactions,
        options=SolverOptions(throw=False),
    )
    pa = res.positions[:, :n]
    pb = res.positions[:, n:]
    # closest approach of the two polylines (edge-edge distances of the middle parts)
    g, H = np.empty(12), np.empty((12, 12))
    dmin = np.array(
        [
            min(
                edge_distance_hessian(np.concatenate([a[i], a[i + 1], b[j], b[j + 1]]), g, H)
                for i in range(14, 26)
                for j in range(14, 26)
            )
            for a, b in zip(pa, pb, strict=True)
        ]
    )
    return res, dmin, pb[:, n // 2, 2] - pa[:, n // 2, 2]


def test_crossing_rods_do_not_pass_through():
    contact = RodContact(stiffness=20.0, sharpness=1.0 / (0.02 * R), friction=SmoothFriction(0.3))
    res, dmin, dz = crossing(8 * R, (contact,))
    assert res.status == "success", res.message
    assert np.all(dz > 0)  # B stays above A at the crossing
    assert dmin.min() > 1.9 * R  # at most 5 % overlap of the two radii
    # it was really pushed: B's ends went 8 r below A
    assert res.positions[-1, 41, 2] < -5 * R


def test_without_contact_they_pass_through():
    res, dmin, dz = crossing(8 * R, ())
    assert dz[-1] < 0
    assert dmin.min() < R


@pytest.mark.parametrize("exclusion", [2])
def test_self_contact_exclusion_default(exclusion):
    rod = Rod.straight(length=0.1, n_nodes=11, radius=R, youngs_modulus=1e6, density=1000.0)
    system = RodSystem((rod,))
    c = RodContact(stiffness=1.0, sharpness=1.0 / R)
    c.begin_step(system, system.initial_state().q, None, 1e-3)
    # a straight rod: no pair closer than the exclusion along it; no force from far pairs
    assert len(c.pairs) > 0
    assert np.all(np.abs(c.pairs[:, 0] - c.pairs[:, 1]) > exclusion)
    assert system.contact_exclusion == exclusion
    assert c.energy(system, system.initial_state().q) < 1e-20


def _hard_push(max_displacement):
    # B's ends driven 40 r down in 2 steps of 10 ms (2 m/s): far more than the soft penalty
    # (K_c = 20 N/m) can stop within one step
    contact = RodContact(
        stiffness=20.0,
        sharpness=1.0 / (0.02 * R),
        friction=SmoothFriction(0.3),
        max_displacement=max_displacement,
    )
    return crossing(40 * R, (contact,), t_end=0.02, dt=0.01)


def test_hard_push_tunnels_without_the_guard():
    res, dmin, dz = _hard_push(None)
    assert res.status == "success"
    assert dz[-1] < -10 * R  # B ended up far below A: it went through


def test_tunnelling_guard_keeps_the_crossing_order():
    res, dmin, dz = _hard_push(0.5)
    assert res.status == "success", res.message
    assert res.stats["rejected_steps"] > 0  # the guard cut the step
    assert np.all(dz > 0)  # B stays above A at the crossing
    assert dmin.min() > 0.5 * R  # squeezed hard, but never through
    assert res.positions[-1, 41, 2] < -30 * R  # the ends really went 40 r down


def test_check_step_threshold():
    rod_a = Rod(positions=[[0, 0, 0], [0.01, 0, 0], [0.02, 0, 0]], radius=R,
                youngs_modulus=1e6, density=1000.0)  # fmt: skip
    rod_b = Rod(positions=[[0.01, -0.01, 2 * R], [0.01, 0, 2 * R], [0.01, 0.01, 2 * R]],
                radius=R, youngs_modulus=1e6, density=1000.0)  # fmt: skip
    system = RodSystem((rod_a, rod_b))
    q0 = system.initial_state().q
    c = RodContact(stiffness=1.0, sharpness=1.0 / R, max_displacement=0.5)
    c.begin_step(system, q0, np.zeros_like(q0), 0.01)
    assert c.pairs.shape[0] > 0
    for frac, rejected in ((0.4, False), (0.6, True)):
        q1 = q0.copy()
        q1[system.node_dofs[4, 2]] -= frac * R  # the middle node of B moves down
        assert (c.check_step(system, q1, q0, 0.01) is not None) == rejected
    c_off = RodContact(stiffness=1.0, sharpness=1.0 / R, max_displacement=None)
    c_off.begin_step(system, q0, np.zeros_like(q0), 0.01)
    assert c_off.check_step(system, q1, q0, 0.01) is None


def test_friction_normal_derivative_brings_jacobian_close_to_exact():
    """At mu = 0.9 the friction's dependence on |F_n| is as large as the penalty Hessian:
    without it dF/dq is off by ~40 % of its largest entry; with it only the (lagged)
    normal direction is missing (~1 %). Central differences of the assembled force."""
    import scipy.sparse as sp

    from knotmech.rod.jacobian import Triplets

    a = Rod(positions=[[0, 0, 0], [0.01, 0, 0], [0.02, 0, 0]], radius=R,
            youngs_modulus=1e6, density=1000.0)  # fmt: skip
    b = Rod(positions=[[0.011, -0.01, 1.9 * R], [0.01, 0, 1.9 * R], [0.009, 0.01, 1.9 * R]],
            radius=R, youngs_modulus=1e6, density=1000.0)  # fmt: skip
    system = RodSystem((a, b))
    q_old = system.initial_state().q
    rng = np.random.default_rng(0)
    q = q_old.copy()
    q[system.node_dofs.ravel()] += rng.normal(0, 2e-5, system.node_dofs.size)
    q[system.node_dofs[3:, 0]] += 3e-4  # B slides along x: full sliding friction
    idx = system.node_dofs.ravel()
    n = system.n_dof
    errors = {}
    for full in (False, True):
        c = RodContact(stiffness=50.0, sharpness=1 / (0.05 * R), friction=SmoothFriction(0.9),
                       friction_normal_derivative=full)  # fmt: skip
        c.begin_step(system, q_old, np.zeros(n), 0.01)

        def force(x, c=c):
            f, t = np.zeros(n), Triplets()
            c.assemble(system, x, q_old, 0.01, f, t)
            return f, t

        _, t = force(q)
        jac = sp.coo_matrix((t.vals, (t.rows, t.cols)), shape=(n, n)).toarray()
        jfd = np.zeros((n, n))
        for i in idx:
            e = np.zeros(n)
            e[i] = 1e-9
            jfd[:, i] = (force(q + e)[0] - force(q - e)[0]) / 2e-9
        errors[full] = np.abs(jac - jfd)[np.ix_(idx, idx)].max() / np.abs(jfd).max()
    assert errors[False] > 0.2
    assert errors[True] < 0.03
