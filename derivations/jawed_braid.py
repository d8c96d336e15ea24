"""The braid law of long overhand knots (Jawed, Dieleman, Audoly & Reis, PRL 115, 118302, 2015).

Run as a script to print the results. Functions:

* :func:`helix_contact_force` - Kirchhoff equations for a naturally straight, untwisted
  isotropic rod bent into a helix of radius a and wave number k under tension T: the
  distributed force it needs is ``p = kappa (T + B tau^2)`` along the principal normal;
  returns the exact expression and its leading order ``B a k^4`` for ``a k -> 0``, T -> 0.
* :func:`braid_force` - sliding friction ``mu p`` over the braid length ``2 pi n / k`` with
  ``a = h`` (strands in contact): ``F = 2 pi mu n h B k^3`` (their Eq. 4).
* :func:`loop_closure` - the loop, a planar elastica ``kappa^2 R^2 = 1 - m sin^2(theta/2)``
  turning by 2 pi: checks that it solves ``B theta'' + P sin(theta) = 0`` with
  ``P = m B/(4 R^2)`` and integrates its length ``4 R K(m)`` and the braid length
  ``R [8 (K - E)/m - 4 K]`` (the chord it leaves between its ends).
* :func:`master_curve` - with ``h k^2 = 1/(sqrt(12) R)`` (their Eq. 3, taken from the
  paper) and the shortening ``e = l + lambda``: ``n^2 h/e`` and ``n^2 F h^2/(mu B)`` as
  functions of ``x = l/R`` and ``lambda/R`` (their Eq. 5).
"""

from __future__ import annotations

from functools import cache

import sympy as sp

a, k, z, T, B = sp.symbols("a k z T B", positive=True)
h, n, mu, R, m = sp.symbols("h n mu R m", positive=True)
x, lam = sp.symbols("x lambda_R", positive=True)


def _frenet_helix():
    """Unit tangent, normal, binormal, curvature, torsion of (a cos kz, a sin kz, z)."""
    pos = sp.Matrix([a * sp.cos(k * z), a * sp.sin(k * z), z])
    dpos = pos.diff(z)
    speed = sp.sqrt(sp.simplify(dpos.dot(dpos)))  # ds/dz
    tangent = sp.simplify(dpos / speed)
    dt_ds = sp.simplify(tangent.diff(z) / speed)
    kappa = sp.simplify(sp.sqrt(sp.simplify(dt_ds.dot(dt_ds))))
    normal = sp.simplify(dt_ds / kappa)
    binormal = sp.simplify(tangent.cross(normal))
    db_ds = sp.simplify(binormal.diff(z) / speed)
    tau = sp.simplify(-db_ds.dot(normal))
    return tangent, normal, binormal, kappa, tau, speed


@cache
def helix_contact_force():
    """(p_exact, p_leading): line force per unit length holding the helix in shape.

    Moment of an untwisted isotropic rod: ``m = B kappa b``. Force ``n = T t + N_b b``.
    Moment balance ``m' + t x n = 0`` fixes ``N_b = -B kappa tau``; force balance
    ``n' + p = 0`` then gives ``p``. Returned as the component along ``-normal`` (pushing
    the strand away from the braid axis, as the other strand does).
    """
    t, nrm, b, kappa, tau, speed = _frenet_helix()
    nb = sp.symbols("N_b")
    moment = B * kappa * b
    force = T * t + nb * b
    moment_balance = sp.simplify(moment.diff(z) / speed + t.cross(force))
    nb_value = sp.solve(sp.simplify(moment_balance.dot(nrm)), nb)[0]
    force = force.subs(nb, nb_value)
    p_vec = -sp.simplify(force.diff(z) / speed)
    p = sp.simplify(-p_vec.dot(nrm))
    # check: no other component, and p = kappa (T + B tau^2)
    assert sp.simplify(p_vec.dot(t)) == 0 and sp.simplify(p_vec.dot(b)) == 0
    assert sp.simplify(p - kappa * (T + B * tau**2)) == 0
    leading = sp.limit(p.subs(T, 0) / (a * k**4), a, 0) * a * k**4
    return p, sp.simplify(leading)


def braid_force():
    """F = mu * p * l with p = B h k^4 (a = h) and l = 2 pi n / k: ``2 pi mu n h B k^3``."""
    _, p_leading = helix_contact_force()
    return sp.simplify(mu * p_leading.subs(a, h) * 2 * sp.pi * n / k)


@cache
def loop_closure():
    """(residual, loop_length, braid_length) of the elastica loop in units of R.

    ``residual`` is ``B theta'' + P sin(theta)`` along ``theta' = sqrt(1 - m sin^2(theta/2))/R``
    with ``P = m B/(4 R^2)`` (zero). Lengths from ``ds = dtheta/theta'``, theta in [0, 2 pi]:
    ``lambda = int ds`` and the chord ``int cos(theta) ds``, whose negative is the braid length
    (the loop re-enters the braid a distance l behind where it left).
    """
    theta, phi = sp.symbols("theta phi", positive=True)
    dtheta = sp.sqrt(1 - m * sp.sin(theta / 2) ** 2) / R
    d2theta = sp.diff(dtheta, theta) * dtheta  # theta'' = d(theta')/dtheta * theta'
    residual = sp.simplify(B * d2theta + m * B / (4 * R**2) * sp.sin(theta))
    # theta = 2 phi, phi in [0, pi]: ds = 2 R dphi / sqrt(1 - m sin^2 phi); symmetric halves
    w = 1 / sp.sqrt(1 - m * sp.sin(phi) ** 2)
    big_k = sp.integrate(w, (phi, 0, sp.pi / 2))
    big_e = sp.integrate(1 / w, (phi, 0, sp.pi / 2))
    loop_length = sp.simplify(2 * 2 * big_k)  # 2R * int_0^pi w dphi / R
    # cos(theta) = 1 - 2 sin^2 phi = (1 - 2/m) + (2/m)(1 - m sin^2 phi)
    chord = sp.simplify(2 * 2 * ((1 - 2 / m) * big_k + (2 / m) * big_e))
    return residual, loop_length, sp.simplify(-chord)


def master_curve():
    """(n^2 h/e, n^2 F h^2/(mu B)) in terms of x = l/R and lambda_R = lambda/R.

    Uses Eq. (3), ``k^2 = 1/(sqrt(12) h R)``, ``l = 2 pi n/k``, ``e = l + lambda`` and
    :func:`braid_force`.
    """
    kk = 1 / sp.sqrt(sp.sqrt(12) * h * R)
    h_of_x = sp.solve(sp.Eq(x, 2 * sp.pi * n / (kk * R)), h)[0]  # x = l/R fixes h/R
    e = R * (x + lam)
    ratio_e = sp.simplify((n**2 * h / e).subs(h, h_of_x))
    force = braid_force().subs(k, kk)
    ratio_f = sp.simplify((n**2 * force * h**2 / (mu * B)).subs(h, h_of_x))
    return ratio_e, ratio_f


if __name__ == "__main__":
    p, p0 = helix_contact_force()
    print("helix line force p =", p, "; leading order:", p0)
    print("braid force F =", braid_force())
    res, lam_r, l_r = loop_closure()
    print("elastica residual:", res, "; lambda/R =", lam_r, "; l/R =", l_r)
    print("master curve (n^2 h/e, n^2 F h^2/(mu B)) =", master_curve())
