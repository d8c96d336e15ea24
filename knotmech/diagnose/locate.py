"""Locate systematic residuals: where along x a model misses, and with what shape.

The residuals of a fit are regressed (generalised least squares under the
fitted noise) on a flexible, shape-agnostic basis: piecewise-linear hat
functions of the control variable, plus one offset per trial. The likelihood
ratio of that augmentation, with the noise re-estimated under it, measures how
much structure is left; its p-value comes from simulating pure noise from the
fitted noise model (a parametric bootstrap, which keeps the test valid under
strongly correlated noise where a chi-square reference is too liberal).
Rows where the smooth mismatch exceeds three pointwise standard errors form the
located regions.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from knotmech.diagnose.fitting import thinned_noise, thinned_rows
from knotmech.diagnose.stats import (
    NoiseModel,
    estimate_noise,
    hat_basis,
    ls_solve,
    monte_carlo_pvalue,
    require_finite,
)

_STEP = "locating the mismatch (smooth-basis regression of the residuals)"

__all__ = [
    "Mismatch",
    "flexible_mismatch",
    "smooth_mismatch",
    "regions_from_mask",
    "describe_shape",
    "counted_pvalue",
]


@dataclass
class Mismatch:
    """Result of :func:`flexible_mismatch`.

    Attributes
    ----------
    statistic : float
        Likelihood ratio of the flexible augmentation.
    p_value : float
        Bootstrap p-value of that statistic under pure noise.
    curve : (n,) array
        Smooth mismatch (data minus model) [units of y].
    z : (n,) array
        ``curve`` divided by its pointwise standard error.
    regions : list of (start, end)
        Located regions in units of x.
    shape : str
        Short description of the mismatch shape.
    """

    statistic: float
    p_value: float
    curve: np.ndarray
    z: np.ndarray
    regions: list
    shape: str


def _design(x, trial, n_knots):
    cols = [hat_basis(x, n_knots)]
    ids = np.unique(trial)
    if ids.size > 1:
        cols.append((trial[:, None] == ids[None, 1:]).astype(float))
    return np.column_stack(cols)


def _whiten_cols(noise, sd, starts, cols):
    u = cols / sd[:, None]
    e = np.empty_like(u)
    c = np.sqrt(1.0 - noise.rho**2)
    e[1:] = (u[1:] - noise.rho * u[:-1]) / c
    e[starts] = u[starts]
    return e


def _augment(resid, mean, noise: NoiseModel, starts, design, given_sigma):
    ll0 = noise.loglik(resid, mean, starts)
    nz = noise
    sd = nz.sd(mean)
    xw = _whiten_cols(nz, sd, starts, design)
    rw = nz.whiten(resid, sd, starts)
    coef = ls_solve(xw, rw, step=_STEP)
    nz = estimate_noise(resid - design @ coef, mean, starts, given_sigma=given_sigma)
    ll1 = nz.loglik(resid - design @ coef, mean, starts)
    return 2.0 * (ll1 - ll0), coef, nz


def flexible_mismatch(
    x,
    resid,
    mean,
    noise: NoiseModel,
    starts,
    trial,
    *,
    given_sigma=None,
    n_knots=10,
    rng=None,
    decide_at=0.01,
) -> Mismatch:
    """Test residuals for structure and locate it (see module docstring).

    Parameters
    ----------
    x, resid, mean : (n,) arrays
        Control variable, residuals ``y - f`` and the fitted mean.
    noise : NoiseModel
        The fit's noise model (the null).
    starts, trial : (n,) arrays
        Trial starts (bool) and ids.
    n_knots : int
        Hat functions over the range of x.
    rng : numpy Generator
    """
    rng = np.random.default_rng(0) if rng is None else rng
    design = _design(x, trial, n_knots)
    stat, coef, nz = _augment(resid, mean, noise, starts, design, given_sigma)

    # long recordings: the pure-noise draws are recordings of every k-th row
    rows, k = thinned_rows(starts)
    b_noise, b_mean, b_starts = thinned_noise(noise, rows, k), mean[rows], starts[rows]
    b_gs = None if given_sigma is None else given_sigma[rows]
    b_design = design if k == 1 else _design(x[rows], trial[rows], n_knots)

    def draw(m):
        out = np.empty(m)
        for i in range(m):
            r = b_noise.sample(b_mean, b_starts, rng)
            n0 = estimate_noise(r, b_mean, b_starts, given_sigma=b_gs)
            out[i] = _augment(r, b_mean, n0, b_starts, b_design, b_gs)[0]
        return out

    p, _ = monte_carlo_pvalue(stat, draw, batches=(19, 40, 80), decide_at=decide_at)
    xw = _whiten_cols(nz, nz.sd(mean), starts, design)
    return _located(x, design, coef, xw, stat, p)


def _located(x, design, coef, xw, stat, p) -> Mismatch:
    """The fitted mismatch curve ``design @ coef``, its pointwise z-scores under the
    whitened design ``xw``, and the regions where |z| > 3."""
    curve = design @ coef
    require_finite(_STEP, xw, curve)
    gram = xw.T @ xw
    require_finite(_STEP, gram)
    cov = np.linalg.pinv(gram)
    se = np.sqrt(np.maximum(np.einsum("ij,jk,ik->i", design, cov, design), 1e-300))
    z = curve / se
    mask = np.abs(z) > 3.0
    regions = regions_from_mask(x, mask)
    return Mismatch(float(stat), float(p), curve, z, regions, describe_shape(x, curve, mask))


def _gls_basis(resid, mean, noise, starts, design):
    sd = noise.sd(mean)
    xw = _whiten_cols(noise, sd, starts, design)
    rw = noise.whiten(resid, sd, starts)
    return ls_solve(xw, rw, step=_STEP), xw


def _smooth_fit(resid, mean, starts, design, given_sigma):
    """Basis coefficients and the noise model estimated with the basis in the mean."""
    coef = ls_solve(design, resid, step=_STEP)
    nz = estimate_noise(resid - design @ coef, mean, starts, given_sigma=given_sigma)
    for _ in range(2):
        coef, _ = _gls_basis(resid, mean, nz, starts, design)
        nz = estimate_noise(resid - design @ coef, mean, starts, given_sigma=given_sigma)
    coef, xw = _gls_basis(resid, mean, nz, starts, design)
    stat = 2.0 * (nz.loglik(resid - design @ coef, mean, starts) - nz.loglik(resid, mean, starts))
    return stat, coef, nz, xw


def smooth_mismatch(
    x,
    resid,
    mean,
    starts,
    trial,
    *,
    given_sigma=None,
    n_knots=5,
    rng=None,
    decide_at=0.005,
    counted=False,
) -> Mismatch:
    """Second structure test: a coarse smooth basis with the noise estimated under it.

    Under strongly correlated noise the noise model of the fit absorbs a broad
    mismatch into a lag-one correlation near 1, so that :func:`flexible_mismatch`
    (whose null keeps that noise) no longer sees it. Here the noise is estimated
    with ``n_knots`` hat functions (plus one offset per trial) in the mean, the
    likelihood ratio of the basis is taken under that common noise model, and its
    null distribution is simulated from that noise model (pure noise, the whole
    procedure repeated on each draw). Located regions as in
    :func:`flexible_mismatch` (smooth mismatch beyond three pointwise standard errors).

    Parameters are those of :func:`flexible_mismatch` (without the null noise model);
    ``counted=True``: the p-value is counted only (:func:`counted_pvalue`, up to
    ``3/decide_at`` draws), no fitted tail.

    Notes
    -----
    :func:`knotmech.diagnose.diagnose` runs it (5 hat functions, at ``alpha``) only on a
    recording the noise floor would call ``undetermined``, with at least 20 rows per hat
    function (``engine.UNDETERMINED_SMOOTH_KNOTS``, ``UNDETERMINED_ROWS_PER_KNOT``): there
    it turns the verdict into ``unexplained``. Its size on all recordings, measured
    before that restriction (issue 5, trial
    ``validation.concealed_effects.smooth_trial_one``: run after the engine's own
    test, at ``alpha / 2 = 0.005``, when the verdict is not already ``unexplained``).
    On the full-table seeds it lifts ``unexplained`` on out-of-catalogue shapes under
    AR(1) rho = 0.9 noise from 2/48 to 24/48 (capstan 0 -> 11/16, pinch 0 -> 11/16,
    tension 2 -> 2/16), leaves white-noise recovery at >= 3 sd unchanged (309/324;
    AR(1) effects at >= 3 sd 139 -> 138/162), but its
    size is not reliably at the nominal 0.5 % under AR(1) noise: 4/299 (1.3 %) on
    fresh AR(1) nulls (all four pinch), and on the table's 240 nulls it adds 0 or 2
    false ``unexplained`` depending on the bootstrap stream (two nulls at p = 0.001
    to 0.003 in one stream), beyond the adoption rule (at most one more).
    """
    rng = np.random.default_rng(0) if rng is None else rng
    design = _design(x, trial, n_knots)
    stat, coef, nz, xw = _smooth_fit(resid, mean, starts, design, given_sigma)

    def draw(m):
        out = np.empty(m)
        for i in range(m):
            r = nz.sample(mean, starts, rng)
            out[i] = _smooth_fit(r, mean, starts, design, given_sigma)[0]
        return out

    if counted:
        p, _ = counted_pvalue(stat, draw, max_draws=int(np.ceil(3.0 / decide_at)))
    else:
        p, _ = monte_carlo_pvalue(stat, draw, batches=(19, 40, 80), decide_at=decide_at)
    return _located(x, design, coef, xw, stat, p)


def counted_pvalue(observed: float, draw, *, max_draws: int = 300, stop_after: int = 5):
    """Sequential Monte Carlo p-value, by counting only (Besag & Clifford 1991).

    Draws ``draw(m)`` in batches until ``stop_after`` simulated statistics reach
    ``observed`` (then ``p = stop_after / B``: clearly not small) or ``max_draws`` are
    drawn (then ``p = (1 + k)/(B + 1)``, Davison & Hinkley 1997 eq. 4.11). No tail is
    fitted, so ``p`` is never below ``1/(max_draws + 1)``.

    Returns
    -------
    p : float
    n_draws : int
    """
    sims = np.empty(0)
    while sims.size < max_draws:
        m = min(max(19, sims.size), max_draws - sims.size)
        sims = np.concatenate([sims, np.asarray(draw(m), dtype=float)])
        k = int(np.sum(sims >= observed))
        if k >= stop_after:
            return float(k / sims.size), int(sims.size)
    k = int(np.sum(sims >= observed))
    return float((1 + k) / (sims.size + 1)), int(sims.size)


def regions_from_mask(x, mask) -> list:
    """Contiguous (in sorted x) runs of ``mask`` as [(start, end)], short gaps bridged."""
    if not np.any(mask):
        return []
    order = np.argsort(x, kind="stable")
    xs, ms = x[order], mask[order]
    n = xs.size
    gap = max(1, n // 50)
    idx = np.flatnonzero(ms)
    runs = []
    a = b = idx[0]
    for i in idx[1:]:
        if i - b <= gap + 1:
            b = i
        else:
            runs.append((a, b))
            a = b = i
    runs.append((a, b))
    return [(float(xs[a]), float(xs[b])) for a, b in runs]


def describe_shape(x, curve, mask) -> str:
    """A few words on the mismatch shape: where it sits and its sign."""
    if not np.any(mask):
        return "no located mismatch"
    lo, hi = float(np.min(x)), float(np.max(x))
    span = hi - lo or 1.0
    xm = x[mask]
    a, b = (float(np.min(xm)) - lo) / span, (float(np.max(xm)) - lo) / span
    sign = "excess" if np.mean(curve[mask]) > 0 else "deficit"
    if b - a > 0.8:
        return f"global {sign} (a rate or level error over the whole range)"
    if a < 0.15:
        return f"{sign} at low x (an intercept or offset)"
    if b > 0.85:
        return f"{sign} at high x (a bend)"
    return f"localized {sign} in the interior (a peak or a step)"
