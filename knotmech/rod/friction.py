"""Friction laws for rod contact.

Two laws, both used through the contact interactions of :mod:`knotmech.rod.contact`:

- :class:`SmoothFriction`, the regularised Coulomb law of the coated-rod paper (eqs. 11-12)
  for rod-rod contact: the sliding force is scaled by a smooth stick-slip weight
  :func:`stick_slip_weight` of the tangential relative speed. It does not truly stick (a held
  load creeps slowly), which is what that paper uses for knots.
- :class:`AnchorFriction`, an elasto-plastic "anchor spring" (return mapping of Coulomb's law
  with a tangential penalty) for contact with rigid cylinders and for rod-rod contact: it
  truly sticks below mu_s N and slides at mu_k N above, with mu_s >= mu_k.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from knotmech.errors import InputError, check_nonnegative, check_positive


def stick_slip_weight(tangential_speed, *, sharpness, threshold):
    r"""Smooth stick-slip weight of the coated-rod paper, eq. (12).

    .. math:: \gamma = \frac{1}{1 + e^{-k(\|v_T\| - c)}}

    Parameters
    ----------
    tangential_speed : array_like [m/s]
        Magnitude of the tangential relative velocity.
    sharpness : float [s/m]
        k; the paper uses k = 50/r0 (r0 the rod radius, in the same length unit).
    threshold : float [m/s]
        c; the paper uses c = 0.15 r0 (per second).

    Returns
    -------
    gamma : ndarray, in [0, 1]
        0 (static) ... 1 (fully sliding friction ``mu |F_n|``).

    References
    ----------
    Coated-rod paper, J. Appl. Mech. (DOI 10.1115/1.4055544), eq. (12).
    """
    v = np.asarray(tangential_speed, dtype=float)
    k = check_positive("sharpness", sharpness)
    c = check_nonnegative("threshold", threshold)
    return 0.5 * (1.0 + np.tanh(0.5 * k * (v - c)))


def default_stick_slip_parameters(rod_radius):
    """The coated-rod paper's choice k = 50/r0 [s/m], c = 0.15 r0 [m/s] (after eq. 12)."""
    r0 = float(check_positive("rod_radius", rod_radius, scalar=True))
    return 50.0 / r0, 0.15 * r0


@dataclass(frozen=True)
class SmoothFriction:
    """Regularised Coulomb friction of the coated-rod paper (eqs. 11-12), for rod-rod contact.

    Parameters
    ----------
    mu : float
        Friction coefficient (>= 0).
    sharpness : float or None [s/m]
        k of the stick-slip weight; None -> 50/r0 with r0 the smallest rod radius.
    threshold : float or None [m/s]
        c of the stick-slip weight; None -> 0.15 r0.
    """

    mu: float
    sharpness: float | None = None
    threshold: float | None = None

    def __post_init__(self):
        check_nonnegative("mu", self.mu)
        if self.sharpness is not None:
            check_positive("sharpness", self.sharpness)
        if self.threshold is not None:
            check_nonnegative("threshold", self.threshold)

    def parameters(self, rod_radius):
        """(mu, k, c) with the defaults resolved for ``rod_radius`` [m]."""
        k0, c0 = default_stick_slip_parameters(rod_radius)
        k = k0 if self.sharpness is None else self.sharpness
        c = c0 if self.threshold is None else self.threshold
        return float(self.mu), float(k), float(c)


#: Default floor of the anchor law's cap width, in units of r_i + r_j (issue 24). Evidence
#: (docs/notes/contact-and-friction/sticking-law-cap-width.md, sections 1-3 and 9): with
#: 1e-2 the sliding pairs of a tight coated n = 3 overhand carry 0.995-1 mu_k |F_n| and no
#: sticking pair exceeds mu_s |F_n|; the knot's tight-phase force follows mu (17.9 / 70.9 /
#: 117 mN at mu 0.2 / 0.6 / 0.9 against the regularised law's 17.9 / 74.9 / 143 mN, where
#: the law without the floor gave 40-50 mN at every mu); a 0.5 s wait slice at mu 0.6
#: costs 251 steps instead of 3434. 1e-3 leaves the sliding pairs' direction flipping
#: (653 steps). Single-pair pull-out and sliding stay within 1 % of 2 mu F_n.
CAP_FLOOR = 1e-2

