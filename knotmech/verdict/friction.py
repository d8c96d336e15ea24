"""Friction from materials for the hold verdict: the published rope-on-post friction range of a
material preset (:func:`knotmech.strength.friction_range`) when ``mu`` is not given, the
verdict over that range, and the critical friction coefficient mu* (the least mu at which
the knot holds at the user's load, found by bisection of the verdict in mu).

The scan assumes what the DER tables' bracketing already assumes: more friction never turns
a hold into a slip, so the verdict over [a, b] is one of "holds for any mu in [a, b]",
"slips for any mu in [a, b]" or "holds only for mu above mu*".

Where no coefficient is published for the pair (``friction.json`` ``not_found``: nylon on
steel, manila, polypropylene, steel wire, the paper's rods), the friction is unknown and
:func:`unknown_friction_verdict` answers over the whole searched range
[:data:`MU_UNKNOWN_LOW`, :data:`MU_SEARCH_MAX`]: HOLDS only if it holds at its low end,
SLIPS (or BREAKS) only if it does not hold at its top, else UNDECIDED with mu*.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from knotmech.errors import InputError

__all__ = [
    "DEFAULT_POST_MATERIAL", "MU_RESOLUTION", "MU_SEARCH_MAX", "MU_UNKNOWN_LOW",
    "FrictionPreset", "critical_mu", "friction_preset", "range_words",
    "unknown_friction_verdict",
]  # fmt: skip

#: the post material assumed when neither ``mu`` nor ``post_material`` is given
DEFAULT_POST_MATERIAL = "steel"
#: the largest friction coefficient the critical-mu search tries [-]
MU_SEARCH_MAX = 1.5
#: the low end of the searched friction when no coefficient is published for the pair [-].
#: Below every coefficient in ``knotmech/data/strength/friction.json`` (the lowest are HMPE
#: on HMPE, 0.08, derived, and HMPE on stainless steel, 0.117, measured): a knot that holds
#: at 0.05 holds at the friction of every rope there. Not 0: no knot with a free end holds
#: without friction in any model here, so a search from 0 could never answer HOLDS.
MU_UNKNOWN_LOW = 0.05
#: bisection steps of the critical-mu search (resolution 2^-steps of the bracket)
BISECTION_STEPS = 6
#: the resolution of mu* when the friction is unknown (bisection of the whole verdict) [-]
MU_RESOLUTION = 1e-3


@dataclass(frozen=True)
class FrictionPreset:
    """The friction of a rope on a counterface when ``mu`` is not given.

    Attributes
    ----------
    low, high : float
        The published range [-]; without one, the searched range
        [:data:`MU_UNKNOWN_LOW`, :data:`MU_SEARCH_MAX`].
    face : str
        The counterface: the post material, or ``rope`` (a bend).
    source : str or None
        The sources of the published range; None without one.
    published : bool
        Whether a published coefficient exists for the pair.
    known : tuple of str
        Without one: the counterfaces of this material that have one (a bend: none offered).
    default_face : bool
        Whether ``face`` is :data:`DEFAULT_POST_MATERIAL` by default (no post material given).
    material : str
        The rope material's name.
    why : str
        Without a published coefficient: the data's note on why (``friction.json``
        ``not_found``), else "".
    """

    low: float
    high: float
    face: str
    source: str | None
    published: bool = True
    known: tuple = ()
    default_face: bool = False
    material: str = ""
    why: str = ""

    def missing(self) -> str:
        """``no published friction coefficient for nylon on steel; published on aluminium,
        rope`` ("" when one is published)."""
        if self.published:
            return ""
        tail = f"; published on {', '.join(self.known)}" if self.known else ""
        return f"no published friction coefficient for {self.material} on {self.face}{tail}"

    def advice(self) -> str:
        """How to decide without a published coefficient: the options to give."""
        if not self.known:
            return "give --mu (mu=) measured for this rope"
        faces = " or ".join(self.known)
        return (f"give --mu (mu=) measured for this rope on this post, or --post-material "
                f"{faces} (post_material=)")  # fmt: skip

    def as_dict(self) -> dict:
        """The preset as the verdict's ``friction`` dict starts it."""
        out = {"post_material": self.face, "default_post_material": self.default_face,
               "range": [self.low, self.high], "source": self.source,
               "published": self.published}  # fmt: skip
        if not self.published:
            out.update(missing=self.missing(), why=self.why,
                       published_post_materials=list(self.known))  # fmt: skip
        return out


