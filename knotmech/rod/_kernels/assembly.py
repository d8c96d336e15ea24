"""Scatter of local Hessians into LAPACK band storage or COO triplets.

Band storage (LAPACK dgbsv layout, Fortran order): A[i, j] lives in
``ab[kl + ku + i - j, j]`` with kl = ku = 10 for the DER dof ordering (a stencil spans 11
contiguous dofs, so |i - j| <= 10). Edge-space Hessians H8 of the variables
y = (e, theta^e, f, theta^f) map to the 11 stencil dofs z = (x_{i-1}, theta^e, x_i,
theta^f, x_{i+1}) by H11 = P^T H8 P, e = x_i - x_{i-1}, f = x_{i+1} - x_i.
"""

import numpy as np
from numba import njit

BAND = 10  # half bandwidth kl = ku of a DER system matrix


@njit(cache=True, inline="always")
def _p_entries(a):
    """Edge-space (index, sign) pairs of local stencil dof ``a`` (second pair unused if n == 1)."""
    if a < 3:
        return 1, a, -1.0, 0, 0.0
    if a == 3:
        return 1, 3, 1.0, 0, 0.0
    if a < 7:
        return 2, a - 4, 1.0, a, -1.0
    if a == 7:
        return 1, 7, 1.0, 0, 0.0
    return 1, a - 4, 1.0, 0, 0.0


@njit(cache=True)
def stencil_local(h8, h11):
    """Write H11 = P^T H8 P (11x11) for one stencil."""
    for a in range(11):
        na, ia, sa, ja, ta = _p_entries(a)
        for b in range(11):
            nb, ib, sb, jb, tb = _p_entries(b)
            v = sa * sb * h8[ia, ib]
            if nb == 2:
                v += sa * tb * h8[ia, jb]
            if na == 2:
                v += ta * sb * h8[ja, ib]
                if nb == 2:
                    v += ta * tb * h8[ja, jb]
            h11[a, b] = v


# P as two (index, sign) pairs per stencil dof (sign 0: unused), for the fast product below
_P_IDX1 = np.array([0, 1, 2, 3, 0, 1, 2, 7, 4, 5, 6], dtype=np.int64)
_P_SGN1 = np.array([-1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0])
_P_IDX2 = np.array([0, 0, 0, 0, 4, 5, 6, 0, 0, 0, 0], dtype=np.int64)
_P_SGN2 = np.array([0.0, 0.0, 0.0, 0.0, -1.0, -1.0, -1.0, 0.0, 0.0, 0.0, 0.0])


@njit(cache=True, fastmath=True)
def _stencil_upper(h8, t, h11, i1, s1, i2, s2):
    """Upper triangle (a <= b) of H11 = P^T H8 P through T = H8 P (8 x 11), branch-free."""
    for b in range(11):
        for y in range(8):
            t[y, b] = s1[b] * h8[y, i1[b]] + s2[b] * h8[y, i2[b]]
    for b in range(11):
        for a in range(b + 1):
            h11[a, b] = s1[a] * t[i1[a], b] + s2[a] * t[i2[a], b]


@njit(cache=True, fastmath=True)
def band_add_hessians(edge_dof0, stencil_edge, hess_s, hess8, ab, off):
    """Add the stretching (6x6 per edge) and bending+twisting (8x8 edge-space per stencil)
    Hessians into the UPPER triangle of a band matrix, A[i, j] at ab[off + i - j, j]:
    off = 20 for the dgbsv layout (31, n), off = 10 for the dpbsv upper layout (11, n).
    The matrix is symmetric; see :func:`band_mirror` for the lower part."""
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        for b in range(6):
            gb = d + b + (b >= 3)
            for a in range(b + 1):
                ga = d + a + (a >= 3)
                ab[off + ga - gb, gb] += hess_s[k, a, b]
    h11 = np.empty((11, 11))
    t = np.empty((8, 11))
    i1, s1, i2, s2 = _P_IDX1, _P_SGN1, _P_IDX2, _P_SGN2
    for s in range(stencil_edge.shape[0]):
        d = edge_dof0[stencil_edge[s] - 1]
        _stencil_upper(hess8[s], t, h11, i1, s1, i2, s2)
        for b in range(11):
            for a in range(b + 1):
                ab[off + a - b, d + b] += h11[a, b]


