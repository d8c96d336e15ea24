"""Rod-rod (edge-edge) contact kernels: distance, penalty energy, gradient, Hessian, friction.

Private module: arrays in, results written in place.

References
----------
- Choi, Tong & Jawed, "Implicit contact model for discrete elastic rods in knot tying",
  J. Appl. Mech. 88 (2021) 051010 (IMC): smooth penalty on the edge-edge distance.
- Coated-rod paper (J. Appl. Mech., DOI 10.1115/1.4055544), eq. (10) (the softplus of the
  gap), eqs. (11)-(12) (friction with the smooth stick-slip weight gamma).
- Lumelsky, "On fast computation of distance between line segments", IPL 21 (1985):
  closest points of two segments with clamping of the parameters.
"""

from __future__ import annotations

import numpy as np
from numba import njit

# The helpers below are inlined into the kernels at numba's IR level (inline="always"):
# called across function boundaries, with their many array arguments, they cost about a
# third of rodrod_assemble's time and half of rodrod_near's (measured on the overhand
# benchmark's pairs). No kernel here is fastmath, so the arithmetic, and the bits, are the
# same either way.

# weight of the regularisation of the closest-point problem, relative to |e1|^2 (see
# _closest_params): below an angle of about sqrt(_REG) = 1e-5 rad the contact point on edge
# i is drawn toward its middle (the former parallel tolerance)
_REG = 1e-10


@njit(cache=True, inline="always")
def _clamp01(x):
    if x < 0.0:
        return 0.0
    if x > 1.0:
        return 1.0
    return x


@njit(cache=True, inline="always")
def _closest_params(a, b, c, d, e):
    """Clamped closest-point parameters from the dot products a = e1.e1, b = e1.e2,
    c = e2.e2, d = e1.w0, e = e2.w0 (w0 = x1 - x3); see :func:`segment_params`.

    The parameters minimise, over the unit square, the regularised squared gap
    ``|w0 + s e1 - t e2|^2 / 2 + eps (s - 1/2)^2 / 2`` with ``eps = _REG a``: strictly
    convex even for parallel edges, so the minimiser is unique and continuous in the nodes
    (Lumelsky's clamping order, 1985, applied to the regularised problem: the line
    solution for s, the best t for it, and if t is clamped the best s for that t). For
    parallel edges with overlapping projections it is the point of the overlap nearest the
    middle of edge i. The gap at it exceeds the true distance by at most ``eps / 8`` in
    the squared gap (``_REG |e1|^2 / (8 Delta)`` in Delta: 2e-17 m for 2.5 mm edges 4 mm
    apart). The former rule (s = 0 below a parallel tolerance) was discontinuous there:
    the nodal forces jumped by |F_n| times the overlap fraction when a pair turned through
    the tolerance, and a nip of side-by-side strands stayed on that surface, where Newton
    cannot converge at any step (the clove-hitch crawl of issue 11).
    """
    eps = _REG * a
    ar = a + eps
    dr = d - 0.5 * eps
    den = ar * c - b * b  # >= eps c > 0 for non-degenerate edges
    s = _clamp01((b * e - c * dr) / den) if den > 0.0 else 0.5
    t = (b * s + e) / c
    if t < 0.0:
        t = 0.0
        s = _clamp01(-dr / ar)
    elif t > 1.0:
        t = 1.0
        s = _clamp01((b - dr) / ar)
    free_s = (s > 0.0) and (s < 1.0)
    free_t = (t > 0.0) and (t < 1.0)
    return s, t, free_s, free_t


@njit(cache=True)
def segment_params(x1, x2, x3, x4):
    """Closest-point parameters (s, t) of segments x1-x2 and x3-x4 (Lumelsky 1985).

    Returns s, t in [0, 1] and flags free_s, free_t telling whether each parameter lies in the
    open interval (the edge-edge case has both free, point-edge one, point-point none).
    The problem is regularised so that (near-)parallel edges have a unique, continuous
    minimiser (see :func:`_closest_params`).
    """
    e1 = x2 - x1
    e2 = x4 - x3
    w0 = x1 - x3
    a = e1 @ e1
    b = e1 @ e2
    c = e2 @ e2
    d = e1 @ w0
    e = e2 @ w0
    return _closest_params(a, b, c, d, e)


@njit(cache=True, inline="always")
def _segment_params_flat(x):
    """:func:`segment_params` of the two edges packed in ``x`` (12,) = (x_i, x_i+1, x_j,
    x_j+1), in scalar arithmetic (no temporary arrays: the broad-phase filter calls it for
    every candidate pair and Newton iterate)."""
    a = 0.0
    b = 0.0
    c = 0.0
    d = 0.0
    e = 0.0
    for m in range(3):
        e1 = x[3 + m] - x[m]
        e2 = x[9 + m] - x[6 + m]
        w0 = x[m] - x[6 + m]
        a += e1 * e1
        b += e1 * e2
        c += e2 * e2
        d += e1 * w0
        e += e2 * w0
    return _closest_params(a, b, c, d, e)


@njit(cache=True, inline="always")
def edge_distance(x):
    """Distance Delta between two edges, ``x`` (12,) = (x_i, x_i+1, x_j, x_j+1) (Lumelsky
    1985); the cheap value-only version of :func:`edge_distance_hessian`."""
    s, t, _, _ = _segment_params_flat(x)
    d2 = 0.0
    for m in range(3):
        w = (1.0 - s) * x[m] + s * x[3 + m] - (1.0 - t) * x[6 + m] - t * x[9 + m]
        d2 += w * w
    return np.sqrt(d2)


@njit(cache=True)
def edge_distance_hessian(x, grad, hess):
    """Distance Delta between two edges, its gradient and Hessian w.r.t. the 12 coordinates.

    ``x`` (12,) = (x_i, x_i+1, x_j, x_j+1). Delta(x) = min_{s,t} |p(s) - q(t)|; with
    phi(x, u) = |A(u) x|^2 / 2, u the free parameters, the value function Phi = Delta^2/2 has
    (envelope theorem and implicit differentiation of phi_u = 0)

    .. math:: \\nabla\\Phi = \\phi_x, \\quad
              \\nabla^2\\Phi = \\phi_{xx} - \\phi_{xu}\\,\\phi_{uu}^{-1}\\,\\phi_{ux},

    and Delta = sqrt(2 Phi): grad Delta = grad Phi / Delta,
    Hess Delta = Hess Phi / Delta - grad Phi grad Phi^T / Delta^3. Clamped parameters (the
    point-edge and point-point cases) are simply held fixed, which is exact away from the
    switching surfaces. Writes ``grad`` (12,) and ``hess`` (12, 12); returns Delta.
    """
    coef = np.empty(4)
    w = np.empty(3)
    gphi = np.empty(12)
    H = np.empty((12, 12))
    B = np.empty((12, 2))
    U = np.empty((2, 2))
    return _edge_distance_hessian_ws(x, grad, hess, coef, w, gphi, H, B, U)


@njit(cache=True, inline="always")
def _gap_at(x, s, t, coef, w):
    """Gap of the two edges in ``x`` (12,) at the parameters (s, t): writes the weights
    ``coef`` (4,) of the four nodes in the gap vector w = A x = (1-s) x1 + s x2 - (1-t) x3
    - t x4 and ``w`` (3,); returns |w|. The one place of this arithmetic: the exact gap
    (:func:`_gap`, (s, t) the closest points) and the held one of the stagnation fallback
    (:func:`_gap_grad_at`, (s, t) held) are the same function of (s, t), bit for bit."""
    coef[0] = 1.0 - s
    coef[1] = s
    coef[2] = -(1.0 - t)
    coef[3] = -t
    d2 = 0.0
    for m in range(3):
        w[m] = coef[0] * x[m] + coef[1] * x[3 + m] + coef[2] * x[6 + m] + coef[3] * x[9 + m]
        d2 += w[m] * w[m]
    return np.sqrt(d2)


@njit(cache=True, inline="always")
def _gap_grad_at(x, s, t, grad, coef, w):
    """Gap |w| of two edges at the parameters (s, t) (:func:`_gap_at`) and its gradient
    (12,) with (s, t) fixed, grad_k = coef_k w / |w|: the gradient of the exact distance
    at the closest points (envelope theorem, :func:`_edge_distance_grad_ws`), and of the
    held gap of the stagnation fallback. At |w| = 0 (the points meet; the force's
    direction is undefined) it raises ZeroDivisionError: the solver rejects the attempt
    (``Stepper._newton``)."""
    dist = _gap_at(x, s, t, coef, w)
    inv_d = 1.0 / dist
    for k in range(4):
        for m in range(3):
            grad[3 * k + m] = (coef[k] * w[m]) * inv_d
    return dist


