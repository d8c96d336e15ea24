r"""Cow hitch (girth hitch, lark's head) on a post: two half hitches in opposite senses.

Both legs leave the post side by side in the same direction; the bight between the two
turns lies over both legs on the front of the post
(:func:`knotmech.scenes.hitch_curves.cow_hitch_curve`). End 0 is one leg (the loaded one),
the last node the other (free, lightly loaded, or loaded like end 0 with
``loading="symmetric"``: the girth hitch of a sling, whose legs share the load). The scene
is the post-hitch scene (:func:`knotmech.scenes._hitch.run_hitch`); the knot type is checked
by the Alexander polynomial of the closed rod (1: the two turns undo each other once the
post is gone) and its linking number with the post (0: the turns are in opposite senses)
on frames of the run, besides the distance checks.
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes._hitch import HitchKnot, hitch_scene
from knotmech.scenes.hitch_curves import hitch_curve, hitch_invariants

__all__ = ["cow_hitch", "COW_HITCH"]


def _curve(post_diameter, rod_diameter, rod_length, n_nodes):
    return hitch_curve("cow_hitch", post_diameter=post_diameter, rod_diameter=rod_diameter,
                       rod_length=rod_length, n_nodes=n_nodes)  # fmt: skip


COW_HITCH = HitchKnot(name="cow_hitch", curve=_curve, pull_angle=2 * np.pi,
                      invariants=hitch_invariants)  # fmt: skip

cow_hitch = hitch_scene(
    COW_HITCH,
    defaults={"loading": "free", "rod_length": None, "n_nodes": None},
    doc=r"""Tie a cow hitch on a post and load it.

    Same keywords as :func:`knotmech.scenes.clove_hitch.clove_hitch` (see
    :func:`knotmech.scenes._hitch.run_hitch` for each), with these defaults: ``loading``
    ``"free"`` (T_high on leg 0, leg 1 free), ``rod_length`` None (the knotted part and a
    64 mm leg at each end: 0.436 m at d = 4 mm, D = 30 mm), ``n_nodes`` None (edges of about
    3.1 mm), ``creep_limit`` 1e-3 d/s (see
    :func:`~knotmech.scenes.two_half_hitches.two_half_hitches`).

    Returns
    -------
    HitchResult
        ``knot = "cow_hitch"``; ``verdict``, ``creep_speed`` [m/s] (``creep_speed_d``
        [d/s]), ``tension`` T(s), ``topology_preserved`` (distances, winding and the
        invariants ``(1,), 0`` kept), ``post_wraps()``.
    """,
)
