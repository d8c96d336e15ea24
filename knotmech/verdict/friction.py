"""Friction from materials for the hold verdict: the published rope-on-post friction range of a
material preset (:func:`knotmech.strength.friction_range`) when ``mu`` is not given, the
verdict over that range, and the critical friction coefficient mu* (the least mu at which
the knot holds at the user's load, found by bisection of the verdict in mu).

The scan assumes what the DER tables' bracketing already assumes: more friction never turns
a hold into a slip, so the verdict over [a, b] is one of "holds for any mu in [a, b]",
"slips for any mu in [a, b]" or "holds only for mu above mu*".
"""

from __future__ import annotations

import math

from knotmech.errors import InputError

__all__ = [
    "DEFAULT_POST_MATERIAL", "MU_SEARCH_MAX", "critical_mu", "friction_preset", "range_words",
]  # fmt: skip

#: the post material assumed when neither ``mu`` nor ``post_material`` is given
DEFAULT_POST_MATERIAL = "steel"
#: the largest friction coefficient the critical-mu search tries [-]
MU_SEARCH_MAX = 1.5
#: bisection steps of the critical-mu search (resolution 2^-steps of the bracket)
BISECTION_STEPS = 6


def friction_preset(knot: str, material, post_material) -> tuple:
    """(low, high, counterface, source) of the friction coefficient for ``material`` on
    ``post_material`` (default :data:`DEFAULT_POST_MATERIAL`; a bend: rope on rope).

    Raises
    ------
    InputError
        No material, or no published coefficient for the pair (one line naming the post
        materials that have one, and ``mu``).
    """
    from knotmech import strength

    if material is None:
        raise InputError("mu is required unless material is given (its friction is then used)")
    face = post_material if post_material is not None else DEFAULT_POST_MATERIAL
    if knot in ("reef", "granny", "thief", "grief"):
        face = "rope"
    try:
        r = strength.friction_range(material, face)
    except strength.NoDataError:
        name = getattr(material, "key", material)
        known = [f for f in strength.counterface_names() if _has(strength, material, f)]
        raise InputError(
            f"no published friction coefficient for {name} on {face}"
            + (f" (published: {', '.join(known)}): give mu or post_material" if known
               else ": give mu")
        ) from None  # fmt: skip
    return float(r.low), float(r.high), face, r.source


def _has(strength, material, face) -> bool:
    try:
        strength.friction_range(material, face)
    except strength.NoDataError:
        return False
    return True


def _bisect(ask, slip_mu: float, hold_mu: float) -> float:
    """The boundary between a friction that does not hold and one that does (upper end)."""
    for _ in range(BISECTION_STEPS):
        m = 0.5 * (slip_mu + hold_mu)
        if ask(m) is True:
            hold_mu = m
        else:
            slip_mu = m
    return hold_mu


def critical_mu(ask, mu: float, held) -> tuple:
    """(mu*, text): the least friction coefficient at which ``ask(mu)`` holds, searched
    from the verdict ``held`` at ``mu`` (bisection; undecided counts as not holding).

    mu* is 0 when it holds without friction, inf when nothing up to
    :data:`MU_SEARCH_MAX` holds, NaN when the verdict at ``mu`` is undecided and nothing
    brackets it.
    """
    if held is True:
        if ask(0.0) is True:
            return 0.0, "holds without friction"
        m = _bisect(ask, 0.0, mu)
        return m, f"holds for mu >= {m:.3g} (bisection of the verdict)"
    if ask(MU_SEARCH_MAX) is not True:
        return math.inf, f"does not hold for any mu up to {MU_SEARCH_MAX:g}"
    m = _bisect(ask, mu, MU_SEARCH_MAX)
    return m, f"holds for mu >= {m:.3g} (bisection of the verdict)"


def range_words(at_low, at_high, low: float, high: float, mu_star: float) -> str:
    """The verdict over [low, high] from its ends (monotone in mu) and the critical mu."""
    if at_low is True:
        return f"holds for any mu in [{low:.3g}, {high:.3g}]"
    if at_high is True:
        where = f"mu* = {mu_star:.3g}" if math.isfinite(mu_star) else "the critical mu"
        return f"holds only for mu above {where} (range {low:.3g}-{high:.3g})"
    if at_low is False and at_high is False:
        return f"does not hold for any mu in [{low:.3g}, {high:.3g}]"
    return f"undecided over mu in [{low:.3g}, {high:.3g}]"
