"""Finite-difference verification of the DER energies' gradients and Hessians.

The reference frames of a perturbed configuration are carried from the base configuration
by parallel transport (Bergou et al. 2010, sec. 6), which defines the energy E(q) whose
derivatives the kernels must reproduce at the base point. The analytic Hessian is the
(symmetric) Hessian of that energy; the finite-difference Jacobian of the analytic gradient
differs from it only by an antisymmetric holonomy term proportional to the twisting torques.
"""

import numpy as np
import pytest

from knotmech import rod
from knotmech.rod._kernels import bend as _bend
from knotmech.rod._kernels import stretch as _st
from knotmech.rod._kernels import twist as _tw


def _base(n=7, seed=0):
    rng = np.random.default_rng(seed)
    s = np.linspace(0.0, 1.0, n)
    pos = np.c_[np.cos(2 * s), np.sin(2 * s), 0.3 * s**2]
    r = rod.Rod(
        positions=pos, radius=0.05, youngs_modulus=1e3, density=1.0,
        thetas=0.3 * rng.standard_normal(n - 1),
    )  # fmt: skip
    system = rod.RodSystem([r])
    st = system.initial_state()
    ws = rod.ElasticWorkspace(system)
    # a base point away from the rest shape (non-zero curvature, twist and strain)
    q0 = st.q + 0.05 * rng.standard_normal(system.n_dof)
    ws.frames(q0, st.tangents, st.d1, st.ref_twist)
    frames0 = (ws.tangents.copy(), ws.d1.copy(), ws.ref_twist.copy())
    return system, ws, q0, frames0


def _family(system, ws, frames0, fam):
    """Energy, gradient and dense Hessian of one energy family, frames transported from base."""

    def energy(q):
        ws.frames(q, *frames0)
        return dict(zip("sbt", ws.energies(q), strict=True))[fam]

    def grad_hess(q):
        ws.frames(q, *frames0)
        g = np.zeros(system.n_dof)
        hs = np.zeros((system.n_edges, 6, 6))
        h8 = np.zeros((system.n_stencils, 8, 8))
        s = system
        if fam == "s":
            _st.stretch_grad_hess(q, s.edge_dof0, s.rest_length, s.ea, g, hs)
        elif fam == "b":
            _bend.bend_grad_hess(
                q, s.edge_dof0, s.stencil_edge, ws.m1, ws.m2, s.kappa_bar, s.ei, s.voronoi, g, h8
            )
        else:
            _tw.twist_grad_hess(
                q, s.edge_dof0, s.stencil_edge, ws.ref_twist, s.twist_bar, s.gj, s.voronoi, g, h8
            )
        ws.hess_s[:] = hs
        ws.hess8[:] = h8
        r, c, v = ws.coo()
        h = np.zeros((s.n_dof, s.n_dof))
        np.add.at(h, (r, c), v)
        return g, h

    return energy, grad_hess


@pytest.mark.parametrize("fam", ["s", "b", "t"])
def test_gradient_matches_central_differences(fam):
    system, ws, q0, frames0 = _base()
    energy, grad_hess = _family(system, ws, frames0, fam)
    g, _ = grad_hess(q0)
    errs = []
    for eps in (1e-3, 1e-4):
        gfd = np.array([
            (energy(q0 + eps * e) - energy(q0 - eps * e)) / (2 * eps) for e in np.eye(q0.size)
        ])  # fmt: skip
        errs.append(np.max(np.abs(gfd - g)) / np.max(np.abs(g)))
    # central differences: error O(eps^2), so 100x smaller for a 10x smaller step
    assert errs[1] < 1e-6
    assert errs[1] < errs[0] / 30


@pytest.mark.parametrize("fam", ["s", "b", "t"])
def test_hessian_matches_differences_of_gradient(fam):
    system, ws, q0, frames0 = _base()
    _, grad_hess = _family(system, ws, frames0, fam)
    _, h = grad_hess(q0)
    eps = 1e-6
    hfd = np.column_stack([
        (grad_hess(q0 + eps * e)[0] - grad_hess(q0 - eps * e)[0]) / (2 * eps)
        for e in np.eye(q0.size)
    ])  # fmt: skip
    sym = 0.5 * (hfd + hfd.T)
    scale = np.max(np.abs(h))
    assert np.max(np.abs(sym - h)) < 1e-7 * scale
    assert np.allclose(h, h.T, atol=1e-12 * scale)


