"""The capstan experiment in simulation: a rod wrapped around a fixed post.

One end carries a dead load T_low, the other is pulled at a constant speed (``mode="pull"``:
T_high(displacement) rises to the sliding plateau T_low exp(mu_eff theta)) or loaded by a
dead load T_high (``mode="hold"``: below the limit the rod must not creep; above it slides).

The post is a rigid cylinder (:class:`knotmech.rod.contact.CylinderContact`) with
elasto-plastic friction acting on the rod's surface, so that a rod of finite thickness
shows the effective coefficient of the clove-hitch paper (eq. 3 and refs. therein),

.. math:: \\mu_\\mathrm{eff} = \\frac{-(1+\\tilde D) + \\sqrt{(1+\\tilde D)^2 +
          4\\mu^2\\tilde D}}{2\\mu},\\qquad \\tilde D = D/d .

Validity: the capstan law (with mu_eff) needs the bending boundary layers at the lift-off
points to be short, eps^2 = EI/(T_low R^2) << 1 (R the centreline radius); the correction is
about -(1+mu^2)/2 eps^2 (see :func:`knotmech.analytic.capstan.capstan_ratio_bending`). A
rope-like rod (``bending_stiffness`` below the solid value) meets it at small strains.

mu_eff is the decay rate away from the ends of the contact (the clove-hitch paper, text of
eq. 3). In the wrap the friction couple (d/2) f is carried by a shear force Q = (d/2) f,
which builds up where the rod comes onto the post (it meets the post at an angle) and
vanishes where it leaves (a layer of length R/|l2|, l2 the second root of
mu a l^2 + l - mu (1-a) = 0, a = d/(D+d)); these end layers multiply the sliding ratio by a
theta-independent factor above 1 that is negligible for thin rods and grows with d/(D+d)
and mu (mu = 0.5: -0.1, +0.5, +1.5, +3.1, +5.5 % at D/d = 10, 4, 2, 1, 0.5, measured with
EI/(T_low R^2) = 0.01; see ``tests/scenes/test_capstan.py``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.analytic.capstan import capstan_ratio_bending
from knotmech.analytic.capstan import mu_eff as _mu_eff
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.materials import VPS32_DENSITY, VPS32_YOUNGS_MODULUS
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.loads import NodeForce, ViscousDamping
from knotmech.rod.solver import SolverOptions
from knotmech.rod.system import Rod, RodSystem
from knotmech.scenes._common import (
    check_numbers,
    check_post_size,
    check_pull_step,
    check_quasi_static,
    check_run_size,
    check_strain,
    equivalent_section,
    fail,
    measured_strain,
)
from knotmech.scenes._scene import RunControl, Scene, SceneRun, post_contact

__all__ = [
    "CapstanResult",
    "CapstanScene",
    "CapstanRod",
    "CapstanLoading",
    "capstan",
    "capstan_two_loops",
]


@dataclass
class CapstanResult:
    """Recorded curves of a capstan run.

    Attributes
    ----------
    mode : "pull" or "hold"
    times : (n,) [s]
    displacement : (n,) [m]  displacement of the high-tension end along its pull direction
    t_high : (n,) [N]  axial force at the high-tension end (first edge)
    t_low : float [N]  the dead load
    ratio : float  sliding ratio mean(T_high)/T_low over the last ``plateau`` part of the
        pull (nan in hold mode)
    creep : float [m]  hold mode: displacement change over the last half of the hold
        (nan in pull mode)
    s : (n_edges,) [m]  arc length of the edge midpoints from the high end (rest lengths)
    tension : (n_edges,) [N]  tension profile T(s) at the end of the run
    contact : (n_nodes,) bool  nodes pressed on the post at the end
    contact_angle : float [rad]  angle swept by the contact nodes around the post
    exp_mu_theta, exp_mu_eff_theta : float  the ideal and thick-rod capstan ratios
    mu_eff : float
    status, message : str  from the solver; "failed" also when the result contradicts a
        capstan (a pull ratio below 1 or above 1.1 exp(mu theta), the rod off the post, a
        strain above 50 %), with the reason
    stats : dict  from the solver
    positions : (n_frames, n_nodes, 3) [m]  trajectory (saved frames)
    bending_group : float  EI/(T_low R^2), the capstan law's small parameter
    ratio_bending : float  :func:`knotmech.analytic.capstan_ratio_bending` with mu_eff (the
        kinetic coefficient in pull mode) for these end loads; nan outside its validity
    warnings : list of str  one line each: where the run leaves the range of the closed form
        or of the rod model (bending lift-off, strain above 10 %, inertia)
    """

    mode: str
    wrap_angle: float
    mu: float
    rod_diameter: float
    post_diameter: float
    times: np.ndarray
    displacement: np.ndarray
    t_high: np.ndarray
    t_low: float
    ratio: float
    creep: float
    s: np.ndarray
    tension: np.ndarray
    contact: np.ndarray
    contact_angle: float
    mu_eff: float
    exp_mu_theta: float
    exp_mu_eff_theta: float
    status: str
    message: str
    stats: dict
    positions: np.ndarray = field(repr=False, default=None)
    bending_group: float = float("nan")
    ratio_bending: float = float("nan")
    warnings: list = field(default_factory=list)

    def summary(self) -> dict:
        """Scalars as a JSON-ready dict."""
        keys = (
            "mode",
            "wrap_angle",
            "mu",
            "rod_diameter",
            "post_diameter",
            "t_low",
            "ratio",
            "creep",
            "contact_angle",
            "mu_eff",
            "exp_mu_theta",
            "exp_mu_eff_theta",
            "bending_group",
            "ratio_bending",
            "status",
            "message",
        )
        out = {k: getattr(self, k) for k in keys}
        out["warnings"] = list(self.warnings)
        out["stats"] = dict(self.stats)
        return {k: (float(v) if isinstance(v, (np.floating, float)) else v) for k, v in out.items()}


#: a pull ratio above this factor times exp(mu theta) is not friction (end layers of a thick
#: rod add at most +5.5 % to exp(mu_eff theta) < exp(mu theta), see the module docstring)
_FRICTION_BOUND = 1.1
#: a pull ratio below this is not a capstan pull (friction only resists the pull; 2 % slack
#: for the drag and the plateau average)
_RATIO_FLOOR = 0.98
#: the bending note appears when capstan_ratio_bending differs from exp(mu_eff theta) by more
_BENDING_NOTE = 0.02


def _ratio_reason(ratio: float, exp_mu_theta: float) -> str | None:
    """Why a pull's sliding ratio cannot be a capstan ratio, or None: below
    :data:`_RATIO_FLOOR` (friction only resists a pull) or above :data:`_FRICTION_BOUND`
    exp(mu theta) (more than friction can carry)."""
    if not np.isfinite(ratio):
        return None
    if ratio < _RATIO_FLOOR:
        return (
            f"T_high/T_low = {ratio:.4g} < 1: impossible for a pull (friction only resists "
            "it); the run did not resolve the sliding (step, loads); no ratio"
        )
    if ratio > _FRICTION_BOUND * exp_mu_theta:
        return (
            f"T_high/T_low = {ratio:.4g} exceeds friction's bound exp(mu theta) = "
            f"{exp_mu_theta:.4g}: the pull force is not friction (bending the rod round the "
            "post, or inertia, carries it); no capstan ratio"
        )
    return None


def _bending_check(*, mu, theta, bending_stiffness, t_low, radius):
    """(EI/(T_low R^2), capstan_ratio_bending or nan, reason it does not apply or None) for
    a rod sliding with coefficient ``mu`` (mu_eff for a thick rod); T_high is the ratio
    itself times T_low (a fixed point: the ratio depends on T_high only through the
    high-end lift-off)."""
    eps2 = bending_stiffness / (t_low * radius**2)
    ratio = float(np.exp(mu * theta))
    try:
        for _ in range(30):
            new = float(
                capstan_ratio_bending(
                    mu,
                    theta,
                    bending_stiffness=bending_stiffness,
                    low_tension=t_low,
                    high_tension=ratio * t_low,
                    radius=radius,
                )
            )
            if abs(new - ratio) <= 1e-12 * ratio:
                break
            ratio = new
    except InputError as exc:
        return eps2, float("nan"), str(exc)
    return eps2, ratio, None


def _bending_note(
    *, eps2, ratio_bending, why, closed_form, contact_angle, theta, measured, mu_name="mu_eff"
):
    """One line when the capstan law's assumption EI/(T_low R^2) << 1 fails, else None."""
    if why is None and abs(ratio_bending / closed_form - 1.0) <= _BENDING_NOTE:
        return None
    head = (
        f"bending: EI/(T_low R^2) = {eps2:.3g} is not << 1, so the rod lifts off the post "
        f"(contact {contact_angle:.2f} of {theta:.2f} rad) and exp({mu_name} theta) = "
        f"{closed_form:.4g} does not apply"
    )
    got = f" (measured {measured:.4g})" if np.isfinite(measured) else ""
    if why is not None:
        return f"{head}; knotmech.analytic.capstan_ratio_bending does not either: {why}"
    return (
        f"{head}; the model that applies is knotmech.analytic.capstan_ratio_bending "
        f"(with {mu_name}) = {ratio_bending:.4g}{got}"
    )


