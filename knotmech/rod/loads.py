"""External loads: gravity, dead forces on nodes, axial torques on edges, viscous damping.

Each load adds its generalized force F (shape (n_dof,)) and the diagonal of dF/dq to the
solver's buffers, and reports its potential energy ``energy(system, q, t)`` (0 for damping).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_finite, check_nonnegative

__all__ = ["Gravity", "NodeForce", "EdgeTorque", "ViscousDamping"]


_GRAVITY_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _ramp(t, ramp_time) -> float:
    """Load factor min(1, t / ramp_time) (1 when ramp_time is 0)."""
    return 1.0 if ramp_time <= 0.0 else min(1.0, max(0.0, t / ramp_time))


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
    ramp_time : float [s]  the load grows linearly from 0 at t = 0 to full at ramp_time
        (default 0: applied at once); a ramp helps quasi-static solves with large dt
    """

    acceleration: tuple = (0.0, 0.0, -9.81)
    ramp_time: float = 0.0

    def __post_init__(self):
        g = check_finite("acceleration", self.acceleration)
        if g.shape != (3,):
            raise InputError(f"acceleration must be a 3-vector, got shape {g.shape}")
        object.__setattr__(self, "acceleration", tuple(float(x) for x in g))
        object.__setattr__(
            self, "ramp_time", float(check_nonnegative("ramp_time", self.ramp_time, scalar=True))
        )

    def _weights(self, system) -> np.ndarray:
        """Full-load generalized force m_i g on every dof (cached per system)."""
        cache = _GRAVITY_CACHE.setdefault(system, {})
        w = cache.get(self.acceleration)
        if w is None:
            w = np.zeros(system.n_dof)
            nd = system.node_dofs
            w[nd] = system.mass[nd] * np.asarray(self.acceleration)[None, :]
            cache[self.acceleration] = w
        return w

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        w = self._weights(system)
        lam = _ramp(t, self.ramp_time)
        if lam == 1.0:
            force += w
        else:
            force += lam * w

    def energy(self, system, q, t=np.inf) -> float:
        return -_ramp(t, self.ramp_time) * float(np.dot(self._weights(system), q))


@dataclass(frozen=True)
class NodeForce:
    """Dead (constant) forces on nodes, e.g. a weight hanging on an end.

    Parameters
    ----------
    nodes : int or sequence of int  global node indices (negative counts from the end)
    force : (3,) or (n, 3) array [N]
    ramp_time : float [s]  linear ramp from 0 at t = 0 (default 0: applied at once)
    """

    nodes: object
    force: object
    ramp_time: float = 0.0

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        nodes = _index_array("nodes", self.nodes, system.n_nodes)
        f = check_finite("force", self.force) * _ramp(t, self.ramp_time)
        force[system.node_dofs[nodes]] += np.broadcast_to(f, (nodes.size, 3))

    def energy(self, system, q, t=np.inf) -> float:
        nodes = _index_array("nodes", self.nodes, system.n_nodes)
        f = check_finite("force", self.force) * _ramp(t, self.ramp_time)
        f = np.broadcast_to(f, (nodes.size, 3))
        return float(-np.sum(q[system.node_dofs[nodes]] * f))


@dataclass(frozen=True)
class EdgeTorque:
    """Dead axial torques on edges (a generalized force on their twist angles).

    Parameters
    ----------
    edges : int or sequence of int  global edge indices
    torque : float or (n,) array [N m]  about the edge tangent
    ramp_time : float [s]  linear ramp from 0 at t = 0 (default 0: applied at once)
    """

    edges: object
    torque: object
    ramp_time: float = 0.0

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        edges = _index_array("edges", self.edges, system.n_edges)
        tau = check_finite("torque", self.torque) * _ramp(t, self.ramp_time)
        force[system.edge_theta_dof[edges]] += tau

    def energy(self, system, q, t=np.inf) -> float:
        edges = _index_array("edges", self.edges, system.n_edges)
        tau = check_finite("torque", self.torque) * _ramp(t, self.ramp_time)
        tau = np.broadcast_to(tau, edges.shape)
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
            self,
            "coefficient",
            float(check_nonnegative("coefficient", self.coefficient, scalar=True)),
        )
        object.__setattr__(
            self, "rotational", float(check_nonnegative("rotational", self.rotational, scalar=True))
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

    def energy(self, system, q, t=np.inf) -> float:
        return 0.0

    def step_potential(self, system, q, q_old, dt) -> float:
        """Rayleigh dissipation potential of the step, sum w (q - q_old)^2 / (2 dt) [J]:
        its q-gradient is -F, so the implicit step stays a minimisation."""
        w = self._weights(system)
        return float(0.5 * np.sum(w * (q - q_old) ** 2) / dt)
