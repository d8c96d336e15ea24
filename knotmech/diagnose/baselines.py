r"""Closed-form models of the three experiments, with their effect augmentations.

A :class:`Model` is one experiment's baseline plus a tuple of effects from the
catalogue (:mod:`knotmech.diagnose.effects`). Each effect adds named parameters
(or, for ``finite_thickness``, changes the meaning of ``mu``); the mean functions
below implement every augmentation of an experiment, so effects compose freely.

Baselines (``shared/spec/recordings.md`` section 2):

.. math::
    \text{capstan\_pull:}\quad T_\mathrm{high} = \min\bigl(T_\mathrm{low} + k\max(u-\delta_0, 0),
        \; T_\mathrm{low} e^{\mu\theta}\bigr)

    \text{pinch:}\quad F_t = 2\mu F_n

    \text{tension\_profile:}\quad T(s) = T_\mathrm{high}\, e^{-\mu s/R},\quad R = (D+d)/2

Augmentations (symbols as in :mod:`knotmech.diagnose.effects`):

- ``static_friction`` (capstan_pull): the rod sticks until the stick line reaches
  :math:`T_\mathrm{low}e^{\mu_s\theta}`, then the tension relaxes to the kinetic
  plateau as :math:`T_k + (T_s - T_k) e^{-(u-u_p)/\ell}`.
- ``finite_thickness``: :math:`\mu \to \mu_\mathrm{eff}(\mu, D/d)` (clove-hitch
  paper, eq. 3), ``mu`` is the material coefficient carrying the ``mu_nominal`` prior.
- ``displacement_offset`` (capstan_pull): the slack :math:`\delta_0 \ge 0` is replaced
  by a signed shift, :math:`u - \delta_0 \to u + u_\mathrm{off}`; a pre-stretch
  (:math:`u_\mathrm{off} > 0`, tension above T_low at zero displacement) is what the
  baseline cannot fit.
- ``rate_dependent_friction``: :math:`\mu \to \mu + \beta \ln(v/v_\mathrm{ref})`,
  :math:`v_\mathrm{ref}` the geometric mean speed.
- ``adhesion`` (pinch): :math:`F_t \to F_t + F_a`.
- ``contact_flattening`` (pinch): beyond :math:`F_c = x_c\,\pi E d D/4` the slope is
  multiplied by ``slope_ratio`` :math:`r \in [0, 1]`:
  :math:`F_t = 2\mu(F_n - (1-r)\max(F_n - F_c, 0))`.
- ``self_contact_nip`` (tension_profile): :math:`T \to T\prod_j (1 - f_j H(s - s_j))`.

The DER baseline plugs in through :func:`get_baseline`: a baseline is any object
with ``name`` and ``check(recording)``; ``closed-form`` is the default, ``der``
(``capstan_pull`` only) replaces the closed-form curve by the force-displacement
curve of :func:`knotmech.scenes.capstan.capstan` with kinetic friction only
(:class:`DERCurves`, :class:`DERModel`): free parameters ``mu`` (interpolated
between simulations on a small grid), a signed displacement shift ``delta0_m`` and a
displacement scale ``u_scale`` (compliance ratio; neither needs a new simulation);
``static_friction`` re-runs the scene with ``mu_s = mu + dmu_static > mu_k``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.analytic.capstan import mu_eff
from knotmech.analytic.pinch import pinch_load_parameter
from knotmech.diagnose.recording import Recording
from knotmech.errors import InputError, SolverError

__all__ = [
    "Model",
    "build_model",
    "get_baseline",
    "BASELINES",
    "pinch_load_parameter",
    "DERCurves",
    "DERModel",
    "build_der_model",
]


@dataclass
class Model:
    """A baseline plus effects, with free and fixed parameters.

    Attributes
    ----------
    rec : Recording
    effects : tuple of str
        Effects in the order they were added (``self_contact_nip`` may repeat).
    names : list of str
        Free parameter names (the order of parameter vectors).
    lower, upper : arrays
        Bounds of the free parameters.
    fixed : dict
        Parameters held fixed (nip positions, ``delta0_m`` under displacement_offset).
    """

    rec: Recording
    effects: tuple
    names: list
    lower: np.ndarray
    upper: np.ndarray
    fixed: dict = field(default_factory=dict)

    def params(self, p: np.ndarray) -> dict:
        d = dict(self.fixed)
        d.update(zip(self.names, (float(v) for v in p), strict=True))
        return d

    def mean(self, p: np.ndarray) -> np.ndarray:
        return MEANS[self.rec.experiment](self.rec, self.params(p), self.effects)

    @property
    def n_free(self) -> int:
        return len(self.names)


def _ln_speed(rec: Recording) -> np.ndarray:
    v = rec.speed
    return np.log(v) - np.mean(np.log(v))


def reference_speed(rec: Recording) -> float:
    """Geometric-mean sliding speed [m/s] (the speed at which ``mu`` is reported)."""
    return float(np.exp(np.mean(np.log(rec.speed))))


def _mu_rows(rec, p, effects):
    mu = p["mu"]
    if "rate_dependent_friction" in effects:
        return np.maximum(mu + p["dmu_dlnv"] * _ln_speed(rec), 0.0)
    return mu


def _apparent(rec, mu, effects):
    if "finite_thickness" in effects:
        d = rec.meta("rod_diameter_m")
        D = rec.meta("post_diameter_m")
        return mu_eff(np.maximum(mu, 0.0), D / d)
    return mu


def _capstan_mean(rec, p, effects):
    u = rec.x
    t_low = rec.meta("T_low_N")
    theta = rec.meta("wrap_angle_rad")
    mu = _mu_rows(rec, p, effects)
    plateau = t_low * np.exp(_apparent(rec, mu, effects) * theta)
    if "displacement_offset" in effects:
        xs = u + p["offset_m"]
    else:
        xs = u - p["delta0_m"]
    k = p["k_N_per_m"]
    stick = t_low + k * np.maximum(xs, 0.0)
    if "static_friction" not in effects:
        return np.minimum(stick, plateau)
    peak = t_low * np.exp(_apparent(rec, mu + p["dmu_static"], effects) * theta)
    u_peak = (peak - t_low) / k
    ell = p["decay_length_m"]
    after = plateau + (peak - plateau) * np.exp(-np.maximum(xs - u_peak, 0.0) / ell)
    return np.where(xs < u_peak, stick, after)


def _pinch_mean(rec, p, effects):
    fn = rec.x
    mu = _mu_rows(rec, p, effects)
    load = fn
    if "contact_flattening" in effects:
        fc = p["onset_load_parameter"] * (
            np.pi
            * rec.meta("youngs_modulus_Pa")
            * rec.meta("rod_diameter_m")
            * rec.meta("pinch_diameter_m")
            / 4.0
        )
        load = fn - (1.0 - p["slope_ratio"]) * np.maximum(fn - fc, 0.0)
    out = 2.0 * mu * load
    if "adhesion" in effects:
        out = out + p["adhesion_force_N"]
    return out


def _tension_mean(rec, p, effects):
    s = rec.x
    r = 0.5 * (rec.meta("post_diameter_m") + rec.meta("rod_diameter_m"))
    mu = _apparent(rec, p["mu"], effects)
    out = rec.meta("T_high_N") * np.exp(-mu * s / r)
    j = 0
    while f"nip_position_{j}" in p:
        out = out * np.where(s > p[f"nip_position_{j}"], 1.0 - p[f"nip_drop_{j}"], 1.0)
        j += 1
    return out


MEANS = {
    "capstan_pull": _capstan_mean,
    "pinch": _pinch_mean,
    "tension_profile": _tension_mean,
}


def build_model(rec: Recording, effects: tuple = (), fixed: dict | None = None) -> Model:
    """Model of ``rec``'s experiment with ``effects`` (free parameters and bounds)."""
    span = float(np.ptp(rec.x)) or 1.0
    ymax = float(np.max(np.abs(rec.y))) or 1.0
    names, lo, hi = ["mu"], [0.0], [5.0]
    fixed = dict(fixed or {})
    exp = rec.experiment
    if exp == "capstan_pull":
        names += ["k_N_per_m"]
        lo += [1e-12]
        hi += [np.inf]
        if "displacement_offset" in effects:
            # signed, so that the model nests the baseline (offset_m = -delta0_m <= 0)
            names += ["offset_m"]
            lo += [-(float(np.max(rec.x)) if np.max(rec.x) > 0 else span)]
            hi += [span]
        else:
            names += ["delta0_m"]
            lo += [0.0]
            hi += [float(np.max(rec.x)) if np.max(rec.x) > 0 else span]
        if "static_friction" in effects:
            dx = np.diff(np.unique(rec.x))
            names += ["dmu_static", "decay_length_m"]
            lo += [0.0, 0.5 * float(np.median(dx)) if dx.size else 1e-4 * span]
            hi += [3.0, span]
    if exp == "pinch":
        if "adhesion" in effects:
            names += ["adhesion_force_N"]
            lo += [0.0]
            hi += [ymax]
        if "contact_flattening" in effects:
            xl = pinch_load_parameter(
                rec.x,
                youngs_modulus=rec.meta("youngs_modulus_Pa"),
                rod_diameter=rec.meta("rod_diameter_m"),
                pinch_diameter=rec.meta("pinch_diameter_m"),
            )
            names += ["onset_load_parameter", "slope_ratio"]
            lo += [float(np.min(xl)), 0.0]
            hi += [float(np.max(xl)), 1.0]
    if "rate_dependent_friction" in effects:
        names += ["dmu_dlnv"]
        lo += [-2.0]
        hi += [2.0]
    if exp == "tension_profile":
        j = 0
        while f"nip_position_{j}" in fixed:
            names += [f"nip_drop_{j}"]
            lo += [0.0]
            hi += [0.95]
            j += 1
    return Model(rec, tuple(effects), names, np.array(lo, float), np.array(hi, float), fixed)