def _centreline(wrap_angle, radius, rise, lead_high, lead_low, h):
    """Polyline: straight high lead (along +y at x = R), helical arc, straight low lead."""
    arc_len = float(np.hypot(wrap_angle * radius, rise))
    n1 = max(2, int(round(lead_high / h)))
    n2 = max(4, int(round(arc_len / h)))
    n3 = max(2, int(round(lead_low / h)))
    y1 = np.linspace(-lead_high, 0.0, n1 + 1)[:-1]
    p1 = np.stack([np.full_like(y1, radius), y1, np.zeros_like(y1)], 1)
    phi = np.linspace(0.0, wrap_angle, n2 + 1)
    p2 = np.stack([radius * np.cos(phi), radius * np.sin(phi), rise * phi / wrap_angle], 1)
    t_end = np.array([-np.sin(wrap_angle), np.cos(wrap_angle), 0.0])
    s3 = np.linspace(0.0, lead_low, n3 + 1)[1:]
    p3 = p2[-1][None, :] + s3[:, None] * t_end[None, :]
    return np.concatenate([p1, p2, p3]), t_end


@dataclass(frozen=True)
class CapstanRod:
    """The wrap, the rod and the post (SI units; :func:`capstan` documents them)."""

    wrap_angle: float
    mu: float
    rod_diameter: float
    post_diameter: float
    youngs_modulus: float
    mu_kinetic: float | None = None
    density: float = 1000.0
    bending_stiffness: float | None = None
    n_elements: int | None = None
    lead_length: float | None = None
    surface_friction: bool = True
    contact_stiffness: float | None = None


