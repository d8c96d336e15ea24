r"""Post hitches from parametric centrelines: two half hitches, round turn and two half
hitches, cow (girth) hitch; their closure and invariants.

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

**Cow hitch** (girth hitch, lark's head): two half hitches on the post in *opposite*
senses. In cylindrical coordinates :math:`(\psi, z, \rho)` about the post, leg 0 arrives
tangentially at :math:`\psi = 0` at height :math:`-z_t`, runs down to :math:`-z_w` and once
round the post plus :math:`\beta`; a U-turn (the bight, a half circle of radius
:math:`z_w` on the unrolled cylinder) brings it to :math:`+z_w`, and it runs back once round
in the opposite sense and leaves at :math:`+z_t`, tangentially at :math:`\psi = 0`. Both legs
leave the post side by side in the same direction (+x), and the bight, lifted off the post
by 1.15 d over the front, lies over both legs: the legs pass through the bight.

Knot type (:func:`hitch_invariants`): the rod closed far away (each end extended along its
tail, the two far points joined at twice that distance without circling the post) has an
Alexander polynomial, and its winding number about the post axis is an integer (the
linking number of rod and post). Both are unchanged unless a strand passes through another
or through the post.
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError, check_positive, check_range
from knotmech.scenes.curves import KnotCurve, min_separation, resample_polyline
from knotmech.scenes.topology import knot_invariant, winding_number

__all__ = [
    "HITCH_KNOTS",
    "two_half_hitches_curve",
    "cow_hitch_curve",
    "hitch_curve",
    "hitch_rod_length",
    "hitch_closure",
    "hitch_invariants",
]

#: knots tied by :func:`hitch_curve` -> post wrap angle of the standing part [rad]
HITCH_KNOTS = {
    "two_half_hitches": np.pi,
    "round_turn_two_half_hitches": 3 * np.pi,
    "cow_hitch": 2 * np.pi,
}

PITCH = 1.15  #: axial distance [d] per turn of the strands that pass side by side


def _smoothstep(u):
    u = np.clip(u, 0.0, 1.0)
    return u * u * (3 - 2 * u)


def _clove_core(R: float, d: float, gap: float, lift: float, m: int):
    """(psi, z, rho) of two same-sense wraps joined by a lifted diagonal (as
    :func:`knotmech.scenes.curves.clove_hitch_curve`, psi in [0, 4 pi])."""
    zt = 0.5 * gap * d
    zw = zt + gap * d
    alpha = 0.5
    psi = np.linspace(0.0, 4 * np.pi, m)
    run = 0.9
    z = np.where(
        psi < 2 * np.pi,
        -zt - (zw - zt) * _smoothstep(psi / run),
        zt + (zw - zt) * _smoothstep((4 * np.pi - psi) / run),
    )
    diag = np.abs(psi - 2 * np.pi) < alpha
    u = (psi - 2 * np.pi + alpha) / (2 * alpha)
    z = np.where(diag, -zw + 2 * zw * _smoothstep(u), z)
    bump_w = alpha + 0.6
    bump = np.where(
        np.abs(psi - 2 * np.pi) < bump_w,
        np.cos(0.5 * np.pi * (psi - 2 * np.pi) / bump_w) ** 2,
        0.0,
    )
    rho = R + (lift * d + R * (1 / np.cos(0.2) - 1)) * bump
    return psi, z, rho, zt, zw


def _hermite(p0, t0, p1, t1, n):
    """Cubic Hermite curve from p0 (tangent t0) to p1 (tangent t1), n points."""
    s = np.linspace(0.0, 1.0, n)[:, None]
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    return h00 * p0 + h10 * t0 + h01 * p1 + h11 * t1


def _arc(p):
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])


def _line(p0, direction, length, ds):
    u = np.asarray(direction, float) / np.linalg.norm(direction)
    k = max(2, int(np.ceil(length / ds)) + 1)
    return p0 + np.linspace(0.0, length, k)[:, None] * u


def _finish(pieces, names, n_nodes, d, info):
    """Join dense pieces (each starting where the previous ended), resample to n_nodes
    equal edges, and map the piece boundaries to node ranges."""
    dense = [pieces[0]] + [p[1:] for p in pieces[1:]]
    lengths = [float(_arc(p)[-1]) for p in pieces]
    p = np.vstack(dense)
    L = float(_arc(p)[-1])
    nodes = resample_polyline(p, n_nodes)
    marks = np.rint(np.cumsum([0.0] + lengths) / L * (n_nodes - 1)).astype(int)
    parts = {nm: (int(marks[k]), int(marks[k + 1]) + (k == len(names) - 1))
             for k, nm in enumerate(names)}  # fmt: skip
    info = {**info, "rod_length": L, "min_separation": min_separation(nodes, rod_radius=0.5 * d)}
    return nodes, parts, info


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
    D = float(check_positive("post_diameter", post_diameter))
    d = float(check_positive("rod_diameter", rod_diameter))
    L = float(check_positive("rod_length", rod_length))
    th = float(check_positive("wrap_angle", wrap_angle))
    g = float(check_range("gap", gap, 1.0, 50.0))
    lf = float(check_range("lift", lift, 1.0, 10.0))
    N = int(n_nodes)
    if N < 40:
        raise InputError(f"n_nodes must be >= 40, got {n_nodes!r}")
    pieces, info = _thh_pieces(D, d, th, g, lf)
    wrap, conn, core = pieces
    R = 0.5 * (D + d)
    ds = 0.05 * d
    fixed = info["x_far_min"] + sum(float(_arc(p)[-1]) for p in pieces)
    rest = L - fixed
    if rest < 2 * 4 * d:
        raise InputError(
            f"rod_length must be at least {fixed + 8 * d:.3g} m for this hitch (post "
            f"{D:g} m, rod {d:g} m: the knotted part and 4 d of each tail), got {L:g}"
        )
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
    D = float(check_positive("post_diameter", post_diameter))
    d = float(check_positive("rod_diameter", rod_diameter))
    L = float(check_positive("rod_length", rod_length))
    g = float(check_range("gap", gap, 1.0, 50.0))
    lf = float(check_range("lift", lift, 1.0, 10.0))
    b = float(check_range("beta", beta, 0.5, 3.0))
    N = int(n_nodes)
    if N < 40:
        raise InputError(f"n_nodes must be >= 40, got {n_nodes!r}")
    core, n_a, n_u, zt, zw = _cow_core(D, d, g, lf, b)
    R = 0.5 * (D + d)
    ds = 0.05 * d
    lc = float(_arc(core)[-1])
    tail = 0.5 * (L - lc)
    if tail < 4 * d:
        raise InputError(
            f"rod_length must be at least {lc + 8 * d:.3g} m for this hitch (post {D:g} m, "
            f"rod {d:g} m: the knotted part and 4 d of each leg), got {L:g}"
        )
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


def _check_knot(knot: str) -> str:
    if knot not in HITCH_KNOTS:
        raise InputError(f"knot must be one of {', '.join(HITCH_KNOTS)}, got {knot!r}")
    return knot


TAIL = 0.064  #: [m] default extra tail length (the clove-hitch paper's rod: 64 mm tails)
EDGE = 0.374 / 119  #: [m] default edge length (the clove-hitch scene's 120 nodes on 374 mm)


def hitch_rod_length(knot: str, *, post_diameter: float, rod_diameter: float,
                     tail: float = TAIL) -> float:  # fmt: skip
    """Default rod length [m] of a hitch: its knotted part (the standing part's run past the
    half hitches included), 4 d at each end and ``tail`` [m] more at each end."""
    D = float(check_positive("post_diameter", post_diameter))
    d = float(check_positive("rod_diameter", rod_diameter))
    t = float(check_positive("tail", tail))
    if _check_knot(knot) == "cow_hitch":
        core = float(_arc(_cow_core(D, d, 1.15, 1.15, 1.2)[0])[-1])
    else:
        pieces, info = _thh_pieces(D, d, HITCH_KNOTS[knot], 1.15, 1.15)
        core = info["x_far_min"] + sum(float(_arc(p)[-1]) for p in pieces)
    return core + 8 * d + 2 * t


def hitch_curve(
    knot: str,
    *,
    post_diameter: float,
    rod_diameter: float,
    rod_length: float | None = None,
    n_nodes: int | None = None,
) -> KnotCurve:
    """The start centreline of a hitch in :data:`HITCH_KNOTS` (see the module docstring).

    ``rod_length`` None: :func:`hitch_rod_length`; ``n_nodes`` None: edges of about
    :data:`EDGE`.
    """
    if rod_length is None:
        rod_length = hitch_rod_length(knot, post_diameter=post_diameter,
                                      rod_diameter=rod_diameter)  # fmt: skip
    if n_nodes is None:
        n_nodes = int(round(float(rod_length) / EDGE)) + 1
    if _check_knot(knot) == "cow_hitch":
        return cow_hitch_curve(post_diameter=post_diameter, rod_diameter=rod_diameter,
                               rod_length=rod_length, n_nodes=n_nodes)  # fmt: skip
    return two_half_hitches_curve(post_diameter=post_diameter, rod_diameter=rod_diameter,
                                  rod_length=rod_length, n_nodes=n_nodes,
                                  wrap_angle=HITCH_KNOTS[knot])  # fmt: skip


def hitch_closure(nodes, *, reach: float | None = None) -> np.ndarray:
    """The rod closed far away: each end extended away from the rod's centroid (along
    end - centroid, so that a tail that swings keeps pointing out) to ``reach`` (default
    3 x the rod's extent), and the two far points joined through a point a further
    ``reach`` out from the post axis in the direction of their mean, so the closing path
    does not circle the post. (n + 3, 3) [m]."""
    x = np.asarray(nodes, dtype=float)
    R = 3.0 * float(np.ptp(x, axis=0).max()) if reach is None else float(reach)
    c = x.mean(axis=0)
    u0 = x[0] - c
    u0 /= np.linalg.norm(u0)
    u1 = x[-1] - c
    u1 /= np.linalg.norm(u1)
    f0 = x[0] + R * u0
    f1 = x[-1] + R * u1
    mid = 0.5 * (f0 + f1)
    radial = np.array([mid[0], mid[1], 0.0])
    nr = np.linalg.norm(radial)
    via = mid + (R * radial / nr if nr > 1e-9 * R else 0.0)
    return np.vstack([x, f1, via, f0])


def hitch_invariants(nodes) -> tuple[tuple[int, ...], int]:
    """(Alexander polynomial of :func:`hitch_closure`, its winding number about the post
    axis rounded: the rod-post linking number); unchanged unless a strand passes through
    another or through the post."""
    c = hitch_closure(nodes)
    inv = knot_invariant(c, closed=True)
    w = winding_number(np.vstack([c, c[:1]]))
    return inv.alexander, int(round(w))
