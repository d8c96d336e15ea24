r"""Pinch contact: an elastic rod squeezed between two rigid cylinders and pulled through.

Two closed forms describe the nip regions of hitches (clove-hitch paper, Extreme Mech.
Lett., DOI 10.1016/j.eml.2022.101788, sec. 9):

* Amontons-Coulomb on both faces, :math:`F_t^* = 2\mu F_n`, with its validity measured by
  the load parameter :math:`x = 4F_n/(\pi E d D)` (Amontons holds for x below about 0.1);
* Hertz contact of two cylinders crossing at right angles (the rod of radius d/2 on a
  pinching cylinder of radius D/2): an elliptical contact patch, its semi-axes, peak
  pressure and approach (Johnson, *Contact Mechanics*, 1985, sec. 4.2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from knotmech.errors import InputError, check_nonnegative, check_positive, check_range, vectorised


# scipy.special is imported on first use (about 0.3 s that `import knotmech` should not pay)
def ellipk(m):
    """Complete elliptic integral of the first kind K(m) (scipy.special.ellipk)."""
    from scipy.special import ellipk as f

    return f(m)


def ellipe(m):
    """Complete elliptic integral of the second kind E(m) (scipy.special.ellipe)."""
    from scipy.special import ellipe as f

    return f(m)


def ellipkm1(p):
    """K(1 - p), accurate near m = 1 (scipy.special.ellipkm1)."""
    from scipy.special import ellipkm1 as f

    return f(p)


__all__ = [
    "PINCH_AMONTONS_LIMIT",
    "HertzContact",
    "pinch_load_parameter",
    "pinch_sliding_force",
    "pinch_amontons_applies",
    "effective_modulus",
    "hertz_circular_contact",
    "hertz_crossed_cylinders",
]

#: Largest load parameter 4 F_n/(pi E d D) for which the clove-hitch paper (sec. 9,
#: Fig. 5d) finds the Amontons-Coulomb pinch law F_t* = 2 mu F_n to hold.
PINCH_AMONTONS_LIMIT = 0.1


@vectorised
def pinch_load_parameter(normal_force, youngs_modulus, rod_diameter, pinch_diameter):
    r"""Dimensionless pinch load :math:`x = 4F_n/(\pi E d D)`.

    Parameters
    ----------
    normal_force : array_like [N], F_n, load pressing the pinching cylinders together.
    youngs_modulus : array_like [Pa], E of the rod.
    rod_diameter : array_like [m], d.
    pinch_diameter : array_like [m], D of the (rigid) pinching cylinders.

    Returns
    -------
    ndarray [-]

    Notes
    -----
    The normal force divided by a stiffness scale :math:`E\,(\pi d D/4)`. The
    clove-hitch paper (sec. 9, Fig. 5d) finds Amontons-Coulomb pinch friction for
    :math:`x \lesssim 0.1` (:data:`PINCH_AMONTONS_LIMIT`) and growing deviations beyond,
    attributed to geometrically nonlinear deformation of the cross-section; in its
    clove hitch :math:`x \approx 0.05`.
    """
    fn = check_nonnegative("normal_force", normal_force)
    e = check_positive("youngs_modulus", youngs_modulus)
    d = check_positive("rod_diameter", rod_diameter)
    dd = check_positive("pinch_diameter", pinch_diameter)
    return 4.0 * fn / (np.pi * e * d * dd)


@vectorised
def pinch_sliding_force(mu, normal_force):
    r"""Critical tangential force to pull a rod through a pinch, :math:`F_t^* = 2\mu F_n`.

    Parameters
    ----------
    mu : array_like [-], Coulomb friction coefficient, >= 0.
    normal_force : array_like [N], >= 0.

    Returns
    -------
    ndarray [N]

    Notes
    -----
    Both contact faces resist sliding, hence the factor 2. Validity: load parameter
    :func:`pinch_load_parameter` below about 0.1 (clove-hitch paper, sec. 9; see
    :func:`pinch_amontons_applies`).
    """
    mu = check_nonnegative("mu", mu)
    fn = check_nonnegative("normal_force", normal_force)
    return 2.0 * mu * fn


@vectorised
def pinch_amontons_applies(normal_force, youngs_modulus, rod_diameter, pinch_diameter):
    """True where the load parameter is at most :data:`PINCH_AMONTONS_LIMIT` (0.1)."""
    x = pinch_load_parameter(normal_force, youngs_modulus, rod_diameter, pinch_diameter)
    return x <= PINCH_AMONTONS_LIMIT


@vectorised
def effective_modulus(youngs_modulus, poisson_ratio, youngs_modulus_2=np.inf, poisson_ratio_2=0.0):
    r"""Hertz contact modulus :math:`E^*`.

    .. math:: \frac{1}{E^*} = \frac{1-\nu_1^2}{E_1} + \frac{1-\nu_2^2}{E_2}

    Parameters
    ----------
    youngs_modulus, poisson_ratio : array_like, [Pa] and [-] of body 1 (nu in [0, 0.5]).
    youngs_modulus_2, poisson_ratio_2 : array_like, body 2; default rigid (E_2 = inf).

    Returns
    -------
    ndarray [Pa]

    Reference: Johnson, *Contact Mechanics* (1985), eq. (4.22).
    """
    e1 = check_positive("youngs_modulus", youngs_modulus)
    n1 = check_range("poisson_ratio", poisson_ratio, 0.0, 0.5)
    n2 = check_range("poisson_ratio_2", poisson_ratio_2, 0.0, 0.5)
    e2 = check_positive("youngs_modulus_2", youngs_modulus_2, allow_inf=True)
    return 1.0 / ((1.0 - n1**2) / e1 + (1.0 - n2**2) / e2)


@dataclass(frozen=True)
class HertzContact:
    """Hertz contact patch (all arrays broadcast together).

    Attributes
    ----------
    semi_major : ndarray [m], a, along the direction of smaller relative curvature.
    semi_minor : ndarray [m], b <= a.
    peak_pressure : ndarray [Pa], p0 = 3P/(2 pi a b).
    approach : ndarray [m], delta, mutual approach of distant points.
    eccentricity : ndarray [-], e = sqrt(1 - b^2/a^2).
    """

    semi_major: np.ndarray
    semi_minor: np.ndarray
    peak_pressure: np.ndarray
    approach: np.ndarray
    eccentricity: np.ndarray


@vectorised
def hertz_circular_contact(*, normal_force, radius, contact_modulus):
    r"""Hertz contact of a sphere of radius R on a flat (or equal crossed cylinders).

    .. math:: a = \left(\frac{3PR}{4E^*}\right)^{1/3}, \quad p_0 = \frac{3P}{2\pi a^2},
              \quad \delta = \frac{a^2}{R}

    Two equal cylinders of radius R crossed at right angles have the same gap function
    :math:`(x^2 + y^2)/(2R)` and so the same contact.

    Parameters
    ----------
    normal_force : array_like [N], P >= 0.
    radius : array_like [m], R (the effective radius).
    contact_modulus : array_like [Pa], E* (:func:`effective_modulus`).

    Returns
    -------
    HertzContact (semi_major == semi_minor == a, eccentricity 0).

    Notes
    -----
    Linear elastic, frictionless, small strain: valid for :math:`a \ll R`.
    Reference: Johnson (1985), eqs. (4.22)-(4.23).
    """
    p = check_nonnegative("normal_force", normal_force)
    r = check_positive("radius", radius)
    es = check_positive("contact_modulus", contact_modulus)
    a = np.cbrt(3.0 * p * r / (4.0 * es))
    with np.errstate(invalid="ignore", divide="ignore"):
        p0 = np.where(a > 0, 3.0 * p / (2.0 * np.pi * np.where(a > 0, a, 1.0) ** 2), 0.0)
    return HertzContact(
        semi_major=a,
        semi_minor=a,
        peak_pressure=p0,
        approach=a**2 / r,
        eccentricity=np.zeros_like(a),
    )


def _k_minus_e_over_m(m):
    """(K(m) - E(m))/m, with its series pi/4 + 3 pi m/32 below m = 1e-5."""
    m = np.asarray(m, dtype=float)
    small = m < 1e-5
    ms = np.where(small, 1.0, m)
    exact = (ellipkm1(1.0 - ms) - ellipe(ms)) / ms
    series = np.pi / 4.0 + 3.0 * np.pi * m / 32.0
    return np.where(small, series, exact)


def _curvature_ratio(m):
    r"""B/A of the Hertz ellipse of parameter m = e^2: [E/(1-m) - K]/(K - E).

    Written as [K - (K-E)/m] / [(1-m)(K-E)/m] to stay accurate as m -> 0 (ratio -> 1).
    """
    m = np.asarray(m, dtype=float)
    kme = _k_minus_e_over_m(m)
    return (ellipkm1(1.0 - m) - kme) / ((1.0 - m) * kme)


#: [-] largest radius ratio of :func:`hertz_crossed_cylinders`: the eccentricity solver
#: meets its curvature ratio to 2.5e-5 at 1e10 (1e-8 at 1e8) and saturates near 1e14
HERTZ_RADIUS_RATIO_MAX = 1e10


def _solve_eccentricity(ratio):
    """Parameter m = e^2 with _curvature_ratio(m) == ratio >= 1 (vectorised bisection)."""
    ratio = np.asarray(ratio, dtype=float)
    lo = np.full(ratio.shape, -40.0)  # logit(m)
    hi = np.full(ratio.shape, 40.0)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        m = 1.0 / (1.0 + np.exp(-mid))
        too_small = _curvature_ratio(m) < ratio
        lo = np.where(too_small, mid, lo)
        hi = np.where(too_small, hi, mid)
    m = 1.0 / (1.0 + np.exp(-0.5 * (lo + hi)))
    return np.where(ratio <= 1.0 + 1e-12, 0.0, m)


@vectorised
def hertz_crossed_cylinders(
    *,
    normal_force,
    radius_1,
    radius_2,
    youngs_modulus,
    poisson_ratio,
    youngs_modulus_2=np.inf,
    poisson_ratio_2=0.0,
):
    r"""Hertz contact of two cylinders crossing at right angles (general elliptical case).

    The gap is :math:`h = A x^2 + B y^2` with :math:`A = 1/(2R_\mathrm{large})`,
    :math:`B = 1/(2R_\mathrm{small})`. The patch is an ellipse of semi-axes
    :math:`a \ge b`, a along x (the direction of smaller relative curvature, i.e. along
    the axis of the thinner cylinder), eccentricity :math:`e^2 = m = 1 - b^2/a^2` solving

    .. math:: \frac{B}{A} = \frac{E(m)/(1-m) - K(m)}{K(m) - E(m)},

    then

    .. math:: a^3 = \frac{3P\,[K(m) - E(m)]}{2\pi E^* A\, m}, \quad
              p_0 = \frac{3P}{2\pi a b}, \quad \delta = \frac{p_0\, b\, K(m)}{E^*}

    with K, E complete elliptic integrals of parameter m. Equal radii give the circular
    contact of :func:`hertz_circular_contact` (effective radius R).

    Parameters
    ----------
    normal_force : array_like [N], P >= 0.
    radius_1, radius_2 : array_like [m], cylinder radii (rod d/2 and pinch D/2).
    youngs_modulus, poisson_ratio : array_like, body 1 (the rod).
    youngs_modulus_2, poisson_ratio_2 : array_like, body 2, default rigid.

    Returns
    -------
    HertzContact

    Notes
    -----
    Assumptions: linear elasticity, frictionless contact, half-space approximation.
    Validity: patch small against both radii, :math:`a \ll R_\mathrm{small}`; for the
    pinch of a soft rod this means a load parameter :math:`4F_n/(\pi E d D) \ll 1`.
    Radii more than :data:`HERTZ_RADIUS_RATIO_MAX` apart are refused (InputError): the
    ellipse is then too slender for the eccentricity solver in floating point.
    Reference: Johnson, *Contact Mechanics* (1985), sec. 4.2, eqs. (4.36)-(4.40).
    """
    p = check_nonnegative("normal_force", normal_force)
    r1 = check_positive("radius_1", radius_1)
    r2 = check_positive("radius_2", radius_2)
    slender = np.maximum(r1, r2) / np.minimum(r1, r2)
    if np.any(slender > HERTZ_RADIUS_RATIO_MAX):
        raise InputError(
            f"radius_1/radius_2 = {float(np.max(np.maximum(slender, 1 / slender))):.3g} is "
            f"beyond {HERTZ_RADIUS_RATIO_MAX:g} (either way): the contact ellipse is too "
            "slender for this Hertz solution in floating point"
        )
    es = effective_modulus(youngs_modulus, poisson_ratio, youngs_modulus_2, poisson_ratio_2)
    p, r1, r2, es = np.broadcast_arrays(p, r1, r2, es)
    a_coef = 1.0 / (2.0 * np.maximum(r1, r2))
    b_coef = 1.0 / (2.0 * np.minimum(r1, r2))
    m = _solve_eccentricity(b_coef / a_coef)
    kme_m = _k_minus_e_over_m(m)
    a = np.cbrt(3.0 * p * kme_m / (2.0 * np.pi * es * a_coef))
    b = a * np.sqrt(1.0 - m)
    pos = a > 0
    safe = np.where(pos, a * b, 1.0)
    p0 = np.where(pos, 3.0 * p / (2.0 * np.pi * safe), 0.0)
    delta = p0 * b * ellipk(m) / es
    return HertzContact(
        semi_major=a,
        semi_minor=b,
        peak_pressure=p0,
        approach=delta,
        eccentricity=np.sqrt(m),
    )