@njit(cache=True)
def band_mirror(ab):
    """Copy the upper triangle of a symmetric band matrix into its lower triangle."""
    off = 2 * BAND
    n = ab.shape[1]
    for j in range(n):
        for i in range(j + 1, min(n, j + BAND + 1)):
            ab[off + i - j, j] = ab[off + j - i, i]


@njit(cache=True)
def coo_hessians(edge_dof0, stencil_edge, hess_s, hess8, rows, cols, vals):
    """Write the same Hessians as COO triplets (36 per edge then 121 per stencil)."""
    p = 0
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        for a in range(6):
            for b in range(6):
                rows[p] = d + a + (a >= 3)
                cols[p] = d + b + (b >= 3)
                vals[p] = hess_s[k, a, b]
                p += 1
    h11 = np.empty((11, 11))
    for s in range(stencil_edge.shape[0]):
        d = edge_dof0[stencil_edge[s] - 1]
        stencil_local(hess8[s], h11)
        for a in range(11):
            for b in range(11):
                rows[p] = d + a
                cols[p] = d + b
                vals[p] = h11[a, b]
                p += 1


@njit(cache=True)
def band_to_dense(ab, n):
    """Dense copy of a band matrix (tests only; call band_mirror first)."""
    off = 2 * BAND
    out = np.zeros((n, n))
    for j in range(n):
        for i in range(max(0, j - BAND), min(n, j + BAND + 1)):
            out[i, j] = ab[off + i - j, j]
    return out


@njit(cache=True)
def band_add_diagonal(diag, ab, off):
    """ab[diagonal] += diag (A[i, j] at ab[off + i - j, j])."""
    for j in range(diag.shape[0]):
        ab[off, j] += diag[j]


@njit(cache=True)
def band_constrain(dofs, ab, off):
    """Replace row and column of each constrained dof by those of the identity, in the
    upper triangle of a symmetric band matrix (A[i, j] at ab[off + i - j, j], i <= j)."""
    n = ab.shape[1]
    for d in dofs:
        for j in range(d, min(n, d + BAND + 1)):
            ab[off + d - j, j] = 0.0  # row d, right of the diagonal
        for i in range(max(0, d - BAND), d):
            ab[off + i - d, d] = 0.0  # column d, above the diagonal
        ab[off, d] = 1.0


@njit(cache=True)
def upper_to_general(pb, gb):
    """Full dgbsv-layout matrix gb (31, n) from the upper band pb (11, n) of a symmetric one."""
    n = pb.shape[1]
    gb[:, :] = 0.0
    for j in range(n):
        for i in range(max(0, j - BAND), j + 1):
            v = pb[BAND + i - j, j]
            gb[2 * BAND + i - j, j] = v
            gb[2 * BAND + j - i, i] = v


@njit(cache=True, fastmath=True)
def residual_and_scales(mass, dt, q, q_old, v_old, grad, fext, is_theta, free, f):
    """Implicit-Euler residual f = M/dt^2 (q - q_old - dt v_old) + grad - fext (coated-rod
    paper eq. (7)) and its size: returns (inertial potential 1/2 |q - q_pred|_M^2 / dt^2,
    force scale on free positions, torque scale on free angles, max |f| on free positions,
    max |f| on free angles); scales are max(|inertia|, |grad|, |fext|)."""
    c = 1.0 / (dt * dt)
    pot = 0.0
    sx = 0.0
    st = 0.0
    rx = 0.0
    rt = 0.0
    for i in range(q.shape[0]):
        dev = q[i] - q_old[i] - dt * v_old[i]
        inert = mass[i] * c * dev
        pot += 0.5 * inert * dev
        fi = inert + grad[i] - fext[i]
        f[i] = fi
        if free[i]:
            sc = max(abs(inert), abs(grad[i]), abs(fext[i]))
            if is_theta[i]:
                st = max(st, sc)
                rt = max(rt, abs(fi))
            else:
                sx = max(sx, sc)
                rx = max(rx, abs(fi))
    return pot, sx, st, rx, rt


