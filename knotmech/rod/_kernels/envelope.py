"""LU factorisation without pivoting restricted to the envelope (profile) of a band matrix.

Private module. The reordered Newton matrix of a rod system with contacts is structurally
symmetric, and after a reverse Cuthill-McKee ordering its rows hold on average far fewer
entries left of the diagonal than the half bandwidth: LU without pivoting keeps all fill
inside the envelope {(i, j): first[max(i, j)] <= min(i, j)} (George & Liu, "Computer
solution of large sparse positive definite systems", Prentice-Hall 1981, ch. 4), so its
cost is the sum of the squared envelope widths instead of n kd^2 (kd^2 to 2 kd^2 per row
for the pivoted band LU, LAPACK dgbtrf). Without pivoting the factorisation can meet a
small pivot or element growth: :func:`env_factor` reports a pivot below ``tiny`` and the
caller checks the backward error of each solve (:func:`band_residual`), falling back to the
pivoted LU when either fails.

Storage: ``ab`` (2 kd + 1, n), Fortran order, A[i, j] at ``ab[kd + i - j, j]``; L (unit
lower) and U overwrite it.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def env_first(ab, kd, first):
    """first[i] = the smallest j <= i with A[i, j] != 0 or A[j, i] != 0 (row/column profile
    of the structurally symmetrised matrix)."""
    n = ab.shape[1]
    for i in range(n):
        f = i
        for j in range(max(0, i - kd), i):
            if ab[kd + i - j, j] != 0.0 or ab[kd + j - i, i] != 0.0:
                f = j
                break
        first[i] = f


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


@njit(cache=True, fastmath=True)
def env_factor(ab, kd, last, tiny):
    """In-place LU without pivoting (Doolittle, right-looking) inside the envelope.

    Returns 0, or k + 1 if the k-th pivot fell to ``|u_kk| <= tiny[k]`` (factorisation
    abandoned; ``ab`` is then garbage)."""
    n = ab.shape[1]
    for k in range(n):
        p = ab[kd, k]
        if not (abs(p) > tiny[k]):
            return k + 1
        inv = 1.0 / p
        lk = last[k]
        for i in range(k + 1, lk + 1):
            ab[kd + i - k, k] *= inv
        for j in range(k + 1, lk + 1):
            ukj = ab[kd + k - j, j]
            if ukj != 0.0:
                for i in range(k + 1, lk + 1):
                    ab[kd + i - j, j] -= ab[kd + i - k, k] * ukj
    return 0


@njit(cache=True)
def env_solve(ab, kd, last, b):
    """Solve L U x = b in place with the factors of :func:`env_factor`."""
    n = ab.shape[1]
    for k in range(n):
        bk = b[k]
        if bk != 0.0:
            for i in range(k + 1, last[k] + 1):
                b[i] -= ab[kd + i - k, k] * bk
    for k in range(n - 1, -1, -1):
        b[k] /= ab[kd, k]
        bk = b[k]
        for i in range(max(0, k - kd), k):
            b[i] -= ab[kd + i - k, k] * bk


@njit(cache=True)
def band_residual(ab, kd, x, b):
    """max_i |(A x - b)_i| / max_i (sum_j |A_ij x_j| + |b_i|): the componentwise backward
    error of a solution x of the band system A (layout above, unfactored) x = b."""
    n = ab.shape[1]
    r = np.zeros(n)
    s = np.zeros(n)
    for j in range(n):
        xj = x[j]
        for i in range(max(0, j - kd), min(n, j + kd + 1)):
            v = ab[kd + i - j, j] * xj
            r[i] += v
            s[i] += abs(v)
    num = 0.0
    den = 0.0
    for i in range(n):
        num = max(num, abs(r[i] - b[i]))
        den = max(den, s[i] + abs(b[i]))
    return num / den if den > 0.0 else 0.0
