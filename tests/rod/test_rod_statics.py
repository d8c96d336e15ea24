"""Static verification of the DER solver against beam theory, the elastica and buckling loads.

Static equilibria are reached with implicit Euler steps far longer than any period of the
rod (dt = 1000 s: the inertia term M/dt^2 is negligible) and loads ramped over a few steps.
A clamp holds two nodes, i.e. the first edge, so it acts at that edge's midpoint; the rods
are built so that the free span from that point is exactly L (tests/rod/_rodtools.py).
Theoretical order of the discretisation error in the edge length h: 2 (Bergou et al. 2008,
the centred curvature and Voronoi lengths are second-order accurate on uniform meshes).
"""

import numpy as np
import pytest
from _rodtools import clamped_rod, min_eig_constrained
from scipy.integrate import solve_bvp
from scipy.optimize import brentq

from knotmech import rod

STATIC = dict(dt=1e3, t_end=1e4)


def _static(system, cons, loads):
    res = rod.simulate(
        system, loads=loads, constraints=cons, options=rod.SolverOptions(rtol=1e-10), **STATIC
    )
    assert res.status == "success"
    return res


def _order(h, err):
    return np.polyfit(np.log(h), np.log(err), 1)[0]


def test_cantilever_under_own_weight_matches_euler_bernoulli():
    """Tip deflection w L^4 / (8 EI) (Timoshenko & Gere, Mechanics of Materials, table G-1),
    deflection/L = 5e-4 so that geometric nonlinearity is below 1e-6."""
    L, r, E, rho, g = 1.0, 1e-2, 1e9, 1000.0, 0.0981
    ei = E * np.pi * r**4 / 4
    w = rho * np.pi * r**2 * g
    exact = w * L**4 / (8 * ei)
    hs, errs = [], []
    for n in (11, 21, 41):
        system, cons, h = clamped_rod(n, length=L, radius=r, youngs_modulus=E, density=rho)
        res = _static(system, cons, [rod.Gravity((0, 0, -g), ramp_time=5e3)])
        tip = -res.positions[-1, -1, 2]
        hs.append(h)
        errs.append(abs(tip - exact) / exact)
        # the clamp carries the whole weight of the rod
        assert res.reactions[-1, :, 2].sum() == pytest.approx(w * system.rods[0].length, rel=1e-7)
    # 8.2925, 8.7841, 8.9338 for N = 21, 41, 81 edges: second order with a large constant
    assert errs[-1] < 7e-3
    assert 1.7 < _order(hs, errs) < 2.3


def test_cantilever_tip_load_small_deflection_matches_euler_bernoulli():
    """Tip deflection P L^3 / (3 EI) for a dead tip load, deflection/L = 3.3e-4."""
    L, r, E = 1.0, 1e-3, 1e9
    ei = E * np.pi * r**4 / 4
    p = 1e-3 * ei / L**2
    hs, errs = [], []
    for n in (11, 21, 41):
        system, cons, h = clamped_rod(n, length=L, radius=r, youngs_modulus=E)
        res = _static(system, cons, [rod.NodeForce(-1, (0, 0, -p))])
        tip = -res.positions[-1, -1, 2]
        exact = p * L**3 / (3 * ei)
        hs.append(h)
        errs.append(abs(tip - exact) / exact)
        # reaction moment balance: the clamp's two node forces are a couple p L + shear p
        rz = res.reactions[-1, :, 2]
        assert rz.sum() == pytest.approx(p, rel=1e-7)
    assert errs[-1] < 1e-3
    assert 1.8 < _order(hs, errs) < 2.3


def _elastica_tip(load):
    """Tip position (x, y) of the inextensible elastica, unit length, clamped at s = 0,
    dead transverse tip load with load = P L^2 / EI: theta'' = -load cos(theta),
    theta(0) = 0, theta'(1) = 0 (Bisshopp & Drucker 1945), solved with solve_bvp."""

    def f(s, y):
        return np.vstack([y[1], -load * np.cos(y[0]), np.cos(y[0]), np.sin(y[0])])

    def bc(a, b):
        return np.array([a[0], b[1], a[2], a[3]])

    s = np.linspace(0, 1, 201)
    y0 = np.zeros((4, s.size))
    y0[2] = s
    sol = solve_bvp(f, bc, s, y0, tol=1e-10, max_nodes=100000)
    assert sol.status == 0
    return sol.y[2, -1], sol.y[3, -1]


