"""External loads: gravity, dead forces on nodes, axial torques on edges, viscous damping.

Each load adds its generalized force F (shape (n_dof,)) and the diagonal of dF/dq to the
solver's buffers, and reports its potential energy (0 for damping).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_finite, check_nonnegative

__all__ = ["Gravity", "NodeForce", "EdgeTorque", "ViscousDamping"]


def _index_array(name, values, upper) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values))
    if arr.size and (arr.dtype.kind not in "iu" or arr.min() < -upper or arr.max() >= upper):
        raise InputError(f"{name} must be integer indices in [-{upper}, {upper}), got {values!r}")
    return np.mod(arr.astype(np.int64), upper) if arr.size else arr.astype(np.int64)


@dataclass(frozen=True)
class Gravity:
    """Uniform gravity on the lumped node masses: F = m_i g.

    Parameters
    ----------
    acceleration : (3,) array [m/s^2], default (0, 0, -9.81)
    """

    acceleration: tuple = (0.0, 0.0, -9.81)

    def __post_init__(self):
        g = check_finite("acceleration", self.acceleration)
        if g.shape != (3,):
            raise InputError(f"acceleration must be a 3-vector, got shape {g.shape}")
        object.__setattr__(self, "acceleration", tuple(float(x) for x in g))

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        g = np.asarray(self.acceleration)
        nd = system.node_dofs
        force[nd] += system.mass[nd] * g[None, :]

    def energy(self, system, q) -> float:
        g = np.asarray(self.acceleration)
        nd = system.node_dofs
        return float(-np.sum(system.mass[nd] * q[nd] * g[None, :]))


@dataclass(frozen=True)
class NodeForce:
    """Dead (constant) forces on nodes, e.g. a weight hanging on an end.

    Parameters
    ----------
    nodes : int or sequence of int  global node indices (negative counts from the end)
    force : (3,) or (n, 3) array [N]
    """

    nodes: object
    force: object

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        nodes = _index_array("nodes", self.nodes, system.n_nodes)
        f = check_finite("force", self.force)
        force[system.node_dofs[nodes]] += np.broadcast_to(f, (nodes.size, 3))

    def energy(self, system, q) -> float:
        nodes = _index_array("nodes", self.nodes, system.n_nodes)
        f = np.broadcast_to(check_finite("force", self.force), (nodes.size, 3))
        return float(-np.sum(q[system.node_dofs[nodes]] * f))


@dataclass(frozen=True)
class EdgeTorque:
    """Dead axial torques on edges (a generalized force on their twist angles).

    Parameters
    ----------
    edges : int or sequence of int  global edge indices
    torque : float or (n,) array [N m]  about the edge tangent
    """

    edges: object
    torque: object

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        edges = _index_array("edges", self.edges, system.n_edges)
        force[system.edge_theta_dof[edges]] += check_finite("torque", self.torque)

    def energy(self, system, q) -> float:
        edges = _index_array("edges", self.edges, system.n_edges)
        tau = np.broadcast_to(check_finite("torque", self.torque), edges.shape)
        return float(-np.sum(q[system.edge_theta_dof[edges]] * tau))


@dataclass(frozen=True)
class ViscousDamping:
    """Linear viscous drag F = -c l_i v_i on the nodes (and -c_r l_k omega_k on the angles).

    Parameters
    ----------
    coefficient : float [N s/m^2]  translational drag per unit length
    rotational : float [N s]  rotational drag per unit length (default 0)

    With v = (q - q_old)/dt the force is implicit: dF/dq = -c l / dt on the diagonal.
    """

    coefficient: float
    rotational: float = 0.0

    def __post_init__(self):
        object.__setattr__(
            self, "coefficient", float(check_nonnegative("coefficient", self.coefficient))
        )
        object.__setattr__(
            self, "rotational", float(check_nonnegative("rotational", self.rotational))
        )

    def _weights(self, system) -> np.ndarray:
        w = np.zeros(system.n_dof)
        le = system.rest_length
        for j in range(3):
            np.add.at(w, system.edge_dof0 + j, 0.5 * le * self.coefficient)
            np.add.at(w, system.edge_dof0 + 4 + j, 0.5 * le * self.coefficient)
        w[system.edge_theta_dof] = le * self.rotational
        return w

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        w = self._weights(system)
        force -= w * (q - q_old) / dt
        jac_diag -= w / dt

    def energy(self, system, q) -> float:
        return 0.0
