"""Contact kernels: finite-difference checks, broad phase against brute force, the couple.

Standalone: a minimal stand-in for the solver's system (the index arrays of
notes/der_contract.md), so these tests do not depend on the DER core.
"""

from types import SimpleNamespace

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.rod._kernels.contact_rodrod import edge_distance_hessian
from knotmech.rod.broadphase import candidate_edge_pairs
from knotmech.rod.contact import Cylinder, CylinderContact, RodContact
from knotmech.rod.friction import AnchorFriction, SmoothFriction, stick_slip_weight


def make_system(rods, radius):
    """Dof layout of the contract: per rod [x0, th0, x1, th1, ..., xN]."""
    node_dofs, edge_nodes, theta, edge_rod, node_rod, q = [], [], [], [], [], []
    off_dof = 0
    off_node = 0
    for r, pts in enumerate(rods):
        pts = np.asarray(pts, float)
        n = len(pts)
        for i in range(n):
            node_dofs.append([off_dof + 4 * i + k for k in range(3)])
            node_rod.append(r)
        for i in range(n - 1):
            edge_nodes.append([off_node + i, off_node + i + 1])
            theta.append(off_dof + 4 * i + 3)
            edge_rod.append(r)
        qr = np.zeros(4 * n - 1)
        for i in range(n):
            qr[4 * i : 4 * i + 3] = pts[i]
        q.append(qr)
        off_dof += 4 * n - 1
        off_node += n
    nd = np.array(node_dofs, dtype=np.int64)
    sysm = SimpleNamespace(
        node_dofs=nd,
        edge_nodes=np.array(edge_nodes, dtype=np.int64),
        edge_theta_dof=np.array(theta, dtype=np.int64),
        edge_rod=np.array(edge_rod, dtype=np.int64),
        node_rod=np.array(node_rod, dtype=np.int64),
        rod_radius_edge=np.full(len(edge_nodes), radius),
        n_dof=off_dof,
        contact_exclusion=2,
    )
    sysm.positions = lambda qq: np.asarray(qq)[nd]
    return sysm, np.concatenate(q)


def assemble_dense(inter, sysm, q, q_old, dt):
    f = np.zeros(sysm.n_dof)
    rows, cols, vals = [], [], []
    inter.assemble(sysm, q, q_old, dt, f, rows, cols, vals)
    J = np.zeros((sysm.n_dof, sysm.n_dof))
    np.add.at(J, (np.array(rows, int), np.array(cols, int)), np.array(vals))
    return f, J


def fd_jacobian(inter, sysm, q, q_old, dt, h=1e-8):
    n = sysm.n_dof
    J = np.zeros((n, n))
    for k in range(n):
        qp = q.copy()
        qm = q.copy()
        qp[k] += h
        qm[k] -= h
        fp, _ = assemble_dense(inter, sysm, qp, q_old, dt)
        fm, _ = assemble_dense(inter, sysm, qm, q_old, dt)
        J[:, k] = (fp - fm) / (2 * h)
    return J


# --- edge-edge distance -------------------------------------------------------------------


@pytest.mark.parametrize(
    "x",
    [
        # edge-edge (both parameters interior)
        [0, 0, 0, 1, 0.1, 0, 0.4, -0.5, 0.3, 0.6, 0.7, 0.35],
        # point-edge (end of the first edge against the interior of the second)
        [0, 0, 0, 1, 0, 0.05, 1.3, -0.5, 0.3, 1.4, 0.6, 0.35],
        # point-point (two ends)
        [0, 0, 0, 1, 0.1, 0, 1.5, 0.4, 0.2, 2.5, 0.9, 0.1],
    ],
)
def test_edge_distance_gradient_hessian_fd(x):
    """Gradient and Hessian of Delta(x) against central differences (3 distance cases)."""
    x = np.array(x, float)
    g = np.empty(12)
    H = np.empty((12, 12))
    d0 = edge_distance_hessian(x, g, H)
    h = 1e-6
    g_fd = np.zeros(12)
    H_fd = np.zeros((12, 12))
    for k in range(12):
        xp, xm = x.copy(), x.copy()
        xp[k] += h
        xm[k] -= h
        gp, gm = np.empty(12), np.empty(12)
        dp = edge_distance_hessian(xp, gp, np.empty((12, 12)))
        dm = edge_distance_hessian(xm, gm, np.empty((12, 12)))
        g_fd[k] = (dp - dm) / (2 * h)
        H_fd[:, k] = (gp - gm) / (2 * h)
    assert d0 > 0
    np.testing.assert_allclose(g, g_fd, atol=1e-8)
    np.testing.assert_allclose(H, H_fd, atol=1e-5 * np.abs(H).max())
    np.testing.assert_allclose(H, H.T, atol=1e-12)


