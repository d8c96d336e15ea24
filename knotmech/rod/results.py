"""The Result of a simulation: trajectory, reactions, internal forces, energies; .npz I/O."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from .system import State

__all__ = ["Result", "load_result"]

_ARRAYS = (
    "times",
    "positions",
    "thetas",
    "reaction_nodes",
    "reactions",
    "reaction_edges",
    "reaction_torques",
    "tension",
    "bending_moment",
    "twisting_moment",
)


@dataclass(eq=False)
class Result:
    """Outcome of :func:`knotmech.rod.simulate`.

    Attributes
    ----------
    status : {"success", "failed"}
    message : str
    stats : dict  steps, newton_iterations, rejected_steps, wall_s
    times : (n_frames,) [s]
    positions : (n_frames, n_nodes, 3) [m]
    thetas : (n_frames, n_edges) [rad]
    reaction_nodes : (k,) int  constrained nodes, in the order of ``reactions``
    reactions : (n_frames, k, 3) [N]  force the constraints exert ON the rod at those nodes
        (at a pulled end: the force the gripper applies, i.e. the measured pull force)
    reaction_edges : (m,) int  edges with a constrained twist angle
    reaction_torques : (n_frames, m) [N m]  axial torque the constraints exert on them
    tension : (n_frames, n_edges) [N]  ``EA (|e|/|ebar| - 1)``
    bending_moment : (n_frames, n_stencils, 2) [N m]  EI (kappa - kbar)/l, material frame
    twisting_moment : (n_frames, n_stencils) [N m]  GJ (m - mbar)/l
    energies : dict of (n_frames,) arrays [J]  stretch, bend, twist, kinetic, external
        (potential of the loads), interaction
    final_state : State  the last accepted state (resume from it)
    """

    status: str
    message: str
    stats: dict
    times: np.ndarray
    positions: np.ndarray
    thetas: np.ndarray
    reaction_nodes: np.ndarray
    reactions: np.ndarray
    reaction_edges: np.ndarray
    reaction_torques: np.ndarray
    tension: np.ndarray
    bending_moment: np.ndarray
    twisting_moment: np.ndarray
    energies: dict = field(default_factory=dict)
    final_state: State | None = None

    @property
    def success(self) -> bool:
        return self.status == "success"

    def reaction(self, node: int) -> np.ndarray:
        """Reaction force history (n_frames, 3) [N] at one constrained global node."""
        hit = np.flatnonzero(self.reaction_nodes == node)
        if hit.size == 0:
            raise InputError(
                f"node {node} is not constrained; constrained: {self.reaction_nodes.tolist()}"
            )
        return self.reactions[:, hit[0], :]

    @property
    def total_energy(self) -> np.ndarray:
        """Sum of all energies per frame [J]."""
        return sum(self.energies.values())

    def save(self, path) -> None:
        """Write everything (including the final state) to one .npz file."""
        out = {name: getattr(self, name) for name in _ARRAYS}
        out["status"] = np.array(self.status)
        out["message"] = np.array(self.message)
        for k, v in self.stats.items():
            out["stats__" + k] = np.array(v)
        for k, v in self.energies.items():
            out["energy__" + k] = v
        if self.final_state is not None:
            for k, v in self.final_state.as_dict().items():
                out["state__" + k] = v
        np.savez_compressed(path, **out)

    @classmethod
    def load(cls, path) -> Result:
        """Read a file written by :meth:`save`."""
        with np.load(path) as d:
            kw = {name: d[name] for name in _ARRAYS}
            stats = {k[7:]: d[k].item() for k in d.files if k.startswith("stats__")}
            energies = {k[8:]: d[k] for k in d.files if k.startswith("energy__")}
            st = {k[7:]: d[k] for k in d.files if k.startswith("state__")}
            return cls(
                status=str(d["status"]),
                message=str(d["message"]),
                stats=stats,
                energies=energies,
                final_state=State.from_dict(st) if st else None,
                **kw,
            )


def load_result(path) -> Result:
    """Read a :class:`Result` saved with :meth:`Result.save`."""
    return Result.load(path)
