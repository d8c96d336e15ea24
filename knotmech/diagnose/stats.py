r"""Noise models, whitening, likelihoods and Monte Carlo p-values.

The noise of a recording is modelled as

.. math::
    y_i - f_i = \sigma_i z_i,\qquad \sigma_i = s\,(1 + g\,|f_i|/f_\mathrm{ref}),\qquad
    z_i = \rho z_{i-1} + \sqrt{1-\rho^2}\,e_i,\quad e_i \sim N(0, 1),

a stationary AR(1) process of unit variance (restarted at every trial start),
scaled by a standard deviation that is constant (``g = 0``) or grows with the
signal. ``s``, ``g`` and ``rho`` are estimated by maximum likelihood from the
residuals (closed-form profile in ``s``, grids in ``rho`` and ``g``). When a
recording carries a ``sigma`` column, :math:`\sigma_i` is taken from it and only
``rho`` is estimated.

Whitening maps residuals to the innovations :math:`e_i` (unit variance and
independent under the model), so that least squares on whitened residuals is
generalised least squares and likelihood ratios stay meaningful under
correlated noise (Box, Jenkins & Reinsel, *Time Series Analysis*, ch. 7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy import signal, stats

from knotmech.errors import DiagnoseError

__all__ = [
    "require_finite",
    "NoiseModel",
    "estimate_noise",
    "trial_starts",
    "monte_carlo_pvalue",
    "wilson_interval",
    "hat_basis",
    "ls_solve",
]

_RHO_GRID = np.concatenate([np.linspace(-0.4, 0.9, 53), np.linspace(0.905, 0.985, 17)])
_G_GRID = np.array([0.0, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0])


def trial_starts(trial: np.ndarray) -> np.ndarray:
    """Boolean mask of rows that start an AR(1) segment (first row, trial changes)."""
    starts = np.ones(trial.size, dtype=bool)
    starts[1:] = trial[1:] != trial[:-1]
    return starts


@dataclass(frozen=True)
class NoiseModel:
    """Heteroscedastic AR(1) noise (see the module docstring).

    Attributes
    ----------
    scale : float
        ``s`` [units of y]; 1 when ``given_sigma`` is used.
    growth : float
        ``g`` (0: constant noise).
    rho : float
        Lag-one correlation of consecutive rows.
    fref : float
        Reference signal level ``f_ref`` (max |baseline|) [units of y].
    given_sigma : (n,) array or None
        Per-row standard deviation from the file's ``sigma`` column.

    Raises
    ------
    DiagnoseError
        ``scale`` or ``fref`` not finite and positive, ``growth`` not finite and
        non-negative, or ``given_sigma`` not finite and positive in every row: :meth:`sd`
        would be zero or not finite, and every whitening, likelihood and located
        z-score a silent NaN (issue 26: a zero high-frequency noise level once reached
        the white model of the noise-floor check).
    """

    scale: float
    growth: float
    rho: float
    fref: float
    given_sigma: np.ndarray | None = None

    def __post_init__(self):
        ok = (
            math.isfinite(self.scale)
            and self.scale > 0
            and math.isfinite(self.fref)
            and self.fref > 0
            and math.isfinite(self.growth)
            and self.growth >= 0
        )
        if not ok:
            raise DiagnoseError(
                f"noise model: scale {self.scale!r}, growth {self.growth!r} and reference "
                f"level {self.fref!r} must be finite, scale and level > 0; the recording's "
                "noise is zero or not finite, so the diagnosis has no noise level to judge by"
            )
        gs = self.given_sigma
        if gs is not None and not (np.all(gs > 0) and np.all(np.isfinite(gs))):
            raise DiagnoseError("noise model: the sigma column must be finite and > 0 in every row")

    def sd(self, mean: np.ndarray) -> np.ndarray:
        """Marginal standard deviation per row [units of y]."""
        if self.given_sigma is not None:
            return self.given_sigma
        return self.scale * (1.0 + self.growth * np.abs(mean) / self.fref)

    def whiten(self, resid: np.ndarray, sd: np.ndarray, starts: np.ndarray) -> np.ndarray:
        """Innovations ``e`` of residuals (unit variance, independent under the model)."""
        u = resid / sd
        e = np.empty_like(u)
        c = np.sqrt(1.0 - self.rho**2)
        np.multiply(u[:-1], -self.rho, out=e[1:])
        e[1:] += u[1:]
        e[1:] /= c
        e[starts] = u[starts]
        return e

    def loglik(self, resid: np.ndarray, mean: np.ndarray, starts: np.ndarray) -> float:
        """Gaussian log-likelihood of the residuals under this noise model."""
        sd = self.sd(mean)
        e = self.whiten(resid, sd, starts)
        n_rest = resid.size - int(starts.sum())
        return float(
            -0.5 * np.dot(e, e)
            - np.sum(np.log(sd))
            - 0.5 * n_rest * np.log(1.0 - self.rho**2)
            - 0.5 * resid.size * np.log(2 * np.pi)
        )

    def sample(self, mean: np.ndarray, starts: np.ndarray, rng: np.random.Generator):
        """One draw of the noise (same shape as ``mean``)."""
        e = rng.standard_normal(mean.size)
        x = np.sqrt(1.0 - self.rho**2) * e
        x[starts] = e[starts]
        idx = np.flatnonzero(starts)
        bounds = np.append(idx, mean.size)
        z = np.empty_like(e)
        for a, b in zip(bounds[:-1], bounds[1:], strict=True):
            z[a:b] = signal.lfilter([1.0], [1.0, -self.rho], x[a:b])
        return self.sd(mean) * z

    def thinned(self, k: int, given_sigma=None) -> NoiseModel:
        """This noise on every ``k``-th row (AR(1): correlation ``rho**k``), with the kept
        rows' ``given_sigma``."""
        return replace(self, rho=float(self.rho**k), given_sigma=given_sigma)

    def describe(self) -> dict:
        out = {"rho": round(self.rho, 4)}
        if self.given_sigma is None:
            out["sigma"] = float(self.scale)
            out["growth"] = float(self.growth)
        else:
            out["sigma"] = "column"
        return out


