"""Frictional contact interactions for the DER solver (rod-rod and rod-rigid cylinder).

Both classes implement the solver's interaction protocol (``begin_step``, ``assemble``,
``end_step``, ``energy``; see ``notes/der_contract.md`` and :mod:`knotmech.rod`): they add a
generalised force F(q) and its derivative dF/dq (as sparse triplets) to the implicit-Euler
Newton system. They only use the system's global index arrays (``node_dofs``,
``edge_nodes``, ``edge_theta_dof``, ``edge_rod``, ``rod_radius_edge``, ``n_dof``), so any
number of rods, self-contact and any number of cylinders are handled alike.

- :class:`RodContact`: the implicit contact model (Choi, Tong & Jawed, J. Appl. Mech. 88
  (2021) 051010) on the edge-edge distance, with the regularised friction of the coated-rod
  paper (eqs. 10-12) or elasto-plastic anchors that stick, and a sort-and-sweep broad
  phase.
- :class:`CylinderContact`: rigid cylinders (posts, capstans, pinching rollers), smooth
  penalty normal force and elasto-plastic friction that truly sticks, applied at the contact
  surface so that thick rods show mu_eff (see :func:`knotmech.analytic.capstan.mu_eff`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.errors import InputError, check_finite, check_nonnegative, check_positive
from knotmech.rod._kernels.contact_cylinder import ENTRIES_PER_CONTACT, cylinder_assemble
from knotmech.rod._kernels.contact_rodrod import (
    ENTRIES_PER_PAIR,
    Z_CUTOFF,
    Z_JACOBIAN,
    align_anchors,
    freeze_parallel_pairs,
    gather_positions,
    max_node_speed,
    max_pair_displacement,
    pair_path_min_gap,
    positions_equal,
    rodrod_anchor_commit,
    rodrod_assemble,
    rodrod_energy,
    rodrod_near,
)
from knotmech.rod.broadphase import candidate_edge_pairs
from knotmech.rod.friction import FLOOR_RULES, AnchorFriction, SmoothFriction

__all__ = ["Cylinder", "CylinderContact", "RodContact"]

# tunnel_check "path": a step moving a contact node by more than PATH_LIMIT times
# max_displacement radii is rejected outright (bounds the cost of the path test, and
# keeps a slip of a step within a few rod diameters)
PATH_LIMIT = 16.0


def _emit(rows, cols, vals, r, c, v):
    """Append triplets to the solver's ``Triplets`` (passed as ``rows``) or to three lists."""
    if hasattr(rows, "add"):
        rows.add(r, c, v)
    else:
        rows.extend(np.asarray(r).tolist())
        cols.extend(np.asarray(c).tolist())
        vals.extend(np.asarray(v).tolist())


def _positions(system, q):
    q = np.asarray(q, dtype=float)
    nd = system.node_dofs
    if q.ndim == 1 and nd.ndim == 2 and nd.dtype == np.int64:
        return gather_positions(q, nd)  # per Newton iterate: one kernel pass
    return np.ascontiguousarray(q[nd])


@dataclass(frozen=True)
class Cylinder:
    """A rigid, fixed cylinder.

    Parameters
    ----------
    point : (3,) array [m]
        A point of the axis (the centre for a finite cylinder).
    axis : (3,) array
        Axis direction (normalised here).
    radius : float [m]
        Radius (> 0).
    length : float [m]
        Length along the axis (inf: infinite). Nodes beyond the ends feel no contact (no caps).
    """

    point: np.ndarray
    axis: np.ndarray
    radius: float
    length: float = float("inf")

    def __post_init__(self):
        p = check_finite("point", self.point).reshape(-1)
        a = check_finite("axis", self.axis).reshape(-1)
        if p.shape != (3,) or a.shape != (3,):
            raise InputError("point and axis must be 3-vectors")
        na = float(np.linalg.norm(a))
        if na == 0.0:
            raise InputError("axis must be a non-zero vector")
        object.__setattr__(self, "point", p)
        object.__setattr__(self, "axis", a / na)
        object.__setattr__(
            self, "radius", float(check_positive("radius", self.radius, scalar=True))
        )
        if not (self.length > 0):
            raise InputError(f"length must be > 0 (or inf), got {self.length}")
        object.__setattr__(self, "length", float(self.length))


