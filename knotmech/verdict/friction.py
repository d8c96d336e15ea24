"""Friction from materials for the hold verdict: the published rope-on-post friction range of a
material preset (:func:`knotmech.strength.friction_range`) when ``mu`` is not given, the
verdict over that range, and the critical friction coefficient mu* (:func:`critical_mu`: the
least mu at which the whole verdict holds at the user's load, by bisection of the verdict in
mu; the same search for a given mu, a published range and an unknown friction).

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
    "DEFAULT_POST_MATERIAL", "MU_RESOLUTION", "MU_SEARCH_MAX", "MU_STEP", "MU_UNKNOWN_LOW",
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
#: the resolution of mu* (bisection of the whole verdict) [-]
MU_RESOLUTION = 1e-3
#: the step of the grid mu* is searched on [-]: MU_SEARCH_MAX / 2^11 = 7.3e-4, finer than
#: :data:`MU_RESOLUTION`; a power of two, so that k * MU_STEP / MU_STEP == k exactly
MU_STEP = MU_SEARCH_MAX / 2**11
#: the most closed-form critical mus tried first in a critical-mu search
MAX_HINTS = 3
#: searches again above a friction found to slip above the mu* found, before giving up
MAX_RESEARCH = 2


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
        known = () if bend else strength.friction_counterfaces(material)
        face = strength.counterface_key(face)
        return FrictionPreset(MU_UNKNOWN_LOW, MU_SEARCH_MAX, face, None, published=False,
                              known=known, default_face=post_material is None and not bend,
                              material=name, why=str(exc))  # fmt: skip
    return FrictionPreset(float(r.low), float(r.high), face, r.source,
                          default_face=post_material is None and not bend,
                          material=name)  # fmt: skip


def critical_mu(at, asked: dict, *, what: str = "the whole verdict", hints=()) -> tuple:
    """(mu*, text): the least friction coefficient at which ``at(mu)`` holds, by bisection
    of the whole verdict in mu, more friction never turning a hold into a slip.

    The search runs on a fixed grid of step :data:`MU_STEP` on [0, :data:`MU_SEARCH_MAX`]
    (so mu* does not depend on the mu the question was asked at): first at the critical
    mu of every closed form inside its validity in the verdicts asked (a model deciding at
    the boundary gives mu* exactly, checked at mu* and mu* - :data:`MU_STEP`), then by
    halving the bracket the verdicts leave. Undecided counts as not holding; the mu*
    returned is one ``at`` was asked at and held (its verdict is ``asked[mu*]``). Every
    verdict asked above mu* is checked: where one slips, mu* is searched again above it
    (at most :data:`MAX_RESEARCH` times), and NaN is returned if the verdict still turns
    from holding to slipping as mu grows.

    Parameters
    ----------
    at : callable
        ``at(mu)``: the :class:`~knotmech.verdict.answer.Verdict` at friction mu [-]; asked
        only where ``asked`` has no verdict (no DER run: the caller's ``at`` must be cheap).
    asked : dict
        {mu: Verdict} already known (at least the question's own), filled in place.
    what : str
        What is bisected, in the text.
    hints : sequence of (float, str)
        (mu, model): critical mus to try first, before the closed forms' (such as the
        deciding DER table's own, from its lookups alone).

    Returns
    -------
    tuple
        (mu*, text): 0 when it holds without friction; inf when nothing up to
        :data:`MU_SEARCH_MAX` holds (the load breaks the rope, or it slips); NaN when it
        holds nowhere it was asked and no model decides at :data:`MU_SEARCH_MAX`, or when
        the verdict is not monotone in mu.
    """
    s = _Search(at, asked, hints)
    held = [m for m, v in asked.items() if v.holds is True]
    if not held:
        top = s.verdict(MU_SEARCH_MAX)
        if top.holds is not True:
            return _none_found(top, what)
    floor = -1.0  # mu* lies above every friction found to slip above an earlier mu*
    for _ in range(MAX_RESEARCH + 1):
        m, text = _bisect(s, floor, what)
        slipped = [k for k, v in asked.items() if k > m and v.holds is False]
        if not slipped:
            return m, text
        floor = max(slipped)
        if not any(v.holds is True for k, v in asked.items() if k > floor):
            top = s.verdict(MU_SEARCH_MAX)
            if top.holds is not True:
                break
    return math.nan, (
        f"not found: {what} is not monotone in mu (holds at mu = {m:.3g}, does not at "
        f"mu = {floor:.3g}); more friction should not turn a hold into a slip"
    )


def _bisect(s, floor: float, what: str) -> tuple:
    """(mu*, text): the least mu above ``floor`` (-1: none) at which the verdicts asked in
    the search ``s`` hold, by the hints, then bisection on the grid of step MU_STEP; the
    least mu asked above ``floor`` that held brackets it from above."""
    asked = s.asked
    first = min(m for m, v in asked.items() if v.holds is True and m > floor)
    lo = max((math.floor(m / MU_STEP) for m, v in asked.items()
              if v.holds is not True and floor <= m < first), default=-1)  # fmt: skip
    hi = math.ceil(first / MU_STEP)
    exact, lo, hi = s.try_hints(lo, hi)
    if exact is not None:
        return exact, (
            f"{s.hint_model}'s, where {what} starts to hold: checked there and {MU_STEP:.2g} below"
        )
    if lo < 0:
        if s.holds(0.0):
            return 0.0, "holds without friction"
        lo = 0
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if s.holds(mid * MU_STEP):
            hi = mid
        else:
            lo = mid
    m = hi * MU_STEP
    if not s.holds(m):  # only when ``first`` (off the grid) holds and the grid point above not
        m = first
    return m, f"holds for mu >= {m:.3g} (bisection of {what} to {MU_RESOLUTION:g})"


def _none_found(top, what: str = "the whole verdict") -> tuple:
    """(mu*, text) when nothing asked holds and ``top`` (the verdict at the top) does not."""
    if top.holds is False and getattr(top, "fails_by", None) == "break":
        return math.inf, "the load breaks the rope whatever the friction"
    if top.holds is False:
        return math.inf, f"does not hold for any mu up to {MU_SEARCH_MAX:g}"
    return math.nan, f"not found: {what} is undecided even at mu = {MU_SEARCH_MAX:g}"


class _Search:
    """The verdicts asked in one critical-mu search (a cache: each mu asked once)."""

    def __init__(self, at, asked: dict, hints=()):
        self.at, self.asked, self.given, self.hint_model = at, asked, tuple(hints), ""

    def verdict(self, m: float):
        if m not in self.asked:
            self.asked[m] = self.at(m)
        return self.asked[m]

    def holds(self, m: float) -> bool:
        return self.verdict(m).holds is True

    def hints(self) -> list:
        """(mu, model): the finite critical mu of each closed form inside its validity in
        the verdicts asked, the deciding ones first (at most :data:`MAX_HINTS`)."""
        out = [(float(m), model) for m, model in self.given if 0 < m < MU_SEARCH_MAX]
        for v in list(self.asked.values()):
            for a in sorted(getattr(v, "answers", ()), key=lambda a: not a.decides):
                m = float(getattr(a, "critical_mu", math.nan))
                if a.inside_validity and 0 < m < MU_SEARCH_MAX and m not in dict(out):
                    out.append((m, a.model))
        return out[: MAX_HINTS + len(self.given)]

    def try_hints(self, lo: int, hi: int) -> tuple:
        """(exact mu* or None, lo, hi): each hint within the bracket (lo, hi) of grid
        indices is asked; one that holds while the verdict MU_STEP below does not is mu*;
        the others narrow the bracket."""
        for m, model in self.hints():
            if not lo * MU_STEP < m < hi * MU_STEP:
                continue
            if self.holds(m):
                if not self.holds(max(0.0, m - MU_STEP)):
                    self.hint_model = f"the {model} model"
                    return m, lo, hi
                hi = math.floor(m / MU_STEP)  # at or above m - MU_STEP, which holds
            else:
                lo = max(lo, math.floor(m / MU_STEP))
        return None, lo, hi


def range_words(at_low, at_high, low: float, high: float, mu_star: float) -> str:
    """The verdict over [low, high] from its ends (monotone in mu) and the critical mu."""
    rng = f"mu = {low:.3g}" if low == high else f"mu in [{low:.3g}, {high:.3g}]"
    if at_low is True and at_high is False:
        return (f"undecided over {rng}: holds at mu = {low:.3g} and slips at {high:.3g}, "
                "against more friction never turning a hold into a slip")  # fmt: skip
    if at_low is True:
        return f"holds for any {rng}" if low != high else f"holds at {rng}"
    if at_high is True:
        where = f"mu* = {mu_star:.3g}" if math.isfinite(mu_star) else "the critical mu"
        return f"holds only for mu above {where} (range {low:.3g}-{high:.3g})"
    if at_low is False and at_high is False:
        return f"does not hold for any {rng}" if low != high else f"does not hold at {rng}"
    return f"undecided over {rng}" if low != high else f"undecided at {rng}"


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
        HOLDS (numbers at the low end) if it holds there and does not slip at the top
        (holding at the low end and slipping at the top is UNDECIDED: not monotone in
        mu); SLIPS or BREAKS (numbers at
        the top) if it does not hold at the top; else UNDECIDED: with numbers at mu* (the
        least mu found to hold, :func:`critical_mu`, to :data:`MU_RESOLUTION`; there it
        holds, and by monotony its slip load there is the
        least over the frictions at which it holds) when it holds at the top, or at the
        top when it is undecided there. ``friction`` says which (``verdict_at_mu``,
        ``verdict_at``), the range, ``published`` False, ``source`` None and mu*
        (``critical_mu``: 0 holds without friction, inf none up to the top, NaN unknown).
    """
    lo, hi = preset.low, preset.high
    asked = {lo: at(lo), hi: at(hi)}
    v_lo, v_hi = asked[lo], asked[hi]
    advice = f"next: {preset.advice()}"
    if v_lo.holds is True and v_hi.holds is not False:
        m, text = critical_mu(at, asked)
        words = f"holds for any mu from {lo:.3g} up"
        return _unknown(v_lo, preset, lo, "low end", words, m, text, True, v_hi.holds)
    if v_lo.holds is True:  # holds at the low end and slips at the top: not monotone
        base = replace(v_lo, holds=None, fails_by=None, next_step=advice)
        words = range_words(True, False, lo, hi, math.nan)
        return _unknown(base, preset, lo, "low end", words, math.nan,
                        f"not found: {words}", True, False)  # fmt: skip
    if v_hi.holds is False:
        m, text = _none_found(v_hi)
        words = ("breaks at any friction: the load reaches the breaking load"
                 if v_hi.fails_by == "break" else text)  # fmt: skip
        return _unknown(v_hi, preset, hi, "top of the search", words, m, text,
                        v_lo.holds, False)  # fmt: skip
    if v_hi.holds is True:
        m, text = critical_mu(at, asked)
        if not math.isfinite(m):  # not monotone in mu
            base = replace(v_hi, holds=None, fails_by=None, next_step=advice)
            return _unknown(base, preset, hi, "top of the search", text, m, text,
                            v_lo.holds, True)  # fmt: skip
        words = f"holds only for mu above mu* = {m:.3g}"
        base = replace(asked[m], holds=None, fails_by=None, next_step=advice)
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
