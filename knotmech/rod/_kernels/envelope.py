"""LU factorisation without pivoting restricted to the envelope (profile) of a band matrix.

Private module. The reordered Newton matrix of a rod system with contacts is structurally
symmetric, and after a reverse Cuthill-McKee ordering its rows hold on average far fewer
entries left of the diagonal than the half bandwidth: LU without pivoting keeps all fill
inside the envelope {(i, j): first[max(i, j)] <= min(i, j)} (George & Liu, "Computer
solution of large sparse positive definite systems", Prentice-Hall 1981, ch. 4), so its
cost is the sum of the squared envelope widths instead of n kd^2 (kd^2 to 2 kd^2 per row
for the pivoted band LU, LAPACK dgbtrf). Without pivoting the factorisation can meet a
small pivot or element growth: :func:`env_factor` reports a pivot that fell below a fraction
of its diagonal entry, and the caller checks the backward error of each solve
(:func:`band_residual`), falling back to the pivoted LU when either check fails.

Storage: ``ab`` (2 kd + 1, n), Fortran order, A[i, j] at ``ab[kd + i - j, j]``; L (unit
lower) and U overwrite it.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _widen(first, i, j):
    """Widen the envelope of row max(i, j) to column min(i, j) (skipped if either is < 0)."""
    if i < 0 or j < 0:
        return
    if i < j:
        i, j = j, i
    if j < first[i]:
        first[i] = j


@njit(cache=True)
def pattern_first(rows, cols, first):
    """Widen the envelope to the entries (rows[k], cols[k]) (skipped if an index is negative):
    first[i] = the smallest j <= i with A[i, j] or A[j, i] structurally non-zero (start
    from first[i] = i)."""
    for k in range(rows.shape[0]):
        _widen(first, rows[k], cols[k])


@njit(cache=True)
def pattern_first_mapped(rows, cols, gmap, first):
    """:func:`pattern_first` of the entries (gmap[rows[k]], gmap[cols[k]])."""
    for k in range(rows.shape[0]):
        _widen(first, gmap[rows[k]], gmap[cols[k]])


@njit(cache=True)
def env_last(first, last):
    """last[k] = max(k, max{i : first[i] <= k}): rows (and, by symmetry, columns) beyond k
    that the elimination of k touches."""
    n = first.shape[0]
    for k in range(n):
        last[k] = k
    for i in range(n):
        if last[first[i]] < i:
            last[first[i]] = i
    for k in range(1, n):
        if last[k] < last[k - 1]:
            last[k] = last[k - 1]


@njit(cache=True)
def copy_band(ab, out):
    """out[...] = ab; returns the largest column sum of |A| (its 1-norm)."""
    norm = 0.0
    for j in range(ab.shape[1]):
        c = 0.0
        for r in range(ab.shape[0]):
            v = ab[r, j]
            out[r, j] = v
            c += abs(v)
        norm = max(norm, c)
    return norm


@njit(cache=True, fastmath=True)
def env_factor(ab, kd, last, orig, rel_tiny, lcol):
    """In-place LU without pivoting (Doolittle, right-looking) inside the envelope.

    ``lcol`` (>= kd,) work array (the multipliers of the current column, kept apart so that
    the column updates vectorise). Returns 0, or k + 1 if the k-th pivot fell to
    ``|u_kk| <= rel_tiny |a_kk|`` (``orig`` the unfactored matrix; factorisation abandoned,
    ``ab`` is then garbage).

    Unsigned indices (see :func:`env_solve`): with signed ones the negative-index tests
    kept the column updates scalar (4.4x slower on the overhand benchmark's Jacobians);
    each entry gets the same fused multiply-subtracts in the same order, the same bits."""
    n = np.uint64(ab.shape[1])
    ukd = np.uint64(kd)
    one = np.uint64(1)
    for k in range(n):
        p = ab[ukd, k]
        if not (abs(p) > rel_tiny * abs(orig[ukd, k])):
            return np.int64(k) + 1
        inv = 1.0 / p
        lk = np.uint64(last[k])
        m = lk - k
        for t in range(m):
            v = ab[ukd + one + t, k] * inv
            ab[ukd + one + t, k] = v
            lcol[t] = v
        for j in range(k + one, lk + one):
            ukj = ab[ukd + k - j, j]
            if ukj != 0.0:
                # indexed in place: a column view (ab[:, j]) per update cost a fifth of
                # the factorisation; the arithmetic is the same
                base = ukd + k + one - j
                for t in range(m):
                    ab[base + t, j] -= lcol[t] * ukj
    return np.int64(0)


@njit(cache=True)
def env_work(last):
    """sum_k (last[k] - k)^2: the multiply-adds of :func:`env_factor` (at most)."""
    w = 0
    for k in range(last.shape[0]):
        d = last[k] - k
        w += d * d
    return w


@njit(cache=True)
def env_solve(ab, kd, first, last, b):
    """Solve L U x = b in place with the factors of :func:`env_factor` (L column k has rows
    up to last[k], U column k rows from first[k]).

    The indices are unsigned (``np.uint64``, all of them: numba turns a mix of signed and
    unsigned integers into floats): a signed index costs a negative-index test per access,
    which keeps LLVM from vectorising the column updates (3.7x slower on the overhand
    benchmark's factors); each b[i] gets the same updates in the same order, the same
    bits."""
    n = np.uint64(ab.shape[1])
    ukd = np.uint64(kd)
    one = np.uint64(1)
    for k in range(n):
        bk = b[k]
        if bk != 0.0:
            for i in range(k + one, np.uint64(last[k]) + one):
                b[i] -= ab[ukd + i - k, k] * bk
    for kk in range(n):
        k = n - one - kk
        b[k] /= ab[ukd, k]
        bk = b[k]
        if bk != 0.0:
            for i in range(np.uint64(first[k]), k):
                b[i] -= ab[ukd + i - k, k] * bk


@njit(cache=True)
def band_residual(ab, kd, x, b, anorm, r):
    """Normwise backward error |A x - b|_inf / (|A| |x|_inf + |b|_inf) of a solution x of the
    band system A (layout above, unfactored) x = b; ``anorm`` a norm of A, ``r`` (n,) work.
    (Unsigned indices in the product, as in :func:`env_solve`: the same sums.)"""
    n = ab.shape[1]
    for i in range(n):
        r[i] = -b[i]
    un = np.uint64(n)
    ukd = np.uint64(kd)
    for j in range(un):
        xj = x[j]
        i0 = j - ukd if j > ukd else np.uint64(0)
        i1 = min(un, j + ukd + np.uint64(1))
        for i in range(i0, i1):
            r[i] += ab[ukd + i - j, j] * xj
    num = 0.0
    xmax = 0.0
    bmax = 0.0
    for i in range(n):
        num = max(num, abs(r[i]))
        xmax = max(xmax, abs(x[i]))
        bmax = max(bmax, abs(b[i]))
    den = anorm * xmax + bmax
    return num / den if den > 0.0 else 0.0
