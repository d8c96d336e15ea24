"""Generalised least-squares fits of a model under an estimated noise model.

A fit alternates twice between the mean (least squares on whitened residuals,
:class:`knotmech.diagnose.stats.NoiseModel`) and the noise (maximum likelihood
from the residuals), so that likelihood ratios compare models each with its own
noise estimate. The ``mu_nominal`` prior enters as one extra whitened residual
``(mu - mu_nominal) / mu_nominal_sigma``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import least_squares

from knotmech.analytic.capstan import mu_from_mu_eff
from knotmech.diagnose.baselines import Model, build_model, pinch_load_parameter
from knotmech.diagnose.stats import NoiseModel, estimate_noise, ls_solve, require_finite
from knotmech.errors import DiagnoseError

#: above this lag-one correlation, effects are also fitted from a moderate-noise first pass
_RHO_SECOND_PASS = 0.95

__all__ = [
    "Data",
    "Fit",
    "fit_model",
    "fit_baseline",
    "fit_with_effect",
    "heldout_errors",
    "heldout_rms",
    "heldout_innovation_rms",
]


@dataclass
class Data:
    """The random part of a recording: measured values and the prior."""

    y: np.ndarray
    mu_nominal: float | None
    mu_sigma: float | None


@dataclass
class Fit:
    """A fitted model: parameters, mean, noise, log-likelihood (data + prior)."""

    model: Model
    p: np.ndarray
    mean: np.ndarray
    noise: NoiseModel
    loglik: float

    @property
    def params(self) -> dict:
        return self.model.params(self.p)

    def resid(self, y):
        return y - self.mean


def _clip(model: Model, p: np.ndarray) -> np.ndarray:
    lo, hi = model.lower, model.upper
    span = np.where(np.isfinite(hi - lo), hi - lo, np.abs(p) + 1.0)
    eps = 1e-9 * span
    return np.minimum(np.maximum(p, lo + eps), hi - eps)


def _ls(model, data, p0, noise, starts):
    rec = model.rec
    mu_idx = model.names.index("mu")
    prior = data.mu_nominal is not None
    sd_holder = {}

    def fun(p):
        f = model.mean(p)
        sd = sd_holder.get("sd")
        if sd is None:
            sd = noise.sd(f)
            sd_holder["sd"] = sd
        e = noise.whiten(data.y - f, sd, starts)
        if prior:
            e = np.append(e, (p[mu_idx] - data.mu_nominal) / data.mu_sigma)
        return e

    sd_holder["sd"] = noise.sd(model.mean(p0))
    del rec
    res = _least_squares(
        fun,
        p0,
        model,
        _step(model),
        method="trf",
        x_scale="jac",
        ftol=1e-8,
        xtol=1e-8,
        gtol=1e-8,
        max_nfev=100,
    )
    return res.x, float(res.cost)


def _step(model) -> str:
    effects = " + ".join(model.effects)
    return f"fitting the {model.rec.experiment} model" + (f" with {effects}" if effects else "")


def _least_squares(fun, p0, model, step, **kw):
    """``scipy.optimize.least_squares`` within ``model``'s bounds, after checking its inputs.

    The bounds, the start and the residuals at the start must be finite (bounds
    ordered, start inside): otherwise :class:`~knotmech.errors.DiagnoseError` naming
    ``step``, instead of a ValueError or a LinAlgError from inside scipy.
    """
    lo, hi = model.lower, model.upper
    bad = ~(lo < hi) | np.isnan(lo) | np.isnan(hi)
    if np.any(bad):
        j = int(np.argmax(bad))
        raise DiagnoseError(
            f"{step}: parameter {model.names[j]} has an empty range [{lo[j]:g}, {hi[j]:g}] "
            "(the recording's values leave it no room)"
        )
    require_finite(f"{step} (start)", p0)
    if np.any(p0 < lo) or np.any(p0 > hi):
        raise DiagnoseError(f"{step}: the starting point is outside the parameter bounds")
    with np.errstate(all="ignore"):
        f0 = fun(p0)
    require_finite(f"{step} (residuals at the start)", f0)
    res = least_squares(fun, p0, bounds=(lo, hi), **kw)
    require_finite(f"{step} (result)", res.x, res.fun)
    return res


def _loglik(model, data, p, noise, starts):
    mean = model.mean(p)
    ll = noise.loglik(data.y - mean, mean, starts)
    if data.mu_nominal is not None:
        mu = p[model.names.index("mu")]
        ll += -0.5 * ((mu - data.mu_nominal) / data.mu_sigma) ** 2
    return ll


def fit_model(model, data, p_starts, noise, starts, *, given_sigma=None, rounds=2) -> Fit:
    """Fit ``model`` from several starting points, re-estimating the noise.

    Parameters
    ----------
    model : Model
    data : Data
    p_starts : list of arrays
        Starting parameter vectors (the best one after the first pass is kept).
    noise : NoiseModel
        Noise used in the first pass.
    starts : (n,) bool array
        Trial starts.
    """
    best = None
    for p0 in p_starts:
        p, cost = _ls(model, data, _clip(model, np.asarray(p0, float)), noise, starts)
        if best is None or cost < best[1]:
            best = (p, cost)
    p = best[0]
    for r in range(rounds):
        mean = model.mean(p)
        noise = estimate_noise(data.y - mean, mean, starts, given_sigma=given_sigma)
        if r < rounds - 1:
            p, _ = _ls(model, data, _clip(model, p), noise, starts)
    mean = model.mean(p)
    return Fit(model, p, mean, noise, _loglik(model, data, p, noise, starts))


def _vector(model: Model, values: dict, defaults: dict) -> np.ndarray:
    return np.array([values.get(n, defaults.get(n, 0.0)) for n in model.names], dtype=float)


def baseline_start(rec, y) -> dict:
    """Heuristic starting values of the baseline parameters."""
    exp = rec.experiment
    x = rec.x
    if exp == "capstan_pull":
        t_low, theta = rec.meta("T_low_N"), rec.meta("wrap_angle_rad")
        top = np.quantile(y, 0.8)
        plateau = float(np.median(y[y >= top]))
        mu = max(np.log(max(plateau, t_low * 1.0001) / t_low) / theta, 1e-3)
        rise = plateau - t_low
        sel = (y > t_low + 0.05 * rise) & (y < t_low + 0.6 * rise)
        span = float(np.ptp(x)) or 1.0
        if sel.sum() >= 3 and np.ptp(x[sel]) > 0:
            b, a = np.polyfit(x[sel], y[sel], 1)
        else:
            b, a = rise / (0.3 * span), t_low
        b = max(b, rise / span * 0.1, 1e-9)
        zero = (t_low - a) / b
        return {"mu": mu, "k_N_per_m": b, "delta0_m": max(zero, 0.0), "offset_m": max(-zero, 0.0)}
    if exp == "pinch":
        mu = max(np.dot(x, y) / (2 * np.dot(x, x)), 1e-3)
        return {"mu": mu}
    r = 0.5 * (rec.meta("post_diameter_m") + rec.meta("rod_diameter_m"))
    pos = y > 0
    if pos.sum() >= 2 and np.ptp(x[pos]) > 0:
        slope = np.polyfit(x[pos], np.log(y[pos] / rec.meta("T_high_N")), 1)[0]
        mu = max(-slope * r, 1e-3)
    else:
        mu = 0.3
    return {"mu": mu}


def fit_baseline(rec, data, starts, *, given_sigma=None, noise=None) -> Fit:
    """Fit the experiment's baseline."""
    model = build_model(rec, ())
    p0 = _vector(model, baseline_start(rec, data.y), {})
    if noise is None:
        f0 = model.mean(_clip(model, p0))
        noise = estimate_noise(data.y - f0, f0, starts, given_sigma=given_sigma)
    fit = fit_model(model, data, [p0], noise, starts, given_sigma=given_sigma)
    return _second_pass(fit, model, data, [p0], noise, starts, given_sigma)