# --- baselines: closed-form (default) and DER (plugs in when the scene exists) -------


@dataclass(frozen=True)
class ClosedFormBaseline:
    """The closed-form baselines of the spec, for every experiment."""

    name: str = "closed-form"

    def check(self, rec: Recording) -> None:
        return None


#: defaults of the DER capstan behind ``--baseline der`` (see :class:`DERCurves`)
DER_ELEMENTS = 40
DER_STEPS = 60
DER_SPEED = 0.01
DER_EI_FACTOR = 1e-4
DER_DENSITY = 1000.0
#: largest wrap the DER baseline runs [rad]: two loops, the largest the project's DER
#: capstan is run and checked at (``capstan_two_loops``); beyond it the DER_ELEMENTS
#: elements span ever more of the post each
DER_MAX_WRAP = 4.0 * np.pi
#: most implicit steps one DER baseline simulation may take
DER_MAX_STEPS = 1000


class DERCurves:
    r"""Force-displacement curves of the DER capstan for one recording, cached by (mu_s, mu_k).

    Each curve is one run of :func:`knotmech.scenes.capstan.capstan` with the
    recording's geometry and loads (``wrap_angle_rad``, ``T_low_N``, ``rod_diameter_m``,
    ``post_diameter_m``, ``youngs_modulus_Pa``), kept from the start of the pull:
    :math:`T_\mathrm{high}(u)` for :math:`u \ge 0`.

    Settings (chosen for speed; the curve is quasi-static):

    - rope-like bending stiffness :math:`EI = 10^{-4}\,EA\,R^2` (``R = (D+d)/2``) unless
      ``bending_stiffness`` is given (as in ``benchmarks/capstan_vs_pyelastica.py``);
      a solid rod at a small ``T_low`` needs tiny steps;
    - ``n_elements`` = 40 elements over the wrap, the leads and the pulled length;
    - pull speed from the recording's ``speed`` (median) or 0.01 m/s; the step is
      :math:`dt = u_\mathrm{max} / (60\,v)` (60 implicit steps over the pull, every step saved);
    - pull distance 1.05 :math:`u_\mathrm{max}`, loads ramped over 0.1 s, density 1000 kg/m^3.

    Curves of other ``mu`` are interpolated linearly in ``mu`` on :math:`\ln T` between
    runs on a grid (the sliding plateau :math:`T_\mathrm{low} e^{\mu_\mathrm{eff}\theta}`
    is then exact where :math:`\mu_\mathrm{eff}` is linear in ``mu``).
    """

    def __init__(self, rec, *, n_elements=None, bending_stiffness=None, pull_speed=None):
        self.theta = rec.meta("wrap_angle_rad")
        self.t_low = rec.meta("T_low_N")
        self.d = rec.meta("rod_diameter_m")
        self.D = rec.meta("post_diameter_m")
        self.E = rec.meta("youngs_modulus_Pa")
        ea = self.E * np.pi * self.d**2 / 4.0
        r = 0.5 * (self.D + self.d)
        self.ei = DER_EI_FACTOR * ea * r**2 if bending_stiffness is None else bending_stiffness
        self.n_elements = DER_ELEMENTS if n_elements is None else int(n_elements)
        if pull_speed is None:
            pull_speed = float(np.median(rec.speed)) if rec.speed is not None else DER_SPEED
        self.v = float(pull_speed)
        self.u_max = max(float(np.max(rec.x)), 1e-6)
        self.dt = self.u_max / (DER_STEPS * self.v)
        self._cache = {}
        self.seconds = 0.0

    def settings(self) -> dict:
        return {
            "n_elements": self.n_elements,
            "bending_stiffness_N_m2": float(f"{self.ei:.6g}"),
            "pull_speed_m_per_s": self.v,
            "dt_s": float(f"{self.dt:.6g}"),
            "pull_distance_m": float(f"{1.05 * self.u_max:.6g}"),
            "simulations": len(self._cache),
            "simulation_seconds": float(f"{self.seconds:.3g}"),
        }

    def curve(self, mu_s: float, mu_k: float):
        """(u, T_high) of one run [m, N], from the start of the pull."""
        key = (round(float(mu_s), 10), round(float(mu_k), 10))
        if key in self._cache:
            return self._cache[key]
        import time

        from knotmech.rod.solver import SolverOptions
        from knotmech.scenes.capstan import capstan

        t0 = time.perf_counter()
        res = capstan(
            wrap_angle=self.theta,
            mu=key[0],
            mu_kinetic=key[1],
            rod_diameter=self.d,
            post_diameter=self.D,
            youngs_modulus=self.E,
            t_low=self.t_low,
            density=DER_DENSITY,
            bending_stiffness=self.ei,
            n_elements=self.n_elements,
            pull_speed=self.v,
            pull_distance=1.05 * self.u_max,
            ramp_time=0.1,
            dt=self.dt,
            options=SolverOptions(throw=False, save_every=self.dt),
        )
        self.seconds += time.perf_counter() - t0
        if res.status != "success":
            raise SolverError(
                f"DER capstan baseline failed at mu_s = {key[0]:.4g}, mu_k = {key[1]:.4g}: "
                f"{res.message}"
            )
        u = np.asarray(res.displacement, float)
        t = np.asarray(res.t_high, float)
        i0 = int(np.nonzero(u <= 1e-12 * self.u_max)[0][-1])
        u, t = u[i0:], t[i0:]
        u, idx = np.unique(u, return_index=True)
        out = (u, np.maximum(t[idx], 1e-12 * self.t_low))
        self._cache[key] = out
        return out

    def at(self, x: np.ndarray, mu_s: float, mu_k: float) -> np.ndarray:
        """T_high at displacements ``x`` [m] of one run (flat beyond both ends)."""
        u, t = self.curve(mu_s, mu_k)
        return np.interp(x, u, t)

    def kinetic_grid(self, mu_guess: float, n: int = 9) -> np.ndarray:
        """Grid of ``mu`` for the kinetic-only baseline, around ``mu_guess``."""
        lo = max(0.4 * mu_guess, 0.01)
        hi = max(1.8 * mu_guess, lo + 0.2)
        return np.linspace(lo, hi, n)


