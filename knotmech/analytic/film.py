r"""Landau-Levich-Derjaguin (LLD) dip-coating film thickness on plates and fibres.

A solid withdrawn at speed :math:`U` from a bath of a wetting Newtonian liquid
(viscosity :math:`\eta`, surface tension :math:`\gamma`, density :math:`\rho`) carries
a film whose thickness is set by matching the curvature of the dynamic meniscus
(viscous drag against capillary pressure, thin-film equation) to the curvature
:math:`\kappa_s` of the static meniscus below it:

.. math:: h = \frac{C_\mathrm{LL}\,(3\,\mathrm{Ca})^{2/3}}{\kappa_s}, \qquad
          \mathrm{Ca} = \frac{\eta U}{\gamma}, \qquad C_\mathrm{LL} = 0.6430\ldots

:math:`C_\mathrm{LL}` is the limiting curvature of the solution of
:math:`H''' = (H - 1)/H^3` that leaves the flat film (Landau & Levich 1942: 0.643; recomputed in
``derivations/lld.py``), so :math:`C_\mathrm{LL}\,3^{2/3} = 1.3376`.

* plate: :math:`\kappa_s = \sqrt 2 / \ell_c`, :math:`\ell_c = \sqrt{\gamma/(\rho g)}`, so
  :math:`h = 0.9458\,\ell_c\,\mathrm{Ca}^{2/3}` (quoted as 0.946 by de Gennes,
  Brochard-Wyart & Quere, *Capillarity and Wetting Phenomena*, 2004, and rounded to
  0.94 in the coated-rod paper, DOI 10.1115/1.4055544, sec. 1);
* thin fibre, :math:`r \ll \ell_c`: :math:`\kappa_s = 1/r`, so
  :math:`h = 1.34\,r\,\mathrm{Ca}^{2/3}` (Goucher & Ward 1922; Quere, Annu. Rev. Fluid
  Mech. 31, 347 (1999)), and with the White & Tallmadge (1966) correction for the
  film's own thickness :math:`h = 1.34\,r\,\mathrm{Ca}^{2/3}/(1 - 1.34\,\mathrm{Ca}^{2/3})`.

The plate constant is exactly the fibre constant divided by :math:`\sqrt 2`:
:data:`LLD_FIBRE_COEFFICIENT` / sqrt(2) = :data:`LLD_PLATE_COEFFICIENT`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from knotmech.errors import InputError, check_positive, vectorised

__all__ = [
    "LANDAU_LEVICH_CURVATURE",
    "LLD_FIBRE_COEFFICIENT",
    "LLD_PLATE_COEFFICIENT",
    "STANDARD_GRAVITY",
    "CA_MAX_LLD",
    "FIBRE_RADIUS_MAX",
    "PLATE_RADIUS_MIN",
    "FilmThickness",
    "capillary_number",
    "capillary_length",
    "film_thickness_plate",
    "film_thickness_fibre",
    "film_thickness_fibre_white_tallmadge",
    "film_thickness",
]

#: Limiting curvature of the Landau-Levich thin-film solution, H''(+inf) for
#: H''' = (H - 1)/H^3 (Landau & Levich 1942; recomputed in derivations/lld.py).
LANDAU_LEVICH_CURVATURE = 0.64304
#: 1.34 = 0.643 * 3^(2/3) (Goucher-Ward fibre law, Quere 1999).
LLD_FIBRE_COEFFICIENT = LANDAU_LEVICH_CURVATURE * 3.0 ** (2.0 / 3.0)
#: 0.946 = 1.3376 / sqrt(2) (plate: static meniscus curvature sqrt(2)/l_c).
LLD_PLATE_COEFFICIENT = LLD_FIBRE_COEFFICIENT / np.sqrt(2.0)
#: Standard gravity [m/s^2].
STANDARD_GRAVITY = 9.80665
#: Largest capillary number for which the regime picker applies LLD (Ca^(1/3) small).
CA_MAX_LLD = 0.1
#: Largest r/l_c treated as a thin fibre (Goucher-Ward needs r << l_c).
FIBRE_RADIUS_MAX = 0.1
#: Smallest r/l_c treated as a plate (the meniscus no longer feels the curvature of the rod).
PLATE_RADIUS_MIN = 10.0


@vectorised
def capillary_number(viscosity, speed, surface_tension):
    r"""Capillary number :math:`\mathrm{Ca} = \eta U/\gamma` [-].

    Parameters
    ----------
    viscosity : array_like [Pa s]
    speed : array_like [m/s], withdrawal speed.
    surface_tension : array_like [N/m]
    """
    eta = check_positive("viscosity", viscosity)
    u = check_positive("speed", speed)
    gamma = check_positive("surface_tension", surface_tension)
    return eta * u / gamma


@vectorised
def capillary_length(surface_tension, density, gravity=STANDARD_GRAVITY):
    r"""Capillary length :math:`\ell_c = \sqrt{\gamma/(\rho g)}` [m]."""
    gamma = check_positive("surface_tension", surface_tension)
    rho = check_positive("density", density)
    g = check_positive("gravity", gravity)
    return np.sqrt(gamma / (rho * g))


@vectorised
def film_thickness_plate(viscosity, speed, surface_tension, density, *, gravity=STANDARD_GRAVITY):
    r"""LLD film thickness on a plate withdrawn vertically from a bath.

    .. math:: h = 0.946\,\ell_c\,\mathrm{Ca}^{2/3}, \qquad
              \ell_c = \sqrt{\gamma/(\rho g)}, \qquad \mathrm{Ca} = \eta U/\gamma

    (the coefficient is :data:`LLD_PLATE_COEFFICIENT` = 0.9458).

    Parameters
    ----------
    viscosity : array_like [Pa s]
    speed : array_like [m/s], withdrawal speed.
    surface_tension : array_like [N/m]
    density : array_like [kg/m^3]
    gravity : float [m/s^2], default standard gravity.

    Returns
    -------
    ndarray [m], the wet film thickness far above the bath.

    Notes
    -----
    Assumptions: Newtonian, perfectly wetting liquid, no surfactant (stress-free
    interface), steady withdrawal, negligible inertia, film thickness set in the
    capillary-viscous region where gravity is negligible.
    Validity: :math:`\mathrm{Ca} \ll 1` (in practice Ca below about 1e-2; at larger Ca
    gravity enters and h approaches the Derjaguin scaling
    :math:`\sqrt{\eta U/(\rho g)}`).
    Reference: Landau & Levich, Acta Physicochim. URSS 17, 42 (1942); Derjaguin (1943);
    de Gennes, Brochard-Wyart & Quere, *Capillarity and Wetting Phenomena* (2004), ch. 5.
    Derivation: ``derivations/lld.py``.
    """
    ca = capillary_number(viscosity, speed, surface_tension)
    lc = capillary_length(surface_tension, density, gravity)
    return LLD_PLATE_COEFFICIENT * lc * ca ** (2.0 / 3.0)


@vectorised
def film_thickness_fibre(radius, viscosity, speed, surface_tension):
    r"""Goucher-Ward (LLD) film thickness on a thin fibre.

    .. math:: h = 1.34\,r\,\mathrm{Ca}^{2/3}, \qquad \mathrm{Ca} = \eta U/\gamma

    (the coefficient is :data:`LLD_FIBRE_COEFFICIENT` = 1.3376).

    Parameters
    ----------
    radius : array_like [m], fibre radius r.
    viscosity : array_like [Pa s]
    speed : array_like [m/s]
    surface_tension : array_like [N/m]

    Returns
    -------
    ndarray [m], wet film thickness.

    Notes
    -----
    Assumptions: as :func:`film_thickness_plate`, with the static meniscus curvature
    set by the fibre, :math:`\kappa_s = 1/r`, and :math:`h \ll r`.
    Validity: :math:`r \ll \ell_c` and :math:`\mathrm{Ca} \ll 1` (the film must stay thin,
    :math:`1.34\,\mathrm{Ca}^{2/3} \ll 1`); for thicker films use
    :func:`film_thickness_fibre_white_tallmadge`.
    Reference: Goucher & Ward, Phil. Mag. 44, 1002 (1922); Quere, Annu. Rev. Fluid
    Mech. 31, 347 (1999), eq. (3); coated-rod paper, DOI 10.1115/1.4055544, sec. 1.
    """
    r = check_positive("radius", radius)
    ca = capillary_number(viscosity, speed, surface_tension)
    return LLD_FIBRE_COEFFICIENT * r * ca ** (2.0 / 3.0)


@vectorised
def film_thickness_fibre_white_tallmadge(radius, viscosity, speed, surface_tension):
    r"""Fibre film thickness with the White-Tallmadge correction.

    .. math:: h = \frac{1.34\,r\,\mathrm{Ca}^{2/3}}{1 - 1.34\,\mathrm{Ca}^{2/3}}

    The denominator accounts for the meniscus curvature being :math:`1/(r + h)` rather
    than :math:`1/r`; it tends to :func:`film_thickness_fibre` as Ca -> 0.

    Parameters
    ----------
    radius : array_like [m]
    viscosity : array_like [Pa s]
    speed : array_like [m/s]
    surface_tension : array_like [N/m]

    Returns
    -------
    ndarray [m]

    Raises
    ------
    InputError
        if :math:`1.34\,\mathrm{Ca}^{2/3} \ge 1` (Ca >= 0.646), where the formula diverges.

    Notes
    -----
    Validity: :math:`r \ll \ell_c`, Ca up to about 0.1 (beyond, inertia and gravity
    matter). Reference: White & Tallmadge, AIChE J. 12, 333 (1966); Quere, Annu. Rev.
    Fluid Mech. 31, 347 (1999), eq. (4).
    """
    r = check_positive("radius", radius)
    ca = capillary_number(viscosity, speed, surface_tension)
    x = LLD_FIBRE_COEFFICIENT * ca ** (2.0 / 3.0)
    if np.any(x >= 1.0):
        raise InputError(
            "viscosity*speed/surface_tension (the capillary number Ca) must be < 0.646 for "
            "the White-Tallmadge film "
            f"(1.34 Ca^(2/3) < 1), got Ca up to {float(np.max(ca)):g}"
        )
    return r * x / (1.0 - x)


@dataclass(frozen=True)
class FilmThickness:
    """Result of :func:`film_thickness`.

    Attributes
    ----------
    thickness : ndarray [m], NaN where ``regime == "none"`` (only with ``strict=False``).
    regime : ndarray of str, ``"plate"``, ``"fibre"`` or ``"none"`` per entry.
    capillary_number : ndarray [-]
    capillary_length : ndarray [m]
    applicable : ndarray of bool, False where no closed form applies.
    message : str, why entries were flagged (empty when all apply).
    """

    thickness: np.ndarray
    regime: np.ndarray
    capillary_number: np.ndarray
    capillary_length: np.ndarray
    applicable: np.ndarray
    message: str


@vectorised
def film_thickness(
    *,
    viscosity,
    speed,
    surface_tension,
    density,
    radius=None,
    gravity=STANDARD_GRAVITY,
    strict=True,
):
    r"""Dip-coating film thickness, picking the LLD regime that applies.

    Rules, per entry (:math:`\ell_c` capillary length, r rod radius):

    * Ca >= :data:`CA_MAX_LLD` (0.1): no closed form ("Ca not small");
    * ``radius is None`` or :math:`r/\ell_c \ge` :data:`PLATE_RADIUS_MIN` (10):
      plate, :func:`film_thickness_plate`;
    * :math:`r/\ell_c \le` :data:`FIBRE_RADIUS_MAX` (0.1): fibre,
      :func:`film_thickness_fibre_white_tallmadge` (Goucher-Ward as Ca -> 0);
    * otherwise (:math:`r \sim \ell_c`): no closed form; the static meniscus curvature
      depends on :math:`r/\ell_c` and neither limit holds.

    Parameters
    ----------
    viscosity, speed, surface_tension, density : array_like, SI units, broadcastable.
    radius : array_like [m] or None (None: a plate).
    gravity : float [m/s^2]
    strict : bool
        Design choice: with ``strict=True`` (default) an entry without a valid regime
        raises :class:`~knotmech.errors.InputError` naming the reason; with
        ``strict=False`` the result is returned flagged: ``applicable`` False,
        ``regime`` "none", ``thickness`` NaN there and ``message`` saying why.

    Returns
    -------
    FilmThickness
    """
    if not isinstance(strict, (bool, np.bool_)):
        raise InputError(f"strict must be True or False, got {strict!r:.40}")
    ca = np.asarray(capillary_number(viscosity, speed, surface_tension))
    lc = np.asarray(capillary_length(surface_tension, density, gravity))
    if radius is None:
        ratio = np.full(np.broadcast(ca, lc).shape, np.inf)
        r = None
    else:
        r = check_positive("radius", radius)
        ratio = r / lc
    ca, lc, ratio = np.broadcast_arrays(ca, lc, ratio)
    small_ca = ca < CA_MAX_LLD
    plate = small_ca & (ratio >= PLATE_RADIUS_MIN)
    fibre = small_ca & (ratio <= FIBRE_RADIUS_MAX)
    applicable = plate | fibre
    reasons = []
    if np.any(~small_ca):
        reasons.append(
            f"viscosity*speed/surface_tension (the capillary number) {float(np.max(ca)):g} "
            f"is not small (LLD needs Ca < {CA_MAX_LLD:g})"
        )
    crossover = small_ca & ~applicable
    if np.any(crossover):
        reasons.append(
            f"radius/capillary length {float(ratio[crossover].min()):.3g} lies between "
            f"{FIBRE_RADIUS_MAX:g} and {PLATE_RADIUS_MIN:g}: "
            "neither thin-fibre nor plate LLD applies"
        )
    message = "; ".join(reasons)
    if strict and not np.all(applicable):
        raise InputError(f"film_thickness: {message}")
    h = np.full(ca.shape, np.nan)
    lc_h = LLD_PLATE_COEFFICIENT * lc * ca ** (2.0 / 3.0)
    h = np.where(plate, lc_h, h)
    if r is not None:
        x = LLD_FIBRE_COEFFICIENT * ca ** (2.0 / 3.0)
        rb = np.broadcast_to(r, ca.shape)
        h = np.where(fibre, rb * x / (1.0 - np.where(fibre, x, 0.0)), h)
    regime = np.where(plate, "plate", np.where(fibre, "fibre", "none"))
    return FilmThickness(
        thickness=h,
        regime=regime,
        capillary_number=ca,
        capillary_length=lc,
        applicable=applicable,
        message=message,
    )
