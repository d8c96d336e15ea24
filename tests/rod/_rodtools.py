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
