"""Holding ratios of hitches in the wrap / nip chain model (used by knotmech.analytic.hitch).

Elements, read from the free end (tension T_low) toward the load (T_high), at the
onset of slip (the rope is pulled through toward the load; every friction force
takes its limiting value):

- wrap of angle theta with friction coefficient m:      T_out = exp(m theta) T_in
- nip under a rider of tension T_r, normal force n T_r, the pinched strand gripped
  on both faces (coefficients below + above = g):          T_out = T_in + g n T_r

Solving the linear equations for T_high/T_low gives the holding ratio K; a
non-positive denominator means the loop "nip -> wrap -> rider -> nip" amplifies
itself: self-locking (Bayman's "self-locking unit"), K = infinity.

Nip force (this work): the rider of diameter d lies on a support of diameter Ds with
its centreline at radius a = (Ds+d)/2 and is lifted to r = (Ds+3d)/2 over the
crossing strand. Its two straight tangents to the circle of radius a meet at the
apex, each turned by arccos(a/r) from the circle, so the point force is
2 T_r sin(arccos(a/r)) = 2 T_r sqrt(1 - (a/r)^2).

Ideal rope: d -> 0 gives n -> 0, and K is the capstan ratio of the total wrap, so a
free end (T_low = 0) never holds: T_high <= K * 0.

Run ``python derivations/hitches.py`` to print the results.
"""

from __future__ import annotations

import sympy as sp

# wrap coefficients (mu or mu_eff on the post, mu_rr or its mu_eff on the standing part)
m_post, m_rope = sp.symbols("m_post m_rope", nonnegative=True)
theta_in, theta_out, theta_p, theta_h = sp.symbols(
    "theta_in theta_out theta_p theta_h", positive=True
)
G, G_r = sp.symbols("G G_r", nonnegative=True)  # grip * nip factor on the post / on the rope
T_low, d, Ds = sp.symbols("T_low d D_s", positive=True)


def nip_factor():
    """n(d, Ds): normal force at a nip per unit rider tension (rider lifted over a strand)."""
    a = (Ds + d) / 2
    r = (Ds + 3 * d) / 2
    psi = sp.acos(a / r)  # turn of each tangent at the apex
    return sp.simplify(2 * sp.sin(psi))


def clove_hitch_ratio():
    """K of the clove hitch: free end -> nip -> wrap theta_out -> rider -> wrap theta_in -> nip.

    Both nips are pressed by the rider (tension T_r); G = (mu + mu_rr) n(d, D).
    """
    t1, Tr, t2, Th = sp.symbols("t1 T_r t2 T_high")
    eqs = [
        sp.Eq(t1, T_low + G * Tr),  # exit nip (free end under the rider)
        sp.Eq(Tr, sp.exp(m_post * theta_out) * t1),  # second turn, up to the rider
        sp.Eq(t2, sp.exp(m_post * theta_in) * Tr),  # first turn, rider to entrance
        sp.Eq(Th, t2 + G * Tr),  # entrance nip (loaded strand under the rider)
    ]
    sol = sp.solve(eqs, [t1, Tr, t2, Th], dict=True)[0]
    return sp.simplify(sol[Th] / T_low)


def half_hitch_factor():
    """Factor h of one half hitch: free end -> nip under its own turn -> wrap theta_h.

    The turn around the standing part is the rider; G_r = 2 mu_rr n(d, d).
    """
    t1, Tr = sp.symbols("t1 T_r")
    eqs = [
        sp.Eq(t1, T_low + G_r * Tr),
        sp.Eq(Tr, sp.exp(m_rope * theta_h) * t1),
    ]
    sol = sp.solve(eqs, [t1, Tr], dict=True)[0]
    return sp.simplify(sol[Tr] / T_low)


def two_half_hitches_ratio():
    """K of a post wrap theta_p followed by two half hitches on the standing part."""
    return sp.simplify(sp.exp(m_post * theta_p) * half_hitch_factor() ** 2)


def round_turn_ratio():
    """K of a round turn (a pure wrap theta_p): the capstan."""
    return sp.exp(m_post * theta_p)


def ideal_limit(expr):
    """The zero-thickness limit (n -> 0, so G, G_r -> 0) of a holding ratio."""
    return sp.simplify(expr.subs({G: 0, G_r: 0}))


def clove_hitch_lock_condition():
    """Self-locking parameter of the clove hitch: K diverges when it reaches 1."""
    den = sp.denom(sp.together(clove_hitch_ratio()))
    # den = exp(-m theta_out)(1 - G exp(m theta_out)) up to a positive factor
    lock = sp.solve(sp.Eq(den, 0), G)[0]
    return sp.simplify(1 / lock)  # = exp(m_post theta_out); locks when G * this >= 1


if __name__ == "__main__":
    print("nip factor n(d, Ds) =", nip_factor())
    print("clove hitch K =", clove_hitch_ratio())
    print("  ideal-rope limit:", ideal_limit(clove_hitch_ratio()))
    print("  locks when G *", clove_hitch_lock_condition(), ">= 1")
    print("half hitch h =", half_hitch_factor())
    print("two half hitches K =", two_half_hitches_ratio())
    print("  ideal-rope limit:", ideal_limit(two_half_hitches_ratio()))
    print("free end: T_high <= K * 0 = 0 for every finite K (ideal rope: always finite)")
