"""Capstan (Euler-Eytelwein) friction, ideal and finite-thickness.

(minimal first version; the analytic helper extends this module)
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import check_nonnegative, check_positive


def capstan_ratio(mu, wrap_angle):
    r"""Ideal capstan tension ratio :math:`T_\mathrm{high}/T_\mathrm{low} = e^{\mu\theta}`."""
    mu = check_nonnegative("mu", mu)
    theta = check_nonnegative("wrap_angle", wrap_angle)
    return np.exp(mu * theta)


def mu_eff(mu, D_over_d):
    r"""Effective capstan friction coefficient of a rod of finite thickness.

    .. math:: \mu_\mathrm{eff} = \frac{-(1+\tilde D) + \sqrt{(1+\tilde D)^2 + 4\mu^2\tilde D}}{2\mu}
    """
    mu = check_nonnegative("mu", mu)
    Dt = check_positive("D_over_d", D_over_d)
    mu_safe = np.where(mu > 0, mu, 1.0)
    out = (-(1 + Dt) + np.sqrt((1 + Dt) ** 2 + 4 * mu_safe**2 * Dt)) / (2 * mu_safe)
    return np.where(mu > 0, out, 0.0)


def mu_from_mu_eff(mu_effective, D_over_d):
    r"""Material coefficient from a measured effective one (inverse of :func:`mu_eff`).

    Solving the quadratic :math:`\mu_e\mu^2 ... `: :math:`\mu = \mu_e (1+\tilde D)/(\tilde D - \mu_e^2)`.
    """
    me = check_nonnegative("mu_effective", mu_effective)
    Dt = check_positive("D_over_d", D_over_d)
    return me * (1 + Dt) / (Dt - me**2)
