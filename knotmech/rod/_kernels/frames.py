"""Reference frames, material frames, reference twist and curvature binormal.

Layout (see ``knotmech.rod.system``): the edge ``k`` of any rod has its first node's
x-dof at ``edge_dof0[k]``, its twist angle at ``edge_dof0[k] + 3`` and its second node at
``edge_dof0[k] + 4``. A bending/twisting stencil ``s`` (an interior node) joins the edges
``stencil_edge[s] - 1`` and ``stencil_edge[s]`` and spans the 11 contiguous dofs starting at
``edge_dof0[stencil_edge[s] - 1]``.

References: Bergou, Wardetzky, Robinson, Audoly, Grinspun, "Discrete elastic rods",
ACM TOG 27 (2008) (B08); Bergou, Audoly, Vouga, Wardetzky, Grinspun, "Discrete viscous
threads", ACM TOG 29 (2010) (B10).
"""

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(cache=True)
def edge_tangents(q, edge_dof0, tangents, lengths):
    """Update unit tangents ``(n_edges, 3)`` and lengths ``(n_edges,)`` [m] from dofs ``q``."""
    for k in range(edge_dof0.shape[0]):
        d = edge_dof0[k]
        e0 = q[d + 4] - q[d]
        e1 = q[d + 5] - q[d + 1]
        e2 = q[d + 6] - q[d + 2]
        n = np.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
        lengths[k] = n
        tangents[k, 0] = e0 / n
        tangents[k, 1] = e1 / n
        tangents[k, 2] = e2 / n


@njit(cache=True, inline="always")
def _transport(u0, u1, u2, a0, a1, a2, b0, b1, b2):
    """Parallel transport of u from unit vector a to unit vector b (B08 sec. 4.2).

    Rotation about a x b by the angle between a and b, written as Rodrigues' formula
    without trigonometry: P(u) = c u + (a x b) x u + (a x b)((a x b).u)/(1 + c), c = a.b.
    """
    c = a0 * b0 + a1 * b1 + a2 * b2
    w0, w1, w2 = _cross(a0, a1, a2, b0, b1, b2)
    if c <= -1.0 + 1e-12:
        return u0, u1, u2  # antiparallel: no unique transport; never met in a time step
    s = (w0 * u0 + w1 * u1 + w2 * u2) / (1.0 + c)
    x0, x1, x2 = _cross(w0, w1, w2, u0, u1, u2)
    return c * u0 + x0 + s * w0, c * u1 + x1 + s * w1, c * u2 + x2 + s * w2


@njit(cache=True)
def transport_frames(t_old, d1_old, t_new, d1_new, d2_new):
    """Time-parallel transport of the reference director d1 of every edge (B10 sec. 6).

    d1_new = P_{t_old -> t_new}(d1_old), re-orthonormalised against t_new; d2 = t x d1.
    """
    for k in range(t_old.shape[0]):
        u0, u1, u2 = _transport(
            d1_old[k, 0], d1_old[k, 1], d1_old[k, 2],
            t_old[k, 0], t_old[k, 1], t_old[k, 2],
            t_new[k, 0], t_new[k, 1], t_new[k, 2],
        )  # fmt: skip
        t0, t1, t2 = t_new[k, 0], t_new[k, 1], t_new[k, 2]
        p = u0 * t0 + u1 * t1 + u2 * t2
        u0 -= p * t0
        u1 -= p * t1
        u2 -= p * t2
        n = np.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
        u0 /= n
        u1 /= n
        u2 /= n
        d1_new[k, 0] = u0
        d1_new[k, 1] = u1
        d1_new[k, 2] = u2
        v0, v1, v2 = _cross(t0, t1, t2, u0, u1, u2)
        d2_new[k, 0] = v0
        d2_new[k, 1] = v1
        d2_new[k, 2] = v2


