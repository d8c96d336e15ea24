"""Stagnation fallback (SolverOptions.rescue): nearly parallel rod-rod edges.

The closest points of two nearly parallel edges sit at one end of their overlap; when the
tiny angle between the edges changes sign they jump to the other end, and the pair's whole
penalty force moves from one node to another (the distance is the smaller of two smooth
functions there). Newton cycles between the two sides (the heavy-load hitch runs of
docs/notes/contact-and-friction/parallel-edge-stall.md). The fallback holds those closest
points at the step start, only where a run would otherwise fail.
"""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import AnchorFriction
from knotmech.rod.solver import SolverOptions
from tests.rod.test_contact import assemble_dense, crossing_rods, make_system

R = 0.01
OVERLAP = 0.995  # centreline gap of the two edges in units of 2r (in contact)


def parallel_rods(tilt):
    """Rod 1 (3 nodes) above rod 0 (3 nodes), shifted by a third of an edge along x,
    its end nodes raised by -/+ tilt/2 [m] (tilt > 0: its first node is the lower)."""
    s = np.linspace(0.0, 0.2, 3)
    a = np.stack([s, 0 * s, 0 * s], 1)
    z = 2 * R * OVERLAP + tilt * (s / 0.2 - 0.5)
    b = np.stack([s + 0.1 / 3, 0 * s, z], 1)
    return make_system([a, b], R)


def contact():
    return RodContact(stiffness=1e4, sharpness=2000.0, friction=AnchorFriction(mu_static=0.5))


def upper_force(c, sysm, q, q_old):
    """z force [N] on the three nodes of the upper rod."""
    f, _ = assemble_dense(c, sysm, q, q_old, 1e-3)
    return f[sysm.node_dofs[3:, 2]]


@pytest.mark.parametrize("eps", [1e-7, 1e-9])
def test_parallel_pair_force_jumps_with_the_tilt_sign(eps):
    """A tilt of +eps and -eps (the edges' angle ~1e-6 or 1e-8 rad) moves the contact
    force of the overlapping edge pair from one end of the overlap to the other: the same
    total (to O(eps k)), but on the upper rod's first node instead of its middle one."""
    sp, qp = parallel_rods(+eps)
    sm, qm = parallel_rods(-eps)
    c = contact()
    c.begin_step(sp, qp, None, 1e-3)
    fp = upper_force(c, sp, qp, qp)
    c.begin_step(sm, qm, None, 1e-3)
    fm = upper_force(c, sm, qm, qm)
    assert fp.sum() == pytest.approx(fm.sum(), rel=1e-4)
    # the penalty at an overlap of 0.5 % of 2r pushes up by ~2 K_c delta = 2 N per pair
    assert fp.sum() > 1.0
    jump = np.abs(fp - fm).max()
    assert jump > 0.3 * fp.sum()  # a finite jump for an infinitesimal motion


def test_hold_switches_makes_the_force_continuous():
    """Held at the +eps state, the pair keeps its closest points: the force at -eps
    differs from the one at +eps by the penalty stiffness times eps only; released, the
    jump (> 30 % of the total) is back."""
    eps = 1e-9
    sp, qp = parallel_rods(+eps)
    _, qm = parallel_rods(-eps)
    c = contact()
    c.begin_step(sp, qp, None, 1e-3)
    n = c.hold_switches(sp, qp)
    assert n >= 1
    held_p = upper_force(c, sp, qp, qp)
    held_m = upper_force(c, sp, qm, qp)
    # the change is the penalty's stiffness (~2 K_c per pair) times the motion eps
    np.testing.assert_allclose(held_m, held_p, atol=2 * 2e4 * eps)
    # at the state it was taken at, holding changes nothing (same closest points)
    c.release_switches()
    free_p = upper_force(c, sp, qp, qp)
    np.testing.assert_allclose(held_p, free_p, rtol=1e-12, atol=1e-15)
    free_m = upper_force(c, sp, qm, qp)
    assert np.abs(free_m - free_p).max() > 0.3 * free_p.sum()


def test_hold_switches_leaves_crossing_pairs_alone():
    """Edges crossing at a finite angle (the usual contact) are never held."""
    sysm, q = crossing_rods(gap=0.0195)
    c = contact()
    c.begin_step(sysm, q, None, 1e-3)
    assert c.hold_switches(sysm, q) == 0
    f0, _ = assemble_dense(c, sysm, q, q, 1e-3)
    c.release_switches()
    f1, _ = assemble_dense(c, sysm, q, q, 1e-3)
    np.testing.assert_array_equal(f0, f1)


def test_rescue_option_is_checked():
    with pytest.raises(InputError, match="rescue"):
        SolverOptions(rescue="yes")