def friction_preset(knot: str, material, post_material) -> FrictionPreset:
    """The friction coefficient of ``material`` on ``post_material`` (default
    :data:`DEFAULT_POST_MATERIAL`; a bend: rope on rope): the published range, or, when none
    is published, the searched range [:data:`MU_UNKNOWN_LOW`, :data:`MU_SEARCH_MAX`] with
    ``published`` False (:func:`unknown_friction_verdict` answers over it).

    Raises
    ------
    InputError
        No material (``mu`` is then required), or an unknown material or post material.
    """
    from knotmech import strength

    if material is None:
        raise InputError("mu is required unless material is given (its friction is then used)")
    face = post_material if post_material is not None else DEFAULT_POST_MATERIAL
    bend = knot in ("reef", "granny", "thief", "grief")
    if bend:
        face = "rope"
    name = getattr(material, "key", material)
    try:
        r = strength.friction_range(material, face)
    except strength.NoDataError as exc:
        known = () if bend else tuple(f for f in strength.counterface_names()
                                      if _has(strength, material, f))  # fmt: skip
        face = strength.counterface_key(face)
        return FrictionPreset(MU_UNKNOWN_LOW, MU_SEARCH_MAX, face, None, published=False,
                              known=known, default_face=post_material is None and not bend,
                              material=name, why=str(exc))  # fmt: skip
    return FrictionPreset(float(r.low), float(r.high), face, r.source,
                          default_face=post_material is None and not bend,
                          material=name)  # fmt: skip


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


def _least_holding(at, slip_mu: float, hold_mu: float, cache: dict) -> float:
    """The least mu within :data:`MU_RESOLUTION` above which ``at(mu)`` (a Verdict) holds,
    from ``slip_mu`` (not holding) and ``hold_mu`` (holding): the holding end of the last
    bracket, so ``at`` holds there."""

    def holds(m):
        if m not in cache:
            cache[m] = at(m)
        return cache[m].holds is True

    steps = max(1, math.ceil(math.log2((hold_mu - slip_mu) / MU_RESOLUTION)))
    for _ in range(steps):
        m = 0.5 * (slip_mu + hold_mu)
        if holds(m):
            hold_mu = m
        else:
            slip_mu = m
    return hold_mu


def unknown_friction_verdict(preset: FrictionPreset, at):
    """The verdict when no friction coefficient is published for the pair: over the whole
    searched range [``preset.low``, ``preset.high``] (:data:`MU_UNKNOWN_LOW`,
    :data:`MU_SEARCH_MAX`), more friction never turning a hold into a slip.

    Parameters
    ----------
    preset : FrictionPreset
        The unpublished preset (``published`` False).
    at : callable
        ``at(mu)``: the :class:`~knotmech.verdict.answer.Verdict` at a given mu [-].

    Returns
    -------
    Verdict
        HOLDS (numbers at the low end) if it holds there; SLIPS or BREAKS (numbers at
        the top) if it does not hold at the top; else UNDECIDED: with numbers at mu* (the
        least mu found to hold, by bisection of the whole verdict to
        :data:`MU_RESOLUTION`; there it holds, and by monotony its slip load there is the
        least over the frictions at which it holds) when it holds at the top, or at the
        top when it is undecided there. ``friction`` says which (``verdict_at_mu``,
        ``verdict_at``), the range, ``published`` False, ``source`` None and mu*
        (``critical_mu``: 0 holds without friction, inf none up to the top, NaN unknown).
    """
    lo, hi = preset.low, preset.high
    cache: dict = {}
    v_lo = cache.setdefault(lo, at(lo))
    if v_lo.holds is True:
        m = 0.0 if cache.setdefault(0.0, at(0.0)).holds is True else (
            _least_holding(at, 0.0, lo, cache))  # fmt: skip
        text = (
            "holds without friction"
            if m == 0
            else (f"holds for mu >= {m:.3g} (bisection of the verdict to {MU_RESOLUTION:g})")
        )
        words = f"holds for any mu from {lo:.3g} up"
        return _unknown(v_lo, preset, lo, "low end", words, m, text, True, True)
    v_hi = cache.setdefault(hi, at(hi))
    if v_hi.holds is False:
        if v_hi.fails_by == "break":
            words = "breaks at any friction: the load reaches the breaking load"
            text = "the load breaks the rope whatever the friction"
        else:
            words = f"does not hold for any mu up to {hi:g}"
            text = words
        return _unknown(v_hi, preset, hi, "top of the search", words,
                        math.inf, text, v_lo.holds, False)  # fmt: skip
    advice = f"next: {preset.advice()}"
    if v_hi.holds is True:
        m = _least_holding(at, lo, hi, cache)
        text = f"holds for mu >= {m:.3g} (bisection of the verdict to {MU_RESOLUTION:g})"
        words = f"holds only for mu above mu* = {m:.3g}"
        base = replace(cache[m], holds=None, fails_by=None, next_step=advice)
        return _unknown(base, preset, m, "critical mu", words, m, text, v_lo.holds, True)
    base = replace(v_hi, holds=None, fails_by=None, next_step=advice)
    words = f"friction unknown and no model decides even at mu = {hi:g}"
    return _unknown(base, preset, hi, "top of the search", words,
                    math.nan, "not found: no model decides at the top of the search",
                    v_lo.holds, v_hi.holds)  # fmt: skip


def _unknown(v, preset, at_mu, where, words, m, text, at_low, at_high):
    """``v`` with the unknown friction's ``friction`` dict."""
    f = preset.as_dict()
    f.update(holds_at_low=at_low, holds_at_high=at_high, words=words, critical_mu=m,
             critical_mu_text=text, verdict_at_mu=at_mu, verdict_at=where)  # fmt: skip
    return replace(v, friction=f)