@dataclass
class RodContact:
    r"""Rod-rod contact (self-contact included) of the implicit contact model, with friction.

    Penalty energy per candidate edge pair (i, j), :math:`\Delta_{ij}` the edge-edge
    minimum distance (point-point, point-edge and edge-edge cases, Lumelsky 1985):

    .. math:: E_{ij} = K_c\left[\frac{\log\left(1 + e^{k(r_i + r_j - \Delta_{ij})}\right)}{k}
              \right]^2

    (the softplus of the coated-rod paper's eq. (10), squared as in Choi, Tong & Jawed 2021,
    so that the force grows like :math:`2K_c\,\delta` with the overlap
    :math:`\delta = r_i + r_j - \Delta`). Its exact gradient and Hessian enter the Newton
    system. Friction, one of two laws:

    - :class:`~knotmech.rod.friction.SmoothFriction` ("imc"): coated-rod paper eqs.
      (11)-(12), with dF/dq through the velocity (and ``|F_n|``; the normal lagged). Stateless;
      it vanishes at zero slip, so a held load creeps.
    - :class:`~knotmech.rod.friction.AnchorFriction` ("anchor"): an elasto-plastic anchor
      per pair in contact, two material points (parameters on the lines of the pair's two
      edges) carried with the rods while the pair sticks, moved back to SLIP_GAP yield
      lengths when it slides, dropped when the pair leaves the penalty's reach (a
      re-found pair starts afresh at its contact point at the step start). The tangential force is
      :math:`-k_t u` (u the anchor's gap in the plane of the two edges) for small u,
      capped smoothly at :math:`\mu_s |F_n|`, and :math:`\mu_k |F_n|` (to 0.5 %) along
      u while sliding; its consistent
      tangent (the plane turning with the rods included) enters the Newton Jacobian. The
      anchors are state: :meth:`state_arrays` / :meth:`load_state_arrays` (carried by
      :class:`knotmech.rod.State` checkpoints). ``tangential_stiffness`` is k_t [N/m] per
      pair (default 2 K_c, the normal penalty's stiffness under load).

    Parameters
    ----------
    stiffness : float [N/m]
        K_c; the force at an overlap delta (>> 1/k) is about 2 K_c delta.
    sharpness : float [1/m]
        k; the penalty acts from a gap of a few 1/k (take 1/k ~ 1 % of the rod diameter).
    friction : SmoothFriction, AnchorFriction or None
    margin : float or None [m]
        Broad-phase margin; None -> 30/k + 2 r (covers the penalty range and motion).
    exclusion : int or None
        Neighbouring edges of the same rod never paired; None -> ``system.contact_exclusion``
        (default 2).
    max_displacement : float or None
        Tunnelling guard (fraction of the rod radius, default 0.5; None: off). A converged
        step is rejected, and retried by the solver with half the step, when a node of an
        edge in a candidate contact pair moved more than ``max_displacement`` times its
        edge radius during the step (:meth:`check_step`). Two edges then approach each
        other by at most one radius per step, so a crossing cannot jump from one side to
        the other between two penalty evaluations (the role of ``colLimit`` in the IMC
        code). It does not stop a penalty that is too soft for the load from being pushed
        through quasi-statically: raise ``stiffness`` for that.
    tunnel_check : {"displacement", "path"} or None
        What the tunnelling guard rejects. None (default): "path" with
        :class:`~knotmech.rod.friction.AnchorFriction`, "displacement" otherwise (issue 24:
        the path test is part of the sticking law's default; the regularised law keeps the
        guard its validations were run with). "displacement": any step that moves a
        node of a candidate pair more than ``max_displacement`` radii, as described
        above (with ``AnchorFriction(cap_floor=0)``, the anchor law as shipped before
        issue 24). "path": such a step is kept if no edge pair passes through itself on the
        straight path between the two states (every pair within reach of the step's
        motion, found by a broad phase of its own, not only the step's candidates): the
        path is sampled so that no node moves more than min(``max_displacement``, 0.5)
        radii between samples, and the step is rejected only where two edges come closer
        than half the sum of their radii (a crossing reaches Delta = 0 and cannot hide
        between samples: the nearest sample has Delta <= (r_i + r_j) / 4), or where a
        node moved more than PATH_LIMIT (16) ``max_displacement`` radii. This keeps the
        fast slips of a sticking law (a pair sliding along its partner, no crossing) in
        one step instead of halving the step for each.
    friction_normal_derivative : bool
        Include the derivative of ``|F_n|`` (through the penalty) in the friction's dF/dq
        (default True; False: only the velocity derivative, ``|F_n|`` and n lagged, as before).
        Unsymmetric, closer to the exact Jacobian: at mu = 0.9 (coated n = 3 quick pull)
        Newton needs 2.9x fewer iterations.
    """

    stiffness: float
    sharpness: float
    friction: SmoothFriction | AnchorFriction | None = None
    margin: float | None = None
    exclusion: int | None = None
    max_displacement: float | None = 0.5
    friction_normal_derivative: bool = True
    tunnel_check: str | None = None
    pairs: np.ndarray = field(default=None, init=False, repr=False)
    last_normal_force: np.ndarray = field(default=None, init=False, repr=False)

    def __post_init__(self):
        self.stiffness = float(check_positive("stiffness", self.stiffness, scalar=True))
        self.sharpness = float(check_positive("sharpness", self.sharpness, scalar=True))
        if self.margin is not None:
            self.margin = float(check_nonnegative("margin", self.margin, scalar=True))
        if self.max_displacement is not None:
            self.max_displacement = float(
                check_positive("max_displacement", self.max_displacement, scalar=True)
            )
        if self.tunnel_check is None:
            self.tunnel_check = (
                "path" if isinstance(self.friction, AnchorFriction) else "displacement"
            )
        if self.tunnel_check not in ("displacement", "path"):
            raise InputError(
                f"tunnel_check must be 'displacement' or 'path', got {self.tunnel_check!r}"
            )
        if self.friction is not None and not isinstance(
            self.friction, (SmoothFriction, AnchorFriction)
        ):
            raise InputError("friction must be a SmoothFriction, an AnchorFriction or None")
        self.reset()

    @property
    def _anchored(self) -> bool:
        return isinstance(self.friction, AnchorFriction)

    @property
    def newton_stagnation(self) -> int | None:
        """Hint for :class:`knotmech.rod.SolverOptions` ``stagnation="auto"``: with the
        anchor law, an attempt whose residual has not halved in 4 Newton iterations is
        given up (retried, then halved). A sliding pair whose tangential gap passes near
        zero during the solve (a lightly loaded pair: the cap's width ``mu |F_n| / k_t`` is then
        much smaller than the motion of a step) can make Newton cycle; measured on the
        first 12 s of the overhand benchmark (n = 1, 301 nodes), 88 attempts spent 21 % of
        all residual evaluations and 63 % of the LU factorizations so, and the cut brings
        the law's CPU time from 1.42x to 1.18x the regularised law's. None otherwise."""
        return 4 if self._anchored else None

    def hold_switches(self, system, q_old) -> int:
        """Stagnation fallback (:class:`knotmech.rod.SolverOptions` ``rescue``): hold the
        closest-point parameters of the nearly parallel pairs in reach (edges within about
        5 degrees) at their values at the step start ``q_old`` until :meth:`release_switches`.
        Their closest points otherwise jump between the two ends of the edges' overlap
        between Newton iterates (the edge distance is the smaller of two smooth functions
        there), moving the pair's whole penalty force from one node to another, and Newton
        cycles (docs/notes/contact-and-friction/parallel-edge-stall.md). Call after
        ``begin_step`` (the pairs of this attempt). While held, :meth:`assemble` and
        :meth:`energy` use the held gaps of these pairs.

        Parameters
        ----------
        system : RodSystem
            The system (node and edge layout, edge radii).
        q_old : (n_dof,) array [m, rad]
            The configuration at the step start; the parameters are taken there.

        Returns
        -------
        int
            The number of pairs held (0: nothing held, the exact closest points stay).
        """
        self._ensure_pairs(system, q_old)
        rad, en, nd = self._arrays(system)[:3]
        held = np.empty((self.pairs.shape[0], 2))
        n = freeze_parallel_pairs(
            _positions(system, q_old), self.pairs, en, rad, self.sharpness, Z_CUTOFF, held
        )
        self._held = held if n else None
        self._energy_cache = None
        return int(n)

    def _held_kwargs(self, npair: int) -> dict:
        """The kernel's ``frozen`` argument while :meth:`hold_switches` holds pairs (else
        none: the call, and its compiled kernel, of a normal step)."""
        held = self._held
        return {} if held is None or held.shape[0] != npair else {"frozen": held}

    def release_switches(self) -> None:
        """End :meth:`hold_switches`: the exact closest points again (a no-op when nothing
        is held).

        Returns
        -------
        None
        """
        self._held = None
        self._energy_cache = None

    def reset(self):
        """Forget the friction state (the anchors of the pairs in contact)."""
        self._held = None
        self._store = (np.zeros(0, dtype=np.int64), np.zeros((0, 2)), np.zeros(0, dtype=bool))
        self._anc = None
        self.pairs = None
        self._pos_old = None
        self._no_anchor = (
            np.zeros((1, 2)),
            np.zeros(1, dtype=bool),
            np.zeros(1, dtype=bool),
            np.ones(1, dtype=bool),
        )

    def state_arrays(self) -> dict:
        """The friction state as arrays (for :class:`knotmech.rod.State` checkpoints): the
        key e_i * n_edges + e_j of each pair in contact, its anchor (s_a, s_b) (material
        parameters on the two edges) and whether it slid at the last accepted step."""
        keys, anc, slip = self._store
        return {"keys": keys, "anchor": anc, "slipping": slip}

    def load_state_arrays(self, d) -> None:
        """Restore the friction state written by :meth:`state_arrays`."""
        self._store = (
            np.array(d["keys"], dtype=np.int64),
            np.array(d["anchor"], dtype=float).reshape(-1, 2),
            np.array(d["slipping"], dtype=bool),
        )
        self._anc = None
        self.pairs = None  # aligned again with the next broad phase

    def _anchor_params(self):
        """(mu_s, mu_k, k_t) of the anchor law; k_t [N/m] defaults to 2 K_c, the normal
        penalty's stiffness under load."""
        fr = self.friction
        kt = fr.tangential_stiffness
        return fr.mu_s, fr.mu_k, float(2.0 * self.stiffness if kt is None else kt)

    def _align_anchors(self, system):
        """Anchors aligned with ``self.pairs``: the committed ones of pairs still in the
        candidate list; new pairs get theirs (the contact point at the step start) when
        first in reach (in the kernels)."""
        keys_old, anc_old, slip_old = self._store
        n_edges = system.edge_nodes.shape[0]
        keys = self.pairs[:, 0] * n_edges + self.pairs[:, 1]
        n = keys.size
        anc = np.empty((n, 2))
        slip = np.empty(n, dtype=bool)
        known = np.empty(n, dtype=bool)
        align_anchors(keys_old, anc_old, slip_old, keys, anc, slip, known)
        self._anc = (keys, anc, slip, np.zeros(n, dtype=bool), known)

    def _exclusion(self, system):
        if self.exclusion is not None:
            return int(self.exclusion)
        return int(getattr(system, "contact_exclusion", 2))

    def begin_step(self, system, q_old, v_old, dt):
        """Broad phase at the start of the step (pairs kept fixed during Newton)."""
        rad, en, nd, rod_of_edge, rmax = self._arrays(system)[:5]
        pos = _positions(system, q_old)
        margin = self.margin
        if margin is None:
            vmax = 0.0
            if v_old is not None:
                vmax = max_node_speed(np.asarray(v_old, dtype=float), nd)
            margin = 30.0 / self.sharpness + 2.0 * rmax + 2.0 * vmax * dt
        self.pairs = candidate_edge_pairs(
            pos,
            en,
            edge_radius=rad,
            margin=margin,
            edge_rod=rod_of_edge,
            exclusion=self._exclusion(system),
            validate=False,
        )
        if self._anchored:
            self._align_anchors(system)
        # the step start's node positions, gathered once per attempt (assemble() runs at
        # every Newton iterate with the same q_old)
        self._pos_old = (q_old, pos)

    def _old_positions(self, system, q_old, nd):
        """Node positions (n_nodes, 3) at ``q_old``: those gathered by begin_step when
        ``q_old`` is the array it was given, else gathered now."""
        cached = self._pos_old
        if cached is not None and cached[0] is q_old:
            return cached[1]
        return _positions(system, q_old)

    def _ensure_pairs(self, system, q):
        if self.pairs is None:
            self.begin_step(system, q, None, 0.0)

    def assemble(self, system, q, q_old, dt, force, rows, cols=None, vals=None):
        """Add the contact + friction force and its dF/dq triplets."""
        self._ensure_pairs(system, q)
        pairs = self.pairs
        npair = pairs.shape[0]
        if npair == 0:
            self.last_normal_force = np.zeros(0)
            return
        rad, en, nd, _, _, rmin = self._arrays(system)
        fp = getattr(self, "_friction_cache", None)
        if fp is None or fp[0] is not self.friction or fp[1] != rmin:
            if isinstance(self.friction, SmoothFriction):
                fp = (self.friction, rmin, self.friction.parameters(rmin))
            else:
                fp = (None, rmin, (0.0, 1.0, 0.0))
            self._friction_cache = fp
        if self._anchored:
            mu, mu_k, k_t = self._anchor_params()
            fk = fc = 0.0
            if self._anc is None:
                self._align_anchors(system)
            _, anc, slip_prev, slip_now, known = self._anc
            law = 1
        else:
            mu, fk, fc = fp[2]
            mu_k = k_t = 0.0
            anc, slip_prev, slip_now, known = self._no_anchor
            law = 0
        pos = _positions(system, q)
        near = self._near_buffer(npair)
        n_near = rodrod_near(pos, pairs, en, rad, self.sharpness, Z_CUTOFF, near)
        # the solver says when it needs no Jacobian (a chord iteration): forces only
        want = bool(getattr(rows, "wanted", True))
        room = n_near * ENTRIES_PER_PAIR if want else 0
        if hasattr(rows, "reserve"):
            r, c, v = rows.reserve(room)
        else:
            r = np.empty(room, dtype=np.int64)
            c = np.empty(room, dtype=np.int64)
            v = np.empty(room)
        fn = np.empty(npair)
        e, cnt = rodrod_assemble(
            pos,
            self._old_positions(system, q_old, nd),
            float(dt) if dt else 1.0,
            pairs,
            near,
            n_near,
            en,
            nd,
            rad,
            self.sharpness,
            self.stiffness,
            mu,
            fk,
            fc,
            1e-3 * fc if fc > 0 else 1e-12,
            force,
            r,
            c,
            v,
            fn,
            bool(self.friction_normal_derivative),
            Z_JACOBIAN,
            want,
            law,
            mu_k,
            k_t,
            anc,
            slip_prev,
            known,
            slip_now,
            float(self.friction.cap_floor) if law == 1 else 0.0,
            _floor_mode(self.friction) if law == 1 else 0,
            **self._held_kwargs(npair),
        )
        self.last_normal_force = fn
        self._energy_cache = (pairs, pos, float(e))  # energy() at the same q is free
        if hasattr(rows, "reserve"):
            rows.commit(cnt)
        else:
            _emit(rows, cols, vals, r[:cnt], c[:cnt], v[:cnt])

    def _arrays(self, system):
        """Contiguous radius, edge-node, node-dof and edge-rod arrays of ``system``, and its
        largest and smallest edge radius (cached per system)."""
        cache = getattr(self, "_array_cache", None)
        if cache is None or cache[0] is not system:
            rad = np.ascontiguousarray(system.rod_radius_edge, dtype=float)
            cache = (
                system,
                rad,
                np.ascontiguousarray(system.edge_nodes, dtype=np.int64),
                np.ascontiguousarray(system.node_dofs, dtype=np.int64),
                np.ascontiguousarray(system.edge_rod, dtype=np.int64),
                float(np.max(rad)) if rad.size else 0.0,
                float(np.min(rad)) if rad.size else 0.0,
            )
            self._array_cache = cache
        return cache[1:]

    def _near_buffer(self, npair):
        buf = getattr(self, "_near", None)
        if buf is None or buf.size < npair:
            buf = np.empty(max(npair, 2 * (0 if buf is None else buf.size)), dtype=np.int64)
            self._near = buf
        return buf

    def check_step(self, system, q_new, q_old, dt):
        """Tunnelling guard: None if the converged step is acceptable, else the reason.

        Rejects the step when a node of an edge in a candidate pair moved more than
        ``max_displacement`` edge radii (see the class docstring); the solver then halves
        the step.
        """
        if self.max_displacement is None or self.pairs is None or self.pairs.shape[0] == 0:
            return None
        rad, en, nd = self._arrays(system)[:3]
        q_new = np.asarray(q_new, dtype=float)
        q_old = np.asarray(q_old, dtype=float)
        worst = max_pair_displacement(self.pairs, en, nd, rad, q_new, q_old)
        if worst <= self.max_displacement:
            return None
        why = (
            f"tunnelling guard: a contact node moved {worst:.3g} radii in one step "
            f"(max_displacement {self.max_displacement:g})"
        )
        if self.tunnel_check == "displacement" or worst > PATH_LIMIT * self.max_displacement:
            return why
        gap = self._path_gap(system, q_new, q_old)
        if gap < 0.5:
            return f"{why}, and two edges came within {gap:.3g} of their radii on the way"
        return None

    def _path_gap(self, system, q_new, q_old) -> float:
        """Smallest Delta / (r_i + r_j) on the straight path from ``q_old`` to ``q_new``
        over every edge pair that can meet on it: those within twice the largest node
        motion D at ``q_old`` (a pair farther apart cannot close its gap), found by a
        broad phase of margin 2 D, so that edges outside the step's candidate list are
        checked too. Sampled so that no node of those pairs moves more than 0.5 radii
        between samples (:func:`pair_path_min_gap`)."""
        rad, en, nd, rod_of_edge = self._arrays(system)[:4]
        pos = _positions(system, q_old)
        reach = 2.0 * max_node_speed(q_new - q_old, nd)
        pairs = candidate_edge_pairs(pos, en, edge_radius=rad, margin=reach,
                                     edge_rod=rod_of_edge, exclusion=self._exclusion(system),
                                     validate=False)  # fmt: skip
        if pairs.shape[0] == 0:
            return np.inf
        worst = max_pair_displacement(pairs, en, nd, rad, q_new, q_old)
        n_sub = max(int(np.ceil(worst / min(self.max_displacement, 0.5))), 1)
        return pair_path_min_gap(pairs, en, nd, rad, q_new, q_old, n_sub)

    @property
    def sliding(self) -> np.ndarray:
        """Anchor law: whether each candidate pair slid at the last assembly (n_pairs,)."""
        return np.zeros(0, dtype=bool) if self._anc is None else self._anc[3]

    def _anchor_pass(self, system, q, q_old, mode, keep):
        rad, en, nd = self._arrays(system)[:3]
        if self._anc is None:
            self._align_anchors(system)
        mu_s, mu_k, k_t = self._anchor_params()
        _, anc, slip, _, known = self._anc
        return rodrod_anchor_commit(
            _positions(system, q), _positions(system, q_old), self.pairs, en, rad,
            self.sharpness, self.stiffness, Z_CUTOFF, mu_s, mu_k, k_t, anc, slip, known,
            keep, mode, float(self.friction.cap_floor), _floor_mode(self.friction),
            **self._held_kwargs(self.pairs.shape[0]),
        )  # fmt: skip

    def end_step(self, system, q_new, q_old, dt):
        """Anchor law: commit the anchors of the pairs in contact at the accepted state
        (stick: kept; slide: moved back to SLIP_GAP yield lengths; out of contact: dropped). The
        regularised law is stateless."""
        if not self._anchored:
            return
        self._ensure_pairs(system, q_old)
        if self._anc is None:
            self._align_anchors(system)
        keys, anc, slip = self._anc[:3]
        keep = np.zeros(keys.size, dtype=bool)
        if keys.size:
            self._anchor_pass(system, q_new, q_old, 1, keep)
        self._store = (keys[keep], anc[keep], slip[keep])
        self._energy_cache = None
        self._pos_old = None
        self._anc = None  # aligned again by the next begin_step (or energy())

    def energy(self, system, q):
        """Penalty energy [J] of the current candidate pairs (anchor law: plus the energy
        stored in the anchors' tangential springs). While :meth:`hold_switches` holds
        pairs, theirs is the energy of the held gaps (the potential of the force
        :meth:`assemble` then gives), at any ``q``."""
        self._ensure_pairs(system, q)
        if self.pairs.shape[0] == 0:
            return 0.0
        q = np.asarray(q, dtype=float)
        nd = self._arrays(system)[2]
        cache = getattr(self, "_energy_cache", None)
        if cache is not None and cache[0] is self.pairs and positions_equal(q, nd, cache[1]):
            return cache[2]
        pos = _positions(system, q)
        e = float(
            rodrod_energy(
                pos,
                self.pairs,
                np.ascontiguousarray(system.edge_nodes, dtype=np.int64),
                np.ascontiguousarray(system.rod_radius_edge, dtype=float),
                self.sharpness,
                self.stiffness,
                **self._held_kwargs(self.pairs.shape[0]),
            )
        )
        if self._anchored:
            keep = np.zeros(self.pairs.shape[0], dtype=bool)
            e += float(self._anchor_pass(system, q, q, 2, keep))
        return e