def _second_pass(fit, model, data, p_starts, noise, starts, given_sigma):
    """Refit from a moderate-correlation first pass when ``noise`` has rho near 1.

    A lag-one correlation near 1 (often a poor start's misfit, or the null model's
    absorbing an effect) leaves a level or slope change almost no weight after
    whitening, so the first pass may stay near its start; the better likelihood is kept.
    """
    if noise.rho <= _RHO_SECOND_PASS:
        return fit
    alt = fit_model(model, data, p_starts, replace(noise, rho=0.5), starts, given_sigma=given_sigma)
    return alt if alt.loglik > fit.loglik else fit


def _material_mu(rec, mu_app):
    d = rec.meta("rod_diameter_m")
    D = rec.meta("post_diameter_m")
    dt = D / d
    mu_app = min(mu_app, 0.95 * np.sqrt(dt))
    return float(mu_from_mu_eff(max(mu_app, 1e-6), dt))


def fit_with_effect(current: Fit, effect: str, data: Data, starts, *, given_sigma=None) -> Fit:
    """Fit ``current``'s model with ``effect`` added (heuristic starts and grids).

    Returns the best fit found; the same routine runs on simulated recordings in
    the bootstrap, so the maximisation over onsets and positions is calibrated.
    """
    rec = current.model.rec
    values = current.params
    effects = current.model.effects + (effect,)
    fixed = dict(current.model.fixed)
    y = data.y
    span = float(np.ptp(rec.x)) or 1.0
    starts_p = []
    if effect == "finite_thickness":
        values = dict(values)
        values["mu"] = _material_mu(rec, values["mu"])
        if "dmu_static" in values:
            values["dmu_static"] = values["dmu_static"] * 1.2
    if effect == "static_friction":
        model = build_model(rec, effects, fixed)
        t_low, theta = rec.meta("T_low_N"), rec.meta("wrap_angle_rad")
        mu_peak = np.log(max(np.max(y), t_low * 1.0001) / t_low) / theta
        base = dict(values)
        base["dmu_static"] = max(mu_peak - values["mu"], 1e-3)
        for frac in (0.01, 0.05, 0.2):
            base["decay_length_m"] = frac * span
            starts_p.append(_vector(model, base, {}))
    elif effect == "displacement_offset":
        model = build_model(rec, effects, fixed)
        b = baseline_start(rec, y)
        v = dict(values)
        v["offset_m"] = b["offset_m"] if b["offset_m"] > 0 else -values["delta0_m"]
        starts_p.append(_vector(model, v, {}))
        starts_p.append(_vector(model, dict(v, offset_m=-values["delta0_m"]), {}))
    elif effect == "adhesion":
        model = build_model(rec, effects, fixed)
        slope, icpt = np.polyfit(rec.x, y, 1)
        v = dict(values)
        v["adhesion_force_N"] = max(icpt, 0.0)
        starts_p.append(_vector(model, v, {}))
        v2 = dict(v)
        v2["mu"] = max(slope / 2, 1e-3)
        starts_p.append(_vector(model, v2, {}))
    elif effect == "contact_flattening":
        model = build_model(rec, effects, fixed)
        starts_p = _flattening_starts(current, model, data, starts)
    elif effect == "rate_dependent_friction":
        model = build_model(rec, effects, fixed)
        starts_p.append(_vector(model, values, {"dmu_dlnv": 0.0}))
    elif effect == "self_contact_nip":
        return _fit_nip(current, data, starts, given_sigma=given_sigma)
    else:  # finite_thickness
        model = build_model(rec, effects, fixed)
        starts_p.append(_vector(model, values, {}))
    fit = fit_model(model, data, starts_p, current.noise, starts, given_sigma=given_sigma)
    return _second_pass(fit, model, data, starts_p, current.noise, starts, given_sigma)