def test_elastica_large_deflection_tip_load_second_order_convergence():
    """Large deflection (P L^2/EI = 3: tip drops 0.603 L) against the elastica; the rod is
    slender (r/L = 1e-3) so extensibility enters at 1e-6."""
    load = 3.0
    x_ref, y_ref = _elastica_tip(load)
    assert y_ref == pytest.approx(0.6033, abs=1e-4)  # Bisshopp & Drucker's table: 0.603
    L, r, E = 1.0, 1e-3, 1e9
    ei = E * np.pi * r**4 / 4
    hs, errs = [], []
    for n in (21, 41, 81):
        system, cons, h = clamped_rod(n, length=L, radius=r, youngs_modulus=E)
        res = _static(system, cons, [rod.NodeForce(-1, (0, 0, -load * ei), ramp_time=8e3)])
        tip = res.positions[-1, -1]
        hs.append(h)
        errs.append(np.hypot(tip[0] - x_ref, -tip[2] - y_ref) / y_ref)
    assert errs[-1] < 3e-4
    assert 1.8 < _order(hs, errs) < 2.4


def test_euler_buckling_load_of_a_clamped_free_column():
    """Critical dead compressive load pi^2 EI / (4 L^2) (Euler; Timoshenko & Gere, Theory of
    Elastic Stability, sec. 2.1): the smallest eigenvalue of the Hessian of the compressed
    straight column (free dofs) crosses zero there."""
    L, r, E = 1.0, 1e-3, 1e9
    ei = E * np.pi * r**4 / 4
    ea = E * np.pi * r**2
    pc = np.pi**2 * ei / (4 * L**2)
    hs, errs = [], []
    for n in (11, 21, 41):
        system, cons, h = clamped_rod(n, length=L, radius=r, youngs_modulus=E)
        st = system.initial_state()
        cdofs = np.concatenate([c.dofs(system) for c in cons])

        def eig(p, system=system, st=st, cdofs=cdofs, h=h):
            q = st.q.copy()
            x1 = q[system.node_dofs[1, 0]]
            i = np.arange(1, system.n_nodes)
            q[system.node_dofs[i, 0]] = x1 + (i - 1) * h * (1 - p / ea)  # equilibrium
            return min_eig_constrained(system, q, st, cdofs)

        p_num = brentq(eig, 0.5 * pc, 1.5 * pc, xtol=1e-14 * pc)
        hs.append(h)
        errs.append(abs(p_num - pc) / pc)
    assert errs[-1] < 1e-3
    assert 1.8 < _order(hs, errs) < 2.3


def test_greenhill_twist_buckling_threshold_of_a_clamped_rod():
    """A straight rod clamped at both ends (no axial force) buckles under the twisting moment
    M = 8.9868 EI / L, where 8.9868/2 = 4.4934 is the first positive root of tan x = x
    (Greenhill 1883; Timoshenko & Gere, Theory of Elastic Stability, sec. 2.16, whose linear
    equation EI w'''' - i M w''' = 0 with w = w' = 0 at both ends gives tan(ML/2EI) = ML/2EI).
    M = GJ Phi / L for an end rotation Phi; the Hessian's smallest eigenvalue crosses zero."""
    x = brentq(lambda x: np.tan(x) - x, 4.0, 4.6)
    mc_theory = 2 * x  # in units of EI/L
    assert mc_theory == pytest.approx(8.9868, abs=1e-4)
    L, r, E = 1.0, 1e-3, 1e9
    hs, errs = [], []
    for n in (22, 42, 82):
        system, cons, h = clamped_rod(n, length=L, radius=r, youngs_modulus=E, both=True)
        rd = system.rods[0]
        st = system.initial_state()
        cdofs = np.concatenate([c.dofs(system) for c in cons])
        k = np.arange(system.n_edges)

        def eig(phi, system=system, st=st, cdofs=cdofs, k=k):
            q = st.q.copy()
            q[system.edge_theta_dof] = phi * k / (system.n_edges - 1)
            return min_eig_constrained(system, q, st, cdofs)

        phi_c = brentq(eig, 5.0, 20.0, xtol=1e-13)
        mc = rd.twisting_stiffness * phi_c / L / (rd.bending_stiffness / L)
        hs.append(h)
        errs.append(abs(mc - mc_theory) / mc_theory)
    # 8.2925, 8.7841, 8.9338 for N = 21, 41, 81 edges: second order with a large constant
    assert errs[-1] < 7e-3
    assert 1.7 < _order(hs, errs) < 2.3