def _profile(u: np.ndarray, starts: np.ndarray, rho: np.ndarray):
    """Sum of squared innovations S(rho) for unit-scale AR(1), vectorised over rho."""
    a = np.sum(u[starts] ** 2)
    rest = ~starts
    rest[0] = False
    cur = u[rest]
    prev = u[np.flatnonzero(rest) - 1]
    b, c, d = np.dot(cur, cur), np.dot(cur, prev), np.dot(prev, prev)
    return a + (b - 2 * rho * c + rho**2 * d) / (1 - rho**2), int(rest.sum())


def estimate_noise(
    resid: np.ndarray,
    mean: np.ndarray,
    starts: np.ndarray,
    *,
    given_sigma: np.ndarray | None = None,
    heteroscedastic: bool = True,
) -> NoiseModel:
    """Maximum-likelihood noise model of residuals.

    Parameters
    ----------
    resid, mean : (n,) arrays
        Residuals ``y - f`` and the fitted mean ``f`` [units of y].
    starts : (n,) bool array
        Rows that start a trial (see :func:`trial_starts`).
    given_sigma : (n,) array, optional
        Per-row standard deviation from the recording; then only ``rho`` is fitted.
    heteroscedastic : bool
        Allow ``g > 0`` (noise growing with the signal); a BIC penalty of
        ``log(n)/2`` is charged for it.

    Returns
    -------
    NoiseModel
    """
    n = resid.size
    rho = _RHO_GRID
    fref = float(np.max(np.abs(mean))) or 1.0
    if given_sigma is not None:
        s_rho, n_rest = _profile(resid / given_sigma, starts, rho)
        ll = -0.5 * s_rho - 0.5 * n_rest * np.log(1 - rho**2)
        j = int(np.argmax(ll))
        return NoiseModel(1.0, 0.0, float(rho[j]), fref, given_sigma)
    grid = _G_GRID if heteroscedastic else _G_GRID[:1]
    # per growth g: u = resid / h, h = 1 + g |f| / fref; sums of u^2 over trial starts (a),
    # over the other rows (b), of u_i u_{i-1} (c) and u_{i-1}^2 (d) over the other rows,
    # one g at a time with dot products (no (len(grid), n) arrays: 1e6-row recordings)
    rest = (~starts).astype(float)
    first = starts.astype(float)
    rel = np.abs(mean) / fref
    a, b, c, d, logh = (np.empty(grid.size) for _ in range(5))
    for i, g in enumerate(grid):
        if g == 0.0:
            u, logh[i] = resid, 0.0
        else:
            h = 1.0 + g * rel
            u = resid / h
            logh[i] = np.sum(np.log(h))
        uu = u * u
        a[i], b[i] = uu @ first, uu @ rest
        c[i], d[i] = (u[1:] * u[:-1]) @ rest[1:], uu[:-1] @ rest[1:]
    r2 = rho[None, :]
    s_rho = a[:, None] + (b[:, None] - 2 * r2 * c[:, None] + r2**2 * d[:, None]) / (1 - r2**2)
    s_rho = np.maximum(s_rho, 1e-300)
    n_rest = int(n - starts.sum())
    ll = (
        -0.5 * n * np.log(s_rho / n)
        - logh[:, None]
        - 0.5 * n_rest * np.log(1 - r2**2)
        - np.where(grid > 0, 0.5 * np.log(n), 0.0)[:, None]
    )
    i, j = np.unravel_index(int(np.argmax(ll)), ll.shape)
    g, r, s = float(grid[i]), float(rho[j]), float(np.sqrt(s_rho[i, j] / n))
    # floor: noise-free data (exact numbers) would make the whitening singular
    s = max(s, 1e-7 * fref)
    return NoiseModel(s, g, r, fref, None)


