r"""Figure-eight bend (Flemish bend, ABoK #1411): two ropes joined by a retraced figure-eight.

Construction: rope A ties a figure-eight and rope B follows it back, lying beside it all
the way (the knot dressed flat): the single-rope long figure-eight of
:func:`~knotmech.scenes.tied._common.long_knot_controls` (a parametric 4_1 cut open at its
outermost point, ends to the far left and right, one kink where the two ends cross) split
into two parallel strands 1.3 d apart. A is the strand on the left of the direction of
travel, run from the far left to the far right; B the other strand, run back::

    A standing  =======\   figure-eight of   /======= A tail
                        >== the doubled rope ==
    B tail      =======/   (4 + 1 crossings)  \======= B standing

A's standing part is node 0 of A (far left), B's is node 0 of B (far right); each tail
lies beside the other rope's standing part.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- each rope closed on its own far outside: a **figure-eight knot 4_1** (Alexander
  polynomial :math:`-1 + 3t - t^2`, determinant 5): each rope is one strand of the doubled
  figure-eight;
- the two ropes, each closed, link :math:`-w` times, w the writhe of the single-rope
  diagram (parallel strands of a flat ribbon link w times; B runs the other way): w = 1
  here (the 4_1 diagram's writhe 0 plus the kink's +1);
- joined into one curve, each standing part to the tail beside it: the **unknot** (the
  boundary of the doubled rope's ribbon, a disk).
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes.tied._common import TiedKnot, check_sizes, finish, ribbon_strands, start_checks

__all__ = ["figure_eight_bend"]

SCALE = 3.4  #: size of the figure-eight [d]
HALF = 0.65  #: half spacing of the two ropes [d]
TAIL = 8.0  #: straight ends of the construction [d]
#: each straight end lengthened by EXTEND [d] (to 24 d beyond the construction's knot):
#: the loose knot's loops (up to 20 d across while it is set) must not reach a held end
#: (with 8 d ends a loop of B slid over B's held standing end during the set and B came
#: undone: docs/notes/knots-and-curves/tied-knots-pulled.md)
EXTEND = 16.0


def _extended(p, length: float) -> np.ndarray:
    """Dense polyline ``p`` [d] with both (straight) ends run on by ``length`` [d] along
    their outward tangents."""
    u0, u1 = p[0] - p[1], p[-1] - p[-2]
    u0, u1 = u0 / np.linalg.norm(u0), u1 / np.linalg.norm(u1)
    return np.vstack([p[0] + length * u0, p, p[-1] + length * u1])


def figure_eight_bend(*, rod_diameter: float, n_nodes: int = 300) -> TiedKnot:
    """Loosely tied figure-eight bend of two ropes A and B.

    Parameters
    ----------
    rod_diameter : float [m]
        d, both ropes.
    n_nodes : int
        Nodes per rope (>= 100; the default 300 gives edges of 0.6-0.7 d, the bend
        scene's 150 edges of 1.2-1.35 d).

    Returns
    -------
    TiedKnot
        ``ropes["A"]``, ``ropes["B"]``, standing part at node 0 of each; ``expected``
        (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 100)
    upper, lower, w = ribbon_strands("figure_eight", SCALE, HALF, TAIL)
    a, b = finish([_extended(upper, EXTEND), _extended(lower[::-1], EXTEND)], d, n)
    return TiedKnot(
        name="figure_eight_bend",
        ropes={"A": a, "B": b},
        ends={"A": ("standing", "tail"), "B": ("standing", "tail")},
        rod_radius=0.5 * d,
        expected={
            "alexander_A": (-1, 3, -1),
            "alexander_B": (-1, 3, -1),
            "linking": -w,
            "alexander_joined": (1,),
        },  # fmt: skip
        info={"writhe": w, "join": [("A", True), ("B", True)], **start_checks([a, b], d)},
    )
