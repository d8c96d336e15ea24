"""Helpers shared by the simulated experiments (scenes): section parameters, tensions."""

from __future__ import annotations

import math

import numpy as np

from knotmech.errors import InputError, check_positive


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


#: default bound on the work of one scene run: nominal steps x nodes (see check_run_size)
MAX_NODE_STEPS = 2e8

#: rough cost of one node-step of a scene with frictional contact [s] (1 us per node per
#: Newton iteration, ``benchmarks/der_step.py``, times 2-4 iterations and contact)
_SECONDS_PER_NODE_STEP = 3e-6


def check_run_size(*, n_nodes, t_end, dt, max_node_steps=None, hint="") -> float:
    """Refuse, before anything is allocated, a run that could not finish in reasonable time.

    The work of an implicit DER run grows as (nominal steps) x (nodes), steps =
    ``t_end / dt``. A run above ``max_node_steps`` (default :data:`MAX_NODE_STEPS`,
    2e8: about 10 minutes at a few microseconds per node-step) is refused with the
    estimate, so that a mistyped time step (``1e-12 s``), speed or element count gets
    one line instead of hours (or an out-of-memory error).

    Parameters
    ----------
    n_nodes : float
        Number of nodes the rod(s) will have (may be an estimate, computed before the
        rod is built).
    t_end : float [s]
        Simulated time.
    dt : float [s]
        Nominal time step.
    max_node_steps : float, optional
        The bound; ``inf`` lifts it.
    hint : str
        What to change, appended to the message (e.g. "use a larger dt").

    Returns
    -------
    float
        The estimated node-steps.

    Raises
    ------
    InputError
        The estimate exceeds the bound, or is not finite.
    """
    limit = MAX_NODE_STEPS if max_node_steps is None else float(max_node_steps)
    if not limit > 0:
        raise InputError(f"max_node_steps must be > 0, got {max_node_steps!r}")
    steps = float(t_end) / float(dt)
    work = steps * float(n_nodes)
    if not math.isfinite(work) or work > limit:
        secs = work * _SECONDS_PER_NODE_STEP
        raise InputError(
            f"this run would take {steps:.3g} steps (t_end {float(t_end):.3g} s / dt "
            f"{float(dt):.3g} s) x {float(n_nodes):.3g} nodes = {work:.3g} node-steps, about "
            f"{_duration(secs)}, above the limit of {limit:.3g} (max_node_steps)"
            + (f"; {hint}" if hint else "")
        )
    return work


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "forever"
    for unit, size in (("years", 3.15e7), ("days", 86400.0), ("hours", 3600.0),
                       ("minutes", 60.0)):  # fmt: skip
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"