@njit(cache=True, inline="always")
def _gap(x, coef, w):
    """Closest points of the two edges in ``x`` (12,): writes the weights ``coef`` (4,) of
    the four nodes in the gap vector w = A x = (1-s) x1 + s x2 - (1-t) x3 - t x4 and ``w``
    (3,); returns (|w|, free_s, free_t) (see :func:`segment_params`, :func:`_gap_at`)."""
    s, t, free_s, free_t = _segment_params_flat(x)
    return _gap_at(x, s, t, coef, w), free_s, free_t


@njit(cache=True, inline="always")
def _edge_distance_hessian_ws(x, grad, hess, coef, w, gphi, H, B, U):
    """:func:`edge_distance_hessian` with caller-provided work arrays coef (4,), w (3,),
    gphi (12,), H (12, 12), B (12, 2), U (2, 2) (no allocation per pair)."""
    dist, free_s, free_t = _gap(x, coef, w)
    # phi_x = A^T w ; phi_xx = (coef coef^T) kron I3
    for k in range(4):
        for m in range(3):
            gphi[3 * k + m] = coef[k] * w[m]
    H[:, :] = 0.0
    for k in range(4):
        for l in range(4):
            for m in range(3):
                H[3 * k + m, 3 * l + m] = coef[k] * coef[l]
    nfree = int(free_s) + int(free_t)
    if nfree > 0:
        _coupling_columns(x, coef, w, free_s, free_t, B, U)
        _subtract_coupling(nfree, H, B, U)
    inv_d = 1.0 / dist
    for i in range(12):
        grad[i] = gphi[i] * inv_d
    inv_d3 = inv_d * inv_d * inv_d
    for i in range(12):
        for j in range(12):
            hess[i, j] = H[i, j] * inv_d - gphi[i] * gphi[j] * inv_d3
    return dist


@njit(cache=True, inline="always")
def _coupling_columns(x, coef, w, free_s, free_t, B, U):
    """The columns phi_xu (``B`` (12, 2)) and the matrix phi_uu (``U`` (2, 2)) of the free
    closest-point parameters (s first if free, then t) of the two edges in ``x`` (12,),
    with the gap's node weights ``coef`` (4,) and gap vector ``w`` (3,) (see
    :func:`_edge_distance_hessian_ws`)."""
    # columns of phi_xu for the free parameters and the matrix phi_uu
    B[:, :] = 0.0
    U[:, :] = 0.0
    col = 0
    idx_s = -1
    idx_t = -1
    if free_s:
        idx_s = col
        col += 1
    if free_t:
        idx_t = col
        col += 1
    e11 = 0.0
    e22 = 0.0
    e12 = 0.0
    for m in range(3):
        a1 = x[3 + m] - x[m]
        a2 = x[9 + m] - x[6 + m]
        e11 += a1 * a1
        e22 += a2 * a2
        e12 += a1 * a2
    if free_s:
        # d/dx (w . e1) = A^T e1 + [-w, w, 0, 0]
        for k in range(4):
            for m in range(3):
                B[3 * k + m, idx_s] = coef[k] * (x[3 + m] - x[m])
        for m in range(3):
            B[m, idx_s] -= w[m]
            B[3 + m, idx_s] += w[m]
        U[idx_s, idx_s] = e11 * (1.0 + _REG)  # the regularised problem's phi_ss
    if free_t:
        # d/dx (-w . e2) = -A^T e2 + [0, 0, w, -w]
        for k in range(4):
            for m in range(3):
                B[3 * k + m, idx_t] = -coef[k] * (x[9 + m] - x[6 + m])
        for m in range(3):
            B[6 + m, idx_t] += w[m]
            B[9 + m, idx_t] -= w[m]
        U[idx_t, idx_t] = e22
    if free_s and free_t:
        U[0, 1] = -e12
        U[1, 0] = U[0, 1]


@njit(cache=True, inline="always")
def _subtract_coupling(nfree, H, B, U):
    """H -= B U^-1 B^T for the ``nfree`` (1 or 2) free parameters (the implicit
    differentiation term of :func:`_edge_distance_hessian_ws`)."""
    if nfree == 1:
        inv = 1.0 / U[0, 0]
        for i in range(12):
            for j in range(12):
                H[i, j] -= B[i, 0] * inv * B[j, 0]
    else:
        det = U[0, 0] * U[1, 1] - U[0, 1] * U[1, 0]
        i00 = U[1, 1] / det
        i11 = U[0, 0] / det
        i01 = -U[0, 1] / det
        for i in range(12):
            bi0 = B[i, 0]
            bi1 = B[i, 1]
            for j in range(12):
                H[i, j] -= bi0 * (i00 * B[j, 0] + i01 * B[j, 1]) + bi1 * (
                    i01 * B[j, 0] + i11 * B[j, 1]
                )


@njit(cache=True, inline="always")
def _edge_distance_grad_ws(x, grad, coef, w):
    """Distance and its gradient only (the arithmetic of :func:`_edge_distance_hessian_ws`,
    so both give bitwise the same values): for pairs that need no Jacobian block."""
    s, t, _, _ = _segment_params_flat(x)
    return _gap_grad_at(x, s, t, grad, coef, w)


@njit(cache=True, inline="always")
def _pair_gap_grad(x, frozen, p, grad, coef, w):
    """Gap and gradient of pair ``p`` (nodes ``x`` (12,)): at its held parameters
    ``frozen[p]`` when held (``frozen`` not None, s >= 0; the stagnation fallback, see
    :func:`freeze_parallel_pairs`), else at its closest points."""
    if frozen is not None and frozen[p, 0] >= 0.0:
        return _gap_grad_at(x, frozen[p, 0], frozen[p, 1], grad, coef, w)
    return _edge_distance_grad_ws(x, grad, coef, w)


@njit(cache=True, inline="always")
def _held_gap_hessian(dist, grad, hess, coef, w, B, U):
    """Hessian (12, 12) of the held gap of :func:`_gap_grad_at`: (coef coef^T) kron
    (I - n n^T) / |w| with n = w/|w| (no parameter-coupling term); ``B`` = 0 and ``U`` = I,
    so that :func:`_normal_jacobian` adds no closest-point motion either."""
    inv_d = 1.0 / dist
    for k in range(4):
        for l in range(4):
            c = coef[k] * coef[l] * inv_d
            for a in range(3):
                for b in range(3):
                    na = w[a] * inv_d
                    nb = w[b] * inv_d
                    hess[3 * k + a, 3 * l + b] = c * ((1.0 if a == b else 0.0) - na * nb)
    B[:, :] = 0.0
    U[:, :] = 0.0
    U[0, 0] = 1.0
    U[1, 1] = 1.0


@njit(cache=True)
def freeze_parallel_pairs(pos, pairs, edge_nodes, radius_edge, sharpness, z_cutoff, out):
    """Closest-point parameters (s, t) of the nearly parallel candidate pairs in reach.

    For (nearly) parallel edges the closest points jump between the two ends of the
    overlap as the tiny angle between them changes sign (the distance is the smaller of
    two smooth functions there), which moves the whole penalty force from one node to
    another between two Newton iterates: the stagnation fallback holds these parameters
    for one step (docs/notes/contact-and-friction/parallel-edge-stall.md).

    Parameters
    ----------
    pos : (n_nodes, 3) array [m]
        Node positions (the step start).
    pairs : (n_pairs, 2) int array
        Candidate edge pairs (e_i, e_j).
    edge_nodes : (n_edges, 2) int array
        The two nodes of each edge.
    radius_edge : (n_edges,) array [m]
        Rod radius of each edge.
    sharpness : float [1/m]
        The penalty's k.
    z_cutoff : float
        Reach: pairs with k (2h - Delta) below it are not held (``Z_CUTOFF``).
    out : (n_pairs, 2) array
        Written: (s, t) of each held pair (edges within reach and with sin^2 of their
        angle below ``_SIN2_PLANE``, about 5 degrees), -1 for the others.

    Returns
    -------
    int
        The number of pairs held.
    """
    x = np.empty(12)
    held = 0
    for p in range(pairs.shape[0]):
        out[p, 0] = -1.0
        out[p, 1] = -1.0
        ei, ej = _pair_nodes(pos, pairs, p, edge_nodes, x)
        two_h = radius_edge[ei] + radius_edge[ej]
        if _beyond(x, two_h - z_cutoff / sharpness):
            continue
        if sharpness * (two_h - edge_distance(x)) < z_cutoff:
            continue
        a11 = 0.0
        a22 = 0.0
        a12 = 0.0
        for m in range(3):
            e1 = x[3 + m] - x[m]
            e2 = x[9 + m] - x[6 + m]
            a11 += e1 * e1
            a22 += e2 * e2
            a12 += e1 * e2
        if a11 * a22 - a12 * a12 > _SIN2_PLANE * a11 * a22:
            continue
        s, t, _, _ = _segment_params_flat(x)
        out[p, 0] = s
        out[p, 1] = t
        held += 1
    return held


