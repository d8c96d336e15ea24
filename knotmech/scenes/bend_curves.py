r"""Centrelines of the four bends of Patil et al. (2020): reef, granny, thief, grief.

A *bend* joins two ropes A and B. All four are two interlocked bights (Patil, Sandt, Kolle &
Dunkel, "Topological mechanics of knots and tangles", Science 367, 71 (2020), Fig. 3): in
the plane z = 0, rope A is a U opening towards -x (its two parts at :math:`y = \pm n`
outside the knot, widening to :math:`\pm W` before its bend, a half circle of radius W about
:math:`(c, 0)`), rope B is A turned half a turn about the z axis. Seen from +z the two
ropes cross six times, all A over or under B:

- C1, C6: A's two parts under/over B's bend (at :math:`x = -c - \sqrt{W^2 - n^2}`),
- C2, C5: A's parts across B's parts in the middle (x = 0),
- C3, C4: A's bend across B's two parts.

The knot type sits in the over/under choice (A's passage at C1 ... C6, along A):

- ``"UOUUOU"``: each rope's two parts pass *together* under the other's bight (both
  under at C1, C6; B's both over A's bend at C3, C4): the **reef** shape. Joined around
  the outside (A's upper end to B's upper end, the lower ends likewise; see
  :func:`bend_closure`) it closes to a knot with Alexander polynomial
  :math:`(1 - t + t^2)^2` (determinant 9) and writhe 0: the square knot
  :math:`3_1 \# 3_1^*`.
- ``"UOUOUO"`` (alternating): the parts pass the other's bight on opposite sides: the
  **granny** shape; it closes to a reduced alternating diagram with the same polynomial
  and writhe -6: the granny knot :math:`3_1 \# 3_1` (for a reduced alternating diagram
  the writhe is an invariant, and it is 0 for the square knot).

Which two ends are pulled makes the other two bends: with the standing parts on the same
edge (both at :math:`y = -n`) and the tails free at :math:`y = +n` the shapes are the reef
and the granny; with the standing parts diagonally opposite (A's at :math:`+n`, B's at
:math:`-n`) they are the **thief** (reef shape) and the **grief** (granny shape).

The heights at the crossings are :math:`\pm h_0` (``lift`` rod diameters); between
crossings z follows a monotone cubic (PCHIP) in arc length. The default design values
(in rod diameters d: n = 1.25, W = 2.6, c = 2.5, lift = 0.6) keep the two ropes at least
1.04 d apart (edge to edge distance of the centrelines) and each rope 2.3 d from itself.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from knotmech import knots
from knotmech.errors import InputError, check_count, check_positive, check_range
from knotmech.scenes.curves import _edge_distances, min_separation, resample_polyline
from knotmech.scenes.topology import knot_invariant

__all__ = [
    "BEND_CODES",
    "BEND_ENDS",
    "BendCurves",
    "bend_curves",
    "bend_closure",
    "bend_linking",
    "bend_invariants",
]

_BENDS = tuple(k for k in knots.records(family="bend") if k.curve.endswith(":bend_curves"))

#: Over/under of rope A at its six crossings with B, along A (see the module docstring); the
#: ``code`` of each bend's record in :mod:`knotmech.knots`.
BEND_CODES = {k.name: k.curve_params["code"] for k in _BENDS}

#: (pulled end of A, pulled end of B): "start"/"end" of each rope. A starts at
#: (-x, +n) and ends at (-x, -n); B starts at (+x, -n) and ends at (+x, +n). The ``ends`` of
#: each bend's record.
BEND_ENDS = {k.name: tuple(k.curve_params["ends"]) for k in _BENDS}


@dataclass(frozen=True)
class BendCurves:
    """Node arrays of the two ropes of a bend and which ends are pulled.

    Attributes
    ----------
    kind : str
    rope_a, rope_b : (n_nodes, 3) arrays [m]
    rod_radius : float [m]
    pulled : (str, str)
        Pulled end ("start" or "end") of A and of B; the other ends are the free tails.
    code : str
        A's over/under at the six crossings.
    info : dict
        Design values [m] and the clearances of the start shape.
    """

    kind: str
    rope_a: np.ndarray
    rope_b: np.ndarray
    rod_radius: float
    pulled: tuple
    code: str
    info: dict


def _plane_path(n, W, c, X, ds):
    """Dense planar path of rope A (x, y) and the arc positions of its six crossings."""
    x1 = np.arange(-X, -c, ds)
    up1 = np.column_stack([x1, np.full_like(x1, n)])
    xb = np.arange(-c, c, ds)
    sm = 0.5 - 0.5 * np.cos(np.pi * (xb + c) / (2 * c))
    up2 = np.column_stack([xb, n + (W - n) * sm])
    th = np.arange(0.5 * np.pi, -0.5 * np.pi, -ds / W)
    bend = np.column_stack([c + W * np.cos(th), W * np.sin(th)])
    p = np.vstack([up1, up2, bend, up2[::-1] * [1, -1], up1[::-1] * [1, -1], [[-X, -n]]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    xc = c + np.sqrt(W * W - n * n)
    half = len(p) // 2
    marks = [(-xc, n, 0, half), (0.0, 0.5 * (W + n), 0, half), (xc, n, 0, len(p))]
    marks += [(xc, -n, 0, len(p)), (0.0, -0.5 * (W + n), half, len(p)), (-xc, -n, half, len(p))]
    sk = []
    for x, y, lo, hi in marks:
        sk.append(s[lo + int(np.argmin(np.hypot(p[lo:hi, 0] - x, p[lo:hi, 1] - y)))])
    return p, s, np.array(sk)


def _lift(s, sk, zk):
    z = PchipInterpolator(sk, zk, extrapolate=False)(s)
    z[s < sk[0]] = zk[0]
    z[s > sk[-1]] = zk[-1]
    return z


def bend_curves(
    kind: str,
    *,
    rod_diameter: float,
    n_nodes: int,
    tail_length: float | None = None,
    spread: float = 1.25,
    bight: float = 2.6,
    overlap: float = 2.5,
    lift: float = 0.6,
) -> BendCurves:
    r"""Loosely tied reef, granny, thief or grief bend (two ropes), ready to be pulled.

    Parameters
    ----------
    kind : {"reef", "granny", "thief", "grief"}
    rod_diameter : float [m]
        d, the diameter of both ropes.
    n_nodes : int
        Nodes per rope (>= 40).
    tail_length : float [m], optional
        Length of each straight part outside the knot, from the far end to x = -c
        (default 14 d).
    spread, bight, overlap, lift : float
        n, W, c and :math:`h_0` in rod diameters (module docstring).

    Returns
    -------
    BendCurves

    Raises
    ------
    InputError
        Unknown kind, or a design whose ropes come closer than one diameter.
    """
    if kind not in BEND_CODES:
        raise InputError(f"kind must be one of {', '.join(BEND_CODES)}, got {kind!r}")
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    N = check_count("n_nodes", n_nodes, 40)
    n = float(check_range("spread", spread, 0.6, 10.0, scalar=True)) * d
    W = float(check_range("bight", bight, 1.0, 20.0, scalar=True)) * d
    c = float(check_range("overlap", overlap, 1.0, 20.0, scalar=True)) * d
    h0 = float(check_range("lift", lift, 0.5, 5.0, scalar=True)) * d
    if W < n + 1.0 * d:
        raise InputError(f"bight must exceed spread + 1 (in rod diameters), got {bight:g}")
    X = c + (
        14.0 * d
        if tail_length is None
        else float(check_positive("tail_length", tail_length, scalar=True))
    )
    p, s, sk = _plane_path(n, W, c, X, 0.02 * d)
    code = BEND_CODES[kind]
    za = np.array([h0 if ch == "O" else -h0 for ch in code])
    # B is A turned by pi about z; its k-th crossing (along B) lies where A has crossing
    # sigma(k), and B is on the other side of A there
    zb = -za[[3, 4, 5, 0, 1, 2]]
    a = resample_polyline(np.column_stack([p, _lift(s, sk, za)]), N)
    b = resample_polyline(np.column_stack([-p[:, 0], -p[:, 1], _lift(s, sk, zb)]), N)
    both = np.vstack([a, b])
    gap = float(_edge_distances(both)[: N - 1, N:].min())
    self_gap = min(min_separation(a, rod_radius=0.5 * d), min_separation(b, rod_radius=0.5 * d))
    if gap < 1.0 * d or self_gap < 1.0 * d:
        raise InputError(
            f"the bend's strands come {min(gap, self_gap) / d:.2f} d apart (< 1 d): "
            "increase lift, bight or n_nodes"
        )
    info = {
        "spread": n,
        "bight_radius": W,
        "overlap": c,
        "lift": h0,
        "half_width": X,
        "rope_length": float(s[-1]),
        "min_gap_between_ropes": gap,
        "min_gap_within_rope": self_gap,
    }
    return BendCurves(kind, a, b, 0.5 * d, BEND_ENDS[kind], code, info)


def bend_closure(rope_a, rope_b, *, reach: float | None = None) -> np.ndarray:
    r"""One closed polygon from the two ropes: A's start joined to B's end around +y, B's
    start to A's end around -y, far from the knot (no new crossing seen from +z).

    Parameters
    ----------
    rope_a, rope_b : (n, 3) arrays [m]
        A's ends on the -x side, B's on the +x side (as :func:`bend_curves` builds them).
    reach : float [m], optional
        Distance of the closing path (default 3 x the extent of the two ropes).

    Returns
    -------
    (2 n + 6, 3) array [m]
        For the reef shape a square knot, for the granny shape a granny knot (Alexander
        polynomial :math:`(1-t+t^2)^2` for both).
    """
    a = np.asarray(rope_a, dtype=float)
    b = np.asarray(rope_b, dtype=float)
    both = np.vstack([a, b])
    R = 3.0 * float(np.ptp(both, axis=0).max()) if reach is None else float(reach)
    ex = np.array([R, 0.0, 0.0])
    top = np.array([0.0, R, 0.0])
    path = [a[::-1], [a[0] - ex, top, b[-1] + ex], b[::-1], [b[0] + ex, -top, a[-1] - ex]]
    return np.vstack(path)


def bend_linking(rope_a, rope_b) -> float:
    r"""Gauss linking number of the two ropes, each closed far away on its own side.

    .. math:: Lk = \frac{1}{4\pi}\sum_{i,j}
              \frac{(\mathbf a_i' \times \mathbf b_j')\cdot(\mathbf a_i - \mathbf b_j)}
                   {|\mathbf a_i - \mathbf b_j|^3}

    (midpoint rule over the segments; rounds to an integer for curves that stay apart).
    """
    a = np.asarray(rope_a, dtype=float)
    b = np.asarray(rope_b, dtype=float)
    R = 3.0 * float(np.ptp(np.vstack([a, b]), axis=0).max())
    ex = np.array([R, 0.0, 0.0])
    ca = np.vstack([a, [a[-1] - ex, a[0] - ex]])
    cb = np.vstack([b, [b[-1] + ex, b[0] + ex]])

    def seg(c):
        c1 = np.roll(c, -1, axis=0)
        return 0.5 * (c + c1), c1 - c

    am, da = seg(ca)
    bm, db = seg(cb)
    r = am[:, None, :] - bm[None, :, :]
    num = np.einsum("ijk,ijk->ij", np.cross(da[:, None, :], db[None, :, :]), r)
    return float((num / np.linalg.norm(r, axis=2) ** 3).sum() / (4 * np.pi))


def bend_invariants(rope_a, rope_b):
    """(Alexander polynomial of :func:`bend_closure`, rounded linking number); the pair is
    unchanged unless a strand passes through another (or a tail end was drawn through)."""
    inv = knot_invariant(bend_closure(rope_a, rope_b), closed=True)
    return inv.alexander, int(round(bend_linking(rope_a, rope_b)))
