"""Elastic forces and Hessians of a rod system, on preallocated buffers.

Thin Python layer over the numba kernels in ``_kernels`` (stretch, bend, twist): reference
frames are carried from the start of the step to the current iterate by time-parallel
transport (Bergou et al. 2010 sec. 6), then the three energy families add their gradients
and local Hessians, which ``assembly`` scatters into band or COO storage.
"""

from __future__ import annotations

import numpy as np

from ._kernels import assembly as _asm
from ._kernels import bend as _bend
from ._kernels import elastic_eval as _ev
from ._kernels import frames as _fr
from ._kernels import stretch as _st
from ._kernels import twist as _tw

__all__ = ["ElasticWorkspace"]


class ElasticWorkspace:
    """Buffers and evaluation of the elastic energy of a :class:`~knotmech.rod.RodSystem`."""

    def __init__(self, system):
        s = system
        self.system = s
        ne, ns, nd = s.n_edges, s.n_stencils, s.n_dof
        self.tangents = np.empty((ne, 3))
        self.lengths = np.empty(ne)
        self.d1 = np.empty((ne, 3))
        self.d2 = np.empty((ne, 3))
        self.m1 = np.empty((ne, 3))
        self.m2 = np.empty((ne, 3))
        self.ref_twist = np.empty(ns)
        self.grad = np.zeros(nd)
        self.hess_s = np.empty((ne, 6, 6))
        self.hess8 = np.empty((ns, 8, 8))
        self.kappa = np.empty((ns, 2))
        self.twist = np.empty(ns)
        # the system's (immutable) arrays, looked up once: evaluations run per Newton iterate
        self._edge_dof0 = s.edge_dof0
        self._stencil_edge = s.stencil_edge
        self._rest_length = s.rest_length
        self._ea = s.ea
        self._kappa_bar = s.kappa_bar
        self._ei = s.ei
        self._voronoi = s.voronoi
        self._twist_bar = s.twist_bar
        self._gj = s.gj

    def frames(self, q, tangents_old, d1_old, ref_twist_old, trig=None) -> None:
        """Reference frames at ``q`` transported from the step-start frames; material frames.
        ``trig``: (cos, sin) of ``ref_twist_old`` if at hand (:func:`._kernels.frames.cos_sin`;
        the same result)."""
        if trig is None:
            _ev.elastic_frames(q, self._edge_dof0, self._stencil_edge, tangents_old, d1_old,
                               ref_twist_old, self.tangents, self.lengths, self.d1, self.d2,
                               self.ref_twist, self.m1, self.m2)  # fmt: skip
            return
        _ev.elastic_frames_cs(q, self._edge_dof0, self._stencil_edge, tangents_old, d1_old,
                              ref_twist_old, trig[0], trig[1], self.tangents, self.lengths,
                              self.d1, self.d2, self.ref_twist, self.m1, self.m2)  # fmt: skip

    def grad_hess(self, q, hessian: bool = True) -> None:
        """Gradient of the elastic energy into ``grad``; local Hessians into hess_s, hess8
        (unless ``hessian`` is False: then they are left stale); the (stretch, bend, twist)
        energies into ``energy_parts``. Call :meth:`frames` first.
        """
        ed0, se, vor, h = self._edge_dof0, self._stencil_edge, self._voronoi, bool(hessian)
        self.grad[:] = 0.0
        e_s = _st.stretch_grad_hess(q, ed0, self._rest_length, self._ea, self.grad, self.hess_s, h)
        e_b = _bend.bend_grad_hess(
            q, ed0, se, self.m1, self.m2, self._kappa_bar, self._ei, vor, self.grad, self.hess8, h
        )
        e_t = _tw.twist_grad_hess(
            q, ed0, se, self.ref_twist, self._twist_bar, self._gj, vor, self.grad, self.hess8, h
        )
        self.energy_parts = (e_s, e_b, e_t)

    def band_add(self, ab, full: bool = True) -> None:
        """Add the elastic Hessian into band storage: ``ab`` (31, n_dof) in the dgbsv layout
        (both triangles unless ``full`` is False), or (11, n_dof) in the dpbsv upper layout."""
        s = self.system
        off = _asm.BAND if ab.shape[0] == _asm.BAND + 1 else 2 * _asm.BAND
        _asm.band_add_hessians(s.edge_dof0, s.stencil_edge, self.hess_s, self.hess8, ab, off)
        if full and ab.shape[0] == 3 * _asm.BAND + 1:
            _asm.band_mirror(ab)

    def coo(self):
        """The elastic Hessian as COO triplets (rows, cols, vals)."""
        s = self.system
        n = 36 * s.n_edges + 121 * s.n_stencils
        rows = np.empty(n, dtype=np.int64)
        cols = np.empty(n, dtype=np.int64)
        vals = np.empty(n)
        _asm.coo_hessians(s.edge_dof0, s.stencil_edge, self.hess_s, self.hess8, rows, cols, vals)
        return rows, cols, vals

    def strains(self, q) -> None:
        """Material curvatures ``kappa`` and twists ``twist`` at ``q`` (call frames first)."""
        s = self.system
        _fr.curvatures(q, s.edge_dof0, s.stencil_edge, self.m1, self.m2, self.kappa)
        _fr.twists(q, s.edge_dof0, s.stencil_edge, self.ref_twist, self.twist)

    def energies(self, q) -> tuple[float, float, float]:
        """(stretching, bending, twisting) energies [J] at ``q`` (call frames first)."""
        s = self.system
        self.strains(q)
        e_s = _st.stretch_energy(q, s.edge_dof0, s.rest_length, s.ea)
        dk = self.kappa - s.kappa_bar
        e_b = float(np.sum(0.5 * s.ei / s.voronoi * (dk[:, 0] ** 2 + dk[:, 1] ** 2)))
        e_t = float(np.sum(0.5 * s.gj / s.voronoi * (self.twist - s.twist_bar) ** 2))
        return float(e_s), e_b, e_t

    def energy(self, q) -> float:
        """Total elastic energy [J] at ``q`` (call frames first)."""
        return float(sum(self.energies(q)))

    def tension(self, q) -> np.ndarray:
        """Axial force per edge [N]."""
        s = self.system
        out = np.empty(s.n_edges)
        _st.stretch_tension(q, s.edge_dof0, s.rest_length, s.ea, out)
        return out

    def moments(self, q):
        """Bending moments (n_stencils, 2) [N m] in the material frame, EI (kappa - kbar)/l,
        and twisting moments (n_stencils,) [N m], GJ (m - mbar)/l (call frames first)."""
        s = self.system
        self.strains(q)
        mb = (s.ei / s.voronoi)[:, None] * (self.kappa - s.kappa_bar)
        mt = s.gj / s.voronoi * (self.twist - s.twist_bar)
        return mb, mt
