"""Bending energy with the 2 tan(phi/2) curvature binormal: gradient and Hessian.

E_b = sum_i EI / (2 l_i) * [(kappa1_i - kbar1_i)^2 + (kappa2_i - kbar2_i)^2]
(coated-rod paper eq. (3) written with the material curvatures of Bergou et al. 2010,
sec. 4.1; l_i = (|ebar^{i-1}| + |ebar^i|)/2 is the Voronoi length).

Derivatives are taken in "edge space", the 8 variables y = (e, theta^e, f, theta^f) of a
stencil with e = x_i - x_{i-1}, f = x_{i+1} - x_i, with the reference frames moving by
parallel transport (Bergou 2010 sec. 7; the Hessian blocks are those of M. Panetta,
"Discrete elastic rods: gradient and Hessian" notes, and of the Jawed/Khuong/Reis DER
primer). With chi = 1 + t^e.t^f, tt = (t^e + t^f)/chi, mt_a = (m_a^e + m_a^f)/chi:
dkappa1/de = (-kappa1 tt + t^f x mt2)/|e|,  dkappa1/df = (-kappa1 tt - t^e x mt2)/|f|,
dkappa2/de = (-kappa2 tt - t^f x mt1)/|e|,  dkappa2/df = (-kappa2 tt + t^e x mt1)/|f|,
dkappa1/dtheta^j = -kb.m1^j/2,  dkappa2/dtheta^j = -kb.m2^j/2.
"""

import numpy as np
from numba import njit