def test_edge_distance_values():
    """Known distances: skew perpendicular edges, parallel overlapping edges."""
    g, H = np.empty(12), np.empty((12, 12))
    x = np.array([-1, 0, 0, 1, 0, 0, 0, -1, 0.3, 0, 1, 0.3], float)
    assert edge_distance_hessian(x, g, H) == pytest.approx(0.3, rel=1e-14)
    x = np.array([0, 0, 0, 1, 0, 0, 0.5, 0.2, 0, 1.5, 0.2, 0], float)
    assert edge_distance_hessian(x, g, H) == pytest.approx(0.2, rel=1e-14)


# --- rod-rod contact interaction ----------------------------------------------------------


def crossing_rods(gap, n=6, radius=0.01):
    s = np.linspace(-0.1, 0.1, n)
    a = np.stack([s, 0.0 * s, 0.0 * s], 1)
    b = np.stack([0.0 * s + 0.003, s + 0.004, 0.0 * s + gap], 1)
    return make_system([a, b], radius)


def test_rodrod_force_is_minus_energy_gradient_and_jacobian_fd():
    sysm, q = crossing_rods(gap=0.0195)
    c = RodContact(stiffness=1e4, sharpness=2000.0)
    c.begin_step(sysm, q, None, 1e-3)
    assert len(c.pairs) > 0
    f, J = assemble_dense(c, sysm, q, q, 1e-3)
    h = 1e-8
    grad = np.zeros(sysm.n_dof)
    for k in range(sysm.n_dof):
        qp, qm = q.copy(), q.copy()
        qp[k] += h
        qm[k] -= h
        grad[k] = (c.energy(sysm, qp) - c.energy(sysm, qm)) / (2 * h)
    np.testing.assert_allclose(f, -grad, atol=1e-6 * np.abs(f).max())
    assert np.abs(f).max() > 1.0  # really in contact (overlap 0.5 mm)
    J_fd = fd_jacobian(c, sysm, q, q, 1e-3, h=1e-7)
    np.testing.assert_allclose(J, J_fd, atol=1e-5 * np.abs(J).max())


def test_rodrod_friction_value_and_velocity_jacobian():
    """Sliding pair: |F_fr| = gamma mu |F_n| opposite to v_T (coated-rod eqs. 11-12)."""
    sysm, q = crossing_rods(gap=0.0195)
    mu = 0.4
    c = RodContact(stiffness=1e4, sharpness=2000.0, friction=SmoothFriction(mu))
    c0 = RodContact(stiffness=1e4, sharpness=2000.0)
    dt = 1e-3
    q_old = q.copy()
    # rod 0 moves along +x at 5 mm/s
    for i in range(6):
        q_old[4 * i] -= 5e-3 * dt
    c.begin_step(sysm, q_old, None, dt)
    c0.begin_step(sysm, q_old, None, dt)
    f, J = assemble_dense(c, sysm, q, q_old, dt)
    f0, _ = assemble_dense(c0, sysm, q, q_old, dt)
    ffr = f - f0
    rod0 = sysm.node_dofs[:6].ravel()
    total0 = ffr[rod0].reshape(-1, 3).sum(0)
    fn_total = np.sum(c.last_normal_force)
    gamma = stick_slip_weight(5e-3, sharpness=50 / 0.01, threshold=0.15 * 0.01)
    assert total0[0] < 0
    assert np.linalg.norm(total0) == pytest.approx(gamma * mu * fn_total, rel=1e-6)
    # Jacobian through the velocity: compare with FD on q with q_old fixed, for the
    # friction part only and only in directions that do not change n, |F_n| (x-translations
    # of rod 0 keep the geometry of the crossing)
    h = 1e-9
    dirn = np.zeros(sysm.n_dof)
    dirn[sysm.node_dofs[:6, 0]] = 1.0
    fp, _ = assemble_dense(c, sysm, q + h * dirn, q_old, dt)
    fm, _ = assemble_dense(c, sysm, q - h * dirn, q_old, dt)
    np.testing.assert_allclose(J @ dirn, (fp - fm) / (2 * h), atol=1e-4 * np.abs(J @ dirn).max())