@njit(cache=True)
def space_parallel_frames(tangents, first_edge, last_edge, d1_first, d1, d2):
    """Space-parallel (Bishop) frames along edges first_edge..last_edge-1 of one rod.

    d1 of ``first_edge`` is ``d1_first`` projected normal to its tangent; each next d1 is the
    parallel transport of the previous one (B08 sec. 4.2), so the reference twist is zero.
    """
    t0, t1, t2 = tangents[first_edge, 0], tangents[first_edge, 1], tangents[first_edge, 2]
    u0, u1, u2 = d1_first[0], d1_first[1], d1_first[2]
    p = u0 * t0 + u1 * t1 + u2 * t2
    u0 -= p * t0
    u1 -= p * t1
    u2 -= p * t2
    n = np.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
    d1[first_edge, 0] = u0 / n
    d1[first_edge, 1] = u1 / n
    d1[first_edge, 2] = u2 / n
    for k in range(first_edge + 1, last_edge):
        u0, u1, u2 = _transport(
            d1[k - 1, 0], d1[k - 1, 1], d1[k - 1, 2],
            tangents[k - 1, 0], tangents[k - 1, 1], tangents[k - 1, 2],
            tangents[k, 0], tangents[k, 1], tangents[k, 2],
        )  # fmt: skip
        t0, t1, t2 = tangents[k, 0], tangents[k, 1], tangents[k, 2]
        p = u0 * t0 + u1 * t1 + u2 * t2
        u0 -= p * t0
        u1 -= p * t1
        u2 -= p * t2
        n = np.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
        d1[k, 0] = u0 / n
        d1[k, 1] = u1 / n
        d1[k, 2] = u2 / n
    for k in range(first_edge, last_edge):
        v0, v1, v2 = _cross(
            tangents[k, 0], tangents[k, 1], tangents[k, 2], d1[k, 0], d1[k, 1], d1[k, 2]
        )
        d2[k, 0] = v0
        d2[k, 1] = v1
        d2[k, 2] = v2


@njit(cache=True)
def reference_twist(stencil_edge, tangents, d1, ref_twist_old, ref_twist):
    """Reference twist of every stencil (B10 sec. 6, eq. for m_ref).

    The signed angle about t^f from the parallel transport of d1^e (e = f - 1) to d1^f,
    unwrapped against ``ref_twist_old``: P(d1^e) is first rotated by the old value and only
    the (small) remaining angle is measured, so values beyond +-pi are tracked continuously.
    """
    for s in range(stencil_edge.shape[0]):
        f = stencil_edge[s]
        e = f - 1
        tf0, tf1, tf2 = tangents[f, 0], tangents[f, 1], tangents[f, 2]
        u0, u1, u2 = _transport(
            d1[e, 0], d1[e, 1], d1[e, 2],
            tangents[e, 0], tangents[e, 1], tangents[e, 2],
            tf0, tf1, tf2,
        )  # fmt: skip
        a = ref_twist_old[s]
        ca = np.cos(a)
        sa = np.sin(a)
        # rotate u about t^f by a (u is normal to t^f)
        w0, w1, w2 = _cross(tf0, tf1, tf2, u0, u1, u2)
        r0 = ca * u0 + sa * w0
        r1 = ca * u1 + sa * w1
        r2 = ca * u2 + sa * w2
        v0, v1, v2 = d1[f, 0], d1[f, 1], d1[f, 2]
        c0, c1, c2 = _cross(r0, r1, r2, v0, v1, v2)
        sin_ = c0 * tf0 + c1 * tf1 + c2 * tf2
        cos_ = r0 * v0 + r1 * v1 + r2 * v2
        ref_twist[s] = a + np.arctan2(sin_, cos_)


@njit(cache=True)
def cos_sin(a, c, s):
    """c = cos(a), s = sin(a) entry by entry (the same libm calls as inside
    :func:`reference_twist`)."""
    for k in range(a.shape[0]):
        c[k] = np.cos(a[k])
        s[k] = np.sin(a[k])


