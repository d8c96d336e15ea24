"""Helpers shared by the simulated experiments (scenes): section parameters, tensions."""

from __future__ import annotations

import numpy as np

from knotmech.errors import check_positive


def equivalent_section(*, diameter, youngs_modulus, density, bending_stiffness=None):
    r"""Radius, modulus and density of a DER rod with given EA, EI and mass per length.

    A solid rod of diameter d has :math:`EA = E\pi d^2/4`, :math:`EI = E\pi d^4/64`,
    :math:`\rho A`. A rope or cord bends far more easily than the solid value; with
    ``bending_stiffness`` B given, the rod used by the solver has radius
    :math:`r' = 2\sqrt{B/EA}` and modulus :math:`E' = EA/(\pi r'^2)` (same EA and B), and
    density :math:`\rho' = \rho A/(\pi r'^2)` (same mass per length). The contact diameter
    stays d (pass it to the contact as ``rod_radius``).

    Returns
    -------
    radius [m], youngs_modulus [Pa], density [kg/m^3] for :class:`knotmech.rod.Rod`.
    """
    d = float(check_positive("rod_diameter", diameter))
    e = float(check_positive("youngs_modulus", youngs_modulus))
    rho = float(check_positive("density", density))
    if bending_stiffness is None:
        return 0.5 * d, e, rho
    b = float(check_positive("bending_stiffness", bending_stiffness))
    area = np.pi * d**2 / 4
    ea = e * area
    r2 = 2.0 * np.sqrt(b / ea)
    return r2, ea / (np.pi * r2**2), rho * area / (np.pi * r2**2)


def edge_tension(system, positions) -> np.ndarray:
    """Axial force EA (|e|/|e_bar| - 1) [N] of every edge, (n_frames, n_edges) or (n_edges,)."""
    pos = np.asarray(positions, dtype=float)
    en = system.edge_nodes
    e = pos[..., en[:, 1], :] - pos[..., en[:, 0], :]
    return system.ea * (np.linalg.norm(e, axis=-1) / system.rest_length - 1.0)
