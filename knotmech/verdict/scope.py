"""Which knots the hold verdict answers and which of its models apply to each, read from the
registry (:mod:`knotmech.knots`): one spelling per name (:func:`knot_key`)."""

from __future__ import annotations

from knotmech import knots
from knotmech.errors import InputError

__all__ = [
    "KNOT_NAMES",
    "HITCHES",
    "BOTH_LEGS_KNOTS",
    "BENDS",
    "DER_HITCHES",
    "knot_key",
    "is_bend",
    "has_der_answer",
    "can_simulate",
    "check_plot_request",
]

#: knots :func:`knotmech.hold` answers (the registry's answered records: capstan, hitches, bends)
KNOT_NAMES = knots.names()
#: the hitches on a post
HITCHES = knots.names(family="hitch")
#: the bends of Patil et al. (Science 2020): two ropes joined and pulled apart
BENDS = knots.names(family="bend")
#: the hitches whose free-end case can have a DER answer: the registry's hitches with a DER
#: scene or a shipped hold table (the clove hitch always has one)
DER_HITCHES = tuple(
    k.name for k in knots.records(family="hitch", answered=True) if k.has_scene or k.hold_table
)


def knot_key(knot) -> str:
    """Canonical knot name, or a one-line :class:`InputError` listing what is answered."""
    key = knots.key(knot) or knots.normalise(knot)
    if key in KNOT_NAMES:
        return key
    supported = ", ".join(KNOT_NAMES)
    if key in knots.REGISTRY:
        why = knots.REGISTRY[key].unanswered
        raise InputError(f"{knot!r} is {why}; hold answers: {supported}")
    raise InputError(f"unknown knot {str(knot)!r}; hold answers: {supported}")


def is_bend(knot) -> bool:
    """Whether ``knot`` (a canonical name) is a bend: two ropes pulled apart, no post."""
    return knot in BENDS


def has_der_answer(knot) -> bool:
    """Whether ``knot`` (a canonical name) has a DER answer: a shipped hold table or a scene."""
    return knot in DER_HITCHES


def can_simulate(knot) -> bool:
    """Whether ``simulate=True`` runs a DER scene for ``knot`` (a canonical name)."""
    if knot in BENDS:
        return True
    return knot in DER_HITCHES and knots.get(knot).has_scene


#: knots that ``simulate`` answers with one DER run and no table (the bends, the loops, the
#: hitches pulled along a pole), whose ``--plot`` draws the simulated knot
ONE_RUN_KNOTS = tuple(
    k.name
    for k in knots.records(answered=True)
    if k.family in ("bend", "loop") or (k.family == "hitch" and "along the pole" in k.loading)
)
#: hitches that ``hold --simulate`` also answers with both legs loaded (T_low =
#: ``free_end_load`` on the other leg; ``knotmech hold --loading both-legs``)
BOTH_LEGS_KNOTS = ("cow-hitch",)


def check_plot_request(knot, *, simulate: bool, free_end_load: float) -> None:
    """Refuse (InputError, one line, before any work) a ``plot`` that would have nothing to
    draw: a hitch's DER answer (its phase table, free end, or a simulation), or the knot of
    a DER run under ``simulate`` (bends, loops, the Prusik; the cow hitch on both legs)."""
    free = float(free_end_load or 0.0)
    if knot in ONE_RUN_KNOTS or (knot in BOTH_LEGS_KNOTS and free > 0):
        if not simulate:
            raise InputError(
                f"plot draws the simulated knot: the {knot} has no table, give simulate "
                "(--simulate) to run it"
            )
        return
    if not has_der_answer(knot) or free > 0:
        raise InputError(
            "plot draws the DER answer (phase diagram or simulated knot): a hitch with a DER "
            f"answer ({', '.join(DER_HITCHES)}) with a free end, or a knot under simulate "
            f"({', '.join(ONE_RUN_KNOTS)}, cow-hitch on both legs)"
        )
