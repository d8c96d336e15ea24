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
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.loads import NodeForce, ViscousDamping
from knotmech.rod.solver import SolverOptions
from knotmech.rod.system import Rod, RodSystem
from knotmech.scenes._common import (
    check_pull_step,
    check_quasi_static,
    check_run_size,
    check_strain,
    equivalent_section,
    fail,
    measured_strain,
)
from knotmech.scenes._scene import SceneRun, post_contact

__all__ = ["CapstanResult", "capstan", "capstan_two_loops"]


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
        keys = ("mode", "wrap_angle", "mu", "rod_diameter", "post_diameter", "t_low", "ratio",
                "creep", "contact_angle", "mu_eff", "exp_mu_theta", "exp_mu_eff_theta",
                "bending_group", "ratio_bending", "status", "message")  # fmt: skip
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
    t_high : float [N]  hold mode: dead load on the high end (ramped up with T_low)
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
    """
    theta = float(check_positive("wrap_angle", wrap_angle))
    mu = float(check_nonnegative("mu", mu))
    d = float(check_positive("rod_diameter", rod_diameter))
    D = float(check_positive("post_diameter", post_diameter))
    E = float(check_positive("youngs_modulus", youngs_modulus))
    t_low = float(check_positive("t_low", t_low))
    if mode not in ("pull", "hold"):
        raise InputError(f"mode must be 'pull' or 'hold', got {mode!r}")
    if mode == "hold":
        if t_high is None:
            raise InputError("t_high is required in hold mode")
        t_high = float(check_positive("t_high", t_high))
    plateau = float(check_positive("plateau", plateau))
    me = float(_mu_eff(mu, D / d))
    exp_mu = float(np.exp(mu * theta))
    exp_mue = float(np.exp(me * theta))
    t_max = t_low * exp_mu if mode == "pull" else max(t_high, t_low)

    radius, e_rod, rho_rod = equivalent_section(
        diameter=d, youngs_modulus=E, density=density, bending_stiffness=bending_stiffness
    )
    ea = E * np.pi * d**2 / 4
    if mode == "pull":
        # the sliding tension: a static peak above it is transient, and the strain it reaches
        # is checked after the run (measured_strain)
        mu_k = mu if mu_kinetic is None else min(float(mu_kinetic), mu)
        t_check, what = (
            t_low * float(np.exp(mu_k * theta)),
            ("the expected sliding T_high = T_low exp(mu_k theta)"),
        )
    else:
        t_check, what = t_max, "the largest load"
    warnings = check_strain(t_check, ea, what=what)
    R = 0.5 * (D + d)
    rise = 0.0 if theta <= np.pi + 1e-9 else max(1.5 * d * theta / (2 * np.pi), 1.5 * d)
    lead = 2.0 * R if lead_length is None else float(check_positive("lead_length", lead_length))
    arc = float(np.hypot(theta * R, rise))
    v = 0.02 if pull_speed is None else float(check_positive("pull_speed", pull_speed))
    if pull_distance is None:
        stretch = t_max * (arc + 2 * lead) / ea
        pull_distance = 3.0 * stretch + 0.3 * R
    pull_distance = float(check_positive("pull_distance", pull_distance))
    lead_low = lead + (pull_distance if mode == "pull" else 0.0)
    if n_elements is None:
        h = 1.0 / (24.0 / R)
    else:
        n_el = int(n_elements)
        if n_el < 8:
            raise InputError(f"n_elements must be >= 8, got {n_elements}")
        h = (arc + lead + lead_low) / n_el
    # the work, estimated before anything is allocated (a huge load or a tiny dt otherwise
    # asks for petabytes or days)
    dt_est = None if dt is None else float(check_positive("dt", dt))
    ramp_est = 0.1 if ramp_time is None else float(check_nonnegative("ramp_time", ramp_time))
    if mode == "pull":
        t_est, dt_est = ramp_est + 0.05 + pull_distance / v, dt_est or h / (4.0 * v)
    else:
        t_est = ramp_est + (2.0 if hold_time is None else float(hold_time))
        dt_est = dt_est or 5e-3
    # a pull faster than the rod's axial wave is refused as such, before the work estimate
    check_quasi_static(length=arc + lead + lead_low, ea=ea,
                       mass_per_length=rho_rod * np.pi * radius**2, times={},
                       speed=v if mode == "pull" else None)  # fmt: skip
    check_run_size(n_nodes=(arc + lead + lead_low) / h + 1, t_end=t_est, dt=dt_est,
                   max_node_steps=max_node_steps,
                   hint="use a larger dt, fewer elements, a lower pull speed or a load "
                   "the rod can carry (T/EA well below 1)")  # fmt: skip
    pts, t_end_dir = _centreline(theta, R, rise, lead, lead_low, h)
    rod = Rod(
        positions=pts,
        radius=radius,
        youngs_modulus=e_rod,
        density=rho_rod,
        natural="straight",
    )
    system = RodSystem((rod,))
    h_mean = float(np.mean(system.rest_length))
    K = 200.0 * t_max / (R * d) if contact_stiffness is None else float(contact_stiffness)
    contact = post_contact(post_diameter=D, rod_diameter=d, force_scale=t_max, mu_static=mu,
                           mu_kinetic=mu_kinetic, stiffness=K,
                           surface_friction=surface_friction)  # fmt: skip
    ramp = 0.1 if ramp_time is None else float(check_nonnegative("ramp_time", ramp_time))
    low_load = NodeForce(nodes=-1, force=t_low * t_end_dir, ramp_time=ramp)
    pull_dir = np.array([0.0, -1.0, 0.0])
    x0 = pts[0].copy()
    mass_per_length = rho_rod * np.pi * radius**2
    total_len = float(np.sum(system.rest_length))
    if mode == "pull":
        t_start = ramp + 0.05
        t_final = t_start + pull_distance / v

        def path(t, x0=x0, v=v, t_start=t_start):
            return x0 + pull_dir * v * max(0.0, t - t_start)

        constraints = (MovingNodes(nodes=[0], path=path), Clamp(edges=[0]))
        loads = [low_load]
        damping = 1e-3 * t_low / (total_len * v)
        step = h_mean / (4.0 * v) if dt is None else float(check_positive("dt", dt))
    else:
        hold = 2.0 if hold_time is None else float(check_positive("hold_time", hold_time))
        t_final = ramp + hold
        high_load = NodeForce(nodes=0, force=t_high * pull_dir, ramp_time=ramp)
        constraints = (Clamp(edges=[0]),)
        loads = [low_load, high_load]
        # critical-ish damping of the slowest axial mode (time scale ~ the ramp)
        damping = 2.0 * mass_per_length / max(ramp, 1e-3)
        step = 5e-3 if dt is None else float(check_positive("dt", dt))
    loads.append(ViscousDamping(coefficient=damping))
    if mode == "pull":
        check_pull_step(step, speed=v, edge_length=h_mean)
    warnings += check_quasi_static(
        length=total_len,
        ea=ea,
        mass_per_length=mass_per_length,
        times={"ramp_time": ramp, "pull": pull_distance / v} if mode == "pull" else
              {"ramp_time": ramp, "hold_time": t_final - ramp},
        speed=v if mode == "pull" else None,
    )  # fmt: skip
    opts = options or SolverOptions(throw=False, save_every=max(step, (t_final) / 400.0))
    stop = None
    if mode == "hold":
        # stop once the rod has clearly slipped off (0.5 lead lengths): the run has decided
        def stop(x, x0=x0, lim=0.5 * lead):
            return float((x[0] - x0) @ pull_dir) > lim

    # one phase (the ramps and the pull's start delay are in the loads and the grip path)
    run = SceneRun(system, interactions=(contact,), options=opts, progress=progress)
    run.phase(mode, t_final, dt=step, loads=tuple(loads), constraints=constraints,
              save_every=step if opts.save_every is None else opts.save_every,
              stop=stop)  # fmt: skip
    times, pos = run.frames()
    tension = run.tension_frames()
    disp = (pos[:, 0, :] - x0) @ pull_dir
    t_hi = tension[:, 0]
    ratio = float("nan")
    creep = float("nan")
    if mode == "pull":
        sel = disp >= (1.0 - plateau) * pull_distance
        if np.any(sel) and run.status == "success":
            ratio = float(np.mean(t_hi[sel]) / t_low)
    else:
        sel = times >= ramp + 0.5 * (t_final - ramp)
        if np.any(sel):
            creep = float(abs(disp[-1] - disp[sel][0]))
    # final contact region and tension profile
    last = pos[-1]
    rad = np.hypot(last[:, 0], last[:, 1])
    in_contact = rad < R + 0.02 * d
    ang = np.unwrap(np.arctan2(last[in_contact, 1], last[in_contact, 0]))
    contact_angle = float(ang.max() - ang.min()) if ang.size > 1 else 0.0
    s_mid = np.cumsum(system.rest_length) - 0.5 * system.rest_length
    # the result checked against what a capstan is: a failure reason or warnings
    reason, more = measured_strain(tension, ea, warned=bool(warnings))
    warnings += more
    if reason is None and mode == "pull" and contact_angle < 0.5 * theta:
        # the solver converged, but the rod is no longer wrapped: no capstan ratio to report
        reason = (
            f"the rod left the post: its contact spans {contact_angle:.2f} rad of the "
            f"{theta:.2f} rad wrap at the end (an unstable set-up, e.g. a thick rod wrapped "
            "more than once round a thin post); no sliding ratio"
        )
    if reason is None and mode == "pull":
        reason = _ratio_reason(ratio, exp_mu)
    if reason is not None:
        ratio = float("nan")
    status, message = fail(run.status, _plain(run.phases[-1].message), reason)
    mu_slide = (mu if mu_kinetic is None else float(mu_kinetic)) if mode == "pull" else mu
    mu_slide = float(_mu_eff(mu_slide, D / d)) if surface_friction else mu_slide
    ei = float(rod.bending_stiffness)
    eps2, ratio_b, why = _bending_check(
        mu=mu_slide, theta=theta, bending_stiffness=ei, t_low=t_low, radius=R
    )
    note = _bending_note(eps2=eps2, ratio_bending=ratio_b, why=why,
                         closed_form=float(np.exp(mu_slide * theta)),
                         contact_angle=contact_angle, theta=theta, measured=ratio,
                         mu_name="mu_eff" if surface_friction else "mu")  # fmt: skip
    if note is not None:
        warnings.append(note)
    return CapstanResult(
        mode=mode,
        wrap_angle=theta,
        mu=mu,
        rod_diameter=d,
        post_diameter=D,
        times=times,
        displacement=disp,
        t_high=t_hi,
        t_low=t_low,
        ratio=ratio,
        creep=creep,
        s=s_mid,
        tension=tension[-1],
        contact=in_contact,
        contact_angle=contact_angle,
        mu_eff=me,
        exp_mu_theta=exp_mu,
        exp_mu_eff_theta=exp_mue,
        status=status,
        message=message,
        stats=dict(run.stats),
        positions=pos,
        bending_group=float(eps2),
        ratio_bending=float(ratio_b),
        warnings=warnings,
    )


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
        youngs_modulus=1.26e6,
        density=1160.0,
        t_low=0.069,
    )
    kw.update(overrides)
    return capstan(**kw)