@dataclass(frozen=True)
class CapstanLoading:
    """Pull or hold, the loads [N] and their schedule [s], [m/s], [m]."""

    t_low: float
    mode: str = "pull"
    t_high: float | None = None
    pull_speed: float | None = None
    pull_distance: float | None = None
    hold_time: float | None = None
    ramp_time: float | None = None
    plateau: float = 0.3


def capstan(
    *,
    wrap_angle,
    mu,
    rod_diameter,
    post_diameter,
    youngs_modulus,
    t_low,
    mode="pull",
    t_high=None,
    mu_kinetic=None,
    density=1000.0,
    bending_stiffness=None,
    pull_speed=None,
    pull_distance=None,
    hold_time=None,
    ramp_time=None,
    n_elements=None,
    lead_length=None,
    surface_friction=True,
    contact_stiffness=None,
    dt=None,
    plateau=0.3,
    options=None,
    progress=False,
    max_node_steps=None,
) -> CapstanResult:
    """Simulate a rod wrapped ``wrap_angle`` around a fixed post.

    Parameters
    ----------
    wrap_angle : float [rad]  contact angle theta (> 0; above pi the wrap is a helix with
        1.5 d between turns and the leads at different heights)
    mu : float  static friction coefficient rod-post (mu_s)
    rod_diameter, post_diameter : float [m]  d and D
    youngs_modulus : float [Pa]  E (EA = E pi d^2/4)
    t_low : float [N]  dead load on the low-tension end
    mode : {"pull", "hold"}
    t_high : float [N]  hold mode: dead load on the high end (ramped up with T_low; at
        least ``t_low``, else the ends swap roles and T_high/T_low is undefined)
    mu_kinetic : float or None  kinetic coefficient (default mu)
    density : float [kg/m^3]
    bending_stiffness : float or None [N m^2]  EI (default the solid pi E d^4/64; a lower
        value models a rope; see :func:`knotmech.scenes._common.equivalent_section`)
    pull_speed : float [m/s]  default 0.02 m/s
    pull_distance : float [m]  default: enough to stretch the wrapped part and slide
    hold_time : float [s]  hold mode: time under constant loads (default 2 s)
    ramp_time : float [s]  loads ramped over this time (default 0.1 s)
    n_elements : int  default: about 24 elements per radian of wrap plus the leads
    lead_length : float [m]  straight length on each side (default 2 R)
    surface_friction : bool  friction on the rod surface (mu_eff) or at the centreline (mu)
    contact_stiffness : float [N/m^2]  penalty K (default 200 T_high_max / (R d))
    dt : float [s]  nominal step (default: pull -> element length/(4 v); hold -> 5 ms)
    plateau : float  fraction of the pull (at the end) averaged for the ratio
    options : SolverOptions or None
    progress : bool
    max_node_steps : float, optional  bound on (t_end/dt) x nodes, checked before the rod is
        built (default :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it)

    Returns
    -------
    CapstanResult
        ``status`` "success" only when the quantity asked for is a number: the sliding
        ratio (pull) or the creep (hold).
    """
    return CapstanScene(
        rod=CapstanRod(
            wrap_angle=wrap_angle,
            mu=mu,
            rod_diameter=rod_diameter,
            post_diameter=post_diameter,
            youngs_modulus=youngs_modulus,
            mu_kinetic=mu_kinetic,
            density=density,
            bending_stiffness=bending_stiffness,
            n_elements=n_elements,
            lead_length=lead_length,
            surface_friction=surface_friction,
            contact_stiffness=contact_stiffness,
        ),
        load=CapstanLoading(
            t_low=t_low,
            mode=mode,
            t_high=t_high,
            pull_speed=pull_speed,
            pull_distance=pull_distance,
            hold_time=hold_time,
            ramp_time=ramp_time,
            plateau=plateau,
        ),
        control=RunControl(
            dt=dt, options=options, progress=progress, max_node_steps=max_node_steps
        ),
    ).run()