@njit(cache=True)
def max_abs_strain(lengths, rest_length):
    """max_k | |e^k| / |ebar^k| - 1 | (the stretching force scale over EA)."""
    out = 0.0
    for k in range(lengths.shape[0]):
        out = max(out, abs(lengths[k] / rest_length[k] - 1.0))
    return out


@njit(cache=True)
def band_add_hessians_mapped(edge_dof0, stencil_edge, hess_s, hess8, gmap, off, ab):
    """Add the full elastic Hessian (stretching 6x6 per edge, then bending+twisting
    H11 = P^T H8 P per stencil) into a general band matrix, row/column i of the system
    going to ``gmap[i]`` (skipped if negative): A[gi, gj] at ``ab[off + gi - gj, gj]``.
    The same entries in the same order as :func:`coo_hessians` + :func:`band_scatter_mapped`
    through ``gmap``, without the COO temporaries."""
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        for a in range(6):
            ga = gmap[d + a + (a >= 3)]
            if ga < 0:
                continue
            for b in range(6):
                gb = gmap[d + b + (b >= 3)]
                if gb >= 0:
                    ab[off + ga - gb, gb] += hess_s[k, a, b]
    h11 = np.empty((11, 11))
    for s in range(stencil_edge.shape[0]):
        d = edge_dof0[stencil_edge[s] - 1]
        stencil_local(hess8[s], h11)
        for a in range(11):
            ga = gmap[d + a]
            if ga < 0:
                continue
            for b in range(11):
                gb = gmap[d + b]
                if gb >= 0:
                    ab[off + ga - gb, gb] += h11[a, b]


@njit(cache=True)
def band_scatter_mapped(rows, cols, vals, gmap, scale, off, ab):
    """Add ``scale * vals`` at (gmap[rows], gmap[cols]) of a general band matrix (entry
    (i, j) at ``ab[off + i - j, j]``); entries with a negative mapped index are skipped."""
    for k in range(rows.shape[0]):
        i = gmap[rows[k]]
        j = gmap[cols[k]]
        if i < 0 or j < 0:
            continue
        ab[off + i - j, j] += scale * vals[k]


@njit(cache=True)
def max_band_mapped(rows, cols, gmap):
    """Largest |gmap[i] - gmap[j]| over the entries with both mapped indices >= 0."""
    kd = 0
    for k in range(rows.shape[0]):
        i = gmap[rows[k]]
        j = gmap[cols[k]]
        if i >= 0 and j >= 0:
            d = i - j if i > j else j - i
            if d > kd:
                kd = d
    return kd


@njit(cache=True)
def masked_norm(f, mask):
    """Euclidean norm of f over the entries where ``mask`` is True."""
    s = 0.0
    for i in range(f.shape[0]):
        if mask[i]:
            s += f[i] * f[i]
    return np.sqrt(s)


@njit(cache=True)
def max_abs_split(dq, alpha, mask_a, mask_b):
    """(max |alpha dq| over mask_a, over mask_b) (0 for an empty mask)."""
    a = 0.0
    b = 0.0
    for i in range(dq.shape[0]):
        v = abs(alpha * dq[i])
        if mask_a[i]:
            a = max(a, v)
        elif mask_b[i]:
            b = max(b, v)
    return a, b


@njit(cache=True)
def all_finite(a):
    """True when every entry of the 1-D array ``a`` is finite."""
    for i in range(a.shape[0]):
        if not np.isfinite(a[i]):
            return False
    return True