def _interp_log(grid, values, at, curves_fn, x):
    """Linear interpolation of ln T between the two grid curves bracketing ``at``."""
    j = int(np.clip(np.searchsorted(grid, at) - 1, 0, grid.size - 2))
    w = (at - grid[j]) / (grid[j + 1] - grid[j])
    a = np.log(curves_fn(values[j], x))
    b = np.log(curves_fn(values[j + 1], x))
    return np.exp((1.0 - w) * a + w * b)


@dataclass
class DERModel(Model):
    """A capstan_pull model whose mean is the DER curve (see :class:`DERCurves`).

    Free parameters: ``mu`` (kinetic), ``delta0_m`` (signed shift of the curve) and
    ``u_scale`` (the recording's compliance over the simulated one: the free leads, the
    load cell and the machine are not simulated); the model is
    :math:`T((u - \\delta_0)/s)`. With ``static_friction`` also
    ``dmu_static`` (:math:`\\mu_s = \\mu + \\Delta\\mu_s`). The static curves are run
    at the baseline's fitted ``mu_k0`` on a grid of ``dmu_static`` and corrected to
    the current ``mu`` to first order:
    :math:`T(\\mu, \\Delta\\mu_s) = K(\\mu) + S(\\mu_{k0}, \\Delta\\mu_s) - S(\\mu_{k0}, 0)`
    (``K`` interpolated on the ``mu`` grid, ``S`` on the ``dmu_static`` grid; at
    ``dmu_static = 0`` the model is the baseline exactly, so the two nest).
    """

    curves: DERCurves = None
    mu_grid: np.ndarray = None
    dmu_grid: np.ndarray = None
    mu_k0: float = None

    def kinetic(self, x, mu):
        return _interp_log(self.mu_grid, self.mu_grid, mu, lambda m, z: self.curves.at(z, m, m), x)

    def mean(self, p: np.ndarray) -> np.ndarray:
        q = self.params(p)
        x = (self.rec.x - q["delta0_m"]) / q["u_scale"]
        out = self.kinetic(x, q["mu"])
        if "static_friction" in self.effects:
            mk = self.mu_k0
            stat = _interp_log(
                self.dmu_grid,
                self.dmu_grid,
                min(q["dmu_static"], self.dmu_grid[-1]),
                lambda dm, z: self.curves.at(z, mk + dm, mk),
                x,
            )
            # the run's own dmu = 0 curve is subtracted, so dmu_static = 0 is the baseline
            out = out + stat - self.curves.at(x, mk, mk)
        return out


