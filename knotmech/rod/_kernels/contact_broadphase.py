"""Broad phase for edge-edge contact: sort-and-sweep of edge bounding boxes.

Private module. Sorting the boxes by their lower x bound and sweeping an active list costs
O(N log N + K) for N edges and K overlapping candidate pairs (Baraff 1992, "Dynamic
simulation of non-penetrating rigid bodies", ch. 4: sweep and prune).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def edge_boxes(pos, edge_nodes, inflate, lo, hi):
    """Axis-aligned boxes of the edges, each grown by ``inflate[e]`` [m] on every side."""
    for e in range(edge_nodes.shape[0]):
        a = edge_nodes[e, 0]
        b = edge_nodes[e, 1]
        for m in range(3):
            u = pos[a, m]
            v = pos[b, m]
            lo[e, m] = min(u, v) - inflate[e]
            hi[e, m] = max(u, v) + inflate[e]


@njit(cache=True)
def _excluded(i, j, edge_nodes, edge_rod, exclusion):
    """Edges ``i``, ``j`` never paired: of the same rod and at most ``exclusion`` indices
    apart, or sharing a node. (Written without ``abs`` and early returns: this form runs
    several times faster inside :func:`sweep_pairs`, the same truth value.)"""
    d = i - j
    near = edge_rod[i] == edge_rod[j] and d <= exclusion and -d <= exclusion
    a0 = edge_nodes[i, 0]
    a1 = edge_nodes[i, 1]
    b0 = edge_nodes[j, 0]
    b1 = edge_nodes[j, 1]
    return near or a0 == b0 or a0 == b1 or a1 == b0 or a1 == b1


@njit(cache=True)
def sweep_pairs(lo, hi, edge_nodes, edge_rod, exclusion):
    """Candidate pairs (i < j) whose boxes overlap, excluding neighbours along a rod."""
    n = lo.shape[0]
    order = np.argsort(lo[:, 0])
    cap = 8 * n + 16
    out = np.empty((cap, 2), dtype=np.int64)
    cnt = 0
    active = np.empty(n, dtype=np.int64)
    nact = 0
    for oi in range(n):
        i = order[oi]
        # drop boxes that end before this one starts
        k = 0
        for a in range(nact):
            j = active[a]
            if hi[j, 0] >= lo[i, 0]:
                active[k] = j
                k += 1
        nact = k
        for a in range(nact):
            j = active[a]
            if lo[i, 1] > hi[j, 1] or lo[j, 1] > hi[i, 1]:
                continue
            if lo[i, 2] > hi[j, 2] or lo[j, 2] > hi[i, 2]:
                continue
            if _excluded(i, j, edge_nodes, edge_rod, exclusion):
                continue
            if cnt == out.shape[0]:
                bigger = np.empty((2 * out.shape[0], 2), dtype=np.int64)
                bigger[:cnt] = out[:cnt]
                out = bigger
            out[cnt, 0] = min(i, j)
            out[cnt, 1] = max(i, j)
            cnt += 1
        active[nact] = i
        nact += 1
    return out[:cnt]


@njit(cache=True)
def brute_pairs(lo, hi, edge_nodes, edge_rod, exclusion):
    """Reference O(N^2) version of :func:`sweep_pairs` (for tests)."""
    n = lo.shape[0]
    out = []
    for i in range(n):
        for j in range(i + 1, n):
            overlap = True
            for m in range(3):
                if lo[i, m] > hi[j, m] or lo[j, m] > hi[i, m]:
                    overlap = False
            if overlap and not _excluded(i, j, edge_nodes, edge_rod, exclusion):
                out.append((i, j))
    res = np.empty((len(out), 2), dtype=np.int64)
    for k in range(len(out)):
        res[k, 0] = out[k][0]
        res[k, 1] = out[k][1]
    return res


@njit(cache=True)
def sort_pairs(pairs, n_edges):
    """``pairs`` (n, 2) with rows (i < j) sorted lexicographically, as a new array (the
    order of ``np.lexsort((pairs[:, 1], pairs[:, 0]))``: the rows are unique, so any
    sort by (i, j) gives it). A counting sort on i (rows with i in 0..n_edges-1), then
    an insertion sort on j within each i (a few rows each): O(n + n_edges)."""
    n = pairs.shape[0]
    start = np.zeros(n_edges + 1, dtype=np.int64)
    for k in range(n):
        start[pairs[k, 0] + 1] += 1
    for e in range(n_edges):
        start[e + 1] += start[e]
    fill = start[:n_edges].copy()
    out = np.empty((n, 2), dtype=np.int64)
    for k in range(n):
        i = pairs[k, 0]
        j = pairs[k, 1]
        # insert j into the run of row i filled so far, keeping it sorted
        pos = fill[i]
        while pos > start[i] and out[pos - 1, 1] > j:
            out[pos, 1] = out[pos - 1, 1]
            pos -= 1
        out[pos, 1] = j
        fill[i] += 1
    for e in range(n_edges):
        for k in range(start[e], start[e + 1]):
            out[k, 0] = e
    return out


@njit(cache=True)
def candidate_pairs(pos, edge_nodes, edge_radius, margin, edge_rod, exclusion):
    """The sorted candidate pairs of :func:`knotmech.rod.broadphase.candidate_edge_pairs`
    (checked arguments) in one call: boxes grown by ``edge_radius + margin / 2``, the
    sweep, the lexicographic sort (the per-step call of the contact interaction, whose
    Python glue around the three kernels cost half as much as the kernels)."""
    n = edge_nodes.shape[0]
    inflate = np.empty(n)
    half = 0.5 * margin
    for e in range(n):
        inflate[e] = edge_radius[e] + half
    lo = np.empty((n, 3))
    hi = np.empty((n, 3))
    edge_boxes(pos, edge_nodes, inflate, lo, hi)
    pairs = sweep_pairs(lo, hi, edge_nodes, edge_rod, exclusion)
    if pairs.shape[0] > 1:
        pairs = sort_pairs(pairs, n)
    return pairs