_PULL_DIR = np.array([0.0, -1.0, 0.0])


class CapstanScene(Scene):
    """A rod wrapped round a post, pulled or held: the phases of :func:`capstan`."""

    def __init__(self, *, rod, load, control):
        self.opts, self.load, self.control = rod, load, control

    # -- setup -----------------------------------------------------------------------
    def setup(self) -> None:
        """Inputs, the closed forms, the strain, the geometry and the cost, up front."""
        self._check_inputs()
        o, d = self.opts, self.d
        self.me = float(_mu_eff(self.mu, self.D / d))
        self.exp_mu = float(np.exp(self.mu * self.theta))
        self.exp_mue = float(np.exp(self.me * self.theta))
        self.radius, self.e_rod, self.rho_rod = equivalent_section(
            diameter=d,
            youngs_modulus=self.E,
            density=o.density,
            bending_stiffness=o.bending_stiffness,
        )
        self.ea = self.E * np.pi * d**2 / 4
        self.warnings = self._strain_warnings()
        self._geometry()
        self._check_cost()

    def _check_inputs(self) -> None:
        o, ld = self.opts, self.load
        self.theta = float(check_positive("wrap_angle", o.wrap_angle, scalar=True))
        self.mu = float(check_nonnegative("mu", o.mu, scalar=True))
        self.d = float(check_positive("rod_diameter", o.rod_diameter, scalar=True))
        self.D = float(check_positive("post_diameter", o.post_diameter, scalar=True))
        check_post_size(self.D, self.d, "capstan")
        self.E = float(check_positive("youngs_modulus", o.youngs_modulus, scalar=True))
        self.t_low = float(check_positive("t_low", ld.t_low, scalar=True))
        if ld.mode not in ("pull", "hold"):
            raise InputError(f"mode must be 'pull' or 'hold', got {ld.mode!r}")
        self.hold = ld.mode == "hold"
        self.t_high = ld.t_high
        if self.hold:
            if ld.t_high is None:
                raise InputError("t_high is required in hold mode")
            self.t_high = float(check_positive("t_high", ld.t_high, scalar=True))
            if self.t_high < self.t_low:
                raise InputError(
                    f"t_high ({self.t_high:g} N) must be >= t_low ({self.t_low:g} N) in hold "
                    "mode: the high end carries the larger load (swap them to load the other "
                    "end)"
                )
        self.plateau = float(check_positive("plateau", ld.plateau, scalar=True))

    def _strain_warnings(self) -> list[str]:
        """Up-front strain check: the sliding tension (pull; a static peak above it is
        transient and checked after the run) or the largest load (hold)."""
        if self.hold:
            self.t_max = max(self.t_high, self.t_low)
            return check_strain(self.t_max, self.ea, what="the largest load")
        self.t_max = self.t_low * self.exp_mu
        mk = self.opts.mu_kinetic
        mu_k = self.mu if mk is None else min(float(mk), self.mu)
        return check_strain(
            self.t_low * float(np.exp(mu_k * self.theta)),
            self.ea,
            what="the expected sliding T_high = T_low exp(mu_k theta)",
        )

    def _geometry(self) -> None:
        """Centreline radius, helix rise, leads, pull distance and element length [m]."""
        o, ld, d, theta = self.opts, self.load, self.d, self.theta
        self.R = R = 0.5 * (self.D + d)
        self.rise = 0.0 if theta <= np.pi + 1e-9 else max(1.5 * d * theta / (2 * np.pi), 1.5 * d)
        self.lead = (
            2.0 * R
            if o.lead_length is None
            else float(check_positive("lead_length", o.lead_length, scalar=True))
        )
        self.arc = float(np.hypot(theta * R, self.rise))
        self.v = (
            0.02
            if ld.pull_speed is None
            else float(check_positive("pull_speed", ld.pull_speed, scalar=True))
        )
        dist = ld.pull_distance
        if dist is None:
            stretch = self.t_max * (self.arc + 2 * self.lead) / self.ea
            dist = 3.0 * stretch + 0.3 * R
        self.pull_distance = float(check_positive("pull_distance", dist, scalar=True))
        self.lead_low = self.lead + (self.pull_distance if not self.hold else 0.0)
        if o.n_elements is None:
            self.h = 1.0 / (24.0 / R)
        else:
            n_el = int(o.n_elements)
            if n_el < 8:
                raise InputError(f"n_elements must be >= 8, got {o.n_elements}")
            self.h = (self.arc + self.lead + self.lead_low) / n_el

    def _check_cost(self) -> None:
        """The work, estimated before anything is allocated (a huge load or a tiny dt
        otherwise asks for petabytes or days); a pull faster than the rod's axial wave is
        refused as such first."""
        ld, c = self.load, self.control
        dt_est = None if c.dt is None else float(check_positive("dt", c.dt, scalar=True))
        ramp_est = (
            0.1
            if ld.ramp_time is None
            else float(check_nonnegative("ramp_time", ld.ramp_time, scalar=True))
        )
        if not self.hold:
            t_est = ramp_est + 0.05 + self.pull_distance / self.v
            dt_est = dt_est or self.h / (4.0 * self.v)
        else:
            t_est = ramp_est + (2.0 if ld.hold_time is None else float(ld.hold_time))
            dt_est = dt_est or 5e-3
        length = self.arc + self.lead + self.lead_low
        check_quasi_static(
            length=length,
            ea=self.ea,
            mass_per_length=self.rho_rod * np.pi * self.radius**2,
            times={},
            speed=self.v if not self.hold else None,
        )
        check_run_size(
            n_nodes=length / self.h + 1,
            t_end=t_est,
            dt=dt_est,
            max_node_steps=c.max_node_steps,
            hint="use a larger dt, fewer elements, a lower pull speed or a load "
            "the rod can carry (T/EA well below 1)",
        )

    # -- build -----------------------------------------------------------------------
    def build(self) -> SceneRun:
        """The rod on its wrap, the post, the loads and grips; a :class:`SceneRun`."""
        o, ld, d = self.opts, self.load, self.d
        pts, t_end_dir = _centreline(
            self.theta, self.R, self.rise, self.lead, self.lead_low, self.h
        )
        self.rod = Rod(
            positions=pts,
            radius=self.radius,
            youngs_modulus=self.e_rod,
            density=self.rho_rod,
            natural="straight",
        )
        self.system = RodSystem((self.rod,))
        K = (
            200.0 * self.t_max / (self.R * d)
            if o.contact_stiffness is None
            else float(o.contact_stiffness)
        )
        contact = post_contact(
            post_diameter=self.D,
            rod_diameter=d,
            force_scale=self.t_max,
            mu_static=self.mu,
            mu_kinetic=o.mu_kinetic,
            stiffness=K,
            surface_friction=o.surface_friction,
        )
        self.ramp = (
            0.1
            if ld.ramp_time is None
            else float(check_nonnegative("ramp_time", ld.ramp_time, scalar=True))
        )
        low_load = NodeForce(nodes=-1, force=self.t_low * t_end_dir, ramp_time=self.ramp)
        self.x0 = pts[0].copy()
        self.mass_per_length = self.rho_rod * np.pi * self.radius**2
        self.total_len = float(np.sum(self.system.rest_length))
        if self.hold:
            loads = self._hold_loads(low_load)
        else:
            loads = self._pull_loads(low_load)
        self.loads = (*loads, ViscousDamping(coefficient=self.damping))
        self._quasi_static()
        c = self.control
        self.solver_opts = c.options or SolverOptions(
            throw=False, save_every=max(self.step, (self.t_final) / 400.0)
        )
        # one phase (the ramps and the pull's start delay are in the loads and the grip path)
        return SceneRun(
            self.system, interactions=(contact,), options=self.solver_opts, progress=c.progress
        )

    def _pull_loads(self, low_load) -> list:
        """End 0 gripped and pulled after the ramp (and 50 ms), a light drag."""
        v, x0 = self.v, self.x0
        t_start = self.ramp + 0.05
        self.t_final = t_start + self.pull_distance / v

        def path(t, x0=x0, v=v, t_start=t_start):
            return x0 + _PULL_DIR * v * max(0.0, t - t_start)

        self.constraints = (MovingNodes(nodes=[0], path=path), Clamp(edges=[0]))
        self.damping = 1e-3 * self.t_low / (self.total_len * v)
        h_mean = float(np.mean(self.system.rest_length))
        dt = self.control.dt
        self.step = (
            h_mean / (4.0 * v) if dt is None else float(check_positive("dt", dt, scalar=True))
        )
        check_pull_step(self.step, speed=v, edge_length=h_mean)
        return [low_load]

    def _hold_loads(self, low_load) -> list:
        """End 0's edge clamped in direction, a dead load T_high on it; critical-ish
        damping of the slowest axial mode (time scale ~ the ramp)."""
        ld = self.load
        hold = (
            2.0
            if ld.hold_time is None
            else float(check_positive("hold_time", ld.hold_time, scalar=True))
        )
        self.t_final = self.ramp + hold
        high_load = NodeForce(nodes=0, force=self.t_high * _PULL_DIR, ramp_time=self.ramp)
        self.constraints = (Clamp(edges=[0]),)
        self.damping = 2.0 * self.mass_per_length / max(self.ramp, 1e-3)
        dt = self.control.dt
        self.step = 5e-3 if dt is None else float(check_positive("dt", dt, scalar=True))
        return [low_load, high_load]

    def _quasi_static(self) -> None:
        if self.hold:
            times = {"ramp_time": self.ramp, "hold_time": self.t_final - self.ramp}
        else:
            times = {"ramp_time": self.ramp, "pull": self.pull_distance / self.v}
        self.warnings += check_quasi_static(
            length=self.total_len,
            ea=self.ea,
            mass_per_length=self.mass_per_length,
            times=times,
            speed=self.v if not self.hold else None,
        )

    def _slid_off(self, x) -> bool:
        """Hold mode: the rod has clearly slipped off (0.5 lead lengths)."""
        return float((x[0] - self.x0) @ _PULL_DIR) > 0.5 * self.lead

    # -- phases ----------------------------------------------------------------------
    def run_phases(self, run: SceneRun) -> None:
        """One phase, ``"pull"`` or ``"hold"``."""
        opts = self.solver_opts
        run.phase(
            self.load.mode,
            self.t_final,
            dt=self.step,
            loads=self.loads,
            constraints=self.constraints,
            save_every=self.step if opts.save_every is None else opts.save_every,
            stop=self._slid_off if self.hold else None,
        )

    # -- measure ---------------------------------------------------------------------
    def measure(self, run: SceneRun) -> CapstanResult:
        """Ratio or creep, contact, tension; checked against what a capstan is."""
        times, pos = run.frames()
        tension = run.tension_frames()
        disp = (pos[:, 0, :] - self.x0) @ _PULL_DIR
        t_hi = tension[:, 0]
        ratio, creep = self._ratio_creep(run, times, disp, t_hi)
        in_contact, contact_angle = self._contact(pos[-1])
        reason = self._reason(tension, contact_angle, ratio)
        if reason is not None:
            ratio = float("nan")
        status, message = fail(run.status, _plain(run.phases[-1].message), reason)
        status, message = fail(status, message, self._nan_reason(ratio, creep, times))
        eps2, ratio_b = self._bending(contact_angle, ratio)
        s_mid = np.cumsum(self.system.rest_length) - 0.5 * self.system.rest_length
        return CapstanResult(
            mode=self.load.mode,
            wrap_angle=self.theta,
            mu=self.mu,
            rod_diameter=self.d,
            post_diameter=self.D,
            times=times,
            displacement=disp,
            t_high=t_hi,
            t_low=self.t_low,
            ratio=ratio,
            creep=creep,
            s=s_mid,
            tension=tension[-1],
            contact=in_contact,
            contact_angle=contact_angle,
            mu_eff=self.me,
            exp_mu_theta=self.exp_mu,
            exp_mu_eff_theta=self.exp_mue,
            status=status,
            message=message,
            stats=dict(run.stats),
            positions=pos,
            bending_group=float(eps2),
            ratio_bending=float(ratio_b),
            warnings=self.warnings,
        )

    def _ratio_creep(self, run, times, disp, t_hi) -> tuple[float, float]:
        """Pull: mean T_high/T_low over the plateau; hold: creep over the hold's last half."""
        ratio = creep = float("nan")
        if not self.hold:
            sel = disp >= (1.0 - self.plateau) * self.pull_distance
            if np.any(sel) and run.status == "success":
                ratio = float(np.mean(t_hi[sel]) / self.t_low)
        else:
            sel = times >= self.ramp + 0.5 * (self.t_final - self.ramp)
            if np.any(sel):
                creep = float(abs(disp[-1] - disp[sel][0]))
        return ratio, creep

    def _contact(self, last):
        """Nodes on the post at the end and the angle they sweep [rad]."""
        in_contact = np.hypot(last[:, 0], last[:, 1]) < self.R + 0.02 * self.d
        ang = np.unwrap(np.arctan2(last[in_contact, 1], last[in_contact, 0]))
        return in_contact, float(ang.max() - ang.min()) if ang.size > 1 else 0.0

    def _reason(self, tension, contact_angle, ratio) -> str | None:
        """Why the result is not a capstan's (strain, the rod off the post, the ratio);
        adds the strain warnings."""
        reason, more = measured_strain(tension, self.ea, warned=bool(self.warnings))
        self.warnings += more
        theta = self.theta
        if reason is None and not self.hold and contact_angle < 0.5 * theta:
            # the solver converged, but the rod is no longer wrapped: no capstan ratio
            reason = (
                f"the rod left the post: its contact spans {contact_angle:.2f} rad of the "
                f"{theta:.2f} rad wrap at the end (an unstable set-up, e.g. a thick rod "
                "wrapped more than once round a thin post); no sliding ratio"
            )
        if reason is None and not self.hold:
            reason = _ratio_reason(ratio, self.exp_mu)
        return reason

    def _nan_reason(self, ratio, creep, times) -> str | None:
        """``success`` only with a number for what was asked: the ratio or the creep."""
        if self.hold and not np.isfinite(creep):
            if times[-1] < self.t_final - 1e-9:
                return (
                    "the high end slid more than half a lead off before the hold's second "
                    "half: the rod slips; no creep"
                )
            return check_numbers(creep=creep)
        return None if self.hold else check_numbers(ratio=ratio)

    def _bending(self, contact_angle, ratio):
        """(EI/(T_low R^2), capstan_ratio_bending); the bending note added when due."""
        o, theta = self.opts, self.theta
        mu_slide = self.mu
        if not self.hold:
            mu_slide = self.mu if o.mu_kinetic is None else float(o.mu_kinetic)
        mu_slide = float(_mu_eff(mu_slide, self.D / self.d)) if o.surface_friction else mu_slide
        eps2, ratio_b, why = _bending_check(
            mu=mu_slide,
            theta=theta,
            bending_stiffness=float(self.rod.bending_stiffness),
            t_low=self.t_low,
            radius=self.R,
        )
        note = _bending_note(
            eps2=eps2,
            ratio_bending=ratio_b,
            why=why,
            closed_form=float(np.exp(mu_slide * theta)),
            contact_angle=contact_angle,
            theta=theta,
            measured=ratio,
            mu_name="mu_eff" if o.surface_friction else "mu",
        )
        if note is not None:
            self.warnings.append(note)
        return eps2, ratio_b


def _plain(message: str) -> str:
    """The solver's message without the phase name (the capstan has one phase)."""
    for name in ("pull: ", "hold: "):
        if message.startswith(name):
            return message[len(name) :]
    return message


def capstan_two_loops(**overrides) -> CapstanResult:
    """The two-loops configuration of the clove-hitch paper (sect. 3, Fig. 1d): theta = 4 pi,
    d = 4 mm, D = 30 mm, E = 1.26 MPa (VPS32), mu = 0.32, T_low = 0.069 N, pulled.

    Any argument of :func:`capstan` can be overridden.
    """
    kw = dict(
        wrap_angle=4 * np.pi,
        mu=0.32,
        rod_diameter=4e-3,
        post_diameter=30e-3,
        youngs_modulus=VPS32_YOUNGS_MODULUS,
        density=VPS32_DENSITY,
        t_low=0.069,
    )
    kw.update(overrides)
    return capstan(**kw)
