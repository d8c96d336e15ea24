"""The interaction protocol (extra forces with non-local Jacobian blocks) and a spring example.

See ``/notes/der_contract.md``: an interaction ADDS its generalized force F(q) into
``force`` and APPENDS the entries of dF/dq to a :class:`~knotmech.rod.Triplets`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from ..errors import InputError, check_finite, check_nonnegative
from .loads import _index_array

__all__ = ["Interaction", "PointSpring"]


@runtime_checkable
class Interaction(Protocol):
    """Protocol of the ``interactions`` passed to :func:`knotmech.rod.simulate`."""

    def begin_step(self, system, q_old, v_old, dt) -> None:
        """Once per attempted step before Newton (idempotent: retried with a smaller dt)."""

    def assemble(self, system, q, q_old, dt, force, triplets) -> None:
        """Add F(q) to ``force`` (n_dof,) and append dF/dq entries to ``triplets``."""

    def end_step(self, system, q_new, q_old, dt) -> None:
        """Commit internal state after an accepted step."""

    def energy(self, system, q) -> float:
        """Potential energy [J] (0.0 for non-conservative terms)."""

    # Optional (looked up with getattr, not part of the runtime check):
    # ``check_step(system, q_new, q_old, dt) -> str | None`` is called on a converged
    # step; a returned reason rejects it and the solver retries with half the step
    # (RodContact's tunnelling guard).
    # ``state_arrays() -> dict`` and ``load_state_arrays(dict)``: internal state committed
    # by ``end_step`` (friction anchors), carried in ``State.interactions`` so that a
    # checkpoint resumes bit-identically in a new process (see
    # :func:`interaction_state`).


def interaction_state(interactions) -> dict:
    """``{k: arrays}`` of the interactions that have a ``state_arrays`` method (k: their
    position in ``interactions``), for :attr:`knotmech.rod.State.interactions`."""
    out = {}
    for k, it in enumerate(interactions):
        get = getattr(it, "state_arrays", None)
        if get is not None:
            out[k] = get()
    return out


def restore_interaction_state(interactions, saved) -> None:
    """Give each interaction its arrays from ``saved`` (a :func:`interaction_state`
    dictionary, e.g. read back by ``State.load``); None leaves them as they are."""
    if saved is None:
        return
    for k, arrays in saved.items():
        put = getattr(interactions[k], "load_state_arrays", None) if k < len(interactions) else None
        if put is None:
            raise InputError(
                f"the state holds the internal state of interaction {k}, which the "
                "interactions passed to simulate do not take (pass the same interactions, "
                "in the same order, as the run that wrote it)"
            )
        put(arrays)


@dataclass(frozen=True)
class PointSpring:
    """Linear springs pulling nodes toward fixed points: F = -k (x - p).

    A minimal interaction (used in the tests to exercise the sparse path); with two
    ``nodes`` and ``pair=True`` it couples them instead, F_a = -k (x_a - x_b - offset) =
    -F_b, a non-local Jacobian block (``offset`` [m] is the rest value of x_a - x_b).
    """

    nodes: object
    stiffness: float
    point: object = (0.0, 0.0, 0.0)
    pair: bool = False
    offset: object = (0.0, 0.0, 0.0)

    def begin_step(self, system, q_old, v_old, dt) -> None:
        pass

    def end_step(self, system, q_new, q_old, dt) -> None:
        pass

    def _idx(self, system):
        return system.node_dofs[_index_array("nodes", self.nodes, system.n_nodes)]

    def assemble(self, system, q, q_old, dt, force, triplets) -> None:
        k = float(check_nonnegative("stiffness", self.stiffness, scalar=True))
        d = self._idx(system)
        eye = np.arange(3)
        if self.pair:
            a, b = d[0], d[1]
            f = -k * (q[a] - q[b] - check_finite("offset", self.offset))
            force[a] += f
            force[b] -= f
            for r, c, s in ((a, a, -k), (b, b, -k), (a, b, k), (b, a, k)):
                triplets.add(r[eye], c[eye], np.full(3, s))
            return
        p = check_finite("point", self.point)
        force[d] += -k * (q[d] - np.broadcast_to(p, d.shape))
        triplets.add(d.ravel(), d.ravel(), np.full(d.size, -k))

    def energy(self, system, q) -> float:
        k = float(self.stiffness)
        d = self._idx(system)
        if self.pair:
            off = np.asarray(self.offset, dtype=float)
            return 0.5 * k * float(np.sum((q[d[0]] - q[d[1]] - off) ** 2))
        p = np.broadcast_to(np.asarray(self.point, dtype=float), d.shape)
        return 0.5 * k * float(np.sum((q[d] - p) ** 2))
