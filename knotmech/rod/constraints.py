"""Kinematic constraints: clamped nodes and twist angles, nodes moved along prescribed paths.

A constraint names dofs and gives their values at the end of each step; the solver
eliminates those dofs from the Newton solve and reports the reaction forces on them.
Values are computed from the previous step's values (``q_old``) so that a run resumed from
a checkpoint reproduces the uninterrupted run bit for bit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_finite
from .loads import _index_array

__all__ = ["Clamp", "MovingNodes", "NodeConstraint", "RotatingEdges", "clamp_end"]


def _cached_dofs(constraint, system) -> np.ndarray:
    """``constraint.dofs(system)``, computed (and its indices checked) once per system: the
    solver asks for the values of a constraint at every step attempt, and its indices are
    fixed at construction (the dataclasses are frozen)."""
    cache = constraint.__dict__.get("_dof_cache")
    if cache is None or cache[0] is not system:
        cache = (system, constraint.dofs(system))
        object.__setattr__(constraint, "_dof_cache", cache)
    return cache[1]


class NodeConstraint:
    """Base of the constraints that prescribe node coordinates and no twist angle: the
    subclass (a frozen dataclass) has a ``nodes`` field and gives ``dofs`` and ``values``."""

    def node_indices(self, system) -> np.ndarray:
        return _index_array("nodes", self.nodes, system.n_nodes)

    def edge_indices(self, system) -> np.ndarray:
        return np.zeros(0, dtype=np.int64)


@dataclass(frozen=True)
class Clamp:
    """Hold nodes (positions) and edges (twist angles) where they are.

    Parameters
    ----------
    nodes : sequence of int  global node indices (default none)
    edges : sequence of int  global edge indices whose twist angle is held (default none)
    """

    nodes: object = ()
    edges: object = ()

    def node_indices(self, system) -> np.ndarray:
        return _index_array("nodes", self.nodes, system.n_nodes)

    def edge_indices(self, system) -> np.ndarray:
        return _index_array("edges", self.edges, system.n_edges)

    def dofs(self, system) -> np.ndarray:
        return np.concatenate(
            [
                system.node_dofs[self.node_indices(system)].ravel(),
                system.edge_theta_dof[self.edge_indices(system)],
            ]
        )

    def values(self, system, t_new, dt, q_old) -> np.ndarray:
        return q_old[_cached_dofs(self, system)]


@dataclass(frozen=True)
class MovingNodes(NodeConstraint):
    """Move nodes along prescribed paths (e.g. pull an end at constant speed).

    Parameters
    ----------
    nodes : sequence of int  global node indices
    velocity : (3,) or (n, 3) array [m/s], optional  constant velocity: x += velocity dt
    path : callable t -> (n, 3) array [m], optional  absolute positions at time t
    Exactly one of ``velocity`` and ``path`` is given.
    """

    nodes: object
    velocity: object = None
    path: object = None

    def __post_init__(self):
        if (self.velocity is None) == (self.path is None):
            raise InputError("MovingNodes needs exactly one of velocity and path")
        if self.path is not None and not callable(self.path):
            raise InputError("path must be a callable t -> (n, 3) positions")

    def dofs(self, system) -> np.ndarray:
        return system.node_dofs[self.node_indices(system)].ravel()

    def values(self, system, t_new, dt, q_old) -> np.ndarray:
        dofs = _cached_dofs(self, system)
        n = dofs.size // 3
        if self.path is not None:
            x = self.path(t_new)
            # per step attempt: the full check only for what is not a finite float array
            if not (isinstance(x, np.ndarray) and x.dtype == float and np.isfinite(x).all()):
                x = check_finite("path(t)", x)
            out = np.empty((n, 3))
            out[...] = x  # broadcasts (3,) or (n, 3), as np.broadcast_to did
            return out.ravel()
        v = np.broadcast_to(check_finite("velocity", self.velocity), (n, 3)).ravel()
        return q_old[dofs] + v * dt


@dataclass(frozen=True)
class RotatingEdges:
    """Turn the twist angle of edges at a constant rate [rad/s] (theta += rate dt)."""

    edges: object
    rate: float

    def node_indices(self, system) -> np.ndarray:
        return np.zeros(0, dtype=np.int64)

    def edge_indices(self, system) -> np.ndarray:
        return _index_array("edges", self.edges, system.n_edges)

    def dofs(self, system) -> np.ndarray:
        return system.edge_theta_dof[self.edge_indices(system)]

    def values(self, system, t_new, dt, q_old) -> np.ndarray:
        return (
            q_old[_cached_dofs(self, system)]
            + float(check_finite("rate", self.rate, scalar=True)) * dt
        )


def clamp_end(system, rod: int = 0, end: str = "start", twist: bool = True) -> Clamp:
    """Clamp one end of a rod: its first (last) two nodes and, if ``twist``, its end edge angle."""
    if end not in ("start", "end"):
        raise InputError(f"end must be 'start' or 'end', got {end!r}")
    if not 0 <= rod < system.n_rods:
        raise InputError(f"rod must lie in [0, {system.n_rods - 1}], got {rod}")
    nodes = system.rod_nodes(rod)
    edges = system.rod_edges(rod)
    if end == "start":
        return Clamp(nodes=nodes[:2], edges=edges[:1] if twist else ())
    return Clamp(nodes=nodes[-2:], edges=edges[-1:] if twist else ())
