"""Rods, the system of rods and the dynamic state of a discrete-elastic-rods simulation.

Degrees of freedom (the DER contract, Bergou et al. 2008): rod r with N_r + 1 nodes and
N_r edges has q_r = [x0, theta0, x1, theta1, ..., x_{N-1}, theta_{N-1}, x_N] (4 N_r + 3
entries); the rods are concatenated in order. Global index arrays (``node_dofs``,
``edge_nodes``, ``edge_theta_dof``, ...) hide that layout from code built on top.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, check_bending_scale, check_finite, check_positive, check_range
from ._kernels import frames as _fr

__all__ = ["Rod", "RodSystem", "State"]


def _frozen(a) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class Rod:
    """One elastic rod with a circular cross-section (immutable parameters).

    Parameters
    ----------
    positions : (n_nodes, 3) array [m]
        Initial node positions x_0 .. x_N (n_nodes >= 3).
    radius : float [m]
        Cross-section radius r; A = pi r^2, I = pi r^4 / 4, J = pi r^4 / 2.
    youngs_modulus : float [Pa]
    density : float [kg/m^3]
    poisson_ratio : float, optional
        Used for G = E / (2 (1 + nu)) unless ``shear_modulus`` is given. Default 0.5.
    shear_modulus : float or None [Pa]
    thetas : (n_edges,) array [rad], optional
        Initial twist angles of the material frames (default 0).
    velocities : (n_nodes, 3) array [m/s], optional
        Initial node velocities (default 0).
    director : (3,) array, optional
        Reference director d1 of the first edge (projected normal to it); default: the
        unit axis least aligned with the first edge.
    natural : {"initial", "straight"}
        Natural (stress-free) shape: the initial shape (rest curvature and twist computed
        from it, the default) or a straight untwisted rod.
    bending_scale : float, optional
        kappa in (0, 1], default 1 (a solid rod). The bending stiffness is
        B = kappa E pi r^4 / 4 and, for simplicity, the twisting stiffness is scaled the
        same way, kappa G pi r^4 / 2; the stretching stiffness E pi r^2 is not. A fibre
        rope bends far more easily than a solid rod of its diameter and axial modulus
        (its yarns slide on one another), kappa of order 0.01 (``knotmech.materials``).
    """

    positions: np.ndarray
    radius: float
    youngs_modulus: float
    density: float
    poisson_ratio: float = 0.5
    shear_modulus: float | None = None
    thetas: np.ndarray | None = None
    velocities: np.ndarray | None = None
    director: np.ndarray | None = None
    natural: str = "initial"
    bending_scale: float = 1.0

    def __post_init__(self):
        pos = check_finite("positions", self.positions)
        if pos.ndim != 2 or pos.shape[1] != 3 or pos.shape[0] < 3:
            raise InputError(f"positions must have shape (n_nodes >= 3, 3), got {pos.shape}")
        if np.any(np.linalg.norm(np.diff(pos, axis=0), axis=1) <= 0):
            raise InputError("positions must not repeat a node (zero-length edge)")
        object.__setattr__(self, "positions", _frozen(pos))
        for name in ("radius", "youngs_modulus", "density"):
            object.__setattr__(
                self, name, float(check_positive(name, getattr(self, name), scalar=True))
            )
        nu = float(check_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5, scalar=True))
        object.__setattr__(self, "poisson_ratio", nu)
        if self.shear_modulus is not None:
            g = float(check_positive("shear_modulus", self.shear_modulus, scalar=True))
            object.__setattr__(self, "shear_modulus", g)
        n_edges = pos.shape[0] - 1
        th = np.zeros(n_edges) if self.thetas is None else check_finite("thetas", self.thetas)
        if th.shape != (n_edges,):
            raise InputError(f"thetas must have shape ({n_edges},), got {th.shape}")
        object.__setattr__(self, "thetas", _frozen(th))
        v = (
            np.zeros_like(pos)
            if self.velocities is None
            else check_finite("velocities", self.velocities)
        )
        if v.shape != pos.shape:
            raise InputError(f"velocities must have shape {pos.shape}, got {v.shape}")
        object.__setattr__(self, "velocities", _frozen(v))
        if self.director is not None:
            d = check_finite("director", self.director)
            t0 = pos[1] - pos[0]
            if d.shape != (3,) or np.linalg.norm(np.cross(d, t0)) <= 1e-12 * np.linalg.norm(
                d
            ) * np.linalg.norm(t0):
                raise InputError("director must be a 3-vector not parallel to the first edge")
            object.__setattr__(self, "director", _frozen(d))
        if self.natural not in ("initial", "straight"):
            raise InputError(f"natural must be 'initial' or 'straight', got {self.natural!r}")
        object.__setattr__(self, "bending_scale", check_bending_scale(self.bending_scale))

    @classmethod
    def straight(
        cls,
        *,
        length: float,
        n_nodes: int,
        radius: float,
        youngs_modulus: float,
        density: float,
        start=(0.0, 0.0, 0.0),
        direction=(1.0, 0.0, 0.0),
        **kwargs,
    ) -> Rod:
        """A straight rod of ``length`` [m] from ``start`` along ``direction``, n_nodes nodes."""
        length = float(check_positive("length", length, scalar=True))
        if int(n_nodes) != n_nodes or n_nodes < 3:
            raise InputError(f"n_nodes must be an integer >= 3, got {n_nodes!r}")
        d = check_finite("direction", direction)
        if d.shape != (3,) or np.linalg.norm(d) == 0:
            raise InputError("direction must be a non-zero 3-vector")
        d = d / np.linalg.norm(d)
        s = np.linspace(0.0, length, int(n_nodes))
        pos = check_finite("start", start)[None, :] + s[:, None] * d[None, :]
        return cls(
            positions=pos, radius=radius, youngs_modulus=youngs_modulus, density=density, **kwargs
        )

    @property
    def n_nodes(self) -> int:
        return self.positions.shape[0]

    @property
    def n_edges(self) -> int:
        return self.positions.shape[0] - 1

    @property
    def shear(self) -> float:
        """Shear modulus G [Pa]: ``shear_modulus`` or E / (2 (1 + nu))."""
        if self.shear_modulus is not None:
            return self.shear_modulus
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def length(self) -> float:
        """Arc length of the initial polyline [m]."""
        return float(np.linalg.norm(np.diff(self.positions, axis=0), axis=1).sum())

    @property
    def bending_stiffness(self) -> float:
        """B = kappa E pi r^4 / 4 [N m^2] (kappa = ``bending_scale``, 1 for a solid rod)."""
        return self.bending_scale * (self.youngs_modulus * np.pi * self.radius**4 / 4.0)

    @property
    def twisting_stiffness(self) -> float:
        """kappa GJ = kappa G pi r^4 / 2 [N m^2] (twist scaled with bending, see ``Rod``)."""
        return self.bending_scale * (self.shear * np.pi * self.radius**4 / 2.0)

    @property
    def stretching_stiffness(self) -> float:
        """EA = E pi r^2 [N]."""
        return self.youngs_modulus * np.pi * self.radius**2


@dataclass(frozen=True, eq=False)
class State:
    """Dynamic state: time, dofs, velocities and the time-parallel reference frames.

    Attributes
    ----------
    t : float [s]
    q : (n_dof,) array  positions [m] and twist angles [rad] in DER order
    v : (n_dof,) array  their rates [m/s, rad/s]
    tangents : (n_edges, 3) array  unit tangents the reference frames belong to
    d1 : (n_edges, 3) array  reference directors (time-parallel transported)
    ref_twist : (n_stencils,) array [rad]  reference twist, tracked continuously
    dt_next : float [s]  step size the adaptive solver will try next (nan: the nominal dt)
    n_good : int  accepted steps since dt was last changed (drives dt growth)
    accel : (n_dof,) array or None  rate of change of ``v`` over the last two steps (the
        solver's second-order predictor; None: not known yet, e.g. at the start)
    h_last : float [s]  the step that led to this state (nan: not known)
    interactions : dict or None  internal state of the interactions (friction anchors),
        ``{k: {name: array}}`` for the k-th interaction passed to ``simulate`` (None: not
        known, the interactions keep theirs); a checkpoint carries it so that a new process
        resumes bit-identically
    linear : dict or None  the solver's linear-algebra state after the step ({name:
        array or scalar}): the RCM ordering of the contact Jacobian with its counters and the LU
        factors that the next step may reuse (chord iterations). Not physics, but it decides
        the round-off of the next steps: with it a resumed run with rod-rod contact repeats
        the uninterrupted one bit for bit (None: a new solver orders and factors afresh,
        which agrees to round-off only). The arrays are shared, not copied: the solver never
        writes into factors it has handed out
    """

    t: float
    q: np.ndarray
    v: np.ndarray
    tangents: np.ndarray
    d1: np.ndarray
    ref_twist: np.ndarray
    dt_next: float = float("nan")
    n_good: int = 0
    accel: np.ndarray | None = None
    h_last: float = float("nan")
    interactions: dict | None = None
    linear: dict | None = None

    def as_dict(self) -> dict:
        out = {
            "t": np.float64(self.t),
            "q": self.q,
            "v": self.v,
            "tangents": self.tangents,
            "d1": self.d1,
            "ref_twist": self.ref_twist,
            "dt_next": np.float64(self.dt_next),
            "n_good": np.int64(self.n_good),
            "h_last": np.float64(self.h_last),
        }
        if self.accel is not None:
            out["accel"] = self.accel
        if self.interactions is not None:
            out["n_interactions"] = np.int64(len(self.interactions))
            for k, arrays in self.interactions.items():
                for name, v in arrays.items():
                    out[f"interaction{int(k)}__{name}"] = v
        if self.linear is not None:
            for name, v in self.linear.items():
                out[f"linear__{name}"] = v
        return out

    @classmethod
    def from_dict(cls, d) -> State:
        return cls(
            t=float(d["t"]),
            q=np.array(d["q"], dtype=float),
            v=np.array(d["v"], dtype=float),
            tangents=np.array(d["tangents"], dtype=float),
            d1=np.array(d["d1"], dtype=float),
            ref_twist=np.array(d["ref_twist"], dtype=float),
            dt_next=float(d["dt_next"]),
            n_good=int(d["n_good"]),
            accel=np.array(d["accel"], dtype=float) if "accel" in d else None,
            h_last=float(d["h_last"]) if "h_last" in d else float("nan"),
            interactions=_interaction_arrays(d),
            linear={k[len("linear__") :]: np.array(d[k]) for k in d.keys()
                    if k.startswith("linear__")} or None,
        )  # fmt: skip

    def save(self, path) -> None:
        """Write the state to an .npz file (checkpoint)."""
        np.savez(path, **self.as_dict())

    @classmethod
    def load(cls, path) -> State:
        """Read a state written by :meth:`save`."""
        with np.load(path) as d:
            return cls.from_dict(d)


def _interaction_arrays(d) -> dict | None:
    """The ``interaction<k>__<name>`` entries of a state dictionary as {k: {name: array}}."""
    if "n_interactions" not in d:
        return None
    out = {k: {} for k in range(int(d["n_interactions"]))}
    for key in d.keys():
        if key.startswith("interaction") and "__" in key:
            head, name = key.split("__", 1)
            k = int(head[len("interaction") :])
            if k not in out:
                raise InputError(f"state entry {key!r} names interaction {k} of {len(out)}")
            out[k][name] = np.array(d[key])
    return out


def _default_director(t0: np.ndarray) -> np.ndarray:
    axis = np.zeros(3)
    axis[int(np.argmin(np.abs(t0)))] = 1.0
    return axis


@dataclass(frozen=True, eq=False)
class RodSystem:
    """Several rods simulated together (parameters, rest shape and index arrays).

    Parameters
    ----------
    rods : sequence of Rod
    contact_exclusion : int
        Edges of one rod closer than this many edges along it never form a contact pair.

    Attributes (global numbering over all rods; numpy int64 unless said)
    ----------
    node_dofs : (n_nodes, 3)  dof indices of x, y, z of each node
    edge_nodes : (n_edges, 2)  node indices of the two ends of each edge
    edge_theta_dof : (n_edges,)  dof index of each edge's twist angle
    edge_rod, node_rod : which rod an edge / node belongs to
    rod_radius_edge : (n_edges,) float [m]
    rod_node_start, rod_edge_start : (n_rods + 1,) first node / edge of each rod (and end)
    edge_dof0 : (n_edges,) dof of the first node of each edge (theta at +3, 2nd node at +4)
    stencil_edge : (n_stencils,) the second edge f of each interior-node stencil (e = f - 1)
    rest_length (n_edges,), voronoi (n_stencils,) [m]; kappa_bar (n_stencils, 2) [-];
    twist_bar (n_stencils,) [rad]; ea (n_edges,) [N]; ei, gj (n_stencils,) [N m^2];
    mass : (n_dof,) lumped mass [kg] (positions) and rotational inertia [kg m^2] (angles).
    """

    rods: tuple
    contact_exclusion: int = 2
    _arrays: dict = field(default=None, repr=False)

    def __post_init__(self):
        rods = tuple(self.rods) if not isinstance(self.rods, Rod) else (self.rods,)
        if len(rods) == 0 or not all(isinstance(r, Rod) for r in rods):
            raise InputError("rods must be a non-empty sequence of knotmech.rod.Rod")
        if int(self.contact_exclusion) != self.contact_exclusion or self.contact_exclusion < 1:
            raise InputError(
                f"contact_exclusion must be an integer >= 1, got {self.contact_exclusion!r}"
            )
        object.__setattr__(self, "rods", rods)
        arrays = self._build(rods)
        object.__setattr__(self, "_arrays", arrays)
        # the arrays as plain instance attributes (the solver reads them at every Newton
        # evaluation; __getattr__ below stays for names the class itself defines)
        for name, value in arrays.items():
            if not hasattr(type(self), name):
                object.__setattr__(self, name, value)

    def __getattr__(self, name):
        arrays = object.__getattribute__(self, "_arrays")
        if arrays is not None and name in arrays:
            return arrays[name]
        raise AttributeError(name)

    @staticmethod
    def _build(rods) -> dict:
        idx = _index_arrays(rods)
        node_dofs, edge_dof0 = idx["node_dofs"], idx["edge_dof0"]
        edge_rod, stencil_rod = idx["edge_rod"], idx["stencil_rod"]
        stencil_edge = idx["stencil_edge"]
        dof_start, node_start, edge_start = idx["dof_start"], idx["node_start"], idx["edge_start"]
        n_dof = int(dof_start[-1])
        q0, v0 = _initial_dofs(rods, idx)
        tangents, lengths, d1, kappa_bar, twist_bar = _rest_shape(rods, idx, q0)

        rest_length = lengths.copy()
        voronoi = 0.5 * (rest_length[stencil_edge - 1] + rest_length[stencil_edge])
        radius_e = np.array([rods[r].radius for r in edge_rod])
        ea = np.array([rods[r].stretching_stiffness for r in edge_rod])
        ei = np.array([rods[r].bending_stiffness for r in stencil_rod])
        gj = np.array([rods[r].twisting_stiffness for r in stencil_rod])
        rho = np.array([rods[r].density for r in edge_rod])
        mass = np.zeros(n_dof)
        m_edge = rho * np.pi * radius_e**2 * rest_length
        for j in range(3):
            np.add.at(mass, edge_dof0 + j, 0.5 * m_edge)
            np.add.at(mass, edge_dof0 + 4 + j, 0.5 * m_edge)
        mass[edge_dof0 + 3] = 0.5 * m_edge * radius_e**2  # rho J l, J = pi r^4 / 2

        out = dict(
            n_rods=len(rods),
            n_dof=n_dof,
            n_nodes=int(node_start[-1]),
            n_edges=int(edge_start[-1]),
            n_stencils=len(stencil_edge),
            node_dofs=node_dofs,
            edge_nodes=idx["edge_nodes"],
            edge_theta_dof=edge_dof0 + 3,
            edge_rod=edge_rod,
            node_rod=idx["node_rod"],
            stencil_rod=stencil_rod,
            rod_radius_edge=radius_e,
            rod_dof_start=dof_start.astype(np.int64),
            rod_node_start=node_start.astype(np.int64),
            rod_edge_start=edge_start.astype(np.int64),
            edge_dof0=edge_dof0,
            stencil_edge=stencil_edge,
            rest_length=rest_length,
            voronoi=voronoi,
            kappa_bar=kappa_bar,
            twist_bar=twist_bar,
            ea=ea,
            ei=ei,
            gj=gj,
            mass=mass,
            is_theta=np.isin(np.arange(n_dof), edge_dof0 + 3),
            _q0=q0,
            _v0=v0,
            _tangents0=tangents,
            _d10=d1,
        )
        for v in out.values():
            if isinstance(v, np.ndarray):
                v.setflags(write=False)
        return out

    # ------------------------------------------------------------------ helpers
    def positions(self, q) -> np.ndarray:
        """Node positions (n_nodes, 3) [m] of a dof vector (a copy)."""
        return np.asarray(q)[self.node_dofs]

    def thetas(self, q) -> np.ndarray:
        """Twist angles (n_edges,) [rad] of a dof vector (a copy)."""
        return np.asarray(q)[self.edge_theta_dof]

    def rod_nodes(self, rod: int = 0) -> np.ndarray:
        """Global node indices of one rod."""
        return np.arange(self.rod_node_start[rod], self.rod_node_start[rod + 1])

    def rod_edges(self, rod: int = 0) -> np.ndarray:
        """Global edge indices of one rod."""
        return np.arange(self.rod_edge_start[rod], self.rod_edge_start[rod + 1])

    def initial_state(self) -> State:
        """The state at t = 0 built from the rods' positions, thetas and velocities."""
        return State(
            t=0.0,
            q=self._q0.copy(),
            v=self._v0.copy(),
            tangents=self._tangents0.copy(),
            d1=self._d10.copy(),
            ref_twist=np.zeros(self.n_stencils),
        )