#: two-sided normal quantile of the Monte Carlo decision's interval (99 %)
_Z_UNDECIDED = 2.5758293035489


def monte_carlo_pvalue(
    observed: float, draw, *, batches=(9, 30, 60, 100), decide_at=0.01, extend=()
):
    """Parametric-bootstrap p-value with early stopping and a fitted tail.

    ``draw(m)`` returns ``m`` statistics simulated under the null. Draws come in
    batches; after each batch we stop when the answer is clear: at least 5
    simulated statistics exceed ``observed`` (p clearly large), or the
    scaled-chi-square tail fitted to the draws puts ``p`` below ``decide_at/20``
    or above ``20*decide_at`` (after the first, small batch: only above
    ``50*decide_at``; a tail fitted to nine draws is not trusted on the small side).
    With no exceedance the p-value is the fitted tail (a ``a chi2_nu`` matched to
    the mean and variance of the positive part of the draws, Satterthwaite 1946; a
    normal tail when many draws are < 0, as for the non-nested ``finite_thickness``
    comparison; when most draws sit on the boundary (likelihood ratio 0), the share
    of positive draws times a scaled chi-square fitted to them, chi2_2 with fewer
    than ten), never above ``1/(B+1)``; otherwise ``(1 + #exceed) / (B + 1)``
    (Davison & Hinkley 1997, eq. 4.11).

    ``extend`` (batch sizes, default none): when every batch of ``batches`` was drawn
    without a decision and the draws still cannot tell the exceedance probability from
    ``decide_at`` (``decide_at`` inside the 99 % Wilson interval of ``k/B``, ``k``
    exceedances of ``B`` draws), draw these batches too, one at a time, until it can.
    With ``decide_at (B + 1)`` near 1 a test rejects only when no draw exceeds, and a
    real effect of exceedance probability ``decide_at/2`` is missed about 40 % of the
    time: the power a Monte Carlo test loses to a small ``B`` (Marriott 1979, Appl.
    Statist. 28, 75-77); drawing on only while undecided keeps the cost of the clear
    cases (sequential Monte Carlo p-values: Besag & Clifford 1991, Biometrika 78,
    301-304; drawing more only when a small B leaves the decision in doubt: Davidson &
    MacKinnon 2000, Econometric Reviews 19, 55-68). The decision after the last batch
    drawn is as above. The level is kept: the interval's upper end for no exceedance,
    ``z^2/(B + z^2)``, is above ``decide_at`` at every early look while ``decide_at <
    0.0094`` (``B <= 699``), so an early stop never rejects, and a rejection after all
    999 draws is one of the fixed 999-draw test, ``(1 + k)/1000 < decide_at``, of size
    below ``decide_at``; the tail-fit decisions of the first batches are unchanged.

    Returns
    -------
    p : float
    n_draws : int
    """
    sims = np.empty(0)
    for i, m in enumerate(batches):
        sims = np.concatenate([sims, np.asarray(draw(m), dtype=float)])
        n_exceed = int(np.sum(sims >= observed))
        p_tail = _tail_p(observed, sims)
        if n_exceed >= 5:
            break
        # the first, small batch decides only that p is large: a tail fitted to nine
        # draws may be off by many orders of magnitude on the small side (four positive
        # draws of 0.1-0.5 gave p = 1e-15 for a likelihood ratio of 8)
        if i == 0:
            if p_tail > 50.0 * decide_at:
                break
        elif p_tail < decide_at / 20.0 or p_tail > 20.0 * decide_at:
            break
    else:
        sims = _extend_undecided(observed, draw, sims, decide_at, extend)
        n_exceed = int(np.sum(sims >= observed))
        p_tail = _tail_p(observed, sims)
    b = sims.size
    if n_exceed == 0:
        return float(min(p_tail, 1.0 / (b + 1))), b
    return float((1 + n_exceed) / (b + 1)), b


