r"""Capstan (Euler-Eytelwein) friction: ideal rope, thick rod, bending rigidity, nonlinear friction.

Every function is a pure, vectorised closed form (numpy broadcasting, SI units,
angles in radians) that raises :class:`knotmech.errors.InputError` on out-of-range
input. The models and the limit in which each reduces to the ideal capstan
:math:`T_\mathrm{high}/T_\mathrm{low} = e^{\mu\theta}`:

- ideal rope: :func:`capstan_ratio`, :func:`capstan_tension_profile`,
  :func:`mu_from_capstan_test`;
- thick rod, friction at the contact radius: :func:`mu_eff`, :func:`mu_from_mu_eff`,
  :func:`capstan_ratio_thick` (ideal as :math:`D/d\to\infty`);
- bending rigidity, elastica lift-off: :func:`capstan_ratio_bending` (ideal as
  :math:`B\to 0`);
- nonlinear (Howell) friction :math:`f = aN^n`: :func:`capstan_high_tension_nonlinear`
  (ideal as :math:`n\to 1`).

Derivations: ``derivations/capstan_ode.py`` (ideal ODE, Howell law, elastica
lift-off) and ``derivations/mu_eff.py`` (force and moment balance of a thick rod).
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError, check_nonnegative, check_positive, vectorised

__all__ = [
    "capstan_ratio",
    "capstan_tension_profile",
    "mu_from_capstan_test",
    "mu_eff",
    "mu_from_mu_eff",
    "capstan_ratio_thick",
    "capstan_end_factors",
    "capstan_ratio_thick_ends",
    "bending_parameter",
    "liftoff_angle",
    "capstan_ratio_bending",
    "capstan_high_tension_nonlinear",
    "capstan_ratio_nonlinear",
]


#: [-] the largest float, 1.8e308: a ratio or tension beyond it is refused, not returned as inf
_FLOAT_MAX = float(np.finfo(float).max)


def _finite_result(value, what: str):
    r"""``value`` if every entry is finite, else InputError: ``what`` overflows a float.

    The arguments are finite when this is called, so a non-finite result is an
    overflow of :math:`e^{\mu\theta}` (:math:`\mu\theta > 709.8`) or of a tension times
    it; ``what`` names the arguments that make it.
    """
    if not np.all(np.isfinite(value)):
        raise InputError(f"{what} is beyond the largest float ({_FLOAT_MAX:.3g}); no rope holds it")
    return value


# --------------------------------------------------------------------------- ideal rope
@vectorised
def capstan_ratio(mu, wrap_angle):
    r"""Ideal capstan (Euler-Eytelwein) tension ratio at the onset of slip.

    .. math:: \frac{T_\mathrm{high}}{T_\mathrm{low}} = e^{\mu\theta}

    Parameters
    ----------
    mu : array_like
        Coulomb friction coefficient rope-post [-], :math:`\mu \ge 0`.
    wrap_angle : array_like
        Contact (wrap) angle :math:`\theta` [rad], :math:`\theta \ge 0`.

    Returns
    -------
    ndarray
        :math:`T_\mathrm{high}/T_\mathrm{low}` [-]; the rope holds while the actual
        ratio is at most this value.

    Notes
    -----
    Assumptions: inextensible, perfectly flexible, infinitely thin rope on a rigid
    circular post, Amontons-Coulomb friction, planar wrap. Valid for any
    :math:`\mu\ge 0,\ \theta\ge 0`; for real rods it over-estimates the grip when
    the rod is not thin compared with the post (use :func:`capstan_ratio_thick`).

    References
    ----------
    Euler (1762), Eytelwein (1808); the clove-hitch paper (Extreme Mech. Lett. 2022,
    DOI 10.1016/j.eml.2022.101788), Sec. 1. Derivation: ``derivations/capstan_ode.py``.
    """
    mu = check_nonnegative("mu", mu)
    theta = check_nonnegative("wrap_angle", wrap_angle)
    with np.errstate(over="ignore"):
        ratio = np.exp(mu * theta)
    return _finite_result(ratio, "the ratio exp(mu*wrap_angle)")


@vectorised
def capstan_tension_profile(s, *, high_tension, mu, radius):
    r"""Tension along the contact arc of an ideal capstan at the onset of slip.

    .. math:: T(s) = T_\mathrm{high}\, e^{-\mu s/R}

    Parameters
    ----------
    s : array_like
        Arc length along the contact measured from the high-tension end [m], >= 0.
    high_tension : array_like
        :math:`T_\mathrm{high}` [N], >= 0.
    mu : array_like
        Friction coefficient [-], >= 0. Pass :func:`mu_eff` for a thick rod (the
        clove-hitch paper's eq. (3)).
    radius : array_like
        Radius of the centreline on the post :math:`R` [m], > 0 (for a rod of
        diameter d on a post of diameter D, :math:`R=(D+d)/2`).

    Returns
    -------
    ndarray
        :math:`T(s)` [N].

    References
    ----------
    Clove-hitch paper eq. (3); ``derivations/capstan_ode.py``.
    """
    s = check_nonnegative("s", s)
    t_high = check_nonnegative("high_tension", high_tension)
    mu = check_nonnegative("mu", mu)
    radius = check_positive("radius", radius)
    return t_high * np.exp(-mu * s / radius)


@vectorised
def mu_from_capstan_test(high_tension, low_tension, wrap_angle):
    r"""Friction coefficient from a capstan test (the coated-rod paper's method).

    .. math:: \mu = \frac{\ln(T_\mathrm{high}/T_\mathrm{low})}{\theta}

    Parameters
    ----------
    high_tension, low_tension : array_like
        Tensions at the two ends at the onset of sliding [N], > 0,
        ``high_tension >= low_tension``.
    wrap_angle : array_like
        Contact angle [rad], > 0.

    Returns
    -------
    ndarray
        :math:`\mu` [-]. For a rod that is not thin compared with the capstan this
        is the *effective* coefficient; :func:`mu_from_mu_eff` gives the material one.

    References
    ----------
    Coated-rod paper (J. Appl. Mech., DOI 10.1115/1.4055544), Sec. on the capstan
    measurement (Fig. 6), inverting the Euler-Eytelwein law.
    """
    t_high = check_positive("high_tension", high_tension)
    t_low = check_positive("low_tension", low_tension)
    theta = check_positive("wrap_angle", wrap_angle)
    if np.any(t_high < t_low):
        raise InputError("high_tension must be >= low_tension (swap the two ends?)")
    return np.log(t_high / t_low) / theta


# --------------------------------------------------------------------------- thick rod
@vectorised
def mu_eff(mu, D_over_d):
    r"""Effective capstan friction coefficient of a rod of finite thickness.

    .. math::

        \mu_\mathrm{eff} = \frac{-(1+\tilde D) + \sqrt{(1+\tilde D)^2 + 4\mu^2\tilde D}}{2\mu},
        \qquad \tilde D = D/d

    so that :math:`T(s) \propto e^{-\mu_\mathrm{eff} s/R}` with :math:`R=(D+d)/2`.

    Parameters
    ----------
    mu : array_like
        Material friction coefficient rod-post [-], >= 0.
    D_over_d : array_like
        Post diameter over rod diameter :math:`\tilde D` [-], > 0.

    Returns
    -------
    ndarray
        :math:`\mu_\mathrm{eff}` [-], with :math:`0 \le \mu_\mathrm{eff} < \mu`,
        :math:`\mu_\mathrm{eff}\to\mu` as :math:`\tilde D\to\infty` and
        :math:`\mu_\mathrm{eff}\approx\mu\tilde D` for :math:`\tilde D \ll 1`.

    Notes
    -----
    Friction acts at the contact line, half a rod diameter off the centreline, so
    it also applies a couple per unit length; with the bending moment constant on
    the wrapped arc the couple is balanced by a shear force whose gradient adds to
    the normal force. The force balance :math:`T' = -\mu N(1-a)` and the normal
    balance :math:`N(1+\mu\mu_\mathrm{eff}a) = T/R`, :math:`a=d/(D+d)`, give the
    quadratic :math:`\mu a\,\mu_\mathrm{eff}^2 + \mu_\mathrm{eff} - \mu(1-a) = 0`
    whose positive root is the formula above (``derivations/mu_eff.py``).
    Assumptions: rigid circular cross-section, planar wrap, Amontons-Coulomb
    friction, inextensible rod, far from the lift-off points. Reference values
    (clove-hitch paper): :math:`\mu=0.3`, :math:`\tilde D = 1, 2, 5, 10` give
    0.147, 0.196, 0.247, 0.271.

    References
    ----------
    Clove-hitch paper, eq. (3) and the text below it; Jung, Pan & Kang, Mech. Mach.
    Theory 43 (2008) 661 (their ref. [36]).
    """
    mu = check_nonnegative("mu", mu)
    Dt = check_positive("D_over_d", D_over_d)
    mu_safe = np.where(mu > 0, mu, 1.0)
    b = 1 + Dt
    disc = b**2 + 4 * mu_safe**2 * Dt
    # the rationalised root 2 mu Dt / (b + sqrt(disc)) avoids cancellation for small mu
    out = 2 * mu_safe * Dt / (b + np.sqrt(disc))
    return np.where(mu > 0, out, 0.0)


@vectorised
def mu_from_mu_eff(mu_effective, D_over_d):
    r"""Material friction coefficient from a measured effective one (inverse of :func:`mu_eff`).

    .. math:: \mu = \frac{\mu_\mathrm{eff}(1+\tilde D)}{\tilde D - \mu_\mathrm{eff}^2}

    Parameters
    ----------
    mu_effective : array_like
        Effective coefficient measured on a capstan [-], :math:`0 \le
        \mu_\mathrm{eff} < \sqrt{\tilde D}` (the supremum of :func:`mu_eff` as
        :math:`\mu\to\infty`).
    D_over_d : array_like
        Post over rod diameter [-], > 0.

    Returns
    -------
    ndarray
        :math:`\mu` [-].

    Notes
    -----
    Solves the quadratic of :func:`mu_eff` for :math:`\mu` (it is linear in
    :math:`\mu`); ``derivations/mu_eff.py`` checks the round trip symbolically.
    """
    me = check_nonnegative("mu_effective", mu_effective)
    Dt = check_positive("D_over_d", D_over_d)
    if np.any(me**2 >= Dt):
        raise InputError(
            "mu_effective must be < sqrt(D_over_d): no material friction coefficient "
            "gives a larger effective one on that post"
        )
    return me * (1 + Dt) / (Dt - me**2)


@vectorised
def capstan_ratio_thick(mu, wrap_angle, D_over_d):
    r"""Capstan tension ratio of a rod of finite thickness.

    .. math:: \frac{T_\mathrm{high}}{T_\mathrm{low}} = e^{\mu_\mathrm{eff}(\mu, D/d)\,\theta}

    Parameters
    ----------
    mu : array_like
        Material friction coefficient [-], >= 0.
    wrap_angle : array_like
        Wrap angle [rad], >= 0.
    D_over_d : array_like
        Post over rod diameter [-], > 0.

    Returns
    -------
    ndarray
        Ratio at slip [-]; equals :func:`capstan_ratio` as :math:`D/d\to\infty`.

    Notes
    -----
    Same assumptions as :func:`mu_eff`; the end regions (lift-off) are neglected.
    Reference: clove-hitch paper eq. (3).
    """
    theta = check_nonnegative("wrap_angle", wrap_angle)
    with np.errstate(over="ignore"):
        ratio = np.exp(mu_eff(mu, D_over_d) * theta)
    return _finite_result(ratio, "the ratio exp(mu_eff(mu, D_over_d)*wrap_angle)")


@vectorised
def capstan_end_factors(mu, D_over_d):
    r"""Entry and exit factors of a sliding thick rod on a post (the end layers of eq. (3)).

    :func:`mu_eff` is the decay rate *away from the ends* of the contact. In the wrap the
    friction couple :math:`(d/2) f` per unit length is carried by a shear force
    :math:`Q = (d/2)\mu N`, which must build up where the rod comes onto the post and fall
    to zero where it leaves; these two layers multiply the sliding ratio by a factor that
    does not depend on the wrap angle:

    .. math::

        \frac{T_\mathrm{high}}{T_\mathrm{low}}
            = e^{\mu_\mathrm{eff}\theta}\; \underbrace{\frac{e^{\mu_\mathrm{eff}\Delta}}
              {\cos\Delta}}_{\text{entry}}\;
              \underbrace{\frac{|\lambda_2|}{|\lambda_2| + \mu_\mathrm{eff}}}_{\text{exit}},
        \qquad \tan\Delta = \frac{a\,\mu_\mathrm{eff}}{1-a},\quad a = \frac{d}{D+d},

    with :math:`\lambda_2 = -\bigl(1 + \sqrt{1 + 4\mu^2 a(1-a)}\bigr)/(2\mu a)` the
    negative root of :math:`\mu a\lambda^2 + \lambda - \mu(1-a) = 0` (the positive root
    is :math:`\mu_\mathrm{eff}`).

    Parameters
    ----------
    mu : array_like
        Material friction coefficient rod-post [-], >= 0.
    D_over_d : array_like
        Post diameter over rod diameter [-], > 0.

    Returns
    -------
    entry, exit : ndarray
        Factor at the high-tension end (>= 1) and at the low-tension end (<= 1) [-]; both
        tend to 1 as :math:`D/d\to\infty` or :math:`\mu\to 0`.

    Notes
    -----
    Derived here (not in the papers) for an inextensible rod in the rope limit
    (:math:`EI\to 0`) with the assumptions of :func:`mu_eff`. Exit: on the wrap
    :math:`T = A e^{-\mu_\mathrm{eff}\varphi} + B e^{-\lambda_2\varphi}`; a straight lead
    carries no shear, so the normal force vanishes where the rod leaves, which fixes the
    fast mode. Entry: the straight lead must bring the shear the wrap needs, so it meets
    the post at the angle :math:`\Delta` before its tangent point and
    :math:`T(0^+) = T_\mathrm{high}\cos\Delta`. Against the DER capstan (surface
    friction, mesh converged) at :math:`\mu = 0.5`, :math:`D/d = 1`: entry 1.0853 vs
    1.0875 measured, exit 0.9472 vs 0.9491; total +2.8 % vs +3.1 % above
    :math:`e^{\mu_\mathrm{eff}\theta}`; within about 1 % over :math:`D/d = 0.5 .. 4`,
    :math:`\mu = 0.2 .. 0.8` (``tests/scenes/test_capstan.py``).

    References
    ----------
    Clove-hitch paper, eq. (3) ("away from the loading ends"); this package.
    """
    mu = check_nonnegative("mu", mu)
    Dt = check_positive("D_over_d", D_over_d)
    mu, Dt = np.broadcast_arrays(mu, Dt)
    a = 1.0 / (1.0 + Dt)
    l1 = mu_eff(mu, Dt)
    delta = np.arctan(a * l1 / (1.0 - a))
    entry = np.exp(l1 * delta) / np.cos(delta)
    # |lambda_2| = (1 + sqrt(1 + 4 mu^2 a (1-a))) / (2 mu a); exit = |l2| / (|l2| + l1)
    # written as 1 / (1 + l1/|l2|) with l1/|l2| = 2 mu a l1 / (1 + sqrt(...)), finite at mu = 0
    ratio = 2.0 * mu * a * l1 / (1.0 + np.sqrt(1.0 + 4.0 * mu**2 * a * (1.0 - a)))
    exit_ = 1.0 / (1.0 + ratio)
    return entry, exit_


@vectorised
def capstan_ratio_thick_ends(mu, wrap_angle, D_over_d):
    r"""Sliding ratio of a thick rod with its end layers: :func:`capstan_ratio_thick` times
    the two factors of :func:`capstan_end_factors`.

    Parameters
    ----------
    mu : array_like
        Material friction coefficient [-], >= 0.
    wrap_angle : array_like
        Wrap angle [rad], >= 0; the end layers must fit in it (about 0.3 rad each at
        :math:`D/d = 1`), so small angles are outside the model.
    D_over_d : array_like
        Post over rod diameter [-], > 0.

    Returns
    -------
    ndarray
        :math:`T_\mathrm{high}/T_\mathrm{low}` at slip [-].
    """
    entry, exit_ = capstan_end_factors(mu, D_over_d)
    with np.errstate(over="ignore"):
        ratio = capstan_ratio_thick(mu, wrap_angle, D_over_d) * entry * exit_
    return _finite_result(ratio, "the ratio of mu, wrap_angle and D_over_d")


# --------------------------------------------------------------------------- bending rigidity
@vectorised
def bending_parameter(*, bending_stiffness, tension, radius):
    r"""Dimensionless bending parameter :math:`\varepsilon = \sqrt{B/(T R^2)}`.

    It is the ratio of the elastic boundary-layer length :math:`\sqrt{B/T}` to the
    capstan radius; the lift-off angle and the concentrated lift-off reaction of
    :func:`capstan_ratio_bending` scale with it.

    Parameters
    ----------
    bending_stiffness : array_like
        :math:`B = EI` [N m^2], >= 0.
    tension : array_like
        Tension of the free straight part [N], > 0.
    radius : array_like
        Radius of the centreline on the post [m], > 0.

    Returns
    -------
    ndarray
        :math:`\varepsilon` [-].
    """
    B = check_nonnegative("bending_stiffness", bending_stiffness)
    T = check_positive("tension", tension)
    R = check_positive("radius", radius)
    return np.sqrt(B / (T * R**2))


def liftoff_angle(epsilon):
    r"""Angle turned by the free elastica between lift-off and the far field.

    .. math:: \varphi = 2\arcsin(\varepsilon/2)

    From the first integral of the elastica under tension,
    :math:`B\varphi'^2/2 = T(1-\cos\varphi)`, with the curvature continuous at
    lift-off (:math:`\varphi' = 1/R`). Defined for :math:`0\le\varepsilon\le 2`.
    """
    eps = check_nonnegative("epsilon", epsilon)
    if np.any(eps > 2):
        raise InputError(
            "epsilon = sqrt(B/(T R^2)) must be <= 2: the rod is too stiff to wrap the post "
            "(it lifts off everywhere)"
        )
    return 2 * np.arcsin(eps / 2)


@vectorised
def capstan_ratio_bending(mu, wrap_angle, *, bending_stiffness, low_tension, high_tension, radius):
    r"""Capstan tension ratio of an elastic rod with bending rigidity (elastica lift-off).

    .. math::

        \frac{T_\mathrm{high}}{T_\mathrm{low}} =
        \frac{\cos\varphi_l + \mu\sin\varphi_l}{\cos\varphi_h - \mu\sin\varphi_h}\,
        e^{\mu(\theta - \varphi_l - \varphi_h)},
        \qquad \varphi_i = 2\arcsin\!\frac{\varepsilon_i}{2},\quad
        \varepsilon_i = \sqrt{\frac{B}{T_i R^2}}

    and for small :math:`\varepsilon` (derivations/capstan_ode.py)

    .. math::

        \frac{T_\mathrm{high}}{T_\mathrm{low}} \approx e^{\mu\theta}
        \Bigl[1 - \tfrac{1+\mu^2}{2}\,\frac{B}{R^2}\Bigl(\frac{1}{T_\mathrm{low}}
        - \frac{1}{T_\mathrm{high}}\Bigr)\Bigr].

    This is the limit (maximum) ratio the rod can hold for the given end tensions:
    the right-hand side depends on :math:`T_\mathrm{high}` only through the small
    lift-off correction, so a hold check compares the actual ratio with it.

    Parameters
    ----------
    mu : array_like
        Friction coefficient rod-post [-], >= 0.
    wrap_angle : array_like
        Angle :math:`\theta` between the directions of the two straight far-field
        parts [rad] (the wrap angle of the end loads), >= 0.
    bending_stiffness : array_like
        :math:`B = EI` [N m^2], >= 0.
    low_tension, high_tension : array_like
        End tensions [N], > 0.
    radius : array_like
        Centreline radius on the post [m], > 0.

    Returns
    -------
    ndarray
        Ratio at slip [-]; exactly :func:`capstan_ratio` when :math:`B = 0`.

    Notes
    -----
    Form implemented: the lift-off mechanism of Stuart (1961) and Jung, Pan & Kang
    (Tribol. Int. 41 (2008) 524; Mech. Mach. Theory 43 (2008) 661) -- on the wrapped
    arc the curvature is :math:`1/R`, the moment :math:`B/R` is constant and the
    ideal capstan law holds; at each lift-off point the free part, an elastica of
    boundary-layer length :math:`\sqrt{B/T}`, turns by :math:`\varphi` and exerts a
    concentrated reaction :math:`P = T\sin\varphi \approx T\varepsilon` carrying
    friction :math:`\mu P`; the contact arc shrinks to :math:`\theta-\varphi_l-\varphi_h`.
    The closed form above is our own derivation of that mechanism
    (``derivations/capstan_ode.py``, checked against a numerical elastica in the
    tests); the printed formulas of Stuart and of Jung et al. could not be
    consulted, so compare with them before relying on the O(B) coefficient. The
    :math:`O(\varepsilon)` point-friction gain and contact-arc loss cancel; the
    net effect is :math:`O(\varepsilon^2)` and *lowers* the ratio (stiff rods grip
    less), as Jung et al. report.

    Assumptions and validity: planar, inextensible Kirchhoff rod, long straight
    free parts, thin rod (friction at the centreline; combine with
    :func:`mu_eff` for thick rods), :math:`\varepsilon_i \le 2`,
    :math:`\varphi_l+\varphi_h \le \theta` and :math:`\mu\tan\varphi_h < 1`;
    otherwise InputError.
    """
    mu = check_nonnegative("mu", mu)
    theta = check_nonnegative("wrap_angle", wrap_angle)
    e_l = bending_parameter(bending_stiffness=bending_stiffness, tension=low_tension, radius=radius)
    e_h = bending_parameter(
        bending_stiffness=bending_stiffness, tension=high_tension, radius=radius
    )
    phi_l = liftoff_angle(e_l)
    phi_h = liftoff_angle(e_h)
    if np.any(phi_l + phi_h > theta):
        raise InputError(
            "wrap_angle is smaller than the two lift-off angles: the rod touches the post "
            "only at points, outside the validity of the capstan-with-bending model"
        )
    den = np.cos(phi_h) - mu * np.sin(phi_h)
    if np.any(den <= 0):
        raise InputError("mu*tan(lift-off angle) must be < 1 at the high-tension end")
    num = np.cos(phi_l) + mu * np.sin(phi_l)
    with np.errstate(over="ignore"):
        ratio = num / den * np.exp(mu * (theta - phi_l - phi_h))
    return _finite_result(ratio, "the ratio exp(mu*wrap_angle) of mu and wrap_angle")


# --------------------------------------------------------------------------- nonlinear friction
@vectorised
def capstan_high_tension_nonlinear(
    *, low_tension, wrap_angle, friction_coefficient, friction_exponent, radius
):
    r"""Largest high-side tension with nonlinear (Howell) friction :math:`f = a N^n`.

    With normal force per unit length :math:`N = T/R` and friction per unit length
    :math:`f = aN^n`, :math:`dT/d\theta = aR^{1-n}T^n` integrates to

    .. math::

        T_\mathrm{high} = \Bigl[T_\mathrm{low}^{1-n} + (1-n)\,a\,R^{1-n}\,\theta\Bigr]^{1/(1-n)},
        \qquad n \ne 1,

    and to :math:`T_\mathrm{low}e^{a\theta}` for :math:`n = 1` (Amontons, :math:`a=\mu`).

    Parameters
    ----------
    low_tension : array_like
        [N], > 0.
    wrap_angle : array_like
        [rad], >= 0.
    friction_coefficient : array_like
        :math:`a` [N^(1-n) m^(n-1)], >= 0 (equals :math:`\mu` when :math:`n=1`).
    friction_exponent : array_like
        :math:`n` [-], in (0, 1]; fibres and polymers typically 0.67-1 (Howell).
        For :math:`n > 1` the law predicts a finite-angle blow-up and is refused.
    radius : array_like
        Centreline radius [m], > 0.

    Returns
    -------
    ndarray
        :math:`T_\mathrm{high}` [N].

    Notes
    -----
    Thin flexible rope, planar wrap, friction local in :math:`N`. Unlike the
    Amontons case the ratio depends on the tension level and on :math:`R`.

    References
    ----------
    Howell, J. Text. Inst. 44 (1953) T359 / 45 (1954) T575; Jung, Pan & Kang,
    Tribol. Int. 41 (2008) 524, Mech. Mach. Theory 43 (2008) 661.
    Derivation: ``derivations/capstan_ode.py``.
    """
    t0 = check_positive("low_tension", low_tension)
    theta = check_nonnegative("wrap_angle", wrap_angle)
    a = check_nonnegative("friction_coefficient", friction_coefficient)
    n = check_positive("friction_exponent", friction_exponent)
    R = check_positive("radius", radius)
    if np.any(n > 1):
        raise InputError("friction_exponent must lie in (0, 1]")
    one_minus_n = 1.0 - n
    linear = np.isclose(one_minus_n, 0.0, atol=1e-9)
    safe = np.where(linear, 1.0, one_minus_n)
    with np.errstate(over="ignore"):
        base = t0**safe + safe * a * R**safe * theta
        nonlinear = base ** (1.0 / safe)
        t_high = np.where(linear, t0 * np.exp(a * theta), nonlinear)
    return _finite_result(
        t_high, "the high tension of low_tension, friction_coefficient and wrap_angle"
    )


@vectorised
def capstan_ratio_nonlinear(
    *, low_tension, wrap_angle, friction_coefficient, friction_exponent, radius
):
    r"""Ratio :math:`T_\mathrm{high}/T_\mathrm{low}` of :func:`capstan_high_tension_nonlinear`."""
    t_high = capstan_high_tension_nonlinear(
        low_tension=low_tension,
        wrap_angle=wrap_angle,
        friction_coefficient=friction_coefficient,
        friction_exponent=friction_exponent,
        radius=radius,
    )
    return t_high / np.asarray(low_tension, dtype=float)
