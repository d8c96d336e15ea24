r"""Friction of particle-coated rods versus particle volume fraction (coated-rod paper).

Measured data of the coated-rod paper ("Systematic Variation of Friction of Rods",
J. Appl. Mech., DOI 10.1115/1.4055544): natural-rubber rods
(d = 1.59 mm, E = 1.83 MPa) dip-coated in a PMMA/1,3-dioxolane carrier (binder volume
fraction 5 %) loaded with iron particles (45-150 um) at particle volume fraction
:math:`\phi_p`, withdrawn at 5 mm/s.

* Friction coefficient fitted by DER simulation of overhand knots (sec. 4 and Fig. 12):
  :math:`\phi_p` = 0, 1, 4, 7, 13 % give :math:`\mu` = 0.2, 0.5, 0.6, 0.7, 0.9.
* Surface coverage (sec. 4, Fig. 7): 4.61 +- 1.15 % at 1 % and 29.02 +- 1.05 % at 13 %;
  the uncoated rod (0 %) has no particles, coverage 0 (our assumption, stated by the
  paper only implicitly). The other points of Fig. 7 are given only graphically and are
  not used.

Both are interpolated by a monotone piecewise-cubic Hermite interpolant (PCHIP,
Fritsch & Carlson 1980), which preserves the monotonicity of the data and passes
through every measured point. The API takes and returns volume fractions and
coverages as fractions (0.01 = 1 %), never percent. Nothing is extrapolated: inputs
outside the measured range raise :class:`~knotmech.errors.InputError`.
"""

from __future__ import annotations

import functools

import numpy as np

from knotmech.errors import InputError, check_finite

__all__ = [
    "COATING_VOLUME_FRACTION",
    "COATING_MU",
    "COVERAGE_VOLUME_FRACTION",
    "COVERAGE",
    "coated_rod_mu",
    "coated_rod_volume_fraction",
    "coated_rod_coverage",
]

#: Particle volume fractions of the coated-rod paper [-] (0, 1, 4, 7, 13 %).
COATING_VOLUME_FRACTION = np.array([0.0, 0.01, 0.04, 0.07, 0.13])
#: Friction coefficients fitted by DER for those fractions (coated-rod paper, Fig. 12).
COATING_MU = np.array([0.2, 0.5, 0.6, 0.7, 0.9])
#: Volume fractions with a coverage quoted in the text of the coated-rod paper [-].
COVERAGE_VOLUME_FRACTION = np.array([0.0, 0.01, 0.13])
#: Surface coverage [-] at those fractions (0 assumed for the uncoated rod; sec. 4, Fig. 7).
COVERAGE = np.array([0.0, 0.0461, 0.2902])


@functools.cache
def _interpolant(name: str):
    """The monotone PCHIP interpolant ``"mu"`` or ``"coverage"`` of phi, built on first use
    (importing scipy.interpolate costs about 0.4 s that ``import knotmech`` should not pay)."""
    from scipy.interpolate import PchipInterpolator

    x, y = {"mu": (COATING_VOLUME_FRACTION, COATING_MU),
            "coverage": (COVERAGE_VOLUME_FRACTION, COVERAGE)}[name]  # fmt: skip
    return PchipInterpolator(x, y, extrapolate=False)


def _MU_OF_PHI(phi):  # noqa: N802 - keeps the name of the former module-level interpolant
    return _interpolant("mu")(phi)


def _COVERAGE_OF_PHI(phi):  # noqa: N802
    return _interpolant("coverage")(phi)


def _check_in(name, value, low, high, unit_hint=""):
    arr = check_finite(name, value)
    if np.any(arr < low) or np.any(arr > high):
        raise InputError(
            f"{name} must lie in [{low:g}, {high:g}]{unit_hint} (no extrapolation beyond the "
            f"coated-rod paper's data), got values in [{arr.min():g}, {arr.max():g}]"
        )
    return arr


def coated_rod_mu(volume_fraction):
    r"""Friction coefficient of a coated rod at particle volume fraction :math:`\phi_p`.

    Parameters
    ----------
    volume_fraction : array_like [-], particle volume fraction as a fraction, in
        [0, 0.13] (0.01 means 1 %).

    Returns
    -------
    ndarray [-], :math:`\mu(\phi_p)`, PCHIP through (0, 0.2), (0.01, 0.5), (0.04, 0.6),
    (0.07, 0.7), (0.13, 0.9).

    Raises
    ------
    InputError
        outside [0, 0.13] (measured range) or NaN.

    Notes
    -----
    Assumptions: the process of the paper (binder 5 %, iron particles 45-150 um,
    withdrawal 5 mm/s, oven-dried); the paper warns that another particle morphology
    needs a new relation. The fitted values at 7 % and 13 % differ slightly from the
    paper's own capstan measurement (particle clustering).
    Reference: coated-rod paper, DOI 10.1115/1.4055544, sec. 4 and Fig. 12.
    """
    phi = _check_in("volume_fraction", volume_fraction, 0.0, COATING_VOLUME_FRACTION[-1])
    return _MU_OF_PHI(phi)


def coated_rod_volume_fraction(mu):
    r"""Particle volume fraction giving a wanted friction coefficient (inverts coated_rod_mu).

    Parameters
    ----------
    mu : array_like [-], wanted friction coefficient in [0.2, 0.9].

    Returns
    -------
    ndarray [-], :math:`\phi_p` as a fraction in [0, 0.13], such that
    ``coated_rod_mu(phi) == mu`` to 1e-12.

    Raises
    ------
    InputError
        for mu outside [0.2, 0.9] (no extrapolation) or NaN.

    Notes
    -----
    The forward PCHIP is strictly increasing (strictly increasing data), so the inverse
    is unique; it is found by vectorised bisection on the forward interpolant.
    Reference: coated-rod paper, sec. 4, Fig. 12 ("can help to predict the required
    particle volume fractions for achieving desired friction coefficient").
    """
    target = _check_in("mu", mu, COATING_MU[0], COATING_MU[-1])
    lo = np.zeros(target.shape)
    hi = np.full(target.shape, COATING_VOLUME_FRACTION[-1])
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        below = _MU_OF_PHI(mid) < target
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    return 0.5 * (lo + hi)


def coated_rod_coverage(volume_fraction):
    r"""Surface coverage of the coated rod at particle volume fraction :math:`\phi_p`.

    Parameters
    ----------
    volume_fraction : array_like [-], in [0, 0.13] (fraction, 0.01 = 1 %).

    Returns
    -------
    ndarray [-], covered area fraction, PCHIP through (0, 0), (0.01, 0.0461),
    (0.13, 0.2902).

    Notes
    -----
    Only the two coverages quoted in the paper's text are used (4.61 +- 1.15 % at 1 %,
    29.02 +- 1.05 % at 13 %); intermediate values are interpolated, not measured.
    Reference: coated-rod paper, DOI 10.1115/1.4055544, sec. 4 and Fig. 7.
    """
    phi = _check_in("volume_fraction", volume_fraction, 0.0, COVERAGE_VOLUME_FRACTION[-1])
    return _COVERAGE_OF_PHI(phi)
