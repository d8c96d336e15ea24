"""Dynamics, outputs, interactions and robustness of the DER implicit-Euler solver."""

import numpy as np
import pytest
from _rodtools import clamped_rod, dense_hessian

from knotmech import rod
from knotmech.errors import InputError, SolverError


def _free_rod(n=21, seed=0):
    rng = np.random.default_rng(seed)
    s = np.linspace(0, 0.3, n)
    pos = np.c_[s, 0.02 * np.sin(20 * s), 0.01 * np.cos(15 * s)]
    r = rod.Rod(
        positions=pos, radius=2e-3, youngs_modulus=1e6, density=1000.0, natural="straight",
        velocities=0.05 * rng.standard_normal((n, 3)),
    )  # fmt: skip
    return rod.RodSystem([r])


def test_free_rod_conserves_linear_momentum_and_only_dissipates_energy():
    """No external force, random initial velocities: sum m v is conserved up to the Newton
    tolerance (internal forces are translation invariant, so the momentum changes only by
    dt times the sum of the residual left) and implicit Euler may only dissipate: kinetic +
    elastic energy never increases from frame to frame."""
    system = _free_rod()
    opts = rod.SolverOptions(save_every=1e-3, rtol=1e-12)
    res = rod.simulate(system, t_end=0.05, dt=1e-3, options=opts)
    m = system.mass[system.node_dofs]
    v0 = system.initial_state().v[system.node_dofs]
    v1 = res.final_state.v[system.node_dofs]
    scale = np.abs(m * v0).sum()
    assert np.allclose(np.sum(m * v1, axis=0), np.sum(m * v0, axis=0), rtol=0, atol=1e-11 * scale)
    e = sum(res.energies[k] for k in ("kinetic", "stretch", "bend", "twist"))
    assert np.all(np.diff(e) <= 1e-12 * e[0])
    assert e[-1] < 0.99 * e[0]


def test_cantilever_first_mode_frequency_and_first_order_numerical_damping():
    """First bending frequency of a cantilever, 1.8751^2 sqrt(EI / rho A) / L^2 (Euler-
    Bernoulli; Rao, Vibration of Continuous Systems, table 11.3), from the Hessian and lumped
    mass matrix; then the rod released in that discrete mode: backward Euler multiplies the
    mode's energy by 1/(1 + omega^2 dt^2) per step, so the fraction lost over a time T is
    omega^2 dt T to leading order (theoretical order 1 in dt, fitted here)."""
    from scipy.linalg import eigh

    system, cons, h = clamped_rod(11, length=0.1, radius=1e-3, youngs_modulus=1e6)
    st = system.initial_state()
    hess, _ = dense_hessian(system, st.q, st)
    free = np.ones(system.n_dof, bool)
    free[np.concatenate([c.dofs(system) for c in cons])] = False
    w2, modes = eigh(hess[np.ix_(free, free)], np.diag(system.mass[free]))
    omega = np.sqrt(w2[0])
    r0 = system.rods[0]
    omega_eb = 1.87510407**2 * np.sqrt(r0.bending_stiffness / (1000.0 * np.pi * 1e-6)) / 0.1**2
    assert omega == pytest.approx(omega_eb, rel=3e-3)
    q = st.q.copy()
    q[free] += modes[:, 0] * 1e-4 / np.max(np.abs(modes[:, 0]))
    released = rod.Rod(
        positions=system.positions(q), thetas=system.thetas(q), radius=1e-3,
        youngs_modulus=1e6, density=1000.0, natural="straight", director=st.d1[0],
    )  # fmt: skip
    system = rod.RodSystem([released])
    t_end = 0.2
    lost, dts = [], [2e-3, 1e-3, 5e-4]
    for dt in dts:
        res = rod.simulate(
            system, t_end=t_end, dt=dt, constraints=cons,
            options=rod.SolverOptions(save_every=t_end),
        )  # fmt: skip
        e = sum(res.energies[k] for k in ("kinetic", "stretch", "bend", "twist"))
        lost.append(1 - e[-1] / e[0])
    order = np.polyfit(np.log(dts), np.log(lost), 1)[0]
    assert 0.95 < order < 1.05
    assert lost[-1] == pytest.approx(
        1 - (1 + (omega * dts[-1]) ** 2) ** (-t_end / dts[-1]), rel=0.05
    )


