r"""Knot invariants of rod centrelines: the check that no strand passed through another.

A contact model that lets one strand cross another changes the knot type of the
centreline. This module closes an open centreline far away from the knot,
projects it on a plane, reads off the crossings (which strand is over) and
computes from them

- the Alexander polynomial :math:`\Delta(t)`, as the determinant of the Alexander
  matrix (the abelianised Fox derivatives of the Wirtinger relations) with one row
  and one column deleted (Alexander 1928; Livingston, *Knot Theory*, 1993, ch. 6),
  normalised so that :math:`\Delta(1) = 1` and the lowest power is :math:`t^0`;
- the knot determinant :math:`|\Delta(-1)|`, which is the determinant of the
  Fox colouring matrix (entries 2, -1, -1 per crossing), independent of crossing signs.

Reference values: unknot :math:`\Delta = 1` (det 1); trefoil :math:`1 - t + t^2` (det 3);
figure-eight :math:`-1 + 3t - t^2` (det 5); the :math:`(2, m)` torus knot (m odd)
:math:`\sum_{i=0}^{m-1} (-t)^i` (det m). An overhand knot with n braid turns is a
two-strand braid with :math:`2n+1` half-twists closed by the loop, so it closes to the
:math:`(2, 2n+1)` torus knot: trefoil :math:`3_1`, cinquefoil :math:`5_1`, :math:`7_1`,
:math:`9_1`, of crossing number :math:`2n+1` (the topological parameter of Jawed,
Dieleman, Audoly & Reis, PRL 115, 118302 (2015)). This is checked in the tests on the
generators of :mod:`knotmech.scenes.curves` and on the start shapes of the
implicit-contact-model code (n1..n4 give 3_1, 5_1, 7_1, 9_1).

For a hitch around a post (not a knot by itself) the module gives the winding number
of the rod about the post axis and the over/under sequence of the rod's self-crossings
seen from the post axis (:func:`post_crossing_code`); both are unchanged unless one
strand passes through another or through the post.

All functions take node arrays ``(n_nodes, 3)`` [m] and are pure numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from knotmech.errors import InputError, check_finite, check_positive

__all__ = [
    "KnotInvariant",
    "Crossings",
    "close_curve",
    "projection_crossings",
    "alexander_polynomial",
    "knot_determinant",
    "knot_invariant",
    "torus_knot_polynomial",
    "identify_knot",
    "winding_number",
    "post_crossing_code",
]


def _as_nodes(name: str, points, min_nodes: int = 2) -> np.ndarray:
    arr = check_finite(name, points)
    if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] < min_nodes:
        raise InputError(f"{name} must be an (n_nodes, 3) array with n_nodes >= {min_nodes}")
    return arr


def close_curve(points, *, extension: float = 3.0) -> np.ndarray:
    r"""Close an open centreline far away from the knot, along its end-to-end axis.

    Each end is extended straight along the end-to-end direction
    :math:`\hat u = (x_N - x_0)/|x_N - x_0|` to a distance :math:`R` from the centroid
    :math:`c`, and the two far points are joined through a point at :math:`2R` off
    the axis, so the closing path stays outside the sphere of radius :math:`0.8 R`
    around :math:`c`:

    .. math:: x_N + a_N \hat u,\quad c + 2R\,\hat w,\quad x_0 - a_0 \hat u,
              \qquad R = \text{extension} \times \max_i |x_i - c|.

    Parameters
    ----------
    points : (n_nodes, 3) array [m]
        Open centreline whose two ends are tails pointing away from the knot.
    extension : float
        :math:`R` over the radius of the curve's bounding sphere (> 1.5).

    Returns
    -------
    (n_nodes + 3, 3) array [m]
        Closed polygon (the last point is joined back to the first implicitly).

    Notes
    -----
    This "closure at infinity along the axis" is the standard one for knots pulled
    by their ends; it is meaningful when the tails leave the knot outward (as in a
    knot under tension), which is the case for every curve this package builds.
    """
    x = _as_nodes("points", points)
    ext = float(check_positive("extension", extension, scalar=True))
    if ext <= 1.5:
        raise InputError(f"extension must be > 1.5, got {ext:g}")
    c = x.mean(axis=0)
    rad = np.max(np.linalg.norm(x - c, axis=1))
    chord = x[-1] - x[0]
    if np.linalg.norm(chord) < 1e-12 * max(rad, 1e-300):
        raise InputError("points: the two ends coincide, the end-to-end axis is undefined")
    u = chord / np.linalg.norm(chord)
    R = ext * rad
    # a direction perpendicular to u
    trial = np.eye(3)[np.argmin(np.abs(u))]
    w = np.cross(u, trial)
    w /= np.linalg.norm(w)
    far_end = c + u * R + (x[-1] - c - u * np.dot(x[-1] - c, u))
    far_start = c - u * R + (x[0] - c - u * np.dot(x[0] - c, u))
    return np.vstack([x, far_end, c + 2.0 * R * w, far_start])


def _random_rotation(rng: np.random.Generator) -> np.ndarray:
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    a, b, c, d = q
    return np.array(
        [
            [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
            [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
            [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d],
        ]
    )


@dataclass(frozen=True)
class Crossings:
    """Crossings of a projected closed polygon (see :func:`projection_crossings`)."""

    over_pos: np.ndarray  # position along the closed polygon (segment index + fraction)
    under_pos: np.ndarray
    sign: np.ndarray  # +1 / -1
    degenerate: bool


def projection_crossings(closed_points, direction=(0.0, 0.0, 1.0)) -> Crossings:
    r"""Crossings of a closed polygon projected along ``direction``.

    The polygon's segments are intersected pairwise in the plane perpendicular to
    ``direction``; at each crossing the strand with the larger coordinate along
    ``direction`` (toward the viewer) is over. The sign of a crossing is
    :math:`\operatorname{sign}((\mathbf t_\mathrm{over}\times\mathbf t_\mathrm{under})\cdot\hat e)`.

    Parameters
    ----------
    closed_points : (n, 3) array [m]
        Closed polygon (the last node joins the first).
    direction : (3,) array
        Viewing direction :math:`\hat e` (need not be normalised).

    Returns
    -------
    Crossings
        ``over_pos``, ``under_pos`` (positions along the polygon, segment index plus
        fraction), ``sign``, and ``degenerate`` (True if a crossing fell within
        1e-9 of a vertex or two strands nearly meet in 3-D, so another direction
        should be used).
    """
    x = _as_nodes("closed_points", closed_points, min_nodes=3)
    e = check_finite("direction", direction).reshape(3)
    ne = np.linalg.norm(e)
    if ne == 0:
        raise InputError("direction must be a non-zero vector")
    e = e / ne
    trial = np.eye(3)[np.argmin(np.abs(e))]
    e1 = np.cross(e, trial)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(e, e1)
    p = np.column_stack([x @ e1, x @ e2])
    h = x @ e
    a = p
    b = np.roll(p, -1, axis=0)
    ha = h
    hb = np.roll(h, -1)
    m = len(x)
    d = b - a
    i, j = np.triu_indices(m, 2)
    keep = ~((i == 0) & (j == m - 1))
    i, j = i[keep], j[keep]
    # bounding-box prefilter
    lo = np.minimum(a, b)
    hi = np.maximum(a, b)
    ov = np.all((lo[i] <= hi[j]) & (lo[j] <= hi[i]), axis=1)
    i, j = i[ov], j[ov]
    di, dj = d[i], d[j]
    r = a[j] - a[i]
    den = di[:, 0] * dj[:, 1] - di[:, 1] * dj[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (r[:, 0] * dj[:, 1] - r[:, 1] * dj[:, 0]) / den
        u = (r[:, 0] * di[:, 1] - r[:, 1] * di[:, 0]) / den
    hit = (den != 0) & (s >= 0) & (s < 1) & (u >= 0) & (u < 1)
    i, j, s, u = i[hit], j[hit], s[hit], u[hit]
    hi_ = ha[i] + s * (hb[i] - ha[i])
    hj_ = ha[j] + u * (hb[j] - ha[j])
    scale = np.max(np.linalg.norm(d, axis=1))
    tol_v = 1e-9
    degenerate = bool(
        np.any((s < tol_v) | (s > 1 - tol_v) | (u < tol_v) | (u > 1 - tol_v))
        or np.any(np.abs(hi_ - hj_) < 1e-9 * scale)
    )
    i_over = hi_ > hj_
    over_pos = np.where(i_over, i + s, j + u)
    under_pos = np.where(i_over, j + u, i + s)
    t3 = np.column_stack([d, (hb - ha)])  # in (e1, e2, e) coordinates
    t_over = np.where(i_over[:, None], t3[i], t3[j])
    t_under = np.where(i_over[:, None], t3[j], t3[i])
    sign = np.sign(t_over[:, 0] * t_under[:, 1] - t_over[:, 1] * t_under[:, 0]).astype(int)
    return Crossings(over_pos, under_pos, sign, degenerate)


def _alexander_matrix_rows(cr: Crossings):
    """Arc indices (over, incoming under, outgoing under) and signs of each crossing."""
    n = len(cr.under_pos)
    order = np.argsort(cr.under_pos)
    under_sorted = cr.under_pos[order]
    # arc k starts at the k-th under-crossing (in sorted order) and ends at the next
    rank = np.empty(n, dtype=int)
    rank[order] = np.arange(n)
    outgoing = rank
    incoming = (rank - 1) % n
    over = (np.searchsorted(under_sorted, cr.over_pos, side="right") - 1) % n
    return over, incoming, outgoing


def _matrix(cr: Crossings, t: complex) -> np.ndarray:
    """Alexander matrix at t: rows (1-t, t, -1) or (1-t, -1, t) at (over, in, out)."""
    n = len(cr.under_pos)
    over, inc, out = _alexander_matrix_rows(cr)
    A = np.zeros((n, n), dtype=complex)
    rows = np.arange(n)
    pos = cr.sign > 0
    np.add.at(A, (rows, over), 1 - t)
    np.add.at(A, (rows, inc), np.where(pos, t, -1.0))
    np.add.at(A, (rows, out), np.where(pos, -1.0, t))
    return A


def _normalise(coeffs: np.ndarray) -> tuple[int, ...]:
    c = np.rint(coeffs.real).astype(np.int64)
    nz = np.nonzero(c)[0]
    if nz.size == 0:
        return (0,)
    c = c[nz[0] : nz[-1] + 1]
    if c.sum() < 0:
        c = -c
    return tuple(int(v) for v in c)


def _poly_from_crossings(cr: Crossings) -> tuple[int, ...]:
    n = len(cr.under_pos)
    if n <= 1:
        return (1,)
    # det of the (n-1)x(n-1) minor is a polynomial of degree <= n-1: sample n points of
    # the unit circle and invert the discrete Fourier transform (exact up to rounding).
    M = n
    ts = np.exp(2j * np.pi * np.arange(M) / M)
    vals = np.array([np.linalg.det(_matrix(cr, t)[:-1, :-1]) for t in ts])
    coeffs = np.fft.fft(vals) / M  # coefficient of t^p is mean(vals * t^-p)
    return _normalise(coeffs)


@dataclass(frozen=True)
class KnotInvariant:
    """Alexander polynomial (coefficients of t^0, t^1, ...) and knot determinant."""

    alexander: tuple[int, ...]
    determinant: int
    crossings: int

    @property
    def name(self) -> str:
        """Knot name (``"0_1"``, ``"3_1"``, ...) if the polynomial is in the table, else ``"?"``."""
        return identify_knot(self.alexander)


def _invariant_once(closed: np.ndarray, rot: np.ndarray) -> tuple[KnotInvariant, bool]:
    cr = projection_crossings(closed @ rot.T)
    poly = _poly_from_crossings(cr)
    det = abs(int(np.sum(np.array(poly) * (-1) ** np.arange(len(poly)))))
    return KnotInvariant(poly, det, len(cr.under_pos)), cr.degenerate


def knot_invariant(points, *, closed: bool = False, n_projections: int = 3, seed: int = 0):
    r"""Alexander polynomial and determinant of a centreline, checked on several projections.

    Parameters
    ----------
    points : (n_nodes, 3) array [m]
        Centreline; open (closed with :func:`close_curve`) unless ``closed``.
    closed : bool
        True if ``points`` already is a closed polygon.
    n_projections : int
        Number of random viewing directions; all must agree (>= 1).
    seed : int
        Seed of the random rotations (the answer does not depend on it).

    Returns
    -------
    KnotInvariant

    Raises
    ------
    InputError
        If the projections disagree (the curve self-intersects in 3-D, to rounding).
    """
    x = _as_nodes("points", points, min_nodes=3 if closed else 2)
    if int(n_projections) < 1:
        raise InputError(f"n_projections must be >= 1, got {n_projections}")
    closed_pts = x if closed else close_curve(x)
    closed_pts = closed_pts - closed_pts.mean(axis=0)
    rng = np.random.default_rng(seed)
    found: list[KnotInvariant] = []
    attempts = 0
    while len(found) < int(n_projections):
        attempts += 1
        if attempts > 10 * int(n_projections) + 10:
            raise InputError("points: no generic projection found (curve self-intersects?)")
        inv, degenerate = _invariant_once(closed_pts, _random_rotation(rng))
        if not degenerate:
            found.append(inv)
    polys = {f.alexander for f in found}
    if len(polys) != 1:
        raise InputError(
            "points: projections disagree on the Alexander polynomial "
            f"({sorted(polys)}); the curve touches itself"
        )
    return found[0]


def alexander_polynomial(points, *, closed: bool = False, seed: int = 0) -> tuple[int, ...]:
    r"""Alexander polynomial :math:`\Delta(t)` of a (closed) centreline.

    Returns the integer coefficients of :math:`t^0, t^1, \dots`, normalised so that
    the lowest power is 0 and :math:`\Delta(1) = 1`; e.g. ``(1, -1, 1)`` for the trefoil.
    See :func:`knot_invariant` for the arguments.
    """
    return knot_invariant(points, closed=closed, seed=seed).alexander


def knot_determinant(points, *, closed: bool = False, seed: int = 0) -> int:
    r"""Knot determinant :math:`|\Delta(-1)|`: 1 unknot, 3 trefoil, 5 figure-eight, m for T(2,m)."""
    return knot_invariant(points, closed=closed, seed=seed).determinant


def torus_knot_polynomial(m: int) -> tuple[int, ...]:
    r"""Alexander polynomial of the :math:`(2, m)` torus knot, m odd >= 1.

    .. math:: \Delta_{T(2,m)}(t) = \frac{t^m + 1}{t + 1} = \sum_{i=0}^{m-1} (-t)^i
    """
    m = int(m)
    if m < 1 or m % 2 == 0:
        raise InputError(f"m must be an odd integer >= 1, got {m}")
    return tuple(int((-1) ** i) for i in range(m))


_TABLE = {
    (1,): "0_1",
    (1, -1, 1): "3_1",
    (-1, 3, -1): "4_1",
    (1, -1, 1, -1, 1): "5_1",
    (2, -3, 2): "5_2",
    (1, -1, 1, -1, 1, -1, 1): "7_1",
    (1, -1, 1, -1, 1, -1, 1, -1, 1): "9_1",
}


def identify_knot(alexander) -> str:
    """Name (Rolfsen table) of a knot from its normalised Alexander polynomial, or ``"?"``.

    Covers the knots this package meets: 0_1, 3_1, 4_1, 5_1, 5_2, 7_1, 9_1. The Alexander
    polynomial does not tell a knot from its mirror image, nor every pair of knots apart;
    for detecting a strand passing through another it is enough.
    """
    return _TABLE.get(tuple(int(v) for v in alexander), "?")


def winding_number(points, *, axis_point=(0.0, 0.0, 0.0), axis_direction=(0.0, 0.0, 1.0)):
    r"""Signed number of turns a centreline makes about an axis.

    .. math:: w = \frac{1}{2\pi}\sum_i \Delta\varphi_i,

    with :math:`\varphi` the polar angle of each node in the plane perpendicular to
    the axis (increments taken in :math:`(-\pi, \pi]`).

    Parameters
    ----------
    points : (n_nodes, 3) array [m]
    axis_point : (3,) array [m]
    axis_direction : (3,) array

    Returns
    -------
    float
        Turns about the axis, positive counter-clockwise looking against ``axis_direction``.
    """
    x = _as_nodes("points", points)
    a = check_finite("axis_direction", axis_direction).reshape(3)
    if np.linalg.norm(a) == 0:
        raise InputError("axis_direction must be a non-zero vector")
    a = a / np.linalg.norm(a)
    p0 = check_finite("axis_point", axis_point).reshape(3)
    e1 = np.cross(a, np.eye(3)[np.argmin(np.abs(a))])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    r = x - p0
    phi = np.arctan2(r @ e2, r @ e1)
    dphi = np.diff(phi)
    dphi = (dphi + np.pi) % (2 * np.pi) - np.pi
    return float(dphi.sum() / (2 * np.pi))


def post_crossing_code(
    points,
    *,
    axis_point=(0.0, 0.0, 0.0),
    axis_direction=(0.0, 0.0, 1.0),
    max_radius: float | None = None,
):
    r"""Over/under sequence of a rod's self-crossings seen from a post's axis.

    The rod is mapped to the unrolled cylinder :math:`(\varphi R_0, z)` around the axis
    (:math:`\varphi` continuous along the rod, :math:`R_0` the mean radial distance), and
    its self-crossings on the cylinder modulo :math:`2\pi` are found; at each one the
    strand farther from the axis is *over*. Walking along the rod, each crossing is met
    twice; the returned string lists ``"O"`` or ``"U"`` at each passage, in order.

    For a clove hitch this is ``"UOOU"``-like (its two nips: the working end passes under
    the first wrap, the second wrap over it); the code, together with
    :func:`winding_number`, does not change unless a strand passes through another
    or through the post. Free tails far from the post may legitimately swing over or
    under other strands (Reidemeister moves add crossing pairs); ``max_radius`` keeps
    only the segments within that distance of the axis (the knot's core on the post).

    Parameters
    ----------
    points : (n_nodes, 3) array [m]
    axis_point, axis_direction : (3,) arrays
        The post axis.
    max_radius : float, optional [m]
        Only segments whose two nodes lie within this distance of the axis count.

    Returns
    -------
    str
        Sequence of ``"O"``/``"U"`` along the rod.
    """
    x = _as_nodes("points", points)
    a = check_finite("axis_direction", axis_direction).reshape(3)
    if np.linalg.norm(a) == 0:
        raise InputError("axis_direction must be a non-zero vector")
    a = a / np.linalg.norm(a)
    p0 = check_finite("axis_point", axis_point).reshape(3)
    e1 = np.cross(a, np.eye(3)[np.argmin(np.abs(a))])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    r = x - p0
    phi = np.unwrap(np.arctan2(r @ e2, r @ e1))
    rho = np.hypot(r @ e1, r @ e2)
    z = r @ a
    R0 = float(np.mean(rho))
    events: list[tuple[float, str]] = []
    n = len(x)
    # compare the rod with copies of itself shifted by whole turns on the unrolled cylinder
    kmax = int(np.ceil((phi.max() - phi.min()) / (2 * np.pi))) + 1
    for k in range(-kmax, kmax + 1):
        y = np.column_stack([(phi + 2 * np.pi * k) * R0, z, rho])
        base = np.column_stack([phi * R0, z, rho])
        # segments of base (index i) against segments of shifted copy (index j)
        a0, a1 = base[:-1, :2], base[1:, :2]
        b0, b1 = y[:-1, :2], y[1:, :2]
        ii, jj = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
        ii, jj = ii.ravel(), jj.ravel()
        m = np.abs(ii - jj) > 1 if k == 0 else np.ones(ii.size, bool)
        if max_radius is not None:
            near = (rho[:-1] <= max_radius) & (rho[1:] <= max_radius)
            m &= near[ii] & near[jj]
        ii, jj = ii[m], jj[m]
        da = a1[ii] - a0[ii]
        db = b1[jj] - b0[jj]
        rr = b0[jj] - a0[ii]
        den = da[:, 0] * db[:, 1] - da[:, 1] * db[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (rr[:, 0] * db[:, 1] - rr[:, 1] * db[:, 0]) / den
            u = (rr[:, 0] * da[:, 1] - rr[:, 1] * da[:, 0]) / den
        hit = (den != 0) & (s >= 0) & (s < 1) & (u >= 0) & (u < 1)
        for i_, j_, s_, u_ in zip(ii[hit], jj[hit], s[hit], u[hit], strict=True):
            rho_i = rho[i_] + s_ * (rho[i_ + 1] - rho[i_])
            rho_j = rho[j_] + u_ * (rho[j_ + 1] - rho[j_])
            events.append((i_ + s_, "O" if rho_i > rho_j else "U"))
    events.sort()
    return "".join(ev for _, ev in events)
