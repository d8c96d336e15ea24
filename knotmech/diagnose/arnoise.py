r"""Autoregressive noise of order p for the noise floor (coloured noise that is noise).

The engine's noise model (:mod:`knotmech.diagnose.stats`) is AR(1). Sensors often give
noise of a richer colour (AR(2) with a spectral peak, 1/f drift); its AR(1) innovations
stay correlated and the noise floor (:mod:`knotmech.diagnose.noisefloor`) could only say
``undetermined``. Here the standardised remainder :math:`u` is fitted by

.. math::
    u_t = \sum_{k=1}^{p} \phi_k u_{t-k} + \sigma_e e_t,\qquad e_t \sim N(0, 1),

within each trial (conditional least squares on the rows with p predecessors in their
trial; Box, Jenkins & Reinsel, *Time Series Analysis*, sec. 7.1), the order chosen by
BIC among :math:`0 \le p \le p_\max(n)` on a common sample. The order is bounded by what
n rows support, :func:`max_order`: ``min(8, n // 20)`` (at least 1), i.e. at least 20
rows per coefficient, so that each :math:`\hat\phi_k` has a standard error of at most
:math:`1/\sqrt{20}` (about 0.22).

The fit is judged by

- the **Ljung-Box** portmanteau statistic of its innovations (Ljung & Box 1978),
  :math:`Q = m(m+2)\sum_{k=1}^{h} r_k^2/(m-k)`, chi-square with :math:`h - p` degrees
  of freedom under a correct model, :math:`h = \min(10, \max(p + 2, m/5))`;
- the **independent stretches** it leaves,
  :math:`n_\mathrm{eff} = n (1 - r)/(1 + r)` with :math:`r` the largest modulus of the
  roots of :math:`z^p - \phi_1 z^{p-1} - \dots - \phi_p` (the slowest decay of the
  autocorrelation; for AR(1) :math:`r = \rho` and this is the AR(1) count of
  :mod:`~knotmech.diagnose.noisefloor`). A smooth misfit folded into the noise needs a
  root near the unit circle (a step: a random walk; a ripple: a complex pair of
  modulus near 1), so it leaves few stretches whatever the order.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = ["ARFit", "fit_ar", "max_order", "ljung_box", "P_MAX", "ROWS_PER_COEF"]

#: the highest order considered at any length
P_MAX = 8
#: rows per AR coefficient (the bound on the order a recording of n rows supports)
ROWS_PER_COEF = 20


def max_order(n: int) -> int:
    """Highest AR order ``n`` rows support: ``min(P_MAX, n // ROWS_PER_COEF)``, at least 1."""
    return int(max(1, min(P_MAX, n // ROWS_PER_COEF)))


@dataclass(frozen=True)
class ARFit:
    """An AR(p) fit of a standardised remainder (module docstring).

    Attributes
    ----------
    order : int
        p chosen by BIC (0: white).
    phi : tuple of float
        Coefficients :math:`\\phi_1..\\phi_p`.
    sigma_e : float
        Innovation sd (units of the standardised remainder).
    root_modulus : float
        Largest modulus of the characteristic roots (0 for p = 0).
    n_eff : float
        ``n (1 - r)/(1 + r)`` (0 when the fit is not stationary, r >= 1).
    q : float
        Ljung-Box statistic of the innovations.
    lags : int
        Its number of lags h.
    p_white : float
        ``P(chi2_{h-p} >= q)``: the innovations are white.
    max_order : int
        The bound on p for these rows.
    """

    order: int
    phi: tuple
    sigma_e: float
    root_modulus: float
    n_eff: float
    q: float
    lags: int
    p_white: float
    max_order: int

    def describe(self) -> dict:
        """JSON-ready numbers (3 significant digits)."""
        return {
            "order": self.order,
            "phi": [float(f"{v:.3g}") for v in self.phi],
            "root_modulus": float(f"{self.root_modulus:.3g}"),
            "n_eff": float(f"{self.n_eff:.3g}"),
            "ljung_box_q": float(f"{self.q:.3g}"),
            "ljung_box_lags": self.lags,
            "p_white": float(f"{self.p_white:.3g}"),
            "max_order": self.max_order,
        }


def _lagged(u: np.ndarray, seg: np.ndarray, p: int):
    """Rows with ``p`` predecessors in their segment: target and (m, p) lag matrix."""
    n = u.size
    # position of each row within its segment
    starts = np.ones(n, bool)
    starts[1:] = seg[1:] != seg[:-1]
    first = np.maximum.accumulate(np.where(starts, np.arange(n), 0))
    pos = np.arange(n) - first
    rows = np.flatnonzero(pos >= p)
    lags = (
        np.column_stack([u[rows - k] for k in range(1, p + 1)]) if p else np.zeros((rows.size, 0))
    )
    return rows, u[rows], lags


def ljung_box(e: np.ndarray, seg: np.ndarray, h: int) -> float:
    """Ljung-Box statistic of ``e`` over lags 1..h, pairs taken within segments."""
    e = np.asarray(e, float) - np.mean(e)
    m = e.size
    den = float(np.dot(e, e))
    if den <= 0 or m <= h + 1:
        return 0.0
    q = 0.0
    for k in range(1, h + 1):
        same = seg[k:] == seg[:-k]
        r = float(np.dot(e[k:][same], e[:-k][same])) / den
        q += r * r / (m - k)
    return float(m * (m + 2) * q)


def _roots_modulus(phi: np.ndarray) -> float:
    if phi.size == 0:
        return 0.0
    return float(np.max(np.abs(np.roots(np.concatenate([[1.0], -phi])))))


def fit_ar(u: np.ndarray, seg: np.ndarray, p_max: int | None = None) -> ARFit:
    """AR(p) fit of a standardised remainder, the order chosen by BIC (module docstring).

    Parameters
    ----------
    u : (n,) array
        Remainder divided by its marginal sd model, in row (time) order.
    seg : (n,) int array
        Segment (trial) label of each row; AR recursions restart at a change.
    p_max : int, optional
        Highest order (default :func:`max_order` of n).

    Returns
    -------
    ARFit
    """
    u = np.asarray(u, float)
    seg = np.asarray(seg)
    n = u.size
    top = max_order(n) if p_max is None else int(p_max)
    # a common sample: the rows with `top` predecessors (BIC compares like with like)
    while top > 0 and _lagged(u, seg, top)[0].size < 3 * top + 3:
        top -= 1
    rows, target, lags = _lagged(u, seg, top)
    m = rows.size
    best = None
    for p in range(top + 1):
        x = lags[:, :p]
        phi = np.linalg.lstsq(x, target, rcond=None)[0] if p else np.zeros(0)
        res = target - x @ phi if p else target.copy()
        s2 = max(float(np.dot(res, res)) / max(m, 1), 1e-300)
        bic = m * np.log(s2) + p * np.log(max(m, 2))
        if best is None or bic < best[0]:
            best = (bic, p, phi)
    _, p, phi = best
    # innovations on every row with p predecessors (not only the common sample)
    rows_p, tgt_p, lag_p = _lagged(u, seg, p)
    e = tgt_p - lag_p @ phi if p else tgt_p
    sigma_e = float(np.sqrt(np.mean(e * e))) if e.size else 0.0
    r = _roots_modulus(phi)
    n_eff = n * (1.0 - r) / (1.0 + r) if r < 1.0 else 0.0
    m_e = e.size
    h = int(min(10, max(p + 2, m_e // 5)))
    if m_e > h + 2 and sigma_e > 0:
        q = ljung_box(e / sigma_e, seg[rows_p], h)
        p_white = float(stats.chi2.sf(q, max(h - p, 1)))
    else:
        q, p_white = 0.0, 1.0
    return ARFit(
        order=int(p),
        phi=tuple(float(v) for v in phi),
        sigma_e=sigma_e,
        root_modulus=r,
        n_eff=float(n_eff),
        q=float(q),
        lags=h,
        p_white=p_white,
        max_order=int(max_order(n) if p_max is None else p_max),
    )
