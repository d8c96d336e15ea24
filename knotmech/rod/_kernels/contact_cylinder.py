"""Rod node - rigid cylinder contact: smooth penalty normal force, elasto-plastic friction.

Private module: arrays in, results written in place.

Normal force: the squared-softplus penalty of the implicit contact model (Choi, Tong & Jawed,
J. Appl. Mech. 88 (2021) 051010; coated-rod paper eq. 10 inside the square) on the signed gap
g = |P_a (x - p)| - (R + r) of each node, weighted by the node's Voronoi length w:

.. math:: E_i = K w_i \\left[\\log(1 + e^{-k g_i})/k\\right]^2 .

Friction: an elasto-plastic anchor spring (Wriggers, "Computational Contact Mechanics", 2nd
ed., sect. 5.2.2, return mapping of Coulomb's law with a tangential penalty): trial force
F_t = -k_t w P_n (x - x_anchor); if |F_t| <= mu N it sticks, otherwise it slips with
|F_t| = mu N along the trial direction, mu = mu_s when the contact stuck at the previous step
and mu_k when it slipped. The friction acts on the contact surface, at r_c = -r n from the
centreline (n the outward normal of the cylinder): its couple C = r_c x F_t on the
cross-section is applied as nodal force pairs +-(C x e)/|e|^2 on the adjacent edges (half to
each) and its twisting part C.t on the edges' twist angles.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from knotmech.rod._kernels.contact_rodrod import penalty_derivs

ENTRIES_PER_CONTACT = 144


@njit(cache=True)
def _cross(a, b):
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


@njit(cache=True)
def _skew(a):
    s = np.zeros((3, 3))
    s[0, 1] = -a[2]
    s[0, 2] = a[1]
    s[1, 0] = a[2]
    s[1, 2] = -a[0]
    s[2, 0] = -a[1]
    s[2, 1] = a[0]
    return s


@njit(cache=True, inline="always")
def _write_block(rows, cols, vals, k0, row_dofs, col_dofs, m):
    """Write the 3x3 block ``m`` (d force[row_dofs] / d q[col_dofs]) as triplets at slots
    k0 + 3 a + b."""
    for a in range(3):
        for b in range(3):
            k = k0 + 3 * a + b
            rows[k] = row_dofs[a]
            cols[k] = col_dofs[b]
            vals[k] = m[a, b]


@njit(cache=True, inline="always")
def _clear_contact(i, c, base, node_dofs, rows, cols, vals, out_normal, out_friction, out_slip):
    """Zero the ENTRIES_PER_CONTACT triplet slots and the outputs of node ``i`` and
    cylinder ``c`` (mode 0: slots left unused stay zero-valued)."""
    for a in range(ENTRIES_PER_CONTACT):
        rows[base + a] = node_dofs[i, 0]
        cols[base + a] = node_dofs[i, 0]
        vals[base + a] = 0.0
    out_normal[i, c] = 0.0
    out_slip[i, c] = False
    for m in range(3):
        out_friction[i, c, m] = 0.0


@njit(cache=True, inline="always")
def _radial_gap(x, point, axis, cyl_radius, half_length, node_radius, sharpness):
    """Radial vector, its length rho [m] and the signed gap g = rho - (R + r) [m] of a node
    at ``x`` from a cylinder; ``far``: beyond the penalty's reach (k g > 40), past the
    cylinder's ends, or on its axis."""
    rel = x - point
    xi = rel @ axis
    radial = rel - xi * axis
    rho = np.sqrt(radial @ radial)
    gap = rho - cyl_radius - node_radius
    far = sharpness * gap > 40.0 or abs(xi) > half_length or rho == 0.0
    return radial, rho, gap, far


@njit(cache=True, inline="always")
def _normal_term(n, axis, rho, de, d2e, normal, dofs, base, force, rows, cols, vals):
    """Penalty force N n on the node and its Jacobian block at ``base``:
    dF/dx = -(d2E n n^T + dE (P_a - n n^T)/rho), P_a = I - a a^T (module docstring's E)."""
    Paxis = np.eye(3) - np.outer(axis, axis)
    for m in range(3):
        force[dofs[m]] += normal * n[m]
    K = -(d2e * np.outer(n, n) + de * (Paxis - np.outer(n, n)) / rho)
    _write_block(rows, cols, vals, base, dofs, dofs, K)


@njit(cache=True, inline="always")
def _friction_trial(x, anc, n, kw, mu, normal):
    """Trial of the return mapping (Wriggers sect. 5.2.2): the tangential offset u from the
    anchor, |u|, the Coulomb limit mu N [N] and whether the trial force k_t w |u| exceeds
    it (slip)."""
    d = x - anc
    u = d - (d @ n) * n
    unorm = np.sqrt(u @ u)
    limit = mu * normal
    slip = kw * unorm > limit
    return u, unorm, limit, slip


@njit(cache=True, inline="always")
def _friction_energy(limit, unorm, kw, slip):
    """Stored energy [J] of the tangential spring (stick) or the plastic potential
    mu N |u| - (mu N)^2/(2 k_t w) (slip), continuous at the yield point."""
    if slip:
        return limit * unorm - 0.5 * limit * limit / kw
    return 0.5 * kw * unorm * unorm