@dataclass
class CylinderContact:
    r"""Contact of the rod nodes with rigid cylinders, with elasto-plastic friction.

    Normal: a smooth penalty on each node's signed gap
    :math:`g = |P_a(x - p)| - (R + r)`, per unit length (w the node's Voronoi length),

    .. math:: E = K\,w\left[\log(1 + e^{-k g})/k\right]^2,\qquad N \simeq 2 K w\,(-g)
              \text{ for } -g \gg 1/k.

    Friction: :class:`~knotmech.rod.friction.AnchorFriction` (sticks below mu_s N, slides
    at mu_k N). With ``surface_friction=True`` (default) the friction acts on the contact
    surface, a rod radius from the centreline toward the cylinder; its couple on the
    cross-section is applied as nodal force pairs on the adjacent edges (and its twisting part
    on their twist angles). This is what gives the capstan ratio
    :math:`e^{\mu_\mathrm{eff}\theta}` of a thick rod; ``surface_friction=False`` applies the
    friction at the centreline and gives :math:`e^{\mu\theta}`.

    Parameters
    ----------
    cylinders : sequence of Cylinder
    stiffness : float [N/m^2]
        K, per unit rod length.
    sharpness : float [1/m]
        k of the softplus; the force at zero gap is K w ln(2)/k, so 1/k sets the residual
        stand-off (take 1/k well below the rod diameter, e.g. d/400 as the scenes do).
    friction : AnchorFriction or None
    surface_friction : bool
    rod_radius : float or None [m]
        Contact radius of the rod (gap and friction lever arm); None -> the system's edge
        radii. Setting it lets a rope-like rod have a bending stiffness below the solid
        value pi E d^4/64 while keeping its contact diameter d.

    Attributes (after each assemble)
    --------------------------------
    normal_force : (n_nodes, n_cyl) [N]; friction_force : (n_nodes, n_cyl, 3) [N];
    sliding : (n_nodes, n_cyl) bool.
    """

    cylinders: tuple
    stiffness: float
    sharpness: float
    friction: AnchorFriction | None = None
    surface_friction: bool = True
    rod_radius: float | None = None
    normal_force: np.ndarray = field(default=None, init=False, repr=False)
    friction_force: np.ndarray = field(default=None, init=False, repr=False)
    sliding: np.ndarray = field(default=None, init=False, repr=False)

    def __post_init__(self):
        cyl = tuple(self.cylinders)
        if len(cyl) == 0 or not all(isinstance(c, Cylinder) for c in cyl):
            raise InputError("cylinders must be a non-empty sequence of Cylinder")
        self.cylinders = cyl
        self.stiffness = float(check_positive("stiffness", self.stiffness, scalar=True))
        self.sharpness = float(check_positive("sharpness", self.sharpness, scalar=True))
        if self.friction is not None and not isinstance(self.friction, AnchorFriction):
            raise InputError("friction must be an AnchorFriction or None")
        if self.rod_radius is not None:
            self.rod_radius = float(check_positive("rod_radius", self.rod_radius, scalar=True))
        self._cp = np.array([c.point for c in cyl])
        self._ca = np.array([c.axis for c in cyl])
        self._cr = np.array([c.radius for c in cyl])
        self._ch = np.array([0.5 * c.length for c in cyl])
        self._topology = None
        self._anchor = None
        self._restored = None

    # --- geometry helpers -------------------------------------------------------------
    def _setup(self, system):
        if self._topology is not None and self._topology[0] is system:
            return
        en = np.ascontiguousarray(system.edge_nodes, dtype=np.int64)
        nd = np.ascontiguousarray(system.node_dofs, dtype=np.int64)
        n_nodes = nd.shape[0]
        node_edges = -np.ones((n_nodes, 2), dtype=np.int64)
        for e, (a, b) in enumerate(en):
            node_edges[b, 0] = e  # edge ending at b is b's previous edge
            node_edges[a, 1] = e
        rad_e = np.asarray(system.rod_radius_edge, dtype=float)
        node_radius = np.zeros(n_nodes)
        cnt = np.zeros(n_nodes)
        np.add.at(node_radius, en[:, 0], rad_e)
        np.add.at(node_radius, en[:, 1], rad_e)
        np.add.at(cnt, en[:, 0], 1.0)
        np.add.at(cnt, en[:, 1], 1.0)
        node_radius /= np.maximum(cnt, 1.0)
        if self.rod_radius is not None:
            node_radius[:] = self.rod_radius
        theta = np.ascontiguousarray(system.edge_theta_dof, dtype=np.int64)
        self._topology = (system, en, nd, node_edges, node_radius, theta)
        nc = len(self.cylinders)
        self._anchor = np.zeros((n_nodes, nc, 3))
        self._valid = np.zeros((n_nodes, nc), dtype=np.bool_)
        self._slipping = np.zeros((n_nodes, nc), dtype=np.bool_)
        self._weight = None
        if self._restored is not None:
            self._apply_restored()

    def state_arrays(self) -> dict:
        """The friction state as arrays (for :class:`knotmech.rod.State` checkpoints): the
        stick anchors (n_nodes, n_cyl, 3) [m], whether each is set, and the slip flags."""
        if self._anchor is None:
            return {}
        return {
            "anchor": self._anchor.copy(),
            "valid": self._valid.copy(),
            "slipping": self._slipping.copy(),
        }

    def load_state_arrays(self, d) -> None:
        """Restore the friction state written by :meth:`state_arrays` (applied when the
        contact first sees its system, if it has not yet)."""
        self._restored = dict(d)
        if self._anchor is not None:
            self._apply_restored()

    def _apply_restored(self):
        d, self._restored = self._restored, None
        if not d:
            self.reset()
            return
        anchor = np.asarray(d["anchor"], dtype=float)
        if anchor.shape != self._anchor.shape:
            raise InputError(
                f"the saved rod-post anchors have shape {anchor.shape}, this contact "
                f"needs {self._anchor.shape} (another system or other cylinders)"
            )
        self._anchor[:] = anchor
        self._valid[:] = np.asarray(d["valid"], dtype=bool)
        self._slipping[:] = np.asarray(d["slipping"], dtype=bool)

    def _node_weight(self, pos):
        _, en, nd, _, _, _ = self._topology
        le = np.linalg.norm(pos[en[:, 1]] - pos[en[:, 0]], axis=1)
        w = np.zeros(nd.shape[0])
        np.add.at(w, en[:, 0], 0.5 * le)
        np.add.at(w, en[:, 1], 0.5 * le)
        return w

    def _friction_params(self):
        if self.friction is None:
            return 0.0, 0.0, 1.0
        kt = self.friction.tangential_stiffness
        if kt is None:
            kt = 2.0 * self.stiffness
        return self.friction.mu_s, self.friction.mu_k, float(kt)

    def _run(self, system, q, q_old, mode, force, r, c, v):
        _, en, nd, node_edges, node_radius, theta = self._topology
        pos = _positions(system, q)
        pos_old = _positions(system, q_old)
        if self._weight is None:
            self._weight = self._node_weight(pos_old)
        mus, muk, kt = self._friction_params()
        n_nodes, nc = nd.shape[0], len(self.cylinders)
        out_n = np.zeros((n_nodes, nc))
        out_f = np.zeros((n_nodes, nc, 3))
        out_s = np.zeros((n_nodes, nc), dtype=np.bool_)
        e = cylinder_assemble(
            pos,
            pos_old,
            nd,
            self._weight,
            node_radius,
            node_edges,
            en,
            theta,
            self._cp,
            self._ca,
            self._cr,
            self._ch,
            self.sharpness,
            self.stiffness,
            mus,
            muk,
            kt,
            bool(self.surface_friction),
            self._anchor,
            self._valid,
            self._slipping,
            mode,
            force,
            r,
            c,
            v,
            out_n,
            out_f,
            out_s,
        )
        if mode == 0:
            self.normal_force, self.friction_force, self.sliding = out_n, out_f, out_s
        return e

    # --- interaction protocol ---------------------------------------------------------
    def begin_step(self, system, q_old, v_old, dt):
        """Fix the nodes' contact lengths for the step (idempotent)."""
        self._setup(system)
        self._weight = self._node_weight(_positions(system, q_old))

    def assemble(self, system, q, q_old, dt, force, rows, cols=None, vals=None):
        """Add the normal + friction (+ couple) forces and their dF/dq triplets."""
        self._setup(system)
        size = system.node_dofs.shape[0] * len(self.cylinders) * ENTRIES_PER_CONTACT
        r = np.empty(size, dtype=np.int64)
        c = np.empty(size, dtype=np.int64)
        v = np.empty(size)
        self._run(system, q, q_old, 0, force, r, c, v)
        keep = v != 0.0
        _emit(rows, cols, vals, r[keep], c[keep], v[keep])

    def check_step(self, system, q_new, q_old, dt):
        """Tunnelling guard: None if the converged step is acceptable, else the reason.

        The penalty is sampled only at the ends of a step, so a node fast enough to cross a
        cylinder in one step never feels it. The step is rejected (and retried by the solver
        with half the step) when a node that started outside a cylinder's solid core
        (distance from the axis >= its radius R) has its straight path over the step,
        projected on the cross-section, come closer than R to the axis within the
        cylinder's length: its centreline then ended inside the post or swept through it,
        a penetration deeper than a full rod radius that the penalty (stand-off ~ 1/k)
        never allows in a resolved step. Nodes already inside at the step start are left
        to the penalty. A load that pushes the rod through quasi-statically (a penalty too
        soft for it) is rejected at every dt, and the run ends "failed" at dt_min: raise
        ``stiffness`` for that.
        """
        nd = np.ascontiguousarray(system.node_dofs, dtype=np.int64)
        x1 = np.asarray(q_new, dtype=float)[nd]
        x0 = np.asarray(q_old, dtype=float)[nd]
        for c in range(len(self.cylinders)):
            p, a, big_r, half = self._cp[c], self._ca[c], self._cr[c], self._ch[c]
            r0, r1 = x0 - p, x1 - p
            s0, s1 = r0 @ a, r1 @ a
            u0 = r0 - s0[:, None] * a
            du = (r1 - s1[:, None] * a) - u0
            outside = np.einsum("ij,ij->i", u0, u0) >= big_r * big_r
            dd = np.einsum("ij,ij->i", du, du)
            with np.errstate(invalid="ignore", divide="ignore"):
                t = np.where(dd > 0.0, -np.einsum("ij,ij->i", u0, du) / dd, 0.0)
            t = np.clip(t, 0.0, 1.0)
            closest = np.linalg.norm(u0 + t[:, None] * du, axis=1)
            within = np.abs(s0 + t * (s1 - s0)) <= half
            bad = np.flatnonzero(outside & within & (closest < big_r))
            if bad.size:
                k = bad[np.argmin(closest[bad])]
                return (
                    f"tunnelling guard: node {k} crossed the solid core of cylinder {c} in "
                    f"one step (closest approach {closest[k] / big_r:.2g} R from the axis, "
                    f"moved {np.linalg.norm(x1[k] - x0[k]) / big_r:.3g} R)"
                )
        return None

    def end_step(self, system, q_new, q_old, dt):
        """Commit the stick anchors and slip flags at the accepted state."""
        self._setup(system)
        dummy_i = np.zeros(1, dtype=np.int64)
        self._run(system, q_new, q_old, 1, np.zeros(1), dummy_i, dummy_i, np.zeros(1))

    def energy(self, system, q):
        """Normal penalty energy [J] (friction is not conservative and adds nothing)."""
        self._setup(system)
        dummy_i = np.zeros(1, dtype=np.int64)
        if self._weight is None:
            self._weight = self._node_weight(_positions(system, q))
        mode_energy_only = 2
        return float(
            self._run(system, q, q, mode_energy_only, np.zeros(1), dummy_i, dummy_i, np.zeros(1))
        )

    def reset(self):
        """Forget the friction state (anchors, slip flags)."""
        if self._anchor is not None:
            self._anchor[:] = 0.0
            self._valid[:] = False
            self._slipping[:] = False


def _floor_mode(friction) -> int:
    """Kernel ``floor_mode`` of an anchor law's ``floor_rule`` (its index in
    :data:`~knotmech.rod.friction.FLOOR_RULES`)."""
    return FLOOR_RULES.index(friction.floor_rule)