def _extend_undecided(observed, draw, sims, decide_at, extend):
    """More draws, batch by batch of ``extend``, while ``decide_at`` lies inside the
    99 % Wilson interval of the exceedance share (see :func:`monte_carlo_pvalue`)."""
    for m in extend:
        lo, hi = wilson_interval(int(np.sum(sims >= observed)), sims.size, _Z_UNDECIDED)
        if not lo <= decide_at <= hi:
            break
        sims = np.concatenate([sims, np.asarray(draw(m), dtype=float)])
    return sims


def _tail_p(observed: float, sims: np.ndarray) -> float:
    pos = np.maximum(sims, 0.0)
    m, v = float(np.mean(pos)), float(np.var(pos))
    if m <= 0 or v <= 0 or np.mean(sims > 0) < 0.2:
        if np.mean(sims < -1e-6) >= 0.2:
            # statistic mostly < 0 under the null (non-nested models): normal tail
            sd = float(np.std(sims))
            if sd <= 0:
                return 0.0 if observed > float(np.mean(sims)) else 1.0
            return float(stats.norm.sf((observed - float(np.mean(sims))) / sd))
        # nested, most draws on the boundary (likelihood ratio 0): a mixture, the share
        # of positive draws (plus one) times a scaled chi-square fitted to them (chi2_2
        # when fewer than ten: a tail fitted to a few nonzero draws would be far too
        # liberal)
        p_pos = sims[sims > 0]
        w = (p_pos.size + 1) / (sims.size + 1)
        a, nu = 1.0, 2.0
        if p_pos.size >= 10 and np.var(p_pos) > 0:
            a = float(np.var(p_pos)) / (2 * float(np.mean(p_pos)))
            nu = max(float(np.mean(p_pos)) / a, 1.0)
        return float(min(w * stats.chi2.sf(observed / a, nu), 1.0))
    a = v / (2 * m)
    nu = m / a
    return float(stats.chi2.sf(observed / a, nu))


def wilson_interval(k: int, n: int, z: float = 1.959964) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion ``k/n`` (Wilson 1927)."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    den = 1 + z**2 / n
    centre = (p + z**2 / (2 * n)) / den
    half = z * np.sqrt(p * (1 - p) / n + z**2 / (4 * n**2)) / den
    return float(max(0.0, centre - half)), float(min(1.0, centre + half))


def hat_basis(x: np.ndarray, n_knots: int) -> np.ndarray:
    """Piecewise-linear hat functions on equally spaced knots over the range of ``x``."""
    lo, hi = float(np.min(x)), float(np.max(x))
    knots = np.linspace(lo, hi, n_knots)
    h = (hi - lo) / (n_knots - 1) if hi > lo else 1.0
    return np.clip(1.0 - np.abs(x[:, None] - knots[None, :]) / h, 0.0, None)


def require_finite(step: str, *arrays) -> None:
    """Raise :class:`~knotmech.errors.DiagnoseError` unless every array is finite.

    Called before every factorisation (``pinv``, ``lstsq``, ``least_squares``): LAPACK
    on NaN or infinity returns garbage, raises ``LinAlgError`` or, in some OpenBLAS
    builds, never returns (``pinv`` of a matrix holding one ``inf``).

    Parameters
    ----------
    step : str
        What the engine was doing, for the message (``"locating the mismatch"``).
    *arrays : array_like
        The matrices and vectors about to be factorised or solved with.
    """
    for a in arrays:
        if not np.all(np.isfinite(a)):
            raise DiagnoseError(
                f"{step}: the numbers overflow (NaN or infinity in the system to solve); "
                "the recording's values or metadata are too extreme for this diagnosis"
            )


def ls_solve(design: np.ndarray, target: np.ndarray, *, step: str = "least squares") -> np.ndarray:
    """Least-squares coefficients of a tall, narrow system via scaled normal equations.

    LAPACK's tall least-squares drivers are slow in some OpenBLAS builds; a
    column-scaled normal-equation solve with a pseudo-inverse of the small Gram
    matrix is accurate enough for the well-conditioned bases used here.

    Raises
    ------
    DiagnoseError
        NaN or infinity in ``design``, ``target`` or the Gram matrix (``step`` names
        the caller's step in the message).
    """
    require_finite(step, design, target)
    with np.errstate(over="ignore", invalid="ignore"):
        norms = np.sqrt(np.sum(design * design, axis=0))
    require_finite(step, norms)
    norms = np.where(norms > 0, norms, 1.0)
    xs = design / norms
    gram = xs.T @ xs
    require_finite(step, gram)
    coef = np.linalg.pinv(gram, rcond=1e-12, hermitian=True) @ (xs.T @ target)
    return coef / norms
