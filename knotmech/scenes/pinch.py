"""The pinch experiment in simulation: a rod pinched between two crossed cylinders, pulled out.

Clove-hitch paper, sect. 9 and Fig. 5: a rod (axis x) lies between two rigid cylinders
(axes y, diameter D); the lower one is fixed, the upper one presses with a dead normal load
F_n; one end of the rod is pulled at a constant speed and the sliding force F_t* is recorded.
Amontons-Coulomb on both contact surfaces gives F_t* = 2 mu F_n, observed for
x = 4 F_n/(pi E d D) below about 0.1.

The cross-section of a discrete elastic rod is rigid (the contact is a penalty on the
centreline distance), so the deviation the paper finds for larger x (cross-section
flattening) is outside this model: here F_t*/(2 mu F_n) = 1 for any x.

The upper cylinder under a dead load is realised by placing it, at the start of every step,
where the penalty forces on the rod's nodes add up to F_n (a quasi-static force control,
lagging one step).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.errors import InputError, check_count, check_nonnegative, check_positive, check_range
from knotmech.materials import VPS32_DENSITY, VPS32_YOUNGS_MODULUS
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.contact import Cylinder, CylinderContact
from knotmech.rod.friction import AnchorFriction
from knotmech.rod.loads import ViscousDamping
from knotmech.rod.solver import SolverOptions, simulate
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
from knotmech.scenes._scene import RunControl, Scene

__all__ = [
    "LoadedCylinderContact",
    "PinchResult",
    "PinchScene",
    "PinchRod",
    "PinchLoading",
    "PinchSweep",
    "pinch",
    "pinch_sweep",
]


#: F_t*/(2 mu F_n) further than this from 1 gets a warning (the rigid-section model gives 1
#: for any x; the README's 0.997-1.003 hold at the validation mesh)
_RATIO_WARN = 0.1
#: ... and outside this range the run failed: not an Amontons pull-out
_RATIO_RANGE = (0.5, 2.0)


def _ratio_check(ratio: float) -> tuple[str | None, list[str]]:
    """(reason to fail, warnings) of a measured F_t*/(2 mu F_n) (nan: no check)."""
    if not np.isfinite(ratio):
        return None, []
    lo, hi = _RATIO_RANGE
    if not lo <= ratio <= hi:
        return (
            f"F_t*/(2 mu F_n) = {ratio:.4g}, outside [{lo:g}, {hi:g}]: the model (rigid "
            "cross-section, Amontons on both contacts) gives 1, so the pull-out was not "
            "resolved (step, pull distance) or is not friction (inertia); no sliding force"
        ), []
    if abs(ratio - 1.0) > _RATIO_WARN:
        return None, [
            f"F_t*/(2 mu F_n) = {ratio:.4g} is more than {_RATIO_WARN:.0%} from the 1 the "
            "model gives: the sliding plateau was not reached or the mesh is too coarse "
            "(cogging of the contact over the nodes; refine n_elements)"
        ]
    return None, []


class LoadedCylinderContact(CylinderContact):
    """A :class:`~knotmech.rod.contact.CylinderContact` whose cylinder ``loaded`` moves along
    ``load_direction`` so that it presses on the rod with the total normal force ``load`` [N]
    (re-placed at the start of each step from the positions then; optional ramp in time)."""

    def __init__(self, cylinders, *, loaded, load, load_direction, ramp_time=0.0, **kw):
        super().__init__(cylinders, **kw)
        self.loaded = int(loaded)
        self.load = float(check_nonnegative("load", load, scalar=True))
        u = np.asarray(load_direction, dtype=float)
        self.load_direction = u / np.linalg.norm(u)
        self.ramp_time = float(check_nonnegative("ramp_time", ramp_time, scalar=True))
        self._origin = self._cp[self.loaded].copy()
        self.offset = 0.0
        self.t = 0.0

    def _total_force(self, pos, offset):
        c = self.loaded
        p = self._origin + offset * self.load_direction
        a = self._ca[c]
        rel = pos - p
        radial = rel - (rel @ a)[:, None] * a[None, :]
        rho = np.linalg.norm(radial, axis=1)
        xi = rel @ a
        gap = rho - self._cr[c] - self._topology[4]
        k = self.sharpness
        z = np.clip(-k * gap, -50, 50)
        sp = np.where(z > 30, z, np.log1p(np.exp(np.minimum(z, 30)))) / k
        sg = 0.5 * (1 + np.tanh(0.5 * z))
        n = 2.0 * self.stiffness * self._weight * sp * sg
        n[np.abs(xi) > self._ch[c]] = 0.0
        n[-k * gap < -40] = 0.0
        return float(np.sum(n))

    def begin_step(self, system, q_old, v_old, dt):
        super().begin_step(system, q_old, v_old, dt)
        target = self.load * (min(1.0, (self.t + dt) / self.ramp_time) if self.ramp_time else 1.0)
        pos = np.asarray(q_old, dtype=float)[system.node_dofs]
        # bisection on the offset (force grows with the offset along load_direction)
        lo, hi = self.offset - 10.0 / self.sharpness, self.offset + 10.0 / self.sharpness
        while self._total_force(pos, lo) > target:
            lo -= 10.0 / self.sharpness
        while self._total_force(pos, hi) < target:
            hi += 10.0 / self.sharpness
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if self._total_force(pos, mid) < target:
                lo = mid
            else:
                hi = mid
        self._step_offset = 0.5 * (lo + hi)
        self._cp[self.loaded] = self._origin + self._step_offset * self.load_direction

    def end_step(self, system, q_new, q_old, dt):
        super().end_step(system, q_new, q_old, dt)
        self.offset = self._step_offset
        self.t += dt


@dataclass
class PinchResult:
    """Recorded curves of one pinch pull-out.

    Attributes
    ----------
    normal_load : float [N]; mu : float; load_parameter : float  x = 4 F_n/(pi E d D)
    times, displacement : (n,) [s], [m]  pulled-end displacement
    pull_force : (n,) [N]  axial force at the pulled end (first edge)
    sliding_force : float [N]  F_t*, mean pull force over the last ``plateau`` of the pull
    ratio : float  F_t*/(2 mu F_n)
    status, message, stats  ("failed" also when the ratio is outside [0.5, 2], impossible
        for this model, or the strain exceeded 50 %)
    warnings : list of str  one line each (ratio more than 10 % from 1, strain, inertia)
    """

    normal_load: float
    mu: float
    load_parameter: float
    times: np.ndarray
    displacement: np.ndarray
    pull_force: np.ndarray
    sliding_force: float
    ratio: float
    status: str
    message: str
    stats: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)

    def summary(self) -> dict:
        keys = (
            "normal_load",
            "mu",
            "load_parameter",
            "sliding_force",
            "ratio",
            "status",
            "message",
        )
        out = {k: getattr(self, k) for k in keys}
        out["warnings"] = list(self.warnings)
        out["stats"] = dict(self.stats)
        return out


def pinch(
    *,
    normal_load,
    mu,
    rod_diameter=4e-3,
    cylinder_diameter=8e-3,
    youngs_modulus=VPS32_YOUNGS_MODULUS,
    density=VPS32_DENSITY,
    rod_length=0.09,
    mu_kinetic=None,
    pull_speed=0.01,
    pull_distance=None,
    n_elements=None,
    ramp_time=0.1,
    dt=None,
    plateau=0.5,
    options=None,
    progress=False,
    max_node_steps=None,
) -> PinchResult:
    """Pull a rod out from between two crossed cylinders pressed with ``normal_load``.

    Parameters
    ----------
    normal_load : float [N]  F_n on the upper cylinder (> 0)
    mu : float  static friction coefficient rod-cylinder (kinetic: ``mu_kinetic``, default mu)
    rod_diameter, cylinder_diameter : float [m]  d and D (defaults 4 mm and 8 mm, clove-hitch
        paper sect. 9)
    youngs_modulus : float [Pa]  (default 1.26 MPa, VPS32)
    density : float [kg/m^3]
    rod_length : float [m]  (default 9 cm)
    pull_speed : float [m/s]; pull_distance : float [m] (default: 1.5 x the stretch of the
        pulled part at 2 mu F_n, plus 2 d)
    n_elements : int  (default: edges of length d/8, 180 for the default rod). The cogging of
        the pull force as nodes pass the cylinders (period one edge) falls with the edge:
        at d/4 the frictionless pull force swings by +-0.04 N and F_t*/(2 mu F_n) reads
        1.014 / 1.047 at x = 0.019 / 0.044; at d/8 it reads 0.997-1.003 for
        x = 0.006-0.047 and the frictionless (mu = 0) mean force is below 0.05 % of
        2 mu F_n (mu = 0.32), see ``tests/scenes/test_pinch_mesh.py``
    ramp_time : float [s]  the normal load is ramped over this time before pulling
    dt : float [s]  (default: element length / (4 v))
    plateau : float  fraction of the pull (at its end) averaged for F_t*
    max_node_steps : float, optional  bound on (t_end/dt) x nodes, checked before anything
        is built (default :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it)

    Returns
    -------
    PinchResult
    """
    return PinchScene(
        rod=PinchRod(
            rod_diameter=rod_diameter,
            cylinder_diameter=cylinder_diameter,
            youngs_modulus=youngs_modulus,
            density=density,
            rod_length=rod_length,
            n_elements=n_elements,
        ),
        load=PinchLoading(
            normal_load=normal_load,
            mu=mu,
            mu_kinetic=mu_kinetic,
            pull_speed=pull_speed,
            pull_distance=pull_distance,
            ramp_time=ramp_time,
            plateau=plateau,
        ),
        control=RunControl(
            dt=dt, options=options, progress=progress, max_node_steps=max_node_steps
        ),
    ).run()


@dataclass(frozen=True)
class PinchRod:
    """The rod and the cylinders (SI units; :func:`pinch` documents them)."""

    rod_diameter: float = 4e-3
    cylinder_diameter: float = 8e-3
    youngs_modulus: float = VPS32_YOUNGS_MODULUS
    density: float = VPS32_DENSITY
    rod_length: float = 0.09
    n_elements: int | None = None


@dataclass(frozen=True)
class PinchLoading:
    """The normal load [N], friction and the pull [m/s], [m], [s]."""

    normal_load: float
    mu: float
    mu_kinetic: float | None = None
    pull_speed: float = 0.01
    pull_distance: float | None = None
    ramp_time: float = 0.1
    plateau: float = 0.5


class PinchScene(Scene):
    """A rod pulled out of a pinch: the phases of :func:`pinch` (one solver call: the load
    ramp and the pull's start delay are in the contact and the grip path)."""

    def __init__(self, *, rod, load, control):
        self.opts, self.load, self.control = rod, load, control

    def setup(self) -> None:
        """Inputs, pull distance, mesh and the cost, before anything is allocated."""
        o, ld = self.opts, self.load
        self.fn = fn = float(check_positive("normal_load", ld.normal_load, scalar=True))
        self.mu = mu = float(check_nonnegative("mu", ld.mu, scalar=True))
        self.d = d = float(check_positive("rod_diameter", o.rod_diameter, scalar=True))
        self.D = float(check_positive("cylinder_diameter", o.cylinder_diameter, scalar=True))
        self.E = float(check_positive("youngs_modulus", o.youngs_modulus, scalar=True))
        self.L = L = float(check_positive("rod_length", o.rod_length, scalar=True))
        self.v = float(check_positive("pull_speed", ld.pull_speed, scalar=True))
        self.ea = self.E * np.pi * d**2 / 4
        # free length between the pulled end and the pinch
        self.stretch = 2 * mu * fn * 0.3 * L / self.ea
        self.dist = self._pull_distance()
        n_el = o.n_elements
        self.n_el = int(round(L / (d / 8))) if n_el is None else check_count("n_elements", n_el)
        if self.n_el < 8:
            raise InputError(f"n_elements must be >= 8, got {o.n_elements}")
        check_range("plateau", ld.plateau, 0.0, 1.0, low_open=True, scalar=True)
        self.t_start = float(check_nonnegative("ramp_time", ld.ramp_time, scalar=True)) + 0.05
        self.t_final = self.t_start + self.dist / self.v
        dt = self.control.dt
        step = (
            (L / self.n_el) / (4.0 * self.v)
            if dt is None
            else float(check_positive("dt", dt, scalar=True))
        )
        check_run_size(
            n_nodes=self.n_el + 1,
            t_end=self.t_final,
            dt=step,
            max_node_steps=self.control.max_node_steps,
            hint="use a larger dt, fewer elements or a lower pull speed",
        )
        self.step = step

    def _pull_distance(self) -> float:
        """The pull's travel [m]; at most 0.4 L (the rod must stay in the pinch)."""
        ld, L = self.load, self.L
        if ld.pull_distance is not None:
            dist = float(check_positive("pull_distance", ld.pull_distance, scalar=True))
            if dist > 0.4 * L:
                raise InputError(
                    f"pull_distance must be <= 0.4 rod_length ({0.4 * L:g} m), got {dist}"
                )
            return dist
        dist = 1.5 * self.stretch + 2 * self.d
        if dist > 0.4 * L:
            raise InputError(
                f"normal_load = {self.fn:g} N stretches the pulled part by "
                f"{self.stretch:.3g} m at the sliding force 2 mu F_n, so the pull would need "
                f"{dist:.3g} m, more than 0.4 rod_length ({0.4 * L:g} m): lower normal_load "
                "or mu, or use a stiffer (youngs_modulus) or longer (rod_length) rod"
            )
        return dist

    def build(self):
        """The rod through the pinch, the two cylinders (the upper one loaded), the grip."""
        o, ld, d, L = self.opts, self.load, self.d, self.L
        radius, e_rod, rho_rod = equivalent_section(
            diameter=d, youngs_modulus=self.E, density=o.density
        )
        # the pinch sits at x = 0, a quarter of the length from the pulled end (x = -L/4 ... )
        x = np.linspace(-0.3 * L, 0.7 * L, self.n_el + 1)
        x += 0.5 * (x[1] - x[0]) * 0.37  # contact not exactly on a node
        pts = np.stack([x, np.zeros_like(x), np.zeros_like(x)], 1)
        self.system = RodSystem(
            (
                Rod(
                    positions=pts,
                    radius=radius,
                    youngs_modulus=e_rod,
                    density=rho_rod,
                    natural="straight",
                ),
            )
        )
        self.h = h = float(np.mean(self.system.rest_length))
        zc = 0.5 * (self.D + d)
        K = 50.0 * self.fn / (d * h)
        lower = Cylinder(point=(0.0, 0.0, -zc), axis=(0.0, 1.0, 0.0), radius=0.5 * self.D)
        upper = Cylinder(point=(0.0, 0.0, zc), axis=(0.0, 1.0, 0.0), radius=0.5 * self.D)
        self.contact = LoadedCylinderContact(
            (lower, upper),
            loaded=1,
            load=self.fn,
            load_direction=(0.0, 0.0, -1.0),
            ramp_time=ld.ramp_time,
            stiffness=K,
            sharpness=400.0 / d,
            friction=AnchorFriction(
                mu_static=self.mu, mu_kinetic=ld.mu_kinetic, tangential_stiffness=K
            ),
        )
        self.x0 = pts[0].copy()
        self.mpl = rho_rod * np.pi * radius**2
        return self.system

    def _checks(self) -> None:
        """Strain, pull step and quasi-static loading, with the element length known."""
        ld = self.load
        if self.control.dt is None:
            self.step = self.h / (4.0 * self.v)
        mu_top = self.mu if ld.mu_kinetic is None else max(self.mu, float(ld.mu_kinetic))
        self.warnings = check_strain(
            2 * mu_top * self.fn, self.ea, what="the sliding force 2 mu F_n"
        )
        check_pull_step(self.step, speed=self.v, edge_length=self.h)
        self.warnings += check_quasi_static(
            length=self.L,
            ea=self.ea,
            mass_per_length=self.mpl,
            times={"ramp_time": ld.ramp_time, "pull": self.dist / self.v},
            speed=self.v,
        )

    def run_phases(self, system) -> None:
        """One solver call: the load ramp, then the pull."""
        self._checks()
        x0, v, t_start = self.x0, self.v, self.t_start

        def path(t):
            return x0 + _PULL_DIR * v * max(0.0, t - t_start)

        damping = 1e-3 * 2 * self.mu * self.fn / (self.L * v)
        step, t_final = self.step, self.t_final
        self.res = simulate(
            system,
            t_end=t_final,
            dt=step,
            loads=(ViscousDamping(coefficient=max(damping, 0.0 * self.mpl)),),
            constraints=(MovingNodes(nodes=[0], path=path), Clamp(edges=[0])),
            interactions=(self.contact,),
            options=self.control.options
            or SolverOptions(throw=False, save_every=max(step, t_final / 400)),
            progress=self.control.progress,
        )

    def measure(self, system) -> PinchResult:
        """F_t* over the plateau, checked (strain, Amontons ratio)."""
        res, mu, fn = self.res, self.mu, self.fn
        disp = (res.positions[:, 0, :] - self.x0) @ _PULL_DIR
        force = res.tension[:, 0]
        sel = disp >= max((1.0 - self.load.plateau) * self.dist, 1.2 * self.stretch)
        ft = float(np.mean(force[sel])) if (np.any(sel) and res.status == "success") else np.nan
        ratio = ft / (2 * mu * fn) if mu > 0 else np.nan
        reason, more = measured_strain(res.tension, self.ea, warned=bool(self.warnings))
        self.warnings += more
        if reason is None:
            reason, more = _ratio_check(ratio)
            self.warnings += more
        if reason is not None:
            ft = ratio = float("nan")
        status, message = fail(res.status, res.message, reason)
        return PinchResult(
            normal_load=fn,
            mu=mu,
            load_parameter=4 * fn / (np.pi * self.E * self.d * self.D),
            times=res.times,
            displacement=disp,
            pull_force=force,
            sliding_force=ft,
            ratio=ratio,
            status=status,
            message=message,
            stats=dict(res.stats),
            warnings=self.warnings,
        )


_PULL_DIR = np.array([-1.0, 0.0, 0.0])


@dataclass
class PinchSweep:
    """F_t* versus F_n: arrays over the normal loads of :func:`pinch_sweep`."""

    normal_load: np.ndarray
    sliding_force: np.ndarray
    ratio: np.ndarray
    load_parameter: np.ndarray
    runs: list


def pinch_sweep(*, normal_loads, **kwargs) -> PinchSweep:
    """Run :func:`pinch` for each normal load [N]; other arguments are passed on."""
    loads = np.atleast_1d(check_positive("normal_loads", normal_loads)).astype(float)
    runs = [pinch(normal_load=float(f), **kwargs) for f in loads]
    return PinchSweep(
        normal_load=loads,
        sliding_force=np.array([r.sliding_force for r in runs]),
        ratio=np.array([r.ratio for r in runs]),
        load_parameter=np.array([r.load_parameter for r in runs]),
        runs=runs,
    )