#: How :attr:`AnchorFriction.floor_rule` measures the cap floor and where it applies
#: (kernel ``floor_mode`` = index; see the class).
FLOOR_RULES = ("all", "sliding", "penalty", "min")
#: Default floor rule since session 15 (issue 24): the smaller of c_f (r_i + r_j) and one
#: penalty width per 1e-2 of c_f. The clove-hitch paper's free-end hitch (sec. 7) holds with
#: it (the radii floor alone, 3 penalty widths there, lets it slip), the coated n = 3
#: overhand pull at mu 0.9 takes 1.31x the regularised law's steps (radii floor, 1.04
#: penalty widths there, is the smaller), the kappa-0.01 clove point holds at 1.5-1.7x a solid
#: rod's CPU (sticking-law-cap-width.md sec. 11).
FLOOR_RULE = "min"


@dataclass(frozen=True)
class AnchorFriction:
    r"""Elasto-plastic (anchor spring) Coulomb friction with static and kinetic coefficients.

    Stick: :math:`F_t = -k_t w\,P_n(x - x_a)` (w the node's length, P_n the tangent-plane
    projector); slip when :math:`|F_t| > \mu N`, then :math:`|F_t| = \mu N` and the anchor
    :math:`x_a` follows. :math:`\mu = \mu_s` for a contact that stuck at the previous step,
    :math:`\mu_k` for one that slid. State is committed once per accepted step.

    Parameters
    ----------
    mu_static : float
        Static coefficient mu_s (>= mu_kinetic).
    mu_kinetic : float or None
        Kinetic coefficient mu_k (>= 0); None -> equal to mu_static.
    tangential_stiffness : float or None
        k_t; rod-cylinder: per unit rod length [N/m^2], rod-rod: per contact pair [N/m];
        None -> the contact's normal penalty stiffness scale.
    cap_floor : float
        Rod-rod only, dimensionless (>= 0): floor on the width of the anchor spring's
        smooth cap, :math:`a = \max(\mu |F_n|/k_t, c_f (r_i + r_j))` [m] (:math:`c_f` the
        floor, r the two edges' radii). Default :data:`CAP_FLOOR` (1e-2): a lightly loaded
        pair sticks on the softer spring :math:`\mu |F_n|/a` and slides (at
        :math:`\mu_k |F_n|`, as before) once its tangential gap exceeds 10 a; the sliding
        pairs' friction direction then no longer flips between Newton iterates. 0 is the
        law as shipped before issue 24 (the stiff cap :math:`\mu |F_n|/k_t` alone, which
        built the hold tables of ``knotmech/data`` up to then), kept to reproduce them. No
        effect on rod-cylinder contact.
    floor_rule : str
        How the floor is measured and where it applies (sticking-law-cap-width.md sec. 11):
        "all": :math:`c_f (r_i + r_j)` on every pair (the default of issue 24 up to
        session 15); "sliding": the same, only
        on the pairs that slid at the last accepted step (a sticking pair keeps the stiff
        cap; the commit moves an anchor whose width changes to the gap that keeps its
        force); "penalty": :math:`(c_f / \mathrm{CAP\_FLOOR}) / k` on every pair, k the
        contact penalty's sharpness [1/m], i.e. the default :math:`c_f` floors the cap at
        the penalty's own width 1/k (the tangential spring no narrower than the normal
        one's); "min" (default, :data:`FLOOR_RULE`): the smaller of the two lengths,
        :math:`\min(c_f (r_i + r_j), (c_f / \mathrm{CAP\_FLOOR}) / k)`, on every pair.

    References
    ----------
    P. Wriggers, Computational Contact Mechanics, 2nd ed. (Springer 2006), sect. 5.2.2.
    """

    mu_static: float
    mu_kinetic: float | None = None
    tangential_stiffness: float | None = None
    cap_floor: float = CAP_FLOOR
    floor_rule: str = FLOOR_RULE

    def __post_init__(self):
        check_nonnegative("mu_static", self.mu_static)
        check_nonnegative("cap_floor", self.cap_floor)
        if self.floor_rule not in FLOOR_RULES:
            raise InputError(
                f"floor_rule must be one of {', '.join(FLOOR_RULES)}, got {self.floor_rule!r}"
            )
        if self.mu_kinetic is not None:
            check_nonnegative("mu_kinetic", self.mu_kinetic)
            if self.mu_kinetic > self.mu_static:
                raise InputError(
                    f"mu_kinetic must be <= mu_static ({self.mu_static}), got {self.mu_kinetic}"
                )
        if self.tangential_stiffness is not None:
            check_positive("tangential_stiffness", self.tangential_stiffness)

    @property
    def mu_k(self) -> float:
        return float(self.mu_static if self.mu_kinetic is None else self.mu_kinetic)

    @property
    def mu_s(self) -> float:
        return float(self.mu_static)
