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

from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.model import Model, build_model, fit_step_name, param_vector
from knotmech.diagnose.noisefloor import without_rows
from knotmech.diagnose.stats import NoiseModel, estimate_noise, require_finite
from knotmech.errors import DiagnoseError

#: above this lag-one correlation, effects are also fitted from a moderate-noise first pass
_RHO_SECOND_PASS = 0.95

#: longest recording whose candidate effect fits (:func:`fit_with_effect`, the nip's
#: candidates) and held-out refits (:func:`heldout_errors`) use every row; beyond it they
#: use every k-th row (at most this many) and the fit kept is refitted on every row
#: (:func:`refit_all_rows`)
FIT_ROWS = 20_000

#: longest recording the parametric bootstraps simulate in full; beyond it each draw is a
#: recording of every k-th row of each trial (:func:`thinned_rows`, :func:`thinned_null`)
BOOT_ROWS = 4000

__all__ = [
    "Data",
    "Fit",
    "fit_model",
    "fit_baseline",
    "fit_with_effect",
    "param_vector",
    "whiten_columns",
    "fit_step_name",
    "baseline_start",
    "heldout_errors",
    "heldout_rms",
    "heldout_innovation_rms",
    "prior_heldout_z",
    "BOOT_ROWS",
    "FIT_ROWS",
    "refit_all_rows",
    "thinned_rows",
    "thinned_noise",
    "thinned_null",
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
        if model.priors:
            e = np.append(e, model.prior_residuals(p))
        return e

    sd_holder["sd"] = noise.sd(model.mean(p0))
    del rec
    res = _least_squares(
        fun,
        p0,
        model,
        fit_step_name(model),
        method="trf",
        x_scale="jac",
        ftol=1e-8,
        xtol=1e-8,
        gtol=1e-8,
        max_nfev=100,
    )
    return res.x, float(res.cost)


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
    if model.priors:
        ll += -0.5 * float(np.sum(model.prior_residuals(p) ** 2))
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


def refit_all_rows(model, data, p, starts, *, given_sigma=None) -> Fit:
    """``model`` refitted on every row from ``p``, the values of a fit on thinned rows.

    One round of :func:`fit_model` in place of its first: the noise estimated from the
    residuals at ``p``, the mean fitted under it (from ``p``), the noise estimated again.
    """
    mean = model.mean(p)
    noise = estimate_noise(data.y - mean, mean, starts, given_sigma=given_sigma)
    return fit_model(model, data, [p], noise, starts, given_sigma=given_sigma, rounds=1)


def baseline_start(rec, y) -> dict:
    """Heuristic starting values of the baseline parameters (the experiment's ``start``)."""
    return get_experiment(rec.experiment).start(rec, y)


def fit_baseline(rec, data, starts, *, given_sigma=None, noise=None) -> Fit:
    """Fit the experiment's baseline."""
    model = build_model(rec, ())
    p0 = param_vector(model, baseline_start(rec, data.y))
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


def _second_pass_own(own, current, effect, data, starts, given_sigma):
    """The second pass of :func:`_second_pass` for an effect with a fit of its own.

    With rho near 1 the effect's own search (nip positions scored on whitened steps)
    runs again under a moderate-correlation copy of the current noise; the model it
    finds is refitted from there under the current noise (on a recording of at most
    :data:`FIT_ROWS` rows; beyond, the effect's fit refits its candidate on every row
    under a noise estimated from them, :func:`refit_all_rows`, and is given ``own`` to
    return when it finds the same model), and the better likelihood is kept.
    """
    if current.noise.rho <= _RHO_SECOND_PASS:
        return own
    moderate = replace(current, noise=replace(current.noise, rho=0.5))
    long = current.model.rec.n > FIT_ROWS
    known = {"known": own} if long else {}
    alt = effect.fit(moderate, data, starts, given_sigma=given_sigma, **known)
    if alt is None or alt is own:
        return own
    if not long:
        # (beyond FIT_ROWS the effect's fit already ends with a fit on every row under a
        # noise estimated from every row's residuals: refit_all_rows)
        alt = fit_model(alt.model, data, [alt.p], current.noise, starts, given_sigma=given_sigma)
    return alt if alt.loglik > own.loglik else own


def fit_with_effect(current: Fit, effect, data: Data, starts, *, given_sigma=None) -> Fit:
    """Fit ``current``'s model with ``effect`` (an Effect object) added.

    The effect's own ``fit`` when it has one (searched positions), else a fit from the
    effect's starting vectors (and the moderate-correlation second pass); on a recording
    longer than :data:`FIT_ROWS` that fit runs on its thinned rows (:func:`thinned_null`)
    and its result is refitted on every row (:func:`refit_all_rows`). Returns the
    best fit found; the same routine runs on simulated recordings in the bootstrap, so
    the maximisation over onsets and positions is calibrated.
    """
    own = effect.fit(current, data, starts, given_sigma=given_sigma)
    if own is not None:
        return _second_pass_own(own, current, effect, data, starts, given_sigma)
    effects = current.model.effect_objects_added + (effect,)
    model = build_model(current.model.rec, effects, current.model.fixed)
    p_starts = effect.starts(current, model, data, starts)
    if model.rec.n > FIT_ROWS:
        # a long recording: the search from every start (and its second pass) on the
        # thinned rows, then the best fit refitted on every row
        sub, sdata, sstarts, sgs = thinned_null(current, data, starts, given_sigma, FIT_ROWS)
        smodel = build_model(sub.model.rec, effects, current.model.fixed)
        thin = fit_model(smodel, sdata, p_starts, sub.noise, sstarts, given_sigma=sgs)
        thin = _second_pass(thin, smodel, sdata, p_starts, sub.noise, sstarts, sgs)
        return refit_all_rows(model, data, thin.p, starts, given_sigma=given_sigma)
    fit = fit_model(model, data, p_starts, current.noise, starts, given_sigma=given_sigma)
    return _second_pass(fit, model, data, p_starts, current.noise, starts, given_sigma)


def whiten_columns(noise: NoiseModel, sd: np.ndarray, starts, cols: np.ndarray) -> np.ndarray:
    """Whitened columns of a design ``cols`` (n, k) under ``noise`` (see NoiseModel.whiten)."""
    u = cols / sd[:, None]
    e = np.empty_like(u)
    c = np.sqrt(1.0 - noise.rho**2)
    e[1:] = (u[1:] - noise.rho * u[:-1]) / c
    e[starts] = u[starts]
    return e


def heldout_errors(fit: Fit, data: Data, trial: np.ndarray, *, n_folds=5):
    """Held-out prediction errors: contiguous blocks (n/50 rows), assigned to folds in turn.

    Each fold's rows are left out, the model is refitted on the rest (weighted by
    the fitted noise sd, warm start; nip positions stay fixed) and predicts them. On a
    recording longer than :data:`FIT_ROWS` the refit uses every k-th of the rest's rows
    (at most ``FIT_ROWS``): the fold's parameters then carry the error of ``FIT_ROWS``
    rows (a relative change of the held-out mean square of order ``n_free / FIT_ROWS``),
    and every fold still predicts all of its held-out rows.

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
        fold_model = model
        if n > FIT_ROWS:
            # a long recording: the fold's model fitted on every k-th of its training rows
            rows = np.flatnonzero(train)
            step = int(np.ceil(rows.size / FIT_ROWS))
            train = np.zeros(n, bool)
            train[rows[::step]] = True
            sub = without_rows(model.rec, np.flatnonzero(~train))
            fold_model = build_model(sub, model.effect_objects_added, model.fixed)
        y_t, sd_t = data.y[train], sd[train]

        def fun(p, fold_model=fold_model, y_t=y_t, sd_t=sd_t, train=train):
            f = fold_model.mean(p)
            whole = f.size != y_t.size
            e = (y_t - (f[train] if whole else f)) / sd_t
            if prior:
                e = np.append(e, (p[mu_idx] - data.mu_nominal) / data.mu_sigma)
            if fold_model.priors:
                e = np.append(e, fold_model.prior_residuals(p))
            return e

        res = _least_squares(
            fun,
            _clip(model, fit.p),
            model,
            "held-out validation: " + fit_step_name(model),
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


def thinned_rows(starts: np.ndarray, n_max: int = BOOT_ROWS):
    """Every k-th row of each trial, ``k = ceil(n / n_max)`` (all rows when ``n <= n_max``).

    Each trial keeps its first row and every k-th after it, so a thinned trial spans
    (nearly) the same range of the control variable and its rows stay equally spaced
    in row order: AR(1) noise of lag-one correlation ``rho`` on the recording is AR(1)
    of correlation ``rho**k`` on the thinned rows (exactly).

    Returns
    -------
    rows : (m,) int array
        Kept rows, in recording order.
    k : int
        Thinning step.
    """
    n = starts.size
    k = max(1, int(np.ceil(n / max(int(n_max), 1))))
    if k == 1:
        return np.arange(n), 1
    first = np.flatnonzero(starts)
    seg = np.repeat(first, np.diff(np.append(first, n)))  # each row's trial start
    rows = np.flatnonzero((np.arange(n) - seg) % k == 0)
    return rows, k


def thinned_noise(noise: NoiseModel, rows: np.ndarray, k: int) -> NoiseModel:
    """``noise`` on the rows of :func:`thinned_rows`: correlation ``rho**k``, sd per row cut."""
    if k == 1:
        return noise
    gs = None if noise.given_sigma is None else noise.given_sigma[rows]
    return noise.thinned(k, gs)


def thinned_null(fit: Fit, data: Data, starts, given_sigma, n_max: int = BOOT_ROWS):
    """The null of a parametric bootstrap on a long recording, on every k-th row.

    A draw of the bootstrap simulates a recording from ``fit`` and repeats the whole
    fitting procedure on it; beyond ``n_max`` rows the draws are recordings of the rows
    of :func:`thinned_rows` (the same model, parameters and noise model, the noise's
    correlation ``rho**k``): the likelihood-ratio statistics being compared have the
    same large-sample null distribution (chi-square for a regular effect) whatever the
    number of rows, and the draws cost ``n_max`` rows instead of ``n``. (For a searched
    position, the maximum over more gaps is slightly larger: see docs/notes/diagbig.md
    for the measured quantiles.)

    Returns
    -------
    fit, data, starts, given_sigma
        Unchanged when ``n <= n_max``; else their thinned counterparts.
    """
    rows, k = thinned_rows(starts, n_max)
    if k == 1:
        return fit, data, starts, given_sigma
    rec = fit.model.rec
    drop = np.ones(rec.n, bool)
    drop[rows] = False
    sub = without_rows(rec, np.flatnonzero(drop))
    model = build_model(sub, fit.model.effect_objects_added, fit.model.fixed)
    noise = thinned_noise(fit.noise, rows, k)
    sub_starts = starts[rows]
    sub_data = Data(data.y[rows], data.mu_nominal, data.mu_sigma)
    mean = model.mean(fit.p)
    sub_fit = Fit(model, fit.p, mean, noise, _loglik(model, sub_data, fit.p, noise, sub_starts))
    return sub_fit, sub_data, sub_starts, None if given_sigma is None else given_sigma[rows]


def prior_heldout_z(fit: Fit, data: Data, starts, *, given_sigma=None) -> float | None:
    r"""The prior ``mu_nominal`` predicted from the data alone, in sd: a held-out check.

    The model is refitted without the prior (its noise held fixed) and its mu compared
    with the independently measured one:
    :math:`z = (\hat\mu - \mu_\mathrm{nominal})/\sqrt{\sigma_\mathrm{nominal}^2 +
    \mathrm{se}(\hat\mu)^2}`, se from the Gauss-Newton covariance of the whitened
    residuals. The prior is the held-out datum: an effect that acts through it (no new
    free parameter, such as ``finite_thickness``, whose mu is the material coefficient)
    improves the prediction exactly when ``|z|`` falls; where the data alone fit the
    same curve either way the raw held-out error cannot show it.

    Returns
    -------
    float or None
        z (dimensionless); None without a prior.
    """
    if data.mu_nominal is None:
        return None
    model = fit.model
    free = Data(data.y, None, None)
    refit = fit_model(model, free, [fit.p], fit.noise, starts, given_sigma=given_sigma, rounds=0)
    j = model.names.index("mu")
    se = _se(model, refit, free, starts)[j]
    mu = float(refit.p[j])
    return float((mu - data.mu_nominal) / np.sqrt(data.mu_sigma**2 + se**2))


def _se(model, fit: Fit, data: Data, starts) -> np.ndarray:
    """Standard errors of ``fit``'s parameters from the Gauss-Newton covariance of the
    whitened residuals (forward differences, the noise held fixed) [units of each]."""
    p = np.asarray(fit.p, float)
    sd = fit.noise.sd(fit.mean)

    def res(q):
        return fit.noise.whiten(data.y - model.mean(q), sd, starts)

    r0 = res(p)
    hi = model.upper
    cols = []
    for k in range(p.size):
        h = 1e-6 * max(abs(p[k]), 1e-3)
        q = p.copy()
        q[k] = p[k] + h if p[k] + h <= hi[k] else p[k] - h
        cols.append((res(q) - r0) / (q[k] - p[k]))
    jac = np.column_stack(cols)
    cov = np.linalg.pinv(jac.T @ jac)
    return np.sqrt(np.maximum(np.diag(cov), 0.0))