@njit(cache=True)
def reference_twist_cs(stencil_edge, tangents, d1, ref_twist_old, cos_old, sin_old, ref_twist):
    """:func:`reference_twist` with the cosines and sines of ``ref_twist_old`` given
    (:func:`cos_sin`; they are the same for every Newton iterate of a step): the same
    arithmetic, the same bits."""
    for s in range(stencil_edge.shape[0]):
        f = stencil_edge[s]
        e = f - 1
        tf0, tf1, tf2 = tangents[f, 0], tangents[f, 1], tangents[f, 2]
        u0, u1, u2 = _transport(
            d1[e, 0], d1[e, 1], d1[e, 2],
            tangents[e, 0], tangents[e, 1], tangents[e, 2],
            tf0, tf1, tf2,
        )  # fmt: skip
        a = ref_twist_old[s]
        ca = cos_old[s]
        sa = sin_old[s]
        w0, w1, w2 = _cross(tf0, tf1, tf2, u0, u1, u2)
        r0 = ca * u0 + sa * w0
        r1 = ca * u1 + sa * w1
        r2 = ca * u2 + sa * w2
        v0, v1, v2 = d1[f, 0], d1[f, 1], d1[f, 2]
        c0, c1, c2 = _cross(r0, r1, r2, v0, v1, v2)
        sin_ = c0 * tf0 + c1 * tf1 + c2 * tf2
        cos_ = r0 * v0 + r1 * v1 + r2 * v2
        ref_twist[s] = a + np.arctan2(sin_, cos_)


@njit(cache=True)
def material_frames(q, edge_dof0, d1, d2, m1, m2):
    """Material directors m1 = cos(theta) d1 + sin(theta) d2, m2 = -sin d1 + cos d2 (B08 eq. 2)."""
    for k in range(edge_dof0.shape[0]):
        th = q[edge_dof0[k] + 3]
        c = np.cos(th)
        s = np.sin(th)
        for j in range(3):
            m1[k, j] = c * d1[k, j] + s * d2[k, j]
            m2[k, j] = -s * d1[k, j] + c * d2[k, j]


@njit(cache=True)
def curvatures(q, edge_dof0, stencil_edge, m1, m2, kappa):
    """Material curvatures (kappa1, kappa2) of every stencil (B10 sec. 4.1).

    kb = 2 e x f / (|e||f| + e.f), |kb| = 2 tan(phi/2) (B08 eq. 1);
    kappa1 = kb.(m2^e + m2^f)/2, kappa2 = -kb.(m1^e + m1^f)/2.
    """
    for s in range(stencil_edge.shape[0]):
        f = stencil_edge[s]
        e = f - 1
        de = edge_dof0[e]
        df = edge_dof0[f]
        e0 = q[de + 4] - q[de]
        e1 = q[de + 5] - q[de + 1]
        e2 = q[de + 6] - q[de + 2]
        f0 = q[df + 4] - q[df]
        f1 = q[df + 5] - q[df + 1]
        f2 = q[df + 6] - q[df + 2]
        den = np.sqrt((e0 * e0 + e1 * e1 + e2 * e2) * (f0 * f0 + f1 * f1 + f2 * f2))
        den += e0 * f0 + e1 * f1 + e2 * f2
        k0, k1, k2 = _cross(e0, e1, e2, f0, f1, f2)
        k0 *= 2.0 / den
        k1 *= 2.0 / den
        k2 *= 2.0 / den
        kappa[s, 0] = 0.5 * (
            k0 * (m2[e, 0] + m2[f, 0]) + k1 * (m2[e, 1] + m2[f, 1]) + k2 * (m2[e, 2] + m2[f, 2])
        )
        kappa[s, 1] = -0.5 * (
            k0 * (m1[e, 0] + m1[f, 0]) + k1 * (m1[e, 1] + m1[f, 1]) + k2 * (m1[e, 2] + m1[f, 2])
        )


@njit(cache=True)
def twists(q, edge_dof0, stencil_edge, ref_twist, twist):
    """Discrete twist m = theta^f - theta^e + m_ref of every stencil (B10 sec. 4.2)."""
    for s in range(stencil_edge.shape[0]):
        f = stencil_edge[s]
        twist[s] = q[edge_dof0[f] + 3] - q[edge_dof0[f - 1] + 3] + ref_twist[s]
