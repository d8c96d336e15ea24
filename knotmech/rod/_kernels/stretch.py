"""Stretching energy, gradient and Hessian (coated-rod paper eq. (2)).

E_s = sum_k EA_k / 2 * (|e^k| / |ebar^k| - 1)^2 |ebar^k|.
With eps = |e|/|ebar| - 1 and t = e/|e|:
dE/de = EA eps t,   d2E/de2 = EA [t t^T / |ebar| + eps (I - t t^T) / |e|].
"""

import numpy as np
from numba import njit


@njit(cache=True)
def stretch_energy(q, edge_dof0, rest_length, ea):
    """Total stretching energy [J]."""
    out = 0.0
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        e0 = q[d + 4] - q[d]
        e1 = q[d + 5] - q[d + 1]
        e2 = q[d + 6] - q[d + 2]
        eps = np.sqrt(e0 * e0 + e1 * e1 + e2 * e2) / rest_length[k] - 1.0
        out += 0.5 * ea[k] * eps * eps * rest_length[k]
    return out


@njit(cache=True)
def stretch_tension(q, edge_dof0, rest_length, ea, tension):
    """Axial force EA (|e|/|ebar| - 1) of every edge [N] (positive in tension)."""
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        e0 = q[d + 4] - q[d]
        e1 = q[d + 5] - q[d + 1]
        e2 = q[d + 6] - q[d + 2]
        tension[k] = ea[k] * (np.sqrt(e0 * e0 + e1 * e1 + e2 * e2) / rest_length[k] - 1.0)


@njit(cache=True)
def stretch_grad_hess(q, edge_dof0, rest_length, ea, grad, hess, with_hess=True):
    """Add dE_s/dq to ``grad`` (n_dof,); write the 6x6 Hessian of each edge in ``hess``
    (skipped if ``with_hess`` is False); return the stretching energy E_s [J].

    ``hess[k]`` is ordered (x_a, x_b) for the edge's two nodes; d2E/dxa2 = d2E/dxb2 =
    -d2E/dxa dxb = d2E/de2.
    """
    e = np.empty(3)
    energy = 0.0
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        for j in range(3):
            e[j] = q[d + 4 + j] - q[d + j]
        n = np.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
        lb = rest_length[k]
        eps = n / lb - 1.0
        a = ea[k]
        energy += 0.5 * a * eps * eps * lb
        for j in range(3):
            g = a * eps * e[j] / n
            grad[d + j] -= g
            grad[d + 4 + j] += g
        if not with_hess:
            continue
        c_par = a / lb
        c_perp = a * eps / n
        for i in range(3):
            ti = e[i] / n
            for j in range(3):
                tj = e[j] / n
                h = (c_par - c_perp) * ti * tj
                if i == j:
                    h += c_perp
                hess[k, i, j] = h
                hess[k, i + 3, j + 3] = h
                hess[k, i, j + 3] = -h
                hess[k, i + 3, j] = -h
    return energy