def _index_arrays(rods) -> dict:
    """Global numbering of a system's dofs: per rod, its nodes' (x, y, z) then each edge's
    twist angle interleaved (x0 y0 z0 theta0 x1 y1 z1 theta1 ... x_n y_n z_n); the edges'
    nodes, first dofs and rods; the bending stencils (interior nodes, named by their
    second edge) and their rods; the rods' first dof, node and edge."""
    nn = np.array([r.n_nodes for r in rods])
    ne = nn - 1
    n_dof_rod = 4 * ne + 3
    dof_start = np.concatenate([[0], np.cumsum(n_dof_rod)])
    node_start = np.concatenate([[0], np.cumsum(nn)])
    edge_start = np.concatenate([[0], np.cumsum(ne)])
    n_nodes, n_edges = int(node_start[-1]), int(edge_start[-1])
    node_dofs = np.empty((n_nodes, 3), dtype=np.int64)
    edge_nodes = np.empty((n_edges, 2), dtype=np.int64)
    edge_dof0 = np.empty(n_edges, dtype=np.int64)
    node_rod = np.empty(n_nodes, dtype=np.int64)
    edge_rod = np.empty(n_edges, dtype=np.int64)
    stencil_edge, stencil_rod = [], []
    for r, rod in enumerate(rods):
        i = np.arange(rod.n_nodes)
        node_dofs[node_start[r] : node_start[r + 1]] = dof_start[r] + 4 * i[:, None] + np.arange(3)
        node_rod[node_start[r] : node_start[r + 1]] = r
        k = np.arange(rod.n_edges)
        edge_nodes[edge_start[r] : edge_start[r + 1], 0] = node_start[r] + k
        edge_nodes[edge_start[r] : edge_start[r + 1], 1] = node_start[r] + k + 1
        edge_dof0[edge_start[r] : edge_start[r + 1]] = dof_start[r] + 4 * k
        edge_rod[edge_start[r] : edge_start[r + 1]] = r
        stencil_edge.append(edge_start[r] + np.arange(1, rod.n_edges))
        stencil_rod.append(np.full(rod.n_edges - 1, r))
    return dict(
        dof_start=dof_start,
        node_start=node_start,
        edge_start=edge_start,
        node_dofs=node_dofs,
        edge_nodes=edge_nodes,
        edge_dof0=edge_dof0,
        node_rod=node_rod,
        edge_rod=edge_rod,
        stencil_edge=np.concatenate(stencil_edge).astype(np.int64),
        stencil_rod=np.concatenate(stencil_rod).astype(np.int64),
    )


