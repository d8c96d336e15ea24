r"""Elastic overhand knots: braid law of Jawed et al. (2015), loose knot of Audoly et al. (2007).

Notation (both papers): h rod radius, :math:`B = EI = E\pi h^4/4` bending stiffness,
F the pulling force on the tails, R the radius of curvature where the rod leaves the
braid for the loop, and e the **end-to-end shortening**: the length of rod held in the
knot, :math:`e = L - D`, with L the rod's (inextensible) length and D the distance
between its two pulled ends (the convention of Jawed et al. 2015; Audoly et al. 2007
call it the end-shortening). e decreases as the knot is pulled tight.

Long overhand knot with n braid turns (Jawed, Dieleman, Audoly & Reis, PRL 115, 118302,
2015; unknotting number n, crossing number 2n + 1). The knot is a braid of two strands
wound n times around each other, each a helix of radius h (the strands touch) and wave
number k, and a planar loop:

* braid wave number, their Eq. (3): :math:`h k^2 = 1/(\sqrt{12} R)`;
* pulling force, their Eq. (4): the strands press on each other with the line force
  :math:`p = B\kappa\tau^2 = B h k^4` that holds an unloaded, untwisted helix of
  curvature :math:`\kappa = h k^2` and torsion :math:`\tau = k` in shape, and sliding
  friction :math:`\mu p` acts over the braid length :math:`\ell = 2\pi n/k`:
  :math:`F = \mu p \ell = 2\pi\mu n h B k^3`;
* loop closure, their Eq. (5): the loop is a planar elastica leaving the braid along
  its axis with curvature 1/R and re-entering it at distance :math:`\ell` after turning by
  :math:`2\pi`, :math:`\kappa^2 R^2 = 1 - m\sin^2(\theta/2)`, whence its length
  :math:`\lambda = 4RK(m)` and :math:`\ell = R[8(K(m) - E(m))/m - 4K(m)]`, and the
  shortening :math:`e = 2\ell + \lambda - \ell = \ell + \lambda` (two strands in the braid,
  minus the braid's own span). Eliminating k and R gives the master curve

  .. math:: \frac{n^2 h}{e} = \frac{g(x)}{8\sqrt3\pi^2}, \qquad
            \frac{n^2 F h^2}{B} = \frac{\mu x^3}{96\sqrt3\pi^2}, \qquad
            g(x) = \frac{x^2}{x + \lambda/R}, \quad x = \ell/R.

Derivations: ``derivations/jawed_braid.py`` (contact force of the helix, the force law
and the elliptic-integral closure). Eq. (3) is taken as quoted, not re-derived: the
paper's full text was not at hand, so its equation numbers follow secondary sources,
and Eqs. (4)-(5) are checked here by derivation rather than against the printed page.

Loose trefoil (Audoly, Clauvelin & Neukirch, PRL 99, 164301, 2007), frictionless leading
order in :math:`\epsilon = \sqrt{h/R} \to 0`: the knot is, at leading order, one circular
loop of radius R, bending energy :math:`\pi B/R` and shortening :math:`e = 2\pi R`, so
:math:`F = -dU/de = 2\pi^2 B/e^2 = B/(2R^2)`, i.e. :math:`F h^2/B = \epsilon^4/2`
(``derivations/audoly_loose_knot.py``). Friction and twist corrections of that paper
are not implemented.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from knotmech.errors import InputError, check_finite, check_nonnegative, check_positive, vectorised


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
    "JAWED_C",
    "LOOSE_KNOT_EPSILON_MAX",
    "OverhandKnot",
    "braid_wavenumber",
    "braid_contact_force_per_length",
    "braid_friction_force",
    "loop_closure",
    "overhand_knot",
    "overhand_pull_force",
    "loose_knot_force",
    "loose_knot_force_from_shortening",
]

#: :math:`\sqrt3\pi^2`, the constant of Jawed et al. (2015) Eq. (5).
JAWED_C = np.sqrt(3.0) * np.pi**2
#: Loop slenderness :math:`\epsilon = \sqrt{h/R}` above which a knot is flagged as too tight
#: for the slender-loop asymptotics (our threshold: R >= 4 h).
LOOSE_KNOT_EPSILON_MAX = 0.5
_SQRT12 = np.sqrt(12.0)


def _check_turns(turns):
    n = check_finite("turns", turns)
    if np.any(n < 1) or np.any(n != np.round(n)):
        raise InputError("turns must be a whole number >= 1 (braid turns n of the overhand knot)")
    return n


@vectorised
def braid_wavenumber(*, loop_radius, rod_radius):
    r"""Braid wave number of a long overhand knot, Jawed et al. (2015) Eq. (3).

    .. math:: k = \left(\sqrt{12}\, h R\right)^{-1/2}, \quad\text{i.e.}\quad
              h k^2 = \frac{1}{\sqrt{12}\,R}

    Parameters
    ----------
    loop_radius : array_like [m], R, radius of curvature where the rod leaves the braid.
    rod_radius : array_like [m], h.

    Returns
    -------
    ndarray [1/m]

    Notes
    -----
    :math:`h k^2` is the curvature of the braid's helical strands, so the strands in the
    braid are :math:`\sqrt{12}` times less curved than the loop where it leaves the braid.
    Validity: :math:`h \ll R`. Reference: Jawed, Dieleman, Audoly & Reis, PRL 115,
    118302 (2015), Eq. (3).
    """
    r = check_positive("loop_radius", loop_radius)
    h = check_positive("rod_radius", rod_radius)
    return 1.0 / np.sqrt(_SQRT12 * h * r)


@vectorised
def braid_contact_force_per_length(*, wavenumber, rod_radius, bending_stiffness):
    r"""Line contact force between the two strands of a braid, :math:`p = B h k^4`.

    A naturally straight, untwisted rod bent into a helix of curvature
    :math:`\kappa = hk^2/(1 + h^2k^2) \approx hk^2` and torsion :math:`\tau \approx k`
    needs, with negligible tension, the distributed force :math:`p = B\kappa\tau^2`
    along its principal normal (Kirchhoff equations; ``derivations/jawed_braid.py``).

    Parameters
    ----------
    wavenumber : array_like [1/m], k.
    rod_radius : array_like [m], h (helix radius: the strands touch).
    bending_stiffness : array_like [N m^2], B.

    Returns
    -------
    ndarray [N/m]

    Notes
    -----
    Validity: :math:`hk \ll 1` and tension :math:`T \ll Bk^2`.
    """
    k = check_positive("wavenumber", wavenumber)
    h = check_positive("rod_radius", rod_radius)
    b = check_positive("bending_stiffness", bending_stiffness)
    return b * h * k**4


@vectorised
def braid_friction_force(*, wavenumber, turns, mu, rod_radius, bending_stiffness):
    r"""Pulling force to slide a braid of n turns, Jawed et al. (2015) Eq. (4).

    .. math:: F = 2\pi\mu n h B k^3, \quad\text{i.e.}\quad \frac{F}{Bk^2} = \mu\,2\pi n h k

    Parameters
    ----------
    wavenumber : array_like [1/m], k.
    turns : array_like [-], n, whole number >= 1.
    mu : array_like [-], rod-rod friction coefficient >= 0.
    rod_radius : array_like [m], h.
    bending_stiffness : array_like [N m^2], B.

    Returns
    -------
    ndarray [N]

    Notes
    -----
    Friction :math:`\mu p` with :math:`p = Bhk^4` over the braid length
    :math:`2\pi n/k`. Linear in mu and n at fixed k. Neglects the loop's own pull
    :math:`B/(2R^2)` (friction-dominated regime) and tension in the contact force.
    Reference: Jawed et al., PRL 115, 118302 (2015), Eq. (4).
    """
    n = _check_turns(turns)
    mu = check_nonnegative("mu", mu)
    p = braid_contact_force_per_length(
        wavenumber=wavenumber, rod_radius=rod_radius, bending_stiffness=bending_stiffness
    )
    k = np.asarray(wavenumber, dtype=float)
    return mu * p * (2.0 * np.pi * n / k)


def _x_of_m(m):
    """Braid length over loop radius, x = l/R = 8 (K - E)/m - 4K (series below 1e-3)."""
    m = np.asarray(m, dtype=float)
    small = m < 1e-3
    ms = np.where(small, 0.5, m)
    exact = 8.0 * (ellipkm1(1.0 - ms) - ellipe(ms)) / ms - 4.0 * ellipkm1(1.0 - ms)
    series = np.pi * (
        m / 4 + 3 * m**2 / 16 + 75 * m**3 / 512 + 245 * m**4 / 2048 + 6615 * m**5 / 65536
    )
    return np.where(small, series, exact)


def loop_closure(elastica_parameter):
    r"""Geometry of the knot's loop: braid length and loop length over R.

    .. math:: \frac{\ell}{R} = \frac{8\,[K(m) - E(m)]}{m} - 4K(m), \qquad
              \frac{\lambda}{R} = 4K(m)

    for the planar elastica :math:`\kappa^2R^2 = 1 - m\sin^2(\theta/2)` turning by
    :math:`2\pi` (m = 0: a circle, :math:`\ell = 0`, :math:`\lambda = 2\pi R`;
    m -> 1: an infinitely long braid).

    Parameters
    ----------
    elastica_parameter : array_like [-], m in [0, 1).

    Returns
    -------
    (braid_over_R, loop_over_R) : tuple of ndarray [-]

    Reference: Jawed et al. (2015), Eq. (5) and its supplement; derived in
    ``derivations/jawed_braid.py``.
    """
    m = check_finite("elastica_parameter", elastica_parameter)
    if np.any(m < 0) or np.any(m >= 1):
        raise InputError("elastica_parameter must lie in [0, 1)")
    return _x_of_m(m), 4.0 * ellipk(m)


def _shortening_ratio(m):
    """e / (n^2 h) as a function of the elastica parameter (decreasing in m)."""
    x = _x_of_m(m)
    k = ellipkm1(1.0 - m)
    return 8.0 * JAWED_C * (x + 4.0 * k) / x**2


_LOGIT_LO, _LOGIT_HI = -60.0, 36.0  # m from 9e-27 to 1 - 2e-16


@functools.cache
def _shortening_bounds() -> tuple[float, float]:
    """Smallest e/(n^2 h) the closure can represent (the long-braid limit m -> 1) and the
    largest the bisection brackets (the loose limit m -> 0); computed on first use."""
    lo = float(_shortening_ratio(1.0 / (1.0 + np.exp(-_LOGIT_HI))))
    hi = float(_shortening_ratio(1.0 / (1.0 + np.exp(-_LOGIT_LO))))
    return lo, hi


@dataclass(frozen=True)
class OverhandKnot:
    """State of a long overhand knot from :func:`overhand_knot` (arrays broadcast together).

    Attributes
    ----------
    force : ndarray [N], pulling force F (Eq. 4 with Eqs. 3, 5).
    loop_radius : ndarray [m], R.
    wavenumber : ndarray [1/m], k.
    braid_length : ndarray [m], l = 2 pi n / k.
    loop_length : ndarray [m], lambda.
    elastica_parameter : ndarray [-], m.
    epsilon : ndarray [-], sqrt(h/R).
    friction_to_loop_pull : ndarray [-], F / (B/(2R^2)); the theory wants it >> 1.
    valid : ndarray of bool, epsilon <= LOOSE_KNOT_EPSILON_MAX and friction_to_loop_pull >= 1.
    message : str, why entries are flagged ('' when none).
    """

    force: np.ndarray
    loop_radius: np.ndarray
    wavenumber: np.ndarray
    braid_length: np.ndarray
    loop_length: np.ndarray
    elastica_parameter: np.ndarray
    epsilon: np.ndarray
    friction_to_loop_pull: np.ndarray
    valid: np.ndarray
    message: str


@vectorised
def overhand_knot(*, end_to_end_shortening, turns, mu, rod_radius, bending_stiffness):
    r"""Long overhand knot of Jawed et al. (2015): solve Eqs. (3)-(5) for a given shortening.

    Finds the elastica parameter m with
    :math:`e/(n^2h) = 8\sqrt3\pi^2\,(x + 4K(m))/x^2`, :math:`x = \ell/R` from
    :func:`loop_closure` (the right side decreases monotonically in m), then
    :math:`R = 8\sqrt3\pi^2 n^2 h/x^2`, :math:`k = 2\pi n/(xR)` and
    :math:`F = 2\pi\mu n h B k^3`.

    Parameters
    ----------
    end_to_end_shortening : array_like [m], e = L - D (rod length minus the distance
        between the pulled ends: the length of rod in the knot).
    turns : array_like [-], n (whole number >= 1).
    mu : array_like [-], rod-rod friction coefficient >= 0.
    rod_radius : array_like [m], h.
    bending_stiffness : array_like [N m^2], B = E pi h^4 / 4.

    Returns
    -------
    OverhandKnot

    Raises
    ------
    InputError
        on bad input, or if :math:`e/(n^2 h)` is below the long-braid limit of the
        closure (about 5.6: tighter than any elastica loop).
    """
    e = check_positive("end_to_end_shortening", end_to_end_shortening)
    n = _check_turns(turns)
    mu = check_nonnegative("mu", mu)
    h = check_positive("rod_radius", rod_radius)
    b = check_positive("bending_stiffness", bending_stiffness)
    e, n, mu, h, b = np.broadcast_arrays(e, n, mu, h, b)
    target = e / (n**2 * h)
    _SHORTENING_MIN, _SHORTENING_MAX = _shortening_bounds()  # noqa: N806
    if np.any(target <= _SHORTENING_MIN):
        raise InputError(
            f"end_to_end_shortening must exceed {_SHORTENING_MIN:.3g} n^2 h "
            "(tighter than the long-braid limit of the Jawed et al. closure)"
        )
    if np.any(target >= _SHORTENING_MAX):
        raise InputError(f"end_to_end_shortening must be below {_SHORTENING_MAX:.3g} n^2 h")
    lo = np.full(target.shape, _LOGIT_LO)
    hi = np.full(target.shape, _LOGIT_HI)
    for _ in range(110):
        mid = 0.5 * (lo + hi)
        m = 1.0 / (1.0 + np.exp(-mid))
        too_loose = _shortening_ratio(m) > target  # ratio decreases with m
        lo = np.where(too_loose, mid, lo)
        hi = np.where(too_loose, hi, mid)
    m = 1.0 / (1.0 + np.exp(-0.5 * (lo + hi)))
    x = _x_of_m(m)
    radius = 8.0 * JAWED_C * n**2 * h / x**2
    k = 2.0 * np.pi * n / (x * radius)
    force = 2.0 * np.pi * mu * n * h * b * k**3
    eps = np.sqrt(h / radius)
    ratio = force / (b / (2.0 * radius**2))
    valid = (eps <= LOOSE_KNOT_EPSILON_MAX) & (ratio >= 1.0)
    reasons = []
    if np.any(eps > LOOSE_KNOT_EPSILON_MAX):
        reasons.append(
            f"loop too tight: sqrt(h/R) = {float(eps.max()):.3g} > {LOOSE_KNOT_EPSILON_MAX:g}"
        )
    if np.any(ratio < 1.0):
        reasons.append(
            f"friction force only {float(ratio.min()):.3g} times the loop pull B/(2R^2): "
            "the friction-dominated braid law does not apply"
        )
    return OverhandKnot(
        force=force,
        loop_radius=radius,
        wavenumber=k,
        braid_length=x * radius,
        loop_length=4.0 * ellipkm1(1.0 - m) * radius,
        elastica_parameter=m,
        epsilon=eps,
        friction_to_loop_pull=ratio,
        valid=valid,
        message="; ".join(reasons),
    )


@vectorised
def overhand_pull_force(end_to_end_shortening, turns, mu, rod_radius, bending_stiffness):
    r"""Pulling force of a long overhand knot, Jawed, Dieleman, Audoly & Reis (2015).

    .. math:: \frac{n^2 h}{e} = \frac{1}{8\sqrt3\pi^2}\,
              g\!\left(\left[\frac{96\sqrt3\pi^2}{\mu}\frac{n^2Fh^2}{B}\right]^{1/3}\right),
              \qquad g(x) = \frac{x^2}{x + \lambda(x)/R}

    with :math:`\lambda/R` and :math:`x = \ell/R` from the loop elastica
    (:func:`loop_closure`); equivalently :math:`F = 2\pi\mu n h B k^3` with
    :math:`hk^2 = 1/(\sqrt{12}R)` and :math:`e = \ell + \lambda`.

    Parameters
    ----------
    end_to_end_shortening : array_like [m]
        e = L - D: the rod length minus the distance between the pulled ends, i.e. the
        length of rod contained in the knot (Jawed et al. convention). Decreases as the
        knot tightens.
    turns : array_like [-], n, braid turns (unknotting number), whole number >= 1.
    mu : array_like [-], rod-rod Coulomb friction coefficient >= 0.
    rod_radius : array_like [m], h.
    bending_stiffness : array_like [N m^2], B = E pi h^4/4.

    Returns
    -------
    ndarray [N], the force needed to keep the knot sliding tighter.

    Notes
    -----
    Assumptions: inextensible, naturally straight, isotropic rods; sliding (kinetic)
    Coulomb friction in the braid; quasi-static pulling; twist-free; friction dominating
    the loop's own pull :math:`B/(2R^2)` (:math:`\mu n \gg \sqrt{h/R}`).
    Validity: long-braid regime (a braid of n >= 1 helical wavelengths, slender helix
    :math:`hk \ll 1`) and a slender loop, :math:`h \ll R`; the force grows as
    :math:`e^{-3/2}` for loose knots and steeply as e approaches a few :math:`n^2 h`
    (tight knots, outside the theory: use :func:`overhand_knot` to see the flags).
    Linear in mu; increasing in n and decreasing in e.
    Reference: Jawed, Dieleman, Audoly & Reis, "Untangling the mechanics and topology
    in the frictional response of long overhand elastic knots", PRL 115, 118302 (2015),
    Eqs. (3)-(5). Derivation: ``derivations/jawed_braid.py``.
    """
    return overhand_knot(
        end_to_end_shortening=end_to_end_shortening,
        turns=turns,
        mu=mu,
        rod_radius=rod_radius,
        bending_stiffness=bending_stiffness,
    ).force


@vectorised
def loose_knot_force(*, loop_radius, bending_stiffness):
    r"""Frictionless loose-trefoil force at leading order, Audoly et al. (2007).

    .. math:: F = \frac{B}{2R^2}, \quad\text{i.e.}\quad \frac{Fh^2}{B} = \frac{\epsilon^4}{2},
              \ \epsilon = \sqrt{h/R}

    Parameters
    ----------
    loop_radius : array_like [m], R.
    bending_stiffness : array_like [N m^2], B.

    Returns
    -------
    ndarray [N]

    Notes
    -----
    Leading order of the matched asymptotics as :math:`\epsilon \to 0`: the loop is a
    circle of radius R; friction (a correction of order :math:`\mu\epsilon^3` in
    :math:`Fh^2/B`) and applied twist are neglected.
    Reference: Audoly, Clauvelin & Neukirch, PRL 99, 164301 (2007); energy derivation
    in ``derivations/audoly_loose_knot.py``.
    """
    r = check_positive("loop_radius", loop_radius)
    b = check_positive("bending_stiffness", bending_stiffness)
    return b / (2.0 * r**2)


@vectorised
def loose_knot_force_from_shortening(*, end_to_end_shortening, bending_stiffness):
    r"""Frictionless loose-trefoil force from the shortening, :math:`F = 2\pi^2 B/e^2`.

    With the loop a circle, :math:`e = 2\pi R` and bending energy
    :math:`U = \pi B/R = 2\pi^2 B/e`; pulling the ends apart by dD = -de does work
    F dD = dU, so :math:`F = -dU/de = 2\pi^2B/e^2 = B/(2R^2)`.

    Parameters
    ----------
    end_to_end_shortening : array_like [m], e = L - D.
    bending_stiffness : array_like [N m^2], B.

    Returns
    -------
    ndarray [N]

    Notes
    -----
    Validity: loose knot, :math:`e \gg h` (:math:`\epsilon^2 = 2\pi h/e \ll 1`),
    negligible friction. Reference: Audoly, Clauvelin & Neukirch, PRL 99, 164301 (2007).
    """
    e = check_positive("end_to_end_shortening", end_to_end_shortening)
    b = check_positive("bending_stiffness", bending_stiffness)
    return 2.0 * np.pi**2 * b / e**2