def test_step_failure_halves_dt_then_stops_with_last_good_state():
    """An interaction that turns NaN after 5 steps: every retry calls begin_step again, the
    step halves down to dt_min, the run stops with status failed and finite last state."""

    class Poison:
        def __init__(self):
            self.calls = 0

        def begin_step(self, system, q_old, v_old, dt):
            self.calls += 1

        def assemble(self, system, q, q_old, dt, force, triplets):
            if self.calls > 5:
                force[0] += np.nan

        def end_step(self, system, q_new, q_old, dt):
            pass

        def energy(self, system, q):
            return 0.0

    system, cons, _ = clamped_rod(11, length=0.1, radius=1e-3, youngs_modulus=1e6)
    poison = Poison()
    opts = rod.SolverOptions(dt_min=1e-6, throw=False)
    res = rod.simulate(
        system, t_end=1.0, dt=1e-3, loads=rod.Gravity(), constraints=cons,
        interactions=[poison], options=opts,
    )  # fmt: skip
    assert res.status == "failed"
    assert "dt_min" in res.message
    assert res.final_state.t == pytest.approx(5e-3)
    assert np.all(np.isfinite(res.final_state.q)) and np.all(np.isfinite(res.positions))
    assert res.stats["rejected_steps"] == 10  # 1e-3 / 2^10 < 1e-6
    assert poison.calls == 5 + 10
    with pytest.raises(SolverError) as info:
        rod.simulate(
            system, t_end=1.0, dt=1e-3, constraints=cons, interactions=[Poison()],
            options=rod.SolverOptions(dt_min=1e-6),
        )  # fmt: skip
    assert info.value.state.t == pytest.approx(5e-3)


def _pull_problem():
    system, cons, _ = clamped_rod(16, length=0.2, radius=1e-3, youngs_modulus=1e6, density=1000)
    cons = [cons[0], rod.MovingNodes(nodes=[system.n_nodes - 1], velocity=(0.05, 0.0, 0.1))]
    loads = [rod.Gravity(), rod.ViscousDamping(0.01)]
    return system, cons, loads


def test_checkpoint_and_resume_is_bit_identical(tmp_path):
    system, cons, loads = _pull_problem()
    kw = dict(dt=2e-3, loads=loads, constraints=cons, options=rod.SolverOptions(save_every=0.01))
    full = rod.simulate(system, t_end=0.1, **kw)
    half = rod.simulate(system, t_end=0.05, **kw)
    path = tmp_path / "state.npz"
    half.final_state.save(path)
    rest = rod.simulate(system, rod.State.load(path), t_end=0.1, **kw)
    assert np.array_equal(rest.final_state.q, full.final_state.q)
    assert np.array_equal(rest.final_state.v, full.final_state.v)
    assert np.array_equal(rest.positions, full.positions[5:])
    assert np.array_equal(rest.reactions[1:], full.reactions[6:])
    # the pulled end moved along its path, and the result file round-trips
    assert full.positions[-1, -1] - full.positions[0, -1] == pytest.approx([0.005, 0, 0.01])
    full.save(tmp_path / "res.npz")
    back = rod.load_result(tmp_path / "res.npz")
    assert back.status == full.status and back.stats["steps"] == full.stats["steps"]
    for name in ("times", "positions", "reactions", "tension", "bending_moment"):
        assert np.array_equal(getattr(back, name), getattr(full, name))
    assert np.array_equal(back.energies["bend"], full.energies["bend"])
    assert np.array_equal(back.final_state.q, full.final_state.q)


def test_sparse_and_banded_solves_agree():
    system, cons, loads = _pull_problem()
    kw = dict(t_end=0.02, dt=2e-3, loads=loads, constraints=cons)
    band = rod.simulate(system, **kw, options=rod.SolverOptions(linear_solver="banded"))
    sparse = rod.simulate(system, **kw, options=rod.SolverOptions(linear_solver="sparse"))
    assert np.allclose(band.positions, sparse.positions, rtol=0, atol=1e-12)