@njit(cache=True, fastmath=True, inline="always")
def _cross3(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(cache=True, fastmath=True, inline="always")
def _dot3(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, fastmath=True)
def edge_geometry(q, edge_dof0, e_idx, f_idx, ev, fv, te, tf, kb):
    """Fill edge vectors, tangents and curvature binormal of a stencil; return (|e|, |f|, chi).

    kb = 2 t^e x t^f / (1 + t^e.t^f) (Bergou 2008 eq. 1).
    """
    de = edge_dof0[e_idx]
    df = edge_dof0[f_idx]
    for j in range(3):
        ev[j] = q[de + 4 + j] - q[de + j]
        fv[j] = q[df + 4 + j] - q[df + j]
    ne = np.sqrt(_dot3(ev, ev))
    nf = np.sqrt(_dot3(fv, fv))
    for j in range(3):
        te[j] = ev[j] / ne
        tf[j] = fv[j] / nf
    chi = 1.0 + _dot3(te, tf)
    _cross3(te, tf, kb)
    for j in range(3):
        kb[j] *= 2.0 / chi
    return ne, nf, chi


@njit(cache=True, fastmath=True)
def bend_grad_hess(q, edge_dof0, stencil_edge, m1, m2, kappa_bar, ei, voronoi, grad, hess8):
    """Add dE_b/dq to ``grad``; WRITE the 8x8 edge-space Hessian of each stencil in ``hess8``;
    return the bending energy E_b [J].

    ``ei`` (n_stencils,) bending stiffness EI [N m^2], ``voronoi`` (n_stencils,) l_i [m],
    ``kappa_bar`` (n_stencils, 2) rest material curvatures. E_b = EI/(2 l) |kappa - kbar|^2,
    so d2E/dy2 = EI/l * sum_a (g_a g_a^T + (kappa_a - kbar_a) H_a).
    """
    ev = np.empty(3)
    fv = np.empty(3)
    te = np.empty(3)
    tf = np.empty(3)
    kb = np.empty(3)
    tt = np.empty(3)
    m1e = np.empty(3)
    m1f = np.empty(3)
    m2e = np.empty(3)
    m2f = np.empty(3)
    d1t = np.empty(3)
    d2t = np.empty(3)
    tmp = np.empty(3)
    tfc_d2 = np.empty(3)
    tec_d2 = np.empty(3)
    tfc_d1 = np.empty(3)
    tec_d1 = np.empty(3)
    g = np.empty((2, 8))
    h = np.empty((2, 8, 8))
    energy = 0.0
    for s in range(stencil_edge.shape[0]):
        f = stencil_edge[s]
        e = f - 1
        ne, nf, chi = edge_geometry(q, edge_dof0, e, f, ev, fv, te, tf, kb)
        for j in range(3):
            tt[j] = (te[j] + tf[j]) / chi
            m1e[j] = m1[e, j]
            m1f[j] = m1[f, j]
            m2e[j] = m2[e, j]
            m2f[j] = m2[f, j]
            d1t[j] = (m1e[j] + m1f[j]) / chi
            d2t[j] = (m2e[j] + m2f[j]) / chi
        kap1 = 0.5 * (_dot3(kb, m2e) + _dot3(kb, m2f))
        kap2 = -0.5 * (_dot3(kb, m1e) + _dot3(kb, m1f))
        kb_m1e = _dot3(kb, m1e)
        kb_m1f = _dot3(kb, m1f)
        kb_m2e = _dot3(kb, m2e)
        kb_m2f = _dot3(kb, m2f)
        for a in range(2):
            h[a, 3, 7] = 0.0
            h[a, 7, 3] = 0.0
        # ---- kappa1: gradient
        _cross3(tf, d2t, tfc_d2)  # t^f x mt2
        _cross3(te, d2t, tec_d2)  # t^e x mt2
        _cross3(tf, d1t, tfc_d1)
        _cross3(te, d1t, tec_d1)
        for j in range(3):
            g[0, j] = (-kap1 * tt[j] + tfc_d2[j]) / ne
            g[0, 4 + j] = (-kap1 * tt[j] - tec_d2[j]) / nf
            g[1, j] = (-kap2 * tt[j] - tfc_d1[j]) / ne
            g[1, 4 + j] = (-kap2 * tt[j] + tec_d1[j]) / nf
        g[0, 3] = -0.5 * kb_m1e
        g[0, 7] = -0.5 * kb_m1f
        g[1, 3] = -0.5 * kb_m2e
        g[1, 7] = -0.5 * kb_m2f
        # ---- position-position blocks
        ne2 = ne * ne
        nf2 = nf * nf
        nef = ne * nf
        for i in range(3):
            for j in range(3):
                ttij = tt[i] * tt[j]
                idt = 1.0 if i == j else 0.0
                # kappa1
                h[0, i, j] = (
                    (2.0 * kap1 * ttij - tfc_d2[i] * tt[j] - tt[i] * tfc_d2[j]) / ne2
                    - kap1 / (chi * ne2) * (idt - te[i] * te[j])
                    + (kb[i] * m2e[j] + m2e[i] * kb[j]) / (4.0 * ne2)
                )
                h[0, 4 + i, 4 + j] = (
                    (2.0 * kap1 * ttij + tec_d2[i] * tt[j] + tt[i] * tec_d2[j]) / nf2
                    - kap1 / (chi * nf2) * (idt - tf[i] * tf[j])
                    + (kb[i] * m2f[j] + m2f[i] * kb[j]) / (4.0 * nf2)
                )
                h[0, i, 4 + j] = (
                    -kap1 / (chi * nef) * (idt + te[i] * tf[j])
                    + (2.0 * kap1 * ttij - tfc_d2[i] * tt[j] + tt[i] * tec_d2[j]) / nef
                )
                # kappa2
                h[1, i, j] = (
                    (2.0 * kap2 * ttij + tfc_d1[i] * tt[j] + tt[i] * tfc_d1[j]) / ne2
                    - kap2 / (chi * ne2) * (idt - te[i] * te[j])
                    - (kb[i] * m1e[j] + m1e[i] * kb[j]) / (4.0 * ne2)
                )
                h[1, 4 + i, 4 + j] = (
                    (2.0 * kap2 * ttij - tec_d1[i] * tt[j] - tt[i] * tec_d1[j]) / nf2
                    - kap2 / (chi * nf2) * (idt - tf[i] * tf[j])
                    - (kb[i] * m1f[j] + m1f[i] * kb[j]) / (4.0 * nf2)
                )
                h[1, i, 4 + j] = (
                    -kap2 / (chi * nef) * (idt + te[i] * tf[j])
                    + (2.0 * kap2 * ttij + tfc_d1[i] * tt[j] - tt[i] * tec_d1[j]) / nef
                )
        # cross-product matrices [mt]_x (a x b = [a]_x b) in the e-f blocks
        h[0, 0, 5] -= -d2t[2] / nef
        h[0, 0, 6] -= d2t[1] / nef
        h[0, 1, 4] -= d2t[2] / nef
        h[0, 1, 6] -= -d2t[0] / nef
        h[0, 2, 4] -= -d2t[1] / nef
        h[0, 2, 5] -= d2t[0] / nef
        h[1, 0, 5] += -d1t[2] / nef
        h[1, 0, 6] += d1t[1] / nef
        h[1, 1, 4] += d1t[2] / nef
        h[1, 1, 6] += -d1t[0] / nef
        h[1, 2, 4] += -d1t[1] / nef
        h[1, 2, 5] += d1t[0] / nef
        for i in range(3):
            for j in range(3):
                h[0, 4 + j, i] = h[0, i, 4 + j]
                h[1, 4 + j, i] = h[1, i, 4 + j]
        # ---- theta-theta
        h[0, 3, 3] = -0.5 * kb_m2e
        h[0, 7, 7] = -0.5 * kb_m2f
        h[1, 3, 3] = 0.5 * kb_m1e
        h[1, 7, 7] = 0.5 * kb_m1f
        # ---- position-theta
        _cross3(tf, m1e, tmp)
        for j in range(3):
            h[0, j, 3] = (0.5 * kb_m1e * tt[j] - tmp[j] / chi) / ne
        _cross3(tf, m1f, tmp)
        for j in range(3):
            h[0, j, 7] = (0.5 * kb_m1f * tt[j] - tmp[j] / chi) / ne
        _cross3(te, m1e, tmp)
        for j in range(3):
            h[0, 4 + j, 3] = (0.5 * kb_m1e * tt[j] + tmp[j] / chi) / nf
        _cross3(te, m1f, tmp)
        for j in range(3):
            h[0, 4 + j, 7] = (0.5 * kb_m1f * tt[j] + tmp[j] / chi) / nf
        _cross3(tf, m2e, tmp)
        for j in range(3):
            h[1, j, 3] = (0.5 * kb_m2e * tt[j] - tmp[j] / chi) / ne
        _cross3(tf, m2f, tmp)
        for j in range(3):
            h[1, j, 7] = (0.5 * kb_m2f * tt[j] - tmp[j] / chi) / ne
        _cross3(te, m2e, tmp)
        for j in range(3):
            h[1, 4 + j, 3] = (0.5 * kb_m2e * tt[j] + tmp[j] / chi) / nf
        _cross3(te, m2f, tmp)
        for j in range(3):
            h[1, 4 + j, 7] = (0.5 * kb_m2f * tt[j] + tmp[j] / chi) / nf
        for a in range(2):
            for j in range(3):
                h[a, 3, j] = h[a, j, 3]
                h[a, 7, j] = h[a, j, 7]
                h[a, 3, 4 + j] = h[a, 4 + j, 3]
                h[a, 7, 4 + j] = h[a, 4 + j, 7]
        # ---- energy derivatives
        k = ei[s] / voronoi[s]
        r1 = kap1 - kappa_bar[s, 0]
        r2 = kap2 - kappa_bar[s, 1]
        energy += 0.5 * k * (r1 * r1 + r2 * r2)
        for i in range(8):
            gi = k * (r1 * g[0, i] + r2 * g[1, i])
            for j in range(8):
                hess8[s, i, j] = k * (
                    g[0, i] * g[0, j] + g[1, i] * g[1, j] + r1 * h[0, i, j] + r2 * h[1, i, j]
                )
            _add_edge_grad(grad, edge_dof0[e], i, gi)
    return energy


@njit(cache=True, fastmath=True, inline="always")
def _add_edge_grad(grad, d0, i, gi):
    """Scatter an edge-space gradient entry i of a stencil whose first dof is d0.

    e = x_i - x_{i-1}, f = x_{i+1} - x_i: d/dx_{i-1} = -d/de, d/dx_i = d/de - d/df,
    d/dx_{i+1} = d/df; the twist angles map one to one.
    """
    if i < 3:
        grad[d0 + i] -= gi
        grad[d0 + 4 + i] += gi
    elif i == 3:
        grad[d0 + 3] += gi
    elif i < 7:
        grad[d0 + i] -= gi
        grad[d0 + 4 + i] += gi
    else:
        grad[d0 + 7] += gi