def test_stick_slip_weight_paper_values():
    """k = 50/r0, c = 0.15 r0 (r0 = 0.795 mm): gamma ~ 1 above ~0.2 mm/s (coated-rod sect. 2)."""
    r0 = 0.795e-3
    k, c = 50 / r0, 0.15 * r0
    assert stick_slip_weight(0.0, sharpness=k, threshold=c) == pytest.approx(
        1 / (1 + np.exp(7.5)), rel=1e-12
    )
    assert stick_slip_weight(0.205e-3, sharpness=k, threshold=c) > 0.98
    with pytest.raises(InputError):
        stick_slip_weight(1.0, sharpness=-1.0, threshold=c)


# --- broad phase ----------------------------------------------------------------------------


def test_broadphase_equals_brute_force():
    rng = np.random.default_rng(3)
    # three random-walk rods in a 5 cm box, 600 edges
    rods = []
    for _ in range(3):
        steps = rng.normal(size=(201, 3)) * 2e-3
        rods.append(np.cumsum(steps, 0) + rng.uniform(-0.01, 0.01, 3))
    sysm, q = make_system(rods, 1e-3)
    pos = sysm.positions(q)
    for margin in (0.0, 1e-3, 5e-3):
        a = candidate_edge_pairs(
            pos, sysm.edge_nodes, edge_radius=1e-3, margin=margin, edge_rod=sysm.edge_rod
        )
        b = candidate_edge_pairs(
            pos,
            sysm.edge_nodes,
            edge_radius=1e-3,
            margin=margin,
            edge_rod=sysm.edge_rod,
            method="brute",
        )
        assert len(a) > 100
        np.testing.assert_array_equal(a, b)
    # exclusion: no pair of edges of one rod within 2 indices, none sharing a node
    same = sysm.edge_rod[a[:, 0]] == sysm.edge_rod[a[:, 1]]
    assert np.all(np.abs(a[same, 0] - a[same, 1]) > 2)


def test_broadphase_scales_like_n_log_n():
    """Sweep on a long straight rod: candidates grow linearly (no O(N^2) pairs)."""
    counts = []
    for n in (1000, 4000):
        s = np.linspace(0, 1, n + 1)
        pos = np.stack([s, 0 * s, 0 * s], 1)
        en = np.stack([np.arange(n), np.arange(1, n + 1)], 1)
        counts.append(len(candidate_edge_pairs(pos, en, edge_radius=1e-4, margin=3 / n)))
    assert counts[1] == pytest.approx(4 * counts[0], rel=0.01)


# --- rod-cylinder contact -------------------------------------------------------------------


def rod_over_cylinder(pen=2e-4):
    """A 5-node rod lying across a horizontal cylinder (axis y), slightly pressed in."""
    r, R = 2e-3, 5e-3
    x = np.linspace(-6e-3, 6e-3, 5)
    z = np.sqrt(np.maximum((R + r - pen) ** 2 - x**2, 0.0))
    pts = np.stack([x, 0 * x + 1e-4, z], 1)
    sysm, q = make_system([pts], r)
    cyl = Cylinder(point=[0, 0, 0], axis=[0, 1, 0], radius=R)
    return sysm, q, cyl


def test_cylinder_normal_force_fd():
    sysm, q, cyl = rod_over_cylinder()
    c = CylinderContact([cyl], stiffness=1e6, sharpness=2e4)
    c.begin_step(sysm, q, None, 1e-3)
    f, J = assemble_dense(c, sysm, q, q, 1e-3)
    h = 1e-8
    grad = np.zeros(sysm.n_dof)
    for k in range(sysm.n_dof):
        qp, qm = q.copy(), q.copy()
        qp[k] += h
        qm[k] -= h
        grad[k] = (c.energy(sysm, qp) - c.energy(sysm, qm)) / (2 * h)
    np.testing.assert_allclose(f, -grad, atol=1e-7 * np.abs(f).max())
    J_fd = fd_jacobian(c, sysm, q, q, 1e-3)
    np.testing.assert_allclose(J, J_fd, atol=1e-5 * np.abs(J).max())
    assert np.all(c.normal_force[:, 0] > 0)


