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

Outliers (:func:`find_outliers`): rows farther than :data:`OUTLIER_SD` high-frequency sd
from the running median of 5 consecutive rows (per trial, sorted by the control), at
most 5 % of the rows; the engine fits without them and reports them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy import ndimage, stats

from knotmech.diagnose.recording import Recording
from knotmech.diagnose.stats import NoiseModel

__all__ = [
    "NoiseFloor",
    "noise_floor",
    "noise_floor_verdict",
    "find_outliers",
    "without_rows",
    "hf_sigma",
    "N_EFF_MIN",
    "OUTLIER_SD",
]

#: the fewest independent stretches, n (1 - rho)/(1 + rho), at which a fitted AR(1)
#: model may be told from a smooth mismatch (fewer: ``unexplained``/``undetermined``):
#: half the 10 knots of the structure test (:func:`~knotmech.diagnose.locate.flexible_mismatch`).
#: Measured: smooth misfits folded into the noise leave 3.0-3.7 (issue 14's nips of 30
#: and 100 sd at 240 rows), AR(1) nulls at rho = 0.9 and 200-240 rows 7.8-8.9
N_EFF_MIN = 5.0
#: an outlier lies farther than this many high-frequency sd from its running median
OUTLIER_SD = 8.0
#: most rows called outliers (a larger share is not outliers but the data)
OUTLIER_SHARE = 0.05
#: white-noise draws calibrating ``level`` and ``hf_white``
_DRAWS = 400
#: up to this many rows the p-values are counted from full-size white draws
_N_COUNTED = 20_000
_MAD = 1.482602218505602


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


def _level(r2d: np.ndarray, seg: np.ndarray) -> np.ndarray:
    sd = _hf_sd(r2d, seg)
    rms = np.sqrt(np.mean(r2d * r2d, axis=0))
    return rms / np.where(sd > 0, sd, np.finfo(float).tiny)


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

    def describe(self) -> dict:
        """JSON-ready numbers (3 significant digits)."""
        return {
            k: (float(f"{v:.3g}") if isinstance(v, float) else v) for k, v in vars(self).items()
        }


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
    level = float(_level(r, seg)[0])
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
        ll = np.log(sims_level)
        z_l = (np.log(level) - np.mean(ll)) / (np.std(ll) * shrink)
        z_h = (hf_l1 - np.mean(sims_hf)) / (np.std(sims_hf) * shrink)
        p_level, p_hf = float(stats.norm.sf(z_l)), float(stats.norm.sf(z_h))
    rho_needed = float(2.0 - np.sqrt(1.0 + 3.0 / max(level, 1.0) ** 2))
    e = noise.whiten(resid, noise.sd(mean), starts)
    pair = ~starts[1:]
    a, b_ = e[1:][pair], e[:-1][pair]
    m = int(pair.sum())
    den = np.sqrt(np.sum(a * a) * np.sum(b_ * b_))
    inn = float(np.sum(a * b_) / den) if den > 0 and m > 2 else 0.0
    p_model = float(2.0 * stats.norm.sf(abs(inn) * np.sqrt(max(m, 1))))
    rho = float(noise.rho)
    n_eff = n * (1.0 - rho) / (1.0 + rho) if rho > 0 else float(n)
    sd = _hf_sd(r, seg)[0]
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
    )


def noise_floor_verdict(nf: NoiseFloor, alpha: float) -> tuple[str, str]:
    """``none``, ``unexplained`` or ``undetermined`` for a remainder, and the reason.

    - ``none`` when the remainder is within the white high-frequency noise
      (``p_level >= alpha``), or when the final noise model describes its own
      innovations (``p_model >= alpha``) and leaves at least :data:`N_EFF_MIN`
      independent stretches;
    - otherwise ``unexplained`` when the high-frequency noise is white
      (``p_hf_white >= alpha``: the excess cannot be correlated noise), else
      ``undetermined`` (a smooth mismatch and correlated noise both fit).

    Each branch is a test at level ``alpha``; ``none`` is overturned only when two
    (``level`` and ``model`` or ``n_eff``) reject.
    """
    if nf.p_level >= alpha:
        return "none", ""
    head = (
        f"the remainder's rms is {nf.level:.3g} times the high-frequency noise "
        f"{nf.sigma_hf:.3g} (p = {nf.p_level:.2g} under white noise; only noise with a "
        f"lag-one correlation of {nf.rho_needed:.3g} would explain it)"
    )
    if nf.p_model >= alpha and nf.n_eff >= N_EFF_MIN:
        return "none", ""
    if nf.p_model < alpha:
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
    return "undetermined", (
        f"{head}; {why}; the recording cannot tell a smooth mismatch from correlated "
        f"noise (lag-one correlation of differences {nf.hf_lag1:.2f}, white -0.5)"
    )


def find_outliers(y: np.ndarray, x: np.ndarray, trial: np.ndarray):
    """Rows of isolated readings far from their neighbours (module docstring).

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
        Their distance from the running median in high-frequency sd (signed).
    """
    empty = (np.zeros(0, int), np.zeros(0))
    y = np.asarray(y, float)
    n = y.size
    if n < 8:
        return empty
    o = _order(x, trial)
    seg = np.unique(trial, return_inverse=True)[1][o]
    ys = y[o]
    sd = float(_hf_sd(ys[:, None], seg)[0])
    flagged = np.zeros(n, bool)
    dev = np.zeros(n)
    scale = None
    for _ in range(20):
        keep = ~flagged
        med = np.empty(n)
        for s_ in np.unique(seg):
            idx = np.flatnonzero((seg == s_) & keep)
            if idx.size:
                med[idx] = ndimage.median_filter(ys[idx], size=min(5, idx.size), mode="nearest")
        d = np.where(keep, ys - np.where(keep, med, 0.0), 0.0)
        if scale is None:
            scale = max(sd, _MAD * float(np.median(np.abs(d - np.median(d)))))
            if not scale > 0:
                return empty
        a = np.abs(d)
        # a local maximum of |deviation| among the kept rows within two of it
        kept = np.flatnonzero(keep)
        ak = a[kept]
        pad = np.pad(ak, 2, constant_values=0.0)
        peak = np.all([ak >= pad[2 + j : 2 + j + ak.size] for j in (-2, -1, 1, 2)], axis=0)
        new = kept[peak & (ak > OUTLIER_SD * scale)]
        if new.size == 0:
            break
        flagged[new] = True
        dev[new] = d[new]
        if flagged.sum() > OUTLIER_SHARE * n:
            return empty
    if not np.any(flagged):
        return empty
    k = np.argsort(-np.abs(dev[flagged]))
    return o[flagged][k], dev[flagged][k] / scale


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
