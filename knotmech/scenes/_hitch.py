r"""The hitch scene: a rod tied round a rigid post, loaded at its ends, held or pulled.

Every post hitch (:mod:`~knotmech.scenes.clove_hitch`,
:mod:`~knotmech.scenes.two_half_hitches`, :mod:`~knotmech.scenes.round_turn_two_half_hitches`,
:mod:`~knotmech.scenes.cow_hitch`) is this scene with its own start centreline: a
:class:`HitchKnot` (a name and a curve) handed to :func:`run_hitch`. Its 31 keywords (the
interface of every hitch scene, unchanged) are gathered into small frozen option objects,
:class:`HitchRod`, :class:`HitchFriction`, :class:`HitchLoading`, :class:`HitchRule` and
:class:`~knotmech.scenes._scene.RunControl`, and :class:`HitchScene` (a
:class:`~knotmech.scenes._scene.Scene`) runs it; the run

0. **sets up**: checks every input, refuses a rod the post cannot take (the start
   curve's strands closer than d/2 or inside the post), bounds steps x nodes and memory;

1. **builds** the naturally straight rod on the curve, the rigid post on the z axis
   (:class:`~knotmech.rod.contact.CylinderContact`, elasto-plastic friction on the rod
   surface) and rod-rod contact (sticking :class:`~knotmech.rod.friction.AnchorFriction` by
   default, ``friction="imc"`` the regularised law of the implicit contact model);
2. **runs phases** on a :class:`~knotmech.scenes._scene.SceneRun`:

   - dead-load loadings (``"symmetric"``, ``"asymmetric"``, ``"free"``): ``"settle"``
     under a pre-tension on both ends for ``settle_time``, ``"load"`` (ramp to the final
     loads over ``load_time``), ``"hold"`` (the final loads for ``hold_time``, with the
     knot's :attr:`HitchKnot.hold_damping` of the settling drag); the clove hitch runs them
     as one phase ``"settle-load-hold"`` whose ramped loads carry the same schedule (the
     numbers of its shipped tables). The free loading stops early once end 0 has run out
     0.3 L;
   - ``"pull"``: ``"settle"`` (both ends at the pre-tension), ``"lower"`` (end 0 clamped
     where it settled, the other end's load lowered to T_low), ``"pull"`` (end 0 pulled
     along its tail at ``pull_speed``); T_high is the clamp's reaction;

3. **measures**: the tension T(s) along the rod, the contacts, the Darboux vector, the
   creep of the loaded end (and the draw-in of the other end) over the end of the hold, the
   winding about the post and, for the knots that declare them, the knot invariants of the
   closed rod on frames of the run (a strand passing through another changes them).

Verdict (``loading="free"``): *slip* when the run stopped early (end 0 ran out), when end 0
crept more than ``slip_distance`` over the last half of the hold, or (``creep_limit`` given)
when end 0 crept faster than ``creep_limit`` rod diameters per second over the creep window
(the last second of the hold, or its last half if shorter), or when the knot invariants
changed (the knot came apart); else *hold*. The free end's
draw-in speed is reported (``tail_creep_speed``) but does not decide: an unloaded tail also
moves as the rod's bending relaxes, without the hitch giving.
The clove hitch keeps the distance rule alone (``creep_limit=None``), the rule its shipped
phase tables were built with; the other hitches use both (default 1e-3 d/s, issue 10).
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass, field

import numpy as np

from knotmech import rod
from knotmech.analytic.capstan import mu_eff as _mu_eff
from knotmech.errors import (
    InputError,
    check_bending_scale,
    check_count,
    check_nonnegative,
    check_positive,
)
from knotmech.materials import PHASE_TABLE_DENSITY, VPS32_YOUNGS_MODULUS
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import AnchorFriction, SmoothFriction
from knotmech.scenes._common import (
    CREEP_LIMIT,
    check_memory,
    check_numbers,
    check_post_size,
    check_pull_step,
    check_run_size,
    check_strain,
    fail,
    frames_bytes,
    measured_strain,
    pair_check_bytes,
)
from knotmech.scenes._scene import RampedEndLoad, RunControl, Scene, SceneRun, post_contact
from knotmech.scenes.curves import _edge_distances
from knotmech.scenes.topology import post_crossing_code, winding_number

__all__ = [
    "HitchKnot",
    "HitchResult",
    "run_hitch",
    "HitchScene",
    "HitchRod",
    "HitchFriction",
    "HitchLoading",
    "HitchRule",
    "hitch_scene",
    "darboux_profile",
    "PAPER_PRETENSION",
    "CREEP_LIMIT",
]

PAPER_PRETENSION = 0.559
"""[N] pre-tension of the clove-hitch paper's pull test (sect. 5: T_low raised to 0.559 N
with an extra 50 g, end 0 displaced until T_high = T_low, then the extra weight removed)."""


#: the hitch scenes' solver options when none are given (``simulate_point`` adds its CPU
#: budget to these, so a budgeted run is the tables' run)
DEFAULT_OPTIONS = rod.SolverOptions(throw=False, rtol=1e-6)


@dataclass(frozen=True)
class HitchKnot:
    """What makes one hitch: its name and its start centreline.

    Attributes
    ----------
    name : str
        Scene name (``result.to_dict()["scene"]``).
    curve : callable(post_diameter, rod_diameter, rod_length, n_nodes) -> KnotCurve
        The start centreline round the post (z axis); node 0 is the loaded end.
        ``rod_length``/``n_nodes`` may be None (the curve picks them).
    pull_angle : float [rad]
        Wrap angle that sizes the contact stiffness of a pull (T_high up to about
        2 T_low exp(mu pull_angle)).
    invariants : callable(nodes) -> tuple, optional
        Knot invariants of a configuration, recomputed on frames of the run; None: only
        the distance and winding checks (the clove hitch).
    creep_limit : float or None [d/s]
        Default creep-speed criterion of the verdict (None: the distance rule only).
    hold_damping : float or None
        Dead-load loadings run as three phases, ``"settle"``, ``"load"``, ``"hold"``, the
        drag of the hold being this fraction of the settling drag; None: one phase
        ``"settle-load-hold"`` with the settling drag throughout (the clove hitch: its
        shipped tables were computed so).
    """

    name: str
    curve: object
    pull_angle: float = 4 * np.pi
    invariants: object = None
    creep_limit: float | None = CREEP_LIMIT
    hold_damping: float | None = 0.1


def darboux_profile(positions, m1):
    r"""Darboux vector components of a discrete rod in its material frame.

    With :math:`\hat d_3` the edge tangent, :math:`\hat d_1` = ``m1`` and
    :math:`\hat d_2 = \hat d_3\times\hat d_1`, eq. (1) of the clove-hitch paper,
    :math:`\hat d_a' = \Omega\times\hat d_a`, gives
    :math:`\Omega_1 = \hat d_2'\cdot\hat d_3 = -\hat d_3'\cdot\hat d_2`,
    :math:`\Omega_2 = \hat d_3'\cdot\hat d_1`, :math:`\Omega_3 = \hat d_1'\cdot\hat d_2`
    (eq. 2, i.e. :math:`\Omega_a = \tfrac12\varepsilon_{abc}\hat d_b'\cdot\hat d_c`). At each
    interior node the derivatives are differences between the two adjacent edges over the
    Voronoi length :math:`\ell_i = (|e^{i-1}| + |e^i|)/2`; :math:`\Omega_3` is the angle from
    :math:`\hat d_1^{i-1}`, parallel-transported onto edge i, to :math:`\hat d_1^i`.

    Parameters
    ----------
    positions : (n_nodes, 3) array [m]
    m1 : (n_nodes - 1, 3) array
        First material director of each edge (unit, normal to the edge).

    Returns
    -------
    s : (n_nodes - 2,) [m]  arc length of the interior nodes
    omega : (n_nodes - 2, 3) [1/m]  :math:`(\Omega_1, \Omega_2, \Omega_3)`
    """
    x = np.asarray(positions, dtype=float)
    d1 = np.asarray(m1, dtype=float)
    e = np.diff(x, axis=0)
    le = np.linalg.norm(e, axis=1)
    t = e / le[:, None]
    d1 = d1 - np.sum(d1 * t, axis=1)[:, None] * t
    d1 /= np.linalg.norm(d1, axis=1)[:, None]
    d2 = np.cross(t, d1)
    li = 0.5 * (le[:-1] + le[1:])
    dt3 = (t[1:] - t[:-1]) / li[:, None]
    a1 = d1[:-1] + d1[1:]
    a1 /= np.linalg.norm(a1, axis=1)[:, None]
    a2 = d2[:-1] + d2[1:]
    a2 /= np.linalg.norm(a2, axis=1)[:, None]
    om1 = -np.sum(dt3 * a2, axis=1)
    om2 = np.sum(dt3 * a1, axis=1)
    # parallel transport of d1^{i-1} onto t^i (rotation about t^{i-1} x t^i)
    ta, tb = t[:-1], t[1:]
    b = np.cross(ta, tb)
    sb = np.linalg.norm(b, axis=1)
    cb = np.sum(ta * tb, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where(sb[:, None] > 1e-14, b / sb[:, None], 0.0)
    v = d1[:-1]
    # Rodrigues: v cos + (u x v) sin + u (u.v)(1 - cos)
    pt = (
        v * cb[:, None]
        + np.cross(u, v) * sb[:, None]
        + u * np.sum(u * v, axis=1)[:, None] * (1 - cb[:, None])
    )
    ang = np.arctan2(np.sum(np.cross(pt, d1[1:]) * tb, axis=1), np.sum(pt * d1[1:], axis=1))
    om3 = ang / li
    s = np.cumsum(le)[:-1]
    return s, np.column_stack([om1, om2, om3])


@dataclass
class HitchResult:
    """Recorded output of a hitch run (:func:`run_hitch`).

    Attributes
    ----------
    loading : "symmetric", "asymmetric", "free" or "pull"
    t_high, t_low : float [N]  final end loads (end 0 carries t_high; ``"pull"``: the
        last recorded T_high)
    times : (n,) [s]; end_displacement : (n,) [m]  displacement of end 0 along its load
    s : (n_edges,) [m]  arc length of edge midpoints from end 0 (rest lengths)
    tension : (n_edges,) [N]  T(s) at the end of the run
    post_contact : (n_nodes,) bool  nodes pressed on the post
    rod_contact : (n_edges,) bool  edges touching another part of the rod
    s_nodes : (n_nodes - 2,) [m]; darboux : (n_nodes - 2, 3) [1/m]  Omega_1, Omega_2, Omega_3
    wrap_radius : float [m]  R = (D + d)/2
    mu_eff : float  thick-rod capstan coefficient for the rod-post friction
    winding_start, winding_end : float  turns about the post axis
    code_start, code_end : str  over/under code of the self-crossings seen from the axis
        (informative: free tails may legitimately add or remove crossing pairs)
    min_rod_distance : float [m]  smallest edge-edge distance between non-neighbouring
        edges over all accepted steps (centrelines; 2h = d at contact)
    min_post_gap : float [m]  smallest surface gap rod-post over all accepted steps
    verdict : "hold", "slip" or "" (only for the free-end loading)
    creep : float [m]  displacement of end 0 during the last half of the hold
    creep_speed : float [m/s]  speed of end 0 along its load over the creep window (the
        last second of the hold, or its last half if shorter; the least-squares slope
        through the frames in it; nan for ``"pull"``)
    tail_creep_speed : float [m/s]  speed at which the other end is drawn in along its
        tail over the same window (positive: into the knot)
    creep_window : float [s]
    creep_limit : float or None [d/s]  the creep-speed criterion the verdict used
    knot : str  scene name
    invariants_start, invariants_end : tuple or None  knot invariants of the start shape
        and of the last frame checked (None: the knot declares none)
    invariants_kept : bool or None  the invariants were the same on every checked frame
    positions : (n, n_nodes, 3) [m]
    status, message : str; stats : dict
    pull_speed : float [m/s]  ``"pull"`` loading: speed of end 0 (0 otherwise)
    pull_displacement : (m,) [m]  ``"pull"``: displacement of end 0 since the pull started
    pull_force : (m,) [N]  ``"pull"``: T_high, the force the moving clamp applies to end 0
        along the pull (its reaction), at each saved frame of the pull
    mu_kinetic : float  kinetic rod-post coefficient (= ``mu_rod_post`` unless given)
    warnings : list of str  one line each (a strain above 10 %); ``status`` is "failed"
        also when the strain exceeded 50 %
    """

    loading: str
    t_high: float
    t_low: float
    times: np.ndarray
    end_displacement: np.ndarray
    s: np.ndarray
    tension: np.ndarray
    post_contact: np.ndarray
    rod_contact: np.ndarray
    s_nodes: np.ndarray
    darboux: np.ndarray
    wrap_radius: float
    mu_eff: float
    winding_start: float
    winding_end: float
    code_start: str
    code_end: str
    verdict: str
    creep: float
    min_rod_distance: float
    min_post_gap: float
    positions: np.ndarray
    status: str
    message: str
    stats: dict = field(default_factory=dict)
    _rod_diameter: float = 0.0
    pull_speed: float = 0.0
    pull_displacement: np.ndarray = field(default_factory=lambda: np.zeros(0))
    pull_force: np.ndarray = field(default_factory=lambda: np.zeros(0))
    mu_kinetic: float = float("nan")
    warnings: list = field(default_factory=list)
    knot: str = "clove_hitch"
    creep_speed: float = float("nan")
    tail_creep_speed: float = float("nan")
    creep_window: float = float("nan")
    creep_limit: float | None = None
    invariants_start: tuple | None = None
    invariants_end: tuple | None = None
    invariants_kept: bool | None = None

    @property
    def rod_diameter(self) -> float:
        """Rod diameter d [m]."""
        return self._rod_diameter

    @property
    def creep_speed_d(self) -> float:
        """:attr:`creep_speed` in rod diameters per second [d/s]."""
        return self.creep_speed / self._rod_diameter

    @property
    def tail_creep_speed_d(self) -> float:
        """:attr:`tail_creep_speed` in rod diameters per second [d/s]."""
        return self.tail_creep_speed / self._rod_diameter

    def post_wraps(self, positions=None) -> list[dict]:
        r"""The stretches of rod lying on the post at the end of the run, with their wrap.

        For each run of consecutive edges whose two nodes touch the post: node range
        ``[i0, i1]``, the wrap angle :math:`\theta` the centreline turns through about the
        post axis between them [rad] (from the positions, not the design), and the
        tensions of the edges just outside it, ``t_in`` (towards end 0) and ``t_out`` [N].
        The capstan law bounds their ratio: :math:`t_\mathrm{in}/t_\mathrm{out} \le
        e^{\mu_\mathrm{eff}\theta}`.
        """
        x = self.positions[-1] if positions is None else np.asarray(positions)
        on = self.post_contact
        out = []
        n = len(on)
        i = 0
        while i < n:
            if not on[i]:
                i += 1
                continue
            j = i
            while j + 1 < n and on[j + 1]:
                j += 1
            if j > i:
                phi = np.unwrap(np.arctan2(x[i : j + 1, 1], x[i : j + 1, 0]))
                t_in = self.tension[i - 1] if i > 0 else self.tension[0]
                t_out = self.tension[j] if j < len(self.tension) else self.tension[-1]
                out.append({"i0": i, "i1": j, "theta": float(abs(phi[-1] - phi[0])),
                            "t_in": float(t_in), "t_out": float(t_out)})  # fmt: skip
            i = j + 1
        return out

    @property
    def ratio_curve(self) -> np.ndarray:
        """``"pull"`` loading: T_high/T_low along the pull (empty otherwise)."""
        return self.pull_force / self.t_low if self.pull_force.size else np.zeros(0)

    def ratio_at(self, displacement) -> float:
        """T_high/T_low at a pulled displacement [m] (linear interpolation; nan if outside)."""
        x = self.pull_displacement
        if x.size < 2 or not x[0] <= displacement <= x[-1]:
            return float("nan")
        return float(np.interp(displacement, x, self.ratio_curve))

    @property
    def topology_preserved(self) -> bool:
        """No strand passed through another or through the post, checked at every step.

        A passage needs two centrelines to meet (distance 0) or the rod to enter the post;
        the contact keeps them at least ``d/2`` apart and the post gap above ``-d/4``, and
        the winding number about the post changes by less than a quarter turn; for knots
        that declare invariants, these were also unchanged on every checked frame.
        """
        return bool(
            self.min_rod_distance > 0.5 * self._rod_diameter
            and self.min_post_gap > -0.25 * self._rod_diameter
            and abs(self.winding_end - self.winding_start) < 0.25
            and self.invariants_kept is not False
        )

    @property
    def curvature(self) -> np.ndarray:
        """Total curvature kappa = (Omega_1^2 + Omega_2^2)^(1/2) [1/m]."""
        return np.hypot(self.darboux[:, 0], self.darboux[:, 1])

    def to_dict(self) -> dict:
        """Plain-JSON dictionary of the profiles and the verdict."""
        return {
            "scene": self.knot,
            "loading": self.loading,
            "t_high": self.t_high,
            "t_low": self.t_low,
            "verdict": self.verdict,
            "creep": self.creep,
            "status": self.status,
            "message": self.message,
            "warnings": list(self.warnings),
            "stats": {k: float(v) for k, v in self.stats.items()},
            "winding": [self.winding_start, self.winding_end],
            "code": [self.code_start, self.code_end],
            "min_rod_distance": self.min_rod_distance,
            "min_post_gap": self.min_post_gap,
            "topology_preserved": self.topology_preserved,
            "s": self.s.tolist(),
            "tension": self.tension.tolist(),
            "rod_contact": self.rod_contact.astype(int).tolist(),
            "post_contact": self.post_contact.astype(int).tolist(),
            "s_nodes": self.s_nodes.tolist(),
            "darboux": self.darboux.tolist(),
            "mu_kinetic": self.mu_kinetic,
            "pull_speed": self.pull_speed,
            "pull_displacement": self.pull_displacement.tolist(),
            "pull_force": self.pull_force.tolist(),
            "ratio_curve": self.ratio_curve.tolist(),
            "creep_speed": _num(self.creep_speed),
            "creep_speed_d": _num(self.creep_speed_d),
            "tail_creep_speed": _num(self.tail_creep_speed),
            "creep_window": _num(self.creep_window),
            "creep_limit": self.creep_limit,
            "invariants_start": _inv(self.invariants_start),
            "invariants_end": _inv(self.invariants_end),
            "invariants_kept": self.invariants_kept,
        }


def _num(v):
    v = float(v)
    return v if np.isfinite(v) else None


def _inv(v):
    if v is None:
        return None
    alex, link = v
    # the polynomial's coefficients as one string: a scalar for JSON summaries
    return {"alexander": " ".join(str(int(c)) for c in alex), "linking": int(link)}


@dataclass
class _ScheduledDamping:
    """Viscous drag per unit length whose coefficient switches at ``t_switch``.

    Same force law as :class:`knotmech.rod.ViscousDamping` (F = -c l v, implicit); the
    coefficient is ``before`` for t <= t_switch and ``after`` later. ``apply`` records the
    coefficient of the step it is called for, and ``step_potential`` (the line-search
    merit, evaluated right after ``apply`` at the same step) uses it.
    """

    before: float
    after: float
    t_switch: float
    _c: float = float("nan")

    def _drag(self, c):
        return rod.ViscousDamping(coefficient=c)

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        self._c = self.before if t <= self.t_switch else self.after
        self._drag(self._c).apply(system, t, q, q_old, dt, force, jac_diag)

    def energy(self, system, q, t=np.inf) -> float:
        return 0.0

    def step_potential(self, system, q, q_old, dt) -> float:
        c = self.before if not np.isfinite(self._c) else self._c
        return self._drag(c).step_potential(system, q, q_old, dt)


def run_hitch(
    knot: HitchKnot,
    *,
    loading: str = "symmetric",
    t_high: float = 1.47,
    t_low: float | None = None,
    rod_diameter: float = 4e-3,
    post_diameter: float = 30e-3,
    rod_length: float | None = 0.374,
    youngs_modulus: float = VPS32_YOUNGS_MODULUS,
    density: float = PHASE_TABLE_DENSITY,
    bending_scale: float = 1.0,
    mu_rod_post: float = 0.3,
    mu_rod_rod: float = 0.3,
    pretension: float | None = None,
    settle_time: float = 0.5,
    load_time: float = 0.5,
    hold_time: float = 1.0,
    n_nodes: int | None = 150,
    dt: float = 2e-3,
    slip_distance: float | None = None,
    n_frames: int = 100,
    options: rod.SolverOptions | None = None,
    progress: bool = False,
    pull_speed: float = 0.02,
    pull_distance: float = 0.04,
    mu_kinetic: float | None = None,
    pull_dt: float | None = None,
    max_node_steps: float | None = None,
    friction: str = "anchor",
    creep_limit: float | None = None,
    creep_window: float | None = None,
    result_type: type | None = None,
) -> HitchResult:
    r"""Tie ``knot`` on a post and load it (the parameters of every hitch scene).

    Parameters
    ----------
    knot : HitchKnot
    loading : {"symmetric", "asymmetric", "free", "pull"}
        Dead loads T_high on end 0 and T_low on the other end (``"symmetric"``: both
        T_high; ``"free"``: T_low = 0, the verdict decides hold or slip); ``"pull"``: the
        clove-hitch paper's force-displacement test (sect. 5, Fig. 1d): the hitch settles
        with dead loads ``pretension`` on both ends; end 0 is then held by a clamp where it
        settled while the other end's dead load is lowered to ``t_low``, and pulled at
        ``pull_speed`` along its tail for ``pull_distance``; T_high is the clamp's reaction.
    t_high : float [N]
        Load on end 0 (and on both ends when symmetric); ignored by ``"pull"``.
    t_low : float [N], optional
        Load on the other end: ``t_high`` (symmetric), required (asymmetric), 0 (free);
        ``"pull"``: the dead load (default 0.069 N, the paper's 7 g).
    rod_diameter, post_diameter : float [m]
    rod_length : float [m] or None
        None: the knot's default (its knotted part and a 64 mm tail at each end).
    youngs_modulus : float [Pa]; density : float [kg/m^3]
    bending_scale : float
        kappa in (0, 1]: bending (and twisting) stiffness kappa E pi d^4 / 64 (1: a solid
        rod, the shipped tables; a fibre rope is of order 0.01, see :class:`knotmech.rod.Rod`).
    mu_rod_post, mu_rod_rod : float
        Rod-post (static, mu_s) and rod-rod friction coefficients (the rod-rod one static
        and kinetic alike).
    pretension : float [N], optional
        Load on both ends while the hitch settles (default ``0.1 * t_high``; ``"pull"``:
        the paper's 0.559 N).
    settle_time, load_time, hold_time : float [s]
        Settling under the pre-tension, ramp to the final loads, hold at the final loads
        (``"pull"``: ``load_time`` lowers the dead load to ``t_low``; no hold).
    n_nodes : int or None
        None: edges of about 3.1 mm (the clove hitch's 120 nodes on 374 mm).
    dt : float [s]
        Nominal step of the settling (and of the dead-load phases).
    slip_distance : float [m], optional
        Free-end loading: slip if end 0 moves more than this during the last half of the
        hold (default one rod diameter); the run stops early once end 0 has moved 0.3 L.
    n_frames : int
    options : knotmech.rod.SolverOptions, optional
    progress : bool
    pull_speed : float [m/s]
        ``"pull"``: speed of end 0 (default 20 mm/s; the drag during the pull is 1 % of
        ``t_low``).
    pull_distance : float [m]
        ``"pull"``: displacement of end 0 (default 40 mm).
    mu_kinetic : float, optional
        Kinetic rod-post coefficient mu_k <= ``mu_rod_post`` (default ``mu_rod_post``).
    pull_dt : float [s], optional
        ``"pull"``: nominal step of the pull (default: end 0 moves 1/4 of an edge per step,
        at most 0.2 rod radii).
    max_node_steps : float, optional
        Bound on (t_end/dt) x nodes, checked before the run (default
        :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it).
    friction : {"anchor", "imc"}
        Rod-rod friction law: ``"anchor"`` the elasto-plastic anchor per contact pair, which
        sticks below ``mu |F_n|`` (:class:`~knotmech.rod.friction.AnchorFriction`, with the
        library's default cap floor and the path tunnelling guard since issue 24); ``"imc"``
        the regularised law of the implicit contact model (:class:`~knotmech.rod.friction.
        SmoothFriction`), which creeps.
    creep_limit : float or None [d/s]
        Free-end verdict: also slip when end 0 creeps faster than this over the creep
        window (None: only the ``slip_distance`` rule).
    creep_window : float [s], optional
        Window of :attr:`HitchResult.creep_speed`: the last this-long of the hold (default
        1 s, at most half the hold).
    result_type : type, optional
        Class of the result (a :class:`HitchResult` subclass).

    Returns
    -------
    HitchResult
    """
    return HitchScene(
        knot,
        rod=HitchRod(
            rod_diameter=rod_diameter,
            post_diameter=post_diameter,
            rod_length=rod_length,
            youngs_modulus=youngs_modulus,
            density=density,
            bending_scale=bending_scale,
            n_nodes=n_nodes,
        ),
        friction=HitchFriction(
            mu_rod_post=mu_rod_post, mu_rod_rod=mu_rod_rod, mu_kinetic=mu_kinetic, law=friction
        ),
        load=HitchLoading(
            loading=loading,
            t_high=t_high,
            t_low=t_low,
            pretension=pretension,
            settle_time=settle_time,
            load_time=load_time,
            hold_time=hold_time,
            pull_speed=pull_speed,
            pull_distance=pull_distance,
            pull_dt=pull_dt,
        ),
        rule=HitchRule(
            slip_distance=slip_distance, creep_limit=creep_limit, creep_window=creep_window
        ),
        control=RunControl(
            dt=dt,
            n_frames=n_frames,
            options=options,
            progress=progress,
            max_node_steps=max_node_steps,
        ),
        result_type=result_type,
    ).run()


@dataclass(frozen=True)
class HitchRod:
    """The rod and the post of a hitch scene (SI units; :func:`run_hitch` documents them)."""

    rod_diameter: float = 4e-3
    post_diameter: float = 30e-3
    rod_length: float | None = 0.374
    youngs_modulus: float = VPS32_YOUNGS_MODULUS
    density: float = PHASE_TABLE_DENSITY
    bending_scale: float = 1.0
    n_nodes: int | None = 150


@dataclass(frozen=True)
class HitchFriction:
    """Rod-post (static ``mu_rod_post``, kinetic ``mu_kinetic``) and rod-rod friction, and
    the rod-rod law ``"anchor"`` or ``"imc"``."""

    mu_rod_post: float = 0.3
    mu_rod_rod: float = 0.3
    mu_kinetic: float | None = None
    law: str = "anchor"


@dataclass(frozen=True)
class HitchLoading:
    """The loading and its schedule [N], [s], [m/s], [m] (:func:`run_hitch` documents them)."""

    loading: str = "symmetric"
    t_high: float = 1.47
    t_low: float | None = None
    pretension: float | None = None
    settle_time: float = 0.5
    load_time: float = 0.5
    hold_time: float = 1.0
    pull_speed: float = 0.02
    pull_distance: float = 0.04
    pull_dt: float | None = None


@dataclass(frozen=True)
class HitchRule:
    """The free-end verdict's rule: ``slip_distance`` [m], ``creep_limit`` [d/s],
    ``creep_window`` [s]."""

    slip_distance: float | None = None
    creep_limit: float | None = None
    creep_window: float | None = None


_LOADINGS = ("symmetric", "asymmetric", "free", "pull")


def _end_loads(loading: str, t_high: float, t_low) -> tuple[float, float]:
    """(T_high, T_low) [N] checked for ``loading``: T_low defaults to T_high (symmetric),
    is required (asymmetric), is 0 (free) or the paper's 0.069 N (pull)."""
    th = float(check_positive("t_high", t_high, scalar=True))
    if loading == "symmetric":
        return th, th if t_low is None else float(check_positive("t_low", t_low, scalar=True))
    if loading == "asymmetric":
        if t_low is None:
            raise InputError("t_low is required for the asymmetric loading")
        return th, float(check_nonnegative("t_low", t_low, scalar=True))
    if loading == "pull":
        return th, 0.069 if t_low is None else float(check_positive("t_low", t_low, scalar=True))
    if t_low not in (None, 0, 0.0):
        raise InputError("t_low must be 0 (or omitted) for the free-end loading")
    return th, 0.0


class HitchScene(Scene):
    """A hitch tied on a post and loaded: the phases of :func:`run_hitch`."""

    def __init__(self, knot, *, rod, friction, load, rule, control, result_type=None):
        self.knot, self.rod_opts, self.fric, self.load = knot, rod, friction, load
        self.rule, self.control = rule, control
        self.result_type = HitchResult if result_type is None else result_type

    # -- setup -----------------------------------------------------------------------
    def setup(self) -> None:
        """Check every input, build the start curve and bound the run's cost."""
        if not isinstance(self.knot, HitchKnot):
            raise InputError(f"knot must be a HitchKnot, got {type(self.knot).__name__}")
        if self.load.loading not in _LOADINGS:
            raise InputError(
                f"loading must be 'symmetric', 'asymmetric', 'free' or 'pull', got "
                f"{self.load.loading!r}"
            )
        self._check_rod()
        self._check_friction()
        self._check_loading()
        self.warnings = check_strain(
            max(self.th if not self.pull else 0.0, self.tl, self.pre),
            self.ea,
            what="the largest end load",
        )
        o = self.rod_opts
        n = None if o.n_nodes is None else int(o.n_nodes)
        self._check_memory(n if n is not None else (self.L_arg or 0.0) / 3.1e-3)
        self.curve = self.knot.curve(self.D, self.d, self.L_arg, n)
        self.x0 = self.curve.nodes
        self.N = len(self.x0)
        self.L = (
            self.L_arg
            if self.L_arg is not None
            else float(self.curve.info.get("rod_length", self.curve.rod_length))
        )
        self._check_cost()

    @property
    def pull(self) -> bool:
        """True for the ``"pull"`` loading."""
        return self.load.loading == "pull"

    def _check_rod(self) -> None:
        o = self.rod_opts
        self.d = float(check_positive("rod_diameter", o.rod_diameter, scalar=True))
        self.D = float(check_positive("post_diameter", o.post_diameter, scalar=True))
        self.L_arg = (
            None
            if o.rod_length is None
            else float(check_positive("rod_length", o.rod_length, scalar=True))
        )
        self.E = float(check_positive("youngs_modulus", o.youngs_modulus, scalar=True))
        self.kappa = check_bending_scale(o.bending_scale)
        self.rho = float(check_positive("density", o.density, scalar=True))
        if o.n_nodes is not None:
            check_count("n_nodes", o.n_nodes, 2)
        check_count("n_frames", self.control.n_frames, 2)
        self.ea = self.E * np.pi * self.d * self.d / 4
        check_post_size(self.D, self.d, "hitch")

    def _check_friction(self) -> None:
        f = self.fric
        self.mrc = float(check_nonnegative("mu_rod_post", f.mu_rod_post, scalar=True))
        self.mrr = float(check_nonnegative("mu_rod_rod", f.mu_rod_rod, scalar=True))
        self.mk = (
            self.mrc
            if f.mu_kinetic is None
            else float(check_nonnegative("mu_kinetic", f.mu_kinetic, scalar=True))
        )
        if self.mk > self.mrc:
            raise InputError(f"mu_kinetic must be <= mu_rod_post ({self.mrc:g}), got {self.mk:g}")
        if f.law not in ("anchor", "imc"):
            raise InputError(f"friction must be 'anchor' or 'imc', got {f.law!r}")
        r = self.rule
        self.climit = (
            None
            if r.creep_limit is None
            else float(check_positive("creep_limit", r.creep_limit, scalar=True))
        )
        self.cwin = (
            1.0
            if r.creep_window is None
            else float(check_positive("creep_window", r.creep_window, scalar=True))
        )
        self.slip = (
            self.d
            if r.slip_distance is None
            else float(check_positive("slip_distance", r.slip_distance, scalar=True))
        )

    def _check_loading(self) -> None:
        ld = self.load
        self.th, self.tl = _end_loads(ld.loading, ld.t_high, ld.t_low)
        if self.pull:
            pre = PAPER_PRETENSION if ld.pretension is None else ld.pretension
            self.pre = float(check_positive("pretension", pre, scalar=True))
            self.v = float(check_positive("pull_speed", ld.pull_speed, scalar=True))
            self.dist = float(check_positive("pull_distance", ld.pull_distance, scalar=True))
        else:
            self.pre = (
                0.1 * self.th
                if ld.pretension is None
                else float(check_positive("pretension", ld.pretension, scalar=True))
            )
            self.v = ld.pull_speed
            check_nonnegative("pull_speed", ld.pull_speed, scalar=True)  # unused: checked
            check_positive("pull_distance", ld.pull_distance, scalar=True)
        for name, val in (("settle_time", ld.settle_time), ("load_time", ld.load_time)):
            check_positive(name, val, scalar=True)
        check_nonnegative("hold_time", ld.hold_time, scalar=True)
        self.step = float(check_positive("dt", self.control.dt, scalar=True))

    def _check_cost(self) -> None:
        """The node-steps bound, and the pull step (one edge at most per step)."""
        ld = self.load
        if self.pull:  # the pull phase's step: edge/4 or d/10 per step
            t_work = ld.settle_time + ld.load_time + self.dist / self.v
            h = self.L / (self.N - 1)
            dt_work = (
                min(0.25 * self.L / self.N, 0.1 * self.d) / self.v
                if ld.pull_dt is None
                else ld.pull_dt
            )
            pstep = min(0.25 * h, 0.1 * self.d) / self.v if ld.pull_dt is None else ld.pull_dt
            self.pstep = float(check_positive("pull_dt", pstep, scalar=True))
        else:
            t_work, dt_work = ld.settle_time + ld.load_time + ld.hold_time, self.control.dt
        check_run_size(
            n_nodes=self.N,
            t_end=t_work,
            dt=float(check_positive("dt", dt_work, scalar=True)),
            max_node_steps=self.control.max_node_steps,
            hint="use a larger dt, fewer nodes or a lower pull speed",
        )
        if self.pull:
            check_pull_step(self.pstep, speed=self.v, edge_length=h, name="pull_dt")
        self._check_memory(self.N)
        self._check_tied()

    def _check_memory(self, n_nodes: float) -> None:
        """The all-pairs distance watch (every step) and the frames, before allocation."""
        n = float(n_nodes)
        check_memory(
            pair_check_bytes(n) + frames_bytes(self.control.n_frames, n),
            what=f"the strands' distance watch on {n:.3g} nodes",
            hint="use fewer nodes (n_nodes) or a shorter rod (rod_length)",
        )

    def _check_tied(self) -> None:
        """Refuse a start curve the scene cannot tie: strands closer than half a diameter
        (the rod thicker than the post allows for this knot) or the rod inside the post;
        the run would start from a shape that already failed its topology check."""
        x, d = self.x0, self.d
        idx = np.arange(self.N - 1)
        gaps = _edge_distances(x)[np.abs(idx[:, None] - idx[None, :]) >= 3]
        gap = float(gaps.min()) if gaps.size else np.inf
        post_gap = float(np.min(np.hypot(x[:, 0], x[:, 1]))) - 0.5 * (self.D + d)
        if gap <= 0.5 * d or post_gap <= -0.25 * d:
            raise InputError(
                f"{self.knot.name} cannot be tied with a {d * 1e3:.3g} mm rod on a "
                f"{self.D * 1e3:.3g} mm post: its start curve's strands come {gap / d:.2f} d "
                f"apart (< 0.5 d) or it enters the post; use a thicker post "
                f"(post_diameter) or a thinner rod (rod_diameter)"
            )

    # -- build -----------------------------------------------------------------------
    def build(self) -> SceneRun:
        """The rod on the start curve, the post, the rod-rod contact and the loads."""
        x0, N, d, ld = self.x0, self.N, self.d, self.load
        self.R = 0.5 * (self.D + d)
        r = rod.Rod(
            positions=x0,
            radius=0.5 * d,
            youngs_modulus=self.E,
            density=self.rho,
            natural="straight",
            bending_scale=self.kappa,
        )
        self.system = rod.RodSystem([r])
        dir0 = x0[0] - x0[1]
        self.dir0 = dir0 / np.linalg.norm(dir0)
        dir1 = x0[-1] - x0[-2]
        self.dir1 = dir1 / np.linalg.norm(dir1)
        self.t1 = float(ld.settle_time)
        self.t2 = self.t1 + float(ld.load_time)
        self.t_end = self.t2 + (self.dist / self.v if self.pull else float(ld.hold_time))
        mass_per_length = self.rho * np.pi * d * d / 4
        self.damp_settle = 2.0 * mass_per_length / (0.1 * self.t1)
        t_max = self._pull_loads() if self.pull else self._dead_loads()
        post = post_contact(
            post_diameter=self.D,
            rod_diameter=d,
            force_scale=t_max,
            mu_static=self.mrc,
            mu_kinetic=self.mk,
        )
        rr_contact = RodContact(
            stiffness=20.0 * t_max / d, sharpness=15.0 / (0.05 * d), friction=self._rod_friction()
        )
        self.closest = {"rod": np.inf, "post": np.inf}
        idx_e = np.arange(N - 1)
        self.far = np.abs(idx_e[:, None] - idx_e[None, :]) >= 3
        c = self.control
        base = c.options if c.options is not None else DEFAULT_OPTIONS
        return SceneRun(
            self.system,
            interactions=[post, rr_contact],
            options=base,
            watch=self._watch,
            progress=c.progress,
        )

    def _rod_friction(self):
        if self.mrr <= 0:
            return None
        if self.fric.law == "anchor":
            # the library's anchor law (cap floor min(1e-2 (r_i + r_j), 1/sharpness) since
            # session 15; the hitches had cap floor 0 in session 13-14: the radii floor alone
            # let the clove-hitch paper's free-end hitch slip, sticking-law-cap-width.md 10-11)
            return AnchorFriction(mu_static=self.mrr)
        return SmoothFriction(self.mrr)

    def _dead_loads(self) -> float:
        """Pre-tension on both ends, ramped to T_high and T_low; returns the force scale."""
        N, pre, t1, t2 = self.N, self.pre, self.t1, self.t2
        self.loads = [
            RampedEndLoad(0, pre * self.dir0, 0.3 * t1),
            RampedEndLoad(N - 1, pre * self.dir1, 0.3 * t1),
            RampedEndLoad(0, (self.th - pre) * self.dir0, t2 - t1, delay=t1),
            RampedEndLoad(N - 1, (self.tl - pre) * self.dir1, t2 - t1, delay=t1),
            rod.ViscousDamping(coefficient=self.damp_settle),
        ]
        return max(self.th, self.tl, self.pre)

    def _pull_loads(self) -> float:
        """Settling: both ends at the pre-tension; then end 0 is clamped where it settled
        and only the other end carries a dead load (lowered to t_low). Returns the force
        scale: T_high up to about 2 T_low exp(mu theta)."""
        N, pre, t1, t2, tl = self.N, self.pre, self.t1, self.t2, self.tl
        self.settle_loads = [
            RampedEndLoad(0, pre * self.dir0, 0.3 * t1),
            RampedEndLoad(N - 1, pre * self.dir1, 0.3 * t1),
            rod.ViscousDamping(coefficient=self.damp_settle),
        ]
        self.loads = [
            RampedEndLoad(N - 1, pre * self.dir1, 0.3 * t1),
            RampedEndLoad(N - 1, (tl - pre) * self.dir1, t2 - t1, delay=t1),
            # drag of the whole rod moving at v: 1 % of T_low
            _ScheduledDamping(self.damp_settle, 0.01 * tl / (self.L * self.v), t2),
        ]
        return max(pre, 2.0 * tl * float(np.exp(self.mrc * self.knot.pull_angle)))

    def _watch(self, x) -> None:
        c = self.closest
        c["rod"] = min(c["rod"], float(_edge_distances(x)[self.far].min()))
        c["post"] = min(c["post"], float(np.min(np.hypot(x[:, 0], x[:, 1])) - self.R))

    def _ran_out(self, x) -> bool:
        lim = 0.3 * self.L if self.load.loading == "free" else np.inf
        return float((x[0] - self.x0[0]) @ self.dir0) > lim

    # -- phases ----------------------------------------------------------------------
    def run_phases(self, run: SceneRun) -> None:
        """Dead loads (one phase or settle/load/hold) or the pull test."""
        self.every = self.t_end / (int(self.control.n_frames) - 1)
        self.pull_disp = self.pull_force = np.zeros(0)
        if self.pull:
            self._pull_phases(run)
        elif self.knot.hold_damping is None:
            run.phase(
                "settle-load-hold",
                self.t_end,
                dt=self.step,
                loads=self.loads,
                save_every=self.every,
                stop=self._ran_out,
            )
        else:
            self._dead_load_phases(run)

    def _dead_load_phases(self, run: SceneRun) -> None:
        ramps = self.loads[:-1]
        drag = rod.ViscousDamping(coefficient=self.damp_settle * self.knot.hold_damping)
        hold_loads = [*ramps, drag]
        for name, t_a, t_b, lds in (
            ("settle", 0.0, self.t1, self.loads),
            ("load", self.t1, self.t2, self.loads),
            ("hold", self.t2, self.t_end, hold_loads),
        ):
            if t_b > t_a and not run.phase(
                name, t_b - t_a, dt=self.step, loads=lds, save_every=self.every, stop=self._ran_out
            ):
                break
            if run.t < t_b - 1e-9:  # stopped early: end 0 ran out
                break

    def _pull_phases(self, run: SceneRun) -> None:
        """Settle, lower the dead load with end 0 held, pull end 0 along its tail; T_high is
        the clamp's reaction on node 0 along the pull."""
        if not run.phase(
            "settle",
            self.t1,
            dt=self.step,
            loads=self.settle_loads,
            save_every=min(self.every, self.t1 / 4),
        ):
            return
        xs = self.system.positions(run.state.q)
        pull_dir = (xs[0] - xs[1]) / np.linalg.norm(xs[0] - xs[1])
        constraints = (
            MovingNodes(nodes=[0], path=_grip(xs[0].copy(), pull_dir, self.v, self.t2)),
            Clamp(edges=[0]),
        )
        # lower the dead load (end 0 held), then pull, each with its own nominal step
        run.phase(
            "lower",
            self.t2 - self.t1,
            dt=min(5 * self.step, self.pstep),
            loads=self.loads,
            constraints=constraints,
            save_every=self.every,
        )
        k0 = len(run.times)
        if (
            run.phase(
                "pull",
                self.t_end - self.t2,
                dt=self.pstep,
                loads=self.loads,
                constraints=constraints,
                save_every=self.every,
            )
            or len(run.times) > k0
        ):
            p = run.phases[-1]
            tt = np.asarray(run.times[k0 - 1 :])
            # the clamp's reaction on node 0 along the pull: what the machine reads (the
            # phase's first frame is its static reaction at the start)
            rx = np.vstack([p.start_reactions[0], run.reaction([0], tt[1:])])
            self.pull_force = rx @ pull_dir
            self.pull_disp = self.v * (tt - self.t2)

    # -- measure ---------------------------------------------------------------------
    def measure(self, run: SceneRun) -> HitchResult:
        """Profiles, contacts, creep and verdict, checked (strain) into a result."""
        times, pos = run.frames()
        disp = (pos[:, 0, :] - self.x0[0]) @ self.dir0
        last = pos[-1]
        on_post, on_rod = self._contacts(last)
        s_nodes, omega = self._darboux(run.state)
        creep, window, v_end, v_tail = self._creep(times, pos, disp)
        inv0 = inv1 = kept = None
        if self.knot.invariants is not None:
            inv0, inv1, kept = _check_invariants(self.knot.invariants, self.x0, pos, disp, self.d)
        verdict = self._verdict(run, times, creep, v_end, kept)
        th = self.th
        if self.pull:
            th = float(self.pull_force[-1]) if self.pull_force.size else float("nan")
        le = self.system.rest_length
        reason, more = measured_strain(
            np.concatenate([run.tension, self.pull_force]), self.ea, warned=bool(self.warnings)
        )
        status, message = fail(run.status, run.message, reason)
        if self.pull:
            status, message = fail(status, message, check_numbers(t_high=th))
        unsettled = self._unsettled(run)
        if unsettled is not None:  # no verdict from a run that never reached its load
            verdict = ""
            status, message = fail(status, message, unsettled)
        return self.result_type(
            loading=self.load.loading,
            t_high=th,
            t_low=self.tl,
            times=times,
            end_displacement=disp,
            s=np.cumsum(le) - 0.5 * le,
            tension=run.tension,
            post_contact=on_post,
            rod_contact=on_rod,
            s_nodes=s_nodes,
            darboux=omega,
            wrap_radius=self.R,
            mu_eff=float(_mu_eff(self.mrc, self.D / self.d)),
            winding_start=winding_number(self.x0),
            winding_end=winding_number(last),
            code_start=post_crossing_code(self.x0),
            code_end=post_crossing_code(last),
            verdict=verdict,
            creep=creep,
            min_rod_distance=self.closest["rod"],
            min_post_gap=self.closest["post"],
            positions=pos,
            status=status,
            message=message,
            stats=run.stats,
            _rod_diameter=self.d,
            pull_speed=self.v if self.pull else 0.0,
            pull_displacement=self.pull_disp,
            pull_force=self.pull_force,
            mu_kinetic=self.mk,
            warnings=self.warnings + more,
            knot=self.knot.name,
            creep_speed=v_end,
            tail_creep_speed=v_tail,
            creep_window=window,
            creep_limit=self.climit,
            invariants_start=inv0,
            invariants_end=inv1,
            invariants_kept=kept,
        )

    def _contacts(self, last):
        """Nodes on the post and edges touching another part of the rod, at ``last``."""
        d = self.d
        on_post = np.hypot(last[:, 0], last[:, 1]) < self.R + 0.05 * d
        ed = _edge_distances(last)
        idx = np.arange(self.N - 1)
        ed[np.abs(idx[:, None] - idx[None, :]) < 3] = np.inf
        return on_post, ed.min(axis=1) < 1.05 * d

    def _darboux(self, st):
        q = st.q
        thetas = self.system.thetas(q)
        ref1 = st.d1
        ref2 = np.cross(st.tangents, ref1)
        m1 = np.cos(thetas)[:, None] * ref1 + np.sin(thetas)[:, None] * ref2
        return darboux_profile(self.system.positions(q), m1)

    def _creep(self, times, pos, disp):
        """(creep [m] over the last half of the hold, window [s], end-0 speed, tail
        draw-in speed [m/s]); nan for the pull."""
        creep = window = v_end = v_tail = float("nan")
        if self.pull:
            return creep, window, v_end, v_tail
        t2 = self.t2
        sel = times >= t2 + 0.5 * (self.t_end - t2)
        if np.any(sel):
            creep = float(disp[-1] - disp[sel][0])
        if times[-1] > t2:
            window = min(self.cwin, 0.5 * (times[-1] - t2))
            ta = times[-1] - window
            if window > 0:
                # along the end edge's last direction: a tail swinging about the knot does
                # not count, a tail drawn into it does
                t_last = pos[-1, -1] - pos[-1, -2]
                draw = (pos[:, -1, :] - self.x0[-1]) @ (-t_last / np.linalg.norm(t_last))
                v_end, v_tail = (_mean_speed(times, u, ta, window) for u in (disp, draw))
        return creep, window, v_end, v_tail

    def _verdict(self, run, times, creep, v_end, kept) -> str:
        """Free-end loading: "slip" or "hold" (see the module docstring); else ""."""
        if self.load.loading != "free":
            return ""
        if run.over_budget and kept is not False:  # cut short by its budget, knot intact
            return ""
        stopped_early = times[-1] < self.t_end - 1e-9 and run.status == "success"
        fast = self.climit is not None and not (abs(v_end) <= self.climit * self.d)
        undone = kept is False  # the knot came apart (or a strand passed through)
        return "slip" if stopped_early or not (creep <= self.slip) or fast or undone else "hold"

    def _unsettled(self, run) -> str | None:
        """Why a dead-load run gives no verdict: it stopped (end 0 ran out, or the solver
        failed) before its settling ended, so the load was never applied; else None."""
        if self.pull or run.t >= self.t1 * (1 - 1e-9):  # relative: a 1e-12 s settle counts
            return None
        if run.status != "success":
            return run.message
        return (
            f"the knot came apart while it settled under the pre-tension ({self.pre:.3g} N): "
            f"end 0 ran out 0.3 L by t = {run.t:.3g} s, before the load phase (from "
            f"{self.t1:g} s); no verdict"
        )


def _mean_speed(times, u, t_a, window) -> float:
    """Speed [m/s] of ``u`` over [t_a, end]: the least-squares slope through the frames in
    the window when there are at least four (a hitch at rest still rings at the 1e-4 d
    level, which an end-point difference over a short window reads as creep), else the
    end-point difference."""
    sel = times >= t_a - 1e-12
    if np.count_nonzero(sel) >= 4:
        return float(np.polyfit(times[sel], u[sel], 1)[0])
    return float((u[-1] - np.interp(t_a, times, u)) / window)


def _grip(x0, u, v, t_start):
    def path(t, xc=x0, u=u, v=v, t2=t_start):
        return xc + u * v * max(0.0, t - t2)

    return path


def _check_invariants(invariants, x0, pos, disp, d):
    """Invariants of the start shape and of every recorded frame while end 0 has moved
    less than 10 d (beyond, a slipping hitch legitimately comes apart): (start's, last
    frame checked's, kept) with kept None when no frame qualifies, False at the first frame
    whose invariants differ (or that cannot be closed)."""
    inv0 = invariants(x0)
    frames = np.flatnonzero(np.abs(disp) < 10 * d)
    if frames.size == 0:
        return inv0, None, None
    last = inv0
    for k in frames:
        try:
            last = invariants(pos[k])
        except InputError:  # a degenerate projection: strands touching at rounding
            return inv0, None, False
        if last != inv0:
            return inv0, last, False
    return inv0, last, True


def hitch_scene(knot: HitchKnot, *, doc: str, defaults: dict | None = None,
                result_type: type | None = None):  # fmt: skip
    """The public scene function of ``knot``: :func:`run_hitch` with ``knot`` and
    ``result_type`` bound, the same keywords (``defaults`` overrides some of their
    defaults) and ``doc`` as docstring.
    """
    sig = inspect.signature(run_hitch)
    over = {"creep_limit": knot.creep_limit, **(defaults or {})}
    params = [
        p.replace(default=over.get(p.name, p.default))
        for p in sig.parameters.values()
        if p.name not in ("knot", "result_type")
    ]

    def scene(**kwargs):
        unknown = sorted(set(kwargs) - {p.name for p in params})
        if unknown:
            raise InputError(f"{knot.name}() got unknown keyword(s): {', '.join(unknown)}")
        args = {p.name: p.default for p in params}
        args.update(kwargs)
        return run_hitch(knot, result_type=result_type, **args)

    scene.__name__ = scene.__qualname__ = knot.name
    scene.__doc__ = doc
    scene.__signature__ = sig.replace(parameters=params)
    return scene
