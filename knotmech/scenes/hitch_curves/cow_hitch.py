r"""Cow hitch (girth hitch, lark's head) on a post: the start centreline.

Coordinates: the post is the z axis (radius D/2), the rod centreline touches it at radius
:math:`R = (D+d)/2`. End 0 (node 0) is the *standing end* (the loaded one), the last node
the *working end* (free or lightly loaded).

**Cow hitch** (girth hitch, lark's head): two half hitches on the post in *opposite*
senses. In cylindrical coordinates :math:`(\psi, z, \rho)` about the post, leg 0 arrives
tangentially at :math:`\psi = 0` at height :math:`-z_t`, runs down to :math:`-z_w` and once
round the post plus :math:`\beta`; a U-turn (the bight, a half circle of radius
:math:`z_w` on the unrolled cylinder) brings it to :math:`+z_w`, and it runs back once round
in the opposite sense and leaves at :math:`+z_t`, tangentially at :math:`\psi = 0`. Both legs
leave the post side by side in the same direction (+x), and the bight, lifted off the post
by 1.15 d over the front, lies over both legs: the legs pass through the bight.
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import check_range
from knotmech.scenes.curves import KnotCurve, _smoothstep
from knotmech.scenes.hitch_curves._parts import _arc, _check_room, _check_sizes, _finish, _line

__all__ = ["cow_hitch_curve", "knotted_length"]


def cow_hitch_curve(
    *,
    post_diameter: float,
    rod_diameter: float,
    rod_length: float,
    n_nodes: int,
    gap: float = 1.15,
    lift: float = 1.15,
    beta: float = 1.2,
) -> KnotCurve:
    r"""Cow (girth) hitch on the post: two half hitches in opposite senses, legs side by side.

    Parameters
    ----------
    post_diameter, rod_diameter, rod_length : float [m]
    n_nodes : int
    gap, lift : float
        Axial gap between the legs (and a leg and the wrap next to it) and radial lift of
        the bight over the legs, in rod diameters.
    beta : float [rad]
        How far past one full turn the bight reaches (its U-turn), beyond the legs'
        run-in to the wraps.

    Returns
    -------
    KnotCurve
        Parts ``leg0``, ``wrap1``, ``bight``, ``wrap2``, ``leg1``; both legs leave along
        +x at heights -/+ gap d/2.
    """
    D, d, L, N, g, lf = _check_sizes(post_diameter, rod_diameter, rod_length, n_nodes,
                                     gap=gap, lift=lift)  # fmt: skip
    b = float(check_range("beta", beta, 0.5, 3.0, scalar=True))
    core, n_a, n_u, zt, zw = _cow_core(D, d, g, lf, b)
    R = 0.5 * (D + d)
    ds = 0.05 * d
    lc = float(_arc(core)[-1])
    tail = 0.5 * _check_room(lc, L, D, d)
    # both legs run along -e2 = +x, the exact tangent at psi = 0 (the run-ins are flat there)
    leg0 = _line(core[0], (1.0, 0.0, 0.0), tail, ds)[::-1]  # from the far end in to the post
    leg1 = _line(core[-1], (1.0, 0.0, 0.0), tail, ds)
    nodes, parts, info = _finish(
        [leg0, core[:n_a], core[n_a - 1 : n_a + n_u], core[n_a + n_u - 1 :], leg1],
        ["leg0", "wrap1", "bight", "wrap2", "leg1"],
        N,
        d,
        {
            "wrap_radius": R,
            "wrap_angle": 2 * np.pi,
            "leg_height": zt,
            "wrap_height": zw,
            "core_length": lc,
        },  # fmt: skip
    )
    return KnotCurve(nodes=nodes, rod_radius=0.5 * d, parts=parts, info=info)


def _cow_core(D, d, g, lf, b):
    """Dense core of :func:`cow_hitch_curve`: (points, n wrap1, n bight, z_t, z_w)."""
    R = 0.5 * (D + d)
    ds = 0.05 * d
    zt = 0.5 * g * d
    zw = zt + g * d
    run = 0.6
    ru = zw / R  # angular radius of the U-turn on the unrolled cylinder
    psi_u = 2 * np.pi + b - ru
    m = max(200, int(np.ceil(psi_u * R / ds)))
    psa = np.linspace(0.0, psi_u, m)
    za = -zt - (zw - zt) * _smoothstep(psa / run)
    tau = np.linspace(-0.5 * np.pi, 0.5 * np.pi, max(60, int(np.ceil(np.pi * zw / ds))))
    psu = psi_u + ru * np.cos(tau)
    zu = zw * np.sin(tau)
    psb = psa[::-1]
    zb = zt + (zw - zt) * _smoothstep(psb / run)
    psi = np.concatenate([psa, psu[1:], psb[1:]])
    z = np.concatenate([za, zu[1:], zb[1:]])
    # the bight (psi from 2 pi - w0 to the U-turn) lifted over the legs
    w0 = 0.6
    lo, hi = 2 * np.pi - w0, 2 * np.pi
    up = np.where(psi < hi, _smoothstep((psi - lo) / w0), 1.0)
    rho = R + lf * d * up * (psi > lo)
    e1, e2 = np.array([0.0, 1.0, 0.0]), np.array([-1.0, 0.0, 0.0])
    core = (rho * np.cos(psi))[:, None] * e1 + (rho * np.sin(psi))[:, None] * e2
    core = core + z[:, None] * np.array([0.0, 0.0, 1.0])
    n_a, n_u = len(psa), len(psu) - 1
    return core, n_a, n_u, zt, zw


def knotted_length(post_diameter: float, rod_diameter: float) -> float:
    """Length [m] of the knotted part (the two wraps and the bight) at post diameter
    ``post_diameter`` and rod diameter ``rod_diameter`` [m]."""
    return float(_arc(_cow_core(post_diameter, rod_diameter, 1.15, 1.15, 1.2)[0])[-1])