@njit(cache=True, inline="always")
def _softplus(z):
    if z > 30.0:
        return z
    if z < -30.0:
        return np.exp(z)
    return np.log1p(np.exp(z))


@njit(cache=True, inline="always")
def _sigmoid(z):
    if z >= 0.0:
        return 1.0 / (1.0 + np.exp(-z))
    ez = np.exp(z)
    return ez / (1.0 + ez)


@njit(cache=True, inline="always")
def penalty_derivs(gap_arg, sharpness, stiffness):
    """Squared-softplus penalty of IMC on z = k (2h - Delta) (coated-rod eq. 10 inside).

    .. math:: E = K_c \\left[\\frac{\\log(1 + e^{k(2h-\\Delta)})}{k}\\right]^2

    ``gap_arg`` = 2h - Delta [m]; returns E, dE/dDelta, d2E/dDelta2.
    """
    z = sharpness * gap_arg
    sp = _softplus(z) / sharpness
    sg = _sigmoid(z)
    e = stiffness * sp * sp
    de = -2.0 * stiffness * sp * sg
    d2e = 2.0 * stiffness * (sg * sg + sp * sg * (1.0 - sg) * sharpness)
    return e, de, d2e


# Pairs with z = k (2h - Delta) below this carry a penalty energy, force and Hessian below
# e^(2 Z_CUTOFF) ~ 4e-18 of their contact scale (the squared softplus decays like e^(2z)):
# negligible against any solver tolerance, so they are skipped before the Hessian.
Z_CUTOFF = -20.0
# Pairs with z below this add their force but no Jacobian entries: their penalty stiffness
# is below e^(2 Z_JACOBIAN) ~ 2e-9 of the contact stiffness, so leaving it out of dF/dq
# does not change Newton's convergence, while it keeps these distant pairs from widening
# the band of the reordered Jacobian (and the cost of its LU)
Z_JACOBIAN = -10.0
# Jacobian entries per near pair: 144 penalty + 144 friction
ENTRIES_PER_PAIR = 288


@njit(cache=True, inline="always")
def _beyond(x, reach):
    """True when the two edges in ``x`` (12,) are certainly farther apart than ``reach``
    [m]: the distance of their midpoints less their half lengths, a lower bound of the
    edge distance ((l_i + l_j)/2 <= sqrt((l_i^2 + l_j^2)/2)), exceeds reach (1 + 1e-6)
    (a margin far above the round-off of either side). A cheap test before
    :func:`edge_distance` that skips only pairs whose exact test fails by far, so the
    pairs kept are the same."""
    d2 = 0.0
    la2 = 0.0
    lb2 = 0.0
    for m in range(3):
        d = 0.5 * (x[m] + x[3 + m]) - 0.5 * (x[6 + m] + x[9 + m])
        ea = x[3 + m] - x[m]
        eb = x[9 + m] - x[6 + m]
        d2 += d * d
        la2 += ea * ea
        lb2 += eb * eb
    bound = np.sqrt(0.5 * (la2 + lb2)) + reach * (1.0 + 1e-6)
    return d2 > bound * bound


@njit(cache=True)
def rodrod_near(pos, pairs, edge_nodes, radius_edge, sharpness, z_cutoff, near):
    """Indices of the candidate pairs with k (2h - Delta) >= ``z_cutoff`` into ``near``;
    returns their number (the cheap distance-only pass before :func:`rodrod_assemble`)."""
    x = np.empty(12)
    cnt = 0
    for p in range(pairs.shape[0]):
        ei = pairs[p, 0]
        ej = pairs[p, 1]
        nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
        for k in range(4):
            for m in range(3):
                x[3 * k + m] = pos[nodes[k], m]
        two_h = radius_edge[ei] + radius_edge[ej]
        if _beyond(x, two_h - z_cutoff / sharpness):  # z far below z_cutoff
            continue
        if sharpness * (two_h - edge_distance(x)) >= z_cutoff:
            near[cnt] = p
            cnt += 1
    return cnt


@njit(cache=True)
def rodrod_assemble(
    pos,
    pos_old,
    dt,
    pairs,
    near,
    n_near,
    edge_nodes,
    node_dofs,
    radius_edge,
    sharpness,
    stiffness,
    mu,
    fric_k,
    fric_c,
    vel_eps,
    force,
    rows,
    cols,
    vals,
    contact_force,
    normal_derivative,
    z_jacobian,
    want_jacobian,
    law,
    mu_k,
    k_t,
    anchor,
    anchor_slip,
    anchor_known,
    out_slip,
    cap_floor=0.0,
    floor_mode=0,
    frozen=None,
):
    """Contact + friction forces and Jacobian blocks of the near candidate pairs.

    ``near[:n_near]`` are the indices (into ``pairs``) of the pairs to assemble (see
    :func:`rodrod_near`; the others have a negligible penalty, ``Z_CUTOFF``). For pair
    p = (i, j): force (12,) = -dE/dx (IMC eq. for the penalty); friction of coated-rod
    eqs. (11)-(12): F_n = force on edge i, n = F_n/|F_n|, v_rel = (v_i + v_i+1 - v_j -
    v_j+1)/2 with v = (x - x_old)/dt, v_T = (I - n n^T) v_rel,
    gamma = 1/(1 + exp(-k(|v_T| - c))), F_fr = -gamma mu |F_n| v_T/|v_T| (capped at mu|F_n|
    by gamma <= 1), distributed (+1/2, +1/2, -1/2, -1/2).

    Jacobian: the exact Hessian of the penalty; for friction the derivative through the
    velocity (and, with ``normal_derivative``, through |F_n|; the normal n is lagged);
    only for pairs with k (2h - Delta) >= ``z_jacobian`` (see ``Z_JACOBIAN``), and not at
    all if ``want_jacobian`` is False (forces only; the same values).
    Entries are written compactly to ``rows/cols/vals`` (room for ``ENTRIES_PER_PAIR`` per
    near pair: 144 penalty, then 144 friction if the pair has friction); returns (energy,
    number of entries written). ``contact_force`` (n_pairs,) receives |F_n| (0 for pairs
    that are not near).

    ``law`` 0 is the regularised friction above (``mu``, ``fric_k``, ``fric_c``,
    ``vel_eps``); ``law`` 1 the elasto-plastic anchor of :func:`_anchor_friction` (static
    ``mu``, kinetic ``mu_k``, tangential stiffness ``k_t`` [N/m], the pairs' anchors
    ``anchor`` (n_pairs, 2) and last slip flags ``anchor_slip``, ``anchor_known`` False
    for a pair without an anchor yet: it is made from ``pos_old`` and the flag set;
    ``out_slip`` (n_pairs,) receives whether each pair slides at ``pos``); the energy then
    includes the anchor springs' (see :func:`rodrod_anchor_commit`). ``cap_floor`` > 0
    floors the cap's width at ``cap_floor`` (r_i + r_j) (see :func:`_anchor_friction`):
    on every pair (``floor_mode`` 0) or only on the pairs that slid at the last accepted
    step (``floor_mode`` 1, ``anchor_slip``; see :func:`rodrod_anchor_commit`).

    ``frozen`` (n_pairs, 2) or None (default): closest-point parameters (s, t) held fixed
    for the pairs with s >= 0 (the solver's stagnation fallback, see
    :func:`freeze_parallel_pairs`): their gap is w = (1-s) x1 + s x2 - (1-t) x3 - t x4
    at those parameters, a smooth function of x, instead of the segments' closest points.
    """
    if not want_jacobian:  # forces only: the compact loop of _assemble_forces
        return _assemble_forces(
            pos, pos_old, dt, pairs, near, n_near, edge_nodes, node_dofs, radius_edge,
            sharpness, stiffness, mu, fric_k, fric_c, vel_eps, force, rows, cols, vals,
            contact_force, normal_derivative, law, mu_k, k_t, anchor, anchor_slip,
            anchor_known, out_slip, cap_floor, floor_mode, frozen,
        )  # fmt: skip
    x = np.empty(12)
    grad = np.empty(12)
    hess = np.empty((12, 12))
    dofs = np.empty(12, dtype=np.int64)
    fn = np.empty(3)
    n = np.empty(3)
    vrel = np.empty(3)
    vt = np.empty(3)
    ffr = np.empty(3)
    Dm = np.empty((3, 3))
    Dp = np.empty((3, 3))
    coef = np.empty(4)
    w = np.empty(3)
    gphi = np.empty(12)
    H = np.empty((12, 12))
    B = np.empty((12, 2))
    U = np.empty((2, 2))
    cw = np.empty(4)
    u = np.empty(3)
    ft = np.empty(3)
    nf = np.empty(3)
    dndx = np.empty((3, 12))
    G3 = np.empty((3, 12))
    xo = np.empty(12)
    coef_o = np.empty(4)
    w_o = np.empty(3)
    n_o = np.empty(3)
    energy = 0.0
    contact_force[:] = 0.0
    if law == 1:
        out_slip[:] = False
    cnt = 0
    for kp in range(n_near):
        p = near[kp]
        ei = pairs[p, 0]
        ej = pairs[p, 1]
        nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
        for k in range(4):
            for m in range(3):
                x[3 * k + m] = pos[nodes[k], m]
                dofs[3 * k + m] = node_dofs[nodes[k], m]
        two_h = radius_edge[ei] + radius_edge[ej]
        held = frozen is not None and frozen[p, 0] >= 0.0
        dist = _pair_gap_grad(x, frozen, p, grad, coef, w)
        # pairs beyond z_jacobian add their force but no Jacobian entries
        jac = want_jacobian and sharpness * (two_h - dist) >= z_jacobian
        if jac and held:
            _held_gap_hessian(dist, grad, hess, coef, w, B, U)
        elif jac:
            dist = _edge_distance_hessian_ws(x, grad, hess, coef, w, gphi, H, B, U)
        e, de, d2e = penalty_derivs(two_h - dist, sharpness, stiffness)
        energy += e
        # force = -dE/dx = -de * grad ; dF/dx = -(d2e grad grad^T + de hess)
        for a in range(12):
            force[dofs[a]] -= de * grad[a]
        for a in range(12 if jac else 0):
            for b in range(12):
                rows[cnt] = dofs[a]
                cols[cnt] = dofs[b]
                vals[cnt] = -(d2e * grad[a] * grad[b] + de * hess[a, b])
                cnt += 1
        # normal force on edge i (sum over its two nodes)
        for m in range(3):
            fn[m] = -de * (grad[m] + grad[3 + m])
        fnorm = np.sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2])
        contact_force[p] = fnorm
        if mu <= 0.0 or fnorm <= 0.0:
            continue
        for m in range(3):
            n[m] = fn[m] / fnorm
        if law == 1:
            if not anchor_known[p]:  # a new pair: its anchor from the step start
                _pair_nodes(pos_old, pairs, p, edge_nodes, xo)
                _fresh_anchor(xo, anchor[p], coef_o, w_o, n_o, nf, cw, u)
                anchor_known[p] = True
            cn = d2e / de if (normal_derivative and de != 0.0) else 0.0
            e_f, slip, cnt = _anchor_friction(
                x, anchor[p], anchor_slip[p], n, fnorm, mu, mu_k, k_t, cn, grad, dofs, jac,
                force, rows, cols, vals, cnt, cw, u, ft, nf, coef, dist, B, U, dndx, G3,
                _cap_min(cap_floor, floor_mode, two_h, sharpness, anchor_slip[p]),
            )  # fmt: skip
            energy += e_f
            out_slip[p] = slip
            continue
        cnt = _smooth_friction(
            pos, pos_old, nodes, dofs, dt, n, fnorm, mu, fric_k, fric_c, vel_eps, jac,
            normal_derivative, de, d2e, grad, force, rows, cols, vals, cnt, vrel, Dm, Dp, vt,
            ffr,
        )  # fmt: skip
    return energy, cnt


