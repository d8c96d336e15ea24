"""The post hitches by name: one keyword interface for all of them.

Every hitch scene takes the keywords of :func:`knotmech.scenes.clove_hitch.clove_hitch`
(:func:`knotmech.scenes._hitch.run_hitch` documents them) and returns a
:class:`~knotmech.scenes._hitch.HitchResult`, so a table builder can run any of them by
name::

    from knotmech.scenes.hitches import hitch
    r = hitch("two_half_hitches", loading="free", t_high=0.1, settle_time=0.2,
              load_time=0.2, hold_time=0.4)
    r.verdict, r.creep_speed_d, r.topology_preserved

The scene modules are imported on first use (each imports the DER solver).
"""

from __future__ import annotations

import importlib

from knotmech.errors import InputError

__all__ = ["HITCHES", "hitch", "hitch_function"]

#: knot name -> module of knotmech.scenes defining the function of the same name
HITCHES = {
    "clove_hitch": "clove_hitch",
    "two_half_hitches": "two_half_hitches",
    "round_turn_two_half_hitches": "round_turn_two_half_hitches",
    "cow_hitch": "cow_hitch",
}


def hitch_function(knot: str):
    """The scene function of ``knot`` (a name in :data:`HITCHES`; hyphens allowed)."""
    name = str(knot).replace("-", "_")
    if name not in HITCHES:
        raise InputError(f"knot must be one of {', '.join(HITCHES)}, got {knot!r}")
    module = importlib.import_module(f"knotmech.scenes.{HITCHES[name]}")
    return getattr(module, name)


def hitch(knot: str, **kwargs):
    """Run the hitch scene ``knot`` with ``kwargs`` (see :func:`hitch_function`)."""
    return hitch_function(knot)(**kwargs)
