r"""Knot centrelines built from parameters: overhand knots, the clove hitch, the coil.

Every generator returns a :class:`KnotCurve`: the node array ``(n_nodes, 3)`` [m]
with equal edge lengths and the prescribed total length, the rod radius, and named
index ranges (tails, braid strands, loop, wraps) that the scenes use to pull ends,
measure loops and read tension profiles.

Overhand knot with n braid turns (Jawed, Dieleman, Audoly & Reis, PRL 115, 118302,
2015; the coated-rod paper, Fig. 8 and table 1): a *loop* of arc length :math:`l`
and a two-strand *braid* in which each strand (arc length :math:`b`) is a helix of
radius :math:`a = h(1+c)` about the braid axis, the two strands half a turn apart,
with :math:`2n+1` half-twists (total helix angle :math:`\Phi = (2n+1)\pi`), so that the
curve closed far away is the :math:`(2, 2n+1)` torus knot (trefoil for n = 1; see
:mod:`knotmech.scenes.topology`). Coordinates: the end-to-end (pulling) axis is
:math:`x`, the loop lies in the :math:`x`-:math:`z` plane above the braid, the two tails
lie on the :math:`x` axis. With :math:`b_x = \sqrt{b^2 - (\Phi a)^2}` the braid's
axial length, the straight tails have length :math:`t = (E - b_x)/2` (E the end-to-end
distance) and the loop takes the rest, :math:`l = L - 2t - 2b`; it is a circular arc
through the two ends of the braid, tangent-continuous to within the angle
:math:`\arcsin(b_x/2R)`, and the junctions are rounded over a few rod radii.
Non-adjacent nodes are at least :math:`2h(1+c)` apart and non-adjacent edges at least
:math:`2h` (the helix radius is enlarged on coarse meshes, whose chords cut inside the
helix), so contact starts clean.

Clove hitch (the clove-hitch paper, sec. 2 and Fig. 1): two wraps around a post at
centreline radius :math:`R = (D+d)/2`, the diagonal between them crossing over both
tails, lifted off the post there so that no strand interpenetrates; the ends leave
tangentially in opposite directions from between the wraps.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.errors import InputError, check_count, check_positive, check_range

__all__ = [
    "KnotCurve",
    "OVERHAND_COATED_TABLE1",
    "OVERHAND_IMC",
    "overhand_knot",
    "overhand_coated",
    "overhand_imc",
    "clove_hitch_curve",
    "coil_curve",
    "resample_polyline",
    "min_separation",
    "end_to_end",
    "loop_metrics",
]


@dataclass(frozen=True)
class KnotCurve:
    """A rod centreline and the index ranges of its parts.

    Attributes
    ----------
    nodes : (n_nodes, 3) array [m]
        Node positions, equal edge lengths.
    rod_radius : float [m]
    parts : dict[str, tuple[int, int]]
        Half-open node index ranges ``[start, stop)`` of named parts, e.g. ``"tail1"``,
        ``"braid1"``, ``"loop"``, ``"braid2"``, ``"tail2"`` (overhand) or ``"wrap1"``,
        ``"diagonal"``, ``"wrap2"`` (clove hitch).
    info : dict
        Design values (lengths [m], turns, axis), for the record.
    """

    nodes: np.ndarray
    rod_radius: float
    parts: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)

    @property
    def rod_length(self) -> float:
        """Polygon length [m]."""
        return float(np.sum(np.linalg.norm(np.diff(self.nodes, axis=0), axis=1)))

    @property
    def edge_length(self) -> float:
        """Mean edge length [m]."""
        return self.rod_length / (len(self.nodes) - 1)


# ---------------------------------------------------------------------------
# small geometric helpers
# ---------------------------------------------------------------------------


def resample_polyline(points, n_nodes: int) -> np.ndarray:
    """Nodes at equal arc-length spacing along a (dense) polyline.

    Parameters
    ----------
    points : (m, 3) array [m]
        Polyline, dense compared with the wanted spacing.
    n_nodes : int
        Number of output nodes (>= 2); the first and last points are kept.

    Returns
    -------
    (n_nodes, 3) array [m]
    """
    p = np.asarray(points, dtype=float)
    n_nodes = check_count("n_nodes", n_nodes, 2)
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    target = np.linspace(0.0, s[-1], int(n_nodes))
    return np.column_stack([np.interp(target, s, p[:, k]) for k in range(3)])


def _march_chords(p: np.ndarray, chord: float, n_nodes: int) -> np.ndarray:
    """Nodes along a dense polyline, each exactly ``chord`` from the previous one."""
    out = np.empty((n_nodes, 3))
    out[0] = p[0]
    j = 0  # current dense segment index
    m = len(p)
    for k in range(1, n_nodes):
        c = out[k - 1]
        # first dense point at distance >= chord, searched forward
        while j < m - 1 and np.linalg.norm(p[j + 1] - c) < chord:
            j += 1
        if j >= m - 1:
            raise InputError("the polyline is too short for the requested nodes")
        a0, a1 = p[j], p[j + 1]
        d = a1 - a0
        f = a0 - c
        # |f + u d| = chord, root in [0, 1]
        A, B, C = d @ d, 2 * f @ d, f @ f - chord * chord
        u = (-B + np.sqrt(max(B * B - 4 * A * C, 0.0))) / (2 * A)
        out[k] = a0 + min(max(u, 0.0), 1.0) * d
    return out


def _exclusion(edge: float, rod_radius: float) -> int:
    """Index gap below which two nodes count as neighbours along the rod."""
    return max(3, int(np.ceil(4.0 * rod_radius / edge)) + 1)


def min_separation(nodes, *, rod_radius: float | None = None, exclude: int | None = None):
    r"""Smallest distance between two nodes that are not neighbours along the rod.

    Pairs :math:`(i, j)` with :math:`|i - j| \ge k` are compared; by default
    :math:`k = \max(3, \lceil 4h/\ell\rceil + 1)` (more than two rod diameters of arc
    length apart, and never closer than the contact exclusion of two edges).

    Parameters
    ----------
    nodes : (n_nodes, 3) array [m]
    rod_radius : float, optional [m]
        Used for the default exclusion.
    exclude : int, optional
        Explicit minimal index gap :math:`k`.

    Returns
    -------
    float [m]
    """
    x = np.asarray(nodes, dtype=float)
    if exclude is None:
        edge = float(np.mean(np.linalg.norm(np.diff(x, axis=0), axis=1)))
        exclude = _exclusion(edge, rod_radius if rod_radius is not None else 0.0)
    n = len(x)
    best = np.inf
    for k in range(int(exclude), n):
        d = np.linalg.norm(x[k:] - x[:-k], axis=1)
        best = min(best, float(d.min()))
    return best


def end_to_end(nodes) -> float:
    """Distance between the first and the last node [m]."""
    x = np.asarray(nodes, dtype=float)
    return float(np.linalg.norm(x[-1] - x[0]))


def _edge_distances(x: np.ndarray) -> np.ndarray:
    """Minimum distance between every pair of edges (segments) of a polyline, (n_e, n_e)."""
    p0 = x[:-1]
    d = np.diff(x, axis=0)
    a = np.einsum("ij,ij->i", d, d)
    r = p0[:, None, :] - p0[None, :, :]  # p_i - p_j
    b = d @ d.T  # d_i . d_j
    c = np.einsum("ijk,ik->ij", r, d)  # d_i . r
    f = np.einsum("ijk,jk->ij", r, d)  # d_j . r
    ai, aj = a[:, None], a[None, :]
    den = ai * aj - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(den > 1e-14 * ai * aj, (b * f - c * aj) / den, 0.0)
    s = np.clip(s, 0.0, 1.0)
    t = (b * s + f) / aj
    t = np.clip(t, 0.0, 1.0)
    s = np.clip((b * t - c) / ai, 0.0, 1.0)
    diff = r + s[:, :, None] * d[:, None, :] - t[:, :, None] * d[None, :, :]
    return np.linalg.norm(diff, axis=2)


def _pair_distances(x: np.ndarray, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """:func:`_edge_distances` ``[i, j]`` for the index pairs (i, j) only (same formula)."""
    p0 = x[:-1]
    d = np.diff(x, axis=0)
    di, dj = d[i], d[j]
    ai = np.einsum("ij,ij->i", di, di)
    aj = np.einsum("ij,ij->i", dj, dj)
    r = p0[i] - p0[j]
    b = np.einsum("ij,ij->i", di, dj)
    c = np.einsum("ij,ij->i", r, di)
    f = np.einsum("ij,ij->i", r, dj)
    den = ai * aj - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(den > 1e-14 * ai * aj, (b * f - c * aj) / den, 0.0)
    s = np.clip(s, 0.0, 1.0)
    t = np.clip((b * s + f) / aj, 0.0, 1.0)
    s = np.clip((b * t - c) / ai, 0.0, 1.0)
    diff = r + s[:, None] * di - t[:, None] * dj
    return np.linalg.norm(diff, axis=1)


def _close_edges(x: np.ndarray, k: int, threshold: float) -> np.ndarray:
    """Sorted indices of the edges i whose distance to some edge j with |i - j| >= k is
    below ``threshold`` (the distances of :func:`_edge_distances`, row i).

    Only pairs whose midpoints lie within ``threshold`` plus their two half-lengths can be
    that close (a lower bound of the segment distance), so those are found first with a
    k-d tree and the distance is evaluated for them alone: the same set as from the dense
    (n_e, n_e) matrix, at a small fraction of its cost on a 300-node knot.
    """
    from scipy.spatial import cKDTree

    d = np.diff(x, axis=0)
    n_e = len(d)
    if n_e == 0:
        return np.zeros(0, dtype=np.int64)
    mid = x[:-1] + 0.5 * d
    half = 0.5 * np.linalg.norm(d, axis=1)
    reach = float(threshold + 2.0 * half.max()) * (1.0 + 1e-9)
    pairs = cKDTree(mid).query_pairs(reach, output_type="ndarray")
    if pairs.size == 0:
        return np.zeros(0, dtype=np.int64)
    i, j = pairs[:, 0], pairs[:, 1]
    gap = np.linalg.norm(mid[i] - mid[j], axis=1) - half[i] - half[j]
    keep = (np.abs(i - j) >= k) & (gap < threshold * (1.0 + 1e-9) + 1e-300)
    i, j = i[keep], j[keep]
    # the dense matrix is not exactly symmetric in floating point: each row uses its own
    near = np.zeros(n_e, dtype=bool)
    near[i[_pair_distances(x, i, j) < threshold]] = True
    near[j[_pair_distances(x, j, i) < threshold]] = True
    return np.flatnonzero(near)


def loop_metrics(nodes, *, rod_radius: float, contact_factor: float = 1.3):
    r"""Braid and loop of an overhand knot read from its shape.

    Edges whose nearest non-neighbouring edge (edge-edge distance, more than two rod
    diameters of arc length away) lies within ``contact_factor`` :math:`\times 2h` are
    *in contact*; the braid strands are the first and the last contiguous runs of
    contacting edges, and the loop is the stretch of rod between them.

    Parameters
    ----------
    nodes : (n_nodes, 3) array [m]
    rod_radius : float [m]
    contact_factor : float
        Contact threshold in rod diameters (> 1).

    Returns
    -------
    dict
        ``loop_length`` [m] (arc length between the braid runs), ``loop_diameter`` [m]
        (largest distance between two loop nodes), ``braid_length`` [m] (mean arc
        length of the two contact runs), ``loop`` (node index range); NaNs if no braid
        is found.
    """
    x = np.asarray(nodes, dtype=float)
    h = float(check_positive("rod_radius", rod_radius, scalar=True))
    edge = float(np.mean(np.linalg.norm(np.diff(x, axis=0), axis=1)))
    k = _exclusion(edge, h)
    close = _close_edges(x, k, contact_factor * 2.0 * h)
    nan = {
        "loop_length": np.nan,
        "loop_diameter": np.nan,
        "braid_length": np.nan,
        "loop": (0, 0),
    }
    if close.size < 2:
        return nan
    runs = np.split(close, np.nonzero(np.diff(close) > 1)[0] + 1)
    if len(runs) < 2:
        return nan
    first, last = runs[0], runs[-1]
    i0, i1 = int(first[-1]) + 1, int(last[0])
    loop = x[i0 : i1 + 1]
    dl = np.linalg.norm(loop[:, None, :] - loop[None, :, :], axis=2)
    return {
        "loop_length": float((i1 - i0) * edge),
        "loop_diameter": float(dl.max()),
        "braid_length": float(0.5 * (first.size + last.size) * edge),
        "loop": (i0, i1 + 1),
    }


def _smooth_corners(p: np.ndarray, s: np.ndarray, s_corners, width: float) -> np.ndarray:
    """Round corners of a dense polyline: Gaussian smoothing blended in near ``s_corners``."""
    ds = s[1] - s[0]
    half = int(np.ceil(3 * width / ds))
    kern = np.exp(-0.5 * (np.arange(-half, half + 1) * ds / width) ** 2)
    kern /= kern.sum()
    pad = np.concatenate([np.repeat(p[:1], half, 0), p, np.repeat(p[-1:], half, 0)])
    # straight-line extrapolation at the ends keeps straight tails straight
    pad[:half] = p[0] + (p[0] - p[1]) * np.arange(half, 0, -1)[:, None]
    pad[-half:] = p[-1] + (p[-1] - p[-2]) * np.arange(1, half + 1)[:, None]
    sm = np.column_stack([np.convolve(pad[:, k], kern, mode="valid") for k in range(3)])
    w = np.zeros_like(s)
    for sc in s_corners:
        w = np.maximum(w, np.exp(-0.5 * ((s - sc) / (1.5 * width)) ** 2))
    return (1 - w[:, None]) * p + w[:, None] * sm


def _arc_through(c_len: float, arc_len: float) -> tuple[float, float]:
    """Radius and angle of a circular arc of length ``arc_len`` on a chord ``c_len``."""
    # arc/chord = theta / (2 sin(theta/2)), increasing on (0, 2 pi)
    ratio = arc_len / c_len
    lo, hi = 1e-9, 2 * np.pi - 1e-12
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid / (2 * np.sin(mid / 2)) < ratio:
            lo = mid
        else:
            hi = mid
    theta = 0.5 * (lo + hi)
    return arc_len / theta, theta


# ---------------------------------------------------------------------------
# overhand knots
# ---------------------------------------------------------------------------

#: Coated-rod paper, table 1: turns -> (tail t, braid b, loop arc l, end-to-end) [m],
#: total rod length 0.300 m (n = 1, 2) and 0.600 m (n = 3, 4); natural rubber d = 1.59 mm.
OVERHAND_COATED_TABLE1 = {
    1: (0.035, 0.030, 0.170, 0.100),
    2: (0.025, 0.055, 0.140, 0.100),
    3: (0.080, 0.095, 0.250, 0.250),
    4: (0.045, 0.110, 0.290, 0.200),
}

#: Implicit-contact-model paper (Choi, Tong & Jawed 2021) start shapes: turns ->
#: (end-to-end [m], braid strand length [m]); rod length 1 m, 301 nodes, h = 1.6 mm.
#: The end-to-end distances are the paper's; the braid lengths are read off its start
#: shapes (arc length of each strand in contact: about 0.12, 0.19, 0.24, 0.28 m).
OVERHAND_IMC = {
    1: (0.280, 0.118),
    2: (0.330, 0.190),
    3: (0.330, 0.240),
    4: (0.330, 0.280),
}


def _overhand_dense(turns, L, h, E, b, a, loop_len, ds, extra):
    """Dense polyline of the overhand design and the arc positions of its junctions."""
    Phi = (2 * turns + 1) * np.pi
    bx = np.sqrt(b * b - (Phi * a) ** 2)
    t = 0.5 * (E - bx)
    R, theta = _arc_through(bx, loop_len)

    def line(p0, p1):
        m = max(2, int(np.ceil(np.linalg.norm(np.subtract(p1, p0)) / ds)) + 1)
        return np.linspace(p0, p1, m)

    m_b = max(8, int(np.ceil(b / ds)) + 1)
    xi = np.linspace(0.0, bx, m_b)
    phi = -0.5 * np.pi + Phi * xi / bx
    strand_a = np.column_stack([xi, a * np.cos(phi), a * np.sin(phi)])
    strand_b = np.column_stack([xi, -a * np.cos(phi), -a * np.sin(phi)])
    tail1 = line((-t, 0.0, -a), (0.0, 0.0, -a))
    tail2 = line((bx, 0.0, -a), (bx + t + extra, 0.0, -a))
    # loop: arc in the x-z plane through (bx, a) and (0, a), counter-clockwise over the top
    hc = -R * np.cos(theta / 2)  # centre height above the chord
    xc, zc = 0.5 * bx, a + hc
    alpha_r = np.arctan2(a - zc, bx - xc)
    m_l = max(16, int(np.ceil(loop_len / ds)) + 1)
    ang = alpha_r + np.linspace(0.0, theta, m_l)
    loop = np.column_stack([xc + R * np.cos(ang), np.zeros(m_l), zc + R * np.sin(ang)])
    pieces = [tail1, strand_a[1:], loop[1:], strand_b[1:], tail2[1:]]
    p = np.vstack(pieces)
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    ends = np.cumsum([len(q) for q in pieces]) - 1
    s_junctions = s[ends[:-1]]
    return p, s, s_junctions, {"tail": t, "bx": bx, "loop_radius": R}


def _overhand_nodes(n, L, h, E, b, a, loop_len, edge, N):
    """Equal-chord nodes of the overhand design for helix radius ``a``."""
    ds = min(edge, a) / 8.0
    width = 1.5 * a
    # equal chords of length L/(N-1); the loop length is adjusted (secant) so that the
    # last node lands on the end of tail 2 (the corner rounding shortens the curve a little)
    design = loop_len
    extra = 4 * edge
    target = None
    prev = None
    for _ in range(12):
        p, s, sj, geo = _overhand_dense(n, L, h, E, b, a, design, ds, extra)
        p = _smooth_corners(p, s, sj, width)
        if target is None:
            target = geo["bx"] + geo["tail"]
        nodes = _march_chords(p, edge, N)
        err = float(target - nodes[-1, 0])
        if abs(err) < 1e-9 * L:
            break
        if prev is None:
            step = err
        else:
            slope = (err - prev[1]) / (design - prev[0])
            step = -err / slope if slope != 0 else err
        prev = (design, err)
        design += step
    else:
        raise InputError("could not place the nodes at equal spacing; check the lengths")
    return nodes, sj, geo, design


def overhand_knot(
    turns: int,
    *,
    rod_length: float,
    rod_radius: float,
    end_to_end_length: float,
    braid_length: float,
    n_nodes: int,
    clearance: float = 0.05,
) -> KnotCurve:
    r"""Open overhand knot with ``turns`` braid turns, from its design lengths.

    Parameters
    ----------
    turns : int
        Braid turns n (1 to 6); the closed curve is the (2, 2n+1) torus knot.
    rod_length : float [m]
        Total length L of the rod.
    rod_radius : float [m]
        h; strands in the braid are :math:`2h(1+c)` apart (centreline to centreline).
    end_to_end_length : float [m]
        Distance E between the two ends (along x), :math:`b_x < E`.
    braid_length : float [m]
        Arc length b of each braid strand, :math:`b > (2n+1)\pi h(1+c)`.
    n_nodes : int
        Number of nodes (>= 20).
    clearance : float
        c, the relative gap added to the contact distance 2h (0 to 1).

    Returns
    -------
    KnotCurve
        Parts ``tail1``, ``braid1``, ``loop``, ``braid2``, ``tail2``; ``info`` holds the
        achieved tail, braid, loop lengths [m] and the loop radius [m].

    Raises
    ------
    InputError
        If the lengths do not make a knot (loop shorter than the braid axis, negative
        tails) or the result would have strands closer than :math:`2h`.

    Notes
    -----
    The total length and the end-to-end distance are met exactly; the braid keeps
    its length b; the tails and the loop take what remains, so nominal tail and loop
    values (e.g. table 1 of the coated-rod paper) are met to within the helix's
    axial shortening.
    """
    n = check_count("turns", turns, 1, 6)
    L = float(check_positive("rod_length", rod_length, scalar=True))
    h = float(check_positive("rod_radius", rod_radius, scalar=True))
    E = float(check_positive("end_to_end_length", end_to_end_length, scalar=True))
    b = float(check_positive("braid_length", braid_length, scalar=True))
    c = float(check_range("clearance", clearance, 0.0, 1.0, scalar=True))
    N = check_count("n_nodes", n_nodes, 20)
    a, loop_len, edge = _overhand_design(n, L, h, E, b, h * (1.0 + c), N)
    nodes, sj, geo, design, a = _overhand_clear(n, L, h, E, b, a, loop_len, edge, N)
    bx, t = geo["bx"], geo["tail"]
    # place the ends on the x axis, centred
    nodes = nodes - np.array([0.5 * (nodes[0, 0] + nodes[-1, 0]), 0.0, nodes[0, 2]])
    edge = L / (N - 1)
    bounds = np.rint(np.concatenate([[0.0], sj, [L]]) / L * (N - 1)).astype(int)
    bounds[-1] = N
    names = ["tail1", "braid1", "loop", "braid2", "tail2"]
    parts = {nm: (int(bounds[k]), int(bounds[k + 1])) for k, nm in enumerate(names)}
    sep = min_separation(nodes, rod_radius=h)
    if sep < 2.0 * h:
        raise InputError(
            f"n_nodes = {N} is too coarse for this knot: non-adjacent nodes come {sep:.3g} m"
            f" apart, below the rod diameter {2 * h:.3g} m; use more nodes"
        )
    info = {
        "turns": n,
        "tail_length": t,
        "braid_length": b,
        "braid_axial_length": bx,
        "loop_length": design + float(np.sum(np.linalg.norm(np.diff(nodes, axis=0), axis=1))) - L,
        "loop_radius": geo["loop_radius"],
        "helix_radius": a,
        "end_to_end_length": end_to_end(nodes),
        "min_separation": sep,
        "edge_length": edge,
        "pull_axis": (1.0, 0.0, 0.0),
    }
    return KnotCurve(nodes=nodes, rod_radius=h, parts=parts, info=info)


def _overhand_design(n, L, h, E, b, a, N):
    """(helix radius a [m], loop length [m], edge [m]) of an overhand design, checked:
    the braid longer than its turns, the ends farther apart than the braid's axis, a loop
    long enough, edges of at most a sixth of the helix pitch."""
    Phi = (2 * n + 1) * np.pi
    if b <= 1.05 * Phi * a:
        raise InputError(
            f"braid_length must exceed (2n+1) pi h (1+c) = {Phi * a:.4g} m for {n} turns, got {b:g}"
        )
    bx = np.sqrt(b * b - (Phi * a) ** 2)
    if E <= bx + 4 * h:
        raise InputError(
            f"end_to_end_length must exceed the braid's axial length + 4h = {bx + 4 * h:.4g} m,"
            f" got {E:g}"
        )
    t = 0.5 * (E - bx)
    loop_len = L - 2 * t - 2 * b
    if loop_len <= 1.2 * bx or loop_len < 10 * np.pi * h:
        raise InputError(
            f"rod_length {L:g} m leaves a loop of {loop_len:.4g} m, too short for a braid of"
            f" axial length {bx:.4g} m; give a longer rod or a shorter braid"
        )
    pitch = 2 * np.pi * bx / Phi
    edge = L / (N - 1)
    if edge > pitch / 6:
        raise InputError(
            f"n_nodes = {N} is too coarse: the edge {edge:.3g} m must not exceed a sixth of"
            f" the braid's helix pitch {pitch:.3g} m"
        )
    return a, loop_len, edge


def _overhand_clear(n, L, h, E, b, a, loop_len, edge, N):
    """The overhand's nodes with every pair of non-neighbouring edges at least 2h apart:
    the helix radius a is spread (up to 8 times) where chords of the helices cut inside
    the clearance on coarse meshes. Returns (nodes, part ends, geometry, design loop
    length, a)."""
    Phi = (2 * n + 1) * np.pi
    idx_e = np.arange(N - 1)
    far = np.abs(idx_e[:, None] - idx_e[None, :]) >= 3
    for _attempt in range(8):
        nodes, sj, geo, design = _overhand_nodes(n, L, h, E, b, a, loop_len, edge, N)
        d_min = float(_edge_distances(nodes)[far].min())
        if d_min >= 2.0 * h:
            return nodes, sj, geo, design, a
        a *= 1.02 * 2.0 * h / d_min
        if b <= 1.05 * Phi * a:
            raise InputError(
                f"n_nodes = {N} is too coarse for braid_length {b:g} m: the strands would"
                " have to be spread beyond the braid length to stay a diameter apart"
            )
    raise InputError(f"n_nodes = {N}: could not keep the strands a rod diameter apart")


def overhand_coated(turns: int, *, n_nodes: int | None = None, clearance: float = 0.05):
    r"""Overhand knot of the coated-rod paper (table 1; natural rubber d = 1.59 mm).

    Uses :data:`OVERHAND_COATED_TABLE1`: rod length 2t + 2b + l (0.300 m for n = 1, 2,
    0.600 m for n = 3, 4), braid b and end-to-end distance as tabulated. Default
    ``n_nodes`` gives an edge of about 1.5 mm (0.94 d).
    """
    n = check_count("turns", turns, 1, 4)  # table 1's rows
    t, b, lo, e2e = OVERHAND_COATED_TABLE1[n]
    L = 2 * t + 2 * b + lo
    if n_nodes is None:
        n_nodes = int(round(L / 0.0015)) + 1
    curve = overhand_knot(
        n,
        rod_length=L,
        rod_radius=0.5 * 1.59e-3,
        end_to_end_length=e2e,
        braid_length=b,
        n_nodes=n_nodes,
        clearance=clearance,
    )
    curve.info.update({"nominal_tail": t, "nominal_loop": lo, "source": "coated-rod table 1"})
    return curve


def overhand_imc(turns: int, *, n_nodes: int = 301, clearance: float = 0.05):
    r"""Overhand knot of the implicit-contact-model paper (L = 1 m, h = 1.6 mm).

    End-to-end 0.280 m (n = 1) and 0.330 m (n = 2-4), braid strands from
    :data:`OVERHAND_IMC`, 301 nodes by default (edge 3.33 mm).
    """
    n = check_count("turns", turns, 1, 4)  # OVERHAND_IMC's rows
    e2e, b = OVERHAND_IMC[n]
    curve = overhand_knot(
        n,
        rod_length=1.0,
        rod_radius=1.6e-3,
        end_to_end_length=e2e,
        braid_length=b,
        n_nodes=n_nodes,
        clearance=clearance,
    )
    curve.info["source"] = "implicit contact model (Choi, Tong & Jawed 2021)"
    return curve


# ---------------------------------------------------------------------------
# post hitches
# ---------------------------------------------------------------------------


def _post_frame(axis):
    a = np.asarray(axis, dtype=float).reshape(3)
    na = np.linalg.norm(a)
    if not np.isfinite(na) or na == 0:
        raise InputError("post_axis must be a finite non-zero vector")
    a = a / na
    e1 = np.cross(a, np.eye(3)[np.argmin(np.abs(a))])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    return e1, e2, a


#: the longest straight tail a wrapped start curve is built with, in rod diameters: the
#: tail is sampled at the wrap's point spacing (0.05-0.1 d) before it is resampled to the
#: rod's nodes, so a mistyped rod length (2.7e5 m for a 4 mm rod) would allocate
#: hundreds of millions of points before any run-size check (the slow CLI campaign's
#: MemoryError)
MAX_TAIL_RATIO = 1.0e4


def _check_tail(tail_length: float, rod_diameter: float) -> float:
    """``tail_length`` [m], refused (InputError, one line) above :data:`MAX_TAIL_RATIO`
    rod diameters."""
    tl = float(check_positive("tail_length", tail_length, scalar=True))
    if tl > MAX_TAIL_RATIO * rod_diameter:
        raise InputError(
            f"a straight tail of {tl:.3g} m is {tl / rod_diameter:.3g} rod diameters, above "
            f"{MAX_TAIL_RATIO:g}: shorten the rod (check the units of rod_length)"
        )
    return tl


def _wrapped(psi, z, rho, tail_len, frame, center, n_nodes, rod_length=None):
    """Curve from cylindrical coordinates along the wraps, plus tangent tails."""
    e1, e2, a = frame
    core = (
        (rho * np.cos(psi))[:, None] * e1
        + (rho * np.sin(psi))[:, None] * e2
        + z[:, None] * a
        + np.asarray(center, dtype=float)
    )
    t0 = core[1] - core[0]
    t0 /= np.linalg.norm(t0)
    t1 = core[-1] - core[-2]
    t1 /= np.linalg.norm(t1)
    m = max(2, int(np.ceil(tail_len / np.linalg.norm(core[1] - core[0]))))
    s = np.linspace(1.0, 0.0, m, endpoint=False)[:, None] * tail_len
    tail1 = core[0] - s * t0
    tail2 = core[-1] + s[::-1] * t1
    p = np.vstack([tail1, core, tail2])
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    svals = np.concatenate([[0.0], np.cumsum(seg)])
    return resample_polyline(p, n_nodes), svals, len(tail1)


def coil_curve(
    *,
    post_diameter: float,
    rod_diameter: float,
    wrap_angle: float = 4 * np.pi,
    tail_length: float,
    n_nodes: int,
    pitch_factor: float = 1.1,
    post_axis=(0.0, 0.0, 1.0),
    post_center=(0.0, 0.0, 0.0),
) -> KnotCurve:
    r"""Rod wrapped ``wrap_angle`` around a post as a helix ("two loops" for :math:`4\pi`).

    Centreline radius :math:`R = (D + d)/2` (touching the post), pitch
    ``pitch_factor`` :math:`\times d` per turn, straight tangent tails of length
    ``tail_length`` at both ends; the wrap starts at angle 0 about ``post_axis``.

    Returns
    -------
    KnotCurve
        Parts ``tail1``, ``wrap``, ``tail2``; ``info["wrap_radius"]`` = R.
    """
    D = float(check_positive("post_diameter", post_diameter, scalar=True))
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    th = float(check_positive("wrap_angle", wrap_angle, scalar=True))
    tl = _check_tail(tail_length, d)
    pf = float(check_range("pitch_factor", pitch_factor, 1.0, 100.0, scalar=True))
    N = check_count("n_nodes", n_nodes, 20)
    R = 0.5 * (D + d)
    frame = _post_frame(post_axis)
    m = max(64, int(np.ceil(th * R / (0.1 * d))))
    psi = np.linspace(0.0, th, m)
    z = pf * d * (psi - 0.5 * th) / (2 * np.pi)
    nodes, svals, _ = _wrapped(psi, z, np.full(m, R), tl, frame, post_center, N)
    L = float(np.sum(np.linalg.norm(np.diff(nodes, axis=0), axis=1)))
    s_wrap = np.hypot(R * th, pf * d * th / (2 * np.pi))
    i0 = int(round(tl / L * (N - 1)))
    i1 = int(round((tl + s_wrap) / L * (N - 1)))
    parts = {"tail1": (0, i0), "wrap": (i0, i1 + 1), "tail2": (i1 + 1, N)}
    info = {
        "wrap_radius": R,
        "wrap_angle": th,
        "rod_length": L,
        "post_axis": tuple(frame[2]),
        "post_center": tuple(np.asarray(post_center, dtype=float)),
    }
    return KnotCurve(nodes=nodes, rod_radius=0.5 * d, parts=parts, info=info)


#: half angular width [rad] of the clove core's diagonal
_DIAGONAL_HALF_WIDTH = 0.5


def _smoothstep(u):
    u = np.clip(u, 0.0, 1.0)
    return u * u * (3 - 2 * u)


def _clove_core(R: float, d: float, gap: float, lift: float, m: int):
    """(psi, z, rho) of two same-sense wraps joined by a lifted diagonal (psi in [0, 4 pi]): the
    core of :func:`clove_hitch_curve` and of the half hitches' and cow hitch's curves."""
    zt = 0.5 * gap * d
    zw = zt + gap * d
    alpha = _DIAGONAL_HALF_WIDTH
    psi = np.linspace(0.0, 4 * np.pi, m)
    run = 0.9  # angle over which the ends run in from +-z_t to +-z_w [rad]
    z = np.where(
        psi < 2 * np.pi,
        -zt - (zw - zt) * _smoothstep(psi / run),
        zt + (zw - zt) * _smoothstep((4 * np.pi - psi) / run),
    )
    diag = np.abs(psi - 2 * np.pi) < alpha
    u = (psi - 2 * np.pi + alpha) / (2 * alpha)
    z = np.where(diag, -zw + 2 * zw * _smoothstep(u), z)
    # lift of the diagonal: smooth bump reaching R/cos(alpha) + lift*d - R at psi = 2 pi
    bump_w = alpha + 0.6
    bump = np.where(
        np.abs(psi - 2 * np.pi) < bump_w,
        np.cos(0.5 * np.pi * (psi - 2 * np.pi) / bump_w) ** 2,
        0.0,
    )
    # the diagonal crosses the tail heights within |psi - 2 pi| < 0.2 alpha, where the
    # straight tails are at most R / cos(0.2) from the axis
    rho = R + (lift * d + R * (1 / np.cos(0.2) - 1)) * bump
    return psi, z, rho, zt, zw


def clove_hitch_curve(
    *,
    post_diameter: float,
    rod_diameter: float,
    tail_length: float,
    n_nodes: int,
    gap: float = 1.15,
    lift: float = 1.15,
    post_axis=(0.0, 0.0, 1.0),
    post_center=(0.0, 0.0, 0.0),
) -> KnotCurve:
    r"""Pre-shaped clove hitch around a post (two wraps, diagonal over both ends).

    In cylindrical coordinates :math:`(\psi, z, \rho)` about the post axis, with
    :math:`R = (D+d)/2` and :math:`\psi` the wrap angle along the rod:

    - tail 1 arrives tangentially at :math:`\psi = 0` at height :math:`-z_t`, runs down
      to the lower wrap at :math:`-z_w` and once round the post;
    - the *diagonal* (:math:`|\psi - 2\pi| < \alpha`) climbs from :math:`-z_w` to :math:`+z_w`
      on the front, lifted to :math:`\rho = R/\cos\alpha +` ``lift`` :math:`\times d` so it
      passes over both tails (which are straight tangents there, at :math:`\rho \le R/\cos\alpha`);
    - the upper wrap at :math:`+z_w` goes round once more and runs in to height
      :math:`+z_t`, leaving tangentially at :math:`\psi = 4\pi` as tail 2.

    The two ends leave the front of the post in opposite directions from between
    the wraps, both under the diagonal: the clove hitch (two half hitches in the
    same sense). :math:`z_t = g d/2` and :math:`z_w = z_t + g d` (g = ``gap``).
    Seen from the axis, the rod's self-crossings read ``"UOOU"``
    (:func:`knotmech.scenes.topology.post_crossing_code`) and the winding number is 2.

    Parameters
    ----------
    post_diameter : float [m]
    rod_diameter : float [m]
    tail_length : float [m]
        Length of each straight tail.
    n_nodes : int
    gap : float
        Axial centreline distance between strands that pass each other on the front
        (the two tails, a tail and the wrap next to it), in rod diameters (>= 1).
    lift : float
        Radial clearance of the diagonal over the tails in rod diameters (>= 1).
    post_axis, post_center : (3,) arrays

    Returns
    -------
    KnotCurve
        Parts ``tail1``, ``wrap1``, ``diagonal``, ``wrap2``, ``tail2``.
    """
    D = float(check_positive("post_diameter", post_diameter, scalar=True))
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    tl = _check_tail(tail_length, d)
    g = float(check_range("gap", gap, 1.0, 50.0, scalar=True))
    lf = float(check_range("lift", lift, 1.0, 10.0, scalar=True))
    N = check_count("n_nodes", n_nodes, 40)
    R = 0.5 * (D + d)
    frame = _post_frame(post_axis)
    m = max(400, int(np.ceil(4 * np.pi * R / (0.05 * d))))
    psi, z, rho, zt, zw = _clove_core(R, d, g, lf, m)
    alpha = _DIAGONAL_HALF_WIDTH
    nodes, svals, n_tail = _wrapped(psi, z, rho, tl, frame, post_center, N)
    L = float(np.sum(np.linalg.norm(np.diff(nodes, axis=0), axis=1)))
    s_core = svals[n_tail - 1 :] - svals[n_tail - 1]
    # arc positions of part boundaries
    s_of = np.interp([2 * np.pi - alpha, 2 * np.pi + alpha, 4 * np.pi], psi, s_core[: len(psi)])
    marks = np.concatenate([[tl], tl + s_of]) / L * (N - 1)
    b = np.rint(marks).astype(int)
    parts = {
        "tail1": (0, int(b[0])),
        "wrap1": (int(b[0]), int(b[1])),
        "diagonal": (int(b[1]), int(b[2])),
        "wrap2": (int(b[2]), int(b[3]) + 1),
        "tail2": (int(b[3]) + 1, N),
    }
    info = {
        "wrap_radius": R,
        "rod_length": L,
        "wrap_height": zw,
        "tail_height": zt,
        "post_axis": tuple(frame[2]),
        "post_center": tuple(np.asarray(post_center, dtype=float)),
        "min_separation": min_separation(nodes, rod_radius=0.5 * d),
    }
    return KnotCurve(nodes=nodes, rod_radius=0.5 * d, parts=parts, info=info)
