r"""Sheet bend (ABoK #1431): a bight in rope A, rope B through it, round both its legs
and tucked under itself.

Crossing design (x to the right, y up, the viewer at +z; A's bight legs along
y = +/-2.2 d to the left, its half turn at x = 7.5 d; B from the far right; at each
crossing the letter is the rope on top)::

                 x = -3   x = 2
                  +--------+              B's nipping loop (y = -5.5 ... 5.5)
                  |        |
    A standing ===B========A=========\     c4 (B over), c5 (A over)
                  |        |   +------)=== B standing    c1: B over A's apex
    A tail     ===B========A===A=====/     c3 (B over), c6, c2 (A over)
                  |        |   |
                  +--------B---+          c7: B's descent over its first run
                           |
    B tail     <===========+              (y = -8.5, beside A's tail)

Along B: over A's apex (c1), under A's tail leg (c2), under its own later descent (c7,
first passage), over A's tail leg and over A's standing leg (c3, c4: the loop's left
side), under A's standing leg and under A's tail leg (c5, c6: the loop's right side), over
its own first run (c7). Both of A's legs pass through B's loop (each over it on one side,
under it on the other) and B passes through A's bight (over the apex, under a leg): that is
the sheet bend (B "up through the bight, round behind both legs, tucked under itself",
seen from behind: a mirror image, which is the same bend). Both tails leave on the same
side (the left), the standing parts in opposite directions; A's tail (y = -2.2 d) and B's
tail (y = -8.5 d) lie on the same edge of the knot (not the left-handed sheet bend).

Node 0 of each rope is its standing part, the last node its tail.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- each rope closed on its own: the **unknot** (A a bight, B a loop with one
  self-crossing: a kink);
- the two ropes each closed: linking number **+1** (the signs of the six crossings of A
  with B, read off the diagram with both ropes run from their standing parts: c4, c5 on
  A's standing leg -1 each, c1, c2, c3, c6 +1 each; (4 - 2)/2 = 1; the test takes the
  Gauss integral);
- joined into one curve (A's tail to B's tail, B's standing part to A's, around the
  outside): the knot **6_2** (Alexander polynomial :math:`-1 + 3t - 3t^2 + 3t^3 - t^4`,
  determinant 11). The same structure with B's tail joined to A's standing part instead
  is the bowline (Turner & van de Griend, *History and Science of Knots*, 1996, p. 125: a
  loop knot is a bend with one working end joined to a standing end); the test builds
  that closure of these two ropes (knot 6_3) and compares it with :mod:`.bowline`'s own
  embedding.
"""

from __future__ import annotations

from knotmech.scenes.tied._common import (
    TiedKnot,
    build_ropes,
    check_sizes,
    finish,
    sheet_controls,
    start_checks,
)

__all__ = ["sheet_bend"]


def sheet_bend(*, rod_diameter: float, n_nodes: int = 200) -> TiedKnot:
    """Loosely tied sheet bend of two ropes of equal diameter.

    Parameters
    ----------
    rod_diameter : float [m]
        d, both ropes.
    n_nodes : int
        Nodes per rope (>= 100).

    Returns
    -------
    TiedKnot
        ``ropes["A"]`` (the bight), ``ropes["B"]`` (the wrapping rope), standing part at
        node 0 of each; ``expected`` (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 100)
    a_ctrl, b_ctrl = sheet_controls()
    (a, b), _ = build_ropes([a_ctrl, b_ctrl])
    a, b = finish([a, b], d, n)
    return TiedKnot(
        name="sheet_bend",
        ropes={"A": a, "B": b},
        ends={"A": ("standing", "tail"), "B": ("standing", "tail")},
        rod_radius=0.5 * d,
        expected={
            "alexander_A": (1,),
            "alexander_B": (1,),
            "linking": 1,
            "alexander_joined": (-1, 3, -3, 3, -1),
        },  # fmt: skip
        info={"join": [("A", True), ("B", False)], **start_checks([a, b], d)},
    )
