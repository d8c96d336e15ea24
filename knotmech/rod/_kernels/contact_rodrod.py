"""Rod-rod (edge-edge) contact kernels: distance, penalty energy, gradient, Hessian, friction.

Private module: arrays in, results written in place.

References
----------
- Choi, Tong & Jawed, "Implicit contact model for discrete elastic rods in knot tying",
  J. Appl. Mech. 88 (2021) 051010 (IMC): smooth penalty on the edge-edge distance.
- Coated-rod paper (J. Appl. Mech., DOI 10.1115/1.4055544), eq. (10) (the softplus of the
  gap), eqs. (11)-(12) (friction with the smooth stick-slip weight gamma).
- Lumelsky, "On fast computation of distance between line segments", IPL 21 (1985):
  closest points of two segments with clamping of the parameters.
"""

from __future__ import annotations

import numpy as np
from numba import njit

_PARALLEL_TOL = 1e-10


@njit(cache=True)
def _clamp01(x):
    if x < 0.0:
        return 0.0
    if x > 1.0:
        return 1.0
    return x


@njit(cache=True)
def segment_params(x1, x2, x3, x4):
    """Closest-point parameters (s, t) of segments x1-x2 and x3-x4 (Lumelsky 1985).

    Returns s, t in [0, 1] and flags free_s, free_t telling whether each parameter lies in the
    open interval (the edge-edge case has both free, point-edge one, point-point none). For
    (near-)parallel edges s is fixed first (one free parameter at most).
    """
    e1 = x2 - x1
    e2 = x4 - x3
    w0 = x1 - x3
    a = e1 @ e1
    b = e1 @ e2
    c = e2 @ e2
    d = e1 @ w0
    e = e2 @ w0
    den = a * c - b * b
    parallel = den <= _PARALLEL_TOL * a * c
    if not parallel:
        s = _clamp01((b * e - c * d) / den)
    else:
        s = 0.0
    t = (b * s + e) / c
    if t < 0.0:
        t = 0.0
        s = _clamp01(-d / a)
    elif t > 1.0:
        t = 1.0
        s = _clamp01((b - d) / a)
    free_s = (s > 0.0) and (s < 1.0)
    free_t = (t > 0.0) and (t < 1.0)
    if parallel and free_s and free_t:
        # one-parameter family of closest points: fix s, leave t free
        free_s = False
    return s, t, free_s, free_t


@njit(cache=True)
def edge_distance(x):
    """Distance Delta between two edges, ``x`` (12,) = (x_i, x_i+1, x_j, x_j+1) (Lumelsky
    1985); the cheap value-only version of :func:`edge_distance_hessian`."""
    s, t, _, _ = segment_params(x[0:3], x[3:6], x[6:9], x[9:12])
    d2 = 0.0
    for m in range(3):
        w = (1.0 - s) * x[m] + s * x[3 + m] - (1.0 - t) * x[6 + m] - t * x[9 + m]
        d2 += w * w
    return np.sqrt(d2)