@njit(cache=True)
def _assemble_forces(
    pos, pos_old, dt, pairs, near, n_near, edge_nodes, node_dofs, radius_edge, sharpness,
    stiffness, mu, fric_k, fric_c, vel_eps, force, rows, cols, vals, contact_force,
    normal_derivative, law, mu_k, k_t, anchor, anchor_slip, anchor_known, out_slip,
    cap_floor, floor_mode, frozen=None,
):  # fmt: skip
    """:func:`rodrod_assemble` with ``want_jacobian`` False (most Newton evaluations: chord
    iterations need no Jacobian): the same statements in the same order without the
    Jacobian's, in a loop compact enough to be compiled well (the loop of
    rodrod_assemble, with the Hessian and Jacobian code inlined in it, ran this case
    about half as fast). The same forces, energy and flags, bit for bit."""
    x = np.empty(12)
    grad = np.empty(12)
    dofs = np.empty(12, dtype=np.int64)
    fn = np.empty(3)
    n = np.empty(3)
    vrel = np.empty(3)
    vt = np.empty(3)
    ffr = np.empty(3)
    Dm = np.empty((3, 3))
    Dp = np.empty((3, 3))
    coef = np.empty(4)
    w = np.empty(3)
    B = np.empty((12, 2))
    U = np.empty((2, 2))
    cw = np.empty(4)
    u = np.empty(3)
    ft = np.empty(3)
    nf = np.empty(3)
    dndx = np.empty((3, 12))
    G3 = np.empty((3, 12))
    xo = np.empty(12)
    coef_o = np.empty(4)
    w_o = np.empty(3)
    n_o = np.empty(3)
    energy = 0.0
    contact_force[:] = 0.0
    if law == 1:
        out_slip[:] = False
    cnt = 0
    for kp in range(n_near):
        p = near[kp]
        ei = pairs[p, 0]
        ej = pairs[p, 1]
        nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
        for k in range(4):
            for m in range(3):
                x[3 * k + m] = pos[nodes[k], m]
                dofs[3 * k + m] = node_dofs[nodes[k], m]
        two_h = radius_edge[ei] + radius_edge[ej]
        dist = _pair_gap_grad(x, frozen, p, grad, coef, w)
        e, de, d2e = penalty_derivs(two_h - dist, sharpness, stiffness)
        energy += e
        for a in range(12):
            force[dofs[a]] -= de * grad[a]
        for m in range(3):
            fn[m] = -de * (grad[m] + grad[3 + m])
        fnorm = np.sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2])
        contact_force[p] = fnorm
        if mu <= 0.0 or fnorm <= 0.0:
            continue
        for m in range(3):
            n[m] = fn[m] / fnorm
        if law == 1:
            if not anchor_known[p]:  # a new pair: its anchor from the step start
                _pair_nodes(pos_old, pairs, p, edge_nodes, xo)
                _fresh_anchor(xo, anchor[p], coef_o, w_o, n_o, nf, cw, u)
                anchor_known[p] = True
            e_f, slip, cnt = _anchor_friction(
                x, anchor[p], anchor_slip[p], n, fnorm, mu, mu_k, k_t, 0.0, grad, dofs, False,
                force, rows, cols, vals, cnt, cw, u, ft, nf, coef, dist, B, U, dndx, G3,
                _cap_min(cap_floor, floor_mode, two_h, sharpness, anchor_slip[p]),
            )  # fmt: skip
            energy += e_f
            out_slip[p] = slip
            continue
        cnt = _smooth_friction(
            pos, pos_old, nodes, dofs, dt, n, fnorm, mu, fric_k, fric_c, vel_eps, False,
            normal_derivative, de, d2e, grad, force, rows, cols, vals, cnt, vrel, Dm, Dp, vt,
            ffr,
        )  # fmt: skip
    return energy, cnt