def _initial_dofs(rods, idx) -> tuple[np.ndarray, np.ndarray]:
    """The start configuration q0 (node positions [m], twist angles [rad]) and velocity v0
    [m/s] (angles at rest) as dof vectors."""
    node_dofs, edge_dof0 = idx["node_dofs"], idx["edge_dof0"]
    node_start, edge_start = idx["node_start"], idx["edge_start"]
    n_dof = int(idx["dof_start"][-1])
    q0 = np.zeros(n_dof)
    v0 = np.zeros(n_dof)
    for r, rod in enumerate(rods):
        sl = slice(node_start[r], node_start[r + 1])
        for j in range(3):
            q0[node_dofs[sl, j]] = rod.positions[:, j]
            v0[node_dofs[sl, j]] = rod.velocities[:, j]
        q0[edge_dof0[edge_start[r] : edge_start[r + 1]] + 3] = rod.thetas
    return q0, v0


def _rest_shape(rods, idx, q0):
    """Tangents, lengths [m] and space-parallel reference directors d1 of the start
    configuration (each rod's first d1 from its ``director`` or a default), and the rest
    material curvatures (n_stencils, 2) [1/m] and twists (n_stencils,) [rad]: those of the
    start shape (``natural="initial"``) or zero (``"straight"``)."""
    edge_dof0, edge_start = idx["edge_dof0"], idx["edge_start"]
    stencil_edge, stencil_rod = idx["stencil_edge"], idx["stencil_rod"]
    n_edges = edge_dof0.size
    tangents = np.empty((n_edges, 3))
    lengths = np.empty(n_edges)
    _fr.edge_tangents(q0, edge_dof0, tangents, lengths)
    d1 = np.empty((n_edges, 3))
    d2 = np.empty((n_edges, 3))
    for r, rod in enumerate(rods):
        a, b = int(edge_start[r]), int(edge_start[r + 1])
        dd = rod.director if rod.director is not None else _default_director(tangents[a])
        _fr.space_parallel_frames(tangents, a, b, np.asarray(dd, dtype=float), d1, d2)
    ref_twist = np.zeros(len(stencil_edge))
    m1 = np.empty_like(d1)
    m2 = np.empty_like(d1)
    _fr.material_frames(q0, edge_dof0, d1, d2, m1, m2)
    kappa_bar = np.zeros((len(stencil_edge), 2))
    twist_bar = np.zeros(len(stencil_edge))
    _fr.curvatures(q0, edge_dof0, stencil_edge, m1, m2, kappa_bar)
    _fr.twists(q0, edge_dof0, stencil_edge, ref_twist, twist_bar)
    straight = np.array([rods[r].natural == "straight" for r in stencil_rod], dtype=bool)
    kappa_bar[straight] = 0.0
    twist_bar[straight] = 0.0
    return tangents, lengths, d1, kappa_bar, twist_bar
