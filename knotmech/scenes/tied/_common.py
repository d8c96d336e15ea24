r"""What the tied-knot curves share: a design language, the lift, the closures, the checks.

A knot is designed in rod diameters d as a *3-D control polygon* per rope: the
:math:`(x, y)` of each control point lays out the knot's diagram in the plane, its
:math:`z` (about :math:`\pm 1`) says which strand is meant to be over where two cross.
:func:`build_ropes` then

1. draws a clamped cubic B-spline through each polygon (smooth: the curve stays in the
   convex hull of four consecutive control points and has continuous curvature),
2. finds every crossing of the ropes' projections on the plane z = 0 (self-crossings and
   crossings between ropes) and reads which strand is over from the spline's own z,
3. replaces z by a monotone cubic (PCHIP) in arc length through :math:`\pm h_0` on a short
   plateau at each crossing (as :mod:`knotmech.scenes.bend_curves` does), so the strands
   at every crossing are :math:`2 h_0` apart and the rest of each rope lies near z = 0,
4. optionally splits a rope into two parallel strands :math:`\pm w` either side of it in
   the plane (a *ribbon*: a knot tied with two ropes held together, or on a bight), and
5. resamples each rope to ``n_nodes`` equal edges.

The diagram (step 2's crossings with their over/under) is the knot: the checks of
:mod:`knotmech.scenes.tied` close the ropes far outside (:func:`join_far`) and compare
the Alexander polynomial, the linking number (:func:`linking_number`) and the winding
about a pin (:func:`knotmech.scenes.topology.winding_number`) with the knot's expected
values, which each curve file derives in its docstring.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import BSpline, PchipInterpolator
from scipy.spatial import cKDTree

from knotmech.errors import InputError, check_positive
from knotmech.scenes.curves import min_separation, resample_polyline
from knotmech.scenes.tied.eye_linking import cut_linking
from knotmech.scenes.topology import knot_invariant, winding_number

__all__ = [
    "TiedKnot",
    "check_sizes",
    "bspline",
    "circle_controls",
    "planar_crossings",
    "build_ropes",
    "join_far",
    "linking_number",
    "max_curvature",
    "rope_gap",
    "writhe",
]

DS = 0.02  #: dense sampling step [d]
LIFT = 0.6  #: crossing height h0 [d]: strands 1.2 d apart at a crossing


@dataclass(frozen=True)
class TiedKnot:
    """Start centreline of a tied knot and what it is.

    Attributes
    ----------
    name : str
        The knot (``"bowline"``, ``"sheet_bend"``, ...).
    ropes : dict[str, (n_nodes, 3) array]
        Nodes of each rope [m], keyed ``"rope"`` (one rope), ``"A"``/``"B"`` (a bend) or
        ``"sling"`` (a closed loop, first node not repeated).
    ends : dict[str, tuple[str, str]]
        Role of each rope's first and last node: ``"standing"`` (loaded), ``"tail"``
        (free), ``"closed"`` (a sling).
    rod_radius : float [m]
    pin : dict or None
        ``{"point": (3,), "axis": (3,), "diameter": D}`` [m] of the pin or pole.
    expected : dict
        Expected invariants (Alexander polynomials as coefficient tuples, linking and
        winding numbers, knot names) the tests compare with.
    info : dict
        Design values [m] and the start shape's clearances.
    """

    name: str
    ropes: dict
    ends: dict
    rod_radius: float
    pin: dict | None = None
    expected: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)


def check_sizes(rod_diameter, n_nodes, min_nodes: int = 60) -> tuple[float, int]:
    """(d [m], n_nodes) checked: d > 0, n_nodes an integer >= ``min_nodes``."""
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    if isinstance(n_nodes, bool) or not float(n_nodes).is_integer() or int(n_nodes) < min_nodes:
        raise InputError(f"n_nodes must be an integer >= {min_nodes}, got {n_nodes!r}")
    return d, int(n_nodes)


def check_pin(pin_diameter, d: float, low: float, high: float) -> float:
    """D [m] of the pin or pole, checked to lie in [low d, high d] (the range the knot's
    start shape is built for)."""
    D = float(check_positive("pin_diameter", pin_diameter, scalar=True))
    if not low * d <= D <= high * d:
        lo, hi = (("d" if k == 1 else f"{k:g} d") for k in (low, high))
        raise InputError(
            f"pin_diameter must lie in [{lo}, {hi}] = [{low * d:g}, {high * d:g}] m, got {D:g}"
        )
    return D


def bspline(ctrl, ds: float = DS) -> np.ndarray:
    """Dense points (step about ``ds``) of the clamped cubic B-spline of a control polygon.

    Parameters
    ----------
    ctrl : (m, k) array
        Control points (m >= 4); the curve starts at the first and ends at the last,
        tangent to the first and the last legs of the polygon.
    ds : float
        Wanted spacing of the output, in the units of ``ctrl``.

    Returns
    -------
    (n, k) array
    """
    c = np.asarray(ctrl, dtype=float)
    m = len(c) - 3
    t = np.concatenate([[0.0] * 3, np.arange(m + 1, dtype=float), [float(m)] * 3])
    spl = BSpline(t, c, 3)
    poly_len = float(np.sum(np.linalg.norm(np.diff(c, axis=0), axis=1)))
    u = np.linspace(0.0, m, max(200, int(4 * poly_len / ds)))
    p = spl(u)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    return resample_polyline(_pad3(p), max(50, int(s[-1] / ds) + 1))[:, : c.shape[1]]


def _pad3(p):
    return p if p.shape[1] == 3 else np.column_stack([p, np.zeros(len(p))])


def circle_controls(center, radius, a0, a1, n, z=0.0) -> np.ndarray:
    r"""Control points on a circular arc such that the cubic B-spline through them lies on
    the circle of ``radius`` (to :math:`O(\theta^4)`): the polygon's circumradius is
    ``radius`` :math:`\times 3/(2 + \cos\theta)`, :math:`\theta` the step angle.
    Angles [rad] from a0 to a1 in n points; returns (n, 3)."""
    a = np.linspace(a0, a1, n)
    th = abs(a1 - a0) / (n - 1)
    rho = radius * 3.0 / (2.0 + np.cos(th))
    return np.column_stack([center[0] + rho * np.cos(a), center[1] + rho * np.sin(a),
                            np.full(n, float(z))])  # fmt: skip


def _arc(p):
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])


def planar_crossings(paths, step: float = 0.1):
    """Crossings of the projections of polylines on the plane z = 0.

    Parameters
    ----------
    paths : list of (n, >=2) arrays
        Polylines (dense), in any length unit.
    step : float
        Resampling step used for the search (same unit).

    Returns
    -------
    list of (i, s_i, j, s_j)
        Rope index and arc position of the two passages of each crossing, with
        ``(i, s_i) < (j, s_j)``; adjacent segments of one rope are not compared.
    """
    segs, owner, s0, ln = [], [], [], []
    for k, p in enumerate(paths):
        s = _arc(p)
        q = resample_polyline(_pad3(p), max(3, int(s[-1] / step) + 1))[:, :2]
        sq = np.linspace(0.0, s[-1], len(q))
        segs.append(np.stack([q[:-1], q[1:]], axis=1))
        owner.append(np.full(len(q) - 1, k))
        s0.append(sq[:-1])
        ln.append(np.diff(sq))
    seg, own, s0, ln = (np.concatenate(v) for v in (segs, owner, s0, ln))
    mid = seg.mean(axis=1)
    reach = 2.0 * float(np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).max())
    pairs = cKDTree(mid).query_pairs(reach, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    keep = (own[i] != own[j]) | (np.abs(i - j) > 1)
    i, j = i[keep], j[keep]
    a, da = seg[i, 0], seg[i, 1] - seg[i, 0]
    b, db = seg[j, 0], seg[j, 1] - seg[j, 0]
    r = b - a
    den = da[:, 0] * db[:, 1] - da[:, 1] * db[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (r[:, 0] * db[:, 1] - r[:, 1] * db[:, 0]) / den
        v = (r[:, 0] * da[:, 1] - r[:, 1] * da[:, 0]) / den
    hit = (den != 0) & (u >= 0) & (u < 1) & (v >= 0) & (v < 1)
    out = []
    for ii, jj, uu, vv in zip(i[hit], j[hit], u[hit], v[hit], strict=True):
        pi_ = (int(own[ii]), float(s0[ii] + uu * ln[ii]))
        pj_ = (int(own[jj]), float(s0[jj] + vv * ln[jj]))
        out.append((*min(pi_, pj_), *max(pi_, pj_)))
    return sorted(out)


def _lift(s, marks, h0):
    """z(s): PCHIP through +/- h0 on plateaus at the crossings ``marks`` [(s_k, +1/-1, w_k)]
    (half-width w_k, at most a fifth of the distance to the next crossing)."""
    if not marks:
        return np.zeros_like(s)
    marks = sorted(marks)
    sk = np.array([m[0] for m in marks])
    zk = np.array([h0 * m[1] for m in marks])
    gaps = np.diff(sk)
    half = np.minimum(np.concatenate([[np.inf], gaps]), np.concatenate([gaps, [np.inf]]))
    w = np.minimum([m[2] for m in marks], 0.2 * half)
    knots = np.column_stack([sk - w, sk + w]).ravel()
    vals = np.repeat(zk, 2)
    z = PchipInterpolator(knots, vals, extrapolate=False)(s)
    z[s <= knots[0]] = vals[0]
    z[s >= knots[-1]] = vals[-1]
    return z


def build_ropes(ctrls, *, ribbon=None, h0: float = LIFT, ds: float = DS):
    r"""Ropes (in d) from 3-D control polygons: spline, crossings, lift (module docstring).

    Parameters
    ----------
    ctrls : list of (m, 3) arrays
        Control polygons [d]; z only orders the strands at crossings.
    ribbon : list of (float or None), optional
        Half spacing w [d] per rope: that rope becomes two parallel strands at
        :math:`\pm w` (left and right of its direction of travel; w = None: one strand).
        Crossings are found and lifted on the rope's own centreline, with plateaus wide
        enough for the two strands.
    h0 : float
        Crossing height [d].
    ds : float
        Dense step [d].

    Returns
    -------
    list of (n, 3) arrays [d], and the list of crossings (as :func:`planar_crossings`,
    with the sign +1 where the first passage is over)
    """
    dense = [bspline(c, ds) for c in ctrls]
    cross = planar_crossings(dense)
    marks = [[] for _ in dense]
    signed = []
    for i, si, j, sj in cross:
        zi = np.interp(si, _arc(dense[i]), dense[i][:, 2])
        zj = np.interp(sj, _arc(dense[j]), dense[j][:, 2])
        if abs(zi - zj) < 0.2:
            raise InputError(f"design: crossing of ropes {i}, {j} at s = {si:.2f}, {sj:.2f} "
                             "has no clear over strand")  # fmt: skip
        up = 1 if zi > zj else -1
        wk = _plateau(dense, ribbon, i, si, j, sj)
        marks[i].append((si, up, wk))
        marks[j].append((sj, -up, wk))
        signed.append((i, si, j, sj, up))
    out = []
    for k, p in enumerate(dense):
        s = _arc(p)
        q = np.column_stack([p[:, :2], _lift(s, marks[k], h0)])
        w = None if ribbon is None else ribbon[k]
        out.extend([q] if w is None else _offset(q, w))
    return out, signed


def _plateau(dense, ribbon, i, si, j, sj) -> float:
    """Half-width [d] of the height plateau at a crossing: 0.6, or for ribbons
    w cot(theta/2) + 0.6, theta the crossing angle (where the four strands cross)."""
    ws = [0.0 if ribbon is None or ribbon[k] is None else ribbon[k] for k in (i, j)]
    if max(ws) == 0.0:
        return 0.6
    ti, tj = _tangent(dense[i], si), _tangent(dense[j], sj)
    cos = abs(ti @ tj) / (np.linalg.norm(ti) * np.linalg.norm(tj))
    th = np.arccos(np.clip(cos, 0.0, 1.0))
    return float(max(ws) / np.tan(0.5 * th) + 0.6)


def _offset(q, w):
    """The two strands at +/- w [d] (left, right of the travel direction) in the plane."""
    t = np.gradient(q[:, :2], axis=0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    n = np.column_stack([-t[:, 1], t[:, 0], np.zeros(len(t))])
    return [q + w * n, q - w * n]


def writhe(signed_crossings, paths) -> int:
    """Sum of the crossing signs of the projected diagram (z up, the order of travel)."""
    tot = 0
    for i, si, j, sj, up in signed_crossings:
        ti = _tangent(paths[i], si)
        tj = _tangent(paths[j], sj)
        over, under = (ti, tj) if up > 0 else (tj, ti)
        tot += int(np.sign(over[0] * under[1] - over[1] * under[0]))
    return tot


def _tangent(p, s):
    sp = _arc(p)
    k = int(np.clip(np.searchsorted(sp, s) - 1, 0, len(p) - 2))
    return p[k + 1, :2] - p[k, :2]


def join_far(pieces, *, reach: float | None = None, avoid=(), center=None) -> np.ndarray:
    """One closed polygon through open pieces joined end to start far outside the knot.

    The end of piece k is lifted straight up (+z) to the height R above the centroid of
    all pieces, carried radially out at that height to radius R, along the circle of radius
    R to the angle of the start of piece k+1 (cyclically), radially back in and down to that
    start. The arc is the shorter one that passes no other piece's end. An end on the
    outside of the knot is so closed as in the plane (nothing lies above it); an end inside
    (a bowline's tail in its eye) is taken out over everything.

    Parameters
    ----------
    pieces : list of (n, 3) arrays
        Open polylines, each oriented in the order of travel of the closed curve.
    reach : float, optional
        R (default 3 x the extent of the pieces).
    avoid : list of (3,) arrays
        Further end points (of other ropes) whose angles the arcs must not pass.
    center : (3,) array, optional
        Centre of the far circle (default the centroid of the pieces).

    Returns
    -------
    (m, 3) array, the closed polygon (last point joined to the first implicitly).
    """
    allp = np.vstack(pieces)
    c = allp.mean(axis=0) if center is None else np.asarray(center, float)
    R = 3.0 * float(np.ptp(allp, axis=0).max()) if reach is None else float(reach)
    ang = [_angle(np.asarray(q) - c) for q in avoid]
    for p in pieces:
        ang.extend([_angle(p[0] - c), _angle(p[-1] - c)])
    out = []
    for k, p in enumerate(pieces):
        out.append(p)
        nxt = pieces[(k + 1) % len(pieces)]
        arc = _far_arc(c, R, _angle(p[-1] - c), _angle(nxt[0] - c), ang)
        arc[:, 2] = c[2] + R
        out.append([p[-1] + [0.0, 0.0, c[2] + R - p[-1][2]]])
        out.append(arc)
        out.append([nxt[0] + [0.0, 0.0, c[2] + R - nxt[0][2]]])
    return np.vstack(out)


def _angle(v):
    return float(np.arctan2(v[1], v[0]))


def _far_arc(c, R, a0, a1, others):
    """Points on the circle of radius R from angle a0 to a1, by the shorter of the sides free
    of the angles ``others``."""
    best = None
    for sgn in (1.0, -1.0):
        span = (sgn * (a1 - a0)) % (2 * np.pi)
        inside = [(sgn * (o - a0)) % (2 * np.pi) for o in others]
        free = all(not (1e-9 < x < span - 1e-9) for x in inside)
        if free and (best is None or span < best[1]):
            best = (sgn, span)
    if best is None:
        raise InputError("join_far: the ends are interleaved; no crossing-free closure")
    a = a0 + best[0] * np.linspace(0.0, best[1], 64)
    return np.column_stack([c[0] + R * np.cos(a), c[1] + R * np.sin(a), np.full(64, c[2])])


def _refine(c, parts: int = 1500):
    """The closed polygon c with its long edges split (no edge longer than 1/parts of the
    polygon's length), so the midpoint rule of :func:`linking_number` converges."""
    e = np.roll(c, -1, axis=0) - c
    le = np.linalg.norm(e, axis=1)
    k = np.maximum(1, np.ceil(le / (le.sum() / parts)).astype(int))
    return np.vstack([c[i] + np.arange(k[i])[:, None] / k[i] * e[i] for i in range(len(c))])


def linking_number(c1, c2) -> float:
    r"""Gauss linking number of two closed polygons (midpoint rule; near an integer)."""

    def seg(c):
        c1_ = np.roll(c, -1, axis=0)
        return 0.5 * (c + c1_), c1_ - c

    am, da = seg(_refine(np.asarray(c1, float)))
    bm, db = seg(_refine(np.asarray(c2, float)))
    tot = 0.0
    for k in range(0, len(am), 400):
        r = am[k : k + 400, None, :] - bm[None, :, :]
        num = np.einsum("ijk,ijk->ij", np.cross(da[k : k + 400, None, :], db[None, :, :]), r)
        tot += float((num / np.linalg.norm(r, axis=2) ** 3).sum())
    return tot / (4 * np.pi)


def max_curvature(nodes) -> float:
    """Largest discrete curvature (turning angle over mean adjacent edge) [1/unit]."""
    x = np.asarray(nodes, float)
    e = np.diff(x, axis=0)
    le = np.linalg.norm(e, axis=1)
    cosang = np.einsum("ij,ij->i", e[:-1], e[1:]) / (le[:-1] * le[1:])
    ang = np.arccos(np.clip(cosang, -1.0, 1.0))
    return float((ang / (0.5 * (le[:-1] + le[1:]))).max())


def rope_gap(ropes, d) -> float:
    """Smallest centreline distance [m] between non-neighbouring parts of the ropes (within
    one rope: more than two diameters of arc apart; between ropes: any two nodes)."""
    best = min(min_separation(r, rod_radius=0.5 * d) for r in ropes)
    for a in range(len(ropes)):
        for b in range(a + 1, len(ropes)):
            dd = np.linalg.norm(ropes[a][:, None, :] - ropes[b][None, :, :], axis=2)
            best = min(best, float(dd.min()))
    return best


def invariant(closed) -> tuple:
    """Alexander polynomial of a closed polygon (three projections agreeing)."""
    return knot_invariant(closed, closed=True).alexander


def finish(ropes_d, d, n_nodes):
    """Ropes in d -> nodes in m, each resampled to n_nodes equal edges."""
    return [resample_polyline(r * d, n_nodes) for r in ropes_d]


# ---------------------------------------------------------------------------
# long knots from parametric closed knots, for knots tied with a doubled rope
# ---------------------------------------------------------------------------


def _trefoil(t):
    """A trefoil 3_1: (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t); apex (0, -3) at t = pi."""
    return np.array([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)])


def _figure_eight(t):
    """A figure-eight 4_1: ((2 + cos 2t) cos 3t, (2 + cos 2t) sin 3t, sin 4t), turned by
    -90 degrees about z so that its apex (t = 0) is (0, -3) with tangent +x."""
    r = 2 + np.cos(2 * t)
    return np.array([r * np.sin(3 * t), -r * np.cos(3 * t), np.sin(4 * t)])


CORES = {"overhand": (_trefoil, np.pi), "figure_eight": (_figure_eight, 0.0)}


def long_knot_controls(core: str, scale: float, tail: float, *, n_ctrl: int = 40,
                       cut: float = 0.45, drop: float = 3.0) -> np.ndarray:  # fmt: skip
    r"""Control polygon [d] of an open (long) overhand or figure-eight knot, ends left and right.

    The closed parametric knot (:data:`CORES`, apex at :math:`(0, -3)` with tangent +x,
    the outermost point of the curve) is scaled by ``scale`` and cut open at the apex: the
    arc :math:`|t - t_\mathrm{apex}| <` ``cut`` is removed. The start comes in from the far
    left ``drop`` below the apex and rises to the first kept point; the end leaves the last
    kept point and runs to the far right at the apex's height, passing *over* the start's
    rise: one extra crossing between the two tails, a kink (Reidemeister I) that does not
    change the knot type of the closure. z of the knot part is the parametric curve's
    (it only orders the strands at the crossings).

    Parameters
    ----------
    core : {"overhand", "figure_eight"}
    scale : float
        Size of the knot [d] (the parametric curve has radius 3).
    tail : float
        Length [d] of each straight end beyond the knot.
    """
    f, ta = CORES[core]
    t = np.linspace(ta + cut, ta + 2 * np.pi - cut, n_ctrl)
    body = np.array([f(tt) for tt in t]) * [scale, scale, 1.0]
    y0 = -3.0 * scale
    x_in, x_out = body[0, 0], body[-1, 0]
    start = [[x_in - tail - 3.0, y0 - drop, -1.0], [x_in - 2.5, y0 - drop, -1.0],
             [x_in - 0.4, y0 - 1.8, -1.0], [x_in - 0.2, y0 - 0.6, -1.0]]  # fmt: skip
    end = [[x_out + 1.0, y0 + 0.0, 1.0], [x_in + 1.0, y0 + 0.2, 1.0],
           [x_in + tail + 3.0, y0 + 0.2, 1.0]]  # fmt: skip
    return np.vstack([start, body, end])


def ribbon_strands(core: str, scale: float, w: float, tail: float):
    """A long overhand or figure-eight (:func:`long_knot_controls`) tied with a doubled rope.

    Returns
    -------
    upper, lower : (n, 3) arrays [d]
        The strands at +w (left of travel, +y at the ends) and -w, both from the far left
        to the far right.
    writhe : int
        Writhe of the single-rope diagram (its crossing signs summed): the linking number
        of the two strands traversed in the same sense (the blackboard framing).
    """
    cp = long_knot_controls(core, scale, tail)
    (upper, lower), signed = build_ropes([cp], ribbon=[w])
    single, _ = build_ropes([cp])
    return upper, lower, writhe(signed, single)


def eye_controls(p_out, p_back, center, radius, reach: float, direction: float = 1.0):
    """Control polygon [d] of an eye: from ``p_out`` (heading ``direction`` x: +1 or -1)
    straight on for ``reach``, along the tangent to the pin's circle (``center``, centreline
    radius ``radius``), round its far side, and back by the other tangent to ``p_back``
    (arriving heading the other way)."""
    sx = np.array([direction, 1.0, 1.0])
    a = np.asarray(p_out, float) * sx
    b = np.asarray(p_back, float) * sx
    c = np.asarray(center, float)[:2] * sx[:2]
    pa, pb = a + [reach, 0, 0], b + [reach, 0, 0]
    ta, tb = _tangent_angle(pa, c, radius, a[1] > b[1]), _tangent_angle(pb, c, radius, b[1] > a[1])
    if a[1] > b[1]:
        tb -= 2 * np.pi * (tb > ta)
    else:
        tb += 2 * np.pi * (tb < ta)
    n_arc = max(13, int(abs(tb - ta) / 0.25) + 1)
    arc = circle_controls(c, radius, ta, tb, n_arc)
    first = [a, a + [1.0, 0, 0], pa, 0.5 * (pa + arc[0])]
    last = [0.5 * (pb + arc[-1]), pb, b + [1.0, 0, 0], b]
    return np.vstack([first, arc, last]) * sx


def _tangent_angle(p, c, radius, upper: bool) -> float:
    """Angle [rad] about c of the point where the tangent from p touches the circle, on the
    upper (or lower) side."""
    v = np.asarray(p[:2], float) - c
    L = float(np.linalg.norm(v))
    if L <= radius * 1.05:
        raise InputError("design: eye leg starts inside the pin's circle")
    base = np.arctan2(v[1], v[0])
    off = np.arccos(radius / L)
    return float(base - off) if upper else float(base + off)


def cut_at(nodes, point) -> int:
    """Index of the node nearest ``point`` (where a loop's eye is cut for the checks)."""
    return int(np.argmin(np.linalg.norm(np.asarray(nodes) - np.asarray(point), axis=1)))


def closed_alone(piece, others=(), *, scale: float = 3.0, center=None) -> np.ndarray:
    """``piece`` closed far outside on its own (circle about ``center``, default the
    centroid of all pieces, radius ``scale`` x their extent), the arc avoiding the ends of
    ``others``."""
    allp = np.vstack([piece, *others])
    c = allp.mean(axis=0) if center is None else np.asarray(center, float)
    return join_far(
        [piece],
        reach=scale * float(np.ptp(allp, axis=0).max()),
        avoid=[q for o in others for q in (o[0], o[-1])],
        center=c,
    )


#: Alexander polynomials (t^0, t^1, ...) of the knots the closures meet (Rolfsen table;
#: composites as products, Delta(K1 # K2) = Delta(K1) Delta(K2)).
KNOT_TABLE = {
    (1,): "0_1",
    (1, -1, 1): "3_1",
    (-1, 3, -1): "4_1",
    (1, -1, 1, -1, 1): "5_1",
    (2, -3, 2): "5_2",
    (2, -5, 2): "6_1",
    (-1, 3, -3, 3, -1): "6_2",
    (1, -3, 5, -3, 1): "6_3",
    (1, -2, 3, -2, 1): "3_1#3_1",
    (-1, 4, -5, 4, -1): "3_1#4_1",
    (1, -6, 11, -6, 1): "4_1#4_1",
}


def knot_name(alexander) -> str:
    """Name of a knot from its Alexander polynomial (:data:`KNOT_TABLE`), else ``"?"``."""
    return KNOT_TABLE.get(tuple(int(v) for v in alexander), "?")


def _open_ropes(knot: TiedKnot):
    return {k: v for k, v in knot.ropes.items() if knot.ends[k][0] != "closed"}


def _pin_winding(closed, pin) -> int:
    w = winding_number(np.vstack([closed, closed[:1]]), axis_point=pin["point"],
                       axis_direction=pin["axis"])  # fmt: skip
    return int(round(w))


def _or_none(f):
    """f(), or None where the ends interleave round the knot (free tails that swung round
    during a run): a closure without new crossings is then not defined."""
    try:
        return f()
    except InputError as e:
        if "interleaved" in str(e):
            return None
        raise


def _two_ropes(a, b, names) -> dict:
    """Each rope closed on its own (its knot type does not depend on the side of the lifted
    closure) and the linking number of the pair (None if their ends interleave)."""
    out = {f"alexander_{names[0]}": invariant(join_far([a])),
           f"alexander_{names[1]}": invariant(join_far([b]))}  # fmt: skip
    out["linking"] = _or_none(lambda: int(round(linking_number(
        closed_alone(a, [b]), closed_alone(b, [a], scale=2.5)))))  # fmt: skip
    return out


def measure(knot: TiedKnot) -> dict:
    """The invariants of a tied knot's start shape (or of any frame with the same ropes),
    under the keys its ``expected`` dict uses:

    - ``alexander`` (one rope closed far outside, standing part to tail; or a sling),
    - ``alexander_A``, ``alexander_B`` (each rope of a bend closed on its own) and
      ``linking`` (their Gauss linking number, rounded; None when the ends of the two
      ropes interleave round the knot, as free tails may after swinging in a run),
    - ``alexander_joined`` (the ropes joined into one curve in the order of
      ``info["join"]``: (rope, forward) pairs; None when the ends interleave),
    - ``winding_pin`` (turns of the closed rope about the pin or pole axis),
    - ``alexander_cut``, ``linking_cut`` (a loop's rope cut at ``info["eye_cut"]``, the
      node of the eye farthest round the pin: the two halves closed on their own, about
      the pin's axis; ``linking_cut`` unless ``info["cut_linking"]`` is False: a tail that
      ends inside the eye makes it depend on the closure; the halves without the cut node,
      each closed out along the ray from the pin's centre through its cut end, counted
      exactly: :func:`~knotmech.scenes.tied.eye_linking.cut_linking`).
    """
    out = {}
    ropes = _open_ropes(knot)
    names = list(ropes)
    if "join" in knot.info:
        pieces = [ropes[n] if fwd else ropes[n][::-1] for n, fwd in knot.info["join"]]
        out["alexander_joined"] = _or_none(lambda: invariant(join_far(pieces)))
    if len(names) == 2:
        out.update(_two_ropes(ropes[names[0]], ropes[names[1]], names))
    if len(names) == 1:
        centre = None if knot.pin is None else knot.pin["point"]
        closed = join_far([ropes[names[0]]], center=centre)
        out["alexander"] = invariant(closed)
        if knot.pin is not None:
            out["winding_pin"] = _pin_winding(closed, knot.pin)
    if "eye_cut" in knot.info:
        r = ropes[names[0]]
        k = knot.info["eye_cut"]
        p1, p2 = r[: k + 1], r[k:]
        c1 = closed_alone(p1, [p2], center=knot.pin["point"])
        c2 = closed_alone(p2, [p1], scale=2.5, center=knot.pin["point"])
        out["alexander_cut"] = (invariant(c1), invariant(c2))
        if knot.info.get("cut_linking", True):
            out["linking_cut"] = cut_linking(r, k, knot.pin["point"])
    for name, rope in knot.ropes.items():
        if knot.ends[name][0] == "closed":
            out["alexander"] = invariant(np.vstack([rope]))
            if knot.pin is not None:
                out["winding_pin"] = _pin_winding(rope, knot.pin)
    return out


def start_checks(ropes_m, d, *, closed: bool = False) -> dict:
    """Clearances of a start shape: ``min_gap`` [m] (:func:`rope_gap`, or
    :func:`closed_gap` for one closed rope) and ``max_curvature`` [1/m] (largest over the
    ropes; a closed rope's seam included)."""
    if closed:
        (x,) = ropes_m
        ext = np.vstack([x[-1:], x, x[:1]])
        return {"min_gap": closed_gap(x, d), "max_curvature": max_curvature(ext)}
    return {"min_gap": rope_gap(ropes_m, d),
            "max_curvature": max(max_curvature(r) for r in ropes_m)}  # fmt: skip


def closed_gap(nodes, d) -> float:
    """Smallest distance [m] between nodes of a closed rope more than two diameters of arc
    apart along it (either way round)."""
    x = np.asarray(nodes, float)
    n = len(x)
    edge = float(np.mean(np.linalg.norm(np.diff(x, axis=0), axis=1)))
    k = max(3, int(np.ceil(2.0 * d / edge)) + 1)
    return min(float(np.linalg.norm(np.roll(x, -o, axis=0) - x, axis=1).min())
               for o in range(k, n - k + 1))  # fmt: skip


# ---------------------------------------------------------------------------
# the sheet-bend structure (sheet bend, bowline): a bight A and a nipping loop B
# ---------------------------------------------------------------------------

LEG = 2.2  #: half spacing of the bight's legs [d]
LOOP = 5.5  #: half height of B's loop round the legs [d]
LOOP_X = (-3.0, 2.0)  #: x of the loop's two sides [d]


def sheet_controls(left: float = -20.0, right: float = 30.0):
    r"""Control polygons [d] of the sheet-bend structure (see :mod:`.sheet_bend`).

    A: a bight, standing leg along y = +LEG from x = ``left`` - 10, a half turn round
    x = 7.5 (apex x = 9.7), tail leg back along y = -LEG to x = ``left``. B: from x =
    ``right`` along y = 0 over A's apex, under A's lower leg, then a loop round both legs
    (down to y = -LOOP, up at x = -3 over both legs, down at x = 2 under both, over its own
    first run), and its tail to the left along y = -8.5 to x = ``left``.
    """
    H, LB = LEG, LOOP
    XL, XR = LOOP_X
    a = [(left - 10, H, 0), (left, H, 0), (-8, H, 0), (XL, H, -1), (XR, H, 1), (5.5, H, 0),
         (7.5, H, 0), (9.7, 1.2, -1), (9.7, -1.2, -1), (7.5, -H, 0), (4.5, -H, 1),
         (XR, -H, 1), (XL, -H, -1), (-8, -H, 0), (left, -H, 0)]  # fmt: skip
    b = [(right, 0, 1), (right - 10, 0, 1), (12, 0, 1), (9.7, 0, 1), (6.5, 0, 0), (4.5, 0, -1),
         (4.5, -H, -1), (4.5, -LB, -1), (XR, -LB, -1), (XL, -LB, 0), (XL, -H, 1), (XL, H, 1),
         (XL, LB, 1), (XR, LB, 0), (XR, H, -1), (XR, -H, -1), (XR, -LB, 1), (XR, -8, 1),
         (-1, -8.5, 0), (-8, -8.5, 0), (left, -8.5, 0)]  # fmt: skip
    return np.array(a, float), np.array(b, float)


def double_sheet_controls(left: float = -22.0, right: float = 32.0, spread: float = 1.0):
    r"""Control polygons [d] of the double sheet bend (see :mod:`.double_sheet_bend`):
    A's bight as in :func:`sheet_controls` (half turn about x = 9.5), B round both legs
    twice: the first turn at x = -2 (up, over) and 1.5 (down, under), the second at x = -5
    and 4, each descent over B's first bottom run. ``spread`` scales the x positions of the
    turns and the heights of B's runs (a second embedding for the tests)."""
    H = LEG
    L1, L2, L3 = 5.5 * spread, 7.5 * spread, 9.5 * spread
    XL2, XL, XR, XR2, XE = (-5.0 * spread, -2.0 * spread, 1.5 * spread, 4.0 * spread,
                            6.5 * spread)  # fmt: skip
    UC = XE + 3.0
    a = [(left - 10, H, 0), (left, H, 0), (XL2 - 4, H, 0), (XL2, H, -1), (XL, H, -1), (XR, H, 1),
         (XR2, H, 1), (UC - 2, H, 0), (UC, H, 0), (UC + 2.2, 1.2, -1), (UC + 2.2, -1.2, -1),
         (UC, -H, 0), (XE, -H, 1), (XR2, -H, 1), (XR, -H, 1), (XL, -H, -1), (XL2, -H, -1),
         (XL2 - 4, -H, 0), (left, -H, 0)]  # fmt: skip
    b = [(right, 0, 1), (right - 10, 0, 1), (UC + 4, 0, 1), (UC + 2.2, 0, 1), (XE + 2, 0, 0),
         (XE, 0, -1), (XE, -H, -1), (XE, -L1, -1), (XR2, -L1, -1), (XR, -L1, -1), (XL, -L1, 0),
         (XL, -H, 1), (XL, H, 1), (XL, L1, 1), (XR, L1, 0), (XR, H, -1), (XR, -H, -1),
         (XR, -L1, 1), (XR, -L2, 0), (XL2, -L2, 0), (XL2, -H, 1), (XL2, H, 1), (XL2, L2, 1),
         (XR2, L2, 0), (XR2, H, -1), (XR2, -H, -1), (XR2, -L1, 1), (XR2, -L3, 0),
         (0, -L3 - 0.5, 0), (XL2 - 4, -L3 - 0.5, 0), (left, -L3 - 0.5, 0)]  # fmt: skip
    return np.array(a, float), np.array(b, float)