def _whiten_cols(noise, sd, starts, cols):
    u = cols / sd[:, None]
    e = np.empty_like(u)
    c = np.sqrt(1.0 - noise.rho**2)
    e[1:] = (u[1:] - noise.rho * u[:-1]) / c
    e[starts] = u[starts]
    return e


def _flattening_starts(current, model, data, starts):
    rec = model.rec
    xl = pinch_load_parameter(
        rec.x,
        youngs_modulus=rec.meta("youngs_modulus_Pa"),
        rod_diameter=rec.meta("rod_diameter_m"),
        pinch_diameter=rec.meta("pinch_diameter_m"),
    )
    scale = rec.x / np.where(xl > 0, xl, 1.0)
    scale = float(np.median(scale[xl > 0])) if np.any(xl > 0) else 1.0
    sd = current.noise.sd(current.mean)
    yw = current.noise.whiten(data.y, sd, starts)
    cands = np.quantile(xl, np.linspace(0.1, 0.9, 17))
    adh = "adhesion" in model.effects
    best = []
    for xc in cands:
        fc = xc * scale
        cols = [rec.x, -np.maximum(rec.x - fc, 0.0)]
        if adh:
            cols.append(np.ones_like(rec.x))
        xw = _whiten_cols(current.noise, sd, starts, np.column_stack(cols))
        coef = ls_solve(xw, yw, step=_step(model))
        ss = float(np.sum((yw - xw @ coef) ** 2))
        a, b = coef[0], coef[1]
        ratio = float(np.clip(1 - b / a, 0.0, 1.0)) if a > 0 else 1.0
        best.append((ss, xc, max(a / 2, 1e-4), ratio, coef[2] if adh else 0.0))
    best.sort(key=lambda t: t[0])
    out = []
    for _ss, xc, mu, ratio, fa in best[:2]:
        v = dict(current.params)
        v.update({"onset_load_parameter": xc, "slope_ratio": min(ratio, 0.98), "mu": mu})
        if adh:
            v["adhesion_force_N"] = max(fa, 0.0)
        out.append(_vector(model, v, {}))
    return out


