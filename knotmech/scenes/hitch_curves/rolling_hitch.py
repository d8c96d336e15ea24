r"""Rolling hitch (Magnus hitch, ABoK #1734-#1735) on a pole: the start centreline.

Coordinates: the post is the z axis (radius D/2), the rod centreline touches it at radius
:math:`R = (D+d)/2`. End 0 (node 0) is the *standing end* (the loaded one), the last node
the *working end* (free or lightly loaded).

**Rolling hitch**: the hitch that takes a pull *along* the pole. In cylindrical coordinates
:math:`(\psi, z, \rho)` about the pole (:math:`\psi = 0` the front), the standing part lies
along the pole at :math:`\psi = 0`, coming up from :math:`z \to -\infty` (the side of the
load); at :math:`z = -r_b` it bends (a quarter circle of radius :math:`r_b` on the unrolled
cylinder) into the first turn at :math:`z = 0`. Two *riding turns* then wind down the pole
towards the load, each crossing over the standing part on the front (lifted over it at
:math:`\psi = 2\pi` and :math:`4\pi`, at :math:`z = -s_1` and :math:`-s_1 - g d`,
:math:`s_1 = r_b + g d`). Half a turn further, on the back (:math:`\psi = 5\pi`), a
*diagonal* lifted over the turns climbs to the other side of the standing part's bend,
:math:`z_3 > 0`, and a last turn there (the half hitch) ends tucked under the diagonal: the
working end leaves the back of the pole perpendicular to it (along +x) at height
:math:`z_t`, between the first turn and the last. Pulled along -z (the load's side), the
riding turns jam the standing part against the pole.
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import check_range
from knotmech.scenes.curves import KnotCurve, _smoothstep
from knotmech.scenes.hitch_curves._parts import _arc, _check_room, _check_sizes, _finish, _line

__all__ = ["rolling_hitch_curve", "knotted_length"]

#: half-width [rad] of the diagonal on the back (as the clove hitch's)
_ALPHA = 0.5
#: half-width [rad] of the lift of a riding turn over the standing part
_RIDE = 0.8
#: angle [rad] over which the working end runs in to its height
_RUN = 0.9
#: how far [rad] before the back the diagonal is centred
_SHIFT = 0.25


def rolling_hitch_curve(
    *,
    post_diameter: float,
    rod_diameter: float,
    rod_length: float,
    n_nodes: int,
    gap: float = 1.3,
    lift: float = 1.15,
    bend: float = 1.2,
) -> KnotCurve:
    r"""Rolling (Magnus) hitch on the pole: two riding turns over the standing part, then a
    half hitch on the other side.

    Parameters
    ----------
    post_diameter, rod_diameter, rod_length : float [m]
    n_nodes : int
    gap, lift : float
        Axial distance between neighbouring turns and radial lift of the strands that
        cross over others, in rod diameters.
    bend : float
        Radius :math:`r_b` of the standing part's bend into the first turn, in rod
        diameters.

    Returns
    -------
    KnotCurve
        Parts ``standing`` (along the pole, -z), ``turns`` (the bend and the two riding
        turns), ``diagonal``, ``half_hitch``, ``tail`` (the working end, along +x);
        ``info``: ``wrap_radius`` R, ``wrap_angle`` (7 pi), ``z_levels`` [m].
    """
    D, d, L, N, g, lf = _check_sizes(post_diameter, rod_diameter, rod_length, n_nodes,
                                     gap=gap, lift=lift, gap_min=1.1)  # fmt: skip
    rb = float(check_range("bend", bend, 1.0, 10.0, scalar=True))
    pieces, marks, info = _core(D, d, g, lf, rb)
    lc = sum(float(_arc(p)[-1]) for p in pieces)
    tail = 0.5 * _check_room(lc, L, D, d)
    ds = 0.05 * d
    bend_piece, core = pieces
    standing = _line(bend_piece[0], (0.0, 0.0, -1.0), tail, ds)[::-1]
    working = _line(core[-1], (1.0, 0.0, 0.0), tail, ds)
    a, b = marks
    nodes, parts, info = _finish(
        [standing, np.vstack([bend_piece, core[1:a]]), core[a - 1 : b], core[b - 1 :], working],
        ["standing", "turns", "diagonal", "half_hitch", "tail"],
        N,
        d,
        {**info, "core_length": lc},
    )
    return KnotCurve(nodes=nodes, rod_radius=0.5 * d, parts=parts, info=info)


def _hermite1(x, x0, y0, m0, x1, y1, m1):
    """Cubic Hermite y(x) from (x0, y0, slope m0) to (x1, y1, slope m1)."""
    h = x1 - x0
    s = (np.asarray(x) - x0) / h
    return ((2 * s**3 - 3 * s**2 + 1) * y0 + (s**3 - 2 * s**2 + s) * h * m0
            + (-2 * s**3 + 3 * s**2) * y1 + (s**3 - s**2) * h * m1)  # fmt: skip


def _bump(psi, centre, width, flat=0.0):
    """Bump of half-width ``width`` [rad] at ``centre``: 1 within ``flat`` x width of it,
    falling as cos^2 to 0 at ``width``."""
    u = np.clip((np.abs(psi - centre) / width - flat) / (1.0 - flat), 0.0, None)
    return np.where(u < 1.0, np.cos(0.5 * np.pi * u) ** 2, 0.0)


def _core(D, d, g, lf, rb):
    """Dense bend and core of :func:`rolling_hitch_curve`: ([bend, core], (index of the
    diagonal's start, of its end) in core, info)."""
    R = 0.5 * (D + d)
    r_b = rb * d
    ds = 0.05 * d
    s1 = r_b + g * d  # the first crossing: below the bend by a turn's gap
    slope = -g * d / (2 * np.pi)  # the riding turns' helix [m/rad]
    # the bend: a quarter circle on the unrolled cylinder (u = R psi, z), centre (r_b, -r_b)
    th = np.linspace(np.pi, 0.5 * np.pi, max(40, int(np.ceil(0.5 * np.pi * r_b / ds))))
    ub, zb = r_b + r_b * np.cos(th), -r_b + r_b * np.sin(th)
    psb = ub / R
    p0 = r_b / R
    m = max(800, int(np.ceil(7 * np.pi * R / ds)))
    psi = np.linspace(p0, 7 * np.pi, m)
    # the diagonal, centred a little before the back so that it has climbed past the
    # working end's height before that end leaves (at psi = 7 pi, the back)
    c5 = 5 * np.pi - _SHIFT
    a0, a1 = c5 - _ALPHA, c5 + _ALPHA
    z_a = -s1 + slope * (a0 - 2 * np.pi)
    z1 = _hermite1(psi, p0, 0.0, 0.0, 2 * np.pi, -s1, slope)  # the first riding turn
    # the working end's height: a gap above the first turn where it leaves under the diagonal
    back = (psi > np.pi - _RUN) & (psi < np.pi + _ALPHA)
    z_t = float(z1[back].max()) + g * d
    z3 = z_t + g * d
    z = np.where(psi < 2 * np.pi, z1, -s1 + slope * (psi - 2 * np.pi))
    z = np.where(psi > a0, _hermite1(psi, a0, z_a, slope, a1, z3, 0.0), z)
    z = np.where(psi > a1, z_t + (z3 - z_t) * _smoothstep((7 * np.pi - psi) / _RUN), z)
    # the riding turns lifted over the standing part: at least 2.2 d of arc either side
    ride = max(_RIDE, 2.2 * d / R)
    lift = lf * d * (_bump(psi, 2 * np.pi, ride, 0.3) + _bump(psi, 4 * np.pi, ride, 0.3))
    # the diagonal passes over the working end, a straight tangent there (<= R / cos 0.3)
    lift += (lf * d + R * (1 / np.cos(0.3) - 1)) * _bump(psi, c5, _ALPHA + 0.6, 0.3)
    rho = R + lift
    e1, e2, ez = np.array([0.0, 1.0, 0.0]), np.array([-1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])

    def cyl(r, ps, zz):
        return (r * np.cos(ps))[:, None] * e1 + (r * np.sin(ps))[:, None] * e2 + zz[:, None] * ez

    bend_piece = cyl(np.full_like(psb, R), psb, zb)
    core = cyl(rho, psi, z)
    marks = (int(np.searchsorted(psi, a0)) + 1, int(np.searchsorted(psi, a1)) + 1)
    info = {"wrap_radius": R, "wrap_angle": 7 * np.pi, "bend_radius": r_b,
            "z_levels": {"first_crossing": -s1, "second_crossing": -s1 - g * d,
                         "working_end": z_t, "half_hitch": z3}}  # fmt: skip
    return [bend_piece, core], marks, info


def knotted_length(post_diameter: float, rod_diameter: float) -> float:
    """Length [m] of the knotted part (the bend, the riding turns, the diagonal and the half
    hitch) at post diameter ``post_diameter`` and rod diameter ``rod_diameter`` [m]."""
    pieces, _, _ = _core(post_diameter, rod_diameter, 1.3, 1.15, 1.2)
    return sum(float(_arc(p)[-1]) for p in pieces)