@njit(cache=True)
def edge_distance_hessian(x, grad, hess):
    """Distance Delta between two edges, its gradient and Hessian w.r.t. the 12 coordinates.

    ``x`` (12,) = (x_i, x_i+1, x_j, x_j+1). Delta(x) = min_{s,t} |p(s) - q(t)|; with
    phi(x, u) = |A(u) x|^2 / 2, u the free parameters, the value function Phi = Delta^2/2 has
    (envelope theorem and implicit differentiation of phi_u = 0)

    .. math:: \\nabla\\Phi = \\phi_x, \\quad
              \\nabla^2\\Phi = \\phi_{xx} - \\phi_{xu}\\,\\phi_{uu}^{-1}\\,\\phi_{ux},

    and Delta = sqrt(2 Phi): grad Delta = grad Phi / Delta,
    Hess Delta = Hess Phi / Delta - grad Phi grad Phi^T / Delta^3. Clamped parameters (the
    point-edge and point-point cases) are simply held fixed, which is exact away from the
    switching surfaces. Writes ``grad`` (12,) and ``hess`` (12, 12); returns Delta.
    """
    x1 = x[0:3]
    x2 = x[3:6]
    x3 = x[6:9]
    x4 = x[9:12]
    s, t, free_s, free_t = segment_params(x1, x2, x3, x4)
    coef = np.array([1.0 - s, s, -(1.0 - t), -t])
    w = coef[0] * x1 + coef[1] * x2 + coef[2] * x3 + coef[3] * x4
    dist = np.sqrt(w @ w)
    e1 = x2 - x1
    e2 = x4 - x3
    # phi_x = A^T w ; phi_xx = (coef coef^T) kron I3
    gphi = np.zeros(12)
    for k in range(4):
        for m in range(3):
            gphi[3 * k + m] = coef[k] * w[m]
    H = np.zeros((12, 12))
    for k in range(4):
        for l in range(4):
            for m in range(3):
                H[3 * k + m, 3 * l + m] = coef[k] * coef[l]
    nfree = int(free_s) + int(free_t)
    if nfree > 0:
        # columns of phi_xu for the free parameters and the matrix phi_uu
        B = np.zeros((12, 2))
        U = np.zeros((2, 2))
        col = 0
        idx_s = -1
        idx_t = -1
        if free_s:
            idx_s = col
            col += 1
        if free_t:
            idx_t = col
            col += 1
        if free_s:
            # d/dx (w . e1) = A^T e1 + [-w, w, 0, 0]
            for k in range(4):
                for m in range(3):
                    B[3 * k + m, idx_s] = coef[k] * e1[m]
            for m in range(3):
                B[m, idx_s] -= w[m]
                B[3 + m, idx_s] += w[m]
            U[idx_s, idx_s] = e1 @ e1
        if free_t:
            # d/dx (-w . e2) = -A^T e2 + [0, 0, w, -w]
            for k in range(4):
                for m in range(3):
                    B[3 * k + m, idx_t] = -coef[k] * e2[m]
            for m in range(3):
                B[6 + m, idx_t] += w[m]
                B[9 + m, idx_t] -= w[m]
            U[idx_t, idx_t] = e2 @ e2
        if free_s and free_t:
            U[0, 1] = -(e1 @ e2)
            U[1, 0] = U[0, 1]
        if nfree == 1:
            inv = 1.0 / U[0, 0]
            for i in range(12):
                for j in range(12):
                    H[i, j] -= B[i, 0] * inv * B[j, 0]
        else:
            det = U[0, 0] * U[1, 1] - U[0, 1] * U[1, 0]
            i00 = U[1, 1] / det
            i11 = U[0, 0] / det
            i01 = -U[0, 1] / det
            for i in range(12):
                bi0 = B[i, 0]
                bi1 = B[i, 1]
                for j in range(12):
                    H[i, j] -= bi0 * (i00 * B[j, 0] + i01 * B[j, 1]) + bi1 * (
                        i01 * B[j, 0] + i11 * B[j, 1]
                    )
    inv_d = 1.0 / dist
    for i in range(12):
        grad[i] = gphi[i] * inv_d
    inv_d3 = inv_d * inv_d * inv_d
    for i in range(12):
        for j in range(12):
            hess[i, j] = H[i, j] * inv_d - gphi[i] * gphi[j] * inv_d3
    return dist


@njit(cache=True)
def _softplus(z):
    if z > 30.0:
        return z
    if z < -30.0:
        return np.exp(z)
    return np.log1p(np.exp(z))


@njit(cache=True)
def _sigmoid(z):
    if z >= 0.0:
        return 1.0 / (1.0 + np.exp(-z))
    ez = np.exp(z)
    return ez / (1.0 + ez)


@njit(cache=True)
def penalty_derivs(gap_arg, sharpness, stiffness):
    """Squared-softplus penalty of IMC on z = k (2h - Delta) (coated-rod eq. 10 inside).

    .. math:: E = K_c \\left[\\frac{\\log(1 + e^{k(2h-\\Delta)})}{k}\\right]^2

    ``gap_arg`` = 2h - Delta [m]; returns E, dE/dDelta, d2E/dDelta2.
    """
    z = sharpness * gap_arg
    sp = _softplus(z) / sharpness
    sg = _sigmoid(z)
    e = stiffness * sp * sp
    de = -2.0 * stiffness * sp * sg
    d2e = 2.0 * stiffness * (sg * sg + sp * sg * (1.0 - sg) * sharpness)
    return e, de, d2e


