r"""Double sheet bend (ABoK #1434): the sheet bend with the wrapping rope taken round the
bight twice, each turn tucked under its own standing part.

Crossing design (as :mod:`.sheet_bend`: A's bight legs along y = +/-2.2 d to the left,
its half turn at x = 9.5 d; B from the far right): B passes over A's apex and under A's
tail leg (through the bight), runs left below the legs (its *first bottom run*, y = -5.5
d), and makes two turns round both legs: up at x = -2 d over both legs, across the top,
down at x = 1.5 d under both legs and over its first bottom run; then below, left, up at
x = -5 d over both legs, across a higher top, down at x = 4 d under both legs and over its
first bottom run again, and its tail runs to the left along y = -10 d, beside A's tail::

        +-------------------+        second turn (x = -5 ... 4)
        |   +--------+      |        first turn  (x = -2 ... 1.5)
    A ==O===O========U======U====\
        |   |        |      |     )  <== B (over A's apex)
    A ==O===O========U======U====/
        |   +--------X------X         B's first bottom run, crossed over twice
        +------------+      |
    B tail  <===============+

12 crossings: c1, c2 as in the sheet bend; per turn four with A's legs and one with B's
first bottom run.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- each rope closed on its own: the **unknot**;
- the two ropes each closed: linking number **+1**, as the sheet bend's (a turn round
  both legs of the bight adds no linking: the two legs carry A in opposite directions);
- joined into one curve (A's tail to B's tail, the standing parts together): Alexander
  polynomial :math:`-1 + t + 3t^2 - 5t^3 + 3t^4 + t^5 - t^6` (determinant 7). This knot is
  not in the small table of :data:`~knotmech.scenes.tied._common.KNOT_TABLE`; it is not
  identified here. The test checks that a second embedding of the same crossing sequence
  with every turn and run spread 1.3 times wider gives the same polynomial, and that it
  differs from the sheet bend's 6_2 (the second turn is a real change of knot type).
"""

from __future__ import annotations

from knotmech.errors import check_range
from knotmech.scenes.tied._common import (
    TiedKnot,
    build_ropes,
    check_sizes,
    double_sheet_controls,
    finish,
    start_checks,
)

__all__ = ["double_sheet_bend"]

JOINED = (-1, 1, 3, -5, 3, 1, -1)  #: Alexander polynomial of the joined closure (measured)


def double_sheet_bend(*, rod_diameter: float, n_nodes: int = 250, spread: float = 1.0) -> TiedKnot:
    """Loosely tied double sheet bend of two ropes of equal diameter.

    Parameters
    ----------
    rod_diameter : float [m]
        d, both ropes.
    n_nodes : int
        Nodes per rope (>= 120).
    spread : float
        Scale of the turns' positions and B's runs (1 to 2; 1 is the design).

    Returns
    -------
    TiedKnot
        ``ropes["A"]`` (the bight), ``ropes["B"]`` (the wrapping rope), standing part at
        node 0 of each; ``expected`` (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 120)
    s = float(check_range("spread", spread, 1.0, 2.0, scalar=True))
    a_ctrl, b_ctrl = double_sheet_controls(spread=s)
    (a, b), _ = build_ropes([a_ctrl, b_ctrl])
    a, b = finish([a, b], d, n)
    return TiedKnot(
        name="double_sheet_bend",
        ropes={"A": a, "B": b},
        ends={"A": ("standing", "tail"), "B": ("standing", "tail")},
        rod_radius=0.5 * d,
        expected={
            "alexander_A": (1,),
            "alexander_B": (1,),
            "linking": 1,
            "alexander_joined": JOINED,
        },  # fmt: skip
        info={"join": [("A", True), ("B", False)], **start_checks([a, b], d)},
    )
