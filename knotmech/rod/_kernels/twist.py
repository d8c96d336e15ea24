"""Twisting energy: gradient and Hessian (coated-rod paper eq. (4)).

E_t = sum_i GJ / (2 l_i) (m_i - mbar_i)^2, m_i = theta^i - theta^{i-1} + m_ref_i
(Bergou 2010 sec. 4.2), l_i the Voronoi length. In the edge-space variables
y = (e, theta^e, f, theta^f) of a stencil, with kb the curvature binormal, chi = 1 + t^e.t^f
and tt = (t^e + t^f)/chi (Bergou 2010 sec. 7; Panetta's gradient/Hessian notes):
dm/de = kb/(2|e|),  dm/df = kb/(2|f|),  dm/dtheta^e = -1,  dm/dtheta^f = 1,
d2m/de2 = -(kb (t^e + tt)^T + (t^e + tt) kb^T)/(4|e|^2),
d2m/df2 = -(kb (t^f + tt)^T + (t^f + tt) kb^T)/(4|f|^2),
d2m/de df = ((2/chi) [t^e]_x - kb tt^T)/(2|e||f|).
"""

import numpy as np
from numba import njit

from .bend import _add_edge_grad, edge_geometry


@njit(cache=True, fastmath=True)
def twist_grad_hess(
    q, edge_dof0, stencil_edge, ref_twist, twist_bar, gj, voronoi, grad, hess8, with_hess=True
):
    """Add dE_t/dq to ``grad`` and the 8x8 edge-space Hessian of each stencil to ``hess8``
    (skipped if ``with_hess`` is False); return the twisting energy E_t [J].

    ``gj`` (n_stencils,) twisting stiffness GJ [N m^2], ``twist_bar`` rest twist [rad].
    d2E/dy2 = GJ/l (g g^T + (m - mbar) H), g = dm/dy, H = d2m/dy2.
    """
    ev = np.empty(3)
    fv = np.empty(3)
    te = np.empty(3)
    tf = np.empty(3)
    kb = np.empty(3)
    tt = np.empty(3)
    g = np.empty(8)
    h = np.zeros((8, 8))
    energy = 0.0
    for s in range(stencil_edge.shape[0]):
        f = stencil_edge[s]
        e = f - 1
        ne, nf, chi = edge_geometry(q, edge_dof0, e, f, ev, fv, te, tf, kb)
        d0 = edge_dof0[e]
        m = q[d0 + 7] - q[d0 + 3] + ref_twist[s]
        for j in range(3):
            tt[j] = (te[j] + tf[j]) / chi
            g[j] = 0.5 * kb[j] / ne
            g[4 + j] = 0.5 * kb[j] / nf
        g[3] = -1.0
        g[7] = 1.0
        k = gj[s] / voronoi[s]
        r = m - twist_bar[s]
        energy += 0.5 * k * r * r
        for i in range(8):
            _add_edge_grad(grad, d0, i, k * r * g[i])
        if not with_hess:
            continue
        ne2 = ne * ne
        nf2 = nf * nf
        nef = ne * nf
        for i in range(3):
            for j in range(3):
                h[i, j] = -(kb[i] * (te[j] + tt[j]) + (te[i] + tt[i]) * kb[j]) / (4.0 * ne2)
                h[4 + i, 4 + j] = -(kb[i] * (tf[j] + tt[j]) + (tf[i] + tt[i]) * kb[j]) / (4.0 * nf2)
                h[i, 4 + j] = -kb[i] * tt[j] / (2.0 * nef)
        c = 1.0 / (chi * nef)  # (2/chi) [t^e]_x / (2 |e||f|)
        h[0, 5] += -te[2] * c
        h[0, 6] += te[1] * c
        h[1, 4] += te[2] * c
        h[1, 6] += -te[0] * c
        h[2, 4] += -te[1] * c
        h[2, 5] += te[0] * c
        for i in range(3):
            for j in range(3):
                h[4 + j, i] = h[i, 4 + j]
        for i in range(8):
            for j in range(8):
                hess8[s, i, j] += k * (g[i] * g[j] + r * h[i, j])
    return energy
