"""One kernel call per Newton evaluation for the elastic energy (frames, gradient, Hessian).

Private module. :func:`elastic_evaluate` runs, in the same order and with the same
arithmetic, what :class:`knotmech.rod.elastic.ElasticWorkspace` did in seven kernel calls
(edge tangents, time-parallel transport of the reference frames, reference twist,
material frames; then the stretching, bending and twisting gradients and local Hessians):
each kernel is compiled on its own, with its own floating-point flags, and called from
here, so the results are the same bit for bit. What it saves is the Python dispatch of
six calls with up to eleven array arguments each, per Newton evaluation.
"""

from __future__ import annotations

from numba import njit

from . import frames as _fr
from .bend import bend_grad_hess
from .stretch import stretch_grad_hess
from .twist import twist_grad_hess


@njit(cache=True)
def elastic_frames(
    q, edge_dof0, stencil_edge, t_old, d1_old, rt_old, tangents, lengths, d1, d2, ref_twist, m1, m2
):
    """Reference frames at ``q`` transported from the step-start frames (``t_old``,
    ``d1_old``, ``rt_old``), then the material frames: the outputs ``tangents`` (n_edges, 3),
    ``lengths`` (n_edges,) [m], ``d1``, ``d2``, ``m1``, ``m2`` (n_edges, 3) and
    ``ref_twist`` (n_stencils,) [rad] are overwritten."""
    _fr.edge_tangents(q, edge_dof0, tangents, lengths)
    _fr.transport_frames(t_old, d1_old, tangents, d1, d2)
    _fr.reference_twist(stencil_edge, tangents, d1, rt_old, ref_twist)
    _fr.material_frames(q, edge_dof0, d1, d2, m1, m2)


@njit(cache=True)
def elastic_grad_hess(
    q,
    edge_dof0,
    stencil_edge,
    rest_length,
    ea,
    m1,
    m2,
    kappa_bar,
    ei,
    voronoi,
    ref_twist,
    twist_bar,
    gj,
    grad,
    hess_s,
    hess8,
    with_hess,
):
    """Zero ``grad`` (n_dof,) and add the stretching, bending and twisting gradients [N, N m]
    to it, in that order; write the local Hessians into ``hess_s`` (n_edges, 6, 6) and
    ``hess8`` (n_stencils, 8, 8) unless ``with_hess`` is False. Returns the three energies
    (E_s, E_b, E_t) [J]. Call :func:`elastic_frames` first (``m1``, ``m2``, ``ref_twist``)."""
    for i in range(grad.shape[0]):
        grad[i] = 0.0
    e_s = stretch_grad_hess(q, edge_dof0, rest_length, ea, grad, hess_s, with_hess)
    e_b = bend_grad_hess(
        q, edge_dof0, stencil_edge, m1, m2, kappa_bar, ei, voronoi, grad, hess8, with_hess
    )
    e_t = twist_grad_hess(
        q, edge_dof0, stencil_edge, ref_twist, twist_bar, gj, voronoi, grad, hess8, with_hess
    )
    return e_s, e_b, e_t