def _crossing_push(rescue):
    """The crossing-rods push of tests/rod/test_contact_sim.py with the anchor law."""
    from knotmech.rod.constraints import Clamp, MovingNodes
    from knotmech.rod.solver import simulate
    from knotmech.rod.system import Rod, RodSystem

    n, r = 21, 1e-3
    s = np.linspace(-0.05, 0.05, n)
    a = np.stack([s, 0 * s, 0 * s], 1)
    b = np.stack([0 * s + 0.0013, s, 0 * s + 2.5 * r], 1)
    rods = [Rod(positions=p, radius=r, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    cons = (
        Clamp(nodes=[0, n - 1], edges=[0, n - 2]),
        MovingNodes(nodes=[n, 2 * n - 1], velocity=(0.0, 0.0, -0.01 / 0.2)),
        Clamp(edges=[n - 1, 2 * n - 3]),
    )
    rr = RodContact(stiffness=1e3, sharpness=15 / (0.1 * r), friction=AnchorFriction(0.5))
    return simulate(RodSystem(rods), t_end=0.2, dt=0.01, constraints=cons, interactions=[rr],
                    options=SolverOptions(throw=False, rescue=rescue))  # fmt: skip


def test_rescue_does_not_engage_on_a_normal_run():
    """A run that succeeds without the fallback is bit-identical with it, and its stats
    carry no trace of it (``rescues``, ``rescue_t``, ``held_steps`` appear only when it
    engaged)."""
    on, off = _crossing_push(True), _crossing_push(False)
    assert on.status == off.status == "success"
    assert on.stats["steps"] == off.stats["steps"] >= 20  # 0.2 s at dt 0.01
    np.testing.assert_array_equal(on.positions, off.positions)
    np.testing.assert_array_equal(on.thetas, off.thetas)
    assert not {"rescues", "rescue_t", "held_steps"} & set(on.stats)


@pytest.mark.slow
def test_cow_hitch_heavy_load_reaches_a_verdict():
    """The cheapest of the table's stalled points (cow hitch, d/2R 0.2308, T/EA 0.3,
    mu 0.5, kappa 0.01): without the fallback its load phase stalled at t = 2.8147 s
    (step 2.4e-9 s, "Newton stagnated"); with it, the run goes on (the fallback engaged
    there) and the loaded end runs off: a slip, as at T/EA 0.01 and 0.1 on that column."""
    from knotmech.verdict.build import simulate_point

    r = simulate_point(d_over_2R=0.2308, t_over_EA=0.3, mu=0.5, knot="cow-hitch",
                       bending_scale=0.01, keep_result=True)  # fmt: skip
    stats = r["result"].stats
    assert stats["rescues"] == 1  # in one phase (the scene sums its phases' stats)
    assert stats["rescue_t"] == pytest.approx(2.8147, abs=1e-3)
    assert stats["held_steps"] >= 1
    assert r["status"] == "success" and r["topology_preserved"]
    assert r["verdict"] == "slip" and r["stopped_in"] == "load"


def _stagnating_after(monkeypatch, t_fail):
    """Every Newton attempt of a step ending after ``t_fail`` [s] stagnates (the predicted
    attempts only: the fallback's held attempt still runs Newton)."""
    from knotmech.rod.solver import Stepper, _StepFailed

    predicted = Stepper._predicted

    def stagnating(self, st, dt, t_new, q_lin):
        if t_new > t_fail:
            raise _StepFailed("Newton stagnated: forced by the test", 4, stalled=True)
        return predicted(self, st, dt, t_new, q_lin)

    monkeypatch.setattr(Stepper, "_predicted", stagnating)


def test_rescue_needs_a_parallel_pair_in_reach(monkeypatch):
    """A run with rod-rod contact (two rods crossing at 90 degrees, pressed together) whose
    steps stagnate from t = 0.1 s fails exactly as without the fallback: no nearly
    parallel pair is in reach, so holding could change nothing. The same message, no
    ``rescues`` in the stats, and no second crawl down to dt_min (the same number of
    rejected attempts: 0.01 s halved 24 times is below dt_min = 1e-9 s)."""
    _stagnating_after(monkeypatch, 0.1)
    on, off = _crossing_push(True), _crossing_push(False)
    assert on.status == off.status == "failed"
    assert on.message == off.message
    assert "did not recover" not in on.message and "dt_min" in on.message
    assert on.stats["rejected_steps"] == off.stats["rejected_steps"] == 24
    assert on.stats["steps"] == off.stats["steps"] == 10
    assert not {"rescues", "rescue_t", "held_steps"} & set(on.stats)
    np.testing.assert_array_equal(on.positions, off.positions)


def test_rescue_engages_with_a_parallel_pair_in_reach(monkeypatch):
    """The same forced stagnation on two parallel rods pressed together (one pair within
    5 degrees, in reach): the fallback engages at the failing state and its held attempts
    converge."""
    from knotmech.rod.solver import simulate
    from knotmech.rod.system import Rod, RodSystem

    _stagnating_after(monkeypatch, 0.0)
    s = np.linspace(0.0, 0.2, 4)
    a = np.stack([s, 0 * s, 0 * s], 1)
    b = np.stack([s + 0.2 / 9, 0 * s, 0 * s + 2 * R * OVERLAP], 1)
    rods = [Rod(positions=p, radius=R, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    res = simulate(RodSystem(rods), t_end=2e-3, dt=1e-3, interactions=[contact()],
                   options=SolverOptions(throw=False))  # fmt: skip
    assert res.stats["rescues"] == 1
    assert res.stats["rescue_t"] == 0.0
    assert res.stats["held_steps"] >= 1


def test_held_gap_at_zero_fails_like_the_exact_gap():
    """At a zero gap the direction w/|w| of the penalty force is undefined. Neither the
    exact gap gradient nor the held one floors |w| (a floor would give a finite but
    arbitrary force, none for a pair that has met): both raise ZeroDivisionError (numba's
    Python error model), never NaN, and ``Stepper._newton`` turns that, as any
    ArithmeticError of an evaluation, into a rejected attempt (dt halved). Away from zero
    the held gap at the exact closest points is the exact gap, bit for bit."""
    from knotmech.rod._kernels.contact_rodrod import (
        _edge_distance_grad_ws,
        _gap_grad_at,
        segment_params,
    )

    # two collinear edges overlapping on [0.5, 1]: they meet, |w| = 0 at any common point
    x = np.array([0.0, 0, 0, 1, 0, 0, 0.5, 0, 0, 1.5, 0, 0])
    grad, coef, w = np.empty(12), np.empty(4), np.empty(3)
    with pytest.raises(ZeroDivisionError):
        _gap_grad_at(x, 0.75, 0.25, grad, coef, w)
    with pytest.raises(ZeroDivisionError):
        _edge_distance_grad_ws(x, grad, coef, w)
    # a held pair whose held points coincide, through RodContact.assemble
    sysm, q = parallel_rods(0.0)
    c = contact()
    c.begin_step(sysm, q, None, 1e-3)
    assert c.hold_switches(sysm, q) >= 1
    q_met = q.copy()
    q_met[sysm.node_dofs[3:, 2]] = 0.0  # rod 1 lowered onto rod 0's line
    with pytest.raises(ZeroDivisionError):
        upper_force(c, sysm, q_met, q)
    # 3-4-5 triangle: the edges 1 m apart at s = t = 1/2
    x = np.array([0.0, 0, 0, 1, 0, 0, 0.5, -0.6, 1, 0.5, 0.6, 1])
    s, t, _, _ = segment_params(x[:3], x[3:6], x[6:9], x[9:])
    g_held = np.empty(12)
    d_held = _gap_grad_at(x, s, t, g_held, coef, w)
    d_exact = _edge_distance_grad_ws(x, grad, coef, w)
    assert d_held == d_exact == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_array_equal(g_held, grad)
    np.testing.assert_allclose(g_held[[2, 5, 8, 11]], [-0.5, -0.5, 0.5, 0.5], rtol=1e-9)


def test_energy_of_held_pairs_is_that_of_the_held_gaps():
    """While pairs are held, ``RodContact.energy`` is the energy of the held gaps (the
    potential whose gradient the assembled force is), also at a configuration other than
    the one assembled last: at a tilt of -eps with the closest points held at +eps it
    equals the assembled (held) energy there, and differs from the exact-gap energy (the
    held gap exceeds the exact one by about the overlap times the edges' angle, 3e-6 m
    here, against a penetration of 1e-4 m)."""
    eps = 1e-5
    sp, qp = parallel_rods(+eps)
    _, qm = parallel_rods(-eps)
    c = contact()
    c.begin_step(sp, qp, None, 1e-3)
    assert c.hold_switches(sp, qp) >= 1
    upper_force(c, sp, qm, qp)  # assembled at qm, held
    e_assembled = c.energy(sp, qm)
    upper_force(c, sp, qp, qp)  # assembled at qp: energy(qm) is computed anew
    e_held = c.energy(sp, qm)
    assert e_held == pytest.approx(e_assembled, rel=1e-12)
    c.release_switches()
    upper_force(c, sp, qm, qp)
    e_exact = c.energy(sp, qm)
    upper_force(c, sp, qp, qp)
    assert c.energy(sp, qm) == pytest.approx(e_exact, rel=1e-12)
    assert e_exact - e_held > 1e-3 * e_exact  # the held gaps are wider
