"""The capstan ODE and its generalisations (used by knotmech.analytic.capstan).

1. Ideal rope: an element of the rope on the post (radius R) at the onset of slip
   has normal force per length N = T/R and friction mu N opposing the slip, so
   dT/ds = mu T / R, i.e. dT/dtheta = mu T: T_high = T_low exp(mu theta), and the
   profile from the high end is T(s) = T_high exp(-mu s/R).
2. Nonlinear (Howell) friction: friction per length f = a N^n with N = T/R gives
   dT/dtheta = a R^(1-n) T^n; separating variables,
   T_high^(1-n) - T_low^(1-n) = (1-n) a R^(1-n) theta.
3. Bending rigidity (Stuart 1961; Jung, Pan & Kang 2008 mechanism): on the wrapped
   arc the curvature is 1/R and the moment B/R constant, so the shear vanishes and
   the ideal law holds there. Each straight free part is an elastica under the
   far-field tension T: B phi'' = T sin(phi) (phi the angle of the tangent to the
   far-field direction), first integral B phi'^2 / 2 = T (1 - cos phi). At lift-off
   the curvature is continuous, phi' = 1/R, hence sin(phi0/2) = eps/2 with
   eps = sqrt(B/(T R^2)). The free part carries the force T along the far-field
   direction; resolving it on the local tangent/normal at lift-off and adding the
   concentrated reaction P = T sin(phi0) with friction mu P gives the tension just
   inside the contact:
       low end:  T_a = T_low (cos phi_l + mu sin phi_l)
       high end: T_high (cos phi_h - mu sin phi_h) = T_b
   and on the arc (angle theta - phi_l - phi_h) T_b = T_a exp(mu (theta - phi_l - phi_h)).

Run ``python derivations/capstan_ode.py`` to print the results.
"""

from __future__ import annotations

import sympy as sp

mu, theta, R, s = sp.symbols("mu theta R s", positive=True)
T_low, T_high = sp.symbols("T_low T_high", positive=True)
a, n = sp.symbols("a n", positive=True)
B, T, eps = sp.symbols("B T epsilon", positive=True)
phi_l, phi_h = sp.symbols("phi_l phi_h", nonnegative=True)


def derive_ideal_ratio():
    """T_high/T_low of the ideal capstan, by solving dT/dtheta = mu T, T(0) = T_low."""
    th = sp.symbols("th")
    Tf = sp.Function("T")
    sol = sp.dsolve(sp.Eq(Tf(th).diff(th), mu * Tf(th)), Tf(th), ics={Tf(0): T_low})
    return sp.simplify(sol.rhs.subs(th, theta) / T_low)


def derive_profile():
    """T(s) from the high end: dT/ds = -mu T / R with T(0) = T_high."""
    Tf = sp.Function("T")
    sol = sp.dsolve(sp.Eq(Tf(s).diff(s), -mu * Tf(s) / R), Tf(s), ics={Tf(0): T_high})
    return sp.simplify(sol.rhs)


def derive_nonlinear_high_tension():
    """T_high for friction per length a N^n (n != 1) by separation of variables."""
    x = sp.symbols("x", positive=True)
    # dT/dtheta = a R^(1-n) T^n  ->  int_{T_low}^{T_high} T^-n dT = a R^(1-n) theta
    # conds="none" returns the n != 1 branch of the Piecewise
    lhs = sp.integrate(x ** (-n), (x, T_low, T_high), conds="none")
    sol = sp.solve(sp.Eq(lhs, a * R ** (1 - n) * theta), T_high)
    return sp.simplify(sol[0])


def derive_liftoff_angle():
    """Lift-off angle phi0(eps) from the elastica first integral with phi' = 1/R at lift-off."""
    phi = sp.symbols("phi", positive=True)
    # first integral of B phi'' = T sin(phi) decaying at infinity
    first_integral = B * (1 / R) ** 2 / 2 - T * (1 - sp.cos(phi))
    sols = sp.solve(first_integral, phi)
    phi0 = min(sols, key=lambda e: sp.N(e.subs({B: 1, T: 1, R: 10})))
    return sp.simplify(phi0.subs(B, eps**2 * T * R**2))


def elastica_first_integral_residual():
    """d/ds of [B phi'^2/2 - T (1 - cos phi)] on solutions of B phi'' = T sin phi (must be 0)."""
    phi = sp.Function("phi")
    expr = B * phi(s).diff(s) ** 2 / 2 - T * (1 - sp.cos(phi(s)))
    d = sp.diff(expr, s).subs(phi(s).diff(s, 2), T * sp.sin(phi(s)) / B)
    return sp.simplify(d)


def derive_bending_ratio():
    """T_high/T_low with bending rigidity, in terms of the lift-off angles phi_l, phi_h."""
    Ta = T_low * (sp.cos(phi_l) + mu * sp.sin(phi_l))
    Tb = Ta * sp.exp(mu * (theta - phi_l - phi_h))
    Th = sp.solve(sp.Eq(T_high * (sp.cos(phi_h) - mu * sp.sin(phi_h)), Tb), T_high)[0]
    return sp.simplify(Th / T_low)


def derive_bending_ratio_series(order=3):
    """Series of the bending ratio in the lift-off angles, to O(phi^order) (ratio/e^{mu theta})."""
    x = sp.symbols("x", positive=True)  # bookkeeping parameter
    expr = derive_bending_ratio() / sp.exp(mu * theta)
    expr = expr.subs({phi_l: x * phi_l, phi_h: x * phi_h})
    ser = sp.series(expr, x, 0, order).removeO().subs(x, 1)
    return sp.expand(sp.simplify(ser))


if __name__ == "__main__":
    print("ideal ratio:", derive_ideal_ratio())
    print("profile:", derive_profile())
    print("Howell T_high:", derive_nonlinear_high_tension())
    print("lift-off angle:", derive_liftoff_angle())
    print("elastica first integral d/ds:", elastica_first_integral_residual())
    print("bending ratio:", derive_bending_ratio())
    print("series / e^(mu theta):", derive_bending_ratio_series())
