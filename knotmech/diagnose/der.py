r"""The DER capstan as the baseline of ``capstan_pull`` (``--baseline der``).

:class:`DERCurves` runs :func:`knotmech.scenes.capstan.capstan` with the recording's
geometry and loads, kinetic friction only; :class:`DERModel` is a
:class:`~knotmech.diagnose.baselines.Model` whose mean is that curve: free parameters
``mu`` (interpolated between simulations on a small grid, refined around the fit), a
signed displacement shift ``delta0_m`` and a displacement scale ``u_scale``
(compliance ratio; neither needs a new simulation). ``static_friction`` re-runs the scene with
``mu_s = mu + dmu_static > mu_k``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2

from knotmech.diagnose.effects import applicable_effects, get_effect
from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.fitting import fit_model, heldout_rms
from knotmech.diagnose.model import Model
from knotmech.diagnose.recording import Recording
from knotmech.diagnose.stats import NoiseModel, estimate_noise
from knotmech.errors import InputError, SolverError

__all__ = [
    "DERCurves",
    "DERModel",
    "build_der_model",
    "fit_der_baseline",
    "select_der",
    "DER_DMU_GRID",
    "DER_EFFECTS",
    "DER_MAX_STEPS",
    "DER_MAX_WRAP",
    "DER_MU_FINE",
    "check_der_recording",
    "refine_grid",
    "step_span",
]

#: the effects modelled under the DER baseline (the scene re-run with mu_s > mu_k)
DER_EFFECTS = ("static_friction",)

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


def check_der_recording(rec: Recording) -> None:
    """Refuse, before any simulation, a recording the DER baseline cannot run on.

    Besides the kind (``capstan_pull``; ``knot_pull`` is checked by
    :mod:`knotmech.diagnose.der_knot`): the wrap beyond :data:`DER_MAX_WRAP` (two
    loops), displacements below the range of the model's shift (``-0.3`` of the
    largest), and a pull so short that one run would need more than
    :data:`DER_MAX_STEPS` implicit steps (the 0.1 s load ramp at the step
    ``s / (60 v)``, ``s`` of :func:`step_span`).

    Raises
    ------
    InputError
        One line naming what is wrong.
    """
    if rec.experiment == "knot_pull":
        return  # the knot's own checks: knotmech.diagnose.der_knot
    if rec.experiment != "capstan_pull":
        raise InputError(
            f"baseline 'der' is not available for {rec.experiment} recordings "
            "(capstan_pull and knot_pull only); use closed-form"
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
      :math:`dt = s / (60\,v)` with :math:`s` the span the recording samples
      (:func:`step_span`; :math:`u_\mathrm{max}` when it starts at or below 0), so 60
      implicit steps over the recorded stretch, every step saved;
    - pull distance 1.05 :math:`u_\mathrm{max}`, loads ramped over 0.1 s, density 1000 kg/m^3.

    Curves of other ``mu`` are interpolated linearly in ``mu`` on :math:`\ln T` between
    runs on a grid (the sliding plateau :math:`T_\mathrm{low} e^{\mu_\mathrm{eff}\theta}`
    is then exact where :math:`\mu_\mathrm{eff}` is linear in ``mu``); the baseline's
    grid is refined around its fitted ``mu`` (:func:`refine_grid`), where the knee of
    the rise is not linear in ``mu``.
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
        self.dt = step_span(rec.x, self.u_max) / (DER_STEPS * self.v)
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

        # imported here, not at the top, for start-up speed: the solver compiles numba
        # kernels, and only --baseline der needs them
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


#: spacing of the runs added around the fitted mu (:func:`refine_grid`): the knee of the
#: rise interpolated between runs 0.064 apart missed the run at mu by up to 5.9 noise sd
#: (1 % T_low), 0.032 apart by 2.0 sd, 0.016 apart by 0.01 sd (issue26-campaign.md s. 14)
DER_MU_FINE = 0.005
#: most refinements of the baseline's grid (:func:`fit_der_baseline`)
DER_POLISH_ROUNDS = 3


def step_span(x, u_max: float) -> float:
    """Displacement span [m] the DER baseline's 60 steps cover: the recording's own.

    ``u_max`` for a recording that starts at or below 0; for one that starts above 0
    (a zero offset) ``u_max - min(x)`` rounded to two significant figures, at least
    ``u_max / 4`` (a recording of only the plateau would otherwise ask for tiny steps).
    The curve's knee moves with the step (40 elements, 1 % T_low noise: by 6.9 sd from
    60 steps over 8 mm to 60 over 10 mm, by 1.5 sd for a step 0.5 % shorter), so a
    recording shifted by an offset is simulated with the step of the same recording
    unshifted, and the rounding keeps the step when the outlier screen drops its first
    row.
    """
    lo = float(np.min(x))
    if lo <= 0.0:
        return u_max
    span = float(f"{u_max - lo:.2g}")
    return min(u_max, max(span, 0.25 * u_max))


def refine_grid(grid: np.ndarray, mu: float, h: float = DER_MU_FINE) -> np.ndarray:
    """``grid`` with runs at ``mu - h``, ``mu``, ``mu + h`` added (those inside it and
    not on it already).

    The run at ``mu`` makes the baseline exact at its fitted value; its neighbours make
    the interpolation in ``mu`` near it accurate for the fit's own steps.
    """
    grid = np.asarray(grid, float)
    fine = np.round(mu + h * np.array([-1.0, 0.0, 1.0]), 10)
    fine = fine[(fine > grid[0]) & (fine < grid[-1])]
    # a run already on the grid (to 1e-9) is not run twice
    fine = fine[np.min(np.abs(fine[:, None] - grid[None, :]), axis=1) > 1e-9]
    return np.union1d(grid, fine)


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
    """DER model of a capstan_pull recording (``effects``: empty or the static_friction
    Effect object)."""
    names, lo, hi = (
        ["mu", "delta0_m", "u_scale"],
        [mu_grid[0], -0.3 * curves.u_max, 0.1],
        [mu_grid[-1], 0.5 * curves.u_max, 10.0],
    )
    if any(e.name == "static_friction" for e in effects):
        names.append("dmu_static")
        lo.append(0.0)
        hi.append(float(DER_DMU_GRID[-1]))
    return DERModel(
        rec,
        tuple(e.name for e in effects),
        names,
        np.array(lo, float),
        np.array(hi, float),
        {},
        get_experiment(rec.experiment),
        tuple(effects),
        curves=curves,
        mu_grid=np.asarray(mu_grid, float),
        dmu_grid=DER_DMU_GRID,
        mu_k0=mu_k0,
    )


# --- the engine's steps under the DER baseline -------------------------------------------

_DER_P_METHOD = (
    "asymptotic: 0.5 * chi2_1 tail of the likelihood ratio of the whitened residuals "
    "(dmu_static = 0 on the boundary); no parametric bootstrap under the DER baseline "
    "(each bootstrap draw would need new simulations); the held-out check still applies"
)


def fit_der_baseline(rec, data, starts, gs):
    """Kinetic-only DER baseline: grid scan, then GLS on (mu, delta0_m, u_scale).

    The GLS starts under white noise (without a ``sigma`` column), then under the AR(1)
    noise of its residuals; it is then refitted on the ``mu`` grid refined at the fit
    (:func:`_polished`). Measured in ``docs/notes/diagnose-noise-and-statistics/
    issue26-campaign.md`` section 14.

    Returns
    -------
    der : (DERCurves, mu grid)
    fit : Fit
    """
    curves = DERCurves(rec)
    mu_app = get_experiment(rec.experiment).start(rec, data.y)["mu"]
    grid = curves.kinetic_grid(mu_app)
    model = build_der_model(rec, curves, grid)
    x = rec.x
    shifts = np.linspace(model.lower[1], model.upper[1], 41)
    best = None
    for mu in grid:
        for d0 in shifts:
            for sc in (0.25, 0.5, 1.0, 2.0, 4.0):
                ss = float(np.sum((data.y - curves.at((x - d0) / sc, mu, mu)) ** 2))
                if best is None or ss < best[0]:
                    best = (ss, mu, d0, sc)
    p0 = np.array(best[1:])
    f0 = model.mean(p0)
    if gs is None:
        # first under white noise: the scan's start leaves the plateau level off, and an
        # AR(1) noise estimated there (rho ~0.985) lets the fit keep a wrong mu
        white = NoiseModel(float(np.std(data.y - f0)), 0.0, 0.0, float(np.max(np.abs(f0))))
        p0 = fit_model(model, data, [p0], white, starts, rounds=0).p
        f0 = model.mean(p0)
    noise = estimate_noise(data.y - f0, f0, starts, given_sigma=gs)
    fit = fit_model(model, data, [p0], noise, starts, given_sigma=gs)
    return _polished(rec, curves, grid, fit, data, starts, gs)


def _polished(rec, curves, grid, fit, data, starts, gs):
    """``fit`` refitted on the grid refined at its ``mu`` (:func:`refine_grid`), again
    while the refit's ``mu`` leaves the runs added last (at most
    :data:`DER_POLISH_ROUNDS` times): between coarse runs the knee is off by up to
    5.9 noise sd, which can also pull the coarse fit's ``mu`` away from the truth.
    """
    for _ in range(DER_POLISH_ROUNDS):
        centre = float(fit.params["mu"])
        grid = refine_grid(grid, centre)
        model = build_der_model(rec, curves, grid)
        f0 = model.mean(fit.p)
        noise = estimate_noise(data.y - f0, f0, starts, given_sigma=gs)
        fit = fit_model(model, data, [fit.p], noise, starts, given_sigma=gs)
        if abs(float(fit.params["mu"]) - centre) <= 0.5 * DER_MU_FINE:
            break
    return (curves, grid), fit


def select_der(der, base, rec, data, starts, gs, alpha, effects):
    """static_friction against the DER baseline (LR / BIC / held-out; see _DER_P_METHOD).

    ``effects``: Effect objects the caller restricts the catalogue to, or None.
    Returns the tuple of the engine's forward selection.
    """
    curves, grid = der
    ok, skipped = applicable_effects(rec)
    for eff in ok:
        if eff.name not in DER_EFFECTS:
            skipped[eff.name] = "not modelled under the DER baseline (only static_friction is)"
    held_before = heldout_rms(base, data, rec.trial)
    static = get_effect("static_friction")
    if effects is not None and static not in effects:
        return base, [], [], [], skipped, held_before, held_before
    mu_k0 = float(base.params["mu"])
    d0 = float(base.params["delta0_m"])
    sc = float(base.params["u_scale"])
    model = build_der_model(rec, curves, grid, (static,), mu_k0=mu_k0)
    sd = base.noise.sd(base.mean)
    scores = []
    for dm in DER_DMU_GRID[1:]:
        p = np.array([mu_k0, d0, sc, dm])
        e = base.noise.whiten(data.y - model.mean(p), sd, starts)
        scores.append((float(e @ e), dm))
    scores.sort()
    p_starts = [np.array([mu_k0, d0, sc, dm]) for _, dm in scores[:2]]
    alt = fit_model(model, data, p_starts, base.noise, starts, given_sigma=gs)
    lr = max(2.0 * (alt.loglik - base.loglik), 0.0)
    dbic = lr - np.log(rec.n)
    p = 0.5 * float(chi2.sf(lr, 1)) if lr > 0 else 1.0
    held_alt = heldout_rms(alt, data, rec.trial)
    ev = {
        "effect": "static_friction",
        "delta_bic": float(f"{dbic:.4g}"),
        "likelihood_ratio": float(f"{lr:.4g}"),
        "p_value": float(f"{p:.3g}"),
        "bootstrap_draws": 0,
        "p_value_method": _DER_P_METHOD,
        "heldout_rms_before": float(f"{held_before:.4g}"),
        "heldout_rms": float(f"{held_alt:.4g}"),
        "accepted": bool(p < alpha and dbic > 0 and held_alt < held_before),
    }
    steps = [{"static_friction": ev["delta_bic"]}]
    if not ev["accepted"]:
        return base, [], [ev], steps, skipped, held_before, held_before
    accepted = [(static, ev, lr)]
    return alt, accepted, [ev], steps, skipped, held_before, held_alt
