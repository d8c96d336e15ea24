r"""Two half hitches round a post: a turn on the post, two half hitches on the standing part.

The rod arrives along the standing part (end 0, the loaded end), wraps the post by
:math:`\pi` (a *turn*) and ties two half hitches in the same sense round its own standing
part (:func:`knotmech.scenes.hitch_curves.two_half_hitches_curve`); the working end (the
last node) is free or lightly loaded. The scene is the post-hitch scene
(:func:`knotmech.scenes._hitch.run_hitch`): settle, load, hold (or pull); the knot type is
checked by the Alexander polynomial of the closed rod, (1 - t + t^2)^2 (each half hitch is an
overhand knot once the post is taken away), and its linking number with the post, -1, on
frames of the run.
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes._hitch import HitchKnot, hitch_scene
from knotmech.scenes.hitch_curves import hitch_curve, hitch_invariants

__all__ = ["two_half_hitches", "TWO_HALF_HITCHES"]


def _curve(post_diameter, rod_diameter, rod_length, n_nodes):
    return hitch_curve("two_half_hitches", post_diameter=post_diameter,
                       rod_diameter=rod_diameter, rod_length=rod_length,
                       n_nodes=n_nodes)  # fmt: skip


TWO_HALF_HITCHES = HitchKnot(
    name="two_half_hitches", curve=_curve, pull_angle=np.pi, invariants=hitch_invariants
)

two_half_hitches = hitch_scene(
    TWO_HALF_HITCHES,
    defaults={"loading": "free", "rod_length": None, "n_nodes": None},
    doc=r"""Tie two half hitches on a post and load them.

    Same keywords as :func:`knotmech.scenes.clove_hitch.clove_hitch` (see
    :func:`knotmech.scenes._hitch.run_hitch` for each), with these defaults: ``loading``
    ``"free"`` (T_high on the standing end, the working end free), ``rod_length`` None (the
    knotted part and a 64 mm tail at each end: 0.411 m at d = 4 mm, D = 30 mm),
    ``n_nodes`` None (edges of about 3.1 mm), ``creep_limit`` 1e-3 d/s: the hitch holds when
    neither end creeps faster than that over the last second of the hold (or its last half
    if shorter) and end 0 moved less than ``slip_distance`` over the last half.

    Returns
    -------
    HitchResult
        ``knot = "two_half_hitches"``; ``verdict``, ``creep_speed`` [m/s] (and
        ``creep_speed_d`` [d/s]), ``tension`` T(s), ``topology_preserved`` (distances,
        winding and the invariants ``(1, -2, 3, -2, 1), -1`` kept), ``post_wraps()``.
    """,
)