def test_pair_spring_couples_two_cantilevers_through_the_sparse_jacobian():
    """Two parallel cantilevers (tip stiffness k_c = 3 EI / L^3) whose tips are joined by a
    spring k; a force F on tip B. Spring force F_s = F / (2 + k_c / k). Quadratic Newton
    convergence (few iterations) shows the non-local Jacobian block is right."""
    n, L, r, E = 21, 1.0, 1e-3, 1e9
    a, _, h = clamped_rod(n, length=L, radius=r, youngs_modulus=E)
    rod_a = a.rods[0]
    rod_b = rod.Rod(
        positions=rod_a.positions + [0, 0.1, 0], radius=r, youngs_modulus=E, density=1000.0
    )
    system = rod.RodSystem([rod_a, rod_b])
    cons = [rod.clamp_end(system, rod=0), rod.clamp_end(system, rod=1)]
    ei = rod_a.bending_stiffness
    kc = 3 * ei / L**3
    k = 2 * kc
    f = 1e-3 * ei / L**2
    tip_a, tip_b = system.rod_nodes(0)[-1], system.rod_nodes(1)[-1]
    spring = rod.PointSpring(nodes=[tip_a, tip_b], stiffness=k, pair=True, offset=(0, -0.1, 0))
    res = rod.simulate(
        system, t_end=3e3, dt=1e3, loads=[rod.NodeForce(tip_b, (0, 0, f))], constraints=cons,
        interactions=[spring], options=rod.SolverOptions(rtol=1e-10),
    )  # fmt: skip
    za = res.positions[-1, tip_a, 2]
    zb = res.positions[-1, tip_b, 2]
    fs = k * (zb - za)
    assert fs == pytest.approx(f / (2 + kc / k), rel=2e-3)
    assert res.stats["newton_iterations"] <= 3 * res.stats["steps"]


def test_tension_and_twisting_moment_outputs():
    """A dead axial pull F gives tension F on every free edge; a dead axial torque tau on the
    free end's edge gives the twisting moment tau along the rod (statics)."""
    system, cons, _ = clamped_rod(11, length=1.0, radius=1e-3, youngs_modulus=1e9)
    f, tau = 0.1, 1e-5
    loads = [rod.NodeForce(-1, (f, 0, 0)), rod.EdgeTorque(system.n_edges - 1, tau)]
    res = rod.simulate(
        system, t_end=3e3, dt=1e3, loads=loads, constraints=cons,
        options=rod.SolverOptions(rtol=1e-11),
    )  # fmt: skip
    assert np.allclose(res.tension[-1, 1:], f, rtol=1e-7)
    assert np.allclose(res.twisting_moment[-1], tau, rtol=1e-7)
    assert res.reaction_torques[-1, 0] == pytest.approx(-tau, rel=1e-7)


def test_bending_moment_of_a_cantilever_is_linear():
    """Tip load P: bending moment P (L - s) at the interior nodes (small deflection)."""
    system, cons, h = clamped_rod(21, length=1.0, radius=1e-3, youngs_modulus=1e9)
    ei = system.rods[0].bending_stiffness
    p = 1e-4 * ei
    res = rod.simulate(
        system, t_end=3e3, dt=1e3, loads=[rod.NodeForce(-1, (0, 0, -p))], constraints=cons,
        options=rod.SolverOptions(rtol=1e-11),
    )  # fmt: skip
    m = np.hypot(*res.bending_moment[-1].T)
    s = (np.arange(1, system.n_nodes - 1) - 0.5) * h  # stencil node arc length from clamp
    assert np.allclose(m, p * (1.0 - s), rtol=0, atol=1e-3 * p)


def test_point_spring_holds_the_weight_of_a_free_rod():
    system = _free_rod()
    w = system.mass[system.node_dofs[:, 2]].sum() * 9.81
    k = 50.0
    spring = rod.PointSpring(nodes=[0], stiffness=k, point=(0, 0, 0))
    res = rod.simulate(
        system, t_end=20.0, dt=0.5, loads=[rod.Gravity(), rod.ViscousDamping(0.5, 1e-4)],
        interactions=[spring], options=rod.SolverOptions(save_every=1.0),
    )  # fmt: skip
    z0 = res.positions[-1, 0, 2]
    assert -k * z0 == pytest.approx(w, rel=1e-4)


def test_callback_progress_and_input_errors():
    system, cons, _ = clamped_rod(11, length=0.1, radius=1e-3, youngs_modulus=1e6)
    res = rod.simulate(
        system, t_end=1.0, dt=1e-2, constraints=cons, progress=True,
        callback=lambda st: st.t >= 0.05 - 1e-12,
    )  # fmt: skip
    assert res.final_state.t == pytest.approx(0.05) and "callback" in res.message
    with pytest.raises(InputError, match="dt"):
        rod.simulate(system, t_end=1.0, dt=0.0)
    with pytest.raises(InputError, match="radius"):
        rod.Rod.straight(length=1, n_nodes=5, radius=-1, youngs_modulus=1, density=1)
    with pytest.raises(InputError, match="nodes"):
        rod.simulate(system, t_end=1.0, dt=0.1, loads=[rod.NodeForce(99, (0, 0, 1))])
    with pytest.raises(InputError, match="same dof"):
        rod.simulate(system, t_end=1.0, dt=0.1, constraints=[cons[0], cons[0]])