@njit(cache=True, inline="always")
def _commit_anchor(i, c, x, anc, u, unorm, limit, kw, slip, anchor, anchor_valid, slipping):
    """Return mapping's state update (mode 1): a sliding contact's anchor follows the node
    to the yield distance mu N/(k_t w) behind it; a sticking one keeps its anchor."""
    if slip:
        anchor[i, c] = x - (limit / kw) * (u / unorm)
    else:
        anchor[i, c] = anc
    anchor_valid[i, c] = True
    slipping[i, c] = slip


@njit(cache=True, inline="always")
def _friction_force(u, unorm, n, kw, mu, limit, slip, dnormal_dg):
    """Friction force F_t [N] and its Jacobian dF_t/dx (normal direction lagged): stick
    F_t = -k_t w u, J = -k_t w P_n; slip F_t = -mu N u/|u|, J = -(mu N/|u|)(I - uh uh^T) P_n
    - mu dN/dg uh n^T."""
    Pn = np.eye(3) - np.outer(n, n)
    if slip:
        uh = u / unorm
        ft = -limit * uh
        J = -(limit / unorm) * ((np.eye(3) - np.outer(uh, uh)) @ Pn)
        J -= mu * dnormal_dg * np.outer(uh, n)
    else:
        ft = -kw * u
        J = -kw * Pn
    return ft, J


@njit(cache=True)
def _couple_on_edge(ed, Ce, dCe, pos, node_dofs, edge_nodes, edge_theta_dof, dofs,
                    force, rows, cols, vals, slot):  # fmt: skip
    """The share ``Ce`` of the friction couple carried by edge ``ed`` (module docstring):
    nodal force pair +-(Ce x e)/|e|^2 and twisting torque Ce.t, with their derivatives
    through the contact node (``dCe`` = dCe/dx_i, lever arm lagged) and through the edge
    vector e = x_b - x_a. Writes 48 triplets from ``slot``; returns the next free slot."""
    na = edge_nodes[ed, 0]
    nb = edge_nodes[ed, 1]
    ev = pos[nb] - pos[na]
    l2 = ev @ ev
    t = ev / np.sqrt(l2)
    fb = _cross(Ce, ev) / l2
    tw = Ce @ t
    for m in range(3):
        force[node_dofs[nb, m]] += fb[m]
        force[node_dofs[na, m]] -= fb[m]
    force[edge_theta_dof[ed]] += tw
    # d fb/dx_i = -[e]x dCe/dx_i / |e|^2 ; d tw/dx_i = t^T dCe/dx_i
    dfb = -(_skew(ev) @ dCe) / l2
    dtw = t @ dCe
    for a in range(3):
        for b in range(3):
            rows[slot] = node_dofs[nb, a]
            cols[slot] = dofs[b]
            vals[slot] = dfb[a, b]
            slot += 1
            rows[slot] = node_dofs[na, a]
            cols[slot] = dofs[b]
            vals[slot] = -dfb[a, b]
            slot += 1
    for b in range(3):
        rows[slot] = edge_theta_dof[ed]
        cols[slot] = dofs[b]
        vals[slot] = dtw[b]
        slot += 1
    # through the edge vector: d fb/d e = [Ce]x/|e|^2 - 2 (Ce x e) e^T/|e|^4,
    # d tw/d e = Ce^T (I - t t^T)/|e|; e = x_b - x_a
    dfe = _skew(Ce) / l2 - 2.0 * np.outer(fb, ev) / l2
    dte = (Ce - (Ce @ t) * t) / np.sqrt(l2)
    for a in range(3):
        for b in range(3):
            rows[slot] = node_dofs[nb, a]
            cols[slot] = node_dofs[nb, b]
            vals[slot] = dfe[a, b]
            rows[slot + 1] = node_dofs[nb, a]
            cols[slot + 1] = node_dofs[na, b]
            vals[slot + 1] = -dfe[a, b]
            rows[slot + 2] = node_dofs[na, a]
            cols[slot + 2] = node_dofs[nb, b]
            vals[slot + 2] = -dfe[a, b]
            rows[slot + 3] = node_dofs[na, a]
            cols[slot + 3] = node_dofs[na, b]
            vals[slot + 3] = dfe[a, b]
            slot += 4
    for b in range(3):
        rows[slot] = edge_theta_dof[ed]
        cols[slot] = node_dofs[nb, b]
        vals[slot] = dte[b]
        rows[slot + 1] = edge_theta_dof[ed]
        cols[slot + 1] = node_dofs[na, b]
        vals[slot + 1] = -dte[b]
        slot += 2
    return slot


