r"""Double fisherman's bend (grapevine bend, ABoK #1415): two ropes laid side by side in
opposite directions, each tied round the other in a double overhand (strangle) knot.

Construction (true 3-D, not a plane diagram): the ropes run along x, A on the line
(y, z) = (0.75, -0.45) d from its standing part at the far left, B on (-0.75, -0.45) d from
its standing part at the far right. Past the middle, A's working part leaves its line at
x = 12 d, winds two turns round both ropes (a helix of centreline radius 2.2 d, pitch
1.5 d, running back towards A's standing part), turns (a half circle in the plane y = 0)
into the coil and runs back out through it along (0, 0.85) d: its tail leaves to the far
right. B is A turned half a turn about z, so its double overhand is on the left, round
both ropes, and its tail leaves to the far left::

    A standing ============================================ >>>>  coil  ==== A tail
                      coil  <<<<  =====================================
    B tail   ==== (B's two turns)                            (A's two turns)
                      ========================================= B standing

Node 0 of each rope is its standing part, the last node its tail.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- each rope closed on its own: the **cinquefoil 5_1** (Alexander polynomial
  :math:`1 - t + t^2 - t^3 + t^4`, determinant 5): each rope is a double overhand knot
  round its own standing part, whose closure is the (2, 5) torus knot (Knot Atlas, 5_1:
  "the strangle knot ... deforms to 5_1"; Wikipedia, *Cinquefoil knot*: "the closed
  version of the double overhand knot"; as :func:`knotmech.scenes.curves.overhand_knot`
  with 2 turns);
- the two ropes, each closed: linking number **-4** (each rope's coil makes two turns
  round the other, both of the same hand since B is A turned about z);
- joined into one curve (A's tail to B's standing part, B's tail to A's, around the
  outside): the **unknot** (measured here, not derived: with each tail joined to the other
  rope's standing part, each strangle knot can slide along that rope onto the other's tail).
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes.tied._common import TiedKnot, bspline, check_sizes, finish, start_checks

__all__ = ["double_fishermans"]

OWN = (0.75, -0.45)  #: (y, z) of A's own line [d]
TUCK = (0.0, 0.85)  #: (y, z) of the tail's run back through the coil [d]
COIL = 2.2  #: centreline radius of the turns [d]
PITCH = 1.5  #: axial advance per turn [d]
X_TURN = 12.0  #: where A's working part leaves its line [d]


def _rope_a_controls(turns: int = 2, left: float = -30.0, tail: float = 20.0) -> np.ndarray:
    """Control polygon [d] of rope A: standing line, entry, coil, half circle, tuck, tail."""
    th0 = np.deg2rad(-40.0)
    th1 = np.deg2rad(90.0) + 2 * np.pi * turns
    step = np.deg2rad(30.0)
    th = np.arange(th0, th1 + 1e-9, step)
    th[-1] = th1
    rho = COIL * 3.0 / (2.0 + np.cos(step))
    x = X_TURN + 2.0 - PITCH * (th - th0) / (2 * np.pi)
    coil = np.column_stack([x, rho * np.cos(th), rho * np.sin(th)])
    xe = x[-1]
    t_in = th0 - 0.7
    lead = [
        (left, *OWN),
        (left + 10, *OWN),
        (X_TURN - 3, *OWN),
        (X_TURN - 0.5, *OWN),
        (X_TURN + 0.4, *OWN),
        (X_TURN + 1.6, 1.3 * np.cos(t_in), 1.3 * np.sin(t_in)),
    ]
    zc = 0.5 * (COIL + TUCK[1])
    rr = 0.5 * (COIL - TUCK[1]) + 0.05
    aa = np.linspace(0.5 * np.pi, 1.5 * np.pi, 7)
    rq = rr * 3.0 / (2.0 + np.cos(aa[1] - aa[0]))
    semi = [(xe - 1.3 + rq * np.cos(q), 0.0, zc + rq * np.sin(q)) for q in aa]
    out = [(xe - 0.3, *TUCK), (xe + 1.0, *TUCK), (X_TURN + 1.5, *TUCK), (X_TURN + 4, 0.5, TUCK[1]),
           (tail, 4.0, TUCK[1])]  # fmt: skip
    return np.vstack([lead, coil, semi, out])


def double_fishermans(*, rod_diameter: float, n_nodes: int = 300) -> TiedKnot:
    """Loosely tied double fisherman's bend of two ropes A and B.

    Parameters
    ----------
    rod_diameter : float [m]
        d, both ropes.
    n_nodes : int
        Nodes per rope (>= 150).

    Returns
    -------
    TiedKnot
        ``ropes["A"]``, ``ropes["B"]``, standing part at node 0 of each (A far left, B far
        right); ``expected`` (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 150)
    a_ctrl = _rope_a_controls()
    a, b = finish([bspline(a_ctrl), bspline(a_ctrl * [-1.0, -1.0, 1.0])], d, n)
    return TiedKnot(
        name="double_fishermans",
        ropes={"A": a, "B": b},
        ends={"A": ("standing", "tail"), "B": ("standing", "tail")},
        rod_radius=0.5 * d,
        expected={
            "alexander_A": (1, -1, 1, -1, 1),
            "alexander_B": (1, -1, 1, -1, 1),
            "linking": -4,
            "alexander_joined": (1,),
        },  # fmt: skip
        info={"join": [("A", True), ("B", True)], **start_checks([a, b], d)},
    )
