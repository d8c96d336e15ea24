r"""Figure-eight bend (Flemish bend, ABoK #1411): two ropes joined by a retraced figure-eight.

Construction: rope A ties a figure-eight and rope B follows it back, lying beside it all
the way (the knot dressed flat): the single-rope long figure-eight of
:func:`~knotmech.scenes.tied._common.long_knot_controls` (a parametric 4_1 cut open at its
outermost point, ends to the far left and right, one kink where the two ends cross) split
into two parallel strands 1.3 d apart, then drawn in by the contract-and-repel pass of
:func:`~knotmech.scenes.tied._snug.snug_figure_eight` (the knot about 9 x 6 x 5 d, strands
at least 1.19 d apart, 45-50 d of each rope; the doubled parametric knot held 120 d of each
rope in loops 5-10 d across). A is the strand on the left of the direction of travel, run
from the far left to the far right; B the other strand, run back::

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

from knotmech.scenes.tied._common import TiedKnot, check_sizes, start_checks
from knotmech.scenes.tied._snug import equal_chords, run_on, snug_figure_eight

__all__ = ["figure_eight_bend"]

#: each end of the drawn-in knot run on by EXTEND [d] along its tangent: a held end must
#: lie clear of the loops (the loose parametric bend, with 8 d ends, had a loop of B slide
#: over B's held standing end during the set: docs/notes/knots-and-curves/tied-knots-pulled.md)
EXTEND = 10.0


def figure_eight_bend(*, rod_diameter: float, n_nodes: int = 52) -> TiedKnot:
    """Figure-eight bend of two ropes A and B, drawn in (snug, not tight).

    Parameters
    ----------
    rod_diameter : float [m]
        d, both ropes.
    n_nodes : int
        Nodes per rope (>= 40; the default 52 gives edges of 1.26-1.34 d on ropes of
        64 and 68 d; 46 nodes, edges 1.4-1.5 d, changed the verdict at mu = 1:
        docs/notes/knots-and-curves/tied-knots-pulled.md).

    Returns
    -------
    TiedKnot
        ``ropes["A"]``, ``ropes["B"]``, standing part at node 0 of each; ``expected``
        (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 40)
    upper, lower, w = snug_figure_eight()
    a, b = (equal_chords(run_on(p, EXTEND, EXTEND) * d, n) for p in (upper, lower[::-1]))
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