@njit(cache=True)
def rodrod_assemble(
    pos,
    pos_old,
    dt,
    pairs,
    edge_nodes,
    node_dofs,
    radius_edge,
    sharpness,
    stiffness,
    mu,
    fric_k,
    fric_c,
    vel_eps,
    force,
    rows,
    cols,
    vals,
    contact_force,
    normal_derivative=False,
):
    """Contact + friction forces and Jacobian blocks of all candidate edge pairs.

    For pair p = (i, j): force (12,) = -dE/dx (IMC eq. for the penalty); friction of
    coated-rod eqs. (11)-(12): F_n = force on edge i, n = F_n/|F_n|,
    v_rel = (v_i + v_i+1 - v_j - v_j+1)/2 with v = (x - x_old)/dt, v_T = (I - n n^T) v_rel,
    gamma = 1/(1 + exp(-k(|v_T| - c))), F_fr = -gamma mu |F_n| v_T/|v_T| (capped at mu|F_n|
    by gamma <= 1), distributed (+1/2, +1/2, -1/2, -1/2).

    Jacobian: the exact Hessian of the penalty; for friction the derivative through the
    velocity only (n and |F_n| lagged at the current iterate, i.e. their dependence on q is
    left out of dF/dq). ``rows/cols/vals`` have room for 144 * 2 entries per pair (penalty and
    friction blocks); unused entries are written with value 0. ``contact_force`` (n_pairs,)
    receives |F_n|. Returns the total penalty energy.
    """
    npairs = pairs.shape[0]
    x = np.empty(12)
    grad = np.empty(12)
    hess = np.empty((12, 12))
    dofs = np.empty(12, dtype=np.int64)
    energy = 0.0
    for p in range(npairs):
        ei = pairs[p, 0]
        ej = pairs[p, 1]
        nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
        for k in range(4):
            for m in range(3):
                x[3 * k + m] = pos[nodes[k], m]
                dofs[3 * k + m] = node_dofs[nodes[k], m]
        base = p * 288
        two_h = radius_edge[ei] + radius_edge[ej]
        contact_force[p] = 0.0
        # far pairs (penalty below e^-40 of its scale): skip before the Hessian
        if sharpness * (two_h - edge_distance(x)) < -40.0:
            for a in range(288):
                rows[base + a] = dofs[0]
                cols[base + a] = dofs[0]
                vals[base + a] = 0.0
            continue
        dist = edge_distance_hessian(x, grad, hess)
        e, de, d2e = penalty_derivs(two_h - dist, sharpness, stiffness)
        energy += e
        # force = -dE/dx = -de * grad ; dF/dx = -(d2e grad grad^T + de hess)
        for a in range(12):
            force[dofs[a]] -= de * grad[a]
        for a in range(12):
            for b in range(12):
                k = base + 12 * a + b
                rows[k] = dofs[a]
                cols[k] = dofs[b]
                vals[k] = -(d2e * grad[a] * grad[b] + de * hess[a, b])
        # normal force on edge i (sum over its two nodes)
        fn = np.zeros(3)
        for m in range(3):
            fn[m] = -de * (grad[m] + grad[3 + m])
        fnorm = np.sqrt(fn @ fn)
        contact_force[p] = fnorm
        base2 = base + 144
        for a in range(144):
            rows[base2 + a] = dofs[0]
            cols[base2 + a] = dofs[0]
            vals[base2 + a] = 0.0
        if mu <= 0.0 or fnorm <= 0.0:
            continue
        n = fn / fnorm
        vrel = np.zeros(3)
        for m in range(3):
            vi = 0.5 * (pos[nodes[0], m] - pos_old[nodes[0], m])
            vi += 0.5 * (pos[nodes[1], m] - pos_old[nodes[1], m])
            vj = 0.5 * (pos[nodes[2], m] - pos_old[nodes[2], m])
            vj += 0.5 * (pos[nodes[3], m] - pos_old[nodes[3], m])
            vrel[m] = (vi - vj) / dt
        vt = vrel - (vrel @ n) * n
        vtn_raw = np.sqrt(vt @ vt)
        vtn = np.sqrt(vtn_raw * vtn_raw + vel_eps * vel_eps)
        gam = _sigmoid(fric_k * (vtn_raw - fric_c))
        dgam = fric_k * gam * (1.0 - gam)
        ffr = -gam * mu * fnorm * vt / vtn
        sgn = (0.5, 0.5, -0.5, -0.5)
        for k in range(4):
            for m in range(3):
                force[dofs[3 * k + m]] += sgn[k] * ffr[m]
        # dF_fr/dv_rel = -mu |Fn| [gamma/vtn (I - vt vt^T/vtn^2) + gamma' vt vt^T/(vtn vtn_raw)] P
        P = np.eye(3) - np.outer(n, n)
        Dm = np.zeros((3, 3))
        for a in range(3):
            for b in range(3):
                Dm[a, b] = gam / vtn * ((1.0 if a == b else 0.0) - vt[a] * vt[b] / (vtn * vtn))
                if vtn_raw > 0.0:
                    Dm[a, b] += dgam * vt[a] * vt[b] / (vtn * vtn_raw)
        Dm = -mu * fnorm * (Dm @ P)
        # with normal_derivative: also the dependence of |F_n| on q (the normal stays
        # lagged), d|F_n|/dx = (d2e/de) |F_n| grad Delta, which makes dF/dq unsymmetric
        cn = d2e / de if (normal_derivative and de != 0.0) else 0.0
        for k in range(4):
            for l in range(4):
                scale = sgn[k] * sgn[l] / dt
                for a in range(3):
                    for b in range(3):
                        kk = base2 + 12 * (3 * k + a) + (3 * l + b)
                        rows[kk] = dofs[3 * k + a]
                        cols[kk] = dofs[3 * l + b]
                        vals[kk] = scale * Dm[a, b] + sgn[k] * ffr[a] * cn * grad[3 * l + b]
    return energy


@njit(cache=True)
def rodrod_energy(pos, pairs, edge_nodes, radius_edge, sharpness, stiffness):
    """Total penalty energy of the candidate pairs (IMC squared softplus)."""
    x = np.empty(12)
    energy = 0.0
    for p in range(pairs.shape[0]):
        ei = pairs[p, 0]
        ej = pairs[p, 1]
        nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
        for k in range(4):
            for m in range(3):
                x[3 * k + m] = pos[nodes[k], m]
        dist = edge_distance(x)
        e, de, d2e = penalty_derivs(radius_edge[ei] + radius_edge[ej] - dist, sharpness, stiffness)
        energy += e
    return energy
