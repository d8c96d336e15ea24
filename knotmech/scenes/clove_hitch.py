r"""The clove hitch on a rigid post in simulation: tie, load, read T(s), contacts, Darboux.

Tying (a pre-shaped curve relaxed with contact, instead of the seven-step protocol of the
clove-hitch paper, sec. 4): :func:`knotmech.scenes.curves.clove_hitch_curve` puts two wraps
on the post at centreline radius :math:`R = (D+d)/2` with the diagonal crossing over both
ends; the naturally straight rod is then released with both ends under a small pre-tension
:math:`T_\mathrm{pre}`, so it settles onto the post (rigid cylinder, elasto-plastic friction
on the rod surface, :class:`knotmech.rod.contact.CylinderContact`) and onto itself (the
implicit contact model, :class:`knotmech.rod.contact.RodContact`).

Loading (the clove-hitch paper, sec. 5-8), dead loads along the two tails:

- ``"symmetric"``: both ends pulled with T (:math:`T_\mathrm{high} = T_\mathrm{low}`);
- ``"asymmetric"``: end 0 with :math:`T_\mathrm{high}`, the other end with :math:`T_\mathrm{low}`;
- ``"free"``: :math:`T_\mathrm{low} = 0`, a hanging load :math:`T_\mathrm{high}` on end 0 and the
  other end free; the run decides *hold* (the loaded end stops) or *slip*.
- ``"pull"``: the force-displacement test of the clove-hitch paper (sect. 5, Fig. 1d): the
  hitch settles with both ends at the pre-tension (0.559 N), end 0 is then clamped where it
  settled, the other end's dead load is lowered to :math:`T_\mathrm{low}` (0.069 N), and
  end 0 is pulled at a constant speed; :math:`T_\mathrm{high}(\Delta)` is the clamp's
  reaction along the pull. Rod-post friction with :math:`\mu_s \ge \mu_k`
  (``mu_rod_post``, ``mu_kinetic``); the rod-rod friction has a single coefficient.

Outputs: tension profile :math:`T(s)` (axial force of each edge), rod-post and rod-rod
contact regions, the components of the Darboux vector :math:`\Omega_a(s)` in the material
frame (curvatures :math:`\Omega_1, \Omega_2` and twist :math:`\Omega_3`, the clove-hitch
paper eqs. 1-2), the knot's winding number about the post and its over/under code.

Default parameters: the clove-hitch paper, sec. 7: (d, D, L) = (4, 30, 374) mm, VPS32
(E = 1.26 MPa), :math:`\mu_{rc} = \mu_{rr} = 0.3`, :math:`T_\mathrm{high}` = 1.47 N.
The rod-rod friction is by default the elasto-plastic anchor (``friction="anchor"``,
:class:`knotmech.rod.friction.AnchorFriction`), which sticks: a held hitch does not creep.
``friction="imc"`` selects the regularised law of the coated-rod paper, which does not
stick exactly (a hitch held only by its nips creeps slowly). The hold/slip verdict
compares the creep over the last half of the hold with ``slip_distance``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech import rod
from knotmech.analytic.capstan import mu_eff as _mu_eff
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.contact import Cylinder, CylinderContact, RodContact
from knotmech.rod.friction import AnchorFriction, SmoothFriction
from knotmech.scenes._common import (
    check_pull_step,
    check_run_size,
    check_strain,
    fail,
    measured_strain,
)
from knotmech.scenes._scene import RampedEndLoad as _RampedEndLoad
from knotmech.scenes.curves import _edge_distances, clove_hitch_curve
from knotmech.scenes.topology import post_crossing_code, winding_number

__all__ = ["CloveHitchResult", "clove_hitch", "darboux_profile"]


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
class CloveHitchResult:
    """Recorded output of a clove-hitch run.

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
        the winding number about the post changes by less than a quarter turn.
        """
        return bool(
            self.min_rod_distance > 0.5 * self._rod_diameter
            and self.min_post_gap > -0.25 * self._rod_diameter
            and abs(self.winding_end - self.winding_start) < 0.25
        )

    @property
    def curvature(self) -> np.ndarray:
        """Total curvature kappa = (Omega_1^2 + Omega_2^2)^(1/2) [1/m]."""
        return np.hypot(self.darboux[:, 0], self.darboux[:, 1])

    def to_dict(self) -> dict:
        """Plain-JSON dictionary of the profiles and the verdict."""
        return {
            "scene": "clove_hitch",
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
        }


PAPER_PRETENSION = 0.559
"""[N] pre-tension of the clove-hitch paper's pull test (sect. 5: T_low raised to 0.559 N
with an extra 50 g, end 0 displaced until T_high = T_low, then the extra weight removed)."""


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


def clove_hitch(
    *,
    loading: str = "symmetric",
    t_high: float = 1.47,
    t_low: float | None = None,
    rod_diameter: float = 4e-3,
    post_diameter: float = 30e-3,
    rod_length: float = 0.374,
    youngs_modulus: float = 1.26e6,
    density: float = 1150.0,
    mu_rod_post: float = 0.3,
    mu_rod_rod: float = 0.3,
    pretension: float | None = None,
    settle_time: float = 0.5,
    load_time: float = 0.5,
    hold_time: float = 1.0,
    n_nodes: int = 150,
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
) -> CloveHitchResult:
    r"""Tie a clove hitch on a post and load it.

    Parameters
    ----------
    loading : {"symmetric", "asymmetric", "free", "pull"}
        ``"pull"``: the clove-hitch paper's force-displacement test (sect. 5, Fig. 1d). The
        hitch settles with dead loads ``pretension`` on both ends; end 0 is then held by a
        clamp where it settled while the other end's dead load is lowered to ``t_low`` (the
        extra weight removed), and pulled at ``pull_speed`` along its tail for
        ``pull_distance``; T_high is the clamp's reaction along the pull.
    t_high : float [N]
        Load on end 0 (and on both ends when symmetric); ignored by ``"pull"``.
    t_low : float [N], optional
        Load on the other end: ``t_high`` (symmetric), required (asymmetric), 0 (free);
        ``"pull"``: the dead load (default 0.069 N, the paper's 7 g).
    rod_diameter, post_diameter, rod_length : float [m]
    youngs_modulus : float [Pa]; density : float [kg/m^3]
    mu_rod_post, mu_rod_rod : float
        Rod-cylinder (static, mu_s) and rod-rod friction coefficients (the rod-rod one
        static and kinetic alike).
    pretension : float [N], optional
        Load on both ends while the hitch settles (default ``0.1 * t_high``; ``"pull"``:
        the paper's 0.559 N).
    settle_time, load_time, hold_time : float [s]
        Settling under the pre-tension, ramp to the final loads, hold at the final loads
        (``"pull"``: ``load_time`` lowers the dead load to ``t_low``; no hold).
    n_nodes : int
    dt : float [s]
        Nominal step of the settling (and of the dead-load phases).
    slip_distance : float [m], optional
        Free-end loading: slip if end 0 moves more than this during the last half of the
        hold (default one rod diameter); the run stops early once end 0 has moved 0.3 L.
    n_frames : int
    options : knotmech.rod.SolverOptions, optional
    progress : bool
    pull_speed : float [m/s]
        ``"pull"``: speed of end 0 (default 20 mm/s; the run is quasi-static: the drag during
        the pull is 1 % of ``t_low``).
    pull_distance : float [m]
        ``"pull"``: displacement of end 0 (default 40 mm).
    mu_kinetic : float, optional
        Kinetic rod-post coefficient mu_k <= ``mu_rod_post`` (default ``mu_rod_post``:
        kinetic friction only).
    pull_dt : float [s], optional
        ``"pull"``: nominal step of the pull (default: end 0 moves 1/4 of an edge per step,
        at most 0.2 rod radii).
    max_node_steps : float, optional
        Bound on (t_end/dt) x nodes, checked before the rod is built (default
        :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it).
    friction : {"anchor", "imc"}
        Rod-rod friction law: ``"anchor"`` (default) the elasto-plastic anchor per contact
        pair, which sticks below mu |F_n| (:class:`~knotmech.rod.friction.AnchorFriction`;
        a held hitch does not creep); ``"imc"`` the regularised law of the implicit
        contact model and the coated-rod paper (:class:`~knotmech.rod.friction.
        SmoothFriction`), which vanishes at zero slip, so that a hitch held by its nips
        creeps (the law of the shipped phase tables).

    Returns
    -------
    CloveHitchResult
    """
    if loading not in ("symmetric", "asymmetric", "free", "pull"):
        raise InputError(
            f"loading must be 'symmetric', 'asymmetric', 'free' or 'pull', got {loading!r}"
        )
    d = float(check_positive("rod_diameter", rod_diameter))
    D = float(check_positive("post_diameter", post_diameter))
    L = float(check_positive("rod_length", rod_length))
    E = float(check_positive("youngs_modulus", youngs_modulus))
    rho = float(check_positive("density", density))
    th = float(check_positive("t_high", t_high))
    mrc = float(check_nonnegative("mu_rod_post", mu_rod_post))
    mrr = float(check_nonnegative("mu_rod_rod", mu_rod_rod))
    mk = mrc if mu_kinetic is None else float(check_nonnegative("mu_kinetic", mu_kinetic))
    if mk > mrc:
        raise InputError(f"mu_kinetic must be <= mu_rod_post ({mrc:g}), got {mk:g}")
    if friction not in ("anchor", "imc"):
        raise InputError(f"friction must be 'anchor' or 'imc', got {friction!r}")
    if loading == "symmetric":
        tl = th if t_low is None else float(check_positive("t_low", t_low))
    elif loading == "asymmetric":
        if t_low is None:
            raise InputError("t_low is required for the asymmetric loading")
        tl = float(check_nonnegative("t_low", t_low))
    elif loading == "pull":
        tl = 0.069 if t_low is None else float(check_positive("t_low", t_low))
    else:
        if t_low not in (None, 0, 0.0):
            raise InputError("t_low must be 0 (or omitted) for the free-end loading")
        tl = 0.0
    if loading == "pull":
        pre = PAPER_PRETENSION if pretension is None else pretension
        pre = float(check_positive("pretension", pre))
        v = float(check_positive("pull_speed", pull_speed))
        dist = float(check_positive("pull_distance", pull_distance))
    else:
        pre = 0.1 * th if pretension is None else float(check_positive("pretension", pretension))
    for name, val in (("settle_time", settle_time), ("load_time", load_time)):
        check_positive(name, val)
    check_nonnegative("hold_time", hold_time)
    ea = E * np.pi * d * d / 4
    warnings = check_strain(max(th if loading != "pull" else 0.0, tl, pre), ea,
                            what="the largest end load")  # fmt: skip
    R = 0.5 * (D + d)
    wraps = 4 * np.pi * R * 1.15
    tail = 0.5 * (L - wraps)
    if tail < 4 * d:
        raise InputError(
            f"rod_length must exceed about 4 pi R + 8 d = {wraps + 8 * d:.3g} m, got {L:g}"
        )
    if loading == "pull":  # the pull phase's step (below): edge/4 or d/10 per step
        t_work = settle_time + load_time + dist / v
        dt_work = min(0.25 * L / int(n_nodes), 0.1 * d) / v if pull_dt is None else pull_dt
    else:
        t_work, dt_work = settle_time + load_time + hold_time, dt
    check_run_size(n_nodes=int(n_nodes), t_end=t_work, dt=float(check_positive("dt", dt_work)),
                   max_node_steps=max_node_steps,
                   hint="use a larger dt, fewer nodes or a lower pull speed")  # fmt: skip
    curve = clove_hitch_curve(
        post_diameter=D, rod_diameter=d, tail_length=tail, n_nodes=int(n_nodes)
    )
    x0 = curve.nodes
    N = len(x0)
    r = rod.Rod(positions=x0, radius=0.5 * d, youngs_modulus=E, density=rho, natural="straight")
    system = rod.RodSystem([r])
    dir0 = x0[0] - x0[1]
    dir0 /= np.linalg.norm(dir0)
    dir1 = x0[-1] - x0[-2]
    dir1 /= np.linalg.norm(dir1)
    t1 = float(settle_time)
    t2 = t1 + float(load_time)
    t_end = t2 + float(hold_time)
    if loading == "pull":
        t_end = t2 + dist / v
    mass_per_length = rho * np.pi * d * d / 4
    damp_settle = 2.0 * mass_per_length / (0.1 * t1)
    if loading == "pull":
        # settling: both ends at the pre-tension; then end 0 is clamped where it settled
        # and only the other end carries a dead load (lowered to t_low)
        settle_loads = [
            _RampedEndLoad(0, pre * dir0, 0.3 * t1),
            _RampedEndLoad(N - 1, pre * dir1, 0.3 * t1),
            rod.ViscousDamping(coefficient=damp_settle),
        ]
        loads = [
            _RampedEndLoad(N - 1, pre * dir1, 0.3 * t1),
            _RampedEndLoad(N - 1, (tl - pre) * dir1, t2 - t1, delay=t1),
            # drag of the whole rod moving at v: 1 % of T_low
            _ScheduledDamping(damp_settle, 0.01 * tl / (L * v), t2),
        ]
        # contact penalties sized for T_high up to about 2 T_low exp(mu 4 pi) (two loops)
        t_max = max(pre, 2.0 * tl * float(np.exp(mrc * 4 * np.pi)))
    else:
        loads = [
            _RampedEndLoad(0, pre * dir0, 0.3 * t1),
            _RampedEndLoad(N - 1, pre * dir1, 0.3 * t1),
            _RampedEndLoad(0, (th - pre) * dir0, t2 - t1, delay=t1),
            _RampedEndLoad(N - 1, (tl - pre) * dir1, t2 - t1, delay=t1),
            rod.ViscousDamping(coefficient=damp_settle),
        ]
        t_max = max(th, tl, pre)
    K = 200.0 * t_max / (R * d)
    post = Cylinder(point=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), radius=0.5 * D)
    post_contact = CylinderContact(
        (post,),
        stiffness=K,
        sharpness=400.0 / d,
        friction=AnchorFriction(mu_static=mrc, mu_kinetic=mk, tangential_stiffness=K),
        rod_radius=0.5 * d,
    )
    rr_contact = RodContact(
        stiffness=20.0 * t_max / d,
        sharpness=15.0 / (0.05 * d),
        friction=None
        if mrr <= 0
        else (AnchorFriction(mu_static=mrr) if friction == "anchor" else SmoothFriction(mrr)),
    )
    slip = d if slip_distance is None else float(check_positive("slip_distance", slip_distance))
    x_start = x0[0].copy()
    lim = 0.3 * L if loading == "free" else np.inf
    idx_e = np.arange(N - 1)
    far = np.abs(idx_e[:, None] - idx_e[None, :]) >= 3
    watch = {"rod": np.inf, "post": np.inf}

    def callback(state):
        x = system.positions(state.q)
        watch["rod"] = min(watch["rod"], float(_edge_distances(x)[far].min()))
        watch["post"] = min(watch["post"], float(np.min(np.hypot(x[:, 0], x[:, 1])) - R))
        return float((x[0] - x_start) @ dir0) > lim

    base = options if options is not None else rod.SolverOptions(throw=False, rtol=1e-6)
    step = float(check_positive("dt", dt))
    if loading != "pull":
        opts = type(base)(**{**base.__dict__, "save_every": t_end / (int(n_frames) - 1)})
        res = rod.simulate(
            system,
            t_end=t_end,
            dt=step,
            loads=loads,
            interactions=[post_contact, rr_contact],
            options=opts,
            progress=progress,
            callback=callback,
        )
        times = np.asarray(res.times)
        pos = np.asarray(res.positions)
        tension_last = np.asarray(res.tension[-1])
        status, message, stats, st = res.status, res.message, dict(res.stats), res.final_state
        pull_disp = pull_force = np.zeros(0)
    else:
        interactions = [post_contact, rr_contact]
        every = t_end / (int(n_frames) - 1)
        opts1 = type(base)(**{**base.__dict__, "save_every": min(every, t1 / 4)})
        res1 = rod.simulate(
            system,
            t_end=t1,
            dt=step,
            loads=settle_loads,
            interactions=interactions,
            options=opts1,
            progress=progress,
            callback=callback,
        )
        status, message, st = res1.status, res1.message, res1.final_state
        stats = dict(res1.stats)
        times, pos = np.asarray(res1.times), np.asarray(res1.positions)
        tension_last = np.asarray(res1.tension[-1])
        pull_disp = pull_force = np.zeros(0)
        if status == "success":
            h = L / (N - 1)
            pstep = min(0.25 * h, 0.1 * d) / v if pull_dt is None else pull_dt
            pstep = float(check_positive("pull_dt", pstep))
            check_pull_step(pstep, speed=v, edge_length=h, name="pull_dt")
            xs = system.positions(st.q)
            pull_dir = (xs[0] - xs[1]) / np.linalg.norm(xs[0] - xs[1])
            x_clamp = xs[0].copy()

            def path(t, xc=x_clamp, u=pull_dir, v=v, t2=t2):
                return xc + u * v * max(0.0, t - t2)

            opts2 = type(base)(**{**base.__dict__, "save_every": every})
            constraints = (MovingNodes(nodes=[0], path=path), Clamp(edges=[0]))
            pt, pf = [], []
            # lower the dead load (end 0 held), then pull, each with its own nominal step
            for t_stop, seg_dt in ((t2, min(5 * step, pstep)), (t_end, pstep)):
                res2 = rod.simulate(
                    system,
                    st,
                    t_end=t_stop,
                    dt=seg_dt,
                    loads=loads,
                    constraints=constraints,
                    interactions=interactions,
                    options=opts2,
                    progress=progress,
                    callback=callback,
                )
                status, message, st = res2.status, res2.message, res2.final_state
                for k, val in res2.stats.items():
                    stats[k] = stats.get(k, 0) + val
                times = np.concatenate([times, np.asarray(res2.times)[1:]])
                pos = np.concatenate([pos, np.asarray(res2.positions)[1:]])
                tension_last = np.asarray(res2.tension[-1])
                if t_stop > t2:
                    pt.append(np.asarray(res2.times))
                    # the clamp's reaction on node 0 along the pull: what the machine reads
                    pf.append(np.asarray(res2.reactions)[:, 0, :] @ pull_dir)
                if status != "success":
                    break
            if pt:
                pull_force = np.concatenate(pf)
                pull_disp = v * (np.concatenate(pt) - t2)
    disp = (pos[:, 0, :] - x0[0]) @ dir0
    last = pos[-1]
    rad = np.hypot(last[:, 0], last[:, 1])
    on_post = rad < R + 0.05 * d
    ed = _edge_distances(last)
    idx = np.arange(N - 1)
    ed[np.abs(idx[:, None] - idx[None, :]) < 3] = np.inf
    on_rod = ed.min(axis=1) < 1.05 * d
    q = st.q
    thetas = system.thetas(q)
    tang = st.tangents
    ref1 = st.d1
    ref2 = np.cross(tang, ref1)
    m1 = np.cos(thetas)[:, None] * ref1 + np.sin(thetas)[:, None] * ref2
    s_nodes, omega = darboux_profile(system.positions(q), m1)
    verdict = ""
    creep = float("nan")
    sel = times >= t2 + 0.5 * (t_end - t2)
    if np.any(sel) and loading != "pull":
        creep = float(disp[-1] - disp[sel][0])
    if loading == "free":
        stopped_early = times[-1] < t_end - 1e-9 and status == "success"
        verdict = "slip" if stopped_early or not (creep <= slip) else "hold"
    if loading == "pull":
        th = float(pull_force[-1]) if pull_force.size else float("nan")
    le = system.rest_length
    s_mid = np.cumsum(le) - 0.5 * le
    reason, more = measured_strain(np.concatenate([tension_last, pull_force]), ea,
                                   warned=bool(warnings))  # fmt: skip
    warnings += more
    status, message = fail(status, message, reason)
    return CloveHitchResult(
        loading=loading,
        t_high=th,
        t_low=tl,
        times=times,
        end_displacement=disp,
        s=s_mid,
        tension=tension_last,
        post_contact=on_post,
        rod_contact=on_rod,
        s_nodes=s_nodes,
        darboux=omega,
        wrap_radius=R,
        mu_eff=float(_mu_eff(mrc, D / d)),
        winding_start=winding_number(x0),
        winding_end=winding_number(last),
        code_start=post_crossing_code(x0),
        code_end=post_crossing_code(last),
        verdict=verdict,
        creep=creep,
        min_rod_distance=watch["rod"],
        min_post_gap=watch["post"],
        positions=pos,
        status=status,
        message=message,
        stats=stats,
        _rod_diameter=d,
        pull_speed=v if loading == "pull" else 0.0,
        pull_displacement=pull_disp,
        pull_force=pull_force,
        mu_kinetic=mk,
        warnings=warnings,
    )
