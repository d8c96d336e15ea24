"""Broad phase of rod-rod contact: candidate edge pairs from bounding boxes.

Sort-and-sweep (sweep and prune) of the edges' axis-aligned boxes, grown by each edge's
radius plus a margin, costs O(N log N + K) for N edges and K candidate pairs, instead of the
O(N^2) of testing all pairs (Baraff, "Dynamic simulation of non-penetrating rigid bodies",
PhD thesis, Cornell 1992, ch. 4).
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError, check_nonnegative
from knotmech.rod._kernels.contact_broadphase import (
    brute_pairs,
    candidate_pairs,
    edge_boxes,
    sweep_pairs,
)

__all__ = ["candidate_edge_pairs"]


def candidate_edge_pairs(
    positions,
    edge_nodes,
    *,
    edge_radius,
    margin,
    edge_rod=None,
    exclusion=2,
    method="sweep",
    validate=True,
):
    """Edge pairs whose grown bounding boxes overlap (candidates for contact).

    Parameters
    ----------
    positions : (n_nodes, 3) array [m]
        Node positions (global numbering).
    edge_nodes : (n_edges, 2) int array
        Global node indices of each edge's ends.
    edge_radius : float or (n_edges,) array [m]
        Rod radius of each edge; each box is grown by ``edge_radius + margin/2``.
    margin : float [m]
        Extra distance under which a pair is kept (covers motion within a step and the
        range of the smooth penalty).
    edge_rod : (n_edges,) int array or None
        Rod of each edge (None: a single rod).
    exclusion : int
        Edges of the same rod less than or equal to this many indices apart are never
        paired; edges sharing a node never are.
    method : {"sweep", "brute"}
        Sort-and-sweep (default) or the O(N^2) reference.
    validate : bool
        Check and convert the arguments (default). False: the caller passes contiguous
        float64 positions and radii (n_edges,), int64 edge_nodes and edge_rod, a margin
        >= 0 (the per-step call of the contact interaction).

    Returns
    -------
    pairs : (n_pairs, 2) int64 array
        Sorted rows (i < j), sorted lexicographically.
    """
    if not validate:  # boxes, sweep and the lexsort's order in one kernel call
        return candidate_pairs(positions, edge_nodes, edge_radius, float(margin), edge_rod,
                               int(exclusion))  # fmt: skip
    pos = np.ascontiguousarray(positions, dtype=float)
    en = np.ascontiguousarray(edge_nodes, dtype=np.int64)
    if pos.ndim != 2 or pos.shape[1] != 3:
        raise InputError(f"positions must have shape (n_nodes, 3), got {pos.shape}")
    if en.ndim != 2 or en.shape[1] != 2:
        raise InputError(f"edge_nodes must have shape (n_edges, 2), got {en.shape}")
    n_edges = en.shape[0]
    margin = float(check_nonnegative("margin", margin, scalar=True))
    rad = np.broadcast_to(check_nonnegative("edge_radius", edge_radius), (n_edges,))
    rod = (
        np.zeros(n_edges, dtype=np.int64)
        if edge_rod is None
        else np.ascontiguousarray(edge_rod, dtype=np.int64)
    )
    if int(exclusion) < 0:
        raise InputError(f"exclusion must be >= 0, got {exclusion}")
    inflate = np.ascontiguousarray(rad + 0.5 * margin, dtype=float)
    lo = np.empty((n_edges, 3))
    hi = np.empty((n_edges, 3))
    edge_boxes(pos, en, inflate, lo, hi)
    if method == "sweep":
        pairs = sweep_pairs(lo, hi, en, rod, int(exclusion))
    elif method == "brute":
        pairs = brute_pairs(lo, hi, en, rod, int(exclusion))
    else:
        raise InputError(f"method must be 'sweep' or 'brute', got {method!r}")
    if pairs.shape[0] > 1:
        order = np.lexsort((pairs[:, 1], pairs[:, 0]))
        pairs = pairs[order]
    return pairs
