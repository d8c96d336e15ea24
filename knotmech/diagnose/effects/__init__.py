"""The effect catalogue: the physics a baseline leaves out, one module per effect.

A new effect is one module with an :class:`~knotmech.diagnose.effects.base.Effect`
subclass and one line below. The registry order is the order in which effects add
parameters to a model and act on its mean (whatever the order they were added in),
and the order in which the engine tries them. :func:`get_effect` is the one lookup
by name. Names are those of ``shared/spec/recordings.md`` section 3, and those this
package adds (section 5).
"""

from __future__ import annotations

from knotmech.diagnose.effects.adhesion import Adhesion
from knotmech.diagnose.effects.base import Effect, PlantContext
from knotmech.diagnose.effects.bending_resistance import BendingResistance
from knotmech.diagnose.effects.bending_stiffness import BendingStiffness
from knotmech.diagnose.effects.contact_flattening import ContactFlattening
from knotmech.diagnose.effects.displacement_offset import DisplacementOffset
from knotmech.diagnose.effects.finite_thickness import FiniteThickness
from knotmech.diagnose.effects.pressure_dependent_friction import PressureDependentFriction
from knotmech.diagnose.effects.rate_dependent_friction import RateDependentFriction
from knotmech.diagnose.effects.self_contact_nip import SelfContactNip
from knotmech.diagnose.effects.sensor_offset import SensorOffset
from knotmech.diagnose.effects.static_friction import StaticFriction
from knotmech.errors import InputError

__all__ = [
    "Effect",
    "PlantContext",
    "CATALOGUE",
    "get_effect",
    "applicable_effects",
    "missing_requirements",
]

#: effect name -> Effect, in registry order
CATALOGUE: dict[str, Effect] = {}


def _register(effect: Effect) -> None:
    if effect.name in CATALOGUE:  # pragma: no cover - a programming error
        raise ValueError(f"effect {effect.name!r} registered twice")
    effect.rank = len(CATALOGUE)
    CATALOGUE[effect.name] = effect


_register(StaticFriction())
_register(FiniteThickness())
_register(Adhesion())
_register(ContactFlattening())
_register(SelfContactNip())
_register(DisplacementOffset())
_register(RateDependentFriction())
# capstan_hold (spec section 5); a log_ratio stage that recomputes comes first
_register(PressureDependentFriction())
_register(BendingResistance())
_register(BendingStiffness())
_register(SensorOffset())


def get_effect(name: str) -> Effect:
    """The catalogue effect called ``name``.

    Raises
    ------
    InputError
        Unknown name (the message lists the known ones).
    """
    try:
        return CATALOGUE[str(name)]
    except KeyError:
        raise InputError(f"unknown effect {name!r}; known: {', '.join(CATALOGUE)}") from None


def missing_requirements(effect: Effect, rec) -> list:
    """What ``rec`` lacks for ``effect`` (empty when it can be tested)."""
    return effect.missing(rec)


def applicable_effects(rec) -> tuple[list, dict]:
    """Effects of ``rec``'s experiment that can be tested (objects, registry order), and
    the skipped ones (name -> why)."""
    ok, skipped = [], {}
    for e in CATALOGUE.values():
        if rec.experiment not in e.experiments:
            continue
        miss = e.missing(rec)
        if miss:
            skipped[e.name] = "needs " + " and ".join(miss)
        else:
            ok.append(e)
    return ok, skipped
