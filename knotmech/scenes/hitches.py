"""The post hitches by name: one keyword interface for all of them.

Every hitch scene takes the keywords of :func:`knotmech.scenes.clove_hitch.clove_hitch`
(:func:`knotmech.scenes._hitch.run_hitch` documents them) and returns a
:class:`~knotmech.scenes._hitch.HitchResult`, so a table builder can run any of them by
name::

    from knotmech.scenes.hitches import hitch
    r = hitch("two_half_hitches", loading="free", t_high=0.1, settle_time=0.2,
              load_time=0.2, hold_time=0.4)
    r.verdict, r.creep_speed_d, r.topology_preserved

The hitches are the registry's (:mod:`knotmech.knots`) hitch records with a scene. A hitch
whose record names no scene function of its own is *made* here from its curve
(:func:`knotmech.scenes.hitch_curves.hitch_curve`): :func:`hitch_function` binds the shared
scene to the record's curve, pull angle, defaults and docstring. Made scenes are attributes
of this module by their identifiers (``knotmech.scenes.hitches.cow_hitch``), so that they
pickle (a sweep sends them to worker processes). The scene modules are imported on first use
(each imports the DER solver).
"""

from __future__ import annotations

import functools

from knotmech import knots
from knotmech.errors import InputError

__all__ = ["HITCHES", "hitch", "hitch_function"]

#: hitch identifier (``clove_hitch``) -> canonical name (``clove-hitch``), every hitch with a
#: DER scene, in registry order
HITCHES = {k.identifier: k.name for k in knots.records(family="hitch") if k.has_scene}


def _record(knot: str):
    k = knots.key(knot)
    if not k or knots.REGISTRY[k].identifier not in HITCHES:
        raise InputError(f"knot must be one of {', '.join(HITCHES)}, got {knot!r}")
    return knots.REGISTRY[k]


@functools.cache
def _made_scene(name: str):
    """The scene function of the hitch record ``name`` that names no scene of its own."""
    from knotmech.scenes._hitch import HitchKnot, hitch_scene
    from knotmech.scenes.hitch_curves import hitch_curve, hitch_invariants

    rec = knots.REGISTRY[name]

    def curve(post_diameter, rod_diameter, rod_length, n_nodes):
        return hitch_curve(rec.identifier, post_diameter=post_diameter,
                           rod_diameter=rod_diameter, rod_length=rod_length,
                           n_nodes=n_nodes)  # fmt: skip

    knot = HitchKnot(name=rec.identifier, curve=curve, pull_angle=rec.pull_angle,
                     invariants=hitch_invariants)  # fmt: skip
    scene = hitch_scene(knot, defaults=dict(rec.scene_defaults), doc=rec.scene_doc)
    scene.__module__ = __name__
    return scene


def hitch_function(knot: str):
    """The scene function of ``knot`` (a name in :data:`HITCHES`, any spelling or alias)."""
    rec = _record(knot)
    if rec.scene:
        return knots.resolve(rec.scene)
    return _made_scene(rec.name)


def hitch(knot: str, **kwargs):
    """Run the hitch scene ``knot`` with ``kwargs`` (see :func:`hitch_function`)."""
    return hitch_function(knot)(**kwargs)


def __getattr__(name: str):
    """A made hitch scene by its identifier (``cow_hitch``)."""
    if name in HITCHES and not knots.REGISTRY[HITCHES[name]].scene:
        return _made_scene(HITCHES[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
