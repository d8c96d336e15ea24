r"""Two half hitches, and a round turn and two half hitches, on a post: the start centreline.

Coordinates: the post is the z axis (radius D/2), the rod centreline touches it at radius
:math:`R = (D+d)/2`. End 0 (node 0) is the *standing end* (the loaded one), the last node
the *working end* (free or lightly loaded).

**Two half hitches** (``wrap_angle`` :math:`\pi`, a *turn*) and **round turn and two half
hitches** (``wrap_angle`` :math:`3\pi`, a *round turn*): the standing part runs along
:math:`y = -R` from :math:`x = X` to the post, wraps it by the wrap angle (a helix of pitch
1.15 d per turn, so that the strands of a round turn pass side by side) and leaves at
:math:`y = +R` parallel to the standing part; the working part then crosses over to the
standing part (a cubic Hermite connector) and ties two half hitches round it: two turns
about the standing part in the same sense, the second tucked under the diagonal between
them. Two half hitches in the same sense are a clove hitch tied round the standing part,
so this part of the curve is :func:`knotmech.scenes.curves.clove_hitch_curve`'s core on a
"post" that is the standing part itself (axis +x, wrap radius d: touching it). The working
end leaves from the top of the standing part along -y.
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import check_positive
from knotmech.scenes.curves import KnotCurve, _clove_core
from knotmech.scenes.hitch_curves._parts import (
    PITCH,
    _arc,
    _check_room,
    _check_sizes,
    _finish,
    _hermite,
    _line,
)

__all__ = ["two_half_hitches_curve", "knotted_length"]


def two_half_hitches_curve(
    *,
    post_diameter: float,
    rod_diameter: float,
    rod_length: float,
    n_nodes: int,
    wrap_angle: float = np.pi,
    gap: float = 1.15,
    lift: float = 1.15,
) -> KnotCurve:
    r"""Two half hitches round the standing part after a turn (or round turn) on the post.

    Parameters
    ----------
    post_diameter, rod_diameter, rod_length : float [m]
    n_nodes : int
    wrap_angle : float [rad]
        Angle the rod wraps the post: :math:`\pi` (a turn: two half hitches) or
        :math:`3\pi` (a round turn: round turn and two half hitches); an odd multiple of
        :math:`\pi` so that the working part leaves parallel to the standing part.
    gap, lift : float
        Axial gap and radial lift of the half hitches, in rod diameters (as the clove
        hitch's).

    Returns
    -------
    KnotCurve
        Parts ``standing``, ``wrap``, ``connector``, ``hitches``, ``tail`` (the working
        end); ``info``: ``wrap_radius`` R, ``wrap_angle``, ``hitch_center`` [m].
    """
    D, d, L, N, g, lf = _check_sizes(post_diameter, rod_diameter, rod_length, n_nodes,
                                     gap=gap, lift=lift)  # fmt: skip
    th = float(check_positive("wrap_angle", wrap_angle, scalar=True))
    pieces, info = _thh_pieces(D, d, th, g, lf)
    wrap, conn, core = pieces
    R = 0.5 * (D + d)
    ds = 0.05 * d
    fixed = info["x_far_min"] + sum(float(_arc(p)[-1]) for p in pieces)
    rest = _check_room(fixed, L, D, d, ends="tail")
    # the spare length goes half to the standing part, half to the working end's tail
    x_far = info["x_far_min"] + 0.5 * rest
    stand = _line(np.array([x_far, -R, 0.0]), (-1.0, 0.0, 0.0), x_far, ds)
    tail = _line(core[-1], (0.0, -1.0, 0.0), 0.5 * rest, ds)  # the tangent e2 at psi = 4 pi
    nodes, parts, info = _finish(
        [stand, wrap, conn, core, tail],
        ["standing", "wrap", "connector", "hitches", "tail"],
        N,
        d,
        info,
    )
    return KnotCurve(nodes=nodes, rod_radius=0.5 * d, parts=parts, info=info)


def _thh_pieces(D, d, th, g, lf):
    """Dense wrap, connector and half hitches of :func:`two_half_hitches_curve`."""
    R = 0.5 * (D + d)
    ds = 0.05 * d
    # the wrap: psi decreasing from -pi/2 (the standing part arrives along -x at y = -R)
    m = max(64, int(np.ceil(th * R / ds)))
    phi = -0.5 * np.pi - np.linspace(0.0, th, m)
    zr = PITCH * d * (phi[0] - phi) / (2 * np.pi)
    wrap = np.column_stack([R * np.cos(phi), R * np.sin(phi), zr])
    # half hitches: the clove core round the standing part (axis +x through (., -R, 0)),
    # e1 = +z (entry on top of the standing part), e2 = a x e1 = -y; wrap radius d
    x_in = 2.0 * R + 2.0 * d  # where the working part meets the standing part
    psi, zc, rho, zt, zw = _clove_core(d, d, g, lf, max(400, int(np.ceil(4 * np.pi * d / ds))))
    xc = x_in + zt
    e1, e2 = np.array([0.0, 0.0, 1.0]), np.array([0.0, -1.0, 0.0])
    core = (
        np.array([xc, -R, 0.0])
        + (rho * np.cos(psi))[:, None] * e1
        + (rho * np.sin(psi))[:, None] * e2
        + zc[:, None] * np.array([1.0, 0.0, 0.0])
    )
    p0, p1 = wrap[-1], core[0]
    t1 = core[1] - core[0]
    t1 /= np.linalg.norm(t1)
    k = np.linalg.norm(p1 - p0)
    conn = _hermite(p0, np.array([1.0, 0.0, 0.0]) * 1.2 * k, p1, t1 * 1.2 * k,
                    max(200, int(np.ceil(3 * k / ds))))  # fmt: skip
    info = {"wrap_radius": R, "wrap_angle": th, "hitch_center": (xc, -R, 0.0),
            "x_far_min": xc + zw + 4 * d, "hitch_wrap_height": zw}  # fmt: skip
    return (wrap, conn, core), info


def knotted_length(post_diameter: float, rod_diameter: float, *, wrap_angle: float) -> float:
    """Length [m] of the knotted part (the standing part's run past the half hitches
    included) at post diameter ``post_diameter`` and rod diameter ``rod_diameter`` [m]."""
    pieces, info = _thh_pieces(post_diameter, rod_diameter, wrap_angle, 1.15, 1.15)
    return info["x_far_min"] + sum(float(_arc(p)[-1]) for p in pieces)
