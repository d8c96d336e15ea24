r"""Flat overhand bend (offset water knot, "European death knot", ABoK #1410 tied offset):
two ropes laid side by side and tied together in one overhand knot.

Construction: the single-rope long overhand of
:func:`~knotmech.scenes.tied._common.long_knot_controls` (a parametric trefoil cut open at
its outermost point, ends to the far left and right, one kink where the two ends cross)
split into two parallel strands 1.3 d apart (the knot dressed flat, the ropes never
crossing each other inside it). Both ropes run from the far left to the far right, A on
the left of the direction of travel::

    A standing  =======\    overhand of the    /======= A tail
                        >=== doubled rope  ====
    B standing  =======/   (3 + 1 crossings)   \======= B tail

Both standing parts leave the knot on the same side (node 0 of A and B, far left: loaded
apart, the bend is ring-loaded and rolls towards its tails), both tails on the other.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- each rope closed on its own far outside: a **trefoil 3_1** (Alexander polynomial
  :math:`1 - t + t^2`, determinant 3): each rope is one strand of the doubled overhand;
- the two ropes, each closed, link w times, w the writhe of the single-rope diagram
  (parallel strands of a flat ribbon, run the same way): w = -2 here (the trefoil
  diagram's -3 plus the kink's +1);
- joined into one curve (standing part to standing part, tail to tail): the **unknot**
  (the boundary of the doubled rope's ribbon, a disk).
"""

from __future__ import annotations

from knotmech.scenes.tied._common import TiedKnot, check_sizes, finish, ribbon_strands, start_checks

__all__ = ["flat_overhand_bend"]

SCALE = 2.4  #: size of the overhand [d]
HALF = 0.65  #: half spacing of the two ropes [d]
TAIL = 8.0  #: straight ends [d]


def flat_overhand_bend(*, rod_diameter: float, n_nodes: int = 150) -> TiedKnot:
    """Loosely tied flat overhand bend of two ropes A and B.

    Parameters
    ----------
    rod_diameter : float [m]
        d, both ropes.
    n_nodes : int
        Nodes per rope (>= 80).

    Returns
    -------
    TiedKnot
        ``ropes["A"]``, ``ropes["B"]``, standing part at node 0 of each (both far left);
        ``expected`` (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 80)
    upper, lower, w = ribbon_strands("overhand", SCALE, HALF, TAIL)
    a, b = finish([upper, lower], d, n)
    return TiedKnot(
        name="flat_overhand_bend",
        ropes={"A": a, "B": b},
        ends={"A": ("standing", "tail"), "B": ("standing", "tail")},
        rod_radius=0.5 * d,
        expected={
            "alexander_A": (1, -1, 1),
            "alexander_B": (1, -1, 1),
            "linking": w,
            "alexander_joined": (1,),
        },  # fmt: skip
        info={"writhe": w, "join": [("A", True), ("B", False)], **start_checks([a, b], d)},
    )
