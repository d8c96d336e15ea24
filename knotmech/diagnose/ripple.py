r"""A deterministic ripple in a remainder, against the AR noise that would absorb it.

A short recording with a ripple (stick-slip chatter: a periodic force ripple growing with
the load) and white noise leaves a remainder that an AR(1) noise model of moderate
correlation describes well enough: its innovations are white, and a ripple of 5-15 rows
a period raises the high-frequency level as much as correlated noise does (issue 26:
55-row pinch recordings with a 6 % ripple, white noise, came out ``none`` under a fitted
rho of 0.61). The noise model cannot tell, but the shape can: a ripple is one frequency.

The statistic is the largest share of the standardised remainder's sum of squares that
a **growing ripple** explains,

.. math::
    S = \max_k \frac{\lVert P_k u\rVert^2}{\lVert u\rVert^2},\qquad
    P_k \text{ the projection on } \{\sin 2\pi k t,\ \cos 2\pi k t,\
    t\sin 2\pi k t,\ t\cos 2\pi k t\},

t the control variable mapped onto [0, 1] within each trial, k on a grid of half
cycles from 1 to n/4 cycles over the range (at least four rows a period). Its p-value is
counted from draws of the AR noise under test (the coefficients the would-be ``none``
rests on, Gaussian innovations, a stationary start), the statistic recomputed on each
(the frequency search included): a small p says the noise model would not produce such
a ripple, so the remainder is structure and the rescue is refused.
"""

from __future__ import annotations

import numpy as np
from scipy import signal

__all__ = ["RIPPLE_MAX_ROWS", "ar_draws", "ripple_p_value", "ripple_p_of_draws", "ripple_statistic"]

#: longer recordings are not tested (p = 1): the short-recording gap this closes is at
#: 30-100 rows, and the noise floor's other statistics resolve a ripple on long ones
RIPPLE_MAX_ROWS = 1000
#: AR draws calibrating the statistic
_DRAWS = 200


def _bases(t: np.ndarray, n: int) -> list:
    """Orthonormal bases (n, 4) of the growing ripple at each frequency of the grid."""
    out = []
    top = max(n / 4.0, 1.0)
    for k in np.arange(1.0, top + 1e-9, 0.5):
        s, c = np.sin(2 * np.pi * k * t), np.cos(2 * np.pi * k * t)
        q, _ = np.linalg.qr(np.column_stack([s, c, t * s, t * c]))
        out.append(q)
    return out


def ripple_statistic(u: np.ndarray, t: np.ndarray, bases=None) -> np.ndarray:
    """S of each column of ``u`` (n, B) (module docstring); ``t`` in [0, 1] (n,)."""
    u = np.asarray(u, float)
    u2 = u if u.ndim == 2 else u[:, None]
    if bases is None:
        bases = _bases(t, u2.shape[0])
    tot = np.sum(u2 * u2, axis=0)
    best = np.zeros(u2.shape[1])
    for q in bases:
        proj = q.T @ u2
        best = np.maximum(best, np.sum(proj * proj, axis=0))
    return best / np.where(tot > 0, tot, 1.0)


def ar_draws(phi, seg, draws, rng) -> np.ndarray:
    """(n, draws) unit-innovation AR(``phi``) series, each trial its own, burnt in."""
    n = seg.size
    out = np.empty((n, draws))
    bounds = np.flatnonzero(np.r_[True, seg[1:] != seg[:-1], True])
    a = np.r_[1.0, -np.asarray(phi, float)]
    for lo, hi in zip(bounds[:-1], bounds[1:], strict=True):
        e = rng.standard_normal((hi - lo + 200, draws))
        out[lo:hi] = signal.lfilter([1.0], a, e, axis=0)[200:]
    return out


def ripple_p_value(u, t, seg, phi, rng, draws: int = _DRAWS) -> float:
    """P(S at least the remainder's | AR(``phi``) noise), counted (1 + k)/(B + 1).

    Parameters
    ----------
    u : (n,) array
        Standardised remainder, rows sorted by the control variable within each trial.
    t : (n,) array
        The control variable mapped onto [0, 1] within each trial, same order.
    seg : (n,) int array
        Trial of each row, same order.
    phi : sequence of float
        AR coefficients of the noise under test (empty: white).
    rng : numpy Generator
    draws : int

    Returns
    -------
    float
        The p-value; 1 for more than :data:`RIPPLE_MAX_ROWS` rows or a non-stationary
        ``phi``.
    """
    n = int(np.size(u))
    roots = np.roots(np.r_[1.0, -np.asarray(phi, float)]) if len(phi) else np.zeros(0)
    if n > RIPPLE_MAX_ROWS or n < 12 or np.any(np.abs(roots) >= 0.999):
        return 1.0
    bases = _bases(np.asarray(t, float), n)
    obs = float(ripple_statistic(np.asarray(u, float), t, bases)[0])
    sims = ripple_statistic(ar_draws(phi, np.asarray(seg), draws, rng), t, bases)
    return (1 + int(np.sum(sims >= obs))) / (draws + 1)


def ripple_p_of_draws(u, t, z) -> float:
    """P(S at least the remainder's | the noise drawn in ``z``), counted (1 + k)/(B + 1).

    As :func:`ripple_p_value`, with the draws of the noise under test given (any
    model: the power-law draws of :mod:`knotmech.diagnose.noisefloor`).

    Parameters
    ----------
    u, t : (n,) arrays
        Standardised remainder and the control mapped onto [0, 1], rows sorted.
    z : (n, B) array
        B draws of the noise under test, laid out as ``u``.

    Returns
    -------
    float
        The p-value; 1 for more than :data:`RIPPLE_MAX_ROWS` or fewer than 12 rows.
    """
    n = int(np.size(u))
    if n > RIPPLE_MAX_ROWS or n < 12:
        return 1.0
    bases = _bases(np.asarray(t, float), n)
    obs = float(ripple_statistic(np.asarray(u, float), t, bases)[0])
    sims = ripple_statistic(z, t, bases)
    return (1 + int(np.sum(sims >= obs))) / (z.shape[1] + 1)