@njit(cache=True)
def worst_strain(q, node_dofs, edge_nodes, rest_length):
    """(edge, strain |e^k| / |ebar^k| - 1) of the edge whose |strain| is largest at ``q``
    (NaN strains skipped; (0, strain[0]) when no strain is finite). The same arithmetic,
    and so the same bits, as numpy's row norm of the edge vectors."""
    n = edge_nodes.shape[0]
    strain = np.empty(n)
    k_best, v_best, seen, finite = 0, 0.0, False, False
    for k in range(n):
        a, b = edge_nodes[k, 0], edge_nodes[k, 1]
        s = 0.0
        for m in range(3):
            d = q[node_dofs[b, m]] - q[node_dofs[a, m]]
            s += d * d
        e = np.sqrt(s) / rest_length[k] - 1.0
        strain[k] = e
        finite = finite or np.isfinite(e)
        v = abs(e)
        if v == v and (not seen or v > v_best):
            k_best, v_best, seen = k, v, True
    if not finite:
        k_best = 0
    return k_best, strain[k_best] if n else 0.0


@njit(cache=True)
def permute_in(rhs, free_idx, gmap, b):
    """b[gmap[i]] = rhs[i] for the free dofs i = ``free_idx`` (the right-hand side in the
    order of the reordered free system; numpy's two fancy-indexed copies in one pass)."""
    for k in range(free_idx.shape[0]):
        i = free_idx[k]
        b[gmap[i]] = rhs[i]


@njit(cache=True)
def permute_out(y, free_idx, gmap, x):
    """x = 0, then x[i] = y[gmap[i]] for the free dofs i = ``free_idx`` (the solution back
    in dof order, zero on the constrained dofs)."""
    x[:] = 0.0
    for k in range(free_idx.shape[0]):
        i = free_idx[k]
        x[i] = y[gmap[i]]


@njit(cache=True)
def _count_mapped(rows, cols, fmap, count):
    for k in range(rows.shape[0]):
        i = fmap[rows[k]]
        j = fmap[cols[k]]
        if i >= 0 and j >= 0:
            count[i + 1] += 1
            count[j + 1] += 1


@njit(cache=True)
def _fill_mapped(rows, cols, fmap, fill, idx):
    for k in range(rows.shape[0]):
        i = fmap[rows[k]]
        j = fmap[cols[k]]
        if i >= 0 and j >= 0:
            idx[fill[i]] = j
            fill[i] += 1
            idx[fill[j]] = i
            fill[j] += 1


@njit(cache=True)
def pattern_csr(rows_a, cols_a, rows_b, cols_b, fmap, n):
    """Sparsity pattern of A + A^T, A the matrix of the entries (fmap[r], fmap[c]) of two
    (rows, cols) lists (those with both mapped indices >= 0), as CSR arrays (indptr
    (n + 1,), indices): column indices sorted and unique within each row, i.e. the
    structure of scipy's canonical CSR matrix ``A + A.T`` (which
    ``reverse_cuthill_mckee(A, symmetric_mode=False)`` orders). Returns (indptr, indices)."""
    count = np.zeros(n + 1, dtype=np.int64)
    _count_mapped(rows_a, cols_a, fmap, count)
    _count_mapped(rows_b, cols_b, fmap, count)
    for i in range(n):
        count[i + 1] += count[i]
    fill = count[:n].copy()
    idx = np.empty(count[n], dtype=np.int64)
    _fill_mapped(rows_a, cols_a, fmap, fill, idx)
    _fill_mapped(rows_b, cols_b, fmap, fill, idx)
    indptr = np.zeros(n + 1, dtype=np.int64)
    out = np.empty(count[n], dtype=np.int64)
    seen = np.full(n, -1, dtype=np.int64)  # seen[j] == i: j already in row i
    m = 0
    for i in range(n):
        start = m
        for k in range(count[i], count[i + 1]):
            j = idx[k]
            if seen[j] == i:
                continue
            seen[j] = i
            # insertion into the sorted run out[start:m] (a few tens of entries per row)
            pos = m
            while pos > start and out[pos - 1] > j:
                out[pos] = out[pos - 1]
                pos -= 1
            out[pos] = j
            m += 1
        indptr[i + 1] = m
    return indptr, out[:m]
