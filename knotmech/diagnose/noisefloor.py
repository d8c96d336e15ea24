r"""The noise floor a verdict of ``none`` must meet, and outliers.

The engine's noise model (:mod:`knotmech.diagnose.stats`) is fitted to the residual of
the model under test; a smooth misfit can then be folded into a lag-one correlation
near 1 and the remainder called noise. This module judges the final remainder against
a noise level that a smooth misfit barely affects: the **high-frequency level** from
second differences of consecutive rows (rows sorted by the control variable within
each trial),

.. math::
    \hat\sigma_\mathrm{hf} = \frac{1.4826\,\mathrm{MAD}(\Delta^2 r)}{\sqrt 6},

exact for white noise (:math:`\mathrm{var}\,\Delta^2 e = 6\sigma^2`) and robust to
outliers (one bad row touches three second differences) and to a smooth mismatch (its
second difference is its curvature times the squared row spacing; von Neumann 1941,
Rice 1984 use first differences the same way).

Three statistics of the remainder ``r`` of the would-be ``none`` model:

- ``level``: :math:`R = \mathrm{rms}(r)/\hat\sigma_\mathrm{hf}`; under white noise
  :math:`R \approx 1`. Its p-value is counted from white-noise draws of the same rows
  and trials, the statistic recomputed on each (the estimate's own scatter included);
  beyond 20 000 rows a normal tail whose mean and sd are measured on 20 000-row draws
  (sd scaled by the square root of the row ratio).
  AR(1) noise of lag-one correlation :math:`\rho` gives
  :math:`R^2 \approx 3/((1-\rho)(3-\rho))`, so :math:`R` names the correlation
  ``rho_needed`` = :math:`2 - \sqrt{1 + 3/R^2}` that noise would need to explain it.
- ``model``: the lag-one autocorrelation of the remainder's innovations under the
  final noise model (its own whitening); under a correct AR(1) model it is
  :math:`N(0, 1/m)` for m pairs. A smooth misfit folded into :math:`\rho \to 1` leaves
  innovations that are nearly first differences of white noise (autocorrelation -1/2).
- ``hf_white``: the lag-one autocorrelation of the first differences (winsorised at
  5 robust sd); white noise gives -1/2, AR(1) :math:`-(1-\rho)/2`, so a value at the
  white-noise level says the high-frequency noise is white and the excess of ``level``
  is structure; its one-sided p-value is counted from the same white draws.

:func:`noise_floor_verdict` turns them into ``none``, ``unexplained`` or
``undetermined`` (with the reason), see its docstring.

Outliers (:func:`find_outliers`): rows farther than :func:`outlier_threshold` noise sd
(4.5 up to 100 rows, 6 at 1e4; the larger of the high-frequency sd and its local value)
from all of their neighbours' references (the median of three rows each side, the lines
through four rows on either side; rows sorted by the control within each trial), at
most 5 % of the rows; the engine fits without them and reports them.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np
from scipy import ndimage, stats

from knotmech.diagnose.arnoise import ARFit, fit_ar
from knotmech.diagnose.powerlaw import BETA_RANGE, fit_power_law, power_law_draws
from knotmech.diagnose.recording import Recording
from knotmech.diagnose.ripple import (
    RIPPLE_MAX_ROWS,
    ar_draws,
    ripple_p_of_draws,
    ripple_p_value,
)
from knotmech.diagnose.stats import NoiseModel

__all__ = [
    "NoiseFloor",
    "noise_floor",
    "noise_floor_verdict",
    "find_outliers",
    "without_rows",
    "outliers_of_remainder",
    "hf_sigma",
    "N_EFF_MIN",
    "NONE_LEVEL_MAX",
    "SHORT_ROWS",
    "short_recording_verdict",
    "OUTLIER_SD",
    "outlier_threshold",
    "HF_SD_FLOOR",
]

#: the fewest independent stretches, n (1 - rho)/(1 + rho), at which a fitted AR(1)
#: model may be told from a smooth mismatch (fewer: ``unexplained``/``undetermined``):
#: half the 10 knots of the structure test (:func:`~knotmech.diagnose.locate.flexible_mismatch`).
#: Measured: smooth misfits folded into the noise leave 3.0-3.7 (issue 14's nips of 30
#: and 100 sd at 240 rows), AR(1) nulls at rho = 0.9 and 200-240 rows 7.8-8.9
N_EFF_MIN = 5.0
#: a remainder whose rms exceeds this many high-frequency sd is never ``none``: no noise
#: model fitted to the recording may absorb a misfit that large (issue 14: 5-16x the
#: noise were called ``none`` under a fitted lag-one correlation of 0.95-0.985)
NONE_LEVEL_MAX = 10.0
#: fewest rows for :attr:`NoiseFloor.p_consistent` (on 40 rows the synthetic capstan-pull
#: template, a null whose noise grows with the signal, gave p = 0.004)
CONSISTENT_ROWS = 100
#: below this many rows (and without a ``sigma`` column) the noise level is estimated
#: from the very rows the fit explains: the second differences of 8 rows of a ripple
#: are the ripple itself (30-sd ripples of 8 rows came out ``none`` 12/12, of 20 rows
#: 3/12), so a would-be ``none`` is ``undetermined``
SHORT_ROWS = 30
#: an outlier lies farther than this many noise sd from its neighbours (up to 100
#: rows; more beyond, see :func:`outlier_threshold`)
OUTLIER_SD = 4.5
#: most rows of the running noise scale of :func:`find_outliers`
_LOCAL_ROWS = 201
#: rows on each side through which :func:`find_outliers` draws a line
_SIDE_ROWS = 4
#: most rows called outliers (a larger share is not outliers but the data)
OUTLIER_SHARE = 0.05
#: white-noise draws calibrating ``level`` and ``hf_white``
_DRAWS = 400
#: up to this many rows the p-values are counted from full-size white draws
_N_COUNTED = 20_000
_MAD = 1.482602218505602
#: the high-frequency sd used in place of a zero one, relative to the model's largest
#: absolute value: the floor of the engine's noise model
#: (:func:`~knotmech.diagnose.stats.estimate_noise`), below which data count as noise-free
HF_SD_FLOOR = 1e-7


def _order(x: np.ndarray, trial: np.ndarray) -> np.ndarray:
    """Row order: by trial (first appearance), then by the control variable."""
    _, first = np.unique(trial, return_index=True)
    rank = np.empty(first.size, int)
    rank[np.argsort(first)] = np.arange(first.size)
    t = rank[np.unique(trial, return_inverse=True)[1]]
    return np.lexsort((x, t))


def _within(values: np.ndarray, seg: np.ndarray, lag: int) -> np.ndarray:
    """Differences of order ``lag`` within segments (rows sorted, ``seg`` their trial)."""
    d = values
    s = seg
    for _ in range(lag):
        same = s[1:] == s[:-1]
        d = (d[1:] - d[:-1])[same] if d.ndim == 1 else (d[1:] - d[:-1])[same]
        s = s[1:][same]
    return d


def _hf_sd(r2d: np.ndarray, seg: np.ndarray) -> np.ndarray:
    """High-frequency sd of each column of ``r2d`` (rows sorted; MAD of 2nd differences)."""
    same = (seg[1:] == seg[:-1])[1:] & (seg[1:-1] == seg[:-2])
    d2 = (r2d[2:] - 2.0 * r2d[1:-1] + r2d[:-2])[same]
    med = np.median(d2, axis=0)
    return _MAD * np.median(np.abs(d2 - med), axis=0) / np.sqrt(6.0)


def hf_sigma(resid: np.ndarray, x: np.ndarray, trial: np.ndarray) -> float:
    """White-equivalent noise sd from second differences (see the module docstring).

    Parameters
    ----------
    resid : (n,) array
        Residuals (or the readings themselves) [units of y].
    x, trial : (n,) arrays
        Control variable and trial labels (rows are sorted by them first).

    Returns
    -------
    float
        :math:`1.4826\\,\\mathrm{MAD}(\\Delta^2 r)/\\sqrt 6` [units of y].
    """
    o = _order(x, trial)
    seg = np.unique(trial, return_inverse=True)[1][o]
    return float(_hf_sd(np.asarray(resid, float)[o][:, None], seg)[0])


def _d1_lag1(r2d: np.ndarray, seg: np.ndarray) -> np.ndarray:
    """Lag-one autocorrelation of first differences, winsorised at 5 robust sd, per column."""
    same = seg[1:] == seg[:-1]
    d1 = (r2d[1:] - r2d[:-1])[same]
    s1 = seg[1:][same]
    med = np.median(d1, axis=0)
    sc = _MAD * np.median(np.abs(d1 - med), axis=0)
    sc = np.where(sc > 0, sc, 1.0)
    d1 = np.clip(d1 - med, -5 * sc, 5 * sc)
    d1 = d1 - np.mean(d1, axis=0)
    pair = s1[1:] == s1[:-1]
    num = np.sum((d1[1:] * d1[:-1])[pair], axis=0)
    den = np.sum(d1 * d1, axis=0)
    return num / np.where(den > 0, den, 1.0)


def _white_draws(seg, draws, rng):
    """``level`` and ``hf_lag1`` of ``draws`` white-noise series laid out as ``seg``."""
    n = seg.size
    sims_level, sims_hf = [], []
    chunk = max(1, min(draws, 2_000_000 // max(n, 1)))
    done = 0
    while done < draws:
        b = min(chunk, draws - done)
        z = rng.standard_normal((n, b))
        sims_level.append(_level(z, seg))
        sims_hf.append(_d1_lag1(z, seg))
        done += b
    return np.concatenate(sims_level), np.concatenate(sims_hf)


def _rms(r2d: np.ndarray) -> np.ndarray:
    """Root mean square of each column."""
    return np.sqrt(np.mean(r2d * r2d, axis=0))


def _level(r2d: np.ndarray, seg: np.ndarray) -> np.ndarray:
    """rms / high-frequency sd of each column (rows sorted, ``seg`` their trial).

    A column whose high-frequency sd is zero (more than half of its second differences
    vanish: a piecewise-linear or constant column) carries no noise scale: its level is
    0 when the column is zero too, else infinite (every draw is below it), never a
    division by zero.
    """
    sd = _hf_sd(r2d, seg)
    rms = _rms(r2d)
    out = np.where(rms > 0, np.inf, 0.0)
    return np.divide(rms, sd, out=out, where=sd > 0)


@dataclass(frozen=True)
class NoiseFloor:
    """The remainder judged against the high-frequency noise (module docstring).

    Attributes
    ----------
    sigma_hf : float
        High-frequency noise sd [units of y].
    level : float
        rms(remainder) / sigma_hf.
    p_level : float
        P(level at least this large | white noise), counted (1 + k)/(B + 1).
    rho_needed : float
        Lag-one correlation an AR(1) noise would need to give ``level``.
    innovation_lag1 : float
        Lag-one autocorrelation of the innovations under the final noise model.
    p_model : float
        Two-sided normal p-value of ``innovation_lag1`` (0 under a correct model).
    hf_lag1 : float
        Lag-one autocorrelation of first differences (-1/2 for white noise).
    p_hf_white : float
        P(hf_lag1 at least this large | white noise), counted.
    n_eff : float
        n (1 - rho)/(1 + rho) of the final noise model's rho.
    n : int
        Rows used.
    ar : ARFit or None
        AR(p) fit of the standardised remainder (:mod:`knotmech.diagnose.arnoise`),
        the coloured-noise explanation tried when the AR(1) one fails.
    p_consistent : float
        P(hf_lag1 at most this | AR(1) noise of the correlation the level needs), on the
        remainder standardised by the noise model's sd profile (counted from draws; 1
        when that level is not above white, or below :data:`CONSISTENT_ROWS` rows).
        Small: the high frequencies are too white for any AR(1) noise that would explain
        the level, so the excess is structure (a narrow bump that a fitted correlation
        near 1 absorbs).
    p_ripple, p_ripple_ar : float
        P(a growing ripple explains at least this share of the standardised remainder |
        the final AR(1) noise model; | the AR(p) fit ``ar``)
        (:mod:`knotmech.diagnose.ripple`; 1 beyond its row limit). Small: that noise
        model would not produce the ripple, so it may not rescue a ``none``.
    p_consistent_ar : float
        As ``p_consistent``, counted from draws of the AR(p) fit ``ar`` itself (the
        model its rescue rests on): twice the smaller of P(hf_lag1 at most this) and
        P(level at least this), at most 1 (:func:`_p_consistent_model`; 1 when the
        fit is white or not stationary, or below :data:`CONSISTENT_ROWS` rows).
    beta : float or None
        Spectral exponent of a power law :math:`f^{-\beta}` fitted to the
        standardised remainder's high frequencies
        (:func:`~knotmech.diagnose.powerlaw.fit_power_law`);
        None below :data:`CONSISTENT_ROWS` rows or with too few ordinates.
    p_power_law : float
        As ``p_consistent_ar``, counted from power-law draws of exponent ``beta``
        (long-memory noise: its low-frequency wander is what raises ``level``); 0 when
        ``beta`` is None or outside :data:`~knotmech.diagnose.powerlaw.BETA_RANGE`.
    p_ripple_pl : float
        As ``p_ripple``, counted from those power-law draws (0 when not tried).
    hf_floored : bool
        The remainder's high-frequency sd was zero (noise-free, constant or quantised
        readings), and ``sigma_hf`` is :data:`HF_SD_FLOOR` times the model's largest
        absolute value instead.
    """

    sigma_hf: float
    level: float
    p_level: float
    rho_needed: float
    innovation_lag1: float
    p_model: float
    hf_lag1: float
    p_hf_white: float
    n_eff: float
    n: int
    ar: ARFit | None = None
    p_consistent: float = 1.0
    p_ripple: float = 1.0
    p_ripple_ar: float = 1.0
    p_consistent_ar: float = 1.0
    beta: float | None = None
    p_power_law: float = 0.0
    p_ripple_pl: float = 0.0
    hf_floored: bool = False

    def describe(self) -> dict:
        """JSON-ready numbers (3 significant digits); ``hf_floored`` only when True."""
        out = {
            k: (float(f"{v:.3g}") if isinstance(v, float) else v)
            for k, v in vars(self).items()
            if k != "ar" and not (k == "hf_floored" and not v)
        }
        if self.ar is not None:
            out["ar"] = self.ar.describe()
        return out


def noise_floor(
    resid: np.ndarray,
    x: np.ndarray,
    trial: np.ndarray,
    noise: NoiseModel,
    mean: np.ndarray,
    starts: np.ndarray,
    rng: np.random.Generator,
    *,
    draws: int = _DRAWS,
) -> NoiseFloor:
    """Judge a remainder against the high-frequency noise floor (module docstring).

    Parameters
    ----------
    resid, x, trial, mean : (n,) arrays
        Remainder ``y - f``, control variable, trial labels, model mean.
    noise : NoiseModel
        The final model's noise (for its innovations and rho).
    starts : (n,) bool array
        Trial starts in the recording's row order.
    rng : numpy Generator
        For the white-noise draws.
    draws : int
        White-noise draws calibrating ``level`` and ``hf_white``.

    Returns
    -------
    NoiseFloor
    """
    resid = np.asarray(resid, float)
    n = resid.size
    o = _order(x, trial)
    seg = np.unique(trial, return_inverse=True)[1][o]
    r = resid[o][:, None]
    sd, floored = _floored_hf_sd(r, seg, noise.fref)
    level = float(_rms(r)[0] / sd)
    hf_l1 = float(_d1_lag1(r, seg)[0])
    if n <= _N_COUNTED:
        sims_level, sims_hf = _white_draws(seg, draws, rng)
        p_level = (1 + int(np.sum(sims_level >= level))) / (draws + 1)
        p_hf = (1 + int(np.sum(sims_hf >= hf_l1))) / (draws + 1)
    else:
        # long recordings: both statistics are averages over n rows, normal to order
        # 1/sqrt(n); their mean and sd are measured on _N_COUNTED white rows (one segment)
        # and the sd scaled by sqrt(_N_COUNTED / n)
        sims_level, sims_hf = _white_draws(np.zeros(_N_COUNTED, int), min(draws, 200), rng)
        shrink = np.sqrt(_N_COUNTED / n)
        z_l = _log_level_z(level, sims_level, shrink)
        z_h = (hf_l1 - np.mean(sims_hf)) / (np.std(sims_hf) * shrink)
        p_level, p_hf = float(stats.norm.sf(z_l)), float(stats.norm.sf(z_h))
    rho_needed = _rho_needed(level)
    e = noise.whiten(resid, noise.sd(mean), starts)
    pair = ~starts[1:]
    a, b_ = e[1:][pair], e[:-1][pair]
    m = int(pair.sum())
    den = np.sqrt(np.sum(a * a) * np.sum(b_ * b_))
    inn = float(np.sum(a * b_) / den) if den > 0 and m > 2 else 0.0
    p_model = float(2.0 * stats.norm.sf(abs(inn) * np.sqrt(max(m, 1))))
    rho = float(noise.rho)
    n_eff = n * (1.0 - rho) / (1.0 + rho) if rho > 0 else float(n)
    # the coloured-noise explanation: an AR(p) of the standardised remainder, in row
    # (time) order, restarted at every trial
    ar = fit_ar(resid / noise.sd(mean), np.cumsum(starts))
    p_cons = 1.0
    if n >= CONSISTENT_ROWS:
        # standardised by the noise model's sd profile (noise that grows with the signal
        # raises the level over the recording's median sd without any structure)
        sdm = noise.sd(mean)
        u = (resid / (sdm / np.mean(sdm)))[o][:, None]
        p_cons = _p_consistent(u, seg, draws, rng)
    p_rip, p_rip_ar = _ripple_p(resid / noise.sd(mean), x, o, seg, noise, ar, rng)
    alt = _alternatives(resid / noise.sd(mean), x, o, seg, starts, ar, draws, rng)
    return NoiseFloor(
        sigma_hf=float(sd),
        level=level,
        p_level=float(p_level),
        rho_needed=rho_needed,
        innovation_lag1=inn,
        p_model=p_model,
        hf_lag1=hf_l1,
        p_hf_white=float(p_hf),
        n_eff=float(n_eff),
        n=int(n),
        ar=ar,
        p_consistent=float(p_cons),
        p_ripple=float(p_rip),
        p_ripple_ar=float(p_rip_ar),
        hf_floored=floored,
        **alt,
    )


def _floored_hf_sd(r2d: np.ndarray, seg: np.ndarray, fref: float) -> tuple[float, bool]:
    """The remainder's high-frequency sd; :data:`HF_SD_FLOOR` times ``fref`` when it is
    zero (or not finite).

    A zero high-frequency sd (more than half of the second differences vanish:
    noise-free, constant or coarsely quantised readings) is no noise level, and dividing
    by it made the level infinite and the white model of the engine's noise-floor check
    singular (issue 26). The floor is the one of the engine's own noise model
    (:func:`~knotmech.diagnose.stats.estimate_noise`): below it the data count as
    noise-free. A positive sd below the floor is kept (as before issue 26: flooring it
    too turned 8 of 653 extreme recordings, round-off remainders, from ``unexplained``
    or ``undetermined`` into ``none``).

    Returns
    -------
    sd : float
        The sd used [units of y].
    floored : bool
        True when the floor replaced the measured sd.
    """
    sd = float(_hf_sd(r2d, seg)[0])
    if sd > 0 and math.isfinite(sd):
        return sd, False
    return HF_SD_FLOOR * float(fref), True


def _log_level_z(level: float, sims_level: np.ndarray, shrink: float) -> float:
    """Normal score of log(level) against white draws' log-levels (long recordings); a
    zero level (a zero remainder) lies below every draw."""
    if not level > 0:
        return -math.inf
    ll = np.log(sims_level)
    return (np.log(level) - np.mean(ll)) / (np.std(ll) * shrink)


def _rho_needed(level: float) -> float:
    """Lag-one correlation AR(1) noise needs for ``level``: :math:`2 - \\sqrt{1 +
    3/R^2}` (module docstring), 1 in the limit of a huge level (no overflow of
    :math:`R^2`)."""
    big = max(level, 1.0)
    if big > 1e100:
        return 1.0
    return float(2.0 - np.sqrt(1.0 + 3.0 / big**2))


def _alternatives(u, x, o, seg, starts, ar, draws, rng) -> dict:
    """``p_consistent_ar``, ``beta``, ``p_power_law``, ``p_ripple_pl`` of
    :class:`NoiseFloor` (``u`` the standardised remainder in row order; below
    :data:`CONSISTENT_ROWS` rows the defaults: no power-law rescue)."""
    if u.size < CONSISTENT_ROWS:
        return {}
    us = np.asarray(u, float)[o][:, None]
    out = {}
    if ar is not None and ar.order > 0 and ar.root_modulus < 1.0:
        sims = _model_draws(seg, lambda sg, b: ar_draws(ar.phi, sg, b, rng), draws)
        out["p_consistent_ar"] = _p_consistent_model(us, seg, sims)
    fit = fit_power_law(u, starts)
    if fit is None:
        return out
    out["beta"] = float(fit.beta)
    lo, hi = BETA_RANGE
    if not lo <= fit.beta <= hi:
        return out
    sims = _model_draws(seg, lambda sg, b: power_law_draws(sg, fit.beta, b, rng), draws)
    out["p_power_law"] = _p_consistent_model(us, seg, sims)
    if u.size <= RIPPLE_MAX_ROWS:
        out["p_ripple_pl"] = ripple_p_of_draws(us[:, 0], _unit_control(x, o, seg), sims[2])
    else:
        out["p_ripple_pl"] = 1.0
    return out


def _unit_control(x, o, seg) -> np.ndarray:
    """The control variable mapped onto [0, 1] within each trial (rows sorted)."""
    xs = np.asarray(x, float)[o]
    t = np.empty_like(xs)
    for g in np.unique(seg):
        m = seg == g
        span = np.ptp(xs[m])
        t[m] = (xs[m] - xs[m].min()) / span if span > 0 else 0.0
    return t


def _model_draws(seg, draw, draws):
    """(level, hf_lag1, series) of ``draws`` draws ``draw(seg, draws)`` of a noise model
    laid out as ``seg``; beyond :data:`_N_COUNTED` rows 200 draws of one
    :data:`_N_COUNTED`-row series (``series`` None)."""
    if seg.size > _N_COUNTED:
        one = np.zeros(_N_COUNTED, int)
        z = draw(one, min(draws, 200))
        return _level(z, one), _d1_lag1(z, one), None
    z = draw(seg, draws)
    return _level(z, seg), _d1_lag1(z, seg), z


def _p_consistent_model(u, seg, sims) -> float:
    """Consistency of a standardised remainder ``u`` (rows sorted) with a noise model
    drawn in ``sims`` (:func:`_model_draws`): twice the smaller of P(hf_lag1 at most the
    remainder's) and P(level at least the remainder's), at most 1 (Bonferroni over the
    two one-sided tests). A narrow bump absorbed by a correlation near 1 is too white
    at high frequencies for that correlation, or too large for its level.
    """
    level = float(_level(u, seg)[0])
    hf = float(_d1_lag1(u, seg)[0])
    s_level, s_hf, z = sims
    if z is not None:
        b = s_hf.size
        p_hf = (1 + int(np.sum(s_hf <= hf))) / (b + 1)
        p_lev = (1 + int(np.sum(s_level >= level))) / (b + 1)
    else:  # long recordings: normal tails, sd scaled by sqrt(_N_COUNTED / n)
        shrink = np.sqrt(_N_COUNTED / seg.size)
        p_hf = float(stats.norm.cdf((hf - np.mean(s_hf)) / (np.std(s_hf) * shrink)))
        p_lev = float(stats.norm.sf(_log_level_z(level, s_level, shrink)))
    return float(min(1.0, 2.0 * min(p_hf, p_lev)))


def _ripple_p(u, x, o, seg, noise, ar, rng) -> tuple[float, float]:
    """(p_ripple, p_ripple_ar) of :class:`NoiseFloor` (``u`` the standardised remainder
    in row order, ``o`` the sorted order, ``seg`` the sorted rows' trials)."""
    if u.size > RIPPLE_MAX_ROWS:
        return 1.0, 1.0
    t = _unit_control(x, o, seg)
    us = np.asarray(u, float)[o]
    rho = float(noise.rho)
    p1 = ripple_p_value(us, t, seg, (rho,) if rho > 0 else (), rng)
    p_ar = ripple_p_value(us, t, seg, tuple(ar.phi), rng) if ar is not None else 1.0
    return p1, p_ar


def _ar1_draws(seg, rho, draws, rng):
    """``draws`` unit AR(1) series of lag-one correlation ``rho`` laid out as ``seg``
    (rows sorted, each trial its own stationary series): (n, draws)."""
    from scipy import signal

    n = seg.size
    out = np.empty((n, draws))
    bounds = np.flatnonzero(np.r_[True, seg[1:] != seg[:-1], True])
    burn = 100
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        e = rng.standard_normal((b - a + burn, draws))
        out[a:b] = signal.lfilter([1.0], [1.0, -rho], e, axis=0)[burn:]
    return out


def _p_consistent(u, seg, draws, rng) -> float:
    """See :attr:`NoiseFloor.p_consistent` (``u``: standardised remainder, rows sorted)."""
    level = float(_level(u, seg)[0])
    if not level > 1.0:
        return 1.0
    rho = _rho_needed(level)
    hf = float(_d1_lag1(u, seg)[0])
    n = seg.size
    if n <= _N_COUNTED:
        sims = _d1_lag1(_ar1_draws(seg, rho, draws, rng), seg)
        return (1 + int(np.sum(sims <= hf))) / (draws + 1)
    sims = _d1_lag1(_ar1_draws(np.zeros(_N_COUNTED, int), rho, min(draws, 200), rng),
                    np.zeros(_N_COUNTED, int))  # fmt: skip
    z = (hf - np.mean(sims)) / (np.std(sims) * np.sqrt(_N_COUNTED / n))
    return float(stats.norm.cdf(z))


def _ar_explains(nf: NoiseFloor, alpha: float) -> bool:
    """The AR(p) fit explains the remainder: the high-frequency noise itself is
    correlated (``p_hf_white < alpha``: white high-frequency noise leaves the excess to
    structure), its innovations are white (Ljung-Box ``p_white >= alpha``) and the
    slower of it and the engine's AR(1) model (:func:`_n_eff_coloured`) leaves at least
    :data:`N_EFF_MIN` independent stretches."""
    ar = nf.ar
    return (
        ar is not None
        and nf.p_hf_white < alpha
        and ar.p_white >= alpha
        and _n_eff_coloured(nf) >= N_EFF_MIN
    )


def _n_eff_coloured(nf: NoiseFloor) -> float:
    """Independent stretches under the slowest decay either noise model implies.

    The smaller of the AR(p) count (largest root) and the AR(1) count of the final
    noise model: conditional least squares on a short remainder underestimates a
    correlation near 1 (40 rows of AR(1) noise at 0.97: AR(1) fitted at 0.6 by least
    squares, 0.875 by the engine's joint likelihood), and a count from the smaller
    correlation would let a short recording claim to tell noise from a smooth mismatch.
    """
    return float(min(nf.ar.n_eff, nf.n_eff)) if nf.ar is not None else nf.n_eff


def _rescued(nf: NoiseFloor, alpha: float) -> bool:
    """A noise model explains the remainder (:func:`noise_floor_verdict`): the final
    AR(1), the AR(p) fit or power-law noise, each only when its own draws are
    consistent with the level and the high frequencies (``p_consistent``,
    ``p_consistent_ar``, ``p_power_law``) and would produce the remainder's best
    ripple."""
    if (
        nf.p_consistent >= alpha
        and nf.p_model >= alpha
        and nf.n_eff >= N_EFF_MIN
        and nf.p_ripple >= alpha
    ):
        return True
    if _ar_explains(nf, alpha) and nf.p_consistent_ar >= alpha and nf.p_ripple_ar >= alpha:
        return True
    return _power_law_explains(nf, alpha)


def _power_law_explains(nf: NoiseFloor, alpha: float) -> bool:
    """Power-law (1/f-type) noise explains the remainder: the high-frequency noise is
    correlated (``p_hf_white < alpha``), its exponent lies in
    :data:`~knotmech.diagnose.powerlaw.BETA_RANGE`, and draws of that power law give
    the level and the high-frequency correlation (``p_power_law >= alpha``) and the
    remainder's best ripple (``p_ripple_pl >= alpha``)."""
    return nf.p_hf_white < alpha and nf.p_power_law >= alpha and nf.p_ripple_pl >= alpha


def _ripple(nf: NoiseFloor, alpha: float) -> bool:
    """A ripple no candidate noise model produces: both ripple tests reject."""
    return nf.p_ripple < alpha and nf.p_ripple_ar < alpha


def _rho_of(nf: NoiseFloor) -> float:
    """The final AR(1) noise model's rho, from its n_eff = n (1 - rho)/(1 + rho)."""
    r = nf.n_eff / nf.n
    return (1.0 - r) / (1.0 + r)


def _ar_failure(nf: NoiseFloor, alpha: float) -> str:
    """Why the AR(p) fit does not rescue the remainder (the first test it fails)."""
    ar = nf.ar
    if ar.p_white < alpha:
        return f"its innovations are not white (Ljung-Box p = {ar.p_white:.2g})"
    if _n_eff_coloured(nf) < N_EFF_MIN:
        return (
            f"it leaves only {_n_eff_coloured(nf):.3g} independent stretches (largest "
            f"root {ar.root_modulus:.3g}, AR(1) count {nf.n_eff:.3g}; at least "
            f"{N_EFF_MIN:g} needed): the recording is too short for its noise"
        )
    if nf.p_consistent_ar < alpha:
        return (
            f"it whitens the remainder (Ljung-Box p = {ar.p_white:.2g}), but its draws "
            f"do not give the level with these high frequencies (p = {nf.p_consistent_ar:.2g})"
        )
    return (
        f"a growing ripple explains more of the remainder than it produces "
        f"(p = {nf.p_ripple_ar:.2g})"
    )


def _power_law_failure(nf: NoiseFloor) -> str:
    """Why power-law noise does not rescue the remainder ('' when it was not tried)."""
    if nf.beta is None:
        return ""
    lo, hi = BETA_RANGE
    if not lo <= nf.beta <= hi:
        return (
            f"; power-law noise is not tried (high-frequency exponent {nf.beta:.2g}, "
            f"outside {lo:g}-{hi:g})"
        )
    return (
        f"; nor does power-law noise of the high frequencies' exponent {nf.beta:.2g} "
        f"(level and high frequencies p = {nf.p_power_law:.2g}, ripple p = {nf.p_ripple_pl:.2g})"
    )


def noise_floor_verdict(nf: NoiseFloor, alpha: float) -> tuple[str, str]:
    """``none``, ``unexplained`` or ``undetermined`` for a remainder, and the reason.

    - ``none`` when the remainder is within the white high-frequency noise
      (``p_level >= alpha``), or when the final AR(1) noise model describes its own
      innovations (``p_model >= alpha``) and leaves at least :data:`N_EFF_MIN`
      independent stretches, or when the high-frequency noise is correlated and an
      AR(p) model (order by BIC, bounded by the rows; :mod:`knotmech.diagnose.arnoise`)
      whitens the remainder and leaves at least :data:`N_EFF_MIN` stretches, or when
      the high-frequency noise is correlated as a power law :math:`f^{-\beta}` with
      :math:`\beta` in :data:`~knotmech.diagnose.powerlaw.BETA_RANGE` (long-memory,
      1/f-type noise: Whittle 1953, Robinson 1995) and at least
      :data:`CONSISTENT_ROWS` rows;
    - each rescue only when draws of its own noise model give the level and the high
      frequencies (AR(1) at the correlation the level needs: ``p_consistent``; the
      AR(p) fit: ``p_consistent_ar``; the power law: ``p_power_law``): a narrow bump
      absorbed by a fitted correlation near 1 is too white at high frequencies for that
      correlation (10-sd bumps of 120 rows on white noise give p_consistent
      0.0025-0.04). The AR(p) rescue was judged by the AR(1) draws until issue 26,
      which vetoed AR(2) nulls of phi (0.7, 0.15) (p_consistent 0.002-0.01);
    - no rescue when a growing ripple explains more of the remainder than that noise
      model produces (``p_ripple``, ``p_ripple_ar``, ``p_ripple_pl``;
      :mod:`knotmech.diagnose.ripple`);
      when both reject, ``unexplained`` (a deterministic ripple: stick-slip chatter on a
      short recording, issue 26);
    - otherwise ``unexplained`` when the high-frequency noise is white
      (``p_hf_white >= alpha``: the excess cannot be correlated noise), else
      ``undetermined`` (a smooth mismatch and correlated noise both fit; the reason
      names the noise models tried and what they lack).

    Each branch is a test at level ``alpha``; ``none`` is overturned only when two
    (``level`` and ``model`` or ``n_eff``) reject, or when the remainder's rms exceeds
    :data:`NONE_LEVEL_MAX` high-frequency sd (no noise model may absorb that much).
    Short recordings are judged again by :func:`short_recording_verdict`.
    """
    if nf.p_level >= alpha:
        return "none", ""
    floor = (
        f" (the floor, {HF_SD_FLOOR:g} of the model's largest value: the remainder's "
        "high-frequency noise is zero, noise-free or quantised readings)"
        if nf.hf_floored
        else ""
    )
    head = (
        f"the remainder's rms is {nf.level:.3g} times the high-frequency noise "
        f"{nf.sigma_hf:.3g}{floor} (p = {nf.p_level:.2g} under white noise; only noise "
        f"with a lag-one correlation of {nf.rho_needed:.3g} would explain it)"
    )
    whiter = nf.p_consistent < alpha
    if nf.level > NONE_LEVEL_MAX:
        head += f" (above the {NONE_LEVEL_MAX:g} no fitted noise model may absorb)"
    elif _rescued(nf, alpha):
        return "none", ""
    if _ripple(nf, alpha):
        return "unexplained", (
            f"{head}; a growing ripple explains more of it than the noise models that "
            f"would rescue it produce (AR(1) at rho {_rho_of(nf):.3g}: p = "
            f"{nf.p_ripple:.2g}; AR(p): p = {nf.p_ripple_ar:.2g}), so the excess is structure"
        )
    if whiter:
        why = (
            f"its high frequencies are whiter (lag-one correlation of differences "
            f"{nf.hf_lag1:.2f}) than AR(1) noise correlated enough to give that level "
            f"(p = {nf.p_consistent:.2g})"
        )
    elif nf.p_model < alpha:
        why = (
            f"the fitted noise model does not describe it (lag-one correlation of its "
            f"innovations {nf.innovation_lag1:.2f}, p = {nf.p_model:.2g})"
        )
    else:
        why = (
            f"its correlated-noise model leaves only {nf.n_eff:.3g} independent stretches "
            f"in {nf.n} rows (at least {N_EFF_MIN:g} are needed to tell it from a smooth "
            "mismatch)"
        )
    if nf.p_hf_white >= alpha:
        return "unexplained", (
            f"{head}; {why}; the high-frequency noise is white (lag-one correlation of "
            f"differences {nf.hf_lag1:.2f}, white -0.5), so the excess is structure"
        )
    ar = nf.ar
    if ar is not None:
        ar_why = _ar_failure(nf, alpha)
        why += (
            f"; the best AR(p) noise model (p = {ar.order} by BIC, at most {ar.max_order} "
            f"for {nf.n} rows) does not either: {ar_why}"
        )
    why += _power_law_failure(nf)
    return "undetermined", (
        f"{head}; {why}; the recording cannot tell a smooth mismatch from correlated "
        f"noise (lag-one correlation of differences {nf.hf_lag1:.2f}, white -0.5)"
    )


def short_recording_verdict(
    resid: np.ndarray,
    sigma: np.ndarray | None,
    nf: NoiseFloor,
    n_params: int,
    alpha: float,
) -> tuple[str, str]:
    """The verdict of a recording of fewer than :data:`SHORT_ROWS` rows.

    With a ``sigma`` column the noise is known: the remainder is tested against it
    (``sum (r/sigma)^2`` against chi-square with ``n - n_params`` degrees of freedom),
    ``none`` when it passes and ``unexplained`` when not. Without one the noise level
    can only be estimated from the rows the fit explains, which a smooth misfit of a
    few rows passes for noise, so a would-be ``none`` is ``undetermined``.

    Parameters
    ----------
    resid : (n,) array
        Remainder ``y - f`` [units of y].
    sigma : (n,) array or None
        The recording's stated noise sd per row [units of y].
    nf : NoiseFloor
        The remainder's noise floor (for ``n`` and the level).
    n_params : int
        Parameters of the fitted model.
    alpha : float
        Test level.

    Returns
    -------
    verdict : str
        ``none``, ``unexplained`` or ``undetermined``.
    reason : str
        Empty for ``none``.
    """
    n = int(nf.n)
    if n >= SHORT_ROWS:
        return "none", ""
    if sigma is not None:
        dof = max(n - int(n_params), 1)
        chi2 = float(np.sum((np.asarray(resid, float) / np.asarray(sigma, float)) ** 2))
        p = float(stats.chi2.sf(chi2, dof))
        if p >= alpha:
            return "none", ""
        return "unexplained", (
            f"the remainder is {np.sqrt(chi2 / dof):.3g} times the stated sigma "
            f"(chi-square {chi2:.3g} on {dof} degrees of freedom, p = {p:.2g})"
        )
    return "undetermined", (
        f"{n} rows without a sigma column: the noise level can only be estimated from "
        f"the rows the fit explains (rms of the remainder {nf.level:.3g} times the "
        f"high-frequency estimate {nf.sigma_hf:.3g}), too few to tell a smooth mismatch "
        f"from noise; record at least {SHORT_ROWS} rows or give the sensor's sigma"
    )


def outlier_threshold(n: int) -> float:
    """Distance [noise sd] beyond which a row of a recording of ``n`` rows is an outlier.

    :data:`OUTLIER_SD` (4.5) up to 100 rows, 0.75 more per decade beyond (5.25 at 1e3,
    6 at 1e4, 7.5 at 1e6 rows). Counted on white-noise recordings of a straight line
    (:func:`_deviation` against the estimated noise sd, its own scatter included), the
    share with any row beyond it is 0.8 % at 40 rows (4000 recordings), 0.45 % at 120
    (2000), 0.3 % at 1000 (400) and 0 of 60 at 1e4; the tail falls about 13-fold per sd,
    about 0.01 expected rows at 1e6.
    """
    return OUTLIER_SD + 0.75 * max(0.0, np.log10(max(n, 1)) - 2.0)


def _local_scale(ys: np.ndarray, seg: np.ndarray, kept: np.ndarray) -> np.ndarray:
    """Running high-frequency sd of each kept row (MAD-type, over a quarter of the
    trial's rows, at least 31, at most :data:`_LOCAL_ROWS`)."""
    out = np.zeros(ys.size)
    for s_ in np.unique(seg[kept]):
        idx = np.flatnonzero((seg == s_) & kept)
        if idx.size < 5:
            continue
        v = ys[idx]
        d2 = np.abs(v[2:] - 2.0 * v[1:-1] + v[:-2])
        # a quarter of the trial, 31-201 rows (mirrored at the ends: a padded window
        # would repeat the end values)
        w = int(min(_LOCAL_ROWS, max(31, idx.size // 4)))
        if d2.size <= w:
            loc = np.full(d2.size, np.median(d2))
        else:
            loc = ndimage.median_filter(d2, size=w, mode="mirror")
        loc = loc * _MAD / np.sqrt(6.0)
        out[idx] = np.concatenate([[loc[0]], loc, [loc[-1]]])
    return out


def _side_line(t: np.ndarray, v: np.ndarray, side: int) -> np.ndarray:
    """Deviation of each row from the straight line fitted to its ``_SIDE_ROWS`` nearest
    rows on one side (``side`` -1 left, +1 right; Theil-Sen in the control), NaN
    where fewer than 2 such rows exist."""
    n = v.size
    k = _SIDE_ROWS
    dt = np.full((n, k), np.nan)
    dv = np.full((n, k), np.nan)
    for m in range(1, k + 1):
        if m >= n:
            break
        if side < 0:
            dt[m:, m - 1] = t[:-m] - t[m:]
            dv[m:, m - 1] = v[:-m] - v[m:]
        else:
            dt[:-m, m - 1] = t[m:] - t[:-m]
            dv[:-m, m - 1] = v[m:] - v[:-m]
    cnt = np.sum(np.isfinite(dv), axis=1)
    # Theil-Sen line (median of the pairwise slopes, median intercept): one bad row of
    # the k does not bend it
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k)]
    with np.errstate(invalid="ignore", divide="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # rows without a side: NaN
        sl = np.stack([(dv[:, j] - dv[:, i]) / (dt[:, j] - dt[:, i]) for i, j in pairs], 1)
        slope = np.nanmedian(np.where(np.isfinite(sl), sl, np.nan), axis=1)
        slope = np.where(np.isfinite(slope), slope, 0.0)
        pred = np.nanmedian(dv - slope[:, None] * dt, axis=1)  # the line at the row itself
    return np.where(cnt >= 2, -pred, np.nan)


def _deviation(t: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Signed distance of each row from its neighbours (one trial, sorted rows).

    Three references: the median of the three rows on each side, and the straight lines
    through the :data:`_SIDE_ROWS` rows on the left and on the right, extrapolated to
    the row. A row deviates only as far as the nearest of them, and only when all
    available references agree in sign: a slope is followed by all three, a kink of
    the signal by the line on its own side, a curved peak by the median. Rows with
    a single reference (the first and last two of a trial) count half their distance
    (the third rows have both lines but not the median).
    """
    n = v.size
    refs = [_side_line(t, v, -1), _side_line(t, v, +1)]
    if n >= 7:
        sym = np.full(n, np.nan)
        nb = np.stack([v[j : n - 6 + j] for j in (0, 1, 2, 4, 5, 6)], axis=1)
        sym[3:-3] = v[3:-3] - np.median(nb, axis=1)
        refs.append(sym)
    r = np.stack(refs, axis=1)
    fin = np.isfinite(r)
    pos = np.all(np.where(fin, r > 0, True), axis=1)
    neg = np.all(np.where(fin, r < 0, True), axis=1)
    mag = np.nanmin(np.where(fin, np.abs(r), np.inf), axis=1)
    # rows next to a trial's end have one reference only (a line from one side, which a
    # curved signal bends away from): they count half as far
    mag = np.where(np.sum(fin, axis=1) >= 2, mag, 0.5 * mag)
    ok = np.any(fin, axis=1) & (pos | neg)
    return np.where(ok, np.where(pos, mag, -mag), 0.0)


def find_outliers(y: np.ndarray, x: np.ndarray, trial: np.ndarray):
    """Rows of isolated readings far from their neighbours (module docstring).

    A row is an outlier when its distance from its neighbours (:func:`_deviation`:
    the nearest of the median of the three rows each side and the lines through the
    :data:`_SIDE_ROWS` rows on either side, all agreeing in sign; rows sorted by the
    control within each trial) exceeds :func:`outlier_threshold` noise sd, the noise sd
    being the larger of the recording's high-frequency sd and the local one of its
    :data:`_LOCAL_ROWS` neighbours (noise that grows with the signal does not make its
    loud rows outliers). Passes repeat without the rows already flagged, one local
    maximum of the distance flagged per stretch of 5 rows and pass (a huge row does not
    drag its neighbours' references).

    Parameters
    ----------
    y, x, trial : (n,) arrays
        Readings, control variable, trial labels.

    Returns
    -------
    rows : (k,) int array
        Row indices (in the recording's order) of the outliers, largest first; empty
        when none or when more than :data:`OUTLIER_SHARE` of the rows would be.
    size : (k,) array
        Their distance from their neighbours in noise sd (signed).
    """
    empty = (np.zeros(0, int), np.zeros(0))
    y = np.asarray(y, float)
    x = np.asarray(x, float)
    n = y.size
    if n < 8:
        return empty
    o = _order(x, trial)
    seg = np.unique(trial, return_inverse=True)[1][o]
    ys, xs = y[o], x[o]
    sd = float(_hf_sd(ys[:, None], seg)[0])
    if not sd > 0:
        return empty
    limit = outlier_threshold(n)
    flagged = np.zeros(n, bool)
    dev = np.zeros(n)
    for _ in range(20):
        keep = ~flagged
        # the local scale of the rows kept (flagged rows would inflate it near them)
        local = np.maximum(_local_scale(ys, seg, keep), sd)
        d = np.zeros(n)
        for s_ in np.unique(seg):
            idx = np.flatnonzero((seg == s_) & keep)
            if idx.size >= 3:
                d[idx] = _deviation(xs[idx], ys[idx])
        a = np.abs(d) / local
        # a local maximum of the distance among the kept rows within two of it
        kept = np.flatnonzero(keep)
        ak = a[kept]
        pad = np.pad(ak, 2, constant_values=0.0)
        peak = np.all([ak >= pad[2 + j : 2 + j + ak.size] for j in (-2, -1, 1, 2)], axis=0)
        new = kept[peak & (ak > limit)]
        if new.size == 0:
            break
        flagged[new] = True
        dev[new] = d[new] / local[new]
        if flagged.sum() > OUTLIER_SHARE * n:
            return empty
    if not np.any(flagged):
        return empty
    z = dev[flagged]
    k = np.argsort(-np.abs(z))
    return o[flagged][k], z[k]


def outliers_of_remainder(rec: Recording, rows, size, mean_kept: np.ndarray):
    """The outliers of ``rec`` again, from the remainder of a baseline fitted without them.

    The first search (:func:`find_outliers` on the readings) must look past the
    signal's own shape: a row next to a kink of the baseline (the capstan's plateau
    onset) or on a strongly curved stretch can hide behind the reference on the wrong
    side. The remainder ``y - f`` of the baseline fitted without the rows found has
    neither; the search is repeated on it (the mean at the rows left out interpolated
    in the control within their trial) and the union kept, at most
    :data:`OUTLIER_SHARE` of the rows (else the first search's rows alone).

    Parameters
    ----------
    rec : Recording
        The recording with every row.
    rows, size : arrays
        The first search's rows (of ``rec``) and sizes.
    mean_kept : (n - k,) array
        The baseline mean at the rows kept, in ``rec``'s order.

    Returns
    -------
    rows, size : arrays
        Rows (largest first) and signed sizes [noise sd]; the remainder search's size
        where it found the row.
    """
    rows = np.asarray(rows, int)
    keep = np.ones(rec.n, bool)
    keep[rows] = False
    mean = np.empty(rec.n)
    mean[keep] = mean_kept
    for t in np.unique(rec.trial[~keep]):
        cur = rec.trial == t
        kx, km = rec.x[cur & keep], mean[cur & keep]
        o = np.argsort(kx)
        lost = np.flatnonzero(cur & ~keep)
        mean[lost] = np.interp(rec.x[lost], kx[o], km[o]) if kx.size else 0.0
    rows2, size2 = find_outliers(rec.y - mean, rec.x, rec.trial)
    found = dict(zip(rows.tolist(), np.asarray(size, float).tolist(), strict=True))
    found.update(zip(rows2.tolist(), size2.tolist(), strict=True))
    if len(found) > OUTLIER_SHARE * rec.n:
        return rows, np.asarray(size, float)
    r = np.array(sorted(found, key=lambda i: -abs(found[i])), int)
    return r, np.array([found[i] for i in r], float)


def without_rows(rec: Recording, rows) -> Recording:
    """``rec`` without the given rows (every per-row array cut alike)."""
    keep = np.ones(rec.n, bool)
    keep[np.asarray(rows, int)] = False

    def cut(a):
        return None if a is None else np.asarray(a)[keep]

    return replace(
        rec,
        x=rec.x[keep],
        y=rec.y[keep],
        sigma=cut(rec.sigma),
        trial=rec.trial[keep],
        speed=cut(rec.speed),
        extra={k: np.asarray(v)[keep] for k, v in rec.extra.items()},
    )