@pytest.mark.parametrize("fam", ["b", "t"])
def test_hessian_matches_second_differences_of_energy(fam):
    """The full Hessian (no symmetrisation) against d2E/dq_i dq_j of the energy itself."""
    system, ws, q0, frames0 = _base(n=5, seed=1)
    energy, grad_hess = _family(system, ws, frames0, fam)
    _, h = grad_hess(q0)
    e = 1e-4
    n = q0.size
    eye = np.eye(n) * e
    hh = np.empty((n, n))
    for i in range(n):
        for j in range(i, n):
            hh[i, j] = hh[j, i] = (
                energy(q0 + eye[i] + eye[j]) - energy(q0 + eye[i] - eye[j])
                - energy(q0 - eye[i] + eye[j]) + energy(q0 - eye[i] - eye[j])
            ) / (4 * e * e)  # fmt: skip
    assert np.max(np.abs(hh - h)) < 1e-5 * np.max(np.abs(h))


def test_band_and_coo_assembly_agree():
    from knotmech.rod._kernels.assembly import band_to_dense

    system, ws, q0, frames0 = _base()
    ws.frames(q0, *frames0)
    ws.grad_hess(q0)
    ab = np.zeros((31, system.n_dof), order="F")
    ws.band_add(ab)
    r, c, v = ws.coo()
    h = np.zeros((system.n_dof, system.n_dof))
    np.add.at(h, (r, c), v)
    assert np.allclose(band_to_dense(ab, system.n_dof), h, rtol=0, atol=1e-13 * np.abs(h).max())


def test_curvature_binormal_is_two_tan_half_angle():
    """|kappa| of a planar kink of turning angle phi is 2 tan(phi/2) (Bergou 2008 eq. 1)."""
    phi = 0.7
    pos = np.array([[0, 0, 0], [1, 0, 0], [1 + np.cos(phi), np.sin(phi), 0.0]])
    r = rod.Rod(positions=pos, radius=0.01, youngs_modulus=1.0, density=1.0)
    system = rod.RodSystem([r])
    st = system.initial_state()
    ws = rod.ElasticWorkspace(system)
    ws.frames(st.q, st.tangents, st.d1, st.ref_twist)
    ws.strains(st.q)
    assert np.hypot(*ws.kappa[0]) == pytest.approx(2 * np.tan(phi / 2), rel=1e-14)
    assert system.kappa_bar[0] == pytest.approx(ws.kappa[0], rel=1e-14)


def test_strains_are_invariant_under_a_large_rigid_rotation():
    """Objectivity of frames, reference twist and curvatures: turn a bent, twisted rod rigidly
    by 3 rad in 40 increments, carrying the reference frames by time-parallel transport and
    tracking the reference twist (Bergou et al. 2010 sec. 6). With the twist angles set so
    that the material frames are the rigidly rotated ones, every material curvature is
    unchanged and every twist is unchanged modulo 2 pi."""
    system, ws, q0, frames0 = _base(n=12, seed=3)
    ws.frames(q0, *frames0)
    ws.strains(q0)
    kappa0, twist0, m1_0 = ws.kappa.copy(), ws.twist.copy(), ws.m1.copy()
    axis = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    kx = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    frames = frames0
    nd = system.node_dofs
    q = q0.copy()
    for ang in np.linspace(0, 3.0, 41)[1:]:
        rot = np.eye(3) + np.sin(ang) * kx + (1 - np.cos(ang)) * kx @ kx
        q[nd] = q0[nd] @ rot.T
        ws.frames(q, *frames)
        frames = (ws.tangents.copy(), ws.d1.copy(), ws.ref_twist.copy())
    target = m1_0 @ rot.T
    q[system.edge_theta_dof] = np.arctan2(
        np.sum(target * ws.d2, axis=1), np.sum(target * ws.d1, axis=1)
    )
    ws.frames(q, *frames)
    ws.strains(q)
    assert np.allclose(ws.kappa, kappa0, atol=1e-12)
    dtw = np.angle(np.exp(1j * (ws.twist - twist0)))
    assert np.allclose(dtw, 0.0, atol=1e-12)
    assert np.max(np.abs(frames[2] - frames0[2])) > 0.01  # the reference twist did change