@njit(cache=True)
def _surface_couple(i, n, ft, J, base, pos, node_radius, node_edges, node_dofs, edge_nodes,
                    edge_theta_dof, force, rows, cols, vals):  # fmt: skip
    """Couple C = r_c x F_t of the friction acting at r_c = -r n (the contact surface) on
    node ``i``'s cross-section, shared equally by its adjacent edges (module docstring);
    triplets from slot base + 18."""
    rc = -node_radius[i] * n
    C = _cross(rc, ft)
    dC = _skew(rc) @ J  # dC/dx_i (3, 3), lever arm lagged
    nadj = 0
    for s in range(2):
        if node_edges[i, s] >= 0:
            nadj += 1
    share = 1.0 / nadj
    slot = base + 18
    for s in range(2):
        ed = node_edges[i, s]
        if ed < 0:
            continue
        slot = _couple_on_edge(ed, share * C, share * dC, pos, node_dofs, edge_nodes,
                               edge_theta_dof, node_dofs[i], force, rows, cols, vals,
                               slot)  # fmt: skip


@njit(cache=True)
def cylinder_assemble(
    pos,
    pos_old,
    node_dofs,
    node_weight,
    node_radius,
    node_edges,
    edge_nodes,
    edge_theta_dof,
    cyl_point,
    cyl_axis,
    cyl_radius,
    cyl_half_length,
    sharpness,
    stiffness,
    mu_s,
    mu_k,
    k_t,
    surface,
    anchor,
    anchor_valid,
    slipping,
    mode,
    force,
    rows,
    cols,
    vals,
    out_normal,
    out_friction,
    out_slip,
):
    """Forces and Jacobian (``mode`` = 0) or state commit (``mode`` = 1) of all node-cylinder
    contacts.

    Shapes: ``pos``, ``pos_old`` (n_nodes, 3) [m]; ``node_edges`` (n_nodes, 2) previous/next
    edge (-1 if none); cylinders (n_cyl, 3), (n_cyl, 3) unit axes, (n_cyl,) radii and half
    lengths (inf for an infinite cylinder); ``anchor`` (n_nodes, n_cyl, 3),
    ``anchor_valid``/``slipping`` (n_nodes, n_cyl) booleans (the committed state).

    mode 0 adds the forces into ``force`` (n_dof,) and writes ENTRIES_PER_CONTACT Jacobian
    triplets (dF/dq) per node-cylinder pair (zeros where unused). Lagged in the Jacobian:
    the normal direction's dependence on x in the friction terms and in the couple's lever
    arm (the edge vectors of the couple are differentiated). mode 1 updates ``anchor``,
    ``anchor_valid``, ``slipping``; mode 2 only sums the energy (penalty, plus the
    tangential spring's energy of contacts with a committed anchor).
    Returns the penalty energy.
    """
    nn = pos.shape[0]
    nc = cyl_point.shape[0]
    energy = 0.0
    for i in range(nn):
        for c in range(nc):
            base = (i * nc + c) * ENTRIES_PER_CONTACT
            if mode == 0:
                _clear_contact(i, c, base, node_dofs, rows, cols, vals, out_normal,
                               out_friction, out_slip)  # fmt: skip
            radial, rho, gap, far = _radial_gap(pos[i], cyl_point[c], cyl_axis[c],
                                                cyl_radius[c], cyl_half_length[c],
                                                node_radius[i], sharpness)  # fmt: skip
            if far:
                if mode == 1:
                    anchor_valid[i, c] = False
                    slipping[i, c] = False
                continue
            n = radial / rho
            e, de, d2e = penalty_derivs(-gap, sharpness, stiffness * node_weight[i])
            # with gap_arg = -g, de = dE/dg and d2e = d2E/dg2
            energy += e
            normal = -de  # >= 0 [N]
            dofs = node_dofs[i]
            if mode == 0:
                _normal_term(n, cyl_axis[c], rho, de, d2e, normal, dofs, base, force,
                             rows, cols, vals)  # fmt: skip
                out_normal[i, c] = normal
            if (mu_s <= 0.0 and mu_k <= 0.0) or (mode == 2 and not anchor_valid[i, c]):
                continue
            # --- elasto-plastic friction (return mapping) ---
            anc = anchor[i, c] if anchor_valid[i, c] else pos_old[i]
            kw = k_t * node_weight[i]
            mu = mu_k if slipping[i, c] else mu_s
            u, unorm, limit, slip = _friction_trial(pos[i], anc, n, kw, mu, normal)
            if mode == 2:
                energy += _friction_energy(limit, unorm, kw, slip)
                continue
            if mode == 1:
                _commit_anchor(i, c, pos[i], anc, u, unorm, limit, kw, slip, anchor,
                               anchor_valid, slipping)  # fmt: skip
                continue
            ft, J = _friction_force(u, unorm, n, kw, mu, limit, slip, -d2e)
            out_slip[i, c] = slip
            for m in range(3):
                force[dofs[m]] += ft[m]
                out_friction[i, c, m] = ft[m]
            _write_block(rows, cols, vals, base + 9, dofs, dofs, J)
            if surface:
                _surface_couple(i, n, ft, J, base, pos, node_radius, node_edges, node_dofs,
                                edge_nodes, edge_theta_dof, force, rows, cols, vals)  # fmt: skip
    return energy
