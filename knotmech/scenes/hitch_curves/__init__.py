"""Post hitches from parametric centrelines, one file per knot, dispatched by the registry.

Each hitch tied here has a curve file (:mod:`.two_half_hitches`: two half hitches and the
round turn and two half hitches; :mod:`.cow_hitch`: the cow hitch) with its curve function
and ``knotted_length(post_diameter, rod_diameter, **curve_params)``, and a record in
:mod:`knotmech.knots` naming that function and its ``curve_params``. :func:`hitch_curve`
and :func:`hitch_rod_length` find a knot's curve through its record; what the curves share
(closure, invariants, the clove core) is in :mod:`._parts`.

Coordinates: the post is the z axis (radius D/2), the rod centreline touches it at radius
:math:`R = (D+d)/2`. End 0 (node 0) is the *standing end* (the loaded one), the last node
the *working end* (free or lightly loaded).
"""

from __future__ import annotations

import importlib

from knotmech import knots
from knotmech.errors import InputError, check_positive
from knotmech.scenes.curves import KnotCurve
from knotmech.scenes.hitch_curves._parts import (
    EDGE,
    PITCH,
    TAIL,
    hitch_closure,
    hitch_invariants,
)

_HERE = __name__ + "."

#: the hitch records whose curve is a file of this package (identifier -> record)
_RECORDS = {k.identifier: k for k in knots.records(family="hitch") if k.curve.startswith(_HERE)}
#: the curve functions by name (``two_half_hitches_curve``) -> "module:function"
_CURVES = {k.curve.partition(":")[2]: k.curve for k in _RECORDS.values()}

__all__ = [
    "HITCH_KNOTS",
    *_CURVES,
    "hitch_curve",
    "hitch_rod_length",
    "hitch_closure",
    "hitch_invariants",
    "PITCH",
    "TAIL",
    "EDGE",
]

#: knots tied by :func:`hitch_curve` (identifiers, ``two_half_hitches``) -> post wrap angle of
#: the standing part [rad]
HITCH_KNOTS = {name: k.pull_angle for name, k in _RECORDS.items()}


def __getattr__(name: str):
    """The curve functions by their old names (``two_half_hitches_curve``), from the files."""
    if name in _CURVES:
        return knots.resolve(_CURVES[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _record(knot: str):
    k = _RECORDS.get(str(knot))
    if k is None:
        raise InputError(f"knot must be one of {', '.join(HITCH_KNOTS)}, got {knot!r}")
    return k


def hitch_rod_length(knot: str, *, post_diameter: float, rod_diameter: float,
                     tail: float = TAIL) -> float:  # fmt: skip
    """Default rod length [m] of a hitch: its knotted part (the standing part's run past the
    half hitches included), 4 d at each end and ``tail`` [m] more at each end."""
    D = float(check_positive("post_diameter", post_diameter, scalar=True))
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    t = float(check_positive("tail", tail, scalar=True))
    k = _record(knot)
    module = importlib.import_module(k.curve.partition(":")[0])
    core = module.knotted_length(D, d, **k.curve_params)
    return core + 8 * d + 2 * t


def hitch_curve(
    knot: str,
    *,
    post_diameter: float,
    rod_diameter: float,
    rod_length: float | None = None,
    n_nodes: int | None = None,
) -> KnotCurve:
    """The start centreline of a hitch in :data:`HITCH_KNOTS` (its record's curve).

    ``rod_length`` None: :func:`hitch_rod_length`; ``n_nodes`` None: edges of about
    :data:`EDGE`.
    """
    k = _record(knot)
    if rod_length is None:
        rod_length = hitch_rod_length(knot, post_diameter=post_diameter,
                                      rod_diameter=rod_diameter)  # fmt: skip
    if n_nodes is None:
        n_nodes = int(round(float(rod_length) / EDGE)) + 1
    return k.curve_function()(post_diameter=post_diameter, rod_diameter=rod_diameter,
                              rod_length=rod_length, n_nodes=n_nodes, **k.curve_params)  # fmt: skip
