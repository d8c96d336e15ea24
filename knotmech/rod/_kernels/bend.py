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
def bend_grad_hess(
    q, edge_dof0, stencil_edge, m1, m2, kappa_bar, ei, voronoi, grad, hess8, with_hess=True
):
    """Add dE_b/dq to ``grad``; WRITE the 8x8 edge-space Hessian of each stencil in ``hess8``
    (skipped, ``hess8`` untouched, if ``with_hess`` is False); return the bending energy
    E_b [J].

    ``ei`` (n_stencils,) bending stiffness EI [N m^2], ``voronoi`` (n_stencils,) l_i [m],
    ``kappa_bar`` (n_stencils, 2) rest material curvatures. E_b = EI/(2 l) |kappa - kbar|^2,
    so d2E/dy2 = EI/l * (g1 g1^T + g2 g2^T + r1 H1 + r2 H2), r_a = kappa_a - kbar_a.
    r1 H1 + r2 H2 is formed directly: the Hessian blocks of kappa1 and kappa2 (Panetta's
    notes; the DER primer) have the same structure, so the combination only needs
    kr = kappa1 r1 + kappa2 r2 and the vectors D = r1 mt2 - r2 mt1,
    M^j = r1 m2^j - r2 m1^j, N^j = r1 m1^j + r2 m2^j:
      d2/de2   = [2 kr tt tt^T - (t^f x D) tt^T - tt (t^f x D)^T]/|e|^2
                 - kr/(chi |e|^2) (I - t^e t^e^T) + (kb M^e^T + M^e kb^T)/(4 |e|^2),
      d2/df2   = [2 kr tt tt^T + (t^e x D) tt^T + tt (t^e x D)^T]/|f|^2
                 - kr/(chi |f|^2) (I - t^f t^f^T) + (kb M^f^T + M^f kb^T)/(4 |f|^2),
      d2/dedf  = -kr/(chi |e||f|) (I + t^e t^f^T)
                 + [2 kr tt tt^T - (t^f x D) tt^T + tt (t^e x D)^T - [D]_x]/(|e||f|),
      d2/dtheta^j2 = -kb.M^j/2,
      d2/de dtheta^j = (kb.N^j tt/2 - t^f x N^j/chi)/|e|,
      d2/df dtheta^j = (kb.N^j tt/2 + t^e x N^j/chi)/|f|.
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
    dv = np.empty(3)
    me = np.empty(3)
    mf = np.empty(3)
    nn_e = np.empty(3)
    nn_f = np.empty(3)
    tfc_d2 = np.empty(3)
    tec_d2 = np.empty(3)
    tfc_d1 = np.empty(3)
    tec_d1 = np.empty(3)
    tfc_d = np.empty(3)
    tec_d = np.empty(3)
    tmp = np.empty(3)
    g = np.empty((2, 8))
    h = np.empty((8, 8))
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
        k = ei[s] / voronoi[s]
        r1 = kap1 - kappa_bar[s, 0]
        r2 = kap2 - kappa_bar[s, 1]
        energy += 0.5 * k * (r1 * r1 + r2 * r2)
        # ---- gradients of kappa1, kappa2 (edge space)
        _cross3(tf, d2t, tfc_d2)
        _cross3(te, d2t, tec_d2)
        _cross3(tf, d1t, tfc_d1)
        _cross3(te, d1t, tec_d1)
        for j in range(3):
            g[0, j] = (-kap1 * tt[j] + tfc_d2[j]) / ne
            g[0, 4 + j] = (-kap1 * tt[j] - tec_d2[j]) / nf
            g[1, j] = (-kap2 * tt[j] - tfc_d1[j]) / ne
            g[1, 4 + j] = (-kap2 * tt[j] + tec_d1[j]) / nf
        g[0, 3] = -0.5 * _dot3(kb, m1e)
        g[0, 7] = -0.5 * _dot3(kb, m1f)
        g[1, 3] = -0.5 * _dot3(kb, m2e)
        g[1, 7] = -0.5 * _dot3(kb, m2f)
        d0 = edge_dof0[e]
        for i in range(8):
            _add_edge_grad(grad, d0, i, k * (r1 * g[0, i] + r2 * g[1, i]))
        if not with_hess:
            continue
        # ---- combined r1 H1 + r2 H2
        kr = kap1 * r1 + kap2 * r2
        for j in range(3):
            dv[j] = r1 * d2t[j] - r2 * d1t[j]
            me[j] = r1 * m2e[j] - r2 * m1e[j]
            mf[j] = r1 * m2f[j] - r2 * m1f[j]
            nn_e[j] = r1 * m1e[j] + r2 * m2e[j]
            nn_f[j] = r1 * m1f[j] + r2 * m2f[j]
        _cross3(tf, dv, tfc_d)
        _cross3(te, dv, tec_d)
        _hess_positions(h, kr, chi, ne, nf, tt, te, tf, kb, dv, me, mf, tfc_d, tec_d)
        _hess_angles(h, chi, ne, nf, tt, te, tf, kb, me, mf, nn_e, nn_f, tmp)
        # ---- energy Hessian
        for i in range(8):
            for j in range(8):
                hess8[s, i, j] = k * (g[0, i] * g[0, j] + g[1, i] * g[1, j] + h[i, j])
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


@njit(cache=True, fastmath=True, inline="always")
def _hess_positions(h, kr, chi, ne, nf, tt, te, tf, kb, dv, me, mf, tfc_d, tec_d):
    """Edge-vector blocks d2/de2, d2/df2, d2/dedf of r1 H1 + r2 H2 (the formulas of
    :func:`bend_grad_hess`'s docstring) into h[:3, :3], h[4:7, 4:7], h[:3, 4:7]."""
    ie2 = 1.0 / (ne * ne)
    if2 = 1.0 / (nf * nf)
    ief = 1.0 / (ne * nf)
    ichi = 1.0 / chi
    for i in range(3):
        for j in range(3):
            ttij = 2.0 * kr * tt[i] * tt[j]
            idt = 1.0 if i == j else 0.0
            h[i, j] = ie2 * (
                ttij - tfc_d[i] * tt[j] - tt[i] * tfc_d[j]
                - kr * ichi * (idt - te[i] * te[j])
                + 0.25 * (kb[i] * me[j] + me[i] * kb[j])
            )  # fmt: skip
            h[4 + i, 4 + j] = if2 * (
                ttij + tec_d[i] * tt[j] + tt[i] * tec_d[j]
                - kr * ichi * (idt - tf[i] * tf[j])
                + 0.25 * (kb[i] * mf[j] + mf[i] * kb[j])
            )  # fmt: skip
            h[i, 4 + j] = ief * (
                -kr * ichi * (idt + te[i] * tf[j]) + ttij - tfc_d[i] * tt[j] + tt[i] * tec_d[j]
            )
    # - [D]_x / (|e||f|)
    h[0, 5] += dv[2] * ief
    h[0, 6] -= dv[1] * ief
    h[1, 4] -= dv[2] * ief
    h[1, 6] += dv[0] * ief
    h[2, 4] += dv[1] * ief
    h[2, 5] -= dv[0] * ief


@njit(cache=True, fastmath=True, inline="always")
def _hess_angles(h, chi, ne, nf, tt, te, tf, kb, me, mf, nn_e, nn_f, tmp):
    """Twist-angle rows and columns of r1 H1 + r2 H2 (d2/dtheta^j2, d2/de dtheta^j,
    d2/df dtheta^j of :func:`bend_grad_hess`'s docstring), then the lower blocks by
    symmetry."""
    ichi = 1.0 / chi
    h[3, 3] = -0.5 * _dot3(kb, me)
    h[7, 7] = -0.5 * _dot3(kb, mf)
    h[3, 7] = 0.0
    h[7, 3] = 0.0
    kbn_e = 0.5 * _dot3(kb, nn_e)
    kbn_f = 0.5 * _dot3(kb, nn_f)
    _cross3(tf, nn_e, tmp)
    for j in range(3):
        h[j, 3] = (kbn_e * tt[j] - tmp[j] * ichi) / ne
    _cross3(tf, nn_f, tmp)
    for j in range(3):
        h[j, 7] = (kbn_f * tt[j] - tmp[j] * ichi) / ne
    _cross3(te, nn_e, tmp)
    for j in range(3):
        h[4 + j, 3] = (kbn_e * tt[j] + tmp[j] * ichi) / nf
    _cross3(te, nn_f, tmp)
    for j in range(3):
        h[4 + j, 7] = (kbn_f * tt[j] + tmp[j] * ichi) / nf
    for i in range(3):
        h[3, i] = h[i, 3]
        h[7, i] = h[i, 7]
        h[3, 4 + i] = h[4 + i, 3]
        h[7, 4 + i] = h[4 + i, 7]
        for j in range(3):
            h[4 + j, i] = h[i, 4 + j]