def _fit_nip(current, data, starts, *, given_sigma=None):
    rec = current.model.rec
    s = rec.x
    fixed = dict(current.model.fixed)
    j = 0
    while f"nip_position_{j}" in fixed:
        j += 1
    order = np.unique(s)
    mids = 0.5 * (order[1:] + order[:-1])
    if mids.size > 4:
        mids = mids[1:-1]
    taken = [fixed[f"nip_position_{i}"] for i in range(j)]
    if taken:
        gap = max(1.5 * float(np.median(np.diff(order))), 0.01 * float(np.ptp(s)))
        keep = np.min(np.abs(mids[:, None] - np.array(taken)[None, :]), axis=1) > gap
        mids = mids[keep]
    if mids.size > 120:
        mids = mids[np.linspace(0, mids.size - 1, 120).astype(int)]
    f = current.mean
    r = 0.5 * (rec.meta("post_diameter_m") + rec.meta("rod_diameter_m"))
    sd = current.noise.sd(f)
    ew = current.noise.whiten(data.y - f, sd, starts)
    jmu = _whiten_cols(current.noise, sd, starts, (-f * s / r)[:, None])[:, 0]
    steps = -f[:, None] * (s[:, None] > mids[None, :])
    sw = _whiten_cols(current.noise, sd, starts, steps)
    # score = reduction of whitened SS when regressing on [d/dmu, step_j], per candidate
    a11 = jmu @ jmu
    a12 = jmu @ sw
    a22 = np.sum(sw * sw, axis=0)
    b1 = jmu @ ew
    b2 = sw.T @ ew
    det = a11 * a22 - a12**2
    det = np.where(det > 1e-300, det, np.inf)
    c2 = (a11 * b2 - a12 * b1) / det
    score = (b1**2 * a22 - 2 * a12 * b1 * b2 + b2**2 * a11) / det
    score = np.where(c2 > 0, score, -np.inf)
    best = None
    for idx in np.argsort(score)[::-1][:2]:
        if not np.isfinite(score[idx]):
            break
        fx = dict(fixed)
        fx[f"nip_position_{j}"] = float(mids[idx])
        model = build_model(rec, current.model.effects + ("self_contact_nip",), fx)
        v = dict(current.params)
        v[f"nip_drop_{j}"] = float(np.clip(c2[idx], 0.01, 0.9))
        v.update(fx)
        fit = fit_model(
            model, data, [_vector(model, v, {})], current.noise, starts, given_sigma=given_sigma
        )
        if best is None or fit.loglik > best.loglik:
            best = fit
    if best is None:  # no drop-shaped candidate: a null step at the middle
        fx = dict(fixed)
        fx[f"nip_position_{j}"] = float(np.median(s))
        model = build_model(rec, current.model.effects + ("self_contact_nip",), fx)
        v = dict(current.params)
        v[f"nip_drop_{j}"] = 0.0
        best = fit_model(
            model, data, [_vector(model, v, {})], current.noise, starts, given_sigma=given_sigma
        )
        return best
    return _refine_nip(best, j, data, starts, given_sigma=given_sigma)