@pytest.mark.parametrize("slip", [False, True])
def test_cylinder_friction_and_couple(slip):
    """Anchor-spring friction: value, Jacobian (FD in the stick and slip branches), and the
    surface couple: zero net force, moment r_c x F_t per node (e x f = c)."""
    sysm, q, cyl = rod_over_cylinder()
    mu = 0.3
    fr = AnchorFriction(mu_static=mu, tangential_stiffness=1e6)
    c = CylinderContact([cyl], stiffness=1e6, sharpness=2e4, friction=fr)
    cc = CylinderContact([cyl], stiffness=1e6, sharpness=2e4, friction=fr, surface_friction=False)
    c0 = CylinderContact([cyl], stiffness=1e6, sharpness=2e4)
    q_old = q.copy()
    shift = 2e-3 if slip else 1e-9
    q_old[sysm.node_dofs[:, 1]] -= shift  # every node moved by +shift along the axis (y)
    for x in (c, cc, c0):
        x.begin_step(sysm, q_old, None, 1e-3)
    f, J = assemble_dense(c, sysm, q, q_old, 1e-3)
    fcl, _ = assemble_dense(cc, sysm, q, q_old, 1e-3)
    f0, _ = assemble_dense(c0, sysm, q, q_old, 1e-3)
    N = c.normal_force[:, 0]
    ft = c.friction_force[:, 0, :]
    assert np.all(c.sliding[:, 0] == slip)
    if slip:
        np.testing.assert_allclose(np.linalg.norm(ft, axis=1), mu * N, rtol=1e-12)
    np.testing.assert_allclose(ft[:, 1] < 0, True)
    # centreline variant = normal + friction only
    fric = (fcl - f0)[sysm.node_dofs]
    np.testing.assert_allclose(fric, ft, rtol=1e-12, atol=1e-15)
    # couple part: zero net force and moment about the origin equals sum r_c x F_t
    pos = sysm.positions(q)
    couple_f = (f - fcl)[sysm.node_dofs]
    np.testing.assert_allclose(couple_f.sum(0), 0, atol=1e-12 * np.abs(ft).max())
    moment = np.cross(pos, couple_f).sum(0)
    n_out = pos.copy()
    n_out[:, 1] = 0
    n_out /= np.linalg.norm(n_out, axis=1)[:, None]
    rc = -2e-3 * n_out
    expected = np.cross(rc, ft).sum(0)
    # the twisting components go to the theta dofs: compare the parts perpendicular to edges
    tw = np.array([(f - fcl)[sysm.edge_theta_dof[e]] for e in range(4)])
    ev = pos[1:] - pos[:-1]
    t = ev / np.linalg.norm(ev, axis=1)[:, None]
    np.testing.assert_allclose(moment + (tw[:, None] * t).sum(0), expected, atol=1e-9)
    # Jacobian against FD (slip: the normal's dependence on x is lagged in the friction
    # and lever-arm terms, a ~1 % effect here)
    J_fd = fd_jacobian(c, sysm, q, q_old, 1e-3, h=1e-10 if not slip else 1e-8)
    np.testing.assert_allclose(J, J_fd, atol=(2e-2 if slip else 2e-3) * np.abs(J).max())


def test_anchor_friction_commit_and_static_kinetic():
    """Stick keeps the anchor; slip moves it so that |F_t| = mu N; mu_s for stuck, mu_k after."""
    sysm, q, cyl = rod_over_cylinder()
    fr = AnchorFriction(mu_static=0.5, mu_kinetic=0.3, tangential_stiffness=1e6)
    c = CylinderContact([cyl], stiffness=1e6, sharpness=2e4, friction=fr)
    q_old = q.copy()
    c.begin_step(sysm, q_old, None, 1e-3)
    q1 = q.copy()
    q1[sysm.node_dofs[:, 1]] += 5e-3
    f, _ = assemble_dense(c, sysm, q1, q_old, 1e-3)
    N = c.normal_force[:, 0]
    np.testing.assert_allclose(np.linalg.norm(c.friction_force[:, 0], axis=1), 0.5 * N)
    c.end_step(sysm, q1, q_old, 1e-3)
    assert np.all(c._slipping[:, 0])
    # next step, same place: trial force is mu_s N > mu_k N -> kinetic slip
    c.begin_step(sysm, q1, None, 1e-3)
    q2 = q1.copy()
    q2[sysm.node_dofs[:, 1]] += 1e-9
    assemble_dense(c, sysm, q2, q1, 1e-3)
    np.testing.assert_allclose(
        np.linalg.norm(c.friction_force[:, 0], axis=1), 0.3 * c.normal_force[:, 0], rtol=1e-6
    )
    with pytest.raises(InputError):
        AnchorFriction(mu_static=0.2, mu_kinetic=0.3)


def test_input_errors():
    with pytest.raises(InputError):
        Cylinder(point=[0, 0, 0], axis=[0, 0, 0], radius=1.0)
    with pytest.raises(InputError):
        Cylinder(point=[0, 0, 0], axis=[0, 0, 1], radius=-1.0)
    with pytest.raises(InputError):
        RodContact(stiffness=-1.0, sharpness=1.0)
    with pytest.raises(InputError):
        CylinderContact([], stiffness=1.0, sharpness=1.0)