#: grid of dmu_static = mu_s - mu_k run by the DER static_friction effect
DER_DMU_GRID = np.array([0.0, 0.04, 0.08, 0.12, 0.18, 0.25, 0.35, 0.5])


def build_der_model(
    rec: Recording, curves: DERCurves, mu_grid, effects: tuple = (), mu_k0=None
) -> DERModel:
    """DER model of a capstan_pull recording (``effects`` empty or ``static_friction``)."""
    names, lo, hi = (
        ["mu", "delta0_m", "u_scale"],
        [mu_grid[0], -0.3 * curves.u_max, 0.1],
        [mu_grid[-1], 0.5 * curves.u_max, 10.0],
    )
    if "static_friction" in effects:
        names.append("dmu_static")
        lo.append(0.0)
        hi.append(float(DER_DMU_GRID[-1]))
    return DERModel(
        rec,
        tuple(effects),
        names,
        np.array(lo, float),
        np.array(hi, float),
        {},
        curves=curves,
        mu_grid=np.asarray(mu_grid, float),
        dmu_grid=DER_DMU_GRID,
        mu_k0=mu_k0,
    )


@dataclass(frozen=True)
class DERBaseline:
    """DER-simulated capstan baseline (kinetic friction only), ``capstan_pull`` only.

    The clove-hitch paper's FEM used kinetic friction only, so its two-loops curve had
    no peak; ``static_friction`` re-runs the scene with ``mu_s > mu_k``.
    """

    name: str = "der"

    def check(self, rec: Recording) -> None:
        """Refuse, before any simulation, a recording this baseline cannot run on.

        Besides the kind: the wrap beyond :data:`DER_MAX_WRAP` (two loops), displacements
        below the range of the model's shift (``-0.3`` of the largest), and a pull so
        short that one run would need more than :data:`DER_MAX_STEPS` implicit steps
        (the 0.1 s load ramp at the step ``u_max / (60 v)``).
        """
        if rec.experiment != "capstan_pull":
            raise InputError(
                f"baseline 'der' is not available for {rec.experiment} recordings "
                "(capstan_pull only); use closed-form"
            )
        theta = rec.meta("wrap_angle_rad")
        if theta > DER_MAX_WRAP:
            raise InputError(
                f"{rec.source}: baseline 'der' runs wraps up to {DER_MAX_WRAP:.4g} rad (two "
                f"loops, the largest its {DER_ELEMENTS}-element capstan is checked at), got "
                f"wrap_angle_rad = {theta:g}; use closed-form"
            )
        u_max = float(np.max(rec.x))
        if u_max <= 0 or float(np.min(rec.x)) < -0.3 * u_max:
            raise InputError(
                f"{rec.source}: baseline 'der' needs displacements from about 0 up (the "
                f"simulated pull starts at 0; shifts down to -0.3 x the largest), got "
                f"[{float(np.min(rec.x)):g}, {u_max:g}] m; re-zero them or use closed-form"
            )
        curves = DERCurves(rec)
        steps = (0.15 + 1.05 * curves.u_max / curves.v) / curves.dt
        if steps > DER_MAX_STEPS:
            raise InputError(
                f"{rec.source}: baseline 'der' would need {steps:.3g} steps per simulation "
                f"(limit {DER_MAX_STEPS}): the pull ({u_max:g} m at {curves.v:g} m/s) is too "
                "short for the 0.1 s load ramp; use closed-form"
            )


BASELINES = {"closed-form": ClosedFormBaseline(), "der": DERBaseline()}


def get_baseline(name: str):
    """Baseline by name: ``closed-form`` or ``der``.

    Raises
    ------
    InputError
        Unknown name.
    """
    if name not in BASELINES:
        raise InputError(f"baseline must be one of {', '.join(BASELINES)}, got {name!r}")
    return BASELINES[name]
