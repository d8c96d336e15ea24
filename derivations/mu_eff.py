"""Effective capstan friction coefficient of a thick rod, from force and moment balance.

A rod of diameter d is wrapped on a post of diameter D; its centreline lies on the
circle of radius R = (D+d)/2 (curvature kappa = 1/R). Per unit centreline length
the post pushes with a normal force N (through the centreline) and a friction
force f = mu N that acts at the contact line, at distance d/2 from the centreline
toward the post. Planar Kirchhoff rod, internal force n = T t + Q nu (nu toward
the post axis), bending moment M = B kappa constant on the wrapped arc:

    tangential force   T' - kappa Q + f = 0
    normal force       kappa T + Q' - N = 0
    moment             M' + Q - (d/2) f = 0    (couple of the friction, r_c x f)

With M' = 0 the moment balance gives Q = (d/2) f, and with an exponential ansatz
T, N ~ exp(-lam s/R) the two force balances become

    T' = -mu N (1 - a),     N (1 + mu lam a) = T/R,     a = d/(D+d),

so mu a lam^2 + lam - mu (1-a) = 0; the positive root, written with
Dt = D/d, is the clove-hitch paper's mu_eff (eq. (3) and text).

Run ``python derivations/mu_eff.py`` to print the results.
"""

from __future__ import annotations

import sympy as sp

mu, lam, Dt = sp.symbols("mu lambda Dt", positive=True)
s, R, d, D, T0, N0 = sp.symbols("s R d D T0 N0", positive=True)


def balance_equations():
    """The three balance equations with the exponential ansatz substituted.

    Returns the list of expressions (each = 0) in the unknowns N0 (normal force
    amplitude) and lam (decay rate), for given T0, mu, d, D.
    """
    kappa = 1 / R
    T = T0 * sp.exp(-lam * s / R)
    N = N0 * sp.exp(-lam * s / R)
    f = mu * N
    Q = d / 2 * f  # from the moment balance with M' = 0
    M = sp.Integer(0)  # constant moment: only its derivative enters
    tangential = sp.diff(T, s) - kappa * Q + f
    normal = kappa * T + sp.diff(Q, s) - N
    moment = sp.diff(M, s) + Q - d / 2 * f
    scale = sp.exp(lam * s / ((D + d) / 2))
    return [sp.simplify(e.subs(R, (D + d) / 2) * scale) for e in (tangential, normal, moment)]


def quadratic():
    """The polynomial in lam (coefficients in mu and Dt) whose root is mu_eff."""
    tangential, normal, _ = balance_equations()
    n0 = sp.solve(normal, N0)[0]
    eq = sp.simplify(tangential.subs(N0, n0) / T0)
    eq = sp.together(eq.subs(D, Dt * d))
    num = sp.numer(eq)
    return sp.Poly(sp.expand(num), lam)


def derive_mu_eff():
    """Return mu_eff(mu, Dt) as a SymPy expression (the positive root)."""
    poly = quadratic()
    roots = sp.solve(poly.as_expr(), lam)
    # the physical root is the one that is positive for mu > 0
    for r in roots:
        val = r.subs({mu: sp.Rational(3, 10), Dt: 2})
        if sp.N(val) > 0:
            return sp.simplify(r)
    raise RuntimeError("no positive root")  # pragma: no cover


def derive_mu_from_mu_eff():
    """Return the material mu as a function of the measured mu_eff (symbol lam) and Dt."""
    poly = quadratic()
    sol = sp.solve(poly.as_expr(), mu)
    return sp.simplify(sol[0])


def paper_form():
    """The clove-hitch paper's printed form, for comparison."""
    return (-(1 + Dt) + sp.sqrt((1 + Dt) ** 2 + 4 * mu**2 * Dt)) / (2 * mu)


if __name__ == "__main__":
    expr = derive_mu_eff()
    print("quadratic in lambda:", quadratic().as_expr())
    print("mu_eff =", expr)
    print("equals the paper's form:", sp.simplify(expr - paper_form()) == 0)
    print("inverse: mu =", derive_mu_from_mu_eff())
    for dt in (1, 2, 5, 10):
        print(f"mu = 0.3, D/d = {dt}: mu_eff = {float(expr.subs({mu: 0.3, Dt: dt})):.4f}")
