"""The reference and material frames of a Newton evaluation in one kernel call.

Private module. :func:`elastic_frames` runs, in the same order, the four frame kernels of
:mod:`.frames` (edge tangents, time-parallel transport of the reference frames, reference
twist, material frames), each compiled on its own (none uses fastmath): the same bits as
four calls from Python, without the dispatch of three calls per evaluation.

The gradient kernels (stretch, bend, twist) are NOT wrapped this way: a numba wrapper
calling the fastmath kernels bend and twist gave the same bits when compiled in the
process but different ones (round-off, 1e-12 relative) once loaded from numba's cache
(``tests/rod/test_speed_golden.py``, clove pull), so they stay three calls from Python.
"""

from __future__ import annotations

from numba import njit

from . import frames as _fr


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
def elastic_frames_cs(
    q, edge_dof0, stencil_edge, t_old, d1_old, rt_old, cos_old, sin_old, tangents, lengths, d1,
    d2, ref_twist, m1, m2,
):  # fmt: skip
    """:func:`elastic_frames` with ``cos_old``, ``sin_old`` = cos, sin of ``rt_old``
    (:func:`.frames.cos_sin`, once per step instead of once per Newton evaluation):
    the same bits."""
    _fr.edge_tangents(q, edge_dof0, tangents, lengths)
    _fr.transport_frames(t_old, d1_old, tangents, d1, d2)
    _fr.reference_twist_cs(stencil_edge, tangents, d1, rt_old, cos_old, sin_old, ref_twist)
    _fr.material_frames(q, edge_dof0, d1, d2, m1, m2)