def _refine_nip(fit, j, data, starts, *, given_sigma=None, window=60):
    """Move nip ``j`` to the best sample gap near it (exact model, other values fixed).

    The candidate grid of :func:`_fit_nip` is coarse for long recordings; here every
    gap between consecutive arc lengths within ``window`` gaps of the current
    position (and not beyond a neighbouring nip) is scored with the exact mean,
    whitened; the model is refitted when the position moves.
    """
    rec = fit.model.rec
    s = rec.x
    p = fit.params
    pos = p[f"nip_position_{j}"]
    drop = p[f"nip_drop_{j}"]
    if drop <= 0:
        return fit
    order = np.unique(s)
    mids = 0.5 * (order[1:] + order[:-1])
    others = [p[f"nip_position_{i}"] for i in range(j + 10) if f"nip_position_{i}" in p and i != j]
    lo = max([o for o in others if o < pos], default=-np.inf)
    hi = min([o for o in others if o > pos], default=np.inf)
    k = int(np.searchsorted(mids, pos))
    cand = mids[max(0, k - window) : k + window + 1]
    cand = cand[(cand > lo) & (cand < hi)]
    if cand.size < 2:
        return fit
    without = fit.mean / np.where(s > pos, 1.0 - drop, 1.0)
    means = without[:, None] * np.where(s[:, None] > cand[None, :], 1.0 - drop, 1.0)
    sd = fit.noise.sd(fit.mean)
    ew = _whiten_cols(fit.noise, sd, starts, data.y[:, None] - means)
    best = float(cand[int(np.argmin(np.sum(ew * ew, axis=0)))])
    if best == pos:
        return fit
    fx = dict(fit.model.fixed)
    fx[f"nip_position_{j}"] = best
    model = build_model(rec, fit.model.effects, fx)
    v = dict(p)
    v.update(fx)
    return fit_model(
        model, data, [_vector(model, v, {})], fit.noise, starts, given_sigma=given_sigma
    )


def heldout_errors(fit: Fit, data: Data, trial: np.ndarray, *, n_folds=5):
    """Held-out prediction errors: contiguous blocks (n/50 rows), assigned to folds in turn.

    Each fold's rows are left out, the model is refitted on the rest (weighted by
    the fitted noise sd, warm start; nip positions stay fixed) and predicts them.

    Returns
    -------
    err : (n,) array
        ``y - prediction`` of every row, predicted with its block held out [units of y].
    block : (n,) int array
        Block index of every row.
    """
    model = fit.model
    n = data.y.size
    size = max(3, n // 50)
    block = np.arange(n) // size
    fold = block % n_folds
    sd = fit.noise.sd(fit.mean)
    mu_idx = model.names.index("mu")
    prior = data.mu_nominal is not None
    err = np.empty(n)
    for k in range(n_folds):
        train = fold != k
        test = ~train

        def fun(p, train=train):
            e = (data.y[train] - model.mean(p)[train]) / sd[train]
            if prior:
                e = np.append(e, (p[mu_idx] - data.mu_nominal) / data.mu_sigma)
            return e

        res = _least_squares(
            fun,
            _clip(model, fit.p),
            model,
            "held-out validation: " + _step(model),
            method="trf",
            x_scale="jac",
            max_nfev=100,
        )
        pred = model.mean(res.x)
        err[test] = data.y[test] - pred[test]
    return err, block


def heldout_rms(fit: Fit, data: Data, trial: np.ndarray, *, n_folds=5) -> float:
    """Held-out RMS [units of y] of :func:`heldout_errors`."""
    err, _ = heldout_errors(fit, data, trial, n_folds=n_folds)
    return float(np.sqrt(np.mean(err**2)))


def heldout_innovation_rms(err, block, noise: NoiseModel, mean, starts) -> float:
    r"""RMS of the whitened one-step-ahead held-out prediction errors (innovations).

    Within each held-out block (and trial) the errors are whitened with ``noise``,
    :math:`e_i = (u_i - \rho u_{i-1})/\sqrt{1-\rho^2}`, :math:`u_i = r_i/\sigma_i`, the
    first row of a block standing alone (:math:`e_i = u_i`): under AR(1) noise a sharp
    mismatch of a few noise sd is several innovation sd, while the raw held-out RMS is
    dominated by the slowly varying noise and barely moves. Dimensionless (1 when the
    model predicts the held-out rows to within the noise).
    """
    first = starts.copy()
    first[1:] |= block[1:] != block[:-1]
    e = noise.whiten(err, noise.sd(mean), first)
    return float(np.sqrt(np.mean(e**2)))
