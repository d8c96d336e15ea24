r"""A snug doubled figure-eight: the parametric one drawn in by a contract-and-repel pass.

The doubled parametric figure-eight of :func:`~knotmech.scenes.tied._common.ribbon_strands`
(scale 3.4 d, strands 1.3 d apart) holds about 120 d of each rope in loops 5-10 d across
(docs/notes/knots-and-curves/tied-knots-pulled.md). :func:`snug_figure_eight` draws it in
without changing its diagram, a crude dressing of the knot by hand:

1. both strands resampled at :data:`H` [d];
2. :data:`STEPS` times: the strands contracted towards their common centroid by
   :data:`SHRINK` in the plane (z kept), then :data:`SUB` times a light Laplacian smoothing
   (:data:`SMOOTH`, ends fixed: it also shortens the curve) and one repulsion sweep: every
   pair of points closer than :data:`GAP` [d] (of different strands, or of one strand more
   than ``2 GAP`` of arc apart) pushed apart along their join by a quarter of the overlap
   each; then resampled at :data:`H`;
3. :data:`FINAL_SWEEPS` repulsion sweeps at :data:`FINAL_GAP` (no smoothing, no
   contraction), so that the curve's clearance is above 1.1 d;
4. each strand drawn as the cubic spline through its points in arc length, sampled every
   :data:`DS` [d] (as the other tied curves' dense polylines).

Each move is a fraction of a diameter while the strands are more than a diameter apart,
so no strand passes through another; the figure-eight bend's and loop's checks
(:func:`~knotmech.scenes.tied._common.measure`, ``tests/scenes/test_tied_curves.py``)
confirm the knot types on the result. The pass is deterministic and takes about 2 s of
CPU; its result is cached.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.spatial import cKDTree

from knotmech.scenes.curves import resample_polyline
from knotmech.scenes.tied._common import ribbon_strands

__all__ = ["equal_chords", "run_on", "snug_figure_eight"]

SCALE = 3.4  #: size of the parametric figure-eight drawn in [d]
HALF = 0.65  #: half spacing of the doubled rope [d]
TAIL = 8.0  #: straight ends of the construction before the pass [d]
H = 0.25  #: point spacing of the pass [d]
STEPS = 100  #: contractions
SHRINK = 0.01  #: each contraction's relative shrink in the plane
SUB = 30  #: smoothing + repulsion sweeps per contraction
SMOOTH = 0.2  #: Laplacian smoothing weight
GAP = 1.25  #: repulsion distance while contracting [d]
FINAL_SWEEPS = 50  #: repulsion sweeps at the end
FINAL_GAP = 1.2  #: repulsion distance of the last sweeps [d]
DS = 0.02  #: dense step of the result [d]


def _resampled(p: np.ndarray) -> np.ndarray:
    n = max(20, int(np.linalg.norm(np.diff(p, axis=0), axis=1).sum() / H))
    return resample_polyline(p, n)


def _smooth(p: np.ndarray) -> np.ndarray:
    q = p.copy()
    q[1:-1] += SMOOTH * (p[:-2] + p[2:] - 2.0 * p[1:-1])
    return q


def _repel(ps: list, gap: float) -> list:
    """One repulsion sweep over the strands ``ps`` [d] (module docstring, step 2)."""
    sizes = [len(p) for p in ps]
    x = np.vstack(ps)
    owner = np.repeat(np.arange(len(ps)), sizes)
    idx = np.concatenate([np.arange(n) for n in sizes])
    i, j = cKDTree(x).query_pairs(gap, output_type="ndarray").T
    far = (owner[i] != owner[j]) | (np.abs(idx[i] - idx[j]) * H > 2.0 * gap)
    i, j = i[far], j[far]
    v = x[i] - x[j]
    dist = np.linalg.norm(v, axis=1)
    push = (0.25 * (gap - dist) / np.maximum(dist, 1e-9))[:, None] * v
    dx = np.zeros_like(x)
    np.add.at(dx, i, push)
    np.add.at(dx, j, -push)
    return np.split(x + dx, np.cumsum(sizes)[:-1])


def _contract(ps: list) -> list:
    c = np.mean(np.vstack(ps), axis=0)
    f = 1.0 - SHRINK
    return [np.column_stack([(p[:, :2] - c[:2]) * f + c[:2], p[:, 2]]) for p in ps]


@lru_cache(maxsize=1)
def _snug() -> tuple:
    upper, lower, w = ribbon_strands("figure_eight", SCALE, HALF, TAIL)
    ps = [_resampled(upper), _resampled(lower)]
    for _ in range(STEPS):
        ps = _contract(ps)
        for _ in range(SUB):
            ps = _repel([_smooth(p) for p in ps], GAP)
        ps = [_resampled(p) for p in ps]
    for _ in range(FINAL_SWEEPS):
        ps = _repel(ps, FINAL_GAP)
    return _dense(ps[0]), _dense(ps[1]), w


def _dense(p: np.ndarray) -> np.ndarray:
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    return CubicSpline(s, p, axis=0)(np.linspace(0.0, s[-1], int(s[-1] / DS) + 1))


def snug_figure_eight() -> tuple[np.ndarray, np.ndarray, int]:
    """The doubled figure-eight of :func:`~knotmech.scenes.tied._common.ribbon_strands`
    (``"figure_eight"``, scale :data:`SCALE`, half spacing :data:`HALF`) drawn in.

    Returns
    -------
    upper, lower : (n, 3) arrays [d]
        The two strands, both from the far left to the far right, as ``ribbon_strands``;
        the knot about 9 x 6 x 5 d, each strand 45-50 d long (short straight ends).
    writhe : int
        Writhe of the single-rope diagram (unchanged by the pass).
    """
    upper, lower, w = _snug()
    return upper.copy(), lower.copy(), w


def run_on(p, left: float, right: float) -> np.ndarray:
    """Polyline ``p`` [d] with its first point run on by ``left`` [d] and its last by
    ``right`` [d], each straight along its outward end tangent."""
    u0, u1 = p[0] - p[1], p[-1] - p[-2]
    u0, u1 = u0 / np.linalg.norm(u0), u1 / np.linalg.norm(u1)
    return np.vstack([p[0] + left * u0, p, p[-1] + right * u1])


def _walk(p: np.ndarray, c: float, n: int) -> tuple[np.ndarray, float]:
    """Nodes from ``p[0]`` along the dense polyline ``p``, each the first point of ``p``
    at distance ``c`` from the one before (on the segment that crosses that distance);
    and the distance past the end of ``p`` the last node would need (negative: short)."""
    out, k = [p[0]], 0
    for _ in range(n - 1):
        dist = np.linalg.norm(p[k + 1 :] - out[-1], axis=1)
        hit = np.flatnonzero(dist >= c)
        if not hit.size:
            return np.array(out), 1.0
        j = k + 1 + int(hit[0])
        a, b = p[j - 1], p[j]
        # |a + t (b - a) - out| = c, t in [0, 1]
        u, v = b - a, a - out[-1]
        qa, qb, qc = u @ u, 2 * (u @ v), v @ v - c * c
        t = (-qb + np.sqrt(max(qb * qb - 4 * qa * qc, 0.0))) / (2 * qa)
        out.append(a + t * u)
        k = j - 1
    rest = float(np.linalg.norm(p[-1] - out[-1]))
    return np.array(out), -rest


def equal_chords(points, n_nodes: int) -> np.ndarray:
    """``n_nodes`` nodes on the dense polyline ``points`` [any unit], the first and last
    its ends, all chords equal (to 1e-9 relative): equal arc steps
    (:func:`~knotmech.scenes.curves.resample_polyline`) leave the chords of a tight knot's
    coarse mesh several per cent apart."""
    p = np.asarray(points, float)
    lo = 0.0
    hi = float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum()) / (n_nodes - 1)
    for _ in range(60):
        c = 0.5 * (lo + hi)
        nodes, miss = _walk(p, c, n_nodes)
        lo, hi = (c, hi) if miss < 0 else (lo, c)
    nodes, _ = _walk(p, lo, n_nodes)
    nodes[-1] = p[-1]
    return nodes
