"""Helpers shared by the rod-core tests (not a test module)."""

import numpy as np

from knotmech import rod


def dense_hessian(system, q, state):
    """Elastic Hessian (n_dof, n_dof) at q with frames transported from ``state``."""
    ws = rod.ElasticWorkspace(system)
    ws.frames(q, state.tangents, state.d1, state.ref_twist)
    ws.grad_hess(q)
    r, c, v = ws.coo()
    h = np.zeros((system.n_dof, system.n_dof))
    np.add.at(h, (r, c), v)
    return h, ws


def clamped_rod(
    n_nodes, *, length=1.0, radius=1e-3, youngs_modulus=1e9, density=1000.0, both=False
):
    """A straight rod along x clamped at nodes 0-1 (and N-1, N if ``both``).

    A clamp holds an edge, so it acts at that edge's midpoint: the rod is built half an edge
    longer per clamped end and its free span, from clamp point to tip (or clamp point),
    is exactly ``length``. Returns (system, constraints, edge length).
    """
    n_edges = n_nodes - 1
    h = length / (n_edges - 1.0) if both else length / (n_edges - 0.5)
    r = rod.Rod.straight(
        length=n_edges * h,
        n_nodes=n_nodes,
        radius=radius,
        youngs_modulus=youngs_modulus,
        density=density,
        start=(-h / 2, 0.0, 0.0),
    )
    system = rod.RodSystem([r])
    cons = [rod.clamp_end(system, end="start")]
    if both:
        cons.append(rod.clamp_end(system, end="end"))
    return system, cons, h


def min_eig_constrained(system, q, state, cdofs):
    """Smallest eigenvalue of the elastic Hessian at q with the ``cdofs`` rows and columns
    replaced by the identity's (their eigenvalue 1 cannot cause a sign change), computed
    from the band storage with scipy.linalg.eig_banded (fast for long rods)."""
    from scipy.linalg import eig_banded

    ws = rod.ElasticWorkspace(system)
    ws.frames(q, state.tangents, state.d1, state.ref_twist)
    ws.grad_hess(q)
    gb = np.zeros((31, system.n_dof), order="F")
    ws.band_add(gb)
    low = np.ascontiguousarray(gb[20:31])  # A[i, j] at low[i - j, j], i >= j
    n = system.n_dof
    for d in cdofs:
        for j in range(max(0, d - 10), d):
            low[d - j, j] = 0.0
        for i in range(d + 1, min(n, d + 11)):
            low[i - d, d] = 0.0
        low[0, d] = 1.0
    return eig_banded(low, lower=True, eigvals_only=True, select="i", select_range=(0, 0))[0]
