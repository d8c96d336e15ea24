"""Loose elastic trefoil at leading order (Audoly, Clauvelin & Neukirch, PRL 99, 164301, 2007).

In the loose limit ``epsilon = sqrt(h/R) -> 0`` the knot is, at leading order, a single
circular loop of radius R (the braid where the rod crosses itself is short against R).
Its bending energy is ``U = (B/2)(1/R)^2 * 2 pi R = pi B/R`` and the rod it holds,
the end-to-end shortening, is ``e = 2 pi R``. Pulling the ends apart by ``dD = -de``
stores ``F dD = dU``, so ``F = -dU/de``. Friction (order ``mu epsilon^3`` in ``F h^2/B``)
and twist, which the paper also treats, are beyond this leading order and not derived.
"""

from __future__ import annotations

import sympy as sp

B, R, e, h = sp.symbols("B R e h", positive=True)


def loose_knot_force():
    """(F(e), F(R), F h^2/B in epsilon): ``2 pi^2 B/e^2``, ``B/(2 R^2)``, ``epsilon^4/2``."""
    energy_of_e = (B / 2 * (1 / R) ** 2 * 2 * sp.pi * R).subs(R, e / (2 * sp.pi))
    force_e = sp.simplify(-sp.diff(energy_of_e, e))
    force_r = sp.simplify(force_e.subs(e, 2 * sp.pi * R))
    eps = sp.symbols("epsilon", positive=True)
    scaled = sp.simplify((force_r * h**2 / B).subs(h, eps**2 * R))
    return force_e, force_r, scaled


if __name__ == "__main__":
    fe, fr, fs = loose_knot_force()
    print("F(e) =", fe, "; F(R) =", fr, "; F h^2/B =", fs)