@pytest.mark.parametrize("factor", [0.9, 1.1])
def test_dynamic_euler_buckling_of_a_clamped_free_column(factor):
    """Time integration around the Euler load pi^2 EI / (4 L^2): a column perturbed by a
    1e-4 L lateral bump stays straight under 0.9 P_c (the perturbation decays, implicit
    Euler only dissipates) and buckles under 1.1 P_c (it grows more than a hundredfold)."""
    L, r, E = 1.0, 1e-3, 1e9
    system0, cons, h = clamped_rod(21, length=L, radius=r, youngs_modulus=E)
    pos = system0.rods[0].positions.copy()
    s = np.clip(pos[:, 0] - h / 2, 0.0, None)
    pos[:, 2] = 1e-4 * (1 - np.cos(np.pi * s / (2 * L)))
    bumped = rod.Rod(positions=pos, radius=r, youngs_modulus=E, density=1000.0, natural="straight")
    system = rod.RodSystem([bumped])
    ei = bumped.bending_stiffness
    pc = np.pi**2 * ei / (4 * L**2)
    res = rod.simulate(
        system, t_end=15.0, dt=0.02, loads=[rod.NodeForce(-1, (-factor * pc, 0, 0))],
        constraints=cons, options=rod.SolverOptions(save_every=0.5),
    )  # fmt: skip
    amp = np.abs(res.positions[:, -1, 2])
    if factor < 1:
        assert amp[-1] < 1.1e-4 and np.max(amp) < 1.5e-4
    else:
        assert np.max(amp) > 1e-2


def test_bending_scale_one_is_the_solid_rod_and_kappa_scales_b_and_gj():
    """kappa = 1 gives exactly the old E pi r^4/4 and G pi r^4/2; kappa scales both."""
    kw = dict(length=1.0, n_nodes=5, radius=2e-3, youngs_modulus=1e9, density=1000.0)
    solid = rod.Rod.straight(**kw)
    assert solid.bending_scale == 1.0
    assert solid.bending_stiffness == 1e9 * np.pi * 2e-3**4 / 4.0
    assert solid.twisting_stiffness == solid.shear * np.pi * 2e-3**4 / 2.0
    soft = rod.Rod.straight(**kw, bending_scale=0.01)
    assert soft.bending_stiffness == pytest.approx(0.01 * 1e9 * np.pi * 2e-3**4 / 4.0, rel=1e-15)
    assert soft.twisting_stiffness == pytest.approx(0.01 * solid.twisting_stiffness, rel=1e-15)
    assert soft.stretching_stiffness == solid.stretching_stiffness


@pytest.mark.parametrize("bad", [0.0, -1.0, 2.0, float("nan"), float("inf"), "x"])
def test_bending_scale_out_of_range_is_a_one_line_error(bad):
    kw = dict(length=1.0, n_nodes=5, radius=2e-3, youngs_modulus=1e9, density=1000.0)
    with pytest.raises(ValueError, match="bending_scale") as e:
        rod.Rod.straight(**kw, bending_scale=bad)
    assert "\n" not in str(e.value)


def test_cantilever_tip_deflection_scales_as_one_over_kappa():
    """Tip deflection P L^3 / (3 kappa EI): kappa = 0.1 deflects 10x the solid rod."""
    L, r, E, n = 1.0, 1e-3, 1e9, 21
    ei = E * np.pi * r**4 / 4
    p = 1e-4 * ei / L**2
    tips = {}
    for kappa in (1.0, 0.1):
        system, cons, _ = clamped_rod(n, length=L, radius=r, youngs_modulus=E)
        r0 = system.rods[0]
        soft = rod.Rod(
            positions=r0.positions,
            radius=r,
            youngs_modulus=E,
            density=1000.0,
            bending_scale=kappa,
        )
        system = rod.RodSystem([soft])
        cons = [rod.clamp_end(system, end="start")]
        res = _static(system, cons, [rod.NodeForce(-1, (0, 0, -p))])
        tips[kappa] = -res.positions[-1, -1, 2]
        assert tips[kappa] == pytest.approx(p * L**3 / (3 * kappa * ei), rel=5e-3)
    assert tips[0.1] / tips[1.0] == pytest.approx(10.0, rel=2e-3)