@njit(cache=True, inline="always")
def _smooth_friction(
    pos, pos_old, nodes, dofs, dt, n, fnorm, mu, fric_k, fric_c, vel_eps, jac,
    normal_derivative, de, d2e, grad, force, rows, cols, vals, cnt, vrel, Dm, Dp, vt, ffr,
):  # fmt: skip
    """Regularised friction of one pair (coated-rod eqs. 11-12; see
    :func:`rodrod_assemble`): adds the force of the pair's ``nodes`` (4,) to ``force`` and,
    if ``jac``, its Jacobian triplets from ``cnt`` on; ``vrel``, ``vt``, ``ffr`` (3,),
    ``Dm`` and ``Dp`` (3, 3) are work arrays (the tangential velocity and the friction
    force written entry by entry, with the operations of the array expressions they
    replace: no temporary arrays per pair). Returns the new entry count."""
    for m in range(3):
        vi = 0.5 * (pos[nodes[0], m] - pos_old[nodes[0], m])
        vi += 0.5 * (pos[nodes[1], m] - pos_old[nodes[1], m])
        vj = 0.5 * (pos[nodes[2], m] - pos_old[nodes[2], m])
        vj += 0.5 * (pos[nodes[3], m] - pos_old[nodes[3], m])
        vrel[m] = (vi - vj) / dt
    vn = vrel[0] * n[0] + vrel[1] * n[1] + vrel[2] * n[2]
    for m in range(3):
        vt[m] = vrel[m] - vn * n[m]
    vtn_raw = np.sqrt(vt @ vt)
    vtn = np.sqrt(vtn_raw * vtn_raw + vel_eps * vel_eps)
    gam = _sigmoid(fric_k * (vtn_raw - fric_c))
    dgam = fric_k * gam * (1.0 - gam)
    c_fr = -gam * mu * fnorm
    for m in range(3):
        ffr[m] = c_fr * vt[m] / vtn
    sgn = (0.5, 0.5, -0.5, -0.5)
    for k in range(4):
        for m in range(3):
            force[dofs[3 * k + m]] += sgn[k] * ffr[m]
    if not jac:
        return cnt
    # dF_fr/dv_rel = -mu |Fn| [gamma/vtn (I - vt vt^T/vtn^2) + gamma' vt vt^T/(vtn vtn_raw)] P
    for a in range(3):
        for b in range(3):
            Dm[a, b] = gam / vtn * ((1.0 if a == b else 0.0) - vt[a] * vt[b] / (vtn * vtn))
            if vtn_raw > 0.0:
                Dm[a, b] += dgam * vt[a] * vt[b] / (vtn * vtn_raw)
    # Dp = -mu |Fn| Dm P, P = I - n n^T
    for a in range(3):
        for b in range(3):
            acc = Dm[a, b]
            for c in range(3):
                acc -= Dm[a, c] * n[c] * n[b]
            Dp[a, b] = -mu * fnorm * acc
    # with normal_derivative: also the dependence of |F_n| on q (the normal stays
    # lagged), d|F_n|/dx = (d2e/de) |F_n| grad Delta, which makes dF/dq unsymmetric
    cn = d2e / de if (normal_derivative and de != 0.0) else 0.0
    for k in range(4):
        for a in range(3):
            for l in range(4):
                scale = sgn[k] * sgn[l] / dt
                for b in range(3):
                    rows[cnt] = dofs[3 * k + a]
                    cols[cnt] = dofs[3 * l + b]
                    vals[cnt] = scale * Dp[a, b] + sgn[k] * ffr[a] * cn * grad[3 * l + b]
                    cnt += 1
    return cnt


# Anchor parameters stay within [ANCHOR_LO, ANCHOR_HI] on the lines of their edges: a pair
# whose closest points sit at a node still holds its anchor where the contact really is,
# up to one edge length beyond the node (on the extension of the edge)
ANCHOR_LO = -1.0
ANCHOR_HI = 2.0
# The anchor spring F = -mu |F_n| u / sqrt(|u|^2 + a^2), a = mu |F_n|/k_t: -k_t u for
# |u| << a, mu |F_n| for |u| >> a, and smooth in between (Newton does not chatter between
# a stick and a slip branch). The pair slides when |u| exceeds SLIP_GAP a: the anchor is
# then moved back to |u| = SLIP_GAP a, where the force is mu |F_n| (1 + SLIP_GAP^-2)^-1/2
# = 0.995 mu |F_n|
SLIP_GAP = 10.0
# edges crossing at less than about 5 degrees use the pair's normal for the friction plane
_SIN2_PLANE = 0.0076


@njit(cache=True, inline="always")
def _friction_normal(x, n, nf):
    """Normal ``nf`` (3,) of the friction's tangent plane: the normal m = e1 x e2/|e1 x e2|
    of the plane of the two edges (the contact normal of the two lines, also when the
    closest points of the segments sit at a node and the pair's normal ``n`` leans
    toward it), or ``n`` for (near-)parallel edges. Returns |e1 x e2| (0: ``n`` used)."""
    a11 = 0.0
    a22 = 0.0
    c0 = 0.0
    c1 = 0.0
    c2 = 0.0
    e1x = x[3] - x[0]
    e1y = x[4] - x[1]
    e1z = x[5] - x[2]
    e2x = x[9] - x[6]
    e2y = x[10] - x[7]
    e2z = x[11] - x[8]
    a11 = e1x * e1x + e1y * e1y + e1z * e1z
    a22 = e2x * e2x + e2y * e2y + e2z * e2z
    c0 = e1y * e2z - e1z * e2y
    c1 = e1z * e2x - e1x * e2z
    c2 = e1x * e2y - e1y * e2x
    cc = c0 * c0 + c1 * c1 + c2 * c2
    if cc <= _SIN2_PLANE * a11 * a22:
        for m in range(3):
            nf[m] = n[m]
        return 0.0
    cn = np.sqrt(cc)
    nf[0] = c0 / cn
    nf[1] = c1 / cn
    nf[2] = c2 / cn
    return cn


@njit(cache=True, inline="always")
def _anchor_gap(x, anc, n, cw, u):
    """Tangential gap of an anchor: u = P_n (X_a - X_b) with the anchor's material points
    X_a = (1 - s_a) x1 + s_a x2 and X_b = (1 - s_b) x3 + s_b x4 (``anc`` = (s_a, s_b),
    ``x`` (12,) the pair's nodes, P_n = I - n n^T); writes the node weights ``cw`` (4,) of
    X_a - X_b and ``u`` (3,); returns (|u|, n . (X_a - X_b))."""
    cw[0] = 1.0 - anc[0]
    cw[1] = anc[0]
    cw[2] = -(1.0 - anc[1])
    cw[3] = -anc[1]
    dn = 0.0
    for m in range(3):
        u[m] = cw[0] * x[m] + cw[1] * x[3 + m] + cw[2] * x[6 + m] + cw[3] * x[9 + m]
        dn += u[m] * n[m]
    un = 0.0
    for m in range(3):
        u[m] -= dn * n[m]
        un += u[m] * u[m]
    return np.sqrt(un), dn


@njit(cache=True, inline="always")
def _shift_anchor(x, anc, dd):
    """Move the anchor's parameters so that X_a - X_b changes by ``dd`` (3,) as nearly as
    the two edge directions allow: least squares ds_a e1 - ds_b e2 = dd with a tiny
    Tikhonov term (parallel edges: the smallest shift), each parameter kept in
    [ANCHOR_LO, ANCHOR_HI] (the other then re-fitted)."""
    a11 = 0.0
    a22 = 0.0
    a12 = 0.0
    b1 = 0.0
    b2 = 0.0
    for m in range(3):
        e1 = x[3 + m] - x[m]
        e2 = x[9 + m] - x[6 + m]
        a11 += e1 * e1
        a22 += e2 * e2
        a12 -= e1 * e2
        b1 += e1 * dd[m]
        b2 -= e2 * dd[m]
    lam = 1e-9 * (a11 + a22)
    det = (a11 + lam) * (a22 + lam) - a12 * a12
    dsa = ((a22 + lam) * b1 - a12 * b2) / det
    dsb = ((a11 + lam) * b2 - a12 * b1) / det
    sa = min(max(anc[0] + dsa, ANCHOR_LO), ANCHOR_HI)
    if sa != anc[0] + dsa:  # s_a at its bound: the best s_b for it
        dsb = (b2 - a12 * (sa - anc[0])) / a22
    sb = min(max(anc[1] + dsb, ANCHOR_LO), ANCHOR_HI)
    if sb != anc[1] + dsb and sa == anc[0] + dsa:
        sa = min(max(anc[0] + (b1 - a12 * (sb - anc[1])) / a11, ANCHOR_LO), ANCHOR_HI)
    anc[0] = sa
    anc[1] = sb


@njit(cache=True, inline="always")
def _normal_jacobian(x, coef, n, dist, B, U, dndx):
    """dn/dx (3, 12) of the pair's normal n = w/|w| (w = A x the gap vector of the
    closest points, ``coef`` its node weights): dw/dx = A - W U^-1 B^T, the closest-point
    parameters moving with x (implicit differentiation of phi_u = 0, with B and U the
    phi_xu columns and phi_uu of the free parameters as left by
    :func:`_edge_distance_hessian_ws`, W = (e1, -e2) their dw/du), and
    dn/dx = P_n dw/dx / |w|."""
    _, _, free_s, free_t = _segment_params_flat(x)
    nfree = int(free_s) + int(free_t)
    wu0 = np.zeros(3)
    wu1 = np.zeros(3)
    if nfree > 0:
        col = np.zeros((3, 2))
        c = 0
        if free_s:
            for m in range(3):
                col[m, c] = x[3 + m] - x[m]
            c += 1
        if free_t:
            for m in range(3):
                col[m, c] = -(x[9 + m] - x[6 + m])
        if nfree == 1:
            for m in range(3):
                wu0[m] = col[m, 0] / U[0, 0]
        else:
            det = U[0, 0] * U[1, 1] - U[0, 1] * U[1, 0]
            for m in range(3):
                wu0[m] = (col[m, 0] * U[1, 1] - col[m, 1] * U[1, 0]) / det
                wu1[m] = (-col[m, 0] * U[0, 1] + col[m, 1] * U[0, 0]) / det
    for m in range(3):
        for j in range(12):
            dw = coef[j // 3] if (j % 3) == m else 0.0
            if nfree > 0:
                dw -= wu0[m] * B[j, 0]
            if nfree > 1:
                dw -= wu1[m] * B[j, 1]
            dndx[m, j] = dw
    for j in range(12):
        proj = n[0] * dndx[0, j] + n[1] * dndx[1, j] + n[2] * dndx[2, j]
        for m in range(3):
            dndx[m, j] = (dndx[m, j] - proj * n[m]) / dist


@njit(cache=True, inline="always")
def _plane_normal_jacobian(x, nf, cnorm, dndx):
    """dm/dx (3, 12) of m = c/|c|, c = e1 x e2 (see :func:`_friction_normal`):
    dc/dx1 = [e2]x, dc/dx2 = -[e2]x, dc/dx3 = -[e1]x, dc/dx4 = [e1]x ([a]x b = a x b),
    dm = (I - m m^T) dc/|c|."""
    e1 = np.empty(3)
    e2 = np.empty(3)
    for m in range(3):
        e1[m] = x[3 + m] - x[m]
        e2[m] = x[9 + m] - x[6 + m]
    for node in range(4):
        v = e2 if node < 2 else e1
        sg = 1.0 if node == 0 or node == 3 else -1.0
        # columns b of sg [v]x: [v]x e_b = v x e_b
        for b in range(3):
            col0 = 0.0
            col1 = 0.0
            col2 = 0.0
            if b == 0:
                col1 = v[2]
                col2 = -v[1]
            elif b == 1:
                col0 = -v[2]
                col2 = v[0]
            else:
                col0 = v[1]
                col1 = -v[0]
            proj = nf[0] * col0 + nf[1] * col1 + nf[2] * col2
            j = 3 * node + b
            dndx[0, j] = sg * (col0 - proj * nf[0]) / cnorm
            dndx[1, j] = sg * (col1 - proj * nf[1]) / cnorm
            dndx[2, j] = sg * (col2 - proj * nf[2]) / cnorm


@njit(cache=True, inline="always")
def _anchor_friction(
    x, anc, slipped, n, fnorm, mu_s, mu_k, k_t, cn, grad, dofs, jac,
    force, rows, cols, vals, cnt, cw, u, ft, nf, coef, dist, B, U, dndx, G, a_min,
):  # fmt: skip
    """Elasto-plastic anchor friction of one rod-rod pair (return mapping of Coulomb's law
    with a tangential penalty; Wriggers, Computational Contact Mechanics, 2nd ed., sect.
    5.2.2), the rod-rod counterpart of the rod-cylinder anchor of ``contact_cylinder``.

    Force on edge i F = -mu |F_n| u / s, s = sqrt(|u|^2 + a^2), a = mu |F_n|/k_t, with
    u = P (X_a - X_b) the anchor's tangential gap (:func:`_anchor_gap`; P the projector on
    the friction plane of :func:`_friction_normal`): the spring -k_t u while |u| << a,
    capped smoothly at mu |F_n| (see ``SLIP_GAP``; a sharp stick/slip switch made Newton
    chatter: 9x the iterations of the regularised law on the clove-hitch pull). The pair
    slides when |u| > SLIP_GAP a (the commit then moves the anchor);
    mu = mu_k if the pair slid at the last accepted step (``slipped``), else mu_s. F acts
    on the anchor's material points: node k of the pair gets cw_k F (edge j the opposite
    force).

    Jacobian (if ``jac``), consistent with the return mapping: with D = X_a - X_b and nf
    the plane normal, du/dx = P C - (nf.D) dnf/dx - nf (u^T dnf/dx) (C = cw (x) I3; the
    plane turns as the rods roll over each other, which a gap of 2r turns into a
    tangential motion of the order of the nodes'),
    dF/dx = -(mu |F_n|/s) (I - u u^T/s^2) du/dx + F (|u|^2/s^2) (c_n grad Delta)^T, the
    last term through |F_n| (``cn`` = d2E/dDelta2 / dE/dDelta, 0 to leave it out).
    Returns (stored energy mu |F_n| (s - a), slides, entries written).

    ``a_min`` [m] > 0 floors the cap's width, a = max(mu |F_n|/k_t, a_min) (the
    ``cap_floor`` of :class:`knotmech.rod.friction.AnchorFriction`): a lightly loaded
    pair then sticks on the softer spring mu |F_n|/a_min, and where a is floored the
    term through |F_n| is F c_n grad^T (a no longer scales with |F_n|). ``a_min`` 0: the
    law as shipped, bit for bit.
    """
    cnorm = _friction_normal(x, n, nf)
    unorm, dpar = _anchor_gap(x, anc, nf, cw, u)
    mu = mu_k if slipped else mu_s
    limit = mu * fnorm
    a = limit / k_t
    floored = a < a_min
    if floored:
        a = a_min
    slip = unorm > SLIP_GAP * a
    sq = np.sqrt(unorm * unorm + a * a)
    if sq > 0.0:
        scale = limit / sq
    else:
        scale = k_t
    e_f = limit * (sq - a)
    for m in range(3):
        ft[m] = -scale * u[m]
    for k in range(4):
        for m in range(3):
            force[dofs[3 * k + m]] += cw[k] * ft[m]
    if not jac:
        return e_f, slip, cnt
    if cnorm > 0.0:
        _plane_normal_jacobian(x, nf, cnorm, dndx)
    else:
        _normal_jacobian(x, coef, n, dist, B, U, dndx)
    # G = du/dx (3, 12)
    for j in range(12):
        und = u[0] * dndx[0, j] + u[1] * dndx[1, j] + u[2] * dndx[2, j]
        c = cw[j // 3]
        b = j % 3
        for a in range(3):
            pab = ((1.0 if a == b else 0.0) - nf[a] * nf[b]) * c
            G[a, j] = pab - dpar * dndx[a, j] - nf[a] * und
    # dF/dx = -scale (I - u u^T/s^2) G + F (|u|^2/s^2) c_n grad^T, s^2 = |u|^2 + a^2
    if sq > 0.0:
        s2 = sq * sq
        wn = cn if floored else unorm * unorm / s2 * cn
        for j in range(12):
            ug = (u[0] * G[0, j] + u[1] * G[1, j] + u[2] * G[2, j]) / s2
            for b in range(3):
                G[b, j] = -scale * (G[b, j] - u[b] * ug) + ft[b] * wn * grad[j]
    else:
        for j in range(12):
            for b in range(3):
                G[b, j] = -scale * G[b, j]
    for k in range(4):
        for a in range(3):
            for j in range(12):
                rows[cnt] = dofs[3 * k + a]
                cols[cnt] = dofs[j]
                vals[cnt] = cw[k] * G[a, j]
                cnt += 1
    return e_f, slip, cnt


@njit(cache=True, inline="always")
def _pair_normal(x, edge_i, edge_j, radius_edge, sharpness, stiffness, grad, coef, w, n, frozen, p):
    """|F_n| of pair ``p`` at ``x`` and its normal into ``n`` (the penalty force on edge i,
    as in :func:`rodrod_assemble`; ``frozen``: its held parameters or None)."""
    dist = _pair_gap_grad(x, frozen, p, grad, coef, w)
    two_h = radius_edge[edge_i] + radius_edge[edge_j]
    _, de, _ = penalty_derivs(two_h - dist, sharpness, stiffness)
    fnorm = 0.0
    for m in range(3):
        n[m] = -de * (grad[m] + grad[3 + m])
        fnorm += n[m] * n[m]
    fnorm = np.sqrt(fnorm)
    if fnorm > 0.0:
        for m in range(3):
            n[m] /= fnorm
    return fnorm


@njit(cache=True, inline="always")
def _fresh_anchor(x, anc, coef, w, n, nf, cw, u):
    """Anchor of a new pair from its nodes ``x`` (12,) at the step start: the material
    points where the two edges touch, i.e. the closest points of the segments moved along
    the edge lines (:func:`_shift_anchor`) until X_a - X_b is normal to the friction plane
    (:func:`_friction_normal`): zero tangential gap. Writes ``anc`` (2,)."""
    dist, _, _ = _gap(x, coef, w)
    anc[0] = coef[1]
    anc[1] = -coef[3]
    if dist <= 0.0:
        return
    for m in range(3):
        n[m] = w[m] / dist
    _friction_normal(x, n, nf)
    _anchor_gap(x, anc, nf, cw, u)
    for m in range(3):
        u[m] = -u[m]
    _shift_anchor(x, anc, u)


@njit(cache=True, inline="always")
def _pair_nodes(pos, pairs, p, edge_nodes, x):
    """The 12 coordinates of pair p's nodes into ``x``; returns (e_i, e_j)."""
    ei = pairs[p, 0]
    ej = pairs[p, 1]
    nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
    for k in range(4):
        for m in range(3):
            x[3 * k + m] = pos[nodes[k], m]
    return ei, ej


@njit(cache=True)
def align_anchors(keys_old, anc_old, slip_old, keys, anc, slip, known):
    """Anchors for the candidate pairs ``keys`` (sorted, e_i * n_edges + e_j) from the
    committed ones (``keys_old`` sorted, ``anc_old`` (k, 2), ``slip_old``): a merge of
    the two sorted lists. Pairs without a committed anchor get ``known`` False (their
    anchor is made from the step-start positions when first needed)."""
    j = 0
    n_old = keys_old.shape[0]
    for i in range(keys.shape[0]):
        while j < n_old and keys_old[j] < keys[i]:
            j += 1
        if j < n_old and keys_old[j] == keys[i]:
            anc[i, 0] = anc_old[j, 0]
            anc[i, 1] = anc_old[j, 1]
            slip[i] = slip_old[j]
            known[i] = True
        else:
            slip[i] = False
            known[i] = False


@njit(cache=True)
def rodrod_anchor_commit(
    pos, pos_old, pairs, edge_nodes, radius_edge, sharpness, stiffness, z_cutoff,
    mu_s, mu_k, k_t, anchor, anchor_slip, known, keep, mode, cap_floor=0.0, floor_mode=0,
    frozen=None,
):  # fmt: skip
    """Commit (``mode`` 1) or stored energy (``mode`` 2) of the rod-rod anchors at ``pos``.

    For each candidate pair within the penalty's reach (k (2h - Delta) >= ``z_cutoff``, as
    in :func:`rodrod_near`) with a normal force (the others get ``keep`` False: the pair
    has left the contact and its anchor is dropped) the return mapping of
    :func:`_anchor_friction` is evaluated (a pair without an anchor yet, ``known`` False,
    gets it from ``pos_old``; mode 2 skips it); mode 1 writes whether it slides to
    ``anchor_slip`` and, if it does, moves the anchor's material points along the two edges
    (:func:`_shift_anchor`) so that the tangential gap shrinks to SLIP_GAP mu |F_n|/k_t.
    ``cap_floor``, ``floor_mode``: see :func:`rodrod_assemble`. With ``floor_mode`` 1 (the
    floor only on pairs that slid at the last step) the width a changes between steps, so
    the commit moves the anchor to the gap of the next step's width: a sliding pair to
    SLIP_GAP max(mu_k |F_n|/k_t, floor), a sticking pair that was floored to the gap that
    keeps its friction force under the unfloored spring (force-preserving transfer).
    ``frozen``: held closest-point parameters, as in :func:`rodrod_assemble` (the normal
    force and normal of a held pair are those of its held gap).
    Returns the anchors' stored energy (mode 2).
    """
    x = np.empty(12)
    grad = np.empty(12)
    coef = np.empty(4)
    w = np.empty(3)
    n = np.empty(3)
    nf = np.empty(3)
    cw = np.empty(4)
    u = np.empty(3)
    keep[:] = False
    energy = 0.0
    for p in range(pairs.shape[0]):
        ei, ej = _pair_nodes(pos, pairs, p, edge_nodes, x)
        if _beyond(x, radius_edge[ei] + radius_edge[ej] - z_cutoff / sharpness):
            continue  # out of the penalty's reach by far (as rodrod_near)
        if sharpness * (radius_edge[ei] + radius_edge[ej] - edge_distance(x)) < z_cutoff:
            continue
        if not known[p]:
            if mode == 2:  # a new pair stores nothing yet
                continue
            _pair_nodes(pos_old, pairs, p, edge_nodes, x)
            _fresh_anchor(x, anchor[p], coef, w, n, nf, cw, u)
            known[p] = True
            _pair_nodes(pos, pairs, p, edge_nodes, x)
        fnorm = _pair_normal(
            x, ei, ej, radius_edge, sharpness, stiffness, grad, coef, w, n, frozen, p
        )
        if not fnorm > 0.0:
            continue
        _friction_normal(x, n, nf)
        unorm, _ = _anchor_gap(x, anchor[p], nf, cw, u)
        mu = mu_k if anchor_slip[p] else mu_s
        limit = mu * fnorm
        a = limit / k_t
        two_h = radius_edge[ei] + radius_edge[ej]
        a_full = _cap_min(cap_floor, floor_mode, two_h, sharpness, True)
        a_min = _cap_min(cap_floor, floor_mode, two_h, sharpness, anchor_slip[p])
        if a < a_min:
            a = a_min
        slip = unorm > SLIP_GAP * a
        keep[p] = True
        if mode == 2:
            energy += limit * (np.sqrt(unorm * unorm + a * a) - a)
            continue
        anchor_slip[p] = slip
        target = SLIP_GAP * a if slip else unorm
        if floor_mode == 1:
            target = _next_gap(unorm, a, limit, slip, fnorm, mu_s, mu_k, k_t, a_full)
        if unorm > 0.0 and target != unorm:
            shrink = (unorm - target) / unorm
            for m in range(3):
                u[m] *= -shrink
            _shift_anchor(x, anchor[p], u)
    return energy


#: the ``cap_floor`` that is one penalty width 1/sharpness under ``floor_mode`` 2 and 3
FLOOR_REF = 1e-2


@njit(cache=True, inline="always")
def _cap_min(cap_floor, floor_mode, two_h, sharpness, slipped):
    """Floor a_min [m] of a pair's cap width: ``cap_floor`` (r_i + r_j) on every pair
    (``floor_mode`` 0) or on the pairs that slid at the last step (1); (``cap_floor`` /
    :data:`FLOOR_REF`) / ``sharpness`` (penalty widths) on every pair (2); the smaller
    of the two lengths on every pair (3)."""
    if floor_mode == 1 and not slipped:
        return 0.0
    radii = cap_floor * two_h
    if floor_mode < 2:
        return radii
    penalty = cap_floor / FLOOR_REF / sharpness
    return penalty if floor_mode == 2 else min(radii, penalty)


@njit(cache=True, inline="always")
def _next_gap(unorm, a, limit, slip, fnorm, mu_s, mu_k, k_t, a_full):
    """Anchor gap [m] after the commit under ``floor_mode`` 1 (the cap floored only on
    pairs that slid at the last step): a sliding pair at SLIP_GAP times the next step's
    (floored) width; a sticking pair at the gap whose force under the next step's
    (unfloored, mu_s) width equals the force it carries now (``limit`` |u|/s)."""
    if slip:
        return SLIP_GAP * max(mu_k * fnorm / k_t, a_full)
    a_next = mu_s * fnorm / k_t
    if a_next == a or mu_s <= 0.0:
        return unorm
    t = limit * unorm / np.sqrt(unorm * unorm + a * a) / (mu_s * fnorm)
    t = min(t, SLIP_GAP / np.sqrt(1.0 + SLIP_GAP * SLIP_GAP))
    return a_next * t / np.sqrt(1.0 - t * t)


@njit(cache=True)
def rodrod_energy(pos, pairs, edge_nodes, radius_edge, sharpness, stiffness, frozen=None):
    """Total penalty energy of the candidate pairs (IMC squared softplus); ``frozen``
    (n_pairs, 2) or None: the pairs with s >= 0 at their held parameters (the gap of
    :func:`_gap_at`, as in :func:`rodrod_assemble`)."""
    x = np.empty(12)
    coef = np.empty(4)
    w = np.empty(3)
    energy = 0.0
    for p in range(pairs.shape[0]):
        ei = pairs[p, 0]
        ej = pairs[p, 1]
        nodes = (edge_nodes[ei, 0], edge_nodes[ei, 1], edge_nodes[ej, 0], edge_nodes[ej, 1])
        for k in range(4):
            for m in range(3):
                x[3 * k + m] = pos[nodes[k], m]
        if frozen is not None and frozen[p, 0] >= 0.0:
            dist = _gap_at(x, frozen[p, 0], frozen[p, 1], coef, w)
        else:
            dist = edge_distance(x)
        e, de, d2e = penalty_derivs(radius_edge[ei] + radius_edge[ej] - dist, sharpness, stiffness)
        energy += e
    return energy


@njit(cache=True)
def max_pair_displacement(pairs, edge_nodes, node_dofs, radius_edge, q_new, q_old):
    """Largest |x_new - x_old| / r_e over the nodes of the edges e in ``pairs`` (each node
    taken with the radius of the paired edge): the tunnelling guard's measure."""
    worst = 0.0
    for p in range(pairs.shape[0]):
        for side in range(2):
            e = pairs[p, side]
            inv_r = 1.0 / radius_edge[e]
            for end in range(2):
                nd = edge_nodes[e, end]
                d2 = 0.0
                for m in range(3):
                    dx = q_new[node_dofs[nd, m]] - q_old[node_dofs[nd, m]]
                    d2 += dx * dx
                ratio = np.sqrt(d2) * inv_r
                if ratio > worst:
                    worst = ratio
    return worst


@njit(cache=True)
def max_node_speed(v, node_dofs):
    """max over nodes of |v_node| (``v`` the generalised velocity)."""
    vmax = 0.0
    for i in range(node_dofs.shape[0]):
        s2 = 0.0
        for m in range(3):
            s2 += v[node_dofs[i, m]] ** 2
        if s2 > vmax:
            vmax = s2
    return np.sqrt(vmax)


# columns of the per-pair table written by :func:`rodrod_friction_census`
CENSUS_COLUMNS = (
    "fnorm",  # |F_n| [N]
    "ft",  # |F_t| of the anchor law [N] (0 without anchors)
    "mu",  # the coefficient in force: mu_k if the pair slid at the last step, else mu_s
    "gap_over_a",  # |u| / a, a = mu |F_n| / k_t (the cap's width) [-]
    "a",  # the cap's width a [m]
    "slides",  # 1 if |u| > SLIP_GAP a
    "fresh",  # 1 if the pair had no committed anchor (made from the step start)
    "free_s",  # closest-point parameter on edge i inside (0, 1)
    "free_t",  # on edge j
    "plane_n",  # 1 if the friction plane is the pair normal's (near-parallel edges)
    "vt",  # |v_T| of the edge midpoints, (x - x_old)/dt projected off n [m/s]
    "ux",  # friction direction u/|u| (3 columns; 0 if |u| = 0)
    "uy",
    "uz",
    "anchor_in_edge",  # 1 if both anchor parameters lie in [0, 1]
)


@njit(cache=True)
def rodrod_friction_census(
    pos, pos_old, dt, pairs, edge_nodes, radius_edge, sharpness, stiffness, z_cutoff,
    mu_s, mu_k, k_t, anchor, anchor_slip, known, out, cap_floor=0.0, floor_mode=0,
):  # fmt: skip
    """Diagnostics of the friction each candidate pair carries at ``pos`` (read-only).
    ``cap_floor``, ``floor_mode``: the floor of the cap width, as in :func:`rodrod_assemble`.

    For each pair within the penalty's reach with a normal force, writes a row of ``out``
    (n_pairs, len(CENSUS_COLUMNS)) as named in :data:`CENSUS_COLUMNS` (rows of the other
    pairs are set to 0, ``fnorm`` 0). The anchor law's |F_t| = mu |F_n| |u| / sqrt(|u|^2 +
    a^2) is that of :func:`_anchor_friction`; a pair without a committed anchor
    (``known`` False) is given one from ``pos_old`` on a copy (the anchors are not
    changed). ``k_t`` <= 0: no anchors (the regularised law), only the geometry and v_T.
    Returns the number of rows written."""
    x = np.empty(12)
    xo = np.empty(12)
    grad = np.empty(12)
    coef = np.empty(4)
    w = np.empty(3)
    n = np.empty(3)
    nf = np.empty(3)
    cw = np.empty(4)
    u = np.empty(3)
    anc = np.empty(2)
    n_o = np.empty(3)
    vr = np.empty(3)
    out[:, :] = 0.0
    rows = 0
    for p in range(pairs.shape[0]):
        ei, ej = _pair_nodes(pos, pairs, p, edge_nodes, x)
        if sharpness * (radius_edge[ei] + radius_edge[ej] - edge_distance(x)) < z_cutoff:
            continue
        fnorm = _pair_normal(
            x, ei, ej, radius_edge, sharpness, stiffness, grad, coef, w, n, None, p
        )
        if not fnorm > 0.0:
            continue
        rows += 1
        _, _, free_s, free_t = _segment_params_flat(x)
        _pair_nodes(pos_old, pairs, p, edge_nodes, xo)
        vt2 = 0.0
        vn = 0.0
        for m in range(3):
            vi = 0.5 * (x[m] - xo[m] + x[3 + m] - xo[3 + m])
            vj = 0.5 * (x[6 + m] - xo[6 + m] + x[9 + m] - xo[9 + m])
            vr[m] = (vi - vj) / dt
            vn += vr[m] * n[m]
        for m in range(3):
            vt2 += (vr[m] - vn * n[m]) ** 2
        out[p, 0] = fnorm
        out[p, 7] = 1.0 if free_s else 0.0
        out[p, 8] = 1.0 if free_t else 0.0
        out[p, 10] = np.sqrt(vt2)
        if k_t <= 0.0:
            continue
        anc[0] = anchor[p, 0]
        anc[1] = anchor[p, 1]
        if not known[p]:
            _fresh_anchor(xo, anc, coef, w, n_o, nf, cw, u)
            out[p, 6] = 1.0
        _pair_normal(x, ei, ej, radius_edge, sharpness, stiffness, grad, coef, w, n, None, p)
        cnorm = _friction_normal(x, n, nf)
        unorm, _ = _anchor_gap(x, anc, nf, cw, u)
        mu = mu_k if anchor_slip[p] else mu_s
        limit = mu * fnorm
        two_h = radius_edge[ei] + radius_edge[ej]
        a = max(limit / k_t, _cap_min(cap_floor, floor_mode, two_h, sharpness, anchor_slip[p]))
        sq = np.sqrt(unorm * unorm + a * a)
        out[p, 1] = limit * unorm / sq if sq > 0.0 else 0.0
        out[p, 2] = mu
        out[p, 3] = unorm / a if a > 0.0 else 0.0
        out[p, 4] = a
        out[p, 5] = 1.0 if unorm > SLIP_GAP * a else 0.0
        out[p, 9] = 1.0 if cnorm == 0.0 else 0.0
        if unorm > 0.0:
            for m in range(3):
                out[p, 11 + m] = u[m] / unorm
        inside = anc[0] >= 0.0 and anc[0] <= 1.0 and anc[1] >= 0.0 and anc[1] <= 1.0
        out[p, 14] = 1.0 if inside else 0.0
    return rows


@njit(cache=True)
def positions_equal(q, node_dofs, pos):
    """True when the node positions of ``q`` equal ``pos`` (n_nodes, 3) entry for entry
    (``np.array_equal(q[node_dofs], pos)`` without gathering them)."""
    if pos.shape[0] != node_dofs.shape[0]:
        return False
    for i in range(node_dofs.shape[0]):
        for m in range(3):
            if q[node_dofs[i, m]] != pos[i, m]:
                return False
    return True


@njit(cache=True)
def pair_path_min_gap(pairs, edge_nodes, node_dofs, radius_edge, q_new, q_old, n_sub):
    """Smallest Delta / (r_i + r_j) of the candidate pairs along the straight path from
    ``q_old`` to ``q_new``, sampled at ``n_sub + 1`` evenly spaced points (both ends
    included): the tunnelling guard's test of an actual crossing. Two edges that pass
    through each other reach Delta = 0 on the path; with samples that move no node by
    more than m radii between them, the sample nearest the crossing has
    Delta / (r_i + r_j) <= m / 2."""
    x = np.empty(12)
    worst = np.inf
    for p in range(pairs.shape[0]):
        e, f = pairs[p, 0], pairs[p, 1]
        nodes = (edge_nodes[e, 0], edge_nodes[e, 1], edge_nodes[f, 0], edge_nodes[f, 1])
        inv_r = 1.0 / (radius_edge[e] + radius_edge[f])
        for j in range(n_sub + 1):
            lam = j / n_sub
            for a in range(4):
                for m in range(3):
                    d = node_dofs[nodes[a], m]
                    x[3 * a + m] = (1.0 - lam) * q_old[d] + lam * q_new[d]
            ratio = edge_distance(x) * inv_r
            if ratio < worst:
                worst = ratio
    return worst


@njit(cache=True)
def gather_positions(q, node_dofs):
    """The node positions ``q[node_dofs]`` (n_nodes, 3) as a new array (numpy's fancy
    indexing of the (n_nodes, 3) index array, in one pass)."""
    n = node_dofs.shape[0]
    pos = np.empty((n, 3))
    for i in range(n):
        for m in range(3):
            pos[i, m] = q[node_dofs[i, m]]
    return pos
